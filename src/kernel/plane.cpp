#include "kernel/plane.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <utility>

namespace minksum {

// The sign of a·x + b·y + c·z − d times the positive dx·dy·dz (x = nx/dx,
// …), no rational normalisation, grouped so that the products stay small:
//   (a·x + b·y + c·z − d)·dx·dy·dz
//     = (a·nx·dy + b·ny·dx)·dz + (c·nz − d·dz)·(dx·dy),
// nine integer products (expanding every term takes eleven, three of them
// by dx·dy·dz-sized factors).
int Plane::side(const Point3& p) const {
  mpz_srcptr nx = p.x.get_num_mpz_t(), ny = p.y.get_num_mpz_t(), nz = p.z.get_num_mpz_t();
  mpz_srcptr dx = p.x.get_den_mpz_t(), dy = p.y.get_den_mpz_t(), dz = p.z.get_den_mpz_t();
  Integer acc, t, u;
  mpz_mul(t.get_mpz_t(), a.get_mpz_t(), nx);
  mpz_mul(acc.get_mpz_t(), t.get_mpz_t(), dy);  // a·nx·dy
  mpz_mul(t.get_mpz_t(), b.get_mpz_t(), ny);
  mpz_addmul(acc.get_mpz_t(), t.get_mpz_t(), dx);  // + b·ny·dx
  mpz_mul(acc.get_mpz_t(), acc.get_mpz_t(), dz);  // (a·nx·dy + b·ny·dx)·dz
  mpz_mul(t.get_mpz_t(), c.get_mpz_t(), nz);
  mpz_submul(t.get_mpz_t(), d.get_mpz_t(), dz);  // c·nz − d·dz
  mpz_mul(u.get_mpz_t(), dx, dy);
  mpz_addmul(acc.get_mpz_t(), t.get_mpz_t(), u.get_mpz_t());
  return sgn(acc);
}

bool operator<(const Plane& p, const Plane& q) {
  if (int c = cmp(p.a, q.a)) return c < 0;
  if (int c = cmp(p.b, q.b)) return c < 0;
  if (int c = cmp(p.c, q.c)) return c < 0;
  return cmp(p.d, q.d) < 0;
}


namespace {
void make_primitive(Plane& pl) {
  Integer g = 0;
  for (Integer* x : {&pl.a, &pl.b, &pl.c, &pl.d}) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), x->get_mpz_t());
  if (g != 1 && g != 0)
    for (Integer* x : {&pl.a, &pl.b, &pl.c, &pl.d}) mpz_divexact(x->get_mpz_t(), x->get_mpz_t(), g.get_mpz_t());
}
}  // namespace

Plane canonical_plane(const Point3& n, const Point3& p) {
  Rational d = dot(n, p);
  Integer l = 1;
  for (const Rational* q : std::initializer_list<const Rational*>{&n.x, &n.y, &n.z, &d})
    mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), q->get_den_mpz_t());
  Plane pl;
  Integer* out[4] = {&pl.a, &pl.b, &pl.c, &pl.d};
  const Rational* in[4] = {&n.x, &n.y, &n.z, &d};
  for (int i = 0; i < 4; ++i) {
    Integer t;
    mpz_divexact(t.get_mpz_t(), l.get_mpz_t(), in[i]->get_den_mpz_t());
    *out[i] = in[i]->get_num() * t;
  }
  make_primitive(pl);
  return pl;
}

ScaledPoint scaled_point(const Point3& p) {
  ScaledPoint s;
  s.den = p.x.get_den();
  mpz_lcm(s.den.get_mpz_t(), s.den.get_mpz_t(), p.y.get_den_mpz_t());
  mpz_lcm(s.den.get_mpz_t(), s.den.get_mpz_t(), p.z.get_den_mpz_t());
  for (int j = 0; j < 3; ++j) {
    mpz_divexact(s.num[j].get_mpz_t(), s.den.get_mpz_t(), p[j].get_den_mpz_t());
    s.num[j] *= p[j].get_num();
  }
  return s;
}

void scaled_difference(const ScaledPoint& p, const ScaledPoint& q, Integer out[3]) {
  Integer g = 0;
  for (int j = 0; j < 3; ++j) {
    mpz_mul(out[j].get_mpz_t(), q.num[j].get_mpz_t(), p.den.get_mpz_t());
    mpz_submul(out[j].get_mpz_t(), p.num[j].get_mpz_t(), q.den.get_mpz_t());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), out[j].get_mpz_t());
  }
  if (g != 1 && g != 0)
    for (int j = 0; j < 3; ++j) mpz_divexact(out[j].get_mpz_t(), out[j].get_mpz_t(), g.get_mpz_t());
}

// n . (p + q) = (n . p.num q.den + n . q.num p.den) / (p.den q.den), so the
// plane n (p.den q.den) . x = n . p.num q.den + n . q.num p.den is the
// plane with normal a positive multiple of n through p + q.
Plane canonical_plane_through_sum(const Integer n[3], const ScaledPoint& p, const ScaledPoint& q) {
  Plane pl;
  Integer dd, s, t;
  mpz_mul(dd.get_mpz_t(), p.den.get_mpz_t(), q.den.get_mpz_t());
  mpz_mul(pl.a.get_mpz_t(), n[0].get_mpz_t(), dd.get_mpz_t());
  mpz_mul(pl.b.get_mpz_t(), n[1].get_mpz_t(), dd.get_mpz_t());
  mpz_mul(pl.c.get_mpz_t(), n[2].get_mpz_t(), dd.get_mpz_t());
  for (const auto& [x, other] : {std::pair<const ScaledPoint*, const ScaledPoint*>{&p, &q}, {&q, &p}}) {
    mpz_mul(t.get_mpz_t(), n[0].get_mpz_t(), x->num[0].get_mpz_t());
    mpz_addmul(t.get_mpz_t(), n[1].get_mpz_t(), x->num[1].get_mpz_t());
    mpz_addmul(t.get_mpz_t(), n[2].get_mpz_t(), x->num[2].get_mpz_t());
    mpz_addmul(s.get_mpz_t(), t.get_mpz_t(), other->den.get_mpz_t());
  }
  mpz_swap(pl.d.get_mpz_t(), s.get_mpz_t());
  make_primitive(pl);
  return pl;
}

