// The exact convex hull of a point cloud: CGAL's convex_hull_3 on exact
// points (Epeck, whose exact number type is mpq_class here), then the
// triangulated hull goes through the validating builder, which merges
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
}  // namespace

ConvexPolytope ConvexPolytope::hull(const std::vector<Point3>& points, const std::string& source) {
  check_dimension(points, source);
  std::vector<KPoint> kp;
  kp.reserve(points.size());
  for (const auto& p : points) kp.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));

  CGAL::Surface_mesh<KPoint> sm;
  CGAL::convex_hull_3(kp.begin(), kp.end(), sm);

  // Map hull vertices back to the input points (first occurrence).
  std::unordered_map<Point3, Index, Point3Hash> index_of;
  index_of.reserve(points.size());
  for (Index i = 0; i < points.size(); ++i) index_of.try_emplace(points[i], i);

  // A canonical mesh, whatever order CGAL produced (it varies between calls):
  // vertices in the order of the input points, each triangle starting at its
  // smallest vertex, triangles sorted.
  std::vector<std::pair<Index, std::size_t>> order;  // (input index, surface-mesh vertex)
  for (auto v : sm.vertices()) {
    auto it = index_of.find(to_point3(sm.point(v)));
    if (it == index_of.end())
      throw std::logic_error("convex hull produced a point that is not an input point");
    order.emplace_back(it->second, std::size_t(v));
  }
  std::sort(order.begin(), order.end());
  Mesh m;
  std::vector<Index> input_index;
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
  ConvexPolytope result = PolytopeBuilder::build(m, source);
  // CGAL may triangulate a coplanar facet differently from call to call,
  // which changes the merged facets' order and first vertices: fix both.
  PolytopeBuilder::canonicalize_facets(result);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

// Points that are all doubles: CGAL's Epick kernel, whose predicates are
// exact (filtered, with exact fallbacks) and whose convex hull traits use no
// constructions (Convex_hull_traits_3: a plane is a triple of points), so the
// hull is the exact one, without a rational per coordinate.
ConvexPolytope ConvexPolytope::hull(const PointList& points, const std::string& source) {
  if (!points.all_doubles()) return hull(points.to_points(), source);
  using E = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<E::Point_3> ep;
  ep.reserve(points.size());
  for (const Vec3d& v : points.approx()) ep.emplace_back(v.x, v.y, v.z);
  // The degenerate cases, decided by the same exact predicates, with the
  // messages of check_dimension.
  const std::string n = std::to_string(ep.size());
  if (ep.empty()) throw InputError(source, "", "no points");
  std::size_t i1 = 1;
  while (i1 < ep.size() && ep[i1] == ep[0]) ++i1;
  if (i1 == ep.size())
    throw InputError(source, "", "degenerate: all " + n + " points coincide (a single point, not a solid)");
  std::size_t i2 = i1 + 1;
  while (i2 < ep.size() && CGAL::collinear(ep[0], ep[i1], ep[i2])) ++i2;
  if (i2 >= ep.size())
    throw InputError(source, "", "degenerate: all " + n + " points are collinear (a segment, not a solid)");
  std::size_t i3 = i2 + 1;
  while (i3 < ep.size() && CGAL::coplanar(ep[0], ep[i1], ep[i2], ep[i3])) ++i3;
  if (i3 >= ep.size())
    throw InputError(source, "", "degenerate: all " + n + " points are coplanar (a polygon, not a solid)");

  CGAL::Surface_mesh<E::Point_3> sm;
  CGAL::convex_hull_3(ep.begin(), ep.end(), sm);
  // Hull vertices back to input points (first occurrence), as above.
  struct Hash {
    std::size_t operator()(const E::Point_3& p) const {
      std::size_t h = 0;
      for (int k = 0; k < 3; ++k) h = (h ^ std::hash<double>()(p[k])) * 0x9e3779b97f4a7c15ULL;
      return h;
    }
  };
  std::unordered_map<E::Point_3, Index, Hash> index_of;
  index_of.reserve(ep.size());
  for (Index i = 0; i < ep.size(); ++i) index_of.try_emplace(ep[i], i);
  std::vector<std::pair<Index, std::size_t>> order;
  for (auto v : sm.vertices()) {
    auto it = index_of.find(sm.point(v));
    if (it == index_of.end()) throw std::logic_error("convex hull produced a point that is not an input point");
    order.emplace_back(it->second, std::size_t(v));
  }
  std::sort(order.begin(), order.end());
  Mesh m;
  std::vector<Index> input_index;
  std::unordered_map<std::size_t, Index> local;
  for (auto [input, v] : order) {
    local[v] = Index(m.points.size());
    m.points.push_back(points.approx(input));
    input_index.push_back(input);
  }
  for (auto f : sm.faces()) {
    std::vector<Index> poly;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) poly.push_back(local[std::size_t(v)]);
    std::rotate(poly.begin(), std::min_element(poly.begin(), poly.end()), poly.end());
    m.faces.push_back(std::move(poly));
  }
  std::sort(m.faces.begin(), m.faces.end());
  ConvexPolytope result = PolytopeBuilder::build(m, source);
  PolytopeBuilder::canonicalize_facets(result);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

}  // namespace minksum
