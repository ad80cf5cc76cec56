// Internal: whether a line provably misses a box, on intervals (a filter
// that only ever answers "misses" when it holds).
//
// The line is {q + s d : s real} with q an exact rational point and d a
// direction of doubles (exact); the box is the closed [lo, hi].
//
// Proof.  The s with q + s d in the box form the intersection over the axes
// k of S_k = {s : lo_k <= q_k + s d_k <= hi_k}: for d_k != 0 the closed
// interval between (lo_k - q_k) / d_k and (hi_k - q_k) / d_k; for d_k = 0
// all of R when lo_k <= q_k <= hi_k, else empty.  Q_k is an interval that
// contains q_k (to_interval), and the quotients are evaluated on intervals
// rounded outward (FastInterval, under the CGAL::Protect_FPU_rounding<true>
// guard the caller holds, which sets upward rounding whatever the mode was),
// so T1 and T2 contain (lo_k - x) / d_k and (hi_k - x) / d_k for every x in
// Q_k, q_k among them, and S_k lies in [min(T1.inf, T2.inf), max(T1.sup,
// T2.sup)].  When the largest lower end of these enclosures exceeds the
// smallest upper end, the intersection of the S_k is empty; for d_k = 0,
// Q_k.sup < lo_k or Q_k.inf > hi_k makes S_k empty.  Either way the line
// misses the box.  An axis with an infinite end among lo_k, hi_k and Q_k
// (d_k != 0) is left out (no claim on it, as inf - inf would be NaN); with
// finite ones, the intervals stay valid through overflow (infinite ends,
// never NaN).
//
// The box of a set of exact points from their nearest doubles x̂ (round to
// nearest: the exact x lies strictly between the neighbours of x̂, also
// when x̂ is a power of two or infinite): lo = the smallest
// nextafter(x̂, −∞), hi = the largest nextafter(x̂, +∞) (widen_box).
#pragma once

#include <cmath>
#include <limits>

#include "kernel/interval.hpp"

namespace minksum {

// Widens [lo, hi], a box of nearest doubles of exact points, to a box that
// contains the exact points (see above).
inline void widen_box(double lo[3], double hi[3]) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::nextafter(lo[k], -inf);
    hi[k] = std::nextafter(hi[k], inf);
  }
}

// Whether the line {q + s d} misses the closed box [lo, hi] for certain
// (false: it may meet it).  q: intervals containing the exact point; d: the
// direction, not zero.  The caller holds CGAL::Protect_FPU_rounding<true>.
inline bool line_misses_box(const FastIPoint& q, const double d[3], const double lo[3], const double hi[3]) {
  const FastInterval* qk[3] = {&q.x, &q.y, &q.z};
  double from = -std::numeric_limits<double>::infinity(), to = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const FastInterval& x = *qk[k];
    if (d[k] == 0) {
      if (x.sup() < lo[k] || x.inf() > hi[k]) return true;
      continue;
    }
    // Infinite ends (a box or a point beyond the doubles) claim nothing on
    // this axis (inf - inf would be NaN).
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || !std::isfinite(x.inf()) || !std::isfinite(x.sup())) continue;
    const FastInterval t1 = (FastInterval(lo[k]) - x) / FastInterval(d[k]);
    const FastInterval t2 = (FastInterval(hi[k]) - x) / FastInterval(d[k]);
    const double a = std::min(t1.inf(), t2.inf()), b = std::max(t1.sup(), t2.sup());
    if (a > from) from = a;
    if (b < to) to = b;
  }
  return from > to;
}

}  // namespace minksum
