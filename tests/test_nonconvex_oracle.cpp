// Non-convex sums against CGAL's Nef polyhedron minkowski_sum_3 (Hachenberger,
// Algorithmica 2009), the exact oracle: equal exact volume and equal sets of
// boundary planes on small non-convex cases.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex_support.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/minkowski_sum_3.h>

#include <gtest/gtest.h>

#include <set>

using namespace minksum;
using namespace minksum::testing;

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Nef = CGAL::Nef_polyhedron_3<K>;
using Polyhedron = CGAL::Polyhedron_3<K>;

Nef nef_of(const Mesh& m) {
  std::vector<K::Point_3> pts;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = m.points[i];
    pts.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
  }
  std::vector<std::vector<std::size_t>> faces;
  for (const auto& f : m.faces) faces.emplace_back(f.begin(), f.end());
  Polyhedron poly;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, faces, poly);
  return Nef(poly);
}

struct Boundary {
  Rational volume;
  std::set<Plane> planes;
};

// The oracle's volume (the signed tetrahedra of each boundary polygon) and
// the planes of its boundary polygons.
Boundary oracle(const Solid& a, const Solid& b) {
  Nef na = nef_of(a.triangles), nb = nef_of(b.triangles);
  Nef s = CGAL::minkowski_sum_3(na, nb);
  std::vector<K::Point_3> pts;
  std::vector<std::vector<std::size_t>> polys;
  CGAL::convert_nef_polyhedron_to_polygon_soup(s, pts, polys, false);
  Mesh m;
  for (const auto& p : pts) {
    const auto& e = CGAL::exact(p);
    m.points.push_back(Point3(Rational(e.x()), Rational(e.y()), Rational(e.z())));
  }
  for (const auto& f : polys) m.faces.emplace_back(f.begin(), f.end());
  Boundary o;
  o.volume = mesh_volume(m);
  o.planes = face_planes(m);
  return o;
}


void expect_like_oracle(const std::string& a, const std::string& b) {
  SCOPED_TRACE(a + " + " + b);
  const Solid sa = validate_solid(catalog_mesh(a), a), sb = validate_solid(catalog_mesh(b), b);
  const NonconvexSum r = minkowski_sum_nonconvex(sa, sb);
  const Boundary o = oracle(sa, sb);
  EXPECT_EQ(r.volume, o.volume);
  EXPECT_EQ(face_planes(r.mesh), o.planes);
}

}  // namespace

TEST(NonconvexOracle, TubePlusCube) { expect_like_oracle("tube", "cube@scale:1/4@rot:3"); }
TEST(NonconvexOracle, LShapePlusOctahedron) { expect_like_oracle("lshape", "octahedron@scale:1/3"); }
TEST(NonconvexOracle, HoleThatClosesExactly) { expect_like_oracle("tube", "box:1:1:1"); }
TEST(NonconvexOracle, StarPlusIcosahedron) { expect_like_oracle("star:5", "sphere:1@scale:1/4"); }
TEST(NonconvexOracle, NonConvexPlusNonConvex) { expect_like_oracle("tube", "lshape@scale:1/4@rot:7"); }
TEST(NonconvexOracle, RingPlusTetrahedron) { expect_like_oracle("ring:6", "tetra@scale:1/8"); }
