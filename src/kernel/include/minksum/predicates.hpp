// minksum — the sign predicates of the exact kernel.
//
// Every geometric decision minksum makes is the sign of one of the small
// polynomials below, evaluated exactly.  Each predicate comes
// in two forms:
//
//   * on Vec3d: the doubles ARE the exact input coordinates (callers
//     guarantee it; every coordinate must be finite).  A floating-point filter
//     with a proven error bound decides almost every call; when it cannot, the
//     polynomial is evaluated exactly with GMP integers.
//   * on Point3: arbitrary exact rationals.  When every coordinate is exactly
//     a double, the Vec3d path is taken; otherwise a filter on the rounded
//     coordinates (whose bound accounts for the rounding) is tried, then the
//     polynomial is evaluated exactly.
//
// The answers never depend on the path: the filter only answers when its
// bound proves the sign, and zero is always the exact zero.  The polynomials,
// their degrees and the error-bound derivations are in docs/kernel.md and
// in src/kernel/include/kernel/filter.hpp (shapes) and predicates_internal.hpp (descriptors).
//
// Notation: for three points a0, a1, a2, their normal is
//   n(a0, a1, a2) = (a1 − a0) × (a2 − a0),
// which points to the side from which a0, a1, a2 appear counterclockwise.
// It is the zero vector exactly when the three points are collinear.
//
// Preconditions: Vec3d coordinates are finite (checked by assert in the
// exact stage).  The filters' bounds hold in every IEEE 754 rounding mode, so
// the predicates may also be called while the FPU rounds upwards (e.g. inside
// interval-arithmetic code).
//
// Thread safety: all predicates are reentrant.  The filter statistics and the
// exact stage's scratch integers are per thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <minksum/kernel.hpp>

namespace minksum {

// ---------------------------------------------------------------------------
// 1. Orientation (degree 3).
//
//   orient3d(a, b, c, d) = sign det[b − a; c − a; d − a]
//                        = sign ⟨d − a, n(a, b, c)⟩.
// +1: d lies strictly on the side of the plane through a, b, c into which
//     n(a, b, c) points (a, b, c appear counterclockwise seen from d);
// −1: the other side;  0: the four points are coplanar (this includes any
//     repeated point and collinear a, b, c).
// Same convention as CGAL::orientation; opposite to Shewchuk's orient3d.
int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// ---------------------------------------------------------------------------
// 2. Support comparison (degree 3).
//
//   support_compare(a0, a1, a2, bi, bj) = sign ⟨bi − bj, n(a0, a1, a2)⟩.
// +1: bi is strictly higher than bj along the normal of the facet of A
//     spanned by a0, a1, a2 (so bj is not a contributing vertex of it);
//  0: equally high (or the normal is zero).
// It compares two vertices of B directly (a difference of two heights), with
// no point of B placed on A's facet plane.
int support_compare(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                    const Vec3d& bj);
int support_compare(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& bi,
                    const Point3& bj);

// ---------------------------------------------------------------------------
// 3. Edge-versus-facet visibility (degree 3).
//
//   edge_facet_sign(p0, p1, a0, a1, a2) = sign ⟨p1 − p0, n(a0, a1, a2)⟩.
// +1: the edge direction p1 − p0 points to the outer side of the facet
//     (the side n points to); 0: the edge is parallel to the facet's plane.
int edge_facet_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                    const Vec3d& a2);
int edge_facet_sign(const Point3& p0, const Point3& p1, const Point3& a0, const Point3& a1,
                    const Point3& a2);

// ---------------------------------------------------------------------------
// 4. Arc-crossing side test (degree 4).
//
//   arc_side(p0, p1, q0, q1, r0, r1, r2) = sign det[e_a; e_b; n]
//                                        = sign ⟨e_a × e_b, n⟩
// with e_a = p1 − p0, e_b = q1 − q0, n = n(r0, r1, r2).
// On the Gaussian sphere, the great circles dual to the edges e_a and e_b
// (the circles orthogonal to them) meet at ±(e_a × e_b); the sign tells
// whether the crossing point e_a × e_b lies in the open hemisphere centred at
// n (+1), in the opposite one (−1), or on the great circle orthogonal to n (0;
// also when e_a ∥ e_b or n = 0).
int arc_side(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1, const Vec3d& r0,
             const Vec3d& r1, const Vec3d& r2);
int arc_side(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
             const Point3& r0, const Point3& r1, const Point3& r2);

// ---------------------------------------------------------------------------
// 5. Facet normals compared (degree 4).  n1 = n(a0, a1, a2), n2 = n(b0, b1, b2).
//
//   normals_dot_sign       = sign ⟨n1, n2⟩.
//   normals_parallel       = (n1 × n2 = 0): the normals are parallel or
//                            opposite, or one of them is zero.
//   normals_same_direction = n1 × n2 = 0 and ⟨n1, n2⟩ > 0: both normals are
//                            non-zero and point the same way (the facets have
//                            the same outer normal direction).  False when
//                            either normal is zero.
int normals_dot_sign(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                     const Vec3d& b1, const Vec3d& b2);
int normals_dot_sign(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                     const Point3& b1, const Point3& b2);
bool normals_parallel(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                      const Vec3d& b1, const Vec3d& b2);
bool normals_parallel(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                      const Point3& b1, const Point3& b2);
bool normals_same_direction(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                            const Vec3d& b1, const Vec3d& b2);
bool normals_same_direction(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                            const Point3& b1, const Point3& b2);

