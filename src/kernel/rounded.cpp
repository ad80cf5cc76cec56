// Predicates on rational points with cached faithful roundings
// (RoundedPoint3, <minksum/predicates.hpp> §7): the filters run on the
// cached doubles, the exact stages on the rationals.  Bounds: the rational
// filter of kernel/filter.hpp (orient3d), and the derivations next to
// plane_side_approx and nearest_plane_candidates in predicates_internal.hpp.
#include <CGAL/FPU.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <minksum/dot_difference.hpp>
#include <minksum/kernel.hpp>
#include <minksum/unit_plane.hpp>

#include "kernel/interval.hpp"
#include "kernel/predicates_internal.hpp"

namespace minksum {

namespace detail {

bool rounded_usable_slow(const RoundedPoint3& p) {
  for (int j = 0; j < 3; ++j) {
    const double x = j == 0 ? p.approx.x : j == 1 ? p.approx.y : p.approx.z;
    if (x == 0) {
      if (sgn(p.exact[j]) != 0) return false;
    } else if (!(std::fabs(x) >= DBL_MIN && std::fabs(x) <= DBL_MAX)) {
      return false;  // subnormal, infinite or NaN
    }
  }
  return true;
}

Approx plane_side_approx(const std::array<double, 4>& r, const RoundedPoint3& s) {
  Approx a;
  if (!rounded_usable(s)) return a;
  for (double c : r)  // integers: a zero rounding is an exact zero
    if (!(std::fabs(c) <= DBL_MAX)) return a;
  if (!plane_side_value(r, s.approx, a.value, a.bound)) return a;
  a.status = Approx::kOk;
  return a;
}

std::optional<int> plane_side_filter(const std::array<double, 4>& r, const RoundedPoint3& s) {
  return certified_sign(plane_side_approx(r, s));
}

int plane_side_exact(const Plane& plane, const Point3& s) { return plane.side(s); }

namespace {
// The enclosure of a faithful rounding: one ulp either side.
FastInterval around(double x) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return FastInterval(std::nextafter(x, -inf), std::nextafter(x, inf));
}
// The enclosure of an exact coordinate from its rounding: exact when the
// rational is zero (a zero rounding of a non-zero rational is possible).
FastInterval around(double x, const Rational& exact) {
  return sgn(exact) == 0 ? FastInterval(0) : around(x);
}
}  // namespace

std::vector<std::size_t> nearest_plane_candidates(const std::array<double, 4>* rounded,
                                                  std::size_t n, const RoundedPoint3& s) {
  std::vector<FastInterval> d2(n);
  double best = std::numeric_limits<double>::infinity();
  {
    CGAL::Protect_FPU_rounding<true> upward;  // FastInterval needs it
    const FastInterval sx = around(s.approx.x, s.exact.x), sy = around(s.approx.y, s.exact.y),
                       sz = around(s.approx.z, s.exact.z);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& r = rounded[i];
      // Integers: a zero rounding is an exact zero.
      const FastInterval a = r[0] == 0 ? FastInterval(0) : around(r[0]);
      const FastInterval b = r[1] == 0 ? FastInterval(0) : around(r[1]);
      const FastInterval c = r[2] == 0 ? FastInterval(0) : around(r[2]);
      const FastInterval d = r[3] == 0 ? FastInterval(0) : around(r[3]);
      const FastInterval gap = d - ((a * sx + b * sy) + c * sz);
      const FastInterval norm2 = (CGAL::square(a) + CGAL::square(b)) + CGAL::square(c);
      d2[i] = CGAL::square(gap) / norm2;  // contains (d − n·s)² / |n|²
      best = std::min(best, d2[i].sup());
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < n; ++i)
    if (!(d2[i].inf() > best)) out.push_back(i);  // NaN bounds stay candidates
  return out;
}

}  // namespace detail

int plane_side(const Plane& plane, const std::array<double, 4>& rounded, const RoundedPoint3& s) {
  const detail::Approx a = detail::plane_side_approx(rounded, s);
  if (a.status == detail::Approx::kOk) {  // certified_sign of a filter without a dynamic step
    if (a.value > a.bound) return 1;
    if (a.value < -a.bound) return -1;
  }
  return detail::plane_side_exact(plane, s.exact);
}

std::size_t nearest_plane(const Plane* const* planes, const std::array<double, 4>* rounded,
                          std::size_t n, const RoundedPoint3& s) {
  return detail::nearest_plane_among(planes, detail::nearest_plane_candidates(rounded, n, s), s);
}

int dot_difference_sign(const RoundedPoint3& u, const RoundedPoint3& p, const RoundedPoint3& q) {
  if (const auto s = dot_difference_filter(u, p, q)) return *s;
  static const Point3 origin(Rational(0), Rational(0), Rational(0));
  static const Vec3d origin_approx{0, 0, 0};
  return dot_sign(RoundedPoint3{origin, origin_approx}, u, p, q);
}

}  // namespace minksum
