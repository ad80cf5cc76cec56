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

using Interval = CGAL::Interval_nt<true>;
inline constexpr int kUncertain = 2;

struct IPoint {
  Interval x, y, z;
};

inline IPoint operator-(const IPoint& a, const IPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline IPoint operator+(const IPoint& a, const IPoint& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline IPoint operator-(const IPoint& a) { return {-a.x, -a.y, -a.z}; }
inline IPoint cross(const IPoint& a, const IPoint& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Interval dot(const IPoint& a, const IPoint& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// -1, 0, +1 when certain; kUncertain otherwise.
inline int sign_of(const Interval& i) {
  if (i.inf() > 0) return 1;
  if (i.sup() < 0) return -1;
  if (i.inf() == 0 && i.sup() == 0) return 0;
  return kUncertain;
}
inline int sign_det(const IPoint& a, const IPoint& b, const IPoint& c) { return sign_of(dot(a, cross(b, c))); }

// Smallest double interval around q (a point interval when q is a double).
Interval to_interval(const Rational& q);
IPoint to_interval(const Point3& p);
Interval to_interval(const Integer& z);

}  // namespace minksum
