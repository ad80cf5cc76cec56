// Exact signs on placed points: interval filter, then rationals
// (placed_predicates.hpp gives the argument).
#include "kernel/interval.hpp"

#include <minksum/error.hpp>
#include <minksum/placed_predicates.hpp>

#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace minksum {
namespace {

thread_local PlacedPredicateCounts g_counts;

// Every function below evaluates in FastInterval under one
// CGAL::Protect_FPU_rounding<true> guard (upward rounding for the whole
// evaluation, the caller's mode restored on return).
FastInterval iv(const Bounds& b) { return FastInterval(b.lo, b.hi); }
FastIPoint iv(const PointBounds& b) { return {iv(b.x), iv(b.y), iv(b.z)}; }

// A x + t (or A x) in intervals.
FastIPoint apply(const PlacedMap& m, const FastIPoint& x, bool translate) {
  const auto& a = m.bounds_a();
  FastIPoint r{iv(a[0]) * x.x + iv(a[1]) * x.y + iv(a[2]) * x.z, iv(a[3]) * x.x + iv(a[4]) * x.y + iv(a[5]) * x.z,
               iv(a[6]) * x.x + iv(a[7]) * x.y + iv(a[8]) * x.z};
  if (translate) r = r + iv(m.bounds_t());
  return r;
}

// A double as m 2^e, m an integer of at most 53 bits (0 for zero).
struct Dyadic {
  std::int64_t m = 0;
  int e = 0;
};
Dyadic dyadic(double x) {
  if (x == 0) return {};
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased != 0 && biased != 0x7ff) {  // normal: (2^52 + fraction) 2^(biased − 1075), as frexp gives it
    const auto m = static_cast<std::int64_t>((bits & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1) << 52));
    return {bits >> 63 ? -m : m, biased - 1075};
  }
  int e = 0;
  const double f = std::frexp(x, &e);  // x = f 2^e, 1/2 ≤ |f| < 1
  return {static_cast<std::int64_t>(std::ldexp(f, 53)), e - 53};
}

bool exact_double(const PointBounds& b) { return b.x.lo == b.x.hi && b.y.lo == b.y.hi && b.z.lo == b.z.hi; }

int exact_sign(const Rational& q) {
  ++g_counts.exact;
  return sgn(q);
}

Rational det3(const Point3& a, const Point3& b, const Point3& c) { return dot(a, cross(b, c)); }

// Stage 1's range (placed_predicates.hpp): zero, or |x| in [2^-240, 2^240).
constexpr double kFastMin = 0x1p-240, kFastMax = 0x1p+240;
inline bool in_range(double x) {
  const double a = std::fabs(x);
  return a == 0 || (a >= kFastMin && a < kFastMax);
}

}  // namespace

Bounds rational_bounds(const Rational& q) {
  const Interval i = to_interval(q);
  return {i.inf(), i.sup()};
}

PointBounds point_bounds(const Point3& p) {
  PointBounds b{rational_bounds(p.x), rational_bounds(p.y), rational_bounds(p.z)};
  b.doubles = b.x.lo == b.x.hi && b.y.lo == b.y.hi && b.z.lo == b.z.hi && in_range(b.x.lo) && in_range(b.y.lo) &&
              in_range(b.z.lo);
  return b;
}

// The identity: what PlacedMap({1, 0, 0, 0, 1, 0, 0, 0, 1}, Vec3d{0, 0, 0})
// makes, without the determinant's check (a vector of N poses starts as N
// of these).
PlacedMap::PlacedMap() : approx_a_{1, 0, 0, 0, 1, 0, 0, 0, 1}, approx_t_{0, 0, 0}, fast_(true) {
  for (int k = 0; k < 9; ++k) bounds_a_[k] = {approx_a_[k], approx_a_[k]};
  bounds_t_ = {{0, 0}, {0, 0}, {0, 0}};
}

PlacedMap::PlacedMap(const std::array<double, 9>& a, const Vec3d& t) {
  set_double_t(t);
  set_double_a(a);
  check_determinant();
  set_fast();
}

PlacedMap::PlacedMap(const std::array<double, 9>& a, const Point3& t) {
  set_double_a(a);
  set_t(t);
  check_determinant();
  set_fast();
}

PlacedMap::PlacedMap(const std::array<std::array<Rational, 3>, 3>& a, const Point3& t) {
  set_rational_a(a);
  set_t(t);
  check_determinant();
  set_fast();
}

PlacedMap PlacedMap::rotation(const std::array<Integer, 4>& q, const Point3& t) {
  PlacedMap m;
  m.set_rotation(q);
  m.set_t(t);  // det = 1: the matrix of a unit quaternion is a rotation
  m.set_fast();
  return m;
}

PlacedMap PlacedMap::rotation64(const std::array<std::int64_t, 4>& q, const Vec3d& t) {
  PlacedMap m;
  m.set_double_t(t);
  if (!m.set_small_rotation(q)) {
    std::array<Integer, 4> big;
    for (int k = 0; k < 4; ++k) mpz_set_si(big[k].get_mpz_t(), static_cast<long>(q[k]));
    m.set_rotation_gmp(big);
  }
  m.set_fast();
  return m;
}

PlacedMap PlacedMap::rotation(const std::array<Integer, 4>& q, const Vec3d& t) {
  PlacedMap m;
  m.set_double_t(t);
  m.set_rotation(q);
  m.set_fast();
  return m;
}

namespace {
// Entry k (row-major) of the rotation matrix of the quaternion (a, b, c, d),
// components of at most 2^25 in magnitude, in lowest terms num / den (den >
// 0): e_k / n in machine integers (|e_k|, n <= 2^52), reduced by their gcd.
// e_0..e_8 (row-major) and n, not reduced.
void small_rotation_fractions(const std::array<std::int64_t, 4>& q, std::int64_t (&e)[9], std::int64_t& n) {
  const std::int64_t a = q[0], b = q[1], c = q[2], d = q[3];
  const std::int64_t aa = a * a, bb = b * b, cc = c * c, dd = d * d;
  n = aa + bb + cc + dd;
  e[0] = aa + bb - cc - dd, e[1] = 2 * (b * c - a * d), e[2] = 2 * (b * d + a * c);
  e[3] = 2 * (b * c + a * d), e[4] = aa - bb + cc - dd, e[5] = 2 * (c * d - a * b);
  e[6] = 2 * (b * d - a * c), e[7] = 2 * (c * d + a * b), e[8] = aa - bb - cc + dd;
}

// The doubles either side of x, finite, normal and not the largest: what
// std::nextafter gives towards −∞ and +∞ (consecutive doubles of one sign
// have consecutive bit patterns).
Bounds neighbours(double x) {
  const std::uint64_t b = std::bit_cast<std::uint64_t>(x);
  const double away = std::bit_cast<double>(b + 1), toward = std::bit_cast<double>(b - 1);
  return x > 0 ? Bounds{toward, away} : Bounds{away, toward};
}

void small_rotation_entry(const std::array<std::int64_t, 4>& q, int k, std::int64_t& num, std::int64_t& den) {
  std::int64_t e[9], n;
  small_rotation_fractions(q, e, n);
  const std::int64_t g = std::gcd(e[k], n);
  num = e[k] / g, den = n / g;
}
}  // namespace

