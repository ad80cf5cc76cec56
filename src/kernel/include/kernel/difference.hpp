// Internal: exact comparison of two difference vectors, p1 − p0 against
// q1 − q0, without multiplications and without rational arithmetic.
//
// Use: a zero certificate for the degree-3 signs  ⟨x − y, n(f)⟩  of the walk.
// When x − y equals ± an edge vector of the facet f, it is orthogonal to
// n(f) and the sign is exactly 0 — which no floating-point filter can
// certify, and which identical, translated (by exact doubles) or point-
// reflected operands produce in almost every degenerate sign.
//
// Doubles.  In round-to-nearest, Knuth's TwoSum gives, for finite a and b
// whose rounded sum s = fl(a + b) is finite, the error e with s + e = a + b
// exactly (underflow included: a sum of doubles that lands in the subnormal
// range is exact, e = 0).  s is the rounding of the exact value, a function
// of it, and e = (a + b) − s; so the pair (s, e) is a function of the exact
// difference: two differences are exactly equal iff their pairs are equal
// (and exactly opposite iff the pairs are opposite).  An overflowing
// difference (s = ±inf) gives e = NaN, which equals nothing: "not decided".
// No bound, no tolerance: the test is error-free, and answers 0 (no
// certificate) whenever it cannot prove the relation.
//
// Rationals.  Only the arithmetic-free case: the same two points (or the
// same two points swapped) by exact equality of coordinates.
#pragma once

#include <minksum/kernel.hpp>

#include <cfenv>

namespace minksum::detail {

namespace difference_detail {
// TwoSum (Knuth) of a and −b: s = fl(a − b), s + e = a − b exactly.
inline void two_diff(double a, double b, double& s, double& e) {
  const double y = -b;  // exact
  s = a + y;
  const double yv = s - a;
  const double av = s - yv;
  e = (a - av) + (y - yv);
}
}  // namespace difference_detail

// +1 when p1 − p0 = q1 − q0 exactly, −1 when p1 − p0 = −(q1 − q0) exactly,
// 0 when neither (or when it cannot be decided: a difference overflows, or
// the rounding mode is not round-to-nearest).  A zero vector is both equal
// and opposite to itself; then +1.  `nearest`: the caller has checked that
// the FPU rounds to nearest (std::fegetround() == FE_TONEAREST), which the
// TwoSum pairs need; with false the answer is always 0.
inline int same_difference(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1, bool nearest) {
  if (!nearest) return 0;
  // The rounded differences first: equal exact values have equal roundings,
  // so a mismatch of the rounded values excludes the relation (no TwoSum).
  const double dx = p1.x - p0.x, dy = p1.y - p0.y, dz = p1.z - p0.z;
  const double ex = q1.x - q0.x, ey = q1.y - q0.y, ez = q1.z - q0.z;
  int rel;
  if (dx == ex && dy == ey && dz == ez) rel = 1;
  else if (dx == -ex && dy == -ey && dz == -ez) rel = -1;
  else return 0;
  using difference_detail::two_diff;
  const double pa[3] = {p1.x, p1.y, p1.z}, pb[3] = {p0.x, p0.y, p0.z};
  const double qa[3] = {q1.x, q1.y, q1.z}, qb[3] = {q0.x, q0.y, q0.z};
  for (int i = 0; i < 3; ++i) {
    double s, e, t, f;
    two_diff(pa[i], pb[i], s, e);
    two_diff(qa[i], qb[i], t, f);
    // s, t finite (else e, f are NaN and the comparison below fails).
    if (rel > 0 ? !(s == t && e == f) : !(s == -t && e == -f)) return 0;
  }
  return rel;
}

// The rational form: +1 when (p0, p1) = (q0, q1), −1 when (p0, p1) =
// (q1, q0) (coordinates compared exactly), else 0 — a certificate, not a
// complete test: other equal differences answer 0.
inline int same_difference(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  if (p0 == q0 && p1 == q1) return 1;
  if (p0 == q1 && p1 == q0) return -1;
  return 0;
}

}  // namespace minksum::detail
