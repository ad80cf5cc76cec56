// minksum — the Minkowski sum A ⊕ B = { a + b : a in A, b in B } of two
// convex polytopes, exactly.
//
// Every method returns the same polytope for the same input (same vertex set,
// same facets after merging coplanar ones); tests assert this exactly.  Each
// result vertex is the sum of one vertex of A and one vertex of B, recorded in
// SumResult::vertex_origin.
#pragma once

#include <minksum/cubical_gaussian_map.hpp>  // minkowski_sum_cgm
#include <minksum/sum_result.hpp>

namespace minksum {

// Compute A ⊕ B with `method`; SumResult::method names the method used.  Throws UsageError if the method is not
// available in this build, Cancelled if options.cancel is set during the sum.
SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b,
                        Method method = Method::automatic, const SumOptions& options = {});

// Output-sensitive exact sum (docs/walk.md): hill climbing to the first
// support, then walks along the great arcs of A's edges over B's Gaussian
// map (and of B's edges over A's), each crossing one output edge facet; every
// output facet is face_A(n) ⊕ face_B(n).  The structure alone, with implicit
// coordinates, is minkowski_walk() in <minksum/walk.hpp>; this wraps it into
// a SumResult (explicit exact coordinates, planes on demand).  counters:
// crossings, walk steps, and the microseconds of the walk and of the
// conversion to the ConvexPolytope.
SumResult minkowski_sum_walk(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});

// The CHMS method (oracle): exact convex hull of all pairwise vertex sums.
SumResult minkowski_sum_chms(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});
// CVMS (Barki et al. 2009, §3-4): contributing vertices, translated / corner / edge facets.
SumResult minkowski_sum_cvms(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});
// ESSDMS (Barki et al. 2009, §5.2): slope diagrams merged without embedding, with
// contributing vertices instead of point-in-polygon queries.  facet_case
// holds the intersection case of each facet (two_facet_points,
// facet_point_on_edge_arc, two_edge_arcs, facet_point_in_vertex_region);
// counters hold the operation counts.
SumResult minkowski_sum_essdms(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});
// Wu et al.'s improved 3D-MSSD as Barki et al. (2009) re-implement it: the same merge
// with point-in-spherical-polygon queries and every pair of edge arcs; the
// same facet cases and counters as essdms.
SumResult minkowski_sum_mssd(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});

// minkowski_sum_cgm(a, b, options), the Cubical Gaussian Map method, is
// declared with the map in <minksum/cubical_gaussian_map.hpp>.

}  // namespace minksum