void PlacedMap::set_rotation(const std::array<Integer, 4>& q) {
  constexpr long kSmall = 1L << 25;
  bool small = true;
  for (const Integer& x : q) small = small && mpz_cmpabs_ui(x.get_mpz_t(), kSmall) <= 0;
  if (small && set_small_rotation({q[0].get_si(), q[1].get_si(), q[2].get_si(), q[3].get_si()})) return;
  set_rotation_gmp(q);
}

// Components of at most 2^25 in magnitude, rounding to nearest: each
// entry's nearest double is one division e_k / n (both exact doubles:
// correctly rounded, ties to even, the value of to_double), exact when
// d·n − e_k = 0 (one fma, exact in sign); the exact entries are not stored
// but made from the components by a() when an exact stage asks (no GMP
// number is made here).  False (nothing set) when that does not apply.
bool PlacedMap::set_small_rotation(const std::array<std::int64_t, 4>& q) {
  constexpr std::int64_t kSmall = std::int64_t(1) << 25;
  for (std::int64_t x : q)
    if (x < -kSmall || x > kSmall) return false;
  if (std::fegetround() != FE_TONEAREST) return false;
  {
    quaternion_ = q;
    if (!quaternion_[0] && !quaternion_[1] && !quaternion_[2] && !quaternion_[3])
      throw UsageError("a rotation needs a non-zero quaternion, got 0,0,0,0");
    bool doubles = true;
    std::int64_t e[9], n;  // e_k / n, not reduced: the same quotient, so the same division and sign
    small_rotation_fractions(quaternion_, e, n);
    for (int k = 0; k < 9; ++k) {
      const double x = double(e[k]) / double(n);  // |x| <= 1, and >= 2^-52 unless 0
      approx_a_[k] = x;
      if (std::fma(x, double(n), -double(e[k])) == 0) {
        bounds_a_[k] = {x, x};
      } else {
        bounds_a_[k] = neighbours(x);
        doubles = false;
      }
    }
    exact_a_.reset();
    small_rotation_ = !doubles;
  }
  return true;
}

void PlacedMap::set_rotation_gmp(const std::array<Integer, 4>& q) {
  const Integer &a = q[0], &b = q[1], &c = q[2], &d = q[3];
  const Integer aa = a * a, bb = b * b, cc = c * c, dd = d * d;
  const Integer n = aa + bb + cc + dd;
  if (sgn(n) == 0) throw UsageError("a rotation needs a non-zero quaternion, got 0,0,0,0");
  const Integer e[3][3] = {
      {aa + bb - cc - dd, 2 * (b * c - a * d), 2 * (b * d + a * c)},
      {2 * (b * c + a * d), aa - bb + cc - dd, 2 * (c * d - a * b)},
      {2 * (b * d - a * c), 2 * (c * d + a * b), aa - bb - cc + dd},
  };
  std::array<std::array<Rational, 3>, 3> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[i][j] = Rational(e[i][j], n);
      r[i][j].canonicalize();
    }
  set_rational_a(r);
}

void PlacedMap::set_double_a(const std::array<double, 9>& a) {
  for (int k = 0; k < 9; ++k) {
    if (!std::isfinite(a[k])) throw UsageError("a placement's matrix must have finite entries");
    approx_a_[k] = a[k];
    bounds_a_[k] = {a[k], a[k]};
  }
  exact_a_.reset();
  small_rotation_ = false;
}

void PlacedMap::set_rational_a(const std::array<std::array<Rational, 3>, 3>& a) {
  bool doubles = true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      approx_a_[3 * i + j] = to_double(a[i][j]);
      bounds_a_[3 * i + j] = rational_bounds(a[i][j]);
      doubles = doubles && bounds_a_[3 * i + j].lo == bounds_a_[3 * i + j].hi;
    }
  if (doubles) exact_a_.reset();
  else exact_a_ = std::make_shared<const std::array<std::array<Rational, 3>, 3>>(a);
  small_rotation_ = false;
}

void PlacedMap::set_double_t(const Vec3d& t) {
  for (double x : {t.x, t.y, t.z})
    if (!std::isfinite(x)) throw UsageError("a placement's translation must be finite");
  approx_t_ = t;
  bounds_t_ = {{t.x, t.x}, {t.y, t.y}, {t.z, t.z}};
  exact_t_.reset();
}

void PlacedMap::set_t(const Point3& t) {
  approx_t_ = to_double(t);
  bounds_t_ = point_bounds(t);
  if (is_double(t)) exact_t_.reset();
  else exact_t_ = std::make_shared<const Point3>(t);
}

void PlacedMap::set_fast() {
  fast_ = doubles();
  for (double x : approx_a_) fast_ = fast_ && in_range(x);
  for (double x : {approx_t_.x, approx_t_.y, approx_t_.z}) fast_ = fast_ && in_range(x);
}

void PlacedMap::check_determinant() const {
  // Stage 1, doubles (a matrix of doubles, every entry zero or of magnitude
  // in [2^-240, 2^240): no product of three leaves the normal range).  With
  // u = 2^-52 (one operation in any rounding mode), each 2×2 minor
  // fl(fl(x y) − fl(z w)) is within γ_2 (|x y| + |z w|) of the exact one,
  // its product with an entry adds one rounding, the two additions two more:
  // |d̂ − det| ≤ γ_5 P with P the permanent Σ |a_0i| (|a_1j a_2k| + |a_1k a_2j|)
  // (γ_5 = 5u / (1 − 5u)).  P̂, the same expression on the absolute values,
  // takes at most five roundings of non-negative doubles: P̂ ≥ (1 − u)^5 P.
  // So d̂ > 2^-48 P̂ = 16 u P̂ ≥ 16 u (1 − u)^5 P > γ_5 P proves det > 0; a
  // rotation matrix of doubles (det ≈ 1, P ≤ 6) passes at once, without
  // switching the rounding mode.  Otherwise the stages below decide.
  if (!exact_a_ && !small_rotation_) {
    const auto& a = approx_a_;
    bool range = true;
    for (double x : a) range = range && in_range(x);
    if (range) {
      const double d = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                       a[2] * (a[3] * a[7] - a[4] * a[6]);
      const auto m = [](double x, double y, double z, double w) {
        return std::fabs(x) * std::fabs(y) + std::fabs(z) * std::fabs(w);
      };
      const double perm = std::fabs(a[0]) * m(a[4], a[8], a[5], a[7]) + std::fabs(a[1]) * m(a[3], a[8], a[5], a[6]) +
                          std::fabs(a[2]) * m(a[3], a[7], a[4], a[6]);
      if (d > 0x1p-48 * perm) return;
    }
  }
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const auto& b = bounds_a_;
    const FastIPoint r0{iv(b[0]), iv(b[1]), iv(b[2])}, r1{iv(b[3]), iv(b[4]), iv(b[5])},
        r2{iv(b[6]), iv(b[7]), iv(b[8])};
    const FastInterval det = dot(r0, cross(r1, r2));
    if (det.inf() > 0) return;
    if (det.sup() <= 0) throw UsageError("a placement's matrix must have a positive determinant (a rotation)");
  }
  const Point3 r0(a(0, 0), a(0, 1), a(0, 2)), r1(a(1, 0), a(1, 1), a(1, 2)), r2(a(2, 0), a(2, 1), a(2, 2));
  if (sgn(det3(r0, r1, r2)) <= 0)
    throw UsageError("a placement's matrix must have a positive determinant (a rotation)");
}

