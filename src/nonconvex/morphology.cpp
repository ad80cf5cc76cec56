// Erosion, opening and closing of a solid by a convex polytope
// (docs/nonconvex.md, "Erosion, opening, closing").
//
// A ⊖ B = {x : x + B ⊆ A} is the complement of Aᶜ ⊕ (−B), Aᶜ the closure of
// A's complement: x + B ⊆ A fails exactly when some x + b lies outside A,
// that is when x ∈ Aᶜ − b.  Aᶜ is unbounded, but its surface is A's, and the
// boundary sweep needs only the surface (its triangles reversed, so that
// their local normal cones are Aᶜ's) and an inside test (Aᶜ's inside is
// A's outside): Aᶜ ⊕ (−B) = (Aᶜ − b) ∪ ⋃ (t ⊕ (−B)) over the triangles t of
// ∂A, b inside B, and the union's boundary components whose points p have
// p + b outside A are dropped.  What is left bounds the cavities of the
// union that lie in the erosion; reversed, it is the erosion's boundary.
// For a convex A the erosion is the intersection of A's facet half-spaces
// moved by B's support (halfspace_erosion.cpp), a convex polytope, which
// erode, opening and closing build directly when they find a point strictly
// inside it; they sweep every other A (and a convex A whose erosion is
// empty or lower-dimensional).
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex/morphology.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

