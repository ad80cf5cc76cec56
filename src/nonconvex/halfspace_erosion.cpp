// The erosion of a convex polytope by a convex polytope as the intersection
// of A's facet half-spaces moved inwards by B's support, built exactly:
// minksum's exact numbers and support, CGAL's exact hull as
// ConvexPolytope::hull takes it (docs/nonconvex.md, "Erosion, opening,
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
// facets of H around v, in their order.  H is CGAL's exact hull of the
// dual points, its triangles grouped into facets exactly (dual_hull); every
// corner is the exact intersection of three of the moved planes (any three
// corners of a facet of H are not collinear, so their planes meet in one
// point); the polytope is built from those polygons, not validated again.  No point strictly inside found
// (the erosion empty, lower-dimensional, or off the candidates below):
// nullopt, and the caller takes the sweep, which decides exactly.
#include "nonconvex/morphology.hpp"

#include "mesh/builder.hpp"
#include "mesh/support.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
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

// The convex hull H of the dual points, as the erosion is read off it: for
// each facet of H, the input points (planes) of three of its corners; for
// each corner of H, the facets around it, counter-clockwise seen from
// outside.
struct DualHull {
  std::vector<std::array<Index, 3>> corners;
  std::vector<std::vector<Index>> around;
};

// CGAL's convex_hull_3 on exact points (Epeck: filtered exact predicates, the
// dual points' rationals exactly), a triangulated surface whose vertices are
// input points.  Its triangles are grouped into H's facets across the edges
// whose two triangles are coplanar (exact test: a facet with more than
// three corners, or with input points inside it or on its sides, is
// several triangles); a vertex around which the triangles lie in three
// facets or more is a corner of H, one in one or two facets (inside a
// facet, or inside an edge) is not.
DualHull dual_hull(const std::vector<Point3>& dual) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::vector<K::Point_3> points;
  points.reserve(dual.size());
  // A point's shared representation (copies of a point share it) -> its index.
  auto id = [](const K::Point_3& p) { return static_cast<const CGAL::Handle&>(p).id(); };
  std::unordered_map<CGAL::Handle::Id_type, Index> input;
  for (const Point3& p : dual) {
    points.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
    input.emplace(id(points.back()), Index(points.size() - 1));
  }
  CGAL::Surface_mesh<K::Point_3> sm;
  CGAL::convex_hull_3(points.begin(), points.end(), sm);
  // Union-find over the triangles: one set per facet of H.
  std::vector<Index> parent(sm.number_of_faces());
  for (Index f = 0; f < parent.size(); ++f) parent[f] = f;
  auto find = [&](Index f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  for (auto e : sm.edges()) {
    const auto h = sm.halfedge(e), o = sm.opposite(h);
    if (CGAL::coplanar(sm.point(sm.source(h)), sm.point(sm.target(h)), sm.point(sm.target(sm.next(h))),
                       sm.point(sm.target(sm.next(o)))))
      parent[find(Index(std::size_t(sm.face(h))))] = find(Index(std::size_t(sm.face(o))));
  }
  // The corners of H (vertices around which the triangles lie in three
  // facets or more), each with the facets around it counter-clockwise seen
  // from outside (the outgoing half-edge h, then the opposite of the one
  // before it), the facets by their triangle sets' roots for now.
  struct Corner {
    Index point;               // the input point
    std::vector<Index> roots;  // around it
  };
  std::vector<Corner> found;
  for (auto v : sm.vertices()) {
    std::vector<Index> around;
    const auto h0 = sm.opposite(sm.halfedge(v));
    auto h = h0;
    do {
      const Index g = find(Index(std::size_t(sm.face(h))));
      if (around.empty() || around.back() != g) around.push_back(g);
      h = sm.opposite(sm.prev(h));
    } while (h != h0);
    if (around.size() > 1 && around.front() == around.back()) around.pop_back();
    if (around.size() < 3) continue;  // not a corner
    const auto it = input.find(id(sm.point(v)));
    if (it == input.end()) throw std::logic_error("halfspace_erosion: a hull vertex that is no dual point");
    found.push_back(Corner{it->second, std::move(around)});
  }
  // Numbered so that the erosion does not depend on the order in which CGAL
  // lists the hull (which follows memory addresses): corners by input
  // point, facets of H by their corners (ascending lists, compared
  // lexicographically), each corner's cycle from its lowest facet.
  std::sort(found.begin(), found.end(), [](const Corner& x, const Corner& y) { return x.point < y.point; });
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
  const DualHull hull = dual_hull(dual);

  // One corner per facet of H: where the planes of three of its corners
  // meet (Cramer's rule on the moved planes).
  PointList corners;
  corners.reserve(hull.corners.size());
  for (const auto& [i, j, k] : hull.corners) {
    const Point3 jk = cross(normal[j], normal[k]), ki = cross(normal[k], normal[i]), ij = cross(normal[i], normal[j]);
    const Rational det = dot(normal[i], jk);
    corners.push_back(Rational(1 / det) * (offset[i] * jk + offset[j] * ki + offset[k] * ij));
  }
  // One facet per corner v of H, its corners those of the facets of H around
  // v in their order (counter-clockwise seen from outside, as polarity keeps
  // it).  The polar of a polytope is one (distinct corners and planes,
  // convex edges), so the parts are trusted; the tests check the invariants.
  return trusted_polytope(std::move(corners), hull.around);
}

}  // namespace minksum::nonconvex_detail