// ---------------------------------------------------------------------------
// 6. Dot products (degree 2).
//
//   dot_sign(p0, p1, q0, q1) = sign ⟨p1 − p0, q1 − q0⟩.
//   compare_along(d, p, q)   = sign ⟨d, p − q⟩: +1 when p is strictly further
//                              than q in the direction d (d is an exact
//                              vector, e.g. an exact facet normal), 0 when
//                              they are equally far or d = 0.  Made for hill
//                              climbing towards the support of d.
int dot_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1);
int dot_sign(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1);
int compare_along(const Vec3d& d, const Vec3d& p, const Vec3d& q);
int compare_along(const Point3& d, const Point3& p, const Point3& q);

//   edge_normal_side(a, b, n, d) = sign ⟨d − a, (b − a) × n⟩, n an exact
//                              vector: orient3d(a, b, a + n, d), the side of d
//                              with respect to the plane through a and b
//                              parallel to n.  With n the outer normal of a
//                              facet and a → b one of its edges (counter-
//                              clockwise seen from outside), +1 when d lies
//                              strictly beyond that edge (the Voronoi
//                              region tests of proximity queries).  Degree 3.
int edge_normal_side(const Vec3d& a, const Vec3d& b, const Vec3d& n, const Vec3d& d);
int edge_normal_side(const Point3& a, const Point3& b, const Point3& n, const Point3& d);

// ---------------------------------------------------------------------------
// 7. Rational inputs with cached roundings (kernel/rounded.cpp).
//
// A RoundedPoint3 pairs an exact point with a faithful rounding of each of
// its coordinates (|approx − exact| < one ulp of approx), such as
// to_double(p) or ConvexPolytope::approx(v), which round to nearest.  The
// filters below run on the cached doubles (no rational → double conversion
// per call); a coordinate whose rounding is subnormal, or zero while the
// exact coordinate is not, makes the filter decline.  The answers are the
// exact ones, as for every predicate.
struct RoundedPoint3 {
  const Point3& exact;
  const Vec3d& approx;
};

// orient3d(a.exact, b.exact, c.exact, d.exact); counted as orient3d.
int orient3d(const RoundedPoint3& a, const RoundedPoint3& b, const RoundedPoint3& c,
             const RoundedPoint3& d);
// support_compare, arc_side, dot_sign and edge_normal_side on rounded
// points; counted as those.
int support_compare(const RoundedPoint3& a0, const RoundedPoint3& a1, const RoundedPoint3& a2,
                    const RoundedPoint3& bi, const RoundedPoint3& bj);
int arc_side(const RoundedPoint3& p0, const RoundedPoint3& p1, const RoundedPoint3& q0,
             const RoundedPoint3& q1, const RoundedPoint3& r0, const RoundedPoint3& r1,
             const RoundedPoint3& r2);
int dot_sign(const RoundedPoint3& p0, const RoundedPoint3& p1, const RoundedPoint3& q0,
             const RoundedPoint3& q1);
int edge_normal_side(const RoundedPoint3& a, const RoundedPoint3& b, const RoundedPoint3& n,
                     const RoundedPoint3& d);

// plane.side(s.exact) = sign(a·x + b·y + c·z − d), given `rounded`, faithful
// roundings of the plane's integers (a, b, c, d).  Not counted in the
// statistics.
int plane_side(const Plane& plane, const std::array<double, 4>& rounded, const RoundedPoint3& s);

// The plane nearest to s: the index i minimising (d_i − n_i·s)² / |n_i|²
// over planes[0..n), the smallest such index on ties.  rounded[i] holds
// faithful roundings of plane i's (a, b, c, d).  Only the planes an interval
// filter cannot rule out are compared exactly.  Precondition: n > 0.
std::size_t nearest_plane(const Plane* const* planes, const std::array<double, 4>* rounded,
                          std::size_t n, const RoundedPoint3& s);

// ---------------------------------------------------------------------------
// Filter statistics.
//
// Every call of a public predicate above counts one call; a call that the
// floating-point filter could not decide and that was evaluated exactly also
// counts one fallback.  (A Point3 call whose coordinates cannot be filtered,
// e.g. rationals outside the filter's range, counts as a fallback too.)
// Counters are per thread and cost one increment each.

enum class PredicateId : int {
  orient3d,
  support_compare,
  edge_facet_sign,
  arc_side,
  normals_dot_sign,
  normals_parallel,
  normals_same_direction,
  dot_sign,
  compare_along,
  edge_normal_side,
};
inline constexpr int kPredicateCount = 10;

// "orient3d", "support_compare", ... (the function names).
const char* predicate_name(PredicateId id);

struct PredicateCounter {
  std::uint64_t calls = 0;
  std::uint64_t fallbacks = 0;
  double fallback_ratio() const { return calls ? double(fallbacks) / double(calls) : 0.0; }
};

struct PredicateStats {
  std::array<PredicateCounter, kPredicateCount> counters{};
  const PredicateCounter& operator[](PredicateId id) const { return counters[int(id)]; }
  // The sum over all predicates.
  PredicateCounter total() const {
    PredicateCounter t;
    for (const auto& c : counters) t.calls += c.calls, t.fallbacks += c.fallbacks;
    return t;
  }
};

// A snapshot of this thread's counters, and their reset to zero.
PredicateStats predicate_stats();
void reset_predicate_stats();

}  // namespace minksum
