// minksum — the Minkowski sum A ⊕ B = { a + b : a in A, b in B } of two
// convex polytopes, exactly.
//
// Every method returns the same polytope for the same input (same vertex set,
// same facets after merging coplanar ones); tests assert this exactly.  Each
// result vertex is the sum of one vertex of A and one vertex of B, recorded in
// SumResult::vertex_origin.
#pragma once

#include <minksum/polytope.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace minksum {

enum class Method { automatic, walk, cvms, essdms, mssd, chms, cgm };

// "auto", "walk", "cvms", ...
const char* method_name(Method m);
// Parse a method name; nullopt if unknown.
std::optional<Method> parse_method(const std::string& name);
// True when the method is implemented in this build.
bool method_available(Method m);

// Where an output facet comes from (seed 000 §4.3, seed 001 §3).  A facet of
// S = A ⊕ B with outer normal n is face_A(n) ⊕ face_B(n), the faces of A and
// B maximising <x, n>; their dimensions (2 facet, 1 edge, 0 vertex) give:
enum class FacetOrigin {
  translated,   // facet of A ⊕ vertex of B
  corner,       // vertex of A ⊕ facet of B
  edge,         // edge of A ⊕ edge of B (non-parallel)
  facet_edge,   // facet of A ⊕ edge of B, or edge of A ⊕ facet of B (parallel)
  facet_facet,  // facet of A ⊕ facet of B (parallel, same orientation)
};
const char* facet_origin_name(FacetOrigin o);

struct FacetProvenance {
  Feature a, b;  // face_A(n) and face_B(n) (Feature: <minksum/polytope.hpp>)
  FacetOrigin origin() const;
  friend bool operator==(const FacetProvenance&, const FacetProvenance&) = default;
};

// The provenance of every facet of s = a ⊕ b, computed independently of any
// method by scanning all vertices of a and b for each facet normal:
// O(F (V_A + V_B)) exact.  For tests and for methods that do not track it.
std::vector<FacetProvenance> facet_provenance(const ConvexPolytope& a, const ConvexPolytope& b,
                                              const ConvexPolytope& s);

struct SumResult {
  ConvexPolytope polytope;
  Method method = Method::chms;
  // vertex_origin[v] = (vertex of A, vertex of B) whose sum is vertex v.
  std::vector<std::pair<Index, Index>> vertex_origin;
  // facet_provenance[f] for every facet f of polytope (empty when the method
  // does not track it; see facet_provenance() above).
  std::vector<FacetProvenance> facet_provenance;
  // Method-specific detail (empty when a method records none):
  // facet_case[f] indexes facet_case_names, e.g. the slope-diagram
  // intersection case behind facet f; counters are named operation counts
  // (predicate evaluations, point-in-polygon queries, ...).
  std::vector<std::uint8_t> facet_case;
  std::vector<std::string> facet_case_names;
  std::vector<std::pair<std::string, long long>> counters;
  double seconds = 0;  // the computation alone
  // Of `seconds`, the time spent making the explicit ConvexPolytope from the
  // method's own result (walk: to_polytope; 0 where the two are one step).
  double explicit_seconds = 0;
};

// The method Method::automatic uses for these operands (see minkowski.cpp).
Method automatic_choice(const ConvexPolytope& a, const ConvexPolytope& b);

// Compute A ⊕ B with `method`; SumResult::method names the method used.  Throws UsageError if the method is not
// available in this build.
SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b,
                        Method method = Method::automatic);

// Output-sensitive exact sum (DESIGN.md §4): hill climbing to the first
// support, then walks along the great arcs of A's edges over B's Gaussian
// map (and of B's edges over A's), each crossing one output edge facet; every
// output facet is face_A(n) ⊕ face_B(n).  The structure alone, with implicit
// coordinates, is minkowski_walk() in <minksum/walk.hpp>; this wraps it into
// a SumResult (explicit exact coordinates, planes on demand).  counters:
// crossings, walk steps, and the microseconds of the walk and of the
// conversion to the ConvexPolytope.
SumResult minkowski_sum_walk(const ConvexPolytope& a, const ConvexPolytope& b);

// Progress of the Minkowski sum being computed (any thread), for progress
// displays: the current phase ("walk", "convert", a method name...; empty
// when none is running) and the fraction of it done in [0, 1], or a negative
// number when the phase does not measure it.  Methods update it a few
// hundred times per sum at most; reading is lock-free.
struct SumProgress {
  std::string phase;
  double fraction = -1;
};
SumProgress sum_progress();
// Set by the methods (and minkowski_sum, which clears it when done).  phase
// must be a string with static storage duration (a literal); nullptr clears.
void report_sum_progress(const char* phase, double fraction);

// The CHMS method (oracle): exact convex hull of all pairwise vertex sums.
SumResult minkowski_sum_chms(const ConvexPolytope& a, const ConvexPolytope& b);
// CVMS (seed 000 §3-4): contributing vertices, translated / corner / edge facets.
SumResult minkowski_sum_cvms(const ConvexPolytope& a, const ConvexPolytope& b);
// ESSDMS (seed 000 §5.2): slope diagrams merged without embedding, with
// contributing vertices instead of point-in-polygon queries.  facet_case
// holds the intersection case of each facet (two_facet_points,
// facet_point_on_edge_arc, two_edge_arcs, facet_point_in_vertex_region);
// counters hold the operation counts.
SumResult minkowski_sum_essdms(const ConvexPolytope& a, const ConvexPolytope& b);
// Wu et al.'s improved 3D-MSSD as seed 000 re-implements it: the same merge
// with point-in-spherical-polygon queries and every pair of edge arcs; the
// same facet cases and counters as essdms.
SumResult minkowski_sum_mssd(const ConvexPolytope& a, const ConvexPolytope& b);
// The Cubical Gaussian Map method (seed 001 §2-3): the overlay of the six
// pairs of planar maps of the two CGMs (<minksum/cubical_gaussian_map.hpp>).
SumResult minkowski_sum_cgm(const ConvexPolytope& a, const ConvexPolytope& b);

}  // namespace minksum
