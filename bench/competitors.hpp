// minksum bench — the competitors: what users pick today instead of minksum.
//
// Each function takes the two validated operands, prepares the competitor's
// own input (untimed), runs the competitor (timed: `seconds`), then counts
// the output's vertices, edges and facets (untimed).  CGAL's heavy headers
// live in one translation unit per competitor, so nothing else pays for them.
#pragma once

#include <minksum/polytope.hpp>

#include <string>

namespace minksum::bench {

struct Outcome {
  double seconds = 0;       // the computation alone (no I/O, no input conversion)
  double sub_seconds = -1;  // a second timing when a contender has two phases (SGM: overlay only, part of
                            // `seconds`; walk: the conversion to a ConvexPolytope, after `seconds`)
  long v = -1, e = -1, f = -1;  // output counts, coplanar facets merged
  std::string note;         // why counts are missing, or how they were obtained
};

// CGAL convex_hull_3 (Epeck) on the exact pairwise sums a_i + b_j (computed
// with Epeck's exact arithmetic).  Counts: the triangulated hull through
// ConvexPolytope::from_mesh (coplanar triangles merged exactly).
Outcome cgal_exact_hull(const ConvexPolytope& a, const ConvexPolytope& b);
// CGAL convex_hull_3 with Epick on the pairwise sums of the nearest doubles,
// added in double arithmetic (what a floating-point user does; the sums are
// prepared before the clock starts, timed: convex_hull_3 alone).  Counts: the
// hull of those rounded points, coplanar triangles merged exactly.
Outcome cgal_epick_hull(const ConvexPolytope& a, const ConvexPolytope& b);
// Qhull (reentrant libqhull_r, options "qhull", i.e. the default C-0
// pre-merge) on the same rounded pairwise sums (prepared untimed; timed:
// qh_new_qhull alone, as bench/qhull_standalone does).  Counts: Qhull's own
// (merged) facets and vertices, E = V + F - 2.
Outcome qhull_rounded(const ConvexPolytope& a, const ConvexPolytope& b);
// CGAL::minkowski_sum_3 on Nef_polyhedron_3<Epeck>; timed: minkowski_sum_3
// alone (the conversion of the operands to Nef polyhedra is not timed).
Outcome cgal_nef_sum(const ConvexPolytope& a, const ConvexPolytope& b);
// CGAL's Arr_polyhedral_sgm (spherical Gaussian map, Epeck): `seconds` =
// construction of both maps + overlay, `sub_seconds` = overlay alone.
Outcome cgal_sgm_sum(const ConvexPolytope& a, const ConvexPolytope& b);

// Fill v/e/f from a closed polygon mesh with exact coordinates by validating
// it as a ConvexPolytope (coplanar facets merged exactly); on failure the
// counts stay -1 and the reason goes to note.
void count_exact(const Mesh& m, Outcome& o);

std::string cgal_version();
std::string qhull_version();

}  // namespace minksum::bench
