// Internal: the validating construction of a ConvexPolytope.
#pragma once

#include <minksum/polytope.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace minksum {

class PolytopeBuilder {
 public:
  // Validate a polygon mesh and build the polytope (see polytope.hpp);
  // `source` names the file in the InputError of the first defect.
  static ConvexPolytope build(const Mesh& mesh, const std::string& source);

  // As build, but nullopt, not an InputError, for a surface that bounds no
  // convex polytope: one that is not a single topological sphere (open,
  // non-manifold, inconsistently oriented, several components, a genus),
  // whose coplanar facets do not form one convex polygon, or whose edges,
  // vertices or merged polygons are not convex.  The probes that try the
  // convex path first (a solid read from a file, a rounded surface before
  // it is written) then pay no exception for the common case.  (A
  // process's first exception makes the unwinder sort its table of
  // functions: milliseconds in the statically linked command.)  Other
  // defects, including a polygon that is not planar, still throw.
  static std::optional<ConvexPolytope> build_if_convex(const Mesh& mesh, const std::string& source);

  // The exact convex hull of `points`, the same polytope as
  // ConvexPolytope::hull(points) gives (vertices in input order, facets
  // canonical), computed for doubles by an incremental triangulation in
  // spatial order: faster than quickhull when nearly every point is a vertex
  // of the hull (points spread over a sphere: 1 000 000 in a few seconds),
  // slower and larger when most points are inside (it triangulates them too).
  static ConvexPolytope hull_of_extreme_points(const PointList& points, const std::string& source);

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

  // The polytope p with its vertices moved to `points` (doubles: the
  // rounded coordinates a writer prints; as many as p's vertices), when the
  // moved surface is provably again a convex polytope with p's facets, or
  // with quadrilaterals no longer planar split along the diagonal that folds
  // outwards (*split counts them).  Certified locally, without validating
  // the mesh from scratch (docs/data-model.md, "Writing rounded
  // coordinates"): p's topology is kept, so every facet planar and strictly
  // convex, every edge strictly convex and every vertex winding once make it
  // a convex polytope, the same from_mesh would build from the moved mesh.
  // nullopt when some point repeats, a larger polygon is no longer planar,
  // two neighbouring facets became coplanar or a test fails: the caller
  // validates the mesh in full then.
  static std::optional<ConvexPolytope> moved(const ConvexPolytope& p, const PointList& points,
                                             std::size_t* split);

 private:
  static std::optional<ConvexPolytope> build(const Mesh& mesh, const std::string& source, bool probe);
};

// Sign of det(a, b, c) = <a, b x c>, exact.
int sign_det(const Point3& a, const Point3& b, const Point3& c);

// Given an axis `a` and vectors d[0..k-1] listed cyclically, decide whether
// the vectors, seen from the tip of `a` (projected along a), turn strictly
// counter-clockwise at every step (det(a, d[i], d[i+1]) > 0) and wind around
// exactly once.  Returns -1 on success, else the index i of the first step
// that fails (k if only the winding number is wrong).
long check_fan(const Point3& a, const std::vector<Point3>& d);

// How many facet and vertex fans (step 8 of validation, and the rounding
// certificate) intervals could not decide, so that check_fan ran on exact
// points, since the process started (all threads).
std::uint64_t exact_fan_tests();

}  // namespace minksum
