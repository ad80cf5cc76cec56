// The exact convex hull of a point cloud: CGAL's convex_hull_3 on exact
// points (Epeck, whose exact number type is mpq_class here) or, when every
// coordinate is a double, on the points as doubles (Epick): convex_hull_3 then
// uses Convex_hull_traits_3<Epick, ..., Tag_true>, whose only geometric
// decision, the side of a plane through three input points, is an
// orientation sign computed exactly (a static floating-point filter, then
// intervals, then exact arithmetic), and it constructs nothing, so the hull
// is the exact one at a fraction of the lazy-exact kernel's time and memory.
// The triangulated hull goes through the validating builder, which merges
// coplanar triangles and drops points in the middle of edges.
//
// This is the only translation unit of src/mesh that includes CGAL.
#include "mesh/builder.hpp"

#include <minksum/error.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <unordered_map>

namespace minksum {

namespace {
using K = CGAL::Exact_predicates_exact_constructions_kernel;
using KPoint = K::Point_3;
using DoubleKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using DPoint = DoubleKernel::Point_3;

// Degenerate point sets are recognised before CGAL sees them, exactly.
void check_dimension(const std::vector<Point3>& pts, const std::string& source) {
  const std::string n = std::to_string(pts.size());
  if (pts.empty()) throw InputError(source, "", "no points");
  std::size_t i1 = 1;
  while (i1 < pts.size() && pts[i1] == pts[0]) ++i1;
  if (i1 == pts.size())
    throw InputError(source, "", "degenerate: all " + n + " points coincide (a single point, not a solid)");
  Point3 e1 = pts[i1] - pts[0];
  std::size_t i2 = i1 + 1;
  Point3 nrm;
  for (; i2 < pts.size(); ++i2) {
    nrm = cross(e1, pts[i2] - pts[0]);
    if (!is_zero(nrm)) break;
  }
  if (i2 >= pts.size())
    throw InputError(source, "", "degenerate: all " + n + " points are collinear (a segment, not a solid)");
  std::size_t i3 = i2 + 1;
  for (; i3 < pts.size(); ++i3)
    if (sgn(dot(nrm, pts[i3] - pts[0])) != 0) break;
  if (i3 >= pts.size())
    throw InputError(source, "", "degenerate: all " + n + " points are coplanar (a polygon, not a solid)");
}

Point3 to_point3(const KPoint& p) {
  const auto& e = CGAL::exact(p);
  return Point3(Rational(e.x()), Rational(e.y()), Rational(e.z()));
}
Point3 to_point3(const DPoint& p) { return Point3(Rational(p.x()), Rational(p.y()), Rational(p.z())); }

bool all_doubles(const std::vector<Point3>& points) {
  for (const auto& p : points)
    if (!is_double(p.x) || !is_double(p.y) || !is_double(p.z)) return false;
  return true;
}

// The triangulated hull of the points, in the kernel of P.
template <class P>
CGAL::Surface_mesh<P> triangulated_hull(const std::vector<Point3>& points) {
  std::vector<P> kp;
  kp.reserve(points.size());
  for (const auto& p : points) {
    if constexpr (std::is_same_v<P, DPoint>) kp.emplace_back(to_double(p.x), to_double(p.y), to_double(p.z));
    else kp.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
  }
  CGAL::Surface_mesh<P> sm;
  CGAL::convex_hull_3(kp.begin(), kp.end(), sm);
  return sm;
}

// The triangulated hull as a canonical mesh, whatever order CGAL produced
// (it varies between calls): vertices in the order of the input points, each
// triangle starting at its smallest vertex, triangles sorted; input_index[i]
// is the input point of mesh vertex i.
template <class P>
Mesh canonical_hull_mesh(const std::vector<Point3>& points, std::vector<Index>& input_index) {
  const CGAL::Surface_mesh<P> sm = triangulated_hull<P>(points);

  // Map hull vertices back to the input points (first occurrence).
  std::unordered_map<Point3, Index, Point3Hash> index_of;
  index_of.reserve(points.size());
  for (Index i = 0; i < points.size(); ++i) index_of.try_emplace(points[i], i);

  std::vector<std::pair<Index, std::size_t>> order;  // (input index, surface-mesh vertex)
  for (auto v : sm.vertices()) {
    auto it = index_of.find(to_point3(sm.point(v)));
    if (it == index_of.end())
      throw std::logic_error("convex hull produced a point that is not an input point");
    order.emplace_back(it->second, std::size_t(v));
  }
  std::sort(order.begin(), order.end());
  Mesh m;
  input_index.clear();
  std::unordered_map<std::size_t, Index> local;  // surface-mesh vertex -> mesh index
  for (auto [input, v] : order) {
    local[v] = Index(m.points.size());
    m.points.push_back(points[input]);
    input_index.push_back(input);
  }
  for (auto f : sm.faces()) {
    std::vector<Index> poly;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) poly.push_back(local[std::size_t(v)]);
    std::rotate(poly.begin(), std::min_element(poly.begin(), poly.end()), poly.end());
    m.faces.push_back(std::move(poly));
  }
  std::sort(m.faces.begin(), m.faces.end());
  return m;
}
}  // namespace

ConvexPolytope ConvexPolytope::hull(const std::vector<Point3>& points, const std::string& source) {
  check_dimension(points, source);
  std::vector<Index> input_index;
  const Mesh m = all_doubles(points) ? canonical_hull_mesh<DPoint>(points, input_index)
                                     : canonical_hull_mesh<KPoint>(points, input_index);
  ConvexPolytope result = PolytopeBuilder::build(m, source);
  // CGAL may triangulate a coplanar facet differently from call to call,
  // which changes the merged facets' order and first vertices: fix both.
  PolytopeBuilder::canonicalize_facets(result);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

ConvexPolytope ConvexPolytope::hull(const PointList& points, const std::string& source) {
  return hull(points.to_points(), source);
}

}  // namespace minksum
