// The exact convex hull of a point cloud: CGAL's convex_hull_3 on exact
// points (Epeck, whose exact number type is mpq_class here), then the
// triangulated hull goes through the validating builder, which merges
// coplanar triangles and drops points in the middle of edges.  Points that
// are all doubles use CGAL's Epick kernel instead, by quickhull or, for
// points that are nearly all extreme, by an incremental triangulation.
//
// This is the only translation unit of src/mesh that includes CGAL.
#include "mesh/builder.hpp"
#include "mesh/weld.hpp"
#include "kernel/big_array.hpp"

#include <minksum/error.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <array>
#include <numeric>
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

[[noreturn]] void not_an_input_point() {
  throw std::logic_error("convex hull produced a point that is not an input point");
}

// The first input point exactly equal to each vertex of the hull's surface
// mesh (indexed by vertex): weld_exact over the input points `all`
// followed by the hull's vertices (`add(all, p)` appends hull point p).
template <class SurfaceMesh, class Add>
std::vector<Index> inputs_of_vertices(const SurfaceMesh& sm, PointList all, Add add) {
  const Index n = Index(all.size());
  std::size_t slots = 0;
  for (auto v : sm.vertices()) slots = std::max(slots, std::size_t(v) + 1);
  std::vector<Index> at(slots, kNoIndex);
  for (auto v : sm.vertices()) {
    at[std::size_t(v)] = Index(all.size());
    add(all, sm.point(v));
  }
  const std::vector<Index> canon = weld_exact(all);
  for (Index& i : at)
    if (i != kNoIndex && (i = canon[i]) >= n) not_an_input_point();
  return at;
}

