// Internal: the support of a direction on a convex polytope — the face whose
// vertices maximise <x, n> — and the face spanned by a set of vertices.
//
// The templates take the direction as a comparison of two vertices,
//   higher(x, y) = sign <p(x) − p(y), n>   (−1, 0, +1, exact),
// so that each caller keeps its own exact predicate: the walk its cached
// det3 filter on a facet normal of the other operand, CVMS and the slope
// diagrams support_compare.  The overloads taking a rational direction n use
// the kernel's compare_along (filtered on the roundings, exact when the
// filter cannot decide).
//
// Facts they rely on (P convex, every edge strictly convex):
//   * a vertex no neighbour of which is strictly higher maximises <x, n>
//     over P (the edges at a vertex span its tangent cone: the simplex
//     method's optimality test), so hill climbing on the vertex graph ends
//     at a maximiser;
//   * around a maximiser b, the neighbours as high as b are those of b's
//     support face: none (the face is b), one (the edge to it) or the two
//     neighbours of b on the facet, which are consecutive around b.
#pragma once

#include <minksum/feature.hpp>  // feature_vertices(p, f)
#include <minksum/polytope.hpp>

#include <optional>
#include <ranges>
#include <stdexcept>
#include <vector>

namespace minksum {

// Hill climbing from `start`: moves to the first neighbour (counter-
// clockwise from vertex_halfedge) strictly higher than the current vertex
// until there is none, and returns that vertex, a maximiser.  One call
// higher(neighbour, current) per neighbour tested.
template <class Higher>
Index climb(const ConvexPolytope& p, Index start, Higher&& higher) {
  Index b = start;
  for (bool moved = true; moved;) {
    moved = false;
    const Index h0 = p.vertex_halfedge(b);
    Index h = h0;
    do {
      if (higher(p.target(h), b) > 0) {
        b = p.target(h);
        moved = true;
        break;
      }
      h = p.next_around_vertex(h);
    } while (h != h0);
  }
  return b;
}

// The support face at vertex b: nothing when a neighbour of b is strictly
// higher (the scan stops at it; b is not a maximiser), else the face of all
// maximisers: b, the edge to b's one neighbour as high, or the facet between
// its two.  One call higher(neighbour, b) per neighbour, counter-clockwise
// from vertex_halfedge(b).
template <class Higher>
std::optional<Feature> support_face_at(const ConvexPolytope& p, Index b, Higher&& higher) {
  const Index h0 = p.vertex_halfedge(b);
  Index h = h0;
  Index first_tie = kNoIndex;  // the first outgoing half-edge to a neighbour as high as b
  Index last_tie = kNoIndex;   // the previous half-edge when its neighbour is as high as b
  Index facet = kNoIndex;
  unsigned ties = 0;
  do {
    const int c = higher(p.target(h), b);
    if (c > 0) return std::nullopt;
    if (c == 0) {
      if (ties++ == 0) first_tie = h;
      // facet(h_i) lies between the outgoing h_i and h_{i+1}.
      if (last_tie != kNoIndex && facet == kNoIndex) facet = p.facet(last_tie);
      last_tie = h;
    } else {
      last_tie = kNoIndex;
    }
    h = p.next_around_vertex(h);
  } while (h != h0);
  if (ties == 0) return Feature::vertex(b);
  if (ties == 1) return Feature::edge(ConvexPolytope::edge(first_tie));
  if (facet == kNoIndex && last_tie != kNoIndex && first_tie == h0) facet = p.facet(last_tie);  // around the end
  if (facet == kNoIndex) throw std::logic_error("support: the vertices as high as a support vertex are no face");
  return Feature::facet(facet);
}

// The maximisers of <x, n> among `candidates` (a range of vertex indices),
// in their order, into `out`: one call higher(candidate, first maximiser so
// far) per candidate after the first.
// One candidate v after those already in `out` (the maximisers so far).
template <class Higher>
void support_candidate(Index v, Higher& higher, std::vector<Index>& out) {
  if (out.empty()) {
    out.push_back(v);
    return;
  }
  const int c = higher(v, out[0]);
  if (c > 0) out.assign(1, v);
  else if (c == 0) out.push_back(v);
}

template <std::ranges::input_range Range, class Higher>
void support_among(Range&& candidates, Higher&& higher, std::vector<Index>& out) {
  out.clear();
  for (const Index v : candidates) support_candidate(v, higher, out);
}

// Every vertex of p maximising <x, n>, in increasing order, by a scan of all
// vertices (V − 1 calls of higher).  (A plain loop: std::views::iota does not
// compile with clang 14 and libstdc++ 12, which the fuzz build uses.)
template <class Higher>
std::vector<Index> support_scan(const ConvexPolytope& p, Higher&& higher) {
  std::vector<Index> out;
  for (Index v = 0; v < p.num_vertices(); ++v) support_candidate(v, higher, out);
  return out;
}

// The same for an exact nonzero direction n.
struct Support {
  Index vertex;  // the maximiser the climb reached
  Feature face;  // the face of all maximisers
};
// By hill climbing from `start` (visits O(√V) vertices on a typical
// polytope, V in the worst case).
Support support(const ConvexPolytope& p, const Point3& n, Index start = 0);
// By a scan of all vertices; increasing order.
std::vector<Index> support_vertices(const ConvexPolytope& p, const Point3& n);

// The face of p whose vertex set is vs (any order): the vertex, the edge
// joining the two vertices, or the facet through the first three.  Throws
// std::logic_error when vs is not the vertex set of a face.  No geometry.
Feature feature_of_vertices(const ConvexPolytope& p, const std::vector<Index>& vs);

// The half-edge from vertex a to vertex b; kNoIndex when they are not
// adjacent.
inline Index halfedge_between(const ConvexPolytope& p, Index a, Index b) {
  const Index h0 = p.vertex_halfedge(a);
  Index h = h0;
  do {
    if (p.target(h) == b) return h;
    h = p.next_around_vertex(h);
  } while (h != h0);
  return kNoIndex;
}

// The vertices of feature f, into `out`: the vertex; the edge's origin and
// target (of its half-edge 2e); the facet's loop, counter-clockwise.
inline void feature_vertices(const ConvexPolytope& p, const Feature& f, std::vector<Index>& out) {
  out.clear();
  switch (f.dim) {
    case FeatureDim::vertex:
      out.push_back(f.index);
      return;
    case FeatureDim::edge:
      out.push_back(p.origin(2 * f.index));
      out.push_back(p.target(2 * f.index));
      return;
    case FeatureDim::facet: {
      const Index h0 = p.facet_halfedge(f.index);
      Index h = h0;
      do {
        out.push_back(p.origin(h));
        h = p.next(h);
      } while (h != h0);
      return;
    }
  }
}
// (The same as a new vector: feature_vertices(p, f) in <minksum/feature.hpp>.)

// Whether two vertex lists sorted increasingly (support sets) share a vertex.
bool share_a_vertex(const std::vector<Index>& x, const std::vector<Index>& y);

}  // namespace minksum