Rational PlacedMap::a(int row, int col) const {
  if (exact_a_) return (*exact_a_)[row][col];
  if (small_rotation_) {
    std::int64_t num, den;
    small_rotation_entry(quaternion_, 3 * row + col, num, den);
    Rational r;
    mpq_set_si(r.get_mpq_t(), long(num), static_cast<unsigned long>(den));
    return r;
  }
  return Rational(approx_a_[3 * row + col]);
}

Point3 PlacedMap::t() const {
  if (exact_t_) return *exact_t_;
  return Point3(approx_t_.x, approx_t_.y, approx_t_.z);
}

Point3 PlacedMap::apply_linear(const Point3& p) const {
  Point3 r;
  for (int i = 0; i < 3; ++i) r[i] = a(i, 0) * p.x + a(i, 1) * p.y + a(i, 2) * p.z;
  return r;
}

Point3 PlacedMap::apply(const Point3& p) const { return apply_linear(p) + t(); }

PulledDirection::PulledDirection(const PlacedMap& m, const Vec3d& n) : m_(&m), n_(n) {
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
    throw UsageError("a direction must have finite coordinates");
  fast_ = m.filter_ready() && in_range(n.x) && in_range(n.y) && in_range(n.z);
  if (fast_) {
    const auto& a = m.approx_a();
    for (int c = 0; c < 3; ++c) {
      uf_[c] = (a[c] * n.x + a[3 + c] * n.y) + a[6 + c] * n.z;
      um_[c] = (std::fabs(a[c]) * std::fabs(n.x) + std::fabs(a[3 + c]) * std::fabs(n.y)) +
               std::fabs(a[6 + c]) * std::fabs(n.z);
    }
    return;  // the enclosure u_ is made on first need (stage 2)
  }
  make_enclosure();
}

void PulledDirection::make_enclosure() const {
  enclosure_ = true;
  const PlacedMap& m = *m_;
  const Vec3d& n = n_;
  CGAL::Protect_FPU_rounding<true> upward;
  const auto& a = m.bounds_a();
  const FastInterval nx(n.x), ny(n.y), nz(n.z);
  for (int c = 0; c < 3; ++c) {
    const FastInterval u = iv(a[c]) * nx + iv(a[3 + c]) * ny + iv(a[6 + c]) * nz;
    u_[c] = {u.inf(), u.sup()};
  }
}

int PulledDirection::second_stage(const PointBounds& ab, const PointBounds& bb) const {
  static_assert(kOpen == kUncertain);
  if (!enclosure_) make_enclosure();
  CGAL::Protect_FPU_rounding<true> upward;
  const FastIPoint d = iv(bb) - iv(ab);
  const int s = sign_of(iv(u_[0]) * d.x + iv(u_[1]) * d.y + iv(u_[2]) * d.z);
  if (s != kUncertain) ++g_counts.filtered;
  return s;
}

int PulledDirection::difference_sign_later(const Point3& a, const PointBounds& ab, const Point3& b,
                                           const PointBounds& bb) const {
  if (const int s = second_stage(ab, bb); s != kOpen) return s;
  if (m_->linear_doubles() && exact_double(ab) && exact_double(bb)) return difference_sign_integers(ab, bb);
  if (!exact_) {
    Point3 u;
    const Point3 n(n_.x, n_.y, n_.z);
    for (int c = 0; c < 3; ++c) u[c] = m_->a(0, c) * n.x + m_->a(1, c) * n.y + m_->a(2, c) * n.z;
    exact_ = std::move(u);
  }
  return exact_sign(dot(*exact_, b - a));
}

// Stage 3 in integers (the top of placed_predicates.hpp): A's entries, n and
// the points doubles.  U_c 2^eu = Σ_r A_rc n_r and B_c 2^eb = b_c − a_c
// exactly, so S = 2^(eu + eb) Σ_c U_c B_c.
int PulledDirection::difference_sign_integers(const PointBounds& ab, const PointBounds& bb) const {
  const auto& a = m_->approx_a();
  const double n[3] = {n_.x, n_.y, n_.z};
  Dyadic da[9], dn[3];
  int eu = std::numeric_limits<int>::max();
  for (int r = 0; r < 3; ++r) dn[r] = dyadic(n[r]);
  for (int i = 0; i < 9; ++i) {
    da[i] = dyadic(a[i]);
    if (da[i].m != 0 && dn[i / 3].m != 0) eu = std::min(eu, da[i].e + dn[i / 3].e);
  }
  const double pa[3] = {ab.x.lo, ab.y.lo, ab.z.lo}, pb[3] = {bb.x.lo, bb.y.lo, bb.z.lo};
  Dyadic xa[3], xb[3];
  int eb = std::numeric_limits<int>::max();
  for (int c = 0; c < 3; ++c) {
    xa[c] = dyadic(pa[c]), xb[c] = dyadic(pb[c]);
    if (xa[c].m != 0) eb = std::min(eb, xa[c].e);
    if (xb[c].m != 0) eb = std::min(eb, xb[c].e);
  }
  ++g_counts.exact;
  if (eu == std::numeric_limits<int>::max() || eb == std::numeric_limits<int>::max()) return 0;  // u = 0 or b = a = 0
  // One thread's scratch integers: no allocation once they have grown.
  struct Scratch {
    mpz_t sum, u, d, t;
    Scratch() { mpz_init(sum), mpz_init(u), mpz_init(d), mpz_init(t); }
    ~Scratch() { mpz_clear(sum), mpz_clear(u), mpz_clear(d), mpz_clear(t); }
  };
  thread_local Scratch z;
  mpz_set_ui(z.sum, 0);
  for (int c = 0; c < 3; ++c) {
    mpz_set_ui(z.d, 0);  // B_c
    if (xb[c].m != 0) {
      mpz_set_si(z.t, static_cast<long>(xb[c].m));
      mpz_mul_2exp(z.d, z.t, static_cast<unsigned long>(xb[c].e - eb));
    }
    if (xa[c].m != 0) {
      mpz_set_si(z.t, static_cast<long>(xa[c].m));
      mpz_mul_2exp(z.t, z.t, static_cast<unsigned long>(xa[c].e - eb));
      mpz_sub(z.d, z.d, z.t);
    }
    if (mpz_sgn(z.d) == 0) continue;
    mpz_set_ui(z.u, 0);  // U_c
    for (int r = 0; r < 3; ++r) {
      const Dyadic &x = da[3 * r + c], &y = dn[r];
      if (x.m == 0 || y.m == 0) continue;
      mpz_set_si(z.t, static_cast<long>(x.m));
      mpz_mul_si(z.t, z.t, static_cast<long>(y.m));
      mpz_mul_2exp(z.t, z.t, static_cast<unsigned long>(x.e + y.e - eu));
      mpz_add(z.u, z.u, z.t);
    }
    mpz_addmul(z.sum, z.u, z.d);
  }
  return mpz_sgn(z.sum);
}

