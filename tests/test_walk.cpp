// walk: exactly equal to the chms oracle and to cvms (same vertex set, same
// facet planes, same counts) on the families of the other method suites, on
// degenerate and near-degenerate pairs, and on 600 random pairs; the
// half-edge structure it builds directly passes every invariant of
// ConvexPolytope re-checked from scratch; provenance equal to the brute-force
// one; commutative.
#include <minksum/catalog.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope cat(const std::string& s) { return catalog_polytope(s); }

void expect_matches_oracle(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                           bool slow_checks = true) {
  SCOPED_TRACE(label);
  const SumResult oracle = minkowski_sum_chms(a, b);
  const WalkSum w = minkowski_walk(a, b);
  // The structure itself has the oracle's counts: nothing left to merge.
  ASSERT_EQ(w.num_vertices(), oracle.polytope.num_vertices());
  ASSERT_EQ(w.num_edges(), oracle.polytope.num_edges());
  ASSERT_EQ(w.num_facets(), oracle.polytope.num_facets());
  const ConvexPolytope s = to_polytope(w, a, b);
  ASSERT_EQ(s.check_invariants(), "");
  EXPECT_TRUE(same_polytope(s, oracle.polytope));
  for (Index v = 0; v < s.num_vertices(); ++v) {
    auto [i, j] = w.vertex_origin[v];
    ASSERT_EQ(s.point(v), a.point(i) + b.point(j));
  }
  if (slow_checks) {
    EXPECT_EQ(w.provenance, facet_provenance(a, b, s));
    EXPECT_TRUE(same_polytope(minkowski_sum_cvms(a, b).polytope, s));
  }
  const SumResult ba = minkowski_sum(b, a, Method::walk);
  EXPECT_TRUE(same_polytope(ba.polytope, s));
}

void expect_matches_oracle(const std::string& a, const std::string& b, bool slow_checks = true) {
  expect_matches_oracle(cat(a), cat(b), a + " + " + b, slow_checks);
}

}  // namespace

TEST(Walk, IsTheAutomaticChoice) {
  EXPECT_TRUE(method_available(Method::walk));
  const SumResult r = minkowski_sum(cat("cube"), cat("octahedron"));
  EXPECT_EQ(r.method, Method::walk);
  EXPECT_EQ(r.polytope.num_vertices(), 24u);
  EXPECT_EQ(r.polytope.num_edges(), 48u);
  EXPECT_EQ(r.polytope.num_facets(), 26u);
}

TEST(Walk, AllPairsOfSmallSolids) {
  for (const std::string& x : small_solids())
    for (const std::string& y : small_solids())
      if (x <= y) expect_matches_oracle(x, y);
}

TEST(Walk, CubeOctahedronProvenance) {
  // 6 translated + 8 corner + 12 edge facets; the 12 edge facets are the
  // 12 crossings of the cube's arcs with the octahedron's.
  const WalkSum w = minkowski_walk(cat("cube"), cat("octahedron"));
  int count[5] = {0, 0, 0, 0, 0};
  for (const auto& p : w.provenance) ++count[int(p.origin())];
  EXPECT_EQ(count[int(FacetOrigin::translated)], 6);
  EXPECT_EQ(count[int(FacetOrigin::corner)], 8);
  EXPECT_EQ(count[int(FacetOrigin::edge)], 12);
  EXPECT_EQ(w.crossings, 12u);
}

TEST(Walk, CubePlusGeodesicSpheres) {
  for (int level = 1; level <= 5; ++level)
    expect_matches_oracle("cube", "sphere:" + std::to_string(level), level <= 3);
}

TEST(Walk, IdenticalOperands) {
  // A = B: every facet of A meets its parallel twin, every arc runs along an
  // arc of B (the walk's overlap state all the way).
  const WalkSum w = minkowski_walk(cat("sphere:3"), cat("sphere:3"));
  EXPECT_EQ(w.num_facets(), 320u);
  EXPECT_EQ(w.crossings, 0u);
  for (const auto& p : w.provenance) EXPECT_EQ(p.origin(), FacetOrigin::facet_facet);
  expect_matches_oracle("sphere:3", "sphere:3");
  expect_matches_oracle("cube", "cube");
  expect_matches_oracle("dodecahedron@rot:3", "dodecahedron@rot:3");
  expect_matches_oracle("random:40:7", "random:40:7");
}

