// CVMS: exactly equal to the chms oracle (same vertex set, same facet planes)
// on the catalog, degenerate pairs and random pairs; commutative; facet
// provenance equal to the brute-force one.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <random>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope cat(const std::string& s) { return catalog_polytope(s); }

// cvms(A, B) == chms(A, B) == cvms(B, A); provenance checked by brute force
// when `check_provenance`.
void expect_matches_oracle(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                           bool check_provenance = true) {
  SCOPED_TRACE(label);
  SumResult oracle = minkowski_sum_chms(a, b);
  SumResult ab = minkowski_sum_cvms(a, b);
  ASSERT_EQ(ab.polytope.num_vertices(), oracle.polytope.num_vertices());
  ASSERT_EQ(ab.polytope.num_edges(), oracle.polytope.num_edges());
  ASSERT_EQ(ab.polytope.num_facets(), oracle.polytope.num_facets());
  EXPECT_TRUE(same_polytope(ab.polytope, oracle.polytope));
  for (Index v = 0; v < ab.polytope.num_vertices(); ++v) {
    auto [i, j] = ab.vertex_origin[v];
    ASSERT_EQ(ab.polytope.point(v), a.point(i) + b.point(j));
  }
  ASSERT_EQ(ab.facet_provenance.size(), ab.polytope.num_facets());
  if (check_provenance) EXPECT_EQ(ab.facet_provenance, facet_provenance(a, b, ab.polytope));
  SumResult ba = minkowski_sum_cvms(b, a);
  EXPECT_TRUE(same_polytope(ba.polytope, ab.polytope));
}

void expect_matches_oracle(const std::string& a, const std::string& b, bool check_provenance = true) {
  expect_matches_oracle(cat(a), cat(b), a + " + " + b, check_provenance);
}


}  // namespace

TEST(Cvms, AllPairsOfSmallSolids) {
  for (const std::string& x : small_solids())
    for (const std::string& y : small_solids())
      if (x <= y) expect_matches_oracle(x, y);
}

TEST(Cvms, CubePlusGeodesicSpheres) {
  for (int level = 1; level <= 5; ++level)
    expect_matches_oracle("cube", "sphere:" + std::to_string(level), level <= 3);
}

TEST(Cvms, IdenticalSpheres) {
  // A = B: every facet of A is parallel to one of B (seed 000's extreme case).
  SumResult r = minkowski_sum_cvms(cat("sphere:3"), cat("sphere:3"));
  EXPECT_EQ(r.polytope.num_facets(), 320u);
  for (const auto& p : r.facet_provenance) EXPECT_EQ(p.origin(), FacetOrigin::facet_facet);
  expect_matches_oracle("sphere:3", "sphere:3");
}

TEST(Cvms, SphereAndRotatedSphere) { expect_matches_oracle("sphere:3", "sphere:3@rot:5", false); }

TEST(Cvms, CubeOctahedronCounts) {
  // 6 translated + 8 corner + 12 edge facets (see the chms suite).
  SumResult r = minkowski_sum_cvms(cat("cube"), cat("octahedron"));
  int count[5] = {0, 0, 0, 0, 0};
  for (const auto& p : r.facet_provenance) ++count[int(p.origin())];
  EXPECT_EQ(count[int(FacetOrigin::translated)], 6);
  EXPECT_EQ(count[int(FacetOrigin::corner)], 8);
  EXPECT_EQ(count[int(FacetOrigin::edge)], 12);
  expect_matches_oracle("octahedron", "cube");
}

TEST(Cvms, DioctagonalPairs) {
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:1,0,0,1");  // 90°: identical pyramids
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:100,0,0,99");  // approximately 90°
  expect_matches_oracle("dioctagonal:9", "dioctagonal:9@rot:7");
}

TEST(Cvms, ZonotopesWithParallelEdges) {
  expect_matches_oracle("zonotope:5:1", "zonotope:5:2");
  expect_matches_oracle("zonotope:6:3", "zonotope:6:3");
  expect_matches_oracle("zonotope:4:7", "cube");
  expect_matches_oracle("zonotope:1,0,0:0,1,0:1,1,0:0,0,1", "zonotope:1,1,0:0,0,1:1,-1,2");
}

TEST(Cvms, MixedSolids) {
  expect_matches_oracle("truncated-cube", "dodecahedron");
  expect_matches_oracle("cube", "truncated-cube");
  expect_matches_oracle("snub-cube", "truncated-icosahedron", false);
}

TEST(Cvms, ThinBoxAndExtremeScales) {
  expect_matches_oracle("box:1:1:1e-12", "sphere:2");
  expect_matches_oracle("box:1e-12:2:3", "box:4:1e-12:5");
  expect_matches_oracle("cube@scale:1e150", "octahedron@scale:1e-150");
  expect_matches_oracle("sphere:2@scale:1e-150", "dodecahedron@scale:1e-150");
  expect_matches_oracle("icosahedron@scale:1e150", "tetra@scale:1e150@rot:3");
}

TEST(Cvms, DegenerateOperandsAreRefusedBeforeAnyMethod) {
  // A flat polygon is not a polytope: the same error as everywhere else.
  std::vector<Point3> flat = {P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(1, 1, 0)};
  EXPECT_THROW(ConvexPolytope::hull(flat, "flat"), InputError);
}

// 1200 pairs with fixed seeds (4 tests of 100 seeds, 3 pairs per seed):
// random hulls, lattice polytopes with many coplanar points, and random exact
// rotations of catalog solids.
void random_pairs(unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(first_seed, last_seed,
                                     [](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                                        unsigned seed) { expect_matches_oracle(a, b, label, seed % 10 == 0); });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

TEST(Cvms, RandomPairsSeeds1To100) { random_pairs(1, 100); }
TEST(Cvms, RandomPairsSeeds101To200) { random_pairs(101, 200); }
TEST(Cvms, RandomPairsSeeds201To300) { random_pairs(201, 300); }
TEST(Cvms, RandomPairsSeeds301To400) { random_pairs(301, 400); }
