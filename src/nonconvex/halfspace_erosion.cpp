// The erosion of a convex polytope by a convex polytope as the intersection
// of A's facet half-spaces moved inwards by B's support, built with
// minksum's own exact kernel (docs/nonconvex.md, "Erosion, opening,
// closing": convex A).  erode, opening and closing take it for a convex A
// (morphology.cpp).
//
// A = ∩ {n_i · x <= d_i} (A's canonical facet planes, integer n_i, d_i)
// gives A ⊖ B = ∩ {n_i · x <= o_i}, o_i = d_i - h_B(n_i), h_B(n) = max over
// B of n · y (hill climbing on B with exact comparisons, then one exact dot
// product).  With q strictly inside every moved half-space, checked with
// exact signs (e_i = o_i - n_i · q > 0 for all i), the erosion is
// 3-dimensional and, translated by -q, is ∩ {y : p_i · y <= 1} for the dual
// points p_i = n_i / e_i.  That is the polar of the convex hull H of the p_i
// (polarity about an interior point, as the erosion is bounded: the p_i
// span 3 dimensions positively since A's normals do): the planes of the
// erosion's facets are those of the vertices of H (a moved plane whose dual
// point is not a vertex of H — inside H, or on a facet or an edge of H
// without being a corner — is redundant), its vertices one per facet of H
// (the point where the planes of that facet's corners meet), and the
// erosion's facet of a vertex v of H has as corners the points of the
// facets of H around v, in their order.  H is minksum's exact hull
// (ConvexPolytope::hull); every corner is the exact intersection of three
// of the moved planes (any three corners of a facet of H are not collinear,
// so their planes meet in one point); the polytope is built from the hull's
// half-edges (below), not validated again.  No point strictly inside found
// (the erosion empty, lower-dimensional, or off the candidates below):
// nullopt, and the caller takes the sweep, which decides exactly.
#include "nonconvex/morphology.hpp"

#include "mesh/builder.hpp"
#include "mesh/support.hpp"

#include <array>
#include <vector>

namespace minksum::nonconvex_detail {

namespace {

// Σ points / count, exactly.
Point3 centroid(const std::vector<Point3>& points) {
  Point3 s(Rational(0), Rational(0), Rational(0));
  for (const Point3& p : points) s = s + p;
  return Rational(1, long(points.size())) * s;
}

// The convex hull of the dual points, as the erosion is read off it: for
// each facet, the input points (planes) of three of its corners; for each
// half-edge (twin h ^ 1), its facet, its target and the half-edge before it
// in its facet; for each vertex, a half-edge into it.
struct DualHull {
  std::vector<std::array<Index, 3>> corners;
  std::vector<Index> facet, target, prev;
  std::vector<Index> into;
};

// Minksum's exact hull of the dual points (ConvexPolytope::hull: coplanar
// triangles merged into polygons, points that are not corners dropped).
DualHull polytope_hull(const std::vector<Point3>& dual) {
  const ConvexPolytope hull = ConvexPolytope::hull(dual, "erosion");
  DualHull d;
  const Index nh = hull.num_halfedges();
  d.facet.resize(nh);
  d.target.resize(nh);
  d.prev.resize(nh);
  for (Index h = 0; h < nh; ++h) {
    d.facet[h] = hull.facet(h);
    d.target[h] = hull.target(h);
    d.prev[h] = hull.prev(h);
  }
  d.corners.resize(hull.num_facets());
  for (Index g = 0; g < hull.num_facets(); ++g) {
    const Index h0 = hull.facet_halfedge(g);
    d.corners[g] = {hull.source_vertex(hull.origin(h0)), hull.source_vertex(hull.origin(hull.next(h0))),
                    hull.source_vertex(hull.origin(hull.next(hull.next(h0))))};
  }
  d.into.resize(hull.num_vertices());
  for (Index v = 0; v < hull.num_vertices(); ++v) d.into[v] = hull.vertex_halfedge(v) ^ 1u;
  return d;
}

}  // namespace

std::optional<ConvexPolytope> halfspace_erosion(const ConvexPolytope& a, const ConvexPolytope& b) {
  const Index n = a.num_facets();
  std::vector<Point3> normal(n);
  std::vector<Rational> offset(n);  // n_i . x <= offset_i
  Index start = 0;
  for (Index f = 0; f < n; ++f) {
    const Plane& h = a.plane(f);
    normal[f] = h.normal();
    start = support(b, normal[f], start).vertex;
    offset[f] = Rational(h.d) - dot(normal[f], b.point(start));
  }
  // A point strictly inside every moved half-space: the difference of A's
  // and B's vertex centroids (inside the erosion for most B small against
  // A), rounded to doubles first (shorter numbers for what follows), else
  // exactly.
  std::vector<Rational> slack(n);  // e_i = offset_i - n_i . q
  auto strictly_inside = [&](const Point3& q) {
    for (Index f = 0; f < n; ++f) {
      slack[f] = offset[f] - dot(normal[f], q);
      if (sgn(slack[f]) <= 0) return false;
    }
    return true;
  };
  const Point3 exact = centroid(a.points()) - centroid(b.points());
  const Vec3d near = to_double(exact);
  if (!strictly_inside(Point3(near.x, near.y, near.z)) && !strictly_inside(exact)) return std::nullopt;

  std::vector<Point3> dual(n);
  for (Index f = 0; f < n; ++f) dual[f] = Rational(1 / slack[f]) * normal[f];
  const DualHull hull = polytope_hull(dual);

  // One corner per facet of the hull: where the planes of three of its
  // corners meet (Cramer's rule on the moved planes).
  PointList corners;
  corners.reserve(hull.corners.size());
  for (const auto& [i, j, k] : hull.corners) {
    const Point3 jk = cross(normal[j], normal[k]), ki = cross(normal[k], normal[i]), ij = cross(normal[i], normal[j]);
    const Rational det = dot(normal[i], jk);
    corners.push_back(Rational(1 / det) * (offset[i] * jk + offset[j] * ki + offset[k] * ij));
  }
  // One facet per vertex v of the hull, its corners those of the facets
  // around v: the hull's half-edge h (facet F on its left, F' = facet(h ^ 1)
  // on its right) becomes the erosion's half-edge h from corner F to
  // corner F' on the facet of target(h); its next is prev(h ^ 1), which
  // leaves F' towards target(h) again.  The polar of a valid polytope is
  // one (distinct corners and planes, convex edges), so the parts are
  // trusted; the tests check the invariants.
  const Index nh = Index(hull.facet.size());
  std::vector<Index> he_next(nh);
  for (Index h = 0; h < nh; ++h) he_next[h] = hull.prev[h ^ 1u];
  return PolytopeBuilder::from_trusted_parts(std::move(corners), hull.facet, std::move(he_next), hull.target,
                                            hull.into);
}

}  // namespace minksum::nonconvex_detail