TEST(Walk, IdenticalOperandsNeedNoExactStage) {
  // A ⊕ A with facets not axis-aligned: almost every degenerate sign is
  // <an edge of one copy, n(the facet of the other copy carrying the same
  // edge)> = 0, or two equal edge vectors in the facet merge, certified by
  // the exact equality of the difference vectors (no GMP).  The few left
  // are nonzero signs too close for the filter.
  const ConvexPolytope a = cat("sphere:4");
  const WalkSum w = minkowski_walk(a, a);
  EXPECT_EQ(w.num_vertices(), 642u);
  EXPECT_EQ(w.num_edges(), 1920u);
  EXPECT_EQ(w.num_facets(), 1280u);
  EXPECT_LT(100 * w.exact_predicates, w.predicates) << w.exact_predicates << " of " << w.predicates;
  expect_matches_oracle(a, a, "sphere:4 + sphere:4", false);
}

TEST(Walk, CopiesTranslatedScaledReflected) {
  // The zero certificates (equal or opposite difference vectors) against
  // copies whose differences are equal (translates by exact doubles),
  // opposite (point reflections), scaled by a power of two (no equal
  // difference), scaled by 3 (rounded), and rational copies (certified only
  // for identical points).
  expect_matches_oracle("sphere:3", "sphere:3@translate:1/2,-3,1/4");
  expect_matches_oracle("sphere:3", "sphere:3@translate:1e-20,0,0", false);
  expect_matches_oracle("sphere:3", "sphere:3@neg");
  expect_matches_oracle("sphere:3@translate:5,0,0", "sphere:3@neg");
  expect_matches_oracle("sphere:3", "sphere:3@scale:2");
  expect_matches_oracle("sphere:3", "sphere:3@scale:3", false);
  expect_matches_oracle("icosahedron@rot:3", "icosahedron@rot:3");
  expect_matches_oracle("sphere:2@rot:1", "sphere:2@rot:1");
  expect_matches_oracle("sphere:2@rot:1", "sphere:2@rot:1@neg");
  expect_matches_oracle("random:60:5", "random:60:5@translate:1/8,1/16,-2");
  expect_matches_oracle("random:60:5", "random:60:5@neg");
}

TEST(Walk, NearlyIdenticalOperandsWithEqualRoundedDifferences) {
  // B is A with one vertex moved by 2^-60 along y: the edges at that vertex
  // differ from A's by 2^-60, below the rounding of their differences
  // (fl(0.5 − 2^-60) = 0.5), so the rounded differences are equal and the
  // exact ones are not: the zero certificate must not fire (the signs are
  // nonzero and decided exactly).
  const std::vector<Vec3d> pts = {{0.3, 0, 0.7},    {1, 0.3, 0.2},     {-0.7, 1, 0.1},   {0.2, -0.9, 0.8},
                                  {0.1, 0.2, -1},   {-0.5, -0.4, -0.6}, {0.6, 0.7, 0.9},  {-0.8, -0.1, 0.5},
                                  {0.5, -0.5, -0.5}};
  std::vector<Point3> pa, pb;
  for (const Vec3d& v : pts) pa.emplace_back(v.x, v.y, v.z);
  pb = pa;
  pb[0] = Point3(0.3, 0x1p-60, 0.7);
  const ConvexPolytope a = ConvexPolytope::hull(pa), b = ConvexPolytope::hull(pb);
  ASSERT_TRUE(a.coordinates_are_doubles());
  ASSERT_TRUE(b.coordinates_are_doubles());
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  expect_matches_oracle(a, b, "A + A with one vertex moved by 2^-60");
  expect_matches_oracle(a, a.negated(), "A + -A");
  expect_matches_oracle(b, a.negated(), "B + -A");
}

TEST(Walk, PointReflections) {
  // A ⊕ −A (the configuration-space obstacle of A against itself): every
  // arc of A meets the antipodal image of itself.
  expect_matches_oracle("tetra", "tetra@neg");
  expect_matches_oracle("sphere:2", "sphere:2@neg");
  expect_matches_oracle("truncated-tetrahedron@rot:5", "truncated-tetrahedron@rot:5@neg");
  expect_matches_oracle("random:30:3", "random:30:3@neg");
}

TEST(Walk, QuarterTurnsAndArcsThroughVertices) {
  // Exact quarter turns map facet normals onto facet normals and arcs onto
  // arcs: normals on arcs, arcs through vertices, arcs along arcs.
  expect_matches_oracle("cube", "cube@rot:1,1,0,0");
  expect_matches_oracle("cube", "octahedron@rot:1,1,0,0");
  expect_matches_oracle("cuboctahedron", "rhombic-dodecahedron@rot:1,0,0,1");
  expect_matches_oracle("truncated-octahedron", "cube@rot:1,1,1,1");
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:1,0,0,1");
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:1,1,0,0");
  expect_matches_oracle("dioctagonal:9", "dioctagonal:9@rot:7");
}

