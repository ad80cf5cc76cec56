// Exact numbers: point algebra, correctly rounded conversion to double,
// parsing and printing.
#include <cfenv>
#include <minksum/kernel.hpp>

#include <algorithm>
#include <bit>
#include <cctype>
#include <climits>
#include <cstdint>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <functional>

namespace minksum {

Point3 operator+(const Point3& a, const Point3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point3 operator-(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point3 operator-(const Point3& a) { return {-a.x, -a.y, -a.z}; }
Point3 operator*(const Rational& s, const Point3& a) { return {s * a.x, s * a.y, s * a.z}; }
Rational dot(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool is_zero(const Point3& a) { return sgn(a.x) == 0 && sgn(a.y) == 0 && sgn(a.z) == 0; }

// Round n/d (d > 0) to the nearest double, ties to even, with gradual
// underflow and overflow to infinity.  mpq_get_d truncates, so it is not used.
namespace {
// Fast path: q = m / 2^k with |m| < 2^53 and k ≤ 1022 is exactly the normal
// double m * 2^-k.  Returns false otherwise (a subnormal result would be
// rounded by ldexp in the current rounding mode, not to nearest).
bool dyadic_short(const Rational& q, double& out) {
  const mpz_srcptr den = q.get_den_mpz_t();
  const mpz_srcptr num = q.get_num_mpz_t();
  std::size_t dbits = mpz_sizeinbase(den, 2);
  if (mpz_scan1(den, 0) != dbits - 1) return false;  // not a power of two
  if (dbits - 1 > 1022) return false;
  if (mpz_sizeinbase(num, 2) > 53) return false;
  out = std::ldexp(mpz_get_d(num), -int(dbits - 1));
  return true;
}
}  // namespace

namespace {
// Nearest double of |n| / d for the usual magnitudes, with one division of
// machine-free scratch integers: the quotient is taken with 55 or 56 bits,
// then rounded to 53 with its low bits and the remainder as sticky bit.
// Returns false (nothing decided) near or beyond the ends of the double
// range, where the general code below handles subnormals and overflow.
// Scratch integers, one set per thread, freed when the thread ends.
struct Scratch {
  mpz_t t, m, r;
  Scratch() { mpz_inits(t, m, r, nullptr); }
  ~Scratch() { mpz_clears(t, m, r, nullptr); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// m, r = the quotient and remainder of |n| 2^k / d (d > 0), in scratch.
void scaled_quotient(mpz_srcptr n, mpz_srcptr d, long k, mpz_ptr t, mpz_ptr m, mpz_ptr r) {
  if (k >= 0) {
    mpz_mul_2exp(t, n, mp_bitcnt_t(k));
    mpz_abs(t, t);
    mpz_tdiv_qr(m, r, t, d);
  } else {
    mpz_mul_2exp(t, d, mp_bitcnt_t(-k));
    mpz_abs(m, n);
    mpz_tdiv_qr(m, r, m, t);
  }
}

bool to_double_fast(mpz_srcptr n, mpz_srcptr d, double& out) {
  Scratch& s = scratch();
  mpz_ptr t = s.t, m = s.m, r = s.r;
  const long bn = long(mpz_sizeinbase(n, 2)), bd = long(mpz_sizeinbase(d, 2));
  const long e0 = bn - bd;                // floor(log2(|n|/d)) is e0 or e0 - 1
  if (e0 > 1000 || e0 < -1000) return false;
  const long k = 55 - e0;                 // |n| 2^k / d lies in [2^54, 2^56)
  scaled_quotient(n, d, k, t, m, r);
  const int bm = int(mpz_sizeinbase(m, 2));  // 55 or 56
  const std::uint64_t q = mpz_get_ui(m);
  const int drop = bm - 53;                  // 2 or 3 low bits to round away
  std::uint64_t kept = q >> drop;
  const std::uint64_t rest = q & ((std::uint64_t(1) << drop) - 1), half = std::uint64_t(1) << (drop - 1);
  if (rest > half || (rest == half && (mpz_sgn(r) != 0 || (kept & 1)))) ++kept;  // kept <= 2^53
  out = std::ldexp(double(kept), int(drop - k));  // exact: normal range, at most 54 bits
  return true;
}
}  // namespace

namespace {
// Nearest binary floating-point value of n / d (n, d > 0) with `precision`
// significant bits, exponents up to `max_exponent` and quanta down to
// 2^min_quantum (subnormals), ties to even; +inf beyond the range.  The
// result is exact in a double for the formats used (double, float).
double round_to_binary(const Integer& n, const Integer& d, int precision, long min_quantum, long max_exponent) {
  // e = floor(log2(n/d)), from bit lengths, corrected by one comparison.
  long e = long(mpz_sizeinbase(n.get_mpz_t(), 2)) - long(mpz_sizeinbase(d.get_mpz_t(), 2));
  {
    // Is n/d >= 2^e ?  i.e. n >= d * 2^e
    Integer lhs = n, rhs = d;
    if (e >= 0) rhs <<= e; else lhs <<= -e;
    if (lhs < rhs) --e;
  }
  if (e > max_exponent) return HUGE_VAL;
  // Quantum: the value of the last mantissa bit; 2^(e - precision + 1) for
  // normal numbers, 2^min_quantum below.
  const long quantum = std::max(e - precision + 1, min_quantum);
  // m = round(n / (d * 2^quantum))
  Integer num = n, den = d;
  if (quantum >= 0) den <<= quantum; else num <<= -quantum;
  Integer m, r;
  mpz_fdiv_qr(m.get_mpz_t(), r.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
  Integer twice_r = r << 1;
  int c = cmp(twice_r, den);
  if (c > 0 || (c == 0 && mpz_odd_p(m.get_mpz_t()))) m += 1;
  // m <= 2^precision; ldexp is exact (a carry to 2^precision past the
  // largest exponent gives +inf, as it must).
  return std::ldexp(m.get_d(), int(quantum));
}
}  // namespace

double to_double(const Rational& q) {
  int s = sgn(q);
  if (s == 0) return 0.0;
  {
    // One-limb fast path: |num| < 2^53 over a one-limb power of two is exact
    // as a double (at most 2^63 in the denominator: no underflow).
    const mpz_srcptr num = q.get_num_mpz_t(), den = q.get_den_mpz_t();
    if constexpr (GMP_NUMB_BITS == 64) {
      if (mpz_size(num) == 1 && mpz_size(den) == 1) {
        const std::uint64_t n = mpz_getlimbn(num, 0), d = mpz_getlimbn(den, 0);
        if (n < (std::uint64_t(1) << 53) && (d & (d - 1)) == 0) {
          // 2^-k for k = log2(d) ≤ 63, built from its exponent bits: exact.
          const double v = double(n) * std::bit_cast<double>(std::uint64_t(1023 - __builtin_ctzll(d)) << 52);
          return s < 0 ? -v : v;
        }
      }
    }
  }
  if (double d; dyadic_short(q, d)) return d;
  if (double d; to_double_fast(q.get_num_mpz_t(), q.get_den_mpz_t(), d)) return s < 0 ? -d : d;
  const double v = round_to_binary(abs(q.get_num()), q.get_den(), 53, -1074, 1023);
  return s < 0 ? -v : v;
}

namespace {
// to_double_rest for |n| / d with floor(log2) within ±900: the quotient of
// |n| 2^k / d with 113 or 114 bits, M + r/d; hi is M rounded to 53 bits
// (ties to even, the remainder r as sticky bit), H its integer value, and
// R = M − H (|R| ≤ 2^60) what is left: |n|/d − hi = (R + r/d) 2^−k.
// lo = R 2^−k, exact when |R| < 2^53 and r = 0; otherwise off by less than
// one unit of R's double (≤ |R| 2^−52, whatever the rounding mode) plus
// r/d < 1, in units of 2^−k: err = (⌊|R| / 2^52⌋ + 2) 2^−k.  Every double
// made here is an exact ldexp of a small integer.
bool to_double_rest_fast(mpz_srcptr n, mpz_srcptr d, double& hi, double& lo, double& err) {
  Scratch& s = scratch();
  mpz_ptr t = s.t, m = s.m, r = s.r;
  const long e0 = long(mpz_sizeinbase(n, 2)) - long(mpz_sizeinbase(d, 2));
  if (e0 > 900 || e0 < -900) return false;
  const long k = 113 - e0;  // |n| 2^k / d lies in [2^112, 2^114)
  scaled_quotient(n, d, k, t, m, r);
  static_assert(GMP_NUMB_BITS == 64, "two limbs hold the 114-bit quotient");
  const unsigned __int128 M = (unsigned __int128)(mpz_getlimbn(m, 1)) << 64 | mpz_getlimbn(m, 0);
  const int bm = 128 - __builtin_clzll(std::uint64_t(M >> 64));  // 113 or 114
  const int drop = bm - 53;                                     // 60 or 61
  std::uint64_t kept = std::uint64_t(M >> drop);
  const std::uint64_t rest = std::uint64_t(M) & ((std::uint64_t(1) << drop) - 1);
  const std::uint64_t half = std::uint64_t(1) << (drop - 1);
  const bool sticky = mpz_sgn(r) != 0;
  std::int64_t R = std::int64_t(rest);
  if (rest > half || (rest == half && (sticky || (kept & 1)))) {
    ++kept;  // <= 2^53
    R -= std::int64_t(std::uint64_t(1) << drop);
  }
  hi = std::ldexp(double(kept), int(drop - k));
  lo = std::ldexp(double(R), int(-k));
  const std::uint64_t aR = std::uint64_t(R < 0 ? -R : R);
  err = !sticky && aR < (std::uint64_t(1) << 53) ? 0.0 : std::ldexp(double((aR >> 52) + 2), int(-k));
  return true;
}
}  // namespace

void to_double_rest(const Rational& q, double& hi, double& lo, double& err) {
  lo = 0;
  err = 0;
  const int s = sgn(q);
  if (s == 0) {
    hi = 0;
    return;
  }
  if (dyadic_short(q, hi)) return;  // exact
  if (to_double_rest_fast(q.get_num_mpz_t(), q.get_den_mpz_t(), hi, lo, err)) {
    if (s < 0) hi = -hi, lo = -lo;
    return;
  }
  // Near the ends of the range: the rest exactly, then its nearest double,
  // whose error is at most half an ulp: ≤ |lo| 2^−53 when normal, ≤ 2^−1075
  // below (both covered by |lo| 2^−52 + 2^−1000, a sum that rounds up or
  // to a value ≥ both terms in every mode).
  hi = to_double(q);
  if (!std::isfinite(hi)) {
    err = HUGE_VAL;
    return;
  }
  const Rational rest = q - Rational(hi);
  if (sgn(rest) == 0) return;
  lo = to_double(rest);
  if (!is_double(rest)) err = std::fabs(lo) * 0x1p-52 + 0x1p-1000;
}

float to_float(const Rational& q) {
  int s = sgn(q);
  if (s == 0) return 0.0f;
  {
    // Fast path: q exactly a double (dyadic, at most 53 significant bits, in
    // range).  Then one rounding, double -> float, is the correct one.
    const mpz_srcptr num = q.get_num_mpz_t(), den = q.get_den_mpz_t();
    const std::size_t den_bits = mpz_sizeinbase(den, 2);
    // The conversion rounds in the current mode: only to nearest here.
    if (mpz_sizeinbase(num, 2) <= 53 && den_bits <= 1000 && mpz_scan1(den, 0) == den_bits - 1 &&
        std::fegetround() == FE_TONEAREST)
      return static_cast<float>(q.get_d());  // get_d exact here; +-inf beyond FLT_MAX
  }
  if (std::fegetround() == FE_TONEAREST) {
    // Through the nearest double d: float(d) is q's nearest float unless d
    // is the boundary between two floats' roundings (the midpoint of two
    // consecutive floats, or FLT_MAX + half its ulp).  Every such boundary
    // m is a double (at most 25 significant bits, at least 2^-150), and
    // rounding to the nearest double is monotone and keeps m, so q < m
    // gives d <= m and q > m gives d >= m: when d is not a boundary, q and
    // d lie strictly on the same side of every boundary and round to the
    // same float.  (A q below the doubles' range gives d = 0, whose float
    // is q's too; one beyond it gives d = +-inf, as q's float is.)
    const double d = to_double(q);
    const float f = static_cast<float>(d);
    if (static_cast<double>(f) == d || !std::isfinite(d)) return f;
    const float g = std::nextafter(f, d > static_cast<double>(f) ? HUGE_VALF : -HUGE_VALF);
    const double boundary = std::isinf(f) || std::isinf(g)
                                ? std::copysign(0x1.ffffffp127, d)                            // FLT_MAX + half an ulp
                                : (static_cast<double>(f) + static_cast<double>(g)) / 2;  // exact
    if (d != boundary) return f;
  }
  const float v = static_cast<float>(round_to_binary(abs(q.get_num()), q.get_den(), 24, -149, 127));
  return s < 0 ? -v : v;
}

Vec3d to_double(const Point3& p) { return {to_double(p.x), to_double(p.y), to_double(p.z)}; }

bool is_double(const Rational& q) {
  if (sgn(q) == 0) return true;
  const mpz_srcptr den = q.get_den_mpz_t();
  std::size_t dbits = mpz_sizeinbase(den, 2);
  if (mpz_scan1(den, 0) != dbits - 1) return false;  // denominator not a power of two
  // q = m * 2^e with m odd.
  const mpz_srcptr num = q.get_num_mpz_t();
  long tz = long(mpz_scan1(num, 0));
  long mbits = long(mpz_sizeinbase(num, 2)) - tz;
  long e = tz - long(dbits - 1);
  if (mbits > 53) return false;
  if (e < -1074) return false;             // below the subnormal quantum
  if (e + mbits - 1 > 1023) return false;  // above DBL_MAX's exponent
  // Normal numbers need mbits <= 53 (checked); subnormals need all bits above 2^-1074 (checked by e).
  return true;
}
bool is_double(const Point3& p) { return is_double(p.x) && is_double(p.y) && is_double(p.z); }

static std::size_t hash_mpz(const mpz_t z) {
  std::size_t h = std::size_t(mpz_sgn(z)) * 0x9e3779b97f4a7c15ULL;
  std::size_t n = mpz_size(z);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= std::hash<mp_limb_t>()(mpz_getlimbn(z, i)) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  }
  return h;
}

std::size_t hash_value(const Point3& p) {
  std::size_t h = 0;
  for (int i = 0; i < 3; ++i) {
    h = h * 1000003u ^ hash_mpz(p[i].get_num_mpz_t());
    h = h * 1000003u ^ hash_mpz(p[i].get_den_mpz_t());
  }
  return h;
}

// ---------------------------------------------------------------------------

static bool parse_integer(std::string_view t, Integer& out) {
  std::size_t i = 0;
  bool neg = false;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) neg = (t[i++] == '-');
  if (i == t.size()) return false;
  for (std::size_t j = i; j < t.size(); ++j)
    if (!std::isdigit(static_cast<unsigned char>(t[j]))) return false;
  std::string digits(t.substr(i));
  if (mpz_set_str(out.get_mpz_t(), digits.c_str(), 10) != 0) return false;
  if (neg) out = -out;
  return true;
}

static bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

std::optional<Rational> parse_number(std::string_view t, std::string* why) {
  auto fail = [&](const char* reason) -> std::optional<Rational> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (t.empty()) return fail("empty number");
  std::string_view body = t;
  if (body[0] == '+' || body[0] == '-') body.remove_prefix(1);
  if (iequals(body, "nan") || (body.size() > 3 && iequals(body.substr(0, 4), "nan(")))
    return fail("NaN");
  if (iequals(body, "inf") || iequals(body, "infinity")) return fail("infinite");

  if (auto slash = t.find('/'); slash != std::string_view::npos) {
    Integer p, q;
    if (!parse_integer(t.substr(0, slash), p) || !parse_integer(t.substr(slash + 1), q))
      return fail("not a number");
    if (sgn(q) == 0) return fail("zero denominator");
    Rational r(p, q);
    r.canonicalize();
    return r;
  }
  Integer z;
  if (parse_integer(t, z)) return Rational(z);

  // Decimal or hexadecimal floating-point token: validate the shape, then strtod.
  std::size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  bool hex = t.size() >= i + 2 && t[i] == '0' && (t[i + 1] == 'x' || t[i + 1] == 'X');
  if (hex) {
    i += 2;
    auto is_hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    std::size_t digits = 0;
    while (i < t.size() && is_hex(t[i])) ++i, ++digits;
    if (i < t.size() && t[i] == '.') {
      ++i;
      while (i < t.size() && is_hex(t[i])) ++i, ++digits;
    }
    if (digits == 0) return fail("not a number");
    if (i < t.size() && (t[i] == 'p' || t[i] == 'P')) {
      ++i;
      if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
      std::size_t e0 = i;
      while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
      if (i == e0) return fail("not a number");
    }
  } else {
    std::size_t digits = 0;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
    if (i < t.size() && t[i] == '.') {
      ++i;
      while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i, ++digits;
    }
    if (digits == 0) return fail("not a number");
    if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
      ++i;
      if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
      std::size_t e0 = i;
      while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
      if (i == e0) return fail("not a number");
    }
  }
  if (i != t.size()) return fail("not a number");
  std::string s(t);
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return fail("not a number");
  if (std::isinf(v)) return fail("out of double range");
  return Rational(v);
}

std::string format_double(double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string format_point(const Point3& p) {
  return "(" + format_double(to_double(p.x)) + ", " + format_double(to_double(p.y)) + ", " +
         format_double(to_double(p.z)) + ")";
}

std::string format_exact(const Rational& q) {
  if (q.get_den() == 1) return q.get_num().get_str();
  return q.get_num().get_str() + "/" + q.get_den().get_str();
}

namespace {
// x = m * 2^e with an integer m, |m| < 2^53 (x finite, nonzero).
inline void split_double(double x, std::int64_t& m, int& e) {
  int ex;
  const double f = std::frexp(x, &ex);
  m = static_cast<std::int64_t>(std::ldexp(f, 53));
  e = ex - 53;
  const int tz = __builtin_ctzll(static_cast<std::uint64_t>(m < 0 ? -m : m));
  m >>= tz;  // exact: the low tz bits are zero
  e += tz;
}
void append_int(std::string& out, long long v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}
void append_uint(std::string& out, unsigned long long v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}
}  // namespace

void append_exact_dyadic(std::string& out, double hi, double lo) {
  if (hi == 0 && lo == 0) {
    out += '0';
    return;
  }
  if (lo == 0 || hi == 0) {
    std::int64_t m;
    int e;
    split_double(hi != 0 ? hi : lo, m, e);  // m odd
    if (e >= 0 && e <= 9) {  // |m| * 2^e < 2^62
      append_int(out, static_cast<long long>(m) << e);
      return;
    }
    if (e < 0 && e >= -63) {
      append_int(out, m);
      out += '/';
      append_uint(out, 1ULL << -e);
      return;
    }
  }
  // General case: N * 2^emin with a GMP integer N.
  std::int64_t m[2] = {0, 0};
  int e[2] = {0, 0};
  int emin = INT_MAX;
  const double parts[2] = {hi, lo};
  for (int i = 0; i < 2; ++i)
    if (parts[i] != 0) {
      split_double(parts[i], m[i], e[i]);
      emin = std::min(emin, e[i]);
    }
  Integer n = 0, t;
  for (int i = 0; i < 2; ++i)
    if (m[i] != 0) {
      mpz_set_si(t.get_mpz_t(), static_cast<long>(m[i]));
      mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), mp_bitcnt_t(e[i] - emin));
      n += t;
    }
  const long tz = long(mpz_scan1(n.get_mpz_t(), 0));
  mpz_fdiv_q_2exp(n.get_mpz_t(), n.get_mpz_t(), mp_bitcnt_t(tz));
  long ex = long(emin) + tz;
  if (ex >= 0) {
    mpz_mul_2exp(n.get_mpz_t(), n.get_mpz_t(), mp_bitcnt_t(ex));
    out += n.get_str();
    return;
  }
  out += n.get_str();
  out += '/';
  Integer d;
  mpz_setbit(d.get_mpz_t(), mp_bitcnt_t(-ex));
  out += d.get_str();
}

std::string format_coordinate(const Rational& q, bool exact) {
  return exact ? format_exact(q) : format_double(to_double(q));
}

}  // namespace minksum
