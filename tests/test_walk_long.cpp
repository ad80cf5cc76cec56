// The long randomised suite of the walk method (`make test-long`, label
// "long"): walk against the chms oracle on 20 100 random pairs of the shared
// families (seeds 10001-16700, three pairs per seed), plus, per seed, the
// degenerate pairs the walk's special cases exist for — a lattice polytope
// with itself and with its point reflection — and, every fifth seed, each
// random operand with itself and with its point reflection, in 10 tests of
// 670 seeds.
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

void expect_walk_matches(const ConvexPolytope& a, const ConvexPolytope& b, const SumResult& oracle) {
  const WalkSum w = minkowski_walk(a, b);
  ASSERT_EQ(w.num_vertices(), oracle.polytope.num_vertices());
  ASSERT_EQ(w.num_edges(), oracle.polytope.num_edges());
  ASSERT_EQ(w.num_facets(), oracle.polytope.num_facets());
  const ConvexPolytope s = to_polytope(w, a, b);
  EXPECT_TRUE(same_polytope(s, oracle.polytope));
}

void walk_agrees(unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(
      first_seed, last_seed, [&](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, unsigned seed) {
        SCOPED_TRACE(label);
        expect_walk_matches(a, b, minkowski_sum_chms(a, b));
        // Every fifth seed, copies of the random operand: A ⊕ A and A ⊕ −A
        // (the zero certificates of equal and opposite edge vectors).
        if (seed % 5 == 0) {
          SCOPED_TRACE("copies of the first operand, seed " + std::to_string(seed));
          const ConvexPolytope n = a.negated();
          expect_walk_matches(a, a, minkowski_sum_chms(a, a));
          expect_walk_matches(a, n, minkowski_sum_chms(a, n));
        }
      });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
  for (unsigned seed = first_seed; seed <= last_seed && !::testing::Test::HasFatalFailure(); ++seed) {
    SCOPED_TRACE("degenerate pairs, seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const ConvexPolytope l = random_lattice_polytope(rng, 6 + int(rng() % 16), 2);
    const ConvexPolytope n = l.negated();
    expect_walk_matches(l, l, minkowski_sum_chms(l, l));
    expect_walk_matches(l, n, minkowski_sum_chms(l, n));
  }
}

}  // namespace

TEST(WalkLong, Seeds10001To10670) { walk_agrees(10001, 10670); }
TEST(WalkLong, Seeds10671To11340) { walk_agrees(10671, 11340); }
TEST(WalkLong, Seeds11341To12010) { walk_agrees(11341, 12010); }
TEST(WalkLong, Seeds12011To12680) { walk_agrees(12011, 12680); }
TEST(WalkLong, Seeds12681To13350) { walk_agrees(12681, 13350); }
TEST(WalkLong, Seeds13351To14020) { walk_agrees(13351, 14020); }
TEST(WalkLong, Seeds14021To14690) { walk_agrees(14021, 14690); }
TEST(WalkLong, Seeds14691To15360) { walk_agrees(14691, 15360); }
TEST(WalkLong, Seeds15361To16030) { walk_agrees(15361, 16030); }
TEST(WalkLong, Seeds16031To16700) { walk_agrees(16031, 16700); }
