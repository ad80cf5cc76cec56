// minksum — sign ⟨u, q − p⟩ for three rational points with cached faithful
// roundings (RoundedPoint3), filtered on the doubles alone, exact otherwise:
//
//   dot_difference_sign(u, p, q) = dot_sign(0, u, p, q) = sign(u · (q − p)).
//
// The non-convex sweep asks it millions of times (where t's vertices lie
// along a facet normal of the convex operand, whether a direction is in a
// vertex's cone); the general rounded dot_sign runs the kernel's generic
// rational filter on four points, one of them the origin, whose zero
// coordinates take its slow path each time.
//
// Error bound of dot_difference_filter.  ε = 2^-52.
//  * Inputs.  Each of the nine doubles is a faithful rounding of its
//    rational (RoundedPoint3: |exact − approx| < ε |approx|), so
//    u_i = û_i (1 + α_i), p_i = p̂_i (1 + β_i), q_i = q̂_i (1 + γ_i) with
//    |α|, |β|, |γ| < ε, and each is zero or of magnitude in [2^-480, 2^480)
//    (checked; a zero double is used only when its rational is zero).
//  * Evaluation, in ANY IEEE 754 rounding mode: d_i = fl(q̂_i − p̂_i),
//    t_i = fl(û_i d_i), s = fl(fl(t_0 + t_1) + t_2).  A non-zero difference
//    of two such doubles is a multiple of 2^-532 and below 2^481, so
//    d_i = (q̂_i − p̂_i)(1 + δ_i), |δ_i| ≤ ε; a non-zero product lies in
//    [2^-1012, 2^961): normal, so t_i = û_i d_i (1 + δ'_i), |δ'_i| ≤ ε; the
//    two additions of normal doubles add at most (2ε + ε²) Σ|t_i| (an
//    addition whose result is subnormal is exact).
//  * With m_i = |û_i| (|q̂_i| + |p̂_i|) and M = Σ m_i:
//    u_i (q_i − p_i) − û_i (q̂_i − p̂_i) = û_i [α_i (q̂_i − p̂_i) +
//    (1 + α_i)(γ_i q̂_i − β_i p̂_i)], at most (2ε + ε²) m_i; t_i differs from
//    û_i (q̂_i − p̂_i) by at most (2ε + ε²) m_i; and Σ|t_i| ≤ (1 + ε)² M.
//    So, P being the exact u · (q − p),
//        |s − P| ≤ (4ε + 2ε²) M + (2ε + ε²)(1 + ε)² M < 6.01 ε M.
//  * The bound computed is M̃ = fl(fl(fl(|û_0| fl(|q̂_0| + |p̂_0|)) + …)):
//    sums and products of non-negative normal doubles, each at least
//    (1 − ε) times exact, four deep, so M̃ ≥ (1 − ε)^4 M, and no overflow
//    (M < 2^963).  The test is 2^48 |s| > M̃, i.e. |s| > 16 ε M̃ ≥
//    16 ε (1 − ε)^4 M > 6.01 ε M ≥ |s − P| when M > 0 (the scaling by 2^48
//    is exact: |s| < 2^963, and a subnormal s scales exactly), so sign(s) =
//    sign(P).  When M̃ = 0 every m_i is 0: each term has û_i = 0 or
//    q̂_i = p̂_i = 0, so its rational factor is zero, and P = 0 exactly.
//  * The analysis holds if the compiler contracts a product and a sum into
//    an FMA (one rounding fewer); it does not hold under -ffast-math, which
//    the kernel refuses.
#pragma once

#include <cmath>
#include <minksum/predicates.hpp>
#include <optional>

namespace minksum {

inline constexpr double kDotDifferenceScale = 0x1p+48;
inline constexpr double kDotDifferenceMin = 0x1p-480;
inline constexpr double kDotDifferenceMax = 0x1p+480;

namespace detail {
// x may enter the filter: zero with its rational zero, or of magnitude in
// [2^-480, 2^480).
inline bool dot_difference_usable(double x, const Rational& exact) {
  const double a = std::fabs(x);
  if (a >= kDotDifferenceMin && a < kDotDifferenceMax) return true;
  return x == 0 && sgn(exact) == 0;
}
inline bool dot_difference_usable(const RoundedPoint3& p) {
  return dot_difference_usable(p.approx.x, p.exact.x) && dot_difference_usable(p.approx.y, p.exact.y) &&
         dot_difference_usable(p.approx.z, p.exact.z);
}
}  // namespace detail

// The sign of u · (q − p) that the bound above proves from the doubles, or
// nothing (an input out of range, or too close to call).
inline std::optional<int> dot_difference_filter(const RoundedPoint3& u, const RoundedPoint3& p,
                                                const RoundedPoint3& q) {
  if (!detail::dot_difference_usable(u) || !detail::dot_difference_usable(p) || !detail::dot_difference_usable(q))
    return std::nullopt;
  const double d0 = q.approx.x - p.approx.x, d1 = q.approx.y - p.approx.y, d2 = q.approx.z - p.approx.z;
  const double s = (u.approx.x * d0 + u.approx.y * d1) + u.approx.z * d2;
  const double m = (std::fabs(u.approx.x) * (std::fabs(q.approx.x) + std::fabs(p.approx.x)) +
                    std::fabs(u.approx.y) * (std::fabs(q.approx.y) + std::fabs(p.approx.y))) +
                   std::fabs(u.approx.z) * (std::fabs(q.approx.z) + std::fabs(p.approx.z));
  const double scaled = kDotDifferenceScale * s;
  if (scaled > m) return 1;
  if (scaled < -m) return -1;
  if (m == 0) return 0;
  return std::nullopt;
}

// sign(u · (q − p)), exactly: the filter above, else dot_sign on the exact
// points (its own filters, then exact arithmetic).
int dot_difference_sign(const RoundedPoint3& u, const RoundedPoint3& p, const RoundedPoint3& q);

}  // namespace minksum
