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

// The method table: every method has one row, its name parses back to it,
// and every row is available and dispatched (the result says which method
// ran); anything else is refused with the list of names.
TEST(Chms, MethodTableAndDispatch) {
  const ConvexPolytope c = poly(cube_mesh(1));
  const Method all[] = {Method::automatic, Method::walk, Method::cvms, Method::essdms,
                        Method::mssd,      Method::chms, Method::cgm};
  EXPECT_EQ(methods().size(), std::size(all));
  EXPECT_EQ(method_list(), "auto, walk, chms, cvms, essdms, mssd, cgm");
  for (Method m : all) {
    SCOPED_TRACE(method_name(m));
    ASSERT_EQ(parse_method(method_name(m)), m);
    EXPECT_TRUE(method_available(m));
    const SumResult r = minkowski_sum(c, c, m);
    EXPECT_EQ(r.method, m == Method::automatic ? Method::walk : m);
    EXPECT_EQ(r.polytope.num_vertices(), 8u);
  }
  EXPECT_EQ(parse_method("hull"), std::nullopt);
  EXPECT_EQ(parse_method("Walk"), std::nullopt);
  const Method bogus = static_cast<Method>(99);
  EXPECT_FALSE(method_available(bogus));
  try {
    minkowski_sum(c, c, bogus);
    ADD_FAILURE() << "an unknown method was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(method_list()), std::string::npos) << e.what();
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