PulledNormalFilter::PulledNormalFilter(const PlacedMap& m, const Point3& n) {
  long top = std::numeric_limits<long>::min();
  for (int r = 0; r < 3; ++r) {
    if (sgn(n[r]) == 0) continue;
    // ⌊log2 |n_r|⌋ within one: from the bit lengths of numerator and denominator.
    const long e = long(mpz_sizeinbase(n[r].get_num_mpz_t(), 2)) - long(mpz_sizeinbase(n[r].get_den_mpz_t(), 2));
    top = std::max(top, e);
  }
  if (top == std::numeric_limits<long>::min()) return;  // N = 0
  std::array<Bounds, 3> nb;
  Rational x;
  for (int r = 0; r < 3; ++r) {
    // N_r 2^−top exactly, then its enclosure (|N_r 2^−top| < 2).
    if (top >= 0) mpq_div_2exp(x.get_mpq_t(), n[r].get_mpq_t(), static_cast<unsigned long>(top));
    else mpq_mul_2exp(x.get_mpq_t(), n[r].get_mpq_t(), static_cast<unsigned long>(-top));
    nb[r] = rational_bounds(x);
  }
  CGAL::Protect_FPU_rounding<true> upward;
  const auto& a = m.bounds_a();
  bool finite = true;
  for (int c = 0; c < 3; ++c) {
    const FastInterval u = iv(a[c]) * iv(nb[0]) + iv(a[3 + c]) * iv(nb[1]) + iv(a[6 + c]) * iv(nb[2]);
    u_[c] = {u.inf(), u.sup()};
    finite = finite && std::isfinite(u.inf()) && std::isfinite(u.sup());
  }
  usable_ = finite;
}

int PulledNormalFilter::difference_sign(const PointBounds& a, const PointBounds& b) const {
  if (!usable_) return kOpen;
  CGAL::Protect_FPU_rounding<true> upward;
  const FastIPoint d = iv(b) - iv(a);
  const int s = sign_of(iv(u_[0]) * d.x + iv(u_[1]) * d.y + iv(u_[2]) * d.z);
  if (s == kUncertain) return kOpen;
  ++g_counts.filtered;
  return s;
}

int placed_gap_sign(const Vec3d& n, const PlacedMap& mp, const Point3& p, const PointBounds& pb, const PlacedMap& mq,
                    const Point3& q, const PointBounds& qb) {
  const int f = placed_gap_filter(n, mp, pb, mq, qb);
  if (f != kGapOpen) return f;
  return exact_sign(dot(Point3(n.x, n.y, n.z), mq.apply(q) - mp.apply(p)));
}

int placed_gap_filter(const Vec3d& n, const PlacedMap& mp, const PointBounds& pb, const PlacedMap& mq,
                      const PointBounds& qb) {
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
    throw UsageError("a direction must have finite coordinates");
  if (mp.filter_ready() && mq.filter_ready() && in_range(n.x) && in_range(n.y) && in_range(n.z) && pb.doubles &&
      qb.doubles) {
    const auto &ap = mp.approx_a(), &aq = mq.approx_a();
    const Vec3d &tp = mp.approx_t(), &tq = mq.approx_t();
    const double P[3] = {pb.x.lo, pb.y.lo, pb.z.lo}, Q[3] = {qb.x.lo, qb.y.lo, qb.z.lo};
    const double T[2][3] = {{tp.x, tp.y, tp.z}, {tq.x, tq.y, tq.z}}, N[3] = {n.x, n.y, n.z};
    double g = 0, b = 0;
    for (int r = 0; r < 3; ++r) {
      const double x = ((aq[3 * r] * Q[0] + aq[3 * r + 1] * Q[1]) + aq[3 * r + 2] * Q[2]) + T[1][r];
      const double y = ((ap[3 * r] * P[0] + ap[3 * r + 1] * P[1]) + ap[3 * r + 2] * P[2]) + T[0][r];
      const double mx = ((std::fabs(aq[3 * r]) * std::fabs(Q[0]) + std::fabs(aq[3 * r + 1]) * std::fabs(Q[1])) +
                         std::fabs(aq[3 * r + 2]) * std::fabs(Q[2])) + std::fabs(T[1][r]);
      const double my = ((std::fabs(ap[3 * r]) * std::fabs(P[0]) + std::fabs(ap[3 * r + 1]) * std::fabs(P[1])) +
                         std::fabs(ap[3 * r + 2]) * std::fabs(P[2])) + std::fabs(T[0][r]);
      // Summed in the order of the analysis: ((t_0 + t_1) + t_2).
      g = r == 0 ? N[r] * (x - y) : g + N[r] * (x - y);
      b = r == 0 ? std::fabs(N[r]) * (mx + my) : b + std::fabs(N[r]) * (mx + my);
    }
    const double scaled = 0x1p+48 * g;
    if (scaled > b || scaled < -b || b == 0) {
      ++g_counts.filtered;
      return scaled > b ? 1 : (scaled < -b ? -1 : 0);
    }
  }
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastIPoint d = apply(mq, iv(qb), true) - apply(mp, iv(pb), true);
    const int s = sign_of(FastInterval(n.x) * d.x + FastInterval(n.y) * d.y + FastInterval(n.z) * d.z);
    if (s != kUncertain) {
      ++g_counts.filtered;
      return s;
    }
  }
  return kGapOpen;
}

namespace {
// The interval stage of placed_tetrahedron_holds_origin: the five signed
// volumes, orient3d(d0, d1, d2, d3) = det(d1 − d0, d2 − d0, d3 − d0) and the
// same with d_k the origin, on intervals; sig[k] kUncertain for those left
// open.  1 or 0 when they decide, kTetrahedronOpen otherwise.
int tetrahedron_intervals(const PlacedMap& mp, const PlacedMap& mq, const std::array<const PointBounds*, 4>& pb,
                          const std::array<const PointBounds*, 4>& qb, std::array<int, 5>& sig) {
  sig.fill(kUncertain);
  {
    CGAL::Protect_FPU_rounding<true> upward;
    std::array<FastIPoint, 4> d;
    for (int k = 0; k < 4; ++k) d[k] = apply(mp, iv(*pb[k]), true) - apply(mq, iv(*qb[k]), true);
    const auto volume = [&](const FastIPoint& a, const FastIPoint& b, const FastIPoint& c, const FastIPoint& e) {
      return sign_of(dot(b - a, cross(c - a, e - a)));
    };
    const FastIPoint o{FastInterval(0), FastInterval(0), FastInterval(0)};
    sig[0] = volume(d[0], d[1], d[2], d[3]);
    bool open = sig[0] == kUncertain, outside = sig[0] == 0;
    for (int k = 0; k < 4 && !outside; ++k) {
      std::array<FastIPoint, 4> e = d;
      e[k] = o;
      sig[k + 1] = volume(e[0], e[1], e[2], e[3]);
      open = open || sig[k + 1] == kUncertain;
      outside = sig[0] != kUncertain && sig[k + 1] != kUncertain && sig[k + 1] != sig[0];
    }
    if (outside || !open) {
      ++g_counts.filtered;
      return !outside;
    }
  }
  return kTetrahedronOpen;
}

// The exact stage, for the volumes sig leaves open.
bool tetrahedron_exact(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 4>& p,
                       const std::array<const PointBounds*, 4>& pb, const std::array<const Point3*, 4>& q,
                       const std::array<const PointBounds*, 4>& qb, const std::array<int, 5>& sig) {
  ++g_counts.exact;
  // The points K d_k = Z_p(p_k) − Z_q(q_k) of one PlacedFrame (integers when
  // the matrices and the points are doubles): the volumes are homogeneous of
  // degree 3, so K > 0 keeps their signs.
  bool pd = true, qd = true;
  int pe = std::numeric_limits<int>::max(), qe = pe;
  const auto scan = [](const PointBounds& b, bool& doubles, int& e) {
    for (const Bounds* c : {&b.x, &b.y, &b.z}) doubles = doubles && c->lo == c->hi, e = std::min(e, dyadic_exponent(c->lo));
  };
  for (int k = 0; k < 4; ++k) scan(*pb[k], pd, pe), scan(*qb[k], qd, qe);
  const PlacedFrame frame(mp, pd, pe, mq, qd, qe);
  std::array<Point3, 4> d;
  for (int k = 0; k < 4; ++k) d[k] = frame.p(*p[k], *pb[k]) - frame.q(*q[k], *qb[k]);
  const Point3 o(0, 0, 0);
  const auto volume = [&](int k) {  // k = 0: the tetrahedron; k > 0: d_{k−1} replaced by the origin
    if (sig[k] != kUncertain) return sig[k];
    std::array<Point3, 4> e = d;
    if (k > 0) e[k - 1] = o;
    return sgn(det3(e[1] - e[0], e[2] - e[0], e[3] - e[0]));
  };
  const int total = volume(0);
  if (total == 0) return false;
  for (int k = 1; k < 5; ++k)
    if (volume(k) != total) return false;
  return true;
}
}  // namespace

