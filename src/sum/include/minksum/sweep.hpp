// minksum — Minkowski sums with points, segments and flat convex polygons:
// sweeps (docs/sweeps.md).
//
// A ⊕ S for a full-dimensional polytope A and a lower-dimensional S is a
// polytope (the region S sweeps when moved over A, or A over S); two
// lower-dimensional sets sum to a set of dimension 0 to 3 (a segment ⊕ a
// segment is a parallelogram, or a segment when they are collinear; two
// polygons in parallel planes a polygon; in general a polytope).  Every
// result is exact and carries its dimension.
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/sum_result.hpp>

namespace minksum {

struct SetSumResult {
  ConvexSet set;                       // the sum; set.dimension() is its dimension
  Method method = Method::walk;        // walk or chms (or the method of two polytopes)
  // How the sum was made: "polytopes" (both operands full-dimensional: the
  // method itself), "translation" (a point), "sweep" (a polytope and a
  // segment or polygon: the walk with the set thickened, then thinned),
  // "hull" (the exact hull of the pairwise vertex sums: chms, and the walk
  // when neither operand is full-dimensional).
  const char* route = "polytopes";
  double seconds = 0;
};

// A ⊕ B for convex sets of any dimension.  Two full-dimensional operands go
// to minkowski_sum(a.polytope(), b.polytope(), method, options).  Otherwise
// the method must be automatic, walk or chms: the others take polytopes only
// (UsageError naming walk).  Cancelled as minkowski_sum.
SetSumResult minkowski_sum_sets(const ConvexSet& a, const ConvexSet& b, Method method = Method::automatic,
                                const SumOptions& options = {});

}  // namespace minksum
