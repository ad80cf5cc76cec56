// Internal helpers shared by the Minkowski-sum methods.
#pragma once

#include <minksum/sum_result.hpp>

#include <array>
#include <vector>

namespace minksum {

// One output facet before assembly: its outer normal and candidate points
// (pairs of input vertices).  assemble_sum() groups candidates by normal
// direction, takes the planar convex hull of each group's points (the facet
// face_A(n) ⊕ face_B(n)) and builds the validated result polytope.
struct FacetCandidate {
  Point3 normal;  // outer normal, any positive scale
  std::vector<std::pair<Index, Index>> points;
  FacetProvenance provenance;
  // Method-specific case (an index into SumResult::facet_case_names), or -1
  // when the method records none.  A group's case is that of its first
  // candidate; SumResult::facet_case is filled when any candidate has one.
  int facet_case = -1;
};

SumResult assemble_sum(const ConvexPolytope& a, const ConvexPolytope& b, std::vector<FacetCandidate> candidates,
                       Method method);

// Primitive integer direction of a nonzero rational vector (equal for
// vectors that are positive multiples of each other).
std::array<Integer, 3> primitive_direction(const Point3& n);

}  // namespace minksum
