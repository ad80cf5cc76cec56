// The boundary sweep of the non-convex sum (docs/nonconvex.md, "Method"):
// the same exact boundary as Hachenberger's decomposition method on every
// case (equal exact volume, vertex set, face planes, face, shell and
// non-manifold edge counts), the normal-cone culling, the pockets of the
// sweep dropped inside A + b, the local cones themselves and the exact
// point-in-solid test.  The CGAL minkowski_sum_3 oracle runs on the default
// (sweep) method in test_nonconvex_oracle.cpp.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex/sweep.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <set>

using namespace minksum;
using namespace minksum::testing;

namespace {

Solid solid(const std::string& spec) { return validate_solid(catalog_mesh(spec), spec); }

// [-2,2]^3 with the cavity [-1,1]^3.
Solid hollow_solid() { return validate_solid(hollow_cube(), "hollow"); }

void expect_same_as_decomposition(const Solid& a, const Solid& b, const std::string& name) {
  SCOPED_TRACE(name);
  const NonconvexSum s = minkowski_sum_nonconvex(a, b, {}, 0, Method::walk, NonconvexMethod::sweep);
  const NonconvexSum d = minkowski_sum_nonconvex(a, b, {}, 0, Method::walk, NonconvexMethod::decomposition);
  EXPECT_STREQ(s.method, "sweep");
  EXPECT_STREQ(d.method, "decomposition");
  expect_closed_oriented(s);
  expect_no_vertex_inside_an_edge(s.mesh);
  EXPECT_EQ(s.volume, d.volume);
  EXPECT_EQ(vertex_set(s.mesh), vertex_set(d.mesh));
  EXPECT_EQ(face_planes(s.mesh), face_planes(d.mesh));
  EXPECT_EQ(s.mesh.faces.size(), d.mesh.faces.size());
  EXPECT_EQ(s.shells, d.shells);
  EXPECT_EQ(s.non_manifold_edges, d.non_manifold_edges);
}

void expect_same_as_decomposition(const std::string& a, const std::string& b) {
  expect_same_as_decomposition(solid(a), solid(b), a + " + " + b);
}

}  // namespace

// ---------------------------------------------------------------------------
// The same boundary as the decomposition method.

TEST(NonconvexSweep, TubePlusRotatedCube) { expect_same_as_decomposition("tube", "cube@scale:1/4@rot:3"); }
TEST(NonconvexSweep, LShapePlusOctahedron) { expect_same_as_decomposition("lshape", "octahedron@scale:1/3"); }
TEST(NonconvexSweep, HoleThatClosesExactly) { expect_same_as_decomposition("tube", "box:1:1:1"); }
TEST(NonconvexSweep, HoleThatAlmostCloses) { expect_same_as_decomposition("tube", "box:1:1:1@scale:9/10"); }
TEST(NonconvexSweep, StarPlusIcosahedron) { expect_same_as_decomposition("star:5", "sphere:1@scale:1/4"); }
TEST(NonconvexSweep, RingPlusTetrahedron) { expect_same_as_decomposition("ring:6", "tetra@scale:1/8"); }
TEST(NonconvexSweep, GearPlusCylinder) { expect_same_as_decomposition("gear:6", "prism:8@scale:1/8"); }
TEST(NonconvexSweep, ConvexOperandFirst) { expect_same_as_decomposition("cube@scale:1/4@rot:3", "tube"); }
TEST(NonconvexSweep, NonConvexPlusNonConvex) { expect_same_as_decomposition("tube", "lshape@scale:1/4@rot:7"); }
TEST(NonconvexSweep, NonConvexPlusLargerNonConvex) { expect_same_as_decomposition("lshape@scale:1/4", "tube"); }
TEST(NonconvexSweep, TorusPlusBall) { expect_same_as_decomposition("torus:8:6", "sphere:1@scale:1/5"); }
TEST(NonconvexSweep, TorusPlusLargeBallClosesTheHole) {
  expect_same_as_decomposition("torus:8:6", "sphere:1@scale:3/4");
}
TEST(NonconvexSweep, AxisAlignedContactsOfTheLShape) { expect_same_as_decomposition("lshape", "box:1:1:1"); }