int placed_tetrahedron_filter(const PlacedMap& mp, const PlacedMap& mq, const std::array<const PointBounds*, 4>& pb,
                              const std::array<const PointBounds*, 4>& qb) {
  std::array<int, 5> sig;
  return tetrahedron_intervals(mp, mq, pb, qb, sig);
}

bool placed_tetrahedron_holds_origin(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 4>& p,
                                     const std::array<const PointBounds*, 4>& pb, const std::array<const Point3*, 4>& q,
                                     const std::array<const PointBounds*, 4>& qb) {
  std::array<int, 5> sig;
  const int f = tetrahedron_intervals(mp, mq, pb, qb, sig);
  if (f != kTetrahedronOpen) return f == 1;
  return tetrahedron_exact(mp, mq, p, pb, q, qb, sig);
}

struct PlacedSimplexPoint::Exact {
  // The placed points A_p p_j + t_p and A_q q_j + t_q over `scale` (a
  // power of two, integers, when the inputs are doubles; else 1).
  std::array<Point3, 3> pp, qp;
  Rational scale = 1;
  Rational g;
  std::array<Rational, 3> l;
  Point3 v;           // V = g v
  Rational vv;        // |v|² g: |d_0 × d_1|² (k = 2), (d_0·n)² (k = 3)
  mutable std::optional<Point3> up, uq;  // −A_pᵀ V, A_qᵀ V (climbs only)
};

namespace {
FastInterval iv_scaled(const FastInterval& s, const FastInterval& x) { return s * x; }
FastIPoint scaled(const FastInterval& s, const FastIPoint& p) {
  return {iv_scaled(s, p.x), iv_scaled(s, p.y), iv_scaled(s, p.z)};
}
Bounds to_bounds(const FastInterval& i) { return {i.inf(), i.sup()}; }
// Aᵀ x for the linear part of a placement, in intervals and exactly.
FastIPoint pull(const PlacedMap& m, const FastIPoint& x) {
  const auto& a = m.bounds_a();
  return {iv(a[0]) * x.x + iv(a[3]) * x.y + iv(a[6]) * x.z, iv(a[1]) * x.x + iv(a[4]) * x.y + iv(a[7]) * x.z,
          iv(a[2]) * x.x + iv(a[5]) * x.y + iv(a[8]) * x.z};
}
Point3 pull(const PlacedMap& m, const Point3& x) {
  Point3 u;
  for (int c = 0; c < 3; ++c) u[c] = m.a(0, c) * x.x + m.a(1, c) * x.y + m.a(2, c) * x.z;
  return u;
}
}  // namespace

namespace {


// The smallest exponent e of the non-zero terms m 2^e of coordinate r of
// A x + t (three products and t_r; A, t and x doubles), lowered into e0.
void lower_exponent(const PlacedMap& m, const PointBounds& x, int r, int& e0) {
  const auto& a = m.approx_a();
  const double t[3] = {m.approx_t().x, m.approx_t().y, m.approx_t().z};
  const double c[3] = {x.x.lo, x.y.lo, x.z.lo};
  for (int k = 0; k < 3; ++k) {
    const Dyadic u = dyadic(a[3 * r + k]), v = dyadic(c[k]);
    if (u.m != 0 && v.m != 0) e0 = std::min(e0, u.e + v.e);
  }
  const Dyadic w = dyadic(t[r]);
  if (w.m != 0) e0 = std::min(e0, w.e);
}

// The coordinate r of A x + t as an integer over 2^e0 (e0 at most the
// exponent of every non-zero term).
Integer placed_integer(const PlacedMap& m, const PointBounds& x, int r, int e0) {
  const auto& a = m.approx_a();
  const double t[3] = {m.approx_t().x, m.approx_t().y, m.approx_t().z};
  const double c[3] = {x.x.lo, x.y.lo, x.z.lo};
  Integer sum = 0, term;
  for (int k = 0; k < 3; ++k) {
    const Dyadic u = dyadic(a[3 * r + k]), v = dyadic(c[k]);
    if (u.m == 0 || v.m == 0) continue;
    term = Integer(static_cast<long>(u.m)) * Integer(static_cast<long>(v.m));
    sum += term << static_cast<unsigned long>(u.e + v.e - e0);
  }
  const Dyadic w = dyadic(t[r]);
  if (w.m != 0) sum += Integer(static_cast<long>(w.m)) << static_cast<unsigned long>(w.e - e0);
  return sum;
}

// sign u · (b − a) for a pulled direction u: on its enclosure first, then
// on the exact u that `exact_u` makes (the climbs of the certificates).
template <class ExactU>
int pulled_sign(const std::array<Bounds, 3>& u, const Point3& a, const PointBounds& ab, const Point3& b,
                const PointBounds& bb, const ExactU& exact_u) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastIPoint d = iv(bb) - iv(ab);
    const int s = sign_of(iv(u[0]) * d.x + iv(u[1]) * d.y + iv(u[2]) * d.z);
    if (s != kUncertain) {
      ++g_counts.filtered;
      return s;
    }
  }
  return exact_sign(dot(exact_u(), b - a));
}


// Whether the exact stage may take the integers below: both maps doubles
// and every point a double.
bool all_dyadic(const PlacedMap& mp, const PlacedMap& mq, int k, const std::array<const PointBounds*, 3>& pb,
                const std::array<const PointBounds*, 3>& qb) {
  bool d = mp.doubles() && mq.doubles();
  for (int j = 0; j < k && d; ++j) d = exact_double(*pb[j]) && exact_double(*qb[j]);
  return d;
}

// The placed points A_p p_j + t_p and A_q q_j + t_q (j < k) over the
// returned scale: with dyadic inputs, one exponent e0 below every term of
// every coordinate makes them integers over 2^e0 (every polynomial in them
// is then a polynomial in integers, and signs and ratios of homogeneous
// ones are free of the scale); otherwise the rationals, over 1.
Rational placed_points(const PlacedMap& mp, const PlacedMap& mq, int k, bool dyadic,
                       const std::array<const Point3*, 3>& p, const std::array<const PointBounds*, 3>& pb,
                       const std::array<const Point3*, 3>& q, const std::array<const PointBounds*, 3>& qb,
                       std::array<Point3, 3>& pp, std::array<Point3, 3>& qp) {
  if (!dyadic) {
    for (int j = 0; j < k; ++j) pp[j] = mp.apply(*p[j]), qp[j] = mq.apply(*q[j]);
    return Rational(1);
  }
  int e0 = std::numeric_limits<int>::max();
  for (int j = 0; j < k; ++j)
    for (int r = 0; r < 3; ++r) lower_exponent(mp, *pb[j], r, e0), lower_exponent(mq, *qb[j], r, e0);
  if (e0 == std::numeric_limits<int>::max()) e0 = 0;
  for (int j = 0; j < k; ++j)
    for (int r = 0; r < 3; ++r) {
      pp[j][r] = Rational(placed_integer(mp, *pb[j], r, e0));
      qp[j][r] = Rational(placed_integer(mq, *qb[j], r, e0));
    }
  const Integer one = 1;
  if (e0 >= 0) return Rational(one << static_cast<unsigned long>(e0));
  return Rational(one, one << static_cast<unsigned long>(-e0));
}

}  // namespace

