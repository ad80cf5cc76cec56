// The long randomised suite of the walk method (`make test-long`, label
// "long"): walk against the chms oracle, by the oracle contract of the
// conformance suite (without its brute-force checks and B ⊕ A), on 20 100
// random pairs of the shared families (seeds 10001-16700, three pairs per
// seed), plus, per seed, the degenerate pairs the walk's special cases exist
// for — a lattice polytope with itself and with its point reflection — and,
// every fifth seed, each random operand with itself and with its point
// reflection, in 10 tests of 670 seeds.
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

// The oracle contract for walk alone, without the brute-force checks and B ⊕ A.
void expect_walk_conforms(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label) {
  expect_conforms(Method::walk, a, b, label, {false, false});
}

void walk_agrees(unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(
      first_seed, last_seed, [&](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, unsigned seed) {
        expect_walk_conforms(a, b, label);
        // Every fifth seed, copies of the random operand: A ⊕ A and A ⊕ −A
        // (the zero certificates of equal and opposite edge vectors).
        if (seed % 5 == 0) {
          expect_walk_conforms(a, a, "first operand of " + label + " twice");
          expect_walk_conforms(a, a.negated(), "first operand of " + label + " and its reflection");
        }
      });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
  for (unsigned seed = first_seed; seed <= last_seed && !::testing::Test::HasFatalFailure(); ++seed) {
    SCOPED_TRACE("degenerate pairs, seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const ConvexPolytope l = random_lattice_polytope(rng, 6 + int(rng() % 16), 2);
    expect_walk_conforms(l, l, "lattice polytope twice");
    expect_walk_conforms(l, l.negated(), "lattice polytope and its reflection");
  }
}

}  // namespace

class WalkLong : public ::testing::TestWithParam<SeedRange> {};

TEST_P(WalkLong, AgreesWithTheOracle) { walk_agrees(GetParam().first, GetParam().last); }

INSTANTIATE_TEST_SUITE_P(Random, WalkLong, ::testing::ValuesIn(seed_ranges(10001, 670, 10)), seed_range_name);
