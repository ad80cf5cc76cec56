// The exact stage of the predicates (kernel/exact.hpp): group vectors
// scaled to integers, the shapes evaluated with mpz.
#include "kernel/exact.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <climits>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace minksum::detail {

struct Workspace {
  mpz_t g[4][3];  // group vectors
  mpz_t c[3][3];  // cross products
  mpz_t s, t, l;  // scalars
  Workspace() {
    for (auto& v : g)
      for (auto& x : v) mpz_init(x);
    for (auto& v : c)
      for (auto& x : v) mpz_init(x);
    mpz_init(s);
    mpz_init(t);
    mpz_init(l);
  }
  ~Workspace() {
    for (auto& v : g)
      for (auto& x : v) mpz_clear(x);
    for (auto& v : c)
      for (auto& x : v) mpz_clear(x);
    mpz_clear(s);
    mpz_clear(t);
    mpz_clear(l);
  }
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;
};

namespace {

Workspace& workspace() {
  thread_local Workspace ws;
  return ws;
}

inline bool finite(const Vec3d& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// x = m · 2^e with m odd (or x = 0, e = INT_MAX), read from the bits.
struct Dyadic {
  std::int64_t m;
  int e;
};
inline Dyadic decompose(double x) {
  assert(std::isfinite(x));
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  const int biased = int((bits >> 52) & 0x7ff);
  std::uint64_t mant = bits & ((std::uint64_t(1) << 52) - 1);
  int e = -1074;  // subnormal: x = mant · 2^-1074
  if (biased != 0) {
    mant |= std::uint64_t(1) << 52;
    e = biased - 1075;
  } else if (mant == 0) {
    return {0, INT_MAX};
  }
  const int tz = std::countr_zero(mant);
  const std::int64_t m = std::int64_t(mant >> tz);
  return {(bits >> 63) ? -m : m, e + tz};
}
inline void set_shifted(mpz_t out, const Dyadic& d, int base) {
  mpz_set_si(out, long(d.m));
  if (d.m != 0) mpz_mul_2exp(out, out, mp_bitcnt_t(d.e - base));
}

#if GMP_LIMB_BITS == 64 && defined(__SIZEOF_INT128__)
// out = v, for |v| < 2^127.
inline void set_int128(mpz_t out, __int128 v) {
  const unsigned __int128 a = v < 0 ? -static_cast<unsigned __int128>(v) : v;
  const std::uint64_t lo = std::uint64_t(a), hi = std::uint64_t(a >> 64);
  if (hi == 0) {
    mpz_set_ui(out, lo);
  } else {
    mp_limb_t* limbs = mpz_limbs_write(out, 2);
    limbs[0] = lo;
    limbs[1] = hi;
    mpz_limbs_finish(out, 2);
  }
  if (v < 0) mpz_neg(out, out);
}
#endif

// out = (a − b) · 2^-base, where a, b are dyadics with exponents ≥ base.
inline void set_diff(mpz_t out, const Dyadic& a, const Dyadic& b, int base, mpz_t tmp) {
#if GMP_LIMB_BITS == 64 && defined(__SIZEOF_INT128__)
  // Shifts up to 70 bits keep both terms below 2^123: 128-bit arithmetic.
  const int sa = a.m ? a.e - base : 0, sb = b.m ? b.e - base : 0;
  if (sa <= 70 && sb <= 70) {
    set_int128(out, static_cast<__int128>(a.m) * (static_cast<__int128>(1) << sa) -
                        static_cast<__int128>(b.m) * (static_cast<__int128>(1) << sb));
    return;
  }
#endif
  set_shifted(out, a, base);
  set_shifted(tmp, b, base);
  mpz_sub(out, out, tmp);
}

// out = (p − q) · 2^-E, E the smallest exponent among the six coordinates.
void load_diff(mpz_t* out, const Vec3d& p, const Vec3d& q, mpz_t tmp) {
  const Dyadic c[6] = {decompose(p.x), decompose(p.y), decompose(p.z),
                       decompose(q.x), decompose(q.y), decompose(q.z)};
  int base = INT_MAX;
  for (const auto& d : c) base = std::min(base, d.e);
  for (int i = 0; i < 3; ++i) {
    if (base == INT_MAX)
      mpz_set_ui(out[i], 0);
    else
      set_diff(out[i], c[i], c[i + 3], base, tmp);
  }
}
// out = d · 2^-E.
void load_vec(mpz_t* out, const Vec3d& d) {
  const Dyadic c[3] = {decompose(d.x), decompose(d.y), decompose(d.z)};
  const int base = std::min(c[0].e, std::min(c[1].e, c[2].e));
  for (int i = 0; i < 3; ++i) {
    if (base == INT_MAX)
      mpz_set_ui(out[i], 0);
    else
      set_shifted(out[i], c[i], base);
  }
}
// out = (p − q) · L, L the lcm of the six denominators (or 1).
void load_diff(mpz_t* out, const Point3& p, const Point3& q, Workspace& w) {
  bool integral = true;
  for (int i = 0; i < 3; ++i)
    integral = integral && mpz_cmp_ui(p[i].get_den_mpz_t(), 1) == 0 &&
               mpz_cmp_ui(q[i].get_den_mpz_t(), 1) == 0;
  if (integral) {
    for (int i = 0; i < 3; ++i) mpz_sub(out[i], p[i].get_num_mpz_t(), q[i].get_num_mpz_t());
    return;
  }
  mpz_set_ui(w.l, 1);
  for (int i = 0; i < 3; ++i) {
    mpz_lcm(w.l, w.l, p[i].get_den_mpz_t());
    mpz_lcm(w.l, w.l, q[i].get_den_mpz_t());
  }
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(w.t, w.l, p[i].get_den_mpz_t());
    mpz_mul(out[i], w.t, p[i].get_num_mpz_t());
    mpz_divexact(w.t, w.l, q[i].get_den_mpz_t());
    mpz_submul(out[i], w.t, q[i].get_num_mpz_t());
  }
}
// out = d · L.
void load_vec(mpz_t* out, const Point3& d, Workspace& w) {
  mpz_set_ui(w.l, 1);
  for (int i = 0; i < 3; ++i) mpz_lcm(w.l, w.l, d[i].get_den_mpz_t());
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(w.t, w.l, d[i].get_den_mpz_t());
    mpz_mul(out[i], w.t, d[i].get_num_mpz_t());
  }
}

