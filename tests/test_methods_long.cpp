// The long randomised agreement suite (`make test-long`, label "long"):
// every available method against the chms oracle on 15 000 random pairs
// (seeds 1001-6000, three pairs per seed, same families as the per-method
// suites), in 10 tests of 500 seeds.
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

void all_methods_agree(unsigned first_seed, unsigned last_seed) {
  std::vector<Method> methods;
  for (Method m : {Method::cvms, Method::essdms, Method::mssd, Method::cgm, Method::walk})
    if (method_available(m)) methods.push_back(m);
  ASSERT_FALSE(methods.empty());
  int checked = for_each_random_pair(
      first_seed, last_seed, [&](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, unsigned) {
        SCOPED_TRACE(label);
        const SumResult oracle = minkowski_sum_chms(a, b);
        for (Method m : methods) {
          SumResult r = minkowski_sum(a, b, m);
          EXPECT_TRUE(same_polytope(r.polytope, oracle.polytope)) << method_name(m);
          for (Index v = 0; v < r.polytope.num_vertices(); ++v) {
            auto [i, j] = r.vertex_origin[v];
            ASSERT_EQ(r.polytope.point(v), a.point(i) + b.point(j)) << method_name(m);
          }
        }
      });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

}  // namespace

TEST(MethodsLong, Seeds1001To1500) { all_methods_agree(1001, 1500); }
TEST(MethodsLong, Seeds1501To2000) { all_methods_agree(1501, 2000); }
TEST(MethodsLong, Seeds2001To2500) { all_methods_agree(2001, 2500); }
TEST(MethodsLong, Seeds2501To3000) { all_methods_agree(2501, 3000); }
TEST(MethodsLong, Seeds3001To3500) { all_methods_agree(3001, 3500); }
TEST(MethodsLong, Seeds3501To4000) { all_methods_agree(3501, 4000); }
TEST(MethodsLong, Seeds4001To4500) { all_methods_agree(4001, 4500); }
TEST(MethodsLong, Seeds4501To5000) { all_methods_agree(4501, 5000); }
TEST(MethodsLong, Seeds5001To5500) { all_methods_agree(5001, 5500); }
TEST(MethodsLong, Seeds5501To6000) { all_methods_agree(5501, 6000); }