double truncated_ratio(const Integer& X, const Integer& W) {
  if (sgn(X) == 0) return 0.0;
  const long s = 56 + long(mpz_sizeinbase(W.get_mpz_t(), 2)) - long(mpz_sizeinbase(X.get_mpz_t(), 2));
  // q = floor(|X| 2^s / W); for s < 0, floor(floor(|X| / 2^-s) / W), the
  // same integer (nested floors of divisions by positive integers).  The
  // scratch numbers are the thread's own, kept between calls.
  thread_local Integer num, q;
  mpz_abs(num.get_mpz_t(), X.get_mpz_t());
  if (s >= 0) mpz_mul_2exp(num.get_mpz_t(), num.get_mpz_t(), mp_bitcnt_t(s));
  else mpz_fdiv_q_2exp(num.get_mpz_t(), num.get_mpz_t(), mp_bitcnt_t(-s));
  mpz_tdiv_q(q.get_mpz_t(), num.get_mpz_t(), W.get_mpz_t());
  const double r = std::ldexp(mpz_get_d(q.get_mpz_t()), int(std::clamp<long>(-s, -100000, 100000)));
  return sgn(X) < 0 ? -r : r;
}

bool plane_filter_doubles(const Integer& a, const Integer& b, const Integer& c, const Integer& d, double out[4]) {
  const Integer* v[4] = {&a, &b, &c, &d};
  std::size_t bits = 0;
  for (const Integer* x : v)
    if (sgn(*x) != 0) bits = std::max(bits, mpz_sizeinbase(x->get_mpz_t(), 2));
  const long k = bits >= 480 ? long(bits) - 470 : 0;
  bool usable = true;
  for (int i = 0; i < 4; ++i) usable = scaled_filter_double(*v[i], k, out[i]) && usable;
  return usable;
}

bool scaled_filter_double(const Integer& x, long k, double& out) {
  if (sgn(x) == 0) {
    out = 0.0;
    return true;
  }
  long e = 0;
  const double m = mpz_get_d_2exp(&e, x.get_mpz_t());
  // |m 2^(e - k)| in [2^(e - k - 1), 2^(e - k)): usable when e - k - 1 >= -480
  // and e - k <= 480 (plane_filter_doubles' choice of k keeps e - k <= 470).
  if (e - k - 1 < -480 || e - k > 480) {
    out = 0.0;
    return false;
  }
  out = std::ldexp(m, int(e - k));
  return true;
}

ScaledIntegers::ScaledIntegers(const double* values, std::size_t n) {
  // Every nonzero double is M * 2^E with an odd or even integer |M| < 2^53;
  // the smallest E over all values is the common exponent.
  exponent = INT_MAX;
  for (std::size_t i = 0; i < n; ++i) {
    if (values[i] == 0) continue;
    int ex;
    std::frexp(values[i], &ex);
    exponent = std::min(exponent, ex - 53);
  }
  if (exponent == INT_MAX) exponent = 0;
  value.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = values[i];
    if (x == 0) continue;
    int ex;
    const double f = std::frexp(x, &ex);
    mpz_set_si(value[i].get_mpz_t(), static_cast<long>(std::ldexp(f, 53)));
    mpz_mul_2exp(value[i].get_mpz_t(), value[i].get_mpz_t(), mp_bitcnt_t(ex - 53 - exponent));
  }
}

Rational ScaledIntegers::unscale(const Integer& v, int degree) const {
  Rational r(v);
  const long e = long(degree) * exponent;
  if (e >= 0) mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(e));
  else mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(-e));
  return r;
}

Plane canonical_plane_of_dyadic_triangle(const Vec3d hi[3], const Vec3d lo[3]) {
  double raw[18];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      raw[3 * i + k] = hi[i][k];
      raw[9 + 3 * i + k] = lo ? lo[i][k] : 0.0;
    }
  // X = the exact coordinates times 2^-emin: integers.
  ScaledIntegers s(raw, lo ? 18 : 9);
  Integer X[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      X[i][k] = s.value[3 * i + k];
      if (lo) X[i][k] += s.value[9 + 3 * i + k];
    }
  const int emin = s.exponent;
  Integer u[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = X[1][k] - X[0][k];
    w[k] = X[2][k] - X[0][k];
  }
  Plane pl;
  pl.a = u[1] * w[2] - u[2] * w[1];
  pl.b = u[2] * w[0] - u[0] * w[2];
  pl.c = u[0] * w[1] - u[1] * w[0];
  pl.d = pl.a * X[0][0] + pl.b * X[0][1] + pl.c * X[0][2];
  // True normal = n * 2^(2 emin), true offset = d * 2^(3 emin): scale by 2^(-2 emin).
  if (emin >= 0) {
    mpz_mul_2exp(pl.d.get_mpz_t(), pl.d.get_mpz_t(), mp_bitcnt_t(emin));
  } else {
    for (Integer* x : {&pl.a, &pl.b, &pl.c}) mpz_mul_2exp(x->get_mpz_t(), x->get_mpz_t(), mp_bitcnt_t(-emin));
  }
  make_primitive(pl);
  return pl;
}

}  // namespace minksum
