// The erosion of a convex polytope by a convex polytope as the intersection
// of A's facet half-spaces moved inwards by B's support, built exactly:
// minksum's exact numbers and support, and an exact hull of the dual points
// on integer determinants (docs/nonconvex.md, "Erosion, opening,
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
// facets of H around v, in their order.  H is the exact hull of the dual
// points, its triangles grouped into facets exactly (dual_hull); every
// corner is the exact intersection of three of the moved planes (any three
// corners of a facet of H are not collinear, so their planes meet in one
// point); the polytope is built from those polygons, not validated again.  No point strictly inside found
// (the erosion empty, lower-dimensional, or off the candidates below):
// nullopt, and the caller takes the sweep, which decides exactly.
#include "nonconvex/morphology.hpp"

#include "mesh/builder.hpp"
#include "mesh/support.hpp"

#include "kernel/plane.hpp"  // scaled_point
#include "mesh/homogeneous_hull.hpp"

#include <CGAL/FPU.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace minksum::nonconvex_detail {

namespace {

// Σ points / count, exactly.
Point3 centroid(const std::vector<Point3>& points) {
  Point3 s(Rational(0), Rational(0), Rational(0));
  for (const Point3& p : points) s = s + p;
  return Rational(1, long(points.size())) * s;
}

// The cross product of two planes' normals.
std::array<Integer, 3> cross(const Plane& u, const Plane& v) {
  return {u.b * v.c - u.c * v.b, u.c * v.a - u.a * v.c, u.a * v.b - u.b * v.a};
}

// The convex hull H of the dual points, as the erosion is read off it: for
// each facet of H, the input points (planes) of three of its corners; for
// each corner of H, the facets around it, counter-clockwise seen from
// outside.
struct DualHull {
  std::vector<std::array<Index, 3>> corners;
  std::vector<std::vector<Index>> around;
};

// The exact hull of the dual points p_i = (n_i scale_i) / w_i, given in
// homogeneous integer coordinates (n_i scale_i, w_i), scale_i, w_i > 0:
// Quickhull on integer determinants (mesh/homogeneous_hull.hpp), no
// rational arithmetic.  Its triangles are grouped into H's facets across the
// edges whose two triangles are coplanar (exact: a facet with more than
// three corners, or with dual points inside it or on its sides, is several
// triangles); a vertex around which the triangles lie in three facets or
// more is a corner of H, one in one or two facets (inside a facet, or
// inside an edge) is not.
DualHull dual_hull(const ConvexPolytope& polytope, const std::vector<Integer>& scale, const std::vector<Integer>& w) {
  HomogeneousHull sm;
  {
    CGAL::Protect_FPU_rounding<true> upward;  // the kernel's interval filter
    std::vector<detail::HomogeneousPoint> points;
    points.reserve(w.size());
    for (Index i = 0; i < w.size(); ++i) {
      const Plane& h = polytope.plane(i);  // integer normal (h.a, h.b, h.c)
      points.push_back(detail::homogeneous_point(Integer(h.a * scale[i]), Integer(h.b * scale[i]),
                                                 Integer(h.c * scale[i]), w[i]));
    }
    sm = homogeneous_hull(points);
  }
  const Index nt = Index(sm.triangles.size());
  // Union-find over the triangles: one set per facet of H.
  std::vector<Index> parent(nt);
  for (Index f = 0; f < nt; ++f) parent[f] = f;
  auto find = [&](Index f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  for (Index t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (sm.flat[t][k]) parent[find(t)] = find(sm.neighbour[t][k]);
  // The corners of H (vertices around which the triangles lie in three
  // facets or more), each with the facets around it counter-clockwise seen
  // from outside (from a triangle t at the vertex, on to the triangle across
  // t's edge into the vertex), the facets by their triangle sets' roots for
  // now.
  struct Corner {
    Index point;               // the input point
    std::vector<Index> roots;  // around it
  };
  std::vector<std::pair<Index, Index>> at(w.size(), {kNoIndex, 0});  // point -> (a triangle, its corner)
  for (Index t = 0; t < nt; ++t)
    for (Index k = 0; k < 3; ++k) at[sm.triangles[t][k]] = {t, k};
  std::vector<Corner> found;
  for (Index v = 0; v < at.size(); ++v) {
    if (at[v].first == kNoIndex) continue;
    std::vector<Index> around;
    const Index t0 = at[v].first;
    Index t = t0, k = at[v].second;
    do {
      const Index g = find(t);
      if (around.empty() || around.back() != g) around.push_back(g);
      const Index u = sm.neighbour[t][(k + 2) % 3];  // across (v_(k+2), v)
      k = sm.triangles[u][0] == v ? 0 : sm.triangles[u][1] == v ? 1 : 2;
      t = u;
    } while (t != t0);
    if (around.size() > 1 && around.front() == around.back()) around.pop_back();
    if (around.size() < 3) continue;  // not a corner
    found.push_back(Corner{v, std::move(around)});
  }
  // Numbered so that the erosion depends on the hull's facets, not on the
  // order in which the hull lists its triangles: corners by input point
  // (as `found` is), facets of H by their corners (ascending lists, compared
  // lexicographically), each corner's cycle from its lowest facet.
  std::unordered_map<Index, std::vector<Index>> corners_of_root;
  for (const Corner& c : found)
    for (Index r : c.roots) corners_of_root[r].push_back(c.point);  // ascending, as `found` is
  std::vector<std::pair<std::vector<Index>, Index>> by_corners;  // (corners, root)
  by_corners.reserve(corners_of_root.size());
  for (auto& [root, corners] : corners_of_root) {
    if (corners.size() < 3) throw std::logic_error("halfspace_erosion: a hull facet with fewer than three corners");
    by_corners.emplace_back(std::move(corners), root);
  }
  std::sort(by_corners.begin(), by_corners.end());
  std::unordered_map<Index, Index> facet_of_root;
  DualHull d;
  d.corners.reserve(by_corners.size());
  for (const auto& [corners, root] : by_corners) {
    facet_of_root.emplace(root, Index(d.corners.size()));
    d.corners.push_back({corners[0], corners[1], corners[2]});
  }
  d.around.reserve(found.size());
  for (const Corner& c : found) {
    std::vector<Index> around;
    around.reserve(c.roots.size());
    for (Index r : c.roots) around.push_back(facet_of_root.at(r));
    std::rotate(around.begin(), std::min_element(around.begin(), around.end()), around.end());
    d.around.push_back(std::move(around));
  }
  return d;
}

// The polytope of the polygons `faces` (loops of point indices,
// counter-clockwise seen from outside) whose validity the caller has
// proven: each edge's two half-edges paired (2e and 2e + 1).
ConvexPolytope trusted_polytope(PointList points, const std::vector<std::vector<Index>>& faces) {
  std::vector<Index> he_origin, he_next, he_facet, facet_he;
  std::unordered_map<std::uint64_t, Index> edge;  // (smaller, larger point) -> its first half-edge
  std::size_t corners = 0;
  for (const auto& f : faces) corners += f.size();
  he_origin.resize(corners);
  he_next.resize(corners);
  he_facet.resize(corners);
  edge.reserve(corners);
  Index next_edge = 0;
  for (Index fi = 0; fi < faces.size(); ++fi) {
    const auto& f = faces[fi];
    std::vector<Index> hs(f.size());
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Index u = f[k], v = f[(k + 1) % f.size()];
      const std::uint64_t key = (std::uint64_t(std::min(u, v)) << 32) | std::max(u, v);
      const auto [it, first] = edge.emplace(key, 2 * next_edge);
      if (first) ++next_edge;
      hs[k] = first ? it->second : it->second + 1;
      he_origin[hs[k]] = u;
      he_facet[hs[k]] = fi;
    }
    for (std::size_t k = 0; k < f.size(); ++k) he_next[hs[k]] = hs[(k + 1) % f.size()];
    facet_he.push_back(hs[0]);
  }
  return PolytopeBuilder::from_trusted_parts(std::move(points), std::move(he_origin), std::move(he_next),
                                            std::move(he_facet), std::move(facet_he));
}

}  // namespace

std::optional<ConvexPolytope> halfspace_erosion(const ConvexPolytope& a, const ConvexPolytope& b) {
  // Integers throughout, over denominators kept apart (no gcd until the
  // corners): B's vertices y = Y / D, the moved offsets o_i = d_i - n_i . y
  // = O_i / D_i (y the support of n_i), the interior point q = Q / E and the
  // slacks e_i = o_i - n_i . q = S_i / (D_i E).
  const Index n = a.num_facets();
  std::vector<ScaledPoint> vertex_of_b(b.num_vertices());
  std::vector<char> made(b.num_vertices(), 0);
  std::vector<Integer> offset(n), denominator(n);  // O_i, D_i
  Index start = 0;
  for (Index f = 0; f < n; ++f) {
    const Plane& h = a.plane(f);
    start = support(b, h.normal(), start).vertex;
    if (!made[start]) vertex_of_b[start] = scaled_point(b.point(start)), made[start] = 1;
    const ScaledPoint& y = vertex_of_b[start];
    offset[f] = h.d * y.den - (h.a * y.num[0] + h.b * y.num[1] + h.c * y.num[2]);
    denominator[f] = y.den;
  }
  // A point strictly inside every moved half-space: the difference of A's
  // and B's vertex centroids (inside the erosion for most B small against
  // A), first on the vertices' doubles (short numbers; A's exact
  // coordinates are not made), else exactly.  The erosion does not depend on
  // which point it is (the dual hull's structure is the erosion's).
  std::vector<Integer> slack(n);  // S_i
  ScaledPoint q;
  auto strictly_inside = [&](const Point3& point) {
    q = scaled_point(point);
    for (Index f = 0; f < n; ++f) {
      const Plane& h = a.plane(f);
      slack[f] = offset[f] * q.den - (h.a * q.num[0] + h.b * q.num[1] + h.c * q.num[2]) * denominator[f];
      if (sgn(slack[f]) <= 0) return false;
    }
    return true;
  };
  double near[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    for (Index v = 0; v < a.num_vertices(); ++v) near[k] += a.approx(v)[k] / a.num_vertices();
    for (Index v = 0; v < b.num_vertices(); ++v) near[k] -= b.approx(v)[k] / b.num_vertices();
  }
  if (!(std::isfinite(near[0]) && std::isfinite(near[1]) && std::isfinite(near[2]) &&
        strictly_inside(Point3(near[0], near[1], near[2]))) &&
      !strictly_inside(centroid(a.points()) - centroid(b.points())))
    return std::nullopt;

  // The dual points n_i / e_i = (n_i D_i E, S_i) homogeneously.
  std::vector<Integer> scale(n);
  for (Index f = 0; f < n; ++f) scale[f] = denominator[f] * q.den;
  const DualHull hull = dual_hull(a, scale, slack);

  // One corner per facet of H: where the planes of three of its corners
  // meet (Cramer's rule on the moved planes), x = Σ o_i (n_j × n_k) / det
  // = Σ O_i D_j D_k (n_j × n_k) / (D_i D_j D_k det), each coordinate then
  // in lowest terms once.
  PointList corners;
  corners.reserve(hull.corners.size());
  for (const auto& [i, j, k] : hull.corners) {
    const Plane &hi = a.plane(i), &hj = a.plane(j), &hk = a.plane(k);
    const std::array<Integer, 3> jk = cross(hj, hk), ki = cross(hk, hi), ij = cross(hi, hj);
    const Integer det = hi.a * jk[0] + hi.b * jk[1] + hi.c * jk[2];
    const Integer ci = offset[i] * denominator[j] * denominator[k], cj = offset[j] * denominator[i] * denominator[k],
                  ck = offset[k] * denominator[i] * denominator[j];
    const Integer den = det * denominator[i] * denominator[j] * denominator[k];
    auto coordinate = [&](const Integer& x, const Integer& y, const Integer& z) {
      Rational r(Integer(ci * x + cj * y + ck * z), den);
      r.canonicalize();
      return r;
    };
    corners.push_back(Point3(coordinate(jk[0], ki[0], ij[0]), coordinate(jk[1], ki[1], ij[1]),
                             coordinate(jk[2], ki[2], ij[2])));
  }
  // One facet per corner v of H, its corners those of the facets of H around
  // v in their order (counter-clockwise seen from outside, as polarity keeps
  // it).  The polar of a polytope is one (distinct corners and planes,
  // convex edges), so the parts are trusted; the tests check the invariants.
  return trusted_polytope(std::move(corners), hull.around);
}

}  // namespace minksum::nonconvex_detail
