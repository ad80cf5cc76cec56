// Non-convex sums against CGAL's Nef polyhedron minkowski_sum_3 (Hachenberger,
// Algorithmica 2009; reference_minkowski_sum), the exact oracle: equal exact
// volume and equal sets of canonical boundary planes on small non-convex cases.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex_support.hpp"

#include <gtest/gtest.h>

using namespace minksum;
using namespace minksum::testing;

namespace {

void expect_like_oracle(const std::string& a, const std::string& b) {
  SCOPED_TRACE(a + " + " + b);
  const Solid sa = validate_solid(catalog_mesh(a), a), sb = validate_solid(catalog_mesh(b), b);
  const NonconvexSum r = minkowski_sum_nonconvex(sa, sb);
  const Mesh o = reference_minkowski_sum(sa, sb);
  EXPECT_EQ(r.volume, mesh_volume(o));
  EXPECT_EQ(face_planes(r.mesh), face_planes(o));
}

}  // namespace

TEST(NonconvexOracle, TubePlusCube) { expect_like_oracle("tube", "cube@scale:1/4@rot:3"); }
TEST(NonconvexOracle, LShapePlusOctahedron) { expect_like_oracle("lshape", "octahedron@scale:1/3"); }
TEST(NonconvexOracle, HoleThatClosesExactly) { expect_like_oracle("tube", "box:1:1:1"); }
TEST(NonconvexOracle, StarPlusIcosahedron) { expect_like_oracle("star:5", "sphere:1@scale:1/4"); }
TEST(NonconvexOracle, NonConvexPlusNonConvex) { expect_like_oracle("tube", "lshape@scale:1/4@rot:7"); }
TEST(NonconvexOracle, RingPlusTetrahedron) { expect_like_oracle("ring:6", "tetra@scale:1/8"); }