TEST(NonconvexSweep, CavityKeptShrinksAndVanishes) {
  const Solid h = hollow_solid();
  for (const char* b : {"box:1/2:1/2:1/2", "box:1:1:1", "box:2:2:2", "sphere:1@scale:1/2", "cube@rot:3@scale:1/3"})
    expect_same_as_decomposition(h, solid(b), std::string("hollow + ") + b);
}

// ---------------------------------------------------------------------------
// Culling and the pockets inside A + b.

TEST(NonconvexSweep, CullsTheFacetsOutsideTheNormalCones) {
  const NonconvexSum r = minkowski_sum_nonconvex(solid("torus:8:6"), solid("sphere:2@scale:1/10"));
  EXPECT_EQ(r.pieces_a, 96u);  // 2 * 8 * 6 triangles swept
  EXPECT_EQ(r.pieces_b, 1u);
  EXPECT_EQ(r.swept, 'a');
  EXPECT_EQ(r.candidate_facets + r.culled_facets, r.pair_facets);
  // A triangle's piece has about 90 facets; at most the triangle itself, a few
  // edge facets and those of its vertices' cones can be on the boundary.
  EXPECT_GT(r.culled_facets, 4 * r.candidate_facets);
  EXPECT_EQ(r.shells, 1u);
}

