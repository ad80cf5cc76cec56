#include "kernel/plane.hpp"

#include <climits>
#include <cmath>
#include <initializer_list>

namespace minksum {

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

Plane canonical_plane_of_double_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  // Every double is M * 2^E with an integer |M| < 2^53.
  const Vec3d* v[3] = {&a, &b, &c};
  long long m[3][3];
  int e[3][3];
  int emin = INT_MAX;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double x = (*v[i])[k];
      if (x == 0) {
        m[i][k] = 0;
        e[i][k] = INT_MAX;
        continue;
      }
      int ex;
      double f = std::frexp(x, &ex);
      m[i][k] = static_cast<long long>(std::ldexp(f, 53));
      e[i][k] = ex - 53;
      if (e[i][k] < emin) emin = e[i][k];
    }
  // X = M * 2^(E - emin): integers; the true coordinates are X * 2^emin.
  Integer X[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      if (m[i][k] == 0) continue;
      mpz_set_si(X[i][k].get_mpz_t(), m[i][k]);
      mpz_mul_2exp(X[i][k].get_mpz_t(), X[i][k].get_mpz_t(), mp_bitcnt_t(e[i][k] - emin));
    }
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