// out = a × b (out distinct from a and b).
void icross(mpz_t* out, mpz_t* a, mpz_t* b) {
  mpz_mul(out[0], a[1], b[2]);
  mpz_submul(out[0], a[2], b[1]);
  mpz_mul(out[1], a[2], b[0]);
  mpz_submul(out[1], a[0], b[2]);
  mpz_mul(out[2], a[0], b[1]);
  mpz_submul(out[2], a[1], b[0]);
}
int sign_idot(mpz_t* a, mpz_t* b, mpz_t s) {
  mpz_mul(s, a[0], b[0]);
  mpz_addmul(s, a[1], b[1]);
  mpz_addmul(s, a[2], b[2]);
  return mpz_sgn(s);
}
bool is_zero(mpz_t* a) { return mpz_sgn(a[0]) == 0 && mpz_sgn(a[1]) == 0 && mpz_sgn(a[2]) == 0; }

template <class Pt>
Workspace& load_groups(const std::array<const Pt*, 2>* groups, std::size_t k) {
  Workspace& w = workspace();
  for (std::size_t i = 0; i < k; ++i) {
    const Pt* p = groups[i][0];
    const Pt* q = groups[i][1];
    if constexpr (std::is_same_v<Pt, Vec3d>) {
      assert(finite(*p) && (!q || finite(*q)));
      if (q)
        load_diff(w.g[i], *p, *q, w.t);
      else
        load_vec(w.g[i], *p);
    } else {
      if (q)
        load_diff(w.g[i], *p, *q, w);
      else
        load_vec(w.g[i], *p, w);
    }
  }
  return w;
}

}  // namespace

Workspace& load(const std::array<const Vec3d*, 2>* groups, std::size_t k) {
  return load_groups(groups, k);
}
Workspace& load(const std::array<const Point3*, 2>* groups, std::size_t k) {
  return load_groups(groups, k);
}

// The exact shapes on loaded groups.
int exact_det3(Workspace& w) {
  icross(w.c[0], w.g[1], w.g[2]);
  return sign_idot(w.g[0], w.c[0], w.s);
}
int exact_dcc(Workspace& w) {
  icross(w.c[0], w.g[0], w.g[1]);
  icross(w.c[1], w.g[2], w.g[3]);
  return sign_idot(w.c[0], w.c[1], w.s);
}
// n1 = c[0], n2 = c[1], n1 × n2 = c[2].
bool exact_parallel(Workspace& w) {
  icross(w.c[0], w.g[0], w.g[1]);
  icross(w.c[1], w.g[2], w.g[3]);
  icross(w.c[2], w.c[0], w.c[1]);
  return is_zero(w.c[2]);
}
bool exact_same_direction(Workspace& w) {
  return exact_parallel(w) && sign_idot(w.c[0], w.c[1], w.s) > 0;
}
int exact_dot(Workspace& w) { return sign_idot(w.g[0], w.g[1], w.s); }


}  // namespace minksum::detail