namespace minksum {

namespace {

// The faces of `m` reversed (each polygon's order).
void reverse_faces(Mesh& m) {
  for (auto& f : m.faces) std::reverse(f.begin() + 1, f.end());
}

const ConvexPolytope& convex_operand(const Solid& b, const char* operation) {
  if (!b.convex)
    throw std::invalid_argument(std::string(operation) + " needs a convex B (the structuring element): B is not convex");
  return *b.convex;
}

// A boundary that a step computed (a NonconvexSum's mesh, exact, possibly
// touching itself along edges or at points) as a Solid to sweep: its
// triangles (reversed for the complement), cut apart where it touches
// itself, so that each part's cones are read off its own faces.  (A step
// on a convex A gives a convex polytope instead: convex_step.)  Its volume
// is the step's, 0 when not computed (first_step): the sweep does not
// read a Solid's volume.
Solid solid_of_boundary(const NonconvexSum& r, bool complement) {
  Solid s;
  Mesh tri = triangulate(r.mesh, r.operation);
  if (complement) reverse_faces(tri);
  s.triangles = nonconvex_detail::separate_contacts(tri);
  s.volume = complement ? -r.volume : r.volume;
  s.faces = r.mesh.faces.size();
  s.vertices = r.mesh.points.size();
  s.complement = complement;
  return s;
}

Solid complement_of(const Solid& a) {
  Solid c;
  c.triangles = a.triangles;
  reverse_faces(c.triangles);
  c.volume = -a.volume;
  c.faces = a.faces;
  c.vertices = a.vertices;
  c.complement = true;
  return c;
}

// The complement of c ⊕ (−B) for c the complement of a solid: the erosion.
NonconvexSum erode_complement(const Solid& c, const ConvexPolytope& b, const SumOptions& options, unsigned threads,
                              Method method) {
  NonconvexSum r =
      minkowski_sum_nonconvex(c, solid_of(b.negated()), options, threads, method, NonconvexMethod::sweep);
  reverse_faces(r.mesh);
  r.volume = -r.volume;
  r.operation = "erosion";
  return r;
}

// `step`'s work added to `total`'s (the boundary, volume and shells are the
// last step's).
void add_work(NonconvexSum& total, const NonconvexSum& step) {
  total.pieces_a += step.pieces_a;
  total.pieces_b += step.pieces_b;
  total.pairs += step.pairs;
  total.candidate_facets += step.candidate_facets;
  total.culled_facets += step.culled_facets;
  total.dropped_components += step.dropped_components;
  total.pair_vertices += step.pair_vertices;
  total.pair_facets += step.pair_facets;
  total.clips += step.clips;
  total.seconds_decompose += step.seconds_decompose;
  total.seconds_pairs += step.seconds_pairs;
  total.seconds_union += step.seconds_union;
  total.seconds_boundary += step.seconds_boundary;
}

// The options of a first step: no exact volume, whatever the caller asked
// of the last step.  The second step sweeps the first one's boundary and
// never reads its volume (solid_of_boundary); the result's volume is the
// second step's.
SumOptions first_step(const SumOptions& options) {
  SumOptions o = options;
  o.volume = false;
  return o;
}

// The boundary of the convex polytope `p` that a step built (its facets,
// one shell; `out.convex` the polytope) and its volume, `seconds_pairs` the
// time it took to build.
void convex_boundary(NonconvexSum& out, const ConvexPolytope& p, double seconds_pairs,
                     const SumOptions& options) {
  using Clock = std::chrono::steady_clock;
  out.method = "decomposition";
  out.pieces_a = out.pieces_b = out.pairs = 1;
  out.pair_vertices = p.num_vertices();
  out.seconds_pairs = seconds_pairs;
  const auto t0 = Clock::now();
  options.report("boundary", 0.0);
  out.mesh = p.to_mesh();
  out.shells = 1;
  out.seconds_boundary = std::chrono::duration<double>(Clock::now() - t0).count();
  if (options.volume) out.volume = p.volume();
  out.convex = p;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The sum of two convex polytopes as the non-convex engine reports a sum of
// two convex solids (the decomposition's one pair), its boundary the
// polytope's facets: the union of one convex polytope is that polytope, its
// maximal planar faces its facets, one shell.  *polytope: the sum.
NonconvexSum convex_step(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options,
                         Method method, ConvexPolytope* polytope = nullptr) {
  NonconvexSum out;
  out.pair_method = method;
  const auto t0 = std::chrono::steady_clock::now();
  options.report("pairs", 0.0);
  ConvexPolytope p = minkowski_sum(a, b, method).polytope;
  options.report("pairs", 1.0);
  out.pair_facets = out.candidate_facets = p.num_facets();
  convex_boundary(out, p, seconds_since(t0), options);
  if (polytope) *polytope = std::move(p);
  return out;
}

// The erosion of a convex A as the intersection of its moved half-spaces
// (halfspace_erosion), reported as convex_step reports the convex path: one
// piece of each operand, one pair, no union; pair_facets the moved
// half-spaces (A's facets), candidate_facets the erosion's facets (the
// others are redundant).  nullopt when halfspace_erosion finds no point
// strictly inside: the caller sweeps.  *polytope: the erosion.
std::optional<NonconvexSum> convex_erosion_step(const ConvexPolytope& a, const ConvexPolytope& b,
                                                const SumOptions& options, Method method,
                                                ConvexPolytope* polytope = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  options.report("pairs", 0.0);
  std::optional<ConvexPolytope> e = nonconvex_detail::halfspace_erosion(a, b);
  if (!e) return std::nullopt;
  options.report("pairs", 1.0);
  NonconvexSum out;
  out.pair_method = method;
  out.operation = "erosion";
  out.pair_facets = a.num_facets();
  out.candidate_facets = e->num_facets();
  convex_boundary(out, *e, seconds_since(t0), options);
  if (polytope) *polytope = std::move(*e);
  return out;
}

NonconvexSum then(NonconvexSum first, NonconvexSum second, const char* operation) {
  add_work(second, first);
  second.operation = operation;
  return second;
}

}  // namespace

NonconvexSum erode(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads, Method method) {
  const ConvexPolytope& pb = convex_operand(b, "erosion");
  if (a.complement) throw std::invalid_argument("erosion of the complement of a solid");
  if (a.convex)
    if (std::optional<NonconvexSum> e = convex_erosion_step(*a.convex, pb, options, method)) return std::move(*e);
  return erode_complement(complement_of(a), pb, options, threads, method);
}

NonconvexSum opening(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads, Method method) {
  const ConvexPolytope& pb = convex_operand(b, "opening");
  if (a.complement) throw std::invalid_argument("erosion of the complement of a solid");
  // For convex A the erosion is convex, and its sum with B is the convex path's.
  if (a.convex) {
    ConvexPolytope inner;
    if (std::optional<NonconvexSum> e = convex_erosion_step(*a.convex, pb, first_step(options), method, &inner))
      return then(std::move(*e), convex_step(inner, pb, options, method), "opening");
  }
  NonconvexSum e = erode_complement(complement_of(a), pb, first_step(options), threads, method);
  if (e.mesh.faces.empty()) {  // B fits nowhere inside A: the opening is empty too
    e.operation = "opening";
    return e;
  }
  if (a.convex) {
    NonconvexSum s = convex_step(ConvexPolytope::from_mesh(e.mesh, e.operation), pb, options, method);
    return then(std::move(e), std::move(s), "opening");
  }
  const Solid inner = solid_of_boundary(e, false);
  NonconvexSum s = minkowski_sum_nonconvex(inner, solid_of(pb), options, threads, method);
  return then(std::move(e), std::move(s), "opening");
}

NonconvexSum closing(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads, Method method) {
  const ConvexPolytope& pb = convex_operand(b, "closing");
  // For convex A the sum is convex: the convex path's, as in the opening,
  // and so is its erosion (A itself: a convex summand cancels).
  ConvexPolytope sum;
  NonconvexSum s = a.convex ? convex_step(*a.convex, pb, first_step(options), method, &sum)
                            : minkowski_sum_nonconvex(a, b, first_step(options), threads, method);
  if (a.convex)
    if (std::optional<NonconvexSum> e = convex_erosion_step(sum, pb, options, method))
      return then(std::move(s), std::move(*e), "closing");
  const Solid outer = solid_of_boundary(s, true);
  NonconvexSum e = erode_complement(outer, pb, options, threads, method);
  return then(std::move(s), std::move(e), "closing");
}

}  // namespace minksum
