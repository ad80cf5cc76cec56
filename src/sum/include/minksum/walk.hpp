// minksum — the output-sensitive exact Minkowski sum (method `walk`,
// docs/walk.md), as a half-edge structure with implicit coordinates.
//
// For convex polytopes A and B, every facet of S = A ⊕ B with outer normal n
// is face_A(n) ⊕ face_B(n), and on the Gaussian sphere the normals n are the
// vertices of the overlay of the Gaussian maps of A and B:
//   * the facet normals of A (S-facet f ⊕ face_B(n_f)),
//   * the facet normals of B not parallel to one of A (face_A(n_g) ⊕ g),
//   * the proper crossings of an arc of A with an arc of B (e_a ⊕ e_b).
// minkowski_walk() finds face_B(n_f) for a first facet of A by hill climbing
// on B's vertex graph, then walks along the great arc of every edge of A (from
// the normal of one of its facets to the other's) through the vertex regions
// of B's Gaussian map: each region boundary crossed is one edge facet, the
// region reached at the end is the support of the next facet.  The same walk
// with the roles swapped gives face_A(n_g) for B's facets.  Degenerate
// positions (a normal of B on an arc of A, arcs running along each other,
// parallel facets, A = B) are decided by the exact signs and take the same
// path: the support face at each event is computed, never assumed.
//
// Cost: O(V + E + F of A and B + the output + the boundary crossings
// walked), with two sign predicates (degree 3, filtered; exact on failure) per
// step.  No hull, no pairwise sums.
//
// The result is the exact sum: vertex v is the point
//   A.point(vertex_origin[v].first) + B.point(vertex_origin[v].second),
// facets are counter-clockwise seen from outside, no two adjacent facets are
// coplanar and no vertex has degree 2 — the invariants of ConvexPolytope,
// whose exact coordinates and canonical planes to_polytope() computes.
#pragma once

#include <minksum/minkowski.hpp>
#include <minksum/polytope.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace minksum {

struct WalkSum {
  // Vertices: (vertex of A, vertex of B).
  std::vector<std::pair<Index, Index>> vertex_origin;
  // Half-edges, with the conventions of ConvexPolytope: twin(h) = h ^ 1,
  // facet(h) on the left, next(h) counter-clockwise around facet(h).
  std::vector<Index> he_origin, he_next, he_facet;
  std::vector<Index> facet_he;  // one half-edge per facet
  std::vector<FacetProvenance> provenance;  // per facet: face_A(n), face_B(n)

  // Work done: arc crossings (edge facets), region steps of the walks, and
  // the sign predicates evaluated (calls, and calls the filter could not
  // decide).
  std::uint64_t crossings = 0, steps = 0, predicates = 0, exact_predicates = 0;

  Index num_vertices() const { return Index(vertex_origin.size()); }
  Index num_halfedges() const { return Index(he_origin.size()); }
  Index num_edges() const { return num_halfedges() / 2; }
  Index num_facets() const { return Index(facet_he.size()); }
  // Input + output features: V + E + F of A, of B and of the sum.
  std::uint64_t features(const ConvexPolytope& a, const ConvexPolytope& b) const;
};

// The exact sum A ⊕ B as a WalkSum.  Throws std::logic_error if an internal
// consistency check fails (a bug, never an input condition).  Reports phase
// "walk" to options (fractions 0 at the start, then every 4096 facets walked,
// 0.8 when the walks are done) and throws Cancelled at one of these points
// once options.cancel is set (SumOptions, sum_result.hpp).
WalkSum minkowski_walk(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});

// The ConvexPolytope of a WalkSum: exact vertex coordinates (a + b, see
// sum_coordinates), connectivity copied, planes computed on demand, no
// re-validation (ConvexPolytope::check_invariants() re-checks everything from
// scratch).  Vertex v of the result is vertex v of w; its source_vertex is v.
ConvexPolytope to_polytope(const WalkSum& w, const ConvexPolytope& a, const ConvexPolytope& b);
// The same, taking w's half-edge arrays instead of copying them (w keeps its
// vertex_origin, provenance and counters; its half-edges are left empty).
ConvexPolytope to_polytope(WalkSum&& w, const ConvexPolytope& a, const ConvexPolytope& b);

// The exact points a_i + b_j for the given index pairs, in the cheapest exact
// form (PointList::sums): exact pairs of doubles (TwoSum, no allocation) when
// both lists hold doubles and the FPU rounds to nearest; otherwise rationals
// made on demand from the two lists, with their nearest doubles decided by a
// filter on the operands' doubles (GMP only where it cannot decide).
PointList sum_coordinates(const std::vector<std::pair<Index, Index>>& pairs, const PointList& a, const PointList& b);

}  // namespace minksum
