// Internal: the validating construction of a ConvexPolytope.
#pragma once

#include <minksum/polytope.hpp>

#include <string>
#include <vector>

namespace minksum {

class PolytopeBuilder {
 public:
  // Validate a polygon mesh and build the polytope (see polytope.hpp).
  // `points_are_hull` skips nothing: it only changes the wording of errors.
  static ConvexPolytope build(const Mesh& mesh, const std::string& source);

  // Renumber the facets of p canonically: each facet's loop starts at its
  // smallest vertex, facets sorted by their loops.  O(n log n), no geometry.
  static void canonicalize_facets(ConvexPolytope& p);

  // A polytope from parts its producer has already proven valid (the walk
  // method builds the half-edge structure of a Minkowski sum directly):
  // points, the half-edge links (twin(h) = h ^ 1), one half-edge per facet.
  // Fills prev and the vertex half-edges; planes are computed on demand like
  // every polytope's.  No validation: call check_invariants() to re-check
  // from scratch.
  static ConvexPolytope from_trusted_parts(PointList points, std::vector<Index> he_origin,
                                           std::vector<Index> he_next, std::vector<Index> he_facet,
                                           std::vector<Index> facet_he);

};

// Sign of det(a, b, c) = <a, b x c>, exact.
int sign_det(const Point3& a, const Point3& b, const Point3& c);

// Given an axis `a` and vectors d[0..k-1] listed cyclically, decide whether
// the vectors, seen from the tip of `a` (projected along a), turn strictly
// counter-clockwise at every step (det(a, d[i], d[i+1]) > 0) and wind around
// exactly once.  Returns -1 on success, else the index i of the first step
// that fails (k if only the winding number is wrong).
long check_fan(const Point3& a, const std::vector<Point3>& d);

}  // namespace minksum
