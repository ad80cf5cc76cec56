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

// Degenerate point sets are recognised before CGAL sees them, exactly:
// `coincide(i)`, `collinear(i1, i)`, `coplanar(i1, i2, i)` test point i
// against point 0 and the points found before it.
template <class Coincide, class Collinear, class Coplanar>
void check_dimension(std::size_t size, Coincide coincide, Collinear collinear, Coplanar coplanar,
                     const std::string& source) {
  const std::string n = std::to_string(size);
  if (size == 0) throw InputError(source, "", "no points");
  std::size_t i1 = 1;
  while (i1 < size && coincide(i1)) ++i1;
  if (i1 == size)
    throw InputError(source, "", "degenerate: all " + n + " points coincide (a single point, not a solid)");
  std::size_t i2 = i1 + 1;
  while (i2 < size && collinear(i1, i2)) ++i2;
  if (i2 >= size)
    throw InputError(source, "", "degenerate: all " + n + " points are collinear (a segment, not a solid)");
  std::size_t i3 = i2 + 1;
  while (i3 < size && coplanar(i1, i2, i3)) ++i3;
  if (i3 >= size)
    throw InputError(source, "", "degenerate: all " + n + " points are coplanar (a polygon, not a solid)");
}

void check_dimension(const std::vector<Point3>& pts, const std::string& source) {
  Point3 nrm;  // of the first non-collinear triple
  check_dimension(
      pts.size(), [&](std::size_t i) { return pts[i] == pts[0]; },
      [&](std::size_t i1, std::size_t i) {
        nrm = cross(pts[i1] - pts[0], pts[i] - pts[0]);
        return is_zero(nrm);
      },
      [&](std::size_t, std::size_t, std::size_t i) { return sgn(dot(nrm, pts[i] - pts[0])) == 0; }, source);
}

// The hull's surface mesh as a canonical Mesh, whatever order CGAL produced
// (it varies between calls): vertices in the order of the input points
// (`input_of(p)`: the first input index of hull point p; `push(points, i)`
// appends input point i), each triangle starting at its smallest vertex,
// triangles sorted.  input_index[v] = the input point of mesh vertex v.
template <class SurfaceMesh, class InputOf, class Push>
Mesh canonical_mesh(const SurfaceMesh& sm, InputOf input_of, Push push, std::vector<Index>& input_index) {
  std::vector<std::pair<Index, std::size_t>> order;  // (input index, surface-mesh vertex)
  for (auto v : sm.vertices()) order.emplace_back(input_of(sm.point(v)), std::size_t(v));
  std::sort(order.begin(), order.end());
  Mesh m;
  std::unordered_map<std::size_t, Index> local;  // surface-mesh vertex -> mesh index
  for (auto [input, v] : order) {
    local[v] = Index(m.points.size());
    push(m.points, input);
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

[[noreturn]] void not_an_input_point() {
  throw std::logic_error("convex hull produced a point that is not an input point");
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
  std::vector<Index> input_index;
  const Mesh m = canonical_mesh(
      sm,
      [&](const KPoint& p) {
        auto it = index_of.find(to_point3(p));
        if (it == index_of.end()) not_an_input_point();
        return it->second;
      },
      [&](PointList& out, Index i) { out.push_back(points[i]); }, input_index);
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
  check_dimension(
      ep.size(), [&](std::size_t i) { return ep[i] == ep[0]; },
      [&](std::size_t i1, std::size_t i) { return CGAL::collinear(ep[0], ep[i1], ep[i]); },
      [&](std::size_t i1, std::size_t i2, std::size_t i) { return CGAL::coplanar(ep[0], ep[i1], ep[i2], ep[i]); },
      source);

  CGAL::Surface_mesh<E::Point_3> sm;
  CGAL::convex_hull_3(ep.begin(), ep.end(), sm);
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
  std::vector<Index> input_index;
  const Mesh m = canonical_mesh(
      sm,
      [&](const E::Point_3& p) {
        auto it = index_of.find(p);
        if (it == index_of.end()) not_an_input_point();
        return it->second;
      },
      [&](PointList& out, Index i) { out.push_back(points.approx(i)); }, input_index);
  ConvexPolytope result = PolytopeBuilder::build(m, source);
  PolytopeBuilder::canonicalize_facets(result);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

}  // namespace minksum
