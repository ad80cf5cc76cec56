#include "kernel/interval.hpp"

#include <cmath>
#include <limits>

namespace minksum {

Interval to_interval(const Rational& q) {
  double d = to_double(q);  // correctly rounded: q lies within one ulp of d
  if (std::isfinite(d) && Rational(d) == q) return Interval(d);
  constexpr double inf = std::numeric_limits<double>::infinity();
  return Interval(std::nextafter(d, -inf), std::nextafter(d, inf));
}

IPoint to_interval(const Point3& p) { return {to_interval(p.x), to_interval(p.y), to_interval(p.z)}; }

Interval to_interval(const Integer& z) { return to_interval(Rational(z)); }

}  // namespace minksum
