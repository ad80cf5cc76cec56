// CHMS, the oracle, and the dispatch around it: methods not built are
// refused by name, auto says which method it used.  The oracle itself is
// checked against the sums known in closed form and against facts that need
// no hull (every facet plane supports A ⊕ B) by the conformance suite
// (test_conformance.cpp), like every method.
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope poly(const Mesh& m) { return ConvexPolytope::from_mesh(m); }

}  // namespace

TEST(Chms, DispatchRefusesMethodsNotBuilt) {
  ConvexPolytope c = poly(cube_mesh(1));
  EXPECT_NO_THROW(minkowski_sum(c, c, Method::chms));
  EXPECT_NO_THROW(minkowski_sum(c, c, Method::automatic));
  for (Method m : {Method::walk, Method::cvms, Method::essdms, Method::mssd, Method::cgm}) {
    if (method_available(m)) continue;
    try {
      minkowski_sum(c, c, m);
      ADD_FAILURE() << method_name(m) << " should be refused";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(method_name(m)), std::string::npos);
    }
  }
}

TEST(Chms, AutoPicksWalkAndSaysWhich) {
  // auto is the output-sensitive walk for double and rational operands; the
  // result is the oracle's either way.
  ConvexPolytope c = poly(cube_mesh(1)), o = poly(octahedron_mesh());
  SumResult small = minkowski_sum(c, o, Method::automatic);
  EXPECT_EQ(small.method, Method::walk);
  EXPECT_TRUE(same_polytope(small.polytope, minkowski_sum(c, o, Method::chms).polytope));
  ConvexPolytope t = poly(tetra_mesh()).translated(Q("1/3", "0", "0"));
  SumResult rational = minkowski_sum(t, o, Method::automatic);
  EXPECT_EQ(rational.method, Method::walk);
  EXPECT_TRUE(same_polytope(rational.polytope, minkowski_sum(t, o, Method::chms).polytope));
}