PlacedSimplexPoint::PlacedSimplexPoint(const PlacedMap& mp, const PlacedMap& mq, int k,
                                       const std::array<const Point3*, 3>& p,
                                       const std::array<const PointBounds*, 3>& pb,
                                       const std::array<const Point3*, 3>& q,
                                       const std::array<const PointBounds*, 3>& qb)
    : mp_(&mp), mq_(&mq), k_(k), p_(p), q_(q), pb_(pb), qb_(qb) {
  if (k < 1 || k > 3) throw std::invalid_argument("PlacedSimplexPoint: k must be 1, 2 or 3");
  dyadic_ = all_dyadic(mp, mq, k, pb, qb);
  CGAL::Protect_FPU_rounding<true> upward;
  std::array<FastIPoint, 3> d;
  for (int j = 0; j < k; ++j) d[j] = apply(mp, iv(*pb[j]), true) - apply(mq, iv(*qb[j]), true);
  FastInterval g(1);
  std::array<FastInterval, 3> l{FastInterval(1), FastInterval(0), FastInterval(0)};
  FastIPoint V = d[0];
  if (k == 2) {
    const FastIPoint e = d[1] - d[0];
    g = dot(e, e);
    l[0] = dot(d[1], e), l[1] = -dot(d[0], e);
    V = scaled(l[0], d[0]) + scaled(l[1], d[1]);
  } else if (k == 3) {
    const FastIPoint n = cross(d[1] - d[0], d[2] - d[0]);
    g = dot(n, n);
    l[0] = dot(n, cross(d[1], d[2])), l[1] = dot(n, cross(d[2], d[0])), l[2] = dot(n, cross(d[0], d[1]));
    V = scaled(dot(d[0], n), n);
  }
  g_ = to_bounds(g);
  for (int j = 0; j < 3; ++j) l_[j] = to_bounds(l[j]);
  v_ = {to_bounds(V.x), to_bounds(V.y), to_bounds(V.z)};
  vv_ = g.inf() > 0 ? to_bounds(dot(V, V) / (g * g)) : Bounds{0, std::numeric_limits<double>::infinity()};
  const FastIPoint up = -pull(mp, V), uq = pull(mq, V);
  up_ = {to_bounds(up.x), to_bounds(up.y), to_bounds(up.z)};
  uq_ = {to_bounds(uq.x), to_bounds(uq.y), to_bounds(uq.z)};
}

PlacedSimplexPoint::~PlacedSimplexPoint() = default;


const PlacedSimplexPoint::Exact& PlacedSimplexPoint::exact() const {
  if (exact_) return *exact_;
  auto e = std::make_unique<Exact>();
  e->scale = placed_points(*mp_, *mq_, k_, dyadic_, p_, pb_, q_, qb_, e->pp, e->qp);
  std::array<Point3, 3> d;
  for (int j = 0; j < k_; ++j) d[j] = e->pp[j] - e->qp[j];
  e->g = 1;
  e->l = {Rational(1), Rational(0), Rational(0)};
  e->v = d[0];
  if (k_ == 2) {
    const Point3 ed = d[1] - d[0];
    e->g = dot(ed, ed);
    e->l[0] = dot(d[1], ed), e->l[1] = -dot(d[0], ed);
    e->v = e->l[0] * d[0] + e->l[1] * d[1];
    const Point3 c = cross(d[0], d[1]);  // |v| |e| = |d_0 × d_1| (the distance to a line)
    e->vv = dot(c, c);
  } else if (k_ == 3) {
    const Point3 n = cross(d[1] - d[0], d[2] - d[0]);
    e->g = dot(n, n);
    e->l[0] = dot(n, cross(d[1], d[2])), e->l[1] = dot(n, cross(d[2], d[0])), e->l[2] = dot(n, cross(d[0], d[1]));
    const Rational h = dot(d[0], n);  // |v| |n| = |d_0 · n| (the distance to a plane)
    e->v = h * n;
    e->vv = h * h;
  } else {
    e->vv = dot(d[0], d[0]);
  }
  exact_ = std::move(e);
  return *exact_;
}

bool PlacedSimplexPoint::independent() const {
  if (g_.lo > 0) {
    ++g_counts.filtered;
    return true;
  }
  if (g_.hi <= 0) {  // g ≥ 0 as a sum of squares: [.., ≤ 0] holds only 0
    ++g_counts.filtered;
    return false;
  }
  return exact_sign(exact().g) > 0;
}

int PlacedSimplexPoint::lambda_sign(int j) const {
  if (j < 0 || j >= k_) throw std::invalid_argument("PlacedSimplexPoint: no such point");
  const Bounds& b = l_[j];
  if (b.lo > 0 || b.hi < 0 || (b.lo == 0 && b.hi == 0)) {
    ++g_counts.filtered;
    return b.lo > 0 ? 1 : (b.hi < 0 ? -1 : 0);
  }
  return exact_sign(exact().l[j]);
}

bool PlacedSimplexPoint::nonzero() const {
  for (const Bounds& b : v_)
    if (b.lo > 0 || b.hi < 0) {
      ++g_counts.filtered;
      return true;
    }
  const Point3& v = exact().v;
  ++g_counts.exact;
  return sgn(v.x) != 0 || sgn(v.y) != 0 || sgn(v.z) != 0;
}

int PlacedSimplexPoint::climb_sign(bool on_p, const Point3& a, const PointBounds& ab, const Point3& b,
                                   const PointBounds& bb) const {
  return pulled_sign(on_p ? up_ : uq_, a, ab, b, bb, [&]() -> const Point3& {
    const Exact& e = exact();
    std::optional<Point3>& u = on_p ? e.up : e.uq;
    if (!u) u = on_p ? Point3(-pull(*mp_, e.v)) : pull(*mq_, e.v);
    return *u;
  });
}

int PlacedSimplexPoint::climb_sign_p(const Point3& a, const PointBounds& ab, const Point3& b,
                                     const PointBounds& bb) const {
  return climb_sign(true, a, ab, b, bb);
}
int PlacedSimplexPoint::climb_sign_q(const Point3& a, const PointBounds& ab, const Point3& b,
                                     const PointBounds& bb) const {
  return climb_sign(false, a, ab, b, bb);
}

Bounds PlacedSimplexPoint::squared_norm_bounds() const {
  if (g_.lo > 0) return vv_;
  return rational_bounds(squared_norm());
}

double PlacedSimplexPoint::lambda_approx(int j) const {
  if (j < 0 || j >= k_) throw std::invalid_argument("PlacedSimplexPoint: no such point");
  const double g = 0.5 * (g_.lo + g_.hi), l = 0.5 * (l_[j].lo + l_[j].hi);
  if (g > 0 && std::isfinite(g) && std::isfinite(l)) return l / g;
  return to_double(lambda(j));
}

