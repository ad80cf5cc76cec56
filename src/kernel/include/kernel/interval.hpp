// Internal: interval arithmetic for filtering signs of exact expressions.
//
// Each filtered sign computes the same expression as its exact version, but
// on intervals (CGAL::Interval_nt, every operation rounded outward), whose
// result is guaranteed to contain the exact value.  If the interval excludes
// zero, its sign is the exact sign; if it is [0, 0] the value is exactly 0;
// otherwise the caller re-evaluates exactly.  The enclosure stays valid
// through overflow (intervals grow to infinity) and underflow (directed
// rounding), so no range conditions are needed.
#pragma once

#include <minksum/kernel.hpp>

#include <CGAL/Interval_nt.h>

namespace minksum {

// Protected intervals switch the FPU to upward rounding around every
// operation; unprotected ones (FastInterval) must only be used while a
// CGAL::Protect_FPU_rounding<true> guard holds the upward mode for a whole
// computation (CGAL's own filtered predicates do the same).
using Interval = CGAL::Interval_nt<true>;
using FastInterval = CGAL::Interval_nt<false>;
inline constexpr int kUncertain = 2;

template <class I>
struct IPointT {
  I x, y, z;
};
using IPoint = IPointT<Interval>;
using FastIPoint = IPointT<FastInterval>;

template <class I>
inline IPointT<I> operator-(const IPointT<I>& a, const IPointT<I>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class I>
inline IPointT<I> operator+(const IPointT<I>& a, const IPointT<I>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class I>
inline IPointT<I> operator-(const IPointT<I>& a) { return {-a.x, -a.y, -a.z}; }
template <class I>
inline IPointT<I> cross(const IPointT<I>& a, const IPointT<I>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class I>
inline I dot(const IPointT<I>& a, const IPointT<I>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// -1, 0, +1 when certain; kUncertain otherwise.
template <bool P>
inline int sign_of(const CGAL::Interval_nt<P>& i) {
  if (i.inf() > 0) return 1;
  if (i.sup() < 0) return -1;
  if (i.inf() == 0 && i.sup() == 0) return 0;
  return kUncertain;
}
template <class I>
inline int sign_det(const IPointT<I>& a, const IPointT<I>& b, const IPointT<I>& c) { return sign_of(dot(a, cross(b, c))); }

// A protected interval point as an unprotected one (same bounds).
inline FastIPoint to_fast(const IPoint& p) {
  return {FastInterval(p.x.inf(), p.x.sup()), FastInterval(p.y.inf(), p.y.sup()), FastInterval(p.z.inf(), p.z.sup())};
}

// Smallest double interval around q (a point interval when q is a double).
Interval to_interval(const Rational& q);
IPoint to_interval(const Point3& p);
Interval to_interval(const Integer& z);

}  // namespace minksum
