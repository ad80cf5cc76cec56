// minksum — what a Minkowski-sum method returns (SumResult, with the
// provenance of every facet), the table of methods and the options every
// method takes (progress, cancellation).  The methods themselves are declared
// in <minksum/minkowski.hpp>.
#pragma once

#include <minksum/error.hpp>  // Cancelled, UsageError
#include <minksum/polytope.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace minksum {

enum class Method { automatic, walk, cvms, essdms, mssd, chms, cgm };

// The methods, one row each: parsing, --help and error messages are built
// from this table.
struct MethodInfo {
  Method method;
  const char* name;     // "auto", "walk", "cvms", ...
  const char* summary;  // one paragraph for --help
};
// Every method, in the order help texts list them (automatic first).
std::span<const MethodInfo> methods();
const char* method_name(Method m);
// Parse a method name; nullopt if unknown.
std::optional<Method> parse_method(const std::string& name);
// True when the method is implemented in this build (every row of the table).
bool method_available(Method m);
// The names joined: "auto, walk, chms, cvms, essdms, mssd, cgm".
std::string method_list();

// Where an output facet comes from (Barki et al. 2009, §4.3; Fogel and Halperin 2006, §3).  A facet of
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

struct SumResult;
// The exact volume of r.polytope = a ⊕ b, from a, b and r.facet_provenance
// (as minkowski_sum returns them) by mixed volumes: a cross product per
// corner of a's and b's facets, in integers when both operands' coordinates
// are doubles, instead of a determinant per triangle of the sum on its
// coordinates (src/sum/shared/sum_volume.cpp).  Equal to
// r.polytope.volume(), which it returns when the provenance is missing or
// an operand has rational coordinates.
Rational sum_volume(const ConvexPolytope& a, const ConvexPolytope& b, const SumResult& r);

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

// How a caller follows and stops one running sum: a progress callback and a
// cancellation flag, passed with the call — no global state, so sums running
// in several threads each report to their own options only.  Both are off
// by default; then a report point costs two null tests.
//
// Report points: every method reports at its start (phase = its name, e.g.
// "cvms", fraction unknown) and at the boundaries of its main stages (same
// phase).  walk reports "walk" with fractions from 0 to 0.8 as the arcs are
// walked (every 4096 facets of an operand; 0.8 once the walks are done, the
// linking of the facet loops remaining), then "convert" (fraction unknown)
// while minkowski_sum_walk makes the explicit polytope.  Reports are rare:
// walk's one per 4096 facets walked is its most frequent.
struct SumOptions {
  // Called at each report point, on the thread computing the sum, with the
  // phase (a string literal: valid for the whole program, comparable by
  // content) and the fraction of the phase done in [0, 1], or a negative
  // number when the phase does not measure it.  Within a phase the fractions
  // never decrease.  Keep it short (it runs inside the sum); to show progress
  // from another thread, store the values in atomics that thread polls (as
  // the progress line of `minksum sum` does).  An exception it throws leaves
  // the sum.
  std::function<void(const char* phase, double fraction)> progress;
  // When not null: once *cancel is true (set from any thread), the sum
  // throws Cancelled (<minksum/error.hpp>) at its next report point, before
  // calling progress.  Methods check it only there (walk: every 4096 facets
  // walked; the other methods between their stages), so a stage under way
  // finishes first.  The flag must outlive the call.
  const std::atomic<bool>* cancel = nullptr;
  // Non-convex sums (<minksum/nonconvex.hpp>): whether the exact volume of
  // the result (NonconvexSum::volume) is computed before the sum returns.
  // When false it is left 0, and a caller with other work to do meanwhile
  // computes it with mesh_volume(result.mesh) (the command line does, while
  // it writes the file: the two take about as long on real meshes).
  bool volume = true;
  // Non-convex sums: when set, the sum's working data that outlives its
  // last step (the boundary sweep's pieces, about 10 KB each, and the
  // union's faces before their points are welded: hundreds of megabytes for
  // the largest sums) is handed to this callback, on the sum's thread, once
  // or more, instead of being freed before the sum returns; the data is
  // then freed when the last copy of the pointer goes.  The command line
  // keeps it to the end of the process (which frees it at once).  Unset:
  // freed by the sum, on its threads.
  std::function<void(std::shared_ptr<void> data)> release;

  // A report point, as the methods call it: throw Cancelled if the flag is
  // set, then call progress if there is one.
  void report(const char* phase, double fraction) const;
};

}  // namespace minksum