Rational PlacedSimplexPoint::squared_norm() const {
  const Exact& e = exact();
  // |v|² has degree 2 in the points: the scale twice.
  return (k_ == 1 ? e.vv : Rational(e.vv / e.g)) * e.scale * e.scale;
}

std::pair<Point3, Point3> PlacedSimplexPoint::points() const {
  const Exact& e = exact();
  Point3 x(0, 0, 0), y(0, 0, 0);
  for (int j = 0; j < k_; ++j) {
    x = x + e.l[j] * e.pp[j];
    y = y + e.l[j] * e.qp[j];
  }
  const Rational f = e.scale / e.g;
  return {f * x, f * y};
}

Rational PlacedSimplexPoint::lambda(int j) const {
  if (j < 0 || j >= k_) throw std::invalid_argument("PlacedSimplexPoint: no such point");
  const Exact& e = exact();
  return e.l[j] / e.g;
}

struct PlacedTriangle::Exact {
  Point3 n;
  std::array<Point3, 3> d;  // the points over `scale`
  Rational h, nn;  // of the points over `scale`: the squared distance is h² / nn · scale²
  Rational scale, scale2;
  mutable std::optional<Point3> up, uq;  // A_pᵀ n, −A_qᵀ n (climbs only)
};

PlacedTriangle::PlacedTriangle(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 3>& p,
                               const std::array<const PointBounds*, 3>& pb, const std::array<const Point3*, 3>& q,
                               const std::array<const PointBounds*, 3>& qb)
    : mp_(&mp), mq_(&mq), p_(p), q_(q), pb_(pb), qb_(qb) {
  std::array<PointBounds, 3> d;
  for (int j = 0; j < 3; ++j) d[j] = placed_difference_bounds(mp, *pb[j], mq, *qb[j]);
  set_from(d);
}

PlacedTriangle::PlacedTriangle(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 3>& p,
                               const std::array<const PointBounds*, 3>& pb, const std::array<const Point3*, 3>& q,
                               const std::array<const PointBounds*, 3>& qb,
                               const std::array<const PointBounds*, 3>& d)
    : mp_(&mp), mq_(&mq), p_(p), q_(q), pb_(pb), qb_(qb) {
  set_from({*d[0], *d[1], *d[2]});
}

PointBounds placed_difference_bounds(const PlacedMap& mp, const PointBounds& pb, const PlacedMap& mq,
                                     const PointBounds& qb) {
  CGAL::Protect_FPU_rounding<true> upward;
  const FastIPoint d = apply(mp, iv(pb), true) - apply(mq, iv(qb), true);
  return {to_bounds(d.x), to_bounds(d.y), to_bounds(d.z)};
}

// n, h and |n|² on the corners' enclosures (each an interval operation
// rounded outward on enclosures: enclosures again).
void PlacedTriangle::set_from(const std::array<PointBounds, 3>& db) {
  CGAL::Protect_FPU_rounding<true> upward;
  const std::array<FastIPoint, 3> d{iv(db[0]), iv(db[1]), iv(db[2])};
  const FastIPoint n = cross(d[1] - d[0], d[2] - d[0]);
  const FastInterval h = dot(n, d[0]), nn = dot(n, n);
  h_ = to_bounds(h), nn_ = to_bounds(nn);
  for (int j = 0; j < 3; ++j) d_[j] = {db[j].x, db[j].y, db[j].z};
  n_ = {to_bounds(n.x), to_bounds(n.y), to_bounds(n.z)};
}

static_assert(kUndecidedSign == kUncertain);

void placed_surface_signs(const std::vector<PointBounds>& d, const std::vector<std::array<int, 3>>& tris, int f,
                          std::vector<std::array<int, 2>>& signs) {
  CGAL::Protect_FPU_rounding<true> upward;
  const auto plane = [&](const std::array<int, 3>& t) {
    const std::array<FastIPoint, 3> c{iv(d[t[0]]), iv(d[t[1]]), iv(d[t[2]])};
    const FastIPoint n = cross(c[1] - c[0], c[2] - c[0]);
    return std::pair{dot(n, c[0]), dot(n, n)};
  };
  const auto [hf, nf] = plane(tris[f]);
  const FastInterval hf2 = hf * hf;
  signs.resize(tris.size());
  for (std::size_t k = 0; k < tris.size(); ++k) {
    const auto [h, nn] = plane(tris[k]);
    signs[k] = {sign_of(h), int(k) == f ? 0 : sign_of(h * h * nf - hf2 * nn)};
    g_counts.filtered += (signs[k][0] != kUncertain) + (signs[k][1] != kUncertain);
  }
}

PlacedTriangle::~PlacedTriangle() = default;
PlacedTriangle::PlacedTriangle(PlacedTriangle&&) noexcept = default;

const PlacedTriangle::Exact& PlacedTriangle::exact() const {
  if (exact_) return *exact_;
  auto e = std::make_unique<Exact>();
  std::array<Point3, 3> pp, qp, d;
  const Rational scale = placed_points(*mp_, *mq_, 3, all_dyadic(*mp_, *mq_, 3, pb_, qb_), p_, pb_, q_, qb_, pp, qp);
  e->scale = scale;
  e->scale2 = scale * scale;
  for (int j = 0; j < 3; ++j) d[j] = pp[j] - qp[j];
  e->d = d;
  e->n = cross(d[1] - d[0], d[2] - d[0]);
  e->h = dot(e->n, d[0]);
  e->nn = dot(e->n, e->n);
  exact_ = std::move(e);
  return *exact_;
}

int PlacedTriangle::offset_sign() const {
  if (h_.lo > 0 || h_.hi < 0 || (h_.lo == 0 && h_.hi == 0)) {
    ++g_counts.filtered;
    return h_.lo > 0 ? 1 : (h_.hi < 0 ? -1 : 0);
  }
  return exact_sign(exact().h);
}

int compare_distance(const PlacedTriangle& a, const PlacedTriangle& b) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastInterval ha = iv(a.h_), hb = iv(b.h_);
    const int s = sign_of(ha * ha * iv(b.nn_) - hb * hb * iv(a.nn_));
    if (s != kUncertain) {
      ++g_counts.filtered;
      return s;
    }
  }
  const PlacedTriangle::Exact &ea = a.exact(), &eb = b.exact();
  return exact_sign(ea.h * ea.h * eb.nn * ea.scale2 - eb.h * eb.h * ea.nn * eb.scale2);
}

int PlacedTriangle::climb_sign(bool on_p, const Point3& a, const PointBounds& ab, const Point3& b,
                               const PointBounds& bb) const {
  if (!pulled_) {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastIPoint n{iv(n_[0]), iv(n_[1]), iv(n_[2])};
    const FastIPoint up = pull(*mp_, n), uq = -pull(*mq_, n);
    up_ = {to_bounds(up.x), to_bounds(up.y), to_bounds(up.z)};
    uq_ = {to_bounds(uq.x), to_bounds(uq.y), to_bounds(uq.z)};
    pulled_ = true;
  }
  return pulled_sign(on_p ? up_ : uq_, a, ab, b, bb, [&]() -> const Point3& {
    const Exact& e = exact();
    std::optional<Point3>& u = on_p ? e.up : e.uq;
    if (!u) u = on_p ? pull(*mp_, e.n) : Point3(-pull(*mq_, e.n));
    return *u;
  });
}

