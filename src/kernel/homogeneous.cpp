// Homogeneous integer points and the side of a plane through three of them
// (kernel/homogeneous.hpp has the filter's argument).
#include "kernel/homogeneous.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace minksum::detail {

namespace {

// An interval enclosing z · 2^-k, for |z| < 2^k (so the result lies in
// [-1, 1]).  mpz_get_d_2exp gives m with 0.5 <= |m| < 1 truncated towards
// zero, z = (m + δ) 2^e with δ of m's sign and |δ| < 2^-53; m ± 2^-53 is a
// double (m's last place), and the scaling by 2^(e - k) is exact unless the
// result would fall below 2^-1000, in which case [-2^-1000, 2^-1000]
// encloses it (|z 2^-k| < 2^(e - k)).
FastInterval scaled(const Integer& z, long k) {
  if (sgn(z) == 0) return FastInterval(0);
  long e = 0;
  const double m = mpz_get_d_2exp(&e, z.get_mpz_t());
  if (e - k < -1000) {
    const double tiny = std::ldexp(1.0, -1000);
    return FastInterval(-tiny, tiny);
  }
  const double ulp = std::ldexp(1.0, -53);
  const double lo = m > 0 ? m : m - ulp, hi = m > 0 ? m + ulp : m;
  return FastInterval(std::ldexp(lo, int(e - k)), std::ldexp(hi, int(e - k)));
}

template <class T>
T det3(const T& a0, const T& a1, const T& a2, const T& b0, const T& b1, const T& b2, const T& c0, const T& c1,
       const T& c2) {
  return a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0);
}

// P = (M_0, −M_1, M_2, −M_3) of the rows a, b, c (homogeneous.hpp).
template <class T>
std::array<T, 4> plane_of(const std::array<T, 4>& a, const std::array<T, 4>& b, const std::array<T, 4>& c) {
  return {det3(a[1], a[2], a[3], b[1], b[2], b[3], c[1], c[2], c[3]),
          -det3(a[0], a[2], a[3], b[0], b[2], b[3], c[0], c[2], c[3]),
          det3(a[0], a[1], a[3], b[0], b[1], b[3], c[0], c[1], c[3]),
          -det3(a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2])};
}

template <class T>
T dot4(const std::array<T, 4>& p, const std::array<T, 4>& x) {
  return p[0] * x[0] + p[1] * x[1] + p[2] * x[2] + p[3] * x[3];
}

}  // namespace

HomogeneousPoint homogeneous_point(Integer x, Integer y, Integer z, Integer w) {
  if (sgn(w) <= 0) throw std::invalid_argument("homogeneous_point: w must be positive");
  HomogeneousPoint p{{std::move(x), std::move(y), std::move(z), std::move(w)}, {}};
  std::size_t bits = 0;
  for (const Integer& v : p.c) bits = std::max(bits, mpz_sizeinbase(v.get_mpz_t(), 2));
  for (int i = 0; i < 4; ++i) p.s[i] = scaled(p.c[i], long(bits));
  return p;
}

HomogeneousPlane homogeneous_plane(const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c) {
  return HomogeneousPlane{plane_of(a.s, b.s, c.s), nullptr};
}

int side_filter(const HomogeneousPlane& h, const HomogeneousPoint& x) { return sign_of(dot4(h.s, x.s)); }

int side(const HomogeneousPlane& h, const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c,
         const HomogeneousPoint& x) {
  const int s = side_filter(h, x);
  if (s != kUncertain) return s;
  if (!h.exact) h.exact = std::make_unique<std::array<Integer, 4>>(plane_of(a.c, b.c, c.c));
  return sgn(Integer(dot4(*h.exact, x.c)));
}

int side_exact(const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c,
               const HomogeneousPoint& x) {
  return sgn(Integer(dot4(plane_of(a.c, b.c, c.c), x.c)));
}

}  // namespace minksum::detail
