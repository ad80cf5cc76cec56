// minksum — the Minkowski sum A ⊕ B = { a + b : a in A, b in B } of two
// convex polytopes, exactly.
//
// Every method returns the same polytope for the same input (same vertex set,
// same facets after merging coplanar ones); tests assert this exactly.  Each
// result vertex is the sum of one vertex of A and one vertex of B, recorded in
// SumResult::vertex_origin.
#pragma once

#include <minksum/polytope.hpp>

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

// Where an output facet comes from (seed 000 §4.3, seed 001 §3): its normal n
// is an outer normal of a k_A-face of A and a k_B-face of B.
enum class FacetOrigin {
  translated,    // facet of A ⊕ vertex of B
  corner,        // vertex of A ⊕ facet of B
  edge,          // edge of A ⊕ edge of B (non-parallel)
  facet_edge,    // facet of A ⊕ edge of B, or edge of A ⊕ facet of B
  facet_facet,   // facet of A ⊕ facet of B (parallel facets)
  edge_parallel  // edge of A ⊕ parallel edge of B (normal on both arcs)
};
const char* facet_origin_name(FacetOrigin o);

struct SumResult {
  ConvexPolytope polytope;
  Method method = Method::chms;
  // vertex_origin[v] = (vertex of A, vertex of B) whose sum is vertex v.
  std::vector<std::pair<Index, Index>> vertex_origin;
  double seconds = 0;  // the computation alone
};

// Compute A ⊕ B with `method`.  Throws UsageError if the method is not
// available in this build.
SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b,
                        Method method = Method::automatic);

// The CHMS method (oracle): exact convex hull of all pairwise vertex sums.
SumResult minkowski_sum_chms(const ConvexPolytope& a, const ConvexPolytope& b);

}  // namespace minksum
