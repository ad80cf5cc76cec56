// The long randomised agreement suite (`make test-long`, label "long"):
// every method against one chms oracle computation per pair, by the oracle
// contract of the conformance suite (without its brute-force checks and
// B ⊕ A), on 15 000 random pairs (seeds 1001-6000, three pairs per seed, the
// families of the conformance suite's random pairs), in 10 tests of 500 seeds.
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

void all_methods_agree(unsigned first_seed, unsigned last_seed) {
  for (Method m : all_methods()) ASSERT_TRUE(method_available(m)) << method_name(m);
  int checked = for_each_random_pair(
      first_seed, last_seed, [&](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, unsigned) {
        SCOPED_TRACE(label);
        expect_all_methods_conform(a, b, {false, false});
      });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

}  // namespace

class MethodsLong : public ::testing::TestWithParam<SeedRange> {};

TEST_P(MethodsLong, AllMethodsAgree) { all_methods_agree(GetParam().first, GetParam().last); }

INSTANTIATE_TEST_SUITE_P(Random, MethodsLong, ::testing::ValuesIn(seed_ranges(1001, 500, 10)), seed_range_name);