int PlacedTriangle::climb_sign_p(const Point3& a, const PointBounds& ab, const Point3& b,
                                 const PointBounds& bb) const {
  return climb_sign(true, a, ab, b, bb);
}
int PlacedTriangle::climb_sign_q(const Point3& a, const PointBounds& ab, const Point3& b,
                                 const PointBounds& bb) const {
  return climb_sign(false, a, ab, b, bb);
}

Bounds PlacedTriangle::squared_distance_bounds() const {
  if (nn_.lo > 0) {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastInterval h = iv(h_);
    return to_bounds(h * h / iv(nn_));
  }
  return rational_bounds(squared_distance());
}

Rational PlacedTriangle::squared_distance() const {
  const Exact& e = exact();
  if (sgn(e.nn) == 0) throw std::invalid_argument("PlacedTriangle: the points are collinear");
  return e.h * e.h / e.nn * e.scale2;
}

Point3 PlacedTriangle::nearest_point() const {
  const Exact& e = exact();
  if (sgn(e.nn) == 0) throw std::invalid_argument("PlacedTriangle: the points are collinear");
  // (h / nn) n has degree 1 in the points: the scale once.
  return Rational(e.h / e.nn * e.scale) * e.n;
}

int PlacedTriangle::edge_sign(int i, const Point3& u, const PointBounds& ub) const {
  if (i < 0 || i > 2) throw std::invalid_argument("PlacedTriangle: no such edge");
  const int j = (i + 1) % 3;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const auto pt = [](const std::array<Bounds, 3>& b) { return FastIPoint{iv(b[0]), iv(b[1]), iv(b[2])}; };
    const int s = sign_det(pt(d_[i]), pt(d_[j]), iv(ub));
    if (s != kUncertain) {
      ++g_counts.filtered;
      return s;
    }
  }
  const Exact& e = exact();
  return exact_sign(det3(e.d[i], e.d[j], u));
}

int PlacedTriangle::direction_sign(const Point3& u, const PointBounds& ub) const {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastIPoint x = iv(ub);
    const int s = sign_of(iv(n_[0]) * x.x + iv(n_[1]) * x.y + iv(n_[2]) * x.z);
    if (s != kUncertain) {
      ++g_counts.filtered;
      return s;
    }
  }
  return exact_sign(dot(exact().n, u));
}

Rational PlacedTriangle::ray_parameter(const Point3& u) const {
  const Exact& e = exact();
  const Rational nu = dot(e.n, u);
  if (sgn(nu) == 0) throw std::invalid_argument("PlacedTriangle: the ray is parallel to the plane");
  // h has degree 3 in the points, n · u degree 2: the scale once.
  return e.h / nu * e.scale;
}

Bounds PlacedTriangle::ray_parameter_bounds(const PointBounds& ub) const {
  CGAL::Protect_FPU_rounding<true> upward;
  const FastIPoint x = iv(ub);
  const FastInterval nu = iv(n_[0]) * x.x + iv(n_[1]) * x.y + iv(n_[2]) * x.z;
  if (nu.inf() > 0 || nu.sup() < 0) return to_bounds(iv(h_) / nu);
  return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
}

Vec3d PlacedTriangle::unit_normal() const {
  const double x = 0.5 * (n_[0].lo + n_[0].hi), y = 0.5 * (n_[1].lo + n_[1].hi), z = 0.5 * (n_[2].lo + n_[2].hi);
  const double l = std::sqrt(x * x + y * y + z * z);
  if (l > 0 && std::isfinite(l)) return {x / l, y / l, z / l};
  return to_double(exact().n);
}

int dyadic_exponent(double x) { return x == 0 ? std::numeric_limits<int>::max() : dyadic(x).e; }

PlacedFrame::PlacedFrame(const PlacedMap& mp, bool p_doubles, int p_exponent, const PlacedMap& mq, bool q_doubles,
                         int q_exponent)
    : mp_(&mp), mq_(&mq) {
  const Point3 dt = mq.t() - mp.t();
  integers_ = p_doubles && q_doubles && mp.linear_doubles() && mq.linear_doubles();
  if (!integers_) {
    tq_ = dt;
    return;
  }
  // E = min(e_A,p + e_x,p, e_A,q + e_x,q, 0); a body with no non-zero
  // coordinate (or a zero matrix, which det A > 0 excludes) bounds nothing.
  e_ = 0;
  const PlacedMap* maps[2] = {&mp, &mq};
  const int pe[2] = {p_exponent, q_exponent};
  for (int w = 0; w < 2; ++w) {
    int ea = std::numeric_limits<int>::max();
    for (int i = 0; i < 9; ++i) {
      const Dyadic d = dyadic(maps[w]->approx_a()[i]);
      am_[w][i] = d.m, ae_[w][i] = d.e;
      if (d.m != 0) ea = std::min(ea, d.e);
    }
    if (ea != std::numeric_limits<int>::max() && pe[w] != std::numeric_limits<int>::max())
      e_ = std::min(e_, ea + pe[w]);
  }
  for (int r = 0; r < 3; ++r) mpz_lcm(d_.get_mpz_t(), d_.get_mpz_t(), dt[r].get_den_mpz_t());
  const Integer k = d_ << static_cast<unsigned long>(-e_);
  k_ = Rational(k);
  for (int r = 0; r < 3; ++r) {
    Integer t = dt[r].get_num() * (d_ / dt[r].get_den());
    tq_[r] = Rational(Integer(t << static_cast<unsigned long>(-e_)));
  }
}

// D 2^−E A x for the map `which` (integers mode): each product m_a m_x
// 2^(e_a + e_x) shifted by e_a + e_x − E ≥ 0 (the caller's bound), summed
// in GMP integers in place (no temporaries), plus K (t_q − t_p) for Q.
Point3 PlacedFrame::linear(int which, const PointBounds& xb) const {
  const double c[3] = {xb.x.lo, xb.y.lo, xb.z.lo};
  Dyadic v[3];
  for (int k = 0; k < 3; ++k) v[k] = dyadic(c[k]);
  Point3 r;
  mpz_t term;
  mpz_init(term);
  for (int i = 0; i < 3; ++i) {
    mpz_ptr sum = mpq_numref(r[i].get_mpq_t());  // the denominator stays 1
    mpz_set_ui(sum, 0);
    for (int k = 0; k < 3; ++k) {
      const std::int64_t m = am_[which][3 * i + k];
      if (m == 0 || v[k].m == 0) continue;
      mpz_set_si(term, static_cast<long>(m));
      mpz_mul_si(term, term, static_cast<long>(v[k].m));
      mpz_mul_2exp(term, term, static_cast<mp_bitcnt_t>(ae_[which][3 * i + k] + v[k].e - e_));
      mpz_add(sum, sum, term);
    }
    if (d_ != 1) mpz_mul(sum, sum, d_.get_mpz_t());
    if (which == 1) mpz_add(sum, sum, mpq_numref(tq_[i].get_mpq_t()));  // an integer in this mode
  }
  mpz_clear(term);
  return r;
}

Point3 PlacedFrame::p(const Point3& x, const PointBounds& xb) const {
  if (!integers_) return mp_->apply_linear(x);
  return linear(0, xb);
}

Point3 PlacedFrame::q(const Point3& y, const PointBounds& yb) const {
  if (!integers_) return mq_->apply_linear(y) + tq_;
  return linear(1, yb);
}

Point3 PlacedFrame::placed(const Point3& z) const {
  if (!integers_) return z + mp_->t();
  return Rational(1) / k_ * z + mp_->t();
}

PlacedPredicateCounts placed_predicate_counts() {
  return g_counts;
}

}  // namespace minksum