// [-2,2]^3 with the cavity [-1,1]^3, plus [-1/4,1/4]^3: the sweep of the
// cavity's surface and of the outer surface leave between them the pocket
// 5/4 <= |x|_inf <= 7/4, inside A + b.  The cavity's reflex corners keep a
// few facets of the box as candidates (their cones are over-approximated);
// they bound that pocket and are dropped with it.
TEST(NonconvexSweep, PocketInsideTheSolidIsDropped) {
  const NonconvexSum r = minkowski_sum_nonconvex(hollow_solid(), solid("box:1/2:1/2:1/2"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(9 * 9 * 9 - 3 * 3 * 3) / 8);
  EXPECT_EQ(r.mesh.faces.size(), 12u);
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_GE(r.dropped_components, 1u);
}

// ---------------------------------------------------------------------------
// The local cones and the point-in-solid test.

TEST(NonconvexSweep, ConesOfACube) {
  const Solid c = validate_solid(cube_mesh(1), "cube");
  const nonconvex_detail::SurfaceCones cones(c.triangles);
  auto p = [](int x, int y, int z) { return Point3(Rational(x), Rational(y), Rational(z)); };
  for (Index t = 0; t < cones.triangles(); ++t) {
    // A triangle's outward normal is in its own cone, the opposite one not.
    const auto& tri = cones.triangle(t);
    const Point3 n = cross(cones.point(tri[1]) - cones.point(tri[0]), cones.point(tri[2]) - cones.point(tri[0]));
    EXPECT_TRUE(cones.candidate(t, n));
    EXPECT_FALSE(cones.candidate(t, -n));
  }
  // Directions into the cube from a face are never candidates; the diagonal
  // (1,1,1) is one only for the triangles at the corner (1,1,1).
  std::size_t with_corner = 0, diagonal = 0;
  for (Index t = 0; t < cones.triangles(); ++t) {
    const auto& tri = cones.triangle(t);
    bool corner = false;
    for (Index v : tri) corner |= cones.point(v) == p(1, 1, 1);
    with_corner += corner;
    const bool cand = cones.candidate(t, p(1, 1, 1));
    diagonal += cand;
    if (cand) {
      EXPECT_TRUE(corner);
    }
  }
  EXPECT_EQ(diagonal, with_corner);
  EXPECT_GT(diagonal, 0u);
}

TEST(NonconvexSweep, ReflexEdgeHasNoConeOfItsOwn) {
  // The L's reflex edge runs along z at (0, 0), between its faces on y = 0
  // (normal +y) and x = 0 (normal +x).  Perpendicular to it, (-1, 1, 0) puts
  // the edge at the top of the triangles on y = 0 and (1, -1, 0) at the top of
  // those on x = 0: the edge's own cone is empty and its end vertices' cones
  // hold neither direction.
  const Solid l = solid("lshape");
  const nonconvex_detail::SurfaceCones cones(l.triangles);
  const Point3 u(Rational(-1), Rational(1), Rational(0));
  std::size_t at_edge = 0;
  for (Index t = 0; t < cones.triangles(); ++t) {
    const auto& tri = cones.triangle(t);
    int on_axis = 0;
    for (Index v : tri) on_axis += sgn(cones.point(v).x) == 0 && sgn(cones.point(v).y) == 0;
    if (on_axis == 2) {
      ++at_edge;
      EXPECT_FALSE(cones.candidate(t, u)) << "triangle " << t;
      EXPECT_FALSE(cones.candidate(t, -u)) << "triangle " << t;
    }
  }
  EXPECT_EQ(at_edge, 2u);
}

TEST(NonconvexSweep, PointInSolidIsExact) {
  const Solid h = hollow_solid();
  const nonconvex_detail::SurfaceCones cones(h.triangles);
  auto p = [](Rational x, Rational y, Rational z) { return Point3(x, y, z); };
  EXPECT_FALSE(cones.strictly_inside(p(0, 0, 0)));                      // in the cavity
  EXPECT_TRUE(cones.strictly_inside(p(Rational(3, 2), 0, 0)));          // in the wall
  EXPECT_TRUE(cones.strictly_inside(p(Rational(3, 2), Rational(3, 2), Rational(3, 2))));  // on many rays' planes
  EXPECT_FALSE(cones.strictly_inside(p(3, 0, 0)));                      // outside
  EXPECT_TRUE(cones.strictly_inside(p(Rational(-199, 100), Rational(199, 100), 0)));  // near an edge
  EXPECT_FALSE(cones.strictly_inside(p(Rational(201, 100), Rational(2), Rational(2))));
  EXPECT_THROW(cones.strictly_inside(p(2, 0, 0)), std::logic_error);    // on the surface
}

// ---------------------------------------------------------------------------
// Properties on a larger case (the decomposition would take minutes here).

// torus:32:16 (1 024 triangles) ⊕ a small ball: one closed genus-1 surface
// (V - E + F = 0), the sum contains the torus (larger volume), and
// translating the torus translates the sum exactly.
TEST(NonconvexSweep, LargeTorusPlusBallProperties) {
  const Solid t = solid("torus:32:16");
  const Solid b = solid("sphere:1@scale:1/20");
  const NonconvexSum r = minkowski_sum_nonconvex(t, b);
  expect_closed_oriented(r);
  EXPECT_EQ(r.shells, 1u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  std::set<std::pair<Index, Index>> edges;
  for (const auto& f : r.mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i)
      edges.insert({std::min(f[i], f[(i + 1) % f.size()]), std::max(f[i], f[(i + 1) % f.size()])});
  EXPECT_EQ(long(r.mesh.points.size()) - long(edges.size()) + long(r.mesh.faces.size()), 0L);
  EXPECT_GT(r.volume, t.volume);
  EXPECT_GT(r.culled_facets, 10 * r.candidate_facets);

  const Solid moved = solid("torus:32:16@translate:1/3,-2,5/7");
  const NonconvexSum m = minkowski_sum_nonconvex(moved, b);
  const Point3 shift(Rational(1, 3), Rational(-2), Rational(5, 7));
  std::set<Point3> expected;
  for (const Point3& p : vertex_set(r.mesh)) expected.insert(p + shift);
  EXPECT_EQ(vertex_set(m.mesh), expected);
  EXPECT_EQ(m.volume, r.volume);
}
