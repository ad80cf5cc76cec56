// minksum — the side of a rational point with respect to a half-space with
// rational coefficients, filtered on the nearest doubles of all seven
// rationals (cached by the caller), exact otherwise.
//
//   half_space_side(a, b, c, d, p) = sign(a·x + b·y + c·z − d),  p = (x, y, z).
//
// The caller keeps, next to each rational q, its nearest double q̂ =
// to_double(q) and whether q̂ may enter the filter
// (half_space_filter_usable(q̂, q)); half_space_side_filter then answers the
// sign from the doubles alone when it can prove it, and the caller falls
// back to half_space_side_exact (or its own exact value) when it answers
// nothing.
//
// Error bound of half_space_side_filter.  ε = 2^-52.
//  * Inputs.  Every one of the seven doubles is within relative 2^-53 of its
//    rational (round to nearest, as to_double), and either zero with the
//    rational zero, or of magnitude in [2^-480, 2^480).  (The bound below
//    holds as well for any faithful rounding, within relative ε.)  So
//    a = â(1 + α), x = x̂(1 + ξ) with |α|, |ξ| ≤ ε, and
//        |a·x − â·x̂| ≤ (2ε + ε²)|â·x̂|,   |d − d̂| ≤ ε|d̂|.
//  * Evaluation, t1 = fl(â·x̂), t2 = fl(b̂·ŷ), t3 = fl(ĉ·ẑ),
//    s = fl(fl(fl(t1 + t2) + t3) − d̂), in ANY IEEE 754 rounding mode.  The
//    non-zero products have magnitudes in [2^-960, 2^960): normal, no
//    underflow, no overflow, so fl(â·x̂) = â·x̂(1 + δ) with |δ| ≤ ε (a zero
//    product is exact); the sums stay below 2^962 and a sum never
//    underflows with a relative error.  Hence |â·x̂| ≤ |t1|/(1 − ε) and
//        |t1 + t2 + t3 − (â·x̂ + b̂·ŷ + ĉ·ẑ)| ≤ ε/(1 − ε) · S,
//        |s − (t1 + t2 + t3 − d̂)|            ≤ γ_3 · S,
//    with S = |t1| + |t2| + |t3| + |d̂| and γ_3 = 3ε/(1 − 3ε).
//  * In all, with P the exact a·x + b·y + c·z − d:
//        |s − P| ≤ (γ_3 + ε/(1 − ε) + (2ε + ε²)/(1 − ε)) · S < 6.001 ε · S.
//  * The bound computed is e = fl(2^-48 · fl(fl(fl(|t1| + |t2|) + |t3|) + |d̂|)):
//    three sums of non-negative terms, each at least (1 − ε) times exact
//    whatever the rounding mode, and an exact scaling by a power of two
//    (S = 0 or S ≥ 2^-960, so 2^-48 S is normal or zero):
//        e ≥ 2^-48 (1 − ε)^3 S = 16 ε (1 − ε)^3 S > 6.001 ε S ≥ |s − P|,
//    strictly when S > 0.  So |s| > e implies |s − P| < |s|: sign(P) =
//    sign(s), i.e. |computed − exact| < 2^-48 (|t1| + |t2| + |t3| + |d̂|).
//    When S = 0 every product and d̂ are exactly zero (no product of usable
//    non-zero doubles rounds to zero), so P = 0 exactly.
//  * The analysis holds if the compiler contracts a product and a sum into
//    an FMA (one rounding fewer on that path); it does not hold under
//    -ffast-math, which the kernel refuses.
#pragma once

#include <cmath>
#include <minksum/kernel.hpp>
#include <optional>

namespace minksum {

// The filter's relative bound (see above) and the usable range of its inputs.
inline constexpr double kHalfSpaceFilterBound = 0x1p-48;
inline constexpr double kHalfSpaceFilterMin = 0x1p-480;
inline constexpr double kHalfSpaceFilterMax = 0x1p+480;

// Whether x, the nearest double of the rational q, may enter
// half_space_side_filter: finite, and zero with q zero, or of magnitude in
// [2^-480, 2^480).
inline bool half_space_filter_usable(double x, const Rational& q) {
  return std::isfinite(x) && std::fabs(x) < kHalfSpaceFilterMax &&
         (x == 0 ? sgn(q) == 0 : std::fabs(x) >= kHalfSpaceFilterMin);
}

// The sign of a·x + b·y + c·z − d that the bound above proves, from the
// nearest doubles of the seven rationals (all usable), or nothing.  Answers
// 0 only when every product and d̂ are zero (then the exact value is 0).
inline std::optional<int> half_space_side_filter(double a, double b, double c, double d, double x,
                                                 double y, double z) {
  const double t1 = a * x, t2 = b * y, t3 = c * z;
  const double s = ((t1 + t2) + t3) - d;
  const double e =
      kHalfSpaceFilterBound * (((std::fabs(t1) + std::fabs(t2)) + std::fabs(t3)) + std::fabs(d));
  if (s > e) return 1;
  if (s < -e) return -1;
  if (e == 0) return 0;  // S = 0: every term exactly zero
  return std::nullopt;
}

// The exact sign of a·x + b·y + c·z − d.
inline int half_space_side_exact(const Rational& a, const Rational& b, const Rational& c,
                                 const Rational& d, const Point3& p) {
  return sgn(Rational(a * p.x + b * p.y + c * p.z - d));
}

}  // namespace minksum