TEST(Walk, NearlyDegeneratePairs) {
  // Rotations by a tiny angle: arcs cross at angles the filter cannot
  // always resolve (exact fallback), features nearly coincide.
  expect_matches_oracle("cube", "cube@rot:100000,1,0,0");
  expect_matches_oracle("cube", "cube@rot:1000000,1,1,1");
  expect_matches_oracle("sphere:2", "sphere:2@rot:100000,1,2,3");
  expect_matches_oracle("icosahedron", "icosahedron@rot:1000000,0,0,1");
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:100,0,0,99");
}

TEST(Walk, ZonotopesWithParallelEdges) {
  expect_matches_oracle("zonotope:5:1", "zonotope:5:2");
  expect_matches_oracle("zonotope:6:3", "zonotope:6:3");
  // Parallel edges everywhere, equal and opposite edge vectors: the zero
  // certificates.
  expect_matches_oracle("zonotope:6:3", "zonotope:6:3@neg");
  expect_matches_oracle("zonotope:6:3", "zonotope:6:3@translate:1/2,1/2,0");
  expect_matches_oracle("zonotope:5:1", "zonotope:5:1@scale:2");
  expect_matches_oracle("zonotope:4:7", "cube");
  expect_matches_oracle("zonotope:1,0,0:0,1,0:1,1,0:0,0,1", "zonotope:1,1,0:0,0,1:1,-1,2");
}

TEST(Walk, MixedSolids) {
  expect_matches_oracle("truncated-cube", "dodecahedron");
  expect_matches_oracle("cube", "truncated-cube");
  expect_matches_oracle("snub-cube", "truncated-icosahedron", false);
  expect_matches_oracle("sphere:3", "sphere:3@rot:5", false);
  expect_matches_oracle("random:300:1", "random:300:2", false);
}

TEST(Walk, ThinBoxAndExtremeScales) {
  // Out of the filter's range: every sign is taken by the exact stage.
  expect_matches_oracle("box:1:1:1e-12", "sphere:2");
  expect_matches_oracle("box:1e-12:2:3", "box:4:1e-12:5");
  expect_matches_oracle("cube@scale:1e150", "octahedron@scale:1e-150");
  expect_matches_oracle("sphere:2@scale:1e-150", "dodecahedron@scale:1e-150");
  expect_matches_oracle("icosahedron@scale:1e150", "tetra@scale:1e150@rot:3");
  expect_matches_oracle("cube@scale:1e-300", "cube@rot:1@scale:1e-300");
  // Rational coordinates below the normal range of doubles: their nearest
  // doubles carry no relative error bound, so the filter stands aside.
  expect_matches_oracle("tetra@rot:3@scale:1e-310", "cube@rot:5@scale:1e-310");
  expect_matches_oracle("octahedron@rot:2@scale:1e-320", "icosahedron@scale:1e-300");
}

TEST(Walk, FarApartOperands) {
  // Translations change no normal: the same structure, shifted.
  expect_matches_oracle("cube@translate:1e6,0,0", "octahedron@translate:0,-1e6,3");
  expect_matches_oracle("sphere:2@translate:1/3,1/7,1/11", "tetra@translate:-1e-9,0,0");
}

TEST(Walk, WorkIsOutputSensitive) {
  // The walk does work proportional to the input and output, not to their
  // product: sphere:5 ⊕ sphere:5@rot:1 (2562 × 2562 vertices) takes a few
  // steps per feature.
  const ConvexPolytope a = cat("sphere:5"), b = cat("sphere:5@rot:1");
  const WalkSum w = minkowski_walk(a, b);
  EXPECT_EQ(w.num_vertices(), 10740u);
  EXPECT_EQ(w.num_edges(), 26596u);
  EXPECT_EQ(w.num_facets(), 15858u);
  EXPECT_LT(double(w.steps), 3.0 * double(w.features(a, b)));
  EXPECT_LT(double(w.predicates), 12.0 * double(w.features(a, b)));
  EXPECT_EQ(w.crossings, w.num_facets() - a.num_facets() - b.num_facets());
}

// 600 pairs with fixed seeds (2 tests of 100 seeds, 3 pairs per seed).
void random_pairs(unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(first_seed, last_seed,
                                     [](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                                        unsigned seed) { expect_matches_oracle(a, b, label, seed % 10 == 0); });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

TEST(Walk, RandomPairsSeeds1To100) { random_pairs(1, 100); }
TEST(Walk, RandomPairsSeeds101To200) { random_pairs(101, 200); }