// The hull's surface mesh as a canonical Mesh, whatever order CGAL produced
// (it varies between calls): vertices in the order of the input points
// (`input_of[v]`: the first input index of hull vertex v; `push(points, i)`
// appends input point i), each triangle starting at its smallest vertex,
// triangles sorted.  input_index[v] = the input point of mesh vertex v.
template <class SurfaceMesh, class Push>
Mesh canonical_mesh(const SurfaceMesh& sm, const std::vector<Index>& input_of, Push push,
                    std::vector<Index>& input_index) {
  std::vector<std::pair<Index, std::size_t>> order;  // (input index, surface-mesh vertex)
  for (auto v : sm.vertices()) order.emplace_back(input_of[std::size_t(v)], std::size_t(v));
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

// The polytope of a triangulated hull: validated (coplanar triangles
// merged, points inside facets and edges dropped), facets in canonical
// order.  The caller numbers its source vertices as the input points.
ConvexPolytope validated_hull(const Mesh& m, const std::string& source) {
  ConvexPolytope result = PolytopeBuilder::build(m, source);
  // CGAL may triangulate a coplanar facet differently from call to call,
  // which changes the merged facets' order and first vertices: fix both.
  PolytopeBuilder::canonicalize_facets(result);
  return result;
}

using E = CGAL::Exact_predicates_inexact_constructions_kernel;

// The points of a list that are all doubles, as Epick points, after the
// exact check that they span 3 dimensions.
std::vector<E::Point_3> epick_points(const PointList& points, const std::string& source) {
  std::vector<E::Point_3> ep;
  ep.reserve(points.size());
  for (const Vec3d& v : points.approx()) ep.emplace_back(v.x, v.y, v.z);
  check_dimension(
      ep.size(), [&](std::size_t i) { return ep[i] == ep[0]; },
      [&](std::size_t i1, std::size_t i) { return CGAL::collinear(ep[0], ep[i1], ep[i]); },
      [&](std::size_t i1, std::size_t i2, std::size_t i) { return CGAL::coplanar(ep[0], ep[i1], ep[i2], ep[i]); },
      source);
  return ep;
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
  std::vector<Index> input_index;
  const Mesh m = canonical_mesh(
      sm, inputs_of_vertices(sm, PointList(points), [](PointList& all, const KPoint& p) { all.push_back(to_point3(p)); }),
      [&](PointList& out, Index i) { out.push_back(points[i]); }, input_index);
  ConvexPolytope result = validated_hull(m, source);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

// Points that are all doubles: CGAL's Epick kernel, whose predicates are
// exact (filtered, with exact fallbacks) and whose convex hull traits use no
// constructions (Convex_hull_traits_3: a plane is a triple of points), so the
// hull is the exact one, without a rational per coordinate.
ConvexPolytope ConvexPolytope::hull(const PointList& points, const std::string& source) {
  if (!points.all_doubles()) return hull(points.to_points(), source);
  const std::vector<E::Point_3> ep = epick_points(points, source);

  CGAL::Surface_mesh<E::Point_3> sm;
  CGAL::convex_hull_3(ep.begin(), ep.end(), sm);
  std::vector<Index> input_index;
  const Mesh m = canonical_mesh(
      sm,
      inputs_of_vertices(sm, points,
                         [](PointList& all, const E::Point_3& p) { all.push_back(Vec3d{p.x(), p.y(), p.z()}); }),
      [&](PointList& out, Index i) { out.push_back(points.approx(i)); }, input_index);
  ConvexPolytope result = validated_hull(m, source);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

// Points that are nearly all extreme (spread over a sphere): quickhull
// spends its time redistributing the outside sets of points that all end on
// the hull.  CGAL's Triangulation_3 builds the same hull incrementally
// instead: the points are inserted in spatial order (Amenta, Choi and Rote,
// "Incremental constructions con BRIO", SoCG 2003), each located from the
// cell of the previous one, and a point outside the current hull is joined to
// the hull facets it sees.  Every decision is an orientation sign of Epick,
// exact (filtered, exact fallback); no point is constructed.  The hull is then
// the link of the infinite vertex: the finite facet of every infinite cell,
// oriented by CGAL's convention so that its normal points to the infinite
// vertex, i.e. outwards.  Points on the boundary that are not extreme (inside
// a facet or an edge of the hull) may be vertices of that triangulated
// surface, where quickhull leaves them out; the builder drops them as it
// drops them from any mesh (degree 2, or vanished inside a merged facet), so
// the polytope is the same, vertex for vertex: the surviving vertices keep
// the order of their input points.
ConvexPolytope PolytopeBuilder::hull_of_extreme_points(const PointList& points, const std::string& source) {
  if (!points.all_doubles()) return ConvexPolytope::hull(points, source);
  const std::size_t n = points.size();
  std::vector<std::array<Index, 3>> triangles;  // input points, counter-clockwise seen from outside
  {
    std::vector<E::Point_3> ep = epick_points(points, source);
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<Index, E>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Triangulation_cell_base_3<E>>;
    using Triangulation = CGAL::Triangulation_3<E, Tds>;
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    using Map = CGAL::Pointer_property_map<E::Point_3>::type;
    CGAL::spatial_sort(order.begin(), order.end(),
                       CGAL::Spatial_sort_traits_adapter_3<E, Map>(CGAL::make_property_map(ep)));
    Triangulation tr;
    Triangulation::Cell_handle hint;
    for (std::size_t i : order) {
      const std::size_t before = tr.number_of_vertices();
      const Triangulation::Vertex_handle v = tr.insert(ep[i], hint);
      // A repeated point is the vertex of its first copy.
      v->info() = tr.number_of_vertices() != before ? Index(i) : std::min(v->info(), Index(i));
      hint = v->cell();
    }
    // The hull's triangles, as input points: the finite facet of each
    // infinite cell.
    const Triangulation::Vertex_handle infinite = tr.infinite_vertex();
    triangles.reserve(2 * n);
    for (auto c = tr.all_cells_begin(); c != tr.all_cells_end(); ++c) {
      int i = 0;
      if (!c->has_vertex(infinite, i)) continue;
      std::array<Index, 3> t;
      for (int k = 0; k < 3; ++k) t[k] = c->vertex(Triangulation::vertex_triple_index(i, k))->info();
      triangles.push_back(t);
    }
  }  // the triangulation is freed before the mesh and the polytope are built
  // Hull vertices numbered in the order of their input points.
  std::vector<Index> local(n, kNoIndex);  // input point -> mesh vertex
  for (const auto& t : triangles)
    for (Index i : t) local[i] = 0;
  std::vector<Index> input_index;  // mesh vertex -> input point
  for (std::size_t i = 0; i < n; ++i)
    if (local[i] == 0) {
      local[i] = Index(input_index.size());
      input_index.push_back(Index(i));
    }
  Mesh m;
  m.points.reserve(input_index.size());
  for (Index i : input_index) m.points.push_back(points.approx(i));
  m.faces.reserve(triangles.size());
  for (const auto& t : triangles) {
    std::vector<Index> tri{local[t[0]], local[t[1]], local[t[2]]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    m.faces.push_back(std::move(tri));
  }
  release(triangles);
  release(local);
  ConvexPolytope result = validated_hull(m, source);
  for (auto& s : result.source_vertex_) s = input_index[s];
  return result;
}

}  // namespace minksum
