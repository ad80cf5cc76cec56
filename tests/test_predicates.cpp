// Tests of the sign predicates (src/kernel/: filter, exact, predicates).
//
// Every answer is compared with an oracle computed here, independently of the
// kernel: the predicate's polynomial evaluated in mpq arithmetic on the exact
// input values (Sarrus' rule for the determinants).  For each input the test
// runs every stage — the double approximation (whose error bound is checked
// exactly: |value − P·2^scale| ≤ bound), the filter, the exact stage, and the
// public function — in both the Vec3d and the Point3 form, and checks that
// the statistics count the filter's failures.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfenv>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <minksum/kernel.hpp>
#include <minksum/predicates.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "kernel/predicates_internal.hpp"

using namespace minksum;
using minksum::detail::Approx;

namespace {

// ---------------------------------------------------------------------------
// Oracle arithmetic (mpq only).

struct QV {
  Rational x, y, z;
};
QV qsub(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QV qvec(const Point3& a) { return {a.x, a.y, a.z}; }
QV qcross(const QV& a, const QV& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Rational qdot(const QV& a, const QV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
// det of the rows u, v, w by Sarrus' rule.
Rational qdet(const QV& u, const QV& v, const QV& w) {
  return u.x * v.y * w.z + u.y * v.z * w.x + u.z * v.x * w.y - u.z * v.y * w.x - u.y * v.x * w.z -
         u.x * v.z * w.y;
}
int sgnq(const Rational& q) { return sgn(q); }

Point3 exact_point(const Vec3d& v) { return Point3(v.x, v.y, v.z); }

// One checked approximation: which polynomial it approximates, status,
// value, bound, scale.  An approximation gives a semi-static entry and, when
// its dynamic step ran, a dynamic entry (per coordinate for vectors).
struct Entry {
  std::size_t poly;
  Approx::Status status;
  double value, bound;
  int scale;
};
std::vector<Entry> entries(const Approx& a, std::size_t poly = 0) {
  std::vector<Entry> r{{poly, a.status, a.value, a.bound, a.scale}};
  if (a.has_dynamic)
    r.push_back({poly, a.status, a.dynamic_value, a.dynamic_bound, a.dynamic_scale});
  return r;
}
std::vector<Entry> entries(const detail::Approx3& a, std::size_t first = 0) {
  std::vector<Entry> r;
  for (std::size_t i = 0; i < 3; ++i) {
    r.push_back({first + i, a.status, a.value[i], a.bound, a.scale});
    if (a.has_dynamic)
      r.push_back({first + i, a.status, a.dynamic_value[i], a.dynamic_bound[i], a.dynamic_scale});
  }
  return r;
}

// ---------------------------------------------------------------------------
// Exact integer vectors for building degenerate configurations.

struct IV {
  std::int64_t x, y, z;
};
IV operator+(IV a, IV b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
IV operator-(IV a, IV b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
IV operator*(std::int64_t s, IV a) { return {s * a.x, s * a.y, s * a.z}; }
IV icross(IV a, IV b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

class Gen {
 public:
  explicit Gen(std::uint64_t seed) : rng_(seed) {}
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng_);
  }
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool coin() { return integer(0, 1) == 1; }
  IV ivec(std::int64_t r = 20) { return {integer(-r, r), integer(-r, r), integer(-r, r)}; }
  Vec3d uvec(double s = 1) { return {s * uniform(-1, 1), s * uniform(-1, 1), s * uniform(-1, 1)}; }
  // A double with a random 53-bit mantissa, sign and exponent in [lo, hi].
  double wild(int lo = -1074, int hi = 1023) {
    const double m =
        std::ldexp(double(integer(std::int64_t(1) << 52, (std::int64_t(1) << 53) - 1)), -53);
    const double v = std::ldexp(m, int(integer(lo, hi)) + 1);
    return coin() ? v : -v;
  }
  Vec3d wvec(int lo = -1074, int hi = 1023) { return {wild(lo, hi), wild(lo, hi), wild(lo, hi)}; }
  std::uint64_t bits() { return rng_(); }

 private:
  std::mt19937_64 rng_;
};

// Rationals p/q with small q (never a double unless q is a power of two).
Rational small_rational(Gen& g, std::int64_t num = 50, std::int64_t den = 40) {
  Rational r(mpz_class(static_cast<long>(g.integer(-num, num))),
             mpz_class(static_cast<long>(g.integer(1, den))));
  r.canonicalize();
  return r;
}
Point3 rational_point(Gen& g) { return {small_rational(g), small_rational(g), small_rational(g)}; }

// ---------------------------------------------------------------------------
// The predicates under test, one traits struct each.  N points; `polys`
// gives the exact polynomials the approximation entries approximate, and
// `answer` the predicate's answer from them.

#define LIFT(f) [](const auto&... args) { return f(args...); }

struct Orient3d {
  static constexpr bool scalar = true;
  static constexpr const char* name = "orient3d";
  static constexpr PredicateId id = PredicateId::orient3d;
  static constexpr std::size_t N = 4;
  static constexpr auto pub = LIFT(orient3d);
  static constexpr auto filter = LIFT(detail::orient3d_filter);
  static constexpr auto exact = LIFT(detail::orient3d_exact);
  static constexpr auto approx = LIFT(detail::orient3d_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdet(qsub(p[1], p[0]), qsub(p[2], p[0]), qsub(p[3], p[0]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  // d in the plane of a, b, c.
  static std::array<IV, N> degenerate(Gen& g) {
    IV a = g.ivec(), b = g.ivec(), c = g.ivec();
    IV d = a + g.integer(-3, 3) * (b - a) + g.integer(-3, 3) * (c - a);
    return {a, b, c, d};
  }
  static constexpr bool translate[N] = {true, true, true, true};
};

struct SupportCompare {
  static constexpr bool scalar = true;
  static constexpr const char* name = "support_compare";
  static constexpr PredicateId id = PredicateId::support_compare;
  static constexpr std::size_t N = 5;
  static constexpr auto pub = LIFT(support_compare);
  static constexpr auto filter = LIFT(detail::support_compare_filter);
  static constexpr auto exact = LIFT(detail::support_compare_exact);
  static constexpr auto approx = LIFT(detail::support_compare_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdet(qsub(p[3], p[4]), qsub(p[1], p[0]), qsub(p[2], p[0]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  // bi − bj parallel to the facet.
  static std::array<IV, N> degenerate(Gen& g) {
    IV a0 = g.ivec(), a1 = g.ivec(), a2 = g.ivec(), bj = g.ivec();
    IV bi = bj + g.integer(-3, 3) * (a1 - a0) + g.integer(-3, 3) * (a2 - a0);
    return {a0, a1, a2, bi, bj};
  }
  static constexpr bool translate[N] = {true, true, true, true, true};
};

struct EdgeFacet {
  static constexpr bool scalar = true;
  static constexpr const char* name = "edge_facet_sign";
  static constexpr PredicateId id = PredicateId::edge_facet_sign;
  static constexpr std::size_t N = 5;
  static constexpr auto pub = LIFT(edge_facet_sign);
  static constexpr auto filter = LIFT(detail::edge_facet_sign_filter);
  static constexpr auto exact = LIFT(detail::edge_facet_sign_exact);
  static constexpr auto approx = LIFT(detail::edge_facet_sign_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdet(qsub(p[1], p[0]), qsub(p[3], p[2]), qsub(p[4], p[2]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  static std::array<IV, N> degenerate(Gen& g) {
    IV a0 = g.ivec(), a1 = g.ivec(), a2 = g.ivec(), p0 = g.ivec();
    IV p1 = p0 + g.integer(-3, 3) * (a1 - a0) + g.integer(-3, 3) * (a2 - a0);
    return {p0, p1, a0, a1, a2};
  }
  static constexpr bool translate[N] = {true, true, true, true, true};
};

struct ArcSide {
  static constexpr bool scalar = true;
  static constexpr const char* name = "arc_side";
  static constexpr PredicateId id = PredicateId::arc_side;
  static constexpr std::size_t N = 7;
  static constexpr auto pub = LIFT(arc_side);
  static constexpr auto filter = LIFT(detail::arc_side_filter);
  static constexpr auto exact = LIFT(detail::arc_side_exact);
  static constexpr auto approx = LIFT(detail::arc_side_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    const QV n = qcross(qsub(p[5], p[4]), qsub(p[6], p[4]));
    return {qdet(qsub(p[1], p[0]), qsub(p[3], p[2]), n)};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  // e_b in the span of e_a and n.
  static std::array<IV, N> degenerate(Gen& g) {
    IV r0 = g.ivec(), r1 = g.ivec(), r2 = g.ivec();
    IV n = icross(r1 - r0, r2 - r0);
    IV p0 = g.ivec(), ea = g.ivec(), q0 = g.ivec();
    IV eb = g.integer(-3, 3) * ea + g.integer(-2, 2) * n;
    return {p0, p0 + ea, q0, q0 + eb, r0, r1, r2};
  }
  static constexpr bool translate[N] = {true, true, true, true, true, true, true};
};

struct NormalsDot {
  static constexpr bool scalar = true;
  static constexpr const char* name = "normals_dot_sign";
  static constexpr PredicateId id = PredicateId::normals_dot_sign;
  static constexpr std::size_t N = 6;
  static constexpr auto pub = LIFT(normals_dot_sign);
  static constexpr auto filter = LIFT(detail::normals_dot_sign_filter);
  static constexpr auto exact = LIFT(detail::normals_dot_sign_exact);
  static constexpr auto approx = LIFT(detail::normals_dot_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    const QV n1 = qcross(qsub(p[1], p[0]), qsub(p[2], p[0]));
    const QV n2 = qcross(qsub(p[4], p[3]), qsub(p[5], p[3]));
    return {qdot(n1, n2)};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  // n1 in the plane of the second facet: n1 ⊥ n2.
  static std::array<IV, N> degenerate(Gen& g) {
    IV a0 = g.ivec(), a1 = g.ivec(), a2 = g.ivec();
    IV n1 = icross(a1 - a0, a2 - a0);
    IV b0 = g.ivec(), w1 = g.ivec();
    IV w2 = g.integer(-3, 3) * w1 + g.integer(-2, 2) * n1;
    return {a0, a1, a2, b0, b0 + w1, b0 + w2};
  }
  static constexpr bool translate[N] = {true, true, true, true, true, true};
};

// Parallel configurations: translated, opposite, scaled, or coplanar facets.
std::array<IV, 6> parallel_configuration(Gen& g) {
  IV a0 = g.ivec(), a1 = g.ivec(), a2 = g.ivec();
  IV t = g.ivec(40);
  switch (g.integer(0, 3)) {
    case 0:
      return {a0, a1, a2, a0 + t, a1 + t, a2 + t};  // same normal
    case 1:
      return {a0, a1, a2, a0 + t, a2 + t, a1 + t};  // opposite normal
    case 2: {
      const std::int64_t k = g.coin() ? -2 : 3;  // n2 = k² n1
      return {a0, a1, a2, t + k * a0, t + k * a1, t + k * a2};
    }
    default: {  // three other points of the plane of a (possibly collinear)
      auto in_plane = [&] {
        return a0 + g.integer(-3, 3) * (a1 - a0) + g.integer(-3, 3) * (a2 - a0);
      };
      return {a0, a1, a2, in_plane(), in_plane(), in_plane()};
    }
  }
}

struct NormalsParallel {
  static constexpr bool scalar = false;
  static constexpr const char* name = "normals_parallel";
  static constexpr PredicateId id = PredicateId::normals_parallel;
  static constexpr std::size_t N = 6;
  static constexpr auto pub = LIFT(normals_parallel);
  static constexpr auto filter = LIFT(detail::normals_parallel_filter);
  static constexpr auto exact = LIFT(detail::normals_parallel_exact);
  static constexpr auto approx = LIFT(detail::normals_cross_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    const QV n1 = qcross(qsub(p[1], p[0]), qsub(p[2], p[0]));
    const QV n2 = qcross(qsub(p[4], p[3]), qsub(p[5], p[3]));
    const QV c = qcross(n1, n2);
    return {c.x, c.y, c.z};
  }
  static int answer(const std::vector<Rational>& v) {
    return sgn(v[0]) == 0 && sgn(v[1]) == 0 && sgn(v[2]) == 0;
  }
  static std::array<IV, N> degenerate(Gen& g) { return parallel_configuration(g); }
  static constexpr bool translate[N] = {true, true, true, true, true, true};
};

struct NormalsSameDirection {
  static constexpr bool scalar = false;
  static constexpr const char* name = "normals_same_direction";
  static constexpr PredicateId id = PredicateId::normals_same_direction;
  static constexpr std::size_t N = 6;
  static constexpr auto pub = LIFT(normals_same_direction);
  static constexpr auto filter = LIFT(detail::normals_same_direction_filter);
  static constexpr auto exact = LIFT(detail::normals_same_direction_exact);
  // Both approximations it uses: ⟨n1, n2⟩, then n1 × n2.
  static constexpr auto approx = [](const auto&... a) {
    std::vector<Entry> r = entries(detail::normals_dot_approx(a...), 0);
    for (const Entry& e : entries(detail::normals_cross_approx(a...), 1)) r.push_back(e);
    return r;
  };
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    const QV n1 = qcross(qsub(p[1], p[0]), qsub(p[2], p[0]));
    const QV n2 = qcross(qsub(p[4], p[3]), qsub(p[5], p[3]));
    const QV c = qcross(n1, n2);
    return {qdot(n1, n2), c.x, c.y, c.z};
  }
  static int answer(const std::vector<Rational>& v) {
    return sgn(v[1]) == 0 && sgn(v[2]) == 0 && sgn(v[3]) == 0 && sgn(v[0]) > 0;
  }
  static std::array<IV, N> degenerate(Gen& g) { return parallel_configuration(g); }
  static constexpr bool translate[N] = {true, true, true, true, true, true};
};

struct DotSign {
  static constexpr bool scalar = true;
  static constexpr const char* name = "dot_sign";
  static constexpr PredicateId id = PredicateId::dot_sign;
  static constexpr std::size_t N = 4;
  static constexpr auto pub = LIFT(dot_sign);
  static constexpr auto filter = LIFT(detail::dot_sign_filter);
  static constexpr auto exact = LIFT(detail::dot_sign_exact);
  static constexpr auto approx = LIFT(detail::dot_sign_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdot(qsub(p[1], p[0]), qsub(p[3], p[2]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  static std::array<IV, N> degenerate(Gen& g) {
    IV e1 = g.ivec(), p0 = g.ivec(), q0 = g.ivec();
    IV e2 = icross(e1, g.ivec());
    return {p0, p0 + e1, q0, q0 + e2};
  }
  static constexpr bool translate[N] = {true, true, true, true};
};

struct CompareAlong {
  static constexpr bool scalar = true;
  static constexpr const char* name = "compare_along";
  static constexpr PredicateId id = PredicateId::compare_along;
  static constexpr std::size_t N = 3;
  static constexpr auto pub = LIFT(compare_along);
  static constexpr auto filter = LIFT(detail::compare_along_filter);
  static constexpr auto exact = LIFT(detail::compare_along_exact);
  static constexpr auto approx = LIFT(detail::compare_along_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdot(qvec(p[0]), qsub(p[1], p[2]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  static std::array<IV, N> degenerate(Gen& g) {
    IV d = g.ivec(), q = g.ivec();
    return {d, q + icross(d, g.ivec()), q};
  }
  static constexpr bool translate[N] = {false, true, true};  // d is a vector
};

struct EdgeNormalSide {
  static constexpr bool scalar = true;
  static constexpr const char* name = "edge_normal_side";
  static constexpr PredicateId id = PredicateId::edge_normal_side;
  static constexpr std::size_t N = 4;
  static constexpr auto pub = LIFT(edge_normal_side);
  static constexpr auto filter = LIFT(detail::edge_normal_side_filter);
  static constexpr auto exact = LIFT(detail::edge_normal_side_exact);
  static constexpr auto approx = LIFT(detail::edge_normal_side_approx);
  static std::vector<Rational> polys(const std::array<Point3, N>& p) {
    return {qdet(qsub(p[3], p[0]), qsub(p[1], p[0]), qvec(p[2]))};
  }
  static int answer(const std::vector<Rational>& v) { return sgnq(v[0]); }
  // d in the plane through a and b parallel to n.
  static std::array<IV, N> degenerate(Gen& g) {
    IV a = g.ivec(), b = g.ivec(), n = g.ivec();
    return {a, b, n, a + g.integer(-3, 3) * (b - a) + g.integer(-3, 3) * n};
  }
  static constexpr bool translate[N] = {true, true, false, true};  // n is a vector
};

std::vector<Entry> as_entries(const Approx& a) { return entries(a); }
std::vector<Entry> as_entries(const detail::Approx3& a) { return entries(a); }
std::vector<Entry> as_entries(const std::vector<Entry>& e) { return e; }

// ---------------------------------------------------------------------------
// The checker: runs every stage on one input and compares with the oracle.

struct Tally {
  std::uint64_t cases = 0;
  std::uint64_t filter_declined = 0;  // Vec3d filter gave no answer
  std::uint64_t stats_fallbacks = 0;  // fallbacks counted by predicate_stats() (Vec3d calls)
  std::uint64_t zero = 0;             // cases whose exact answer is 0 / false
  void add(const Tally& t) {
    cases += t.cases, filter_declined += t.filter_declined, stats_fallbacks += t.stats_fallbacks,
        zero += t.zero;
  }
  double ratio() const { return cases ? double(stats_fallbacks) / double(cases) : 0; }
};

void check_entries(const std::vector<Entry>& es, const std::vector<Rational>& ps,
                   const char* form) {
  for (std::size_t i = 0; i < es.size(); ++i) {
    const Entry& e = es[i];
    ASSERT_LT(e.poly, ps.size()) << form;
    const Rational& p = ps[e.poly];
    if (e.status == Approx::kZero) {
      EXPECT_EQ(sgn(p), 0) << form << ": the filter claimed an exact zero, entry " << i;
    } else if (e.status == Approx::kOk) {
      ASSERT_TRUE(std::isfinite(e.value) && std::isfinite(e.bound)) << form;
      Rational scaled = p;
      if (e.scale >= 0)
        mpq_mul_2exp(scaled.get_mpq_t(), scaled.get_mpq_t(), mp_bitcnt_t(e.scale));
      else
        mpq_div_2exp(scaled.get_mpq_t(), scaled.get_mpq_t(), mp_bitcnt_t(-e.scale));
      const Rational err = abs(Rational(e.value) - scaled);
      EXPECT_LE(err, Rational(e.bound))
          << form << ": error bound violated, entry " << i << ": value " << e.value << " bound "
          << e.bound << " scale " << e.scale << " exact " << p.get_d();
    }
  }
}

template <class P>
std::string describe(const std::array<Vec3d, P::N>& v) {
  std::ostringstream os;
  os << std::setprecision(17) << P::name << "(";
  for (std::size_t i = 0; i < P::N; ++i)
    os << (i ? ", " : "") << "(" << v[i].x << ", " << v[i].y << ", " << v[i].z << ")";
  return os.str() + ")";
}
template <class P>
std::string describe(const std::array<Point3, P::N>& v) {
  std::ostringstream os;
  os << P::name << "(";
  for (std::size_t i = 0; i < P::N; ++i)
    os << (i ? ", " : "") << "(" << format_exact(v[i].x) << ", " << format_exact(v[i].y) << ", "
       << format_exact(v[i].z) << ")";
  return os.str() + ")";
}

template <class P>
std::uint64_t fallbacks_now() {
  return predicate_stats()[P::id].fallbacks;
}

// Inputs are doubles: both forms, all stages.
template <class P>
void check_doubles(const std::array<Vec3d, P::N>& v, Tally& t) {
  SCOPED_TRACE(describe<P>(v));
  std::array<Point3, P::N> q;
  for (std::size_t i = 0; i < P::N; ++i) q[i] = exact_point(v[i]);
  const std::vector<Rational> ps = P::polys(q);
  const int want = P::answer(ps);
  ++t.cases;
  if (want == 0) ++t.zero;

  const auto approx_v = std::apply(P::approx, v);
  check_entries(as_entries(approx_v), ps, "Vec3d approx");
  check_entries(as_entries(std::apply(P::approx, q)), ps, "Point3 approx");

  const auto f = std::apply(P::filter, v);
  if constexpr (P::scalar) {
    // The filter is the approximation's certified sign (semi-static, then dynamic).
    EXPECT_EQ(f.has_value(), detail::certified_sign(approx_v).has_value());
  }
  if (f) {
    EXPECT_EQ(int(*f), want) << "Vec3d filter";
  } else {
    ++t.filter_declined;
  }
  const auto fq = std::apply(P::filter, q);
  if (fq) {
    EXPECT_EQ(int(*fq), want) << "Point3 filter";
  }

  EXPECT_EQ(int(std::apply(P::exact, v)), want) << "Vec3d exact";
  EXPECT_EQ(int(std::apply(P::exact, q)), want) << "Point3 exact";

  const std::uint64_t before = fallbacks_now<P>();
  EXPECT_EQ(int(std::apply(P::pub, v)), want) << "Vec3d public";
  const std::uint64_t fell = fallbacks_now<P>() - before;
  EXPECT_EQ(fell, f ? 0u : 1u) << "the statistics must count exactly the filter's failures";
  t.stats_fallbacks += fell;

  const std::uint64_t before_q = fallbacks_now<P>();
  EXPECT_EQ(int(std::apply(P::pub, q)), want) << "Point3 public";
  EXPECT_EQ(fallbacks_now<P>() - before_q, fq ? 0u : 1u);
}

// Inputs are rationals: Point3 form only.
template <class P>
void check_rationals(const std::array<Point3, P::N>& q, Tally& t) {
  SCOPED_TRACE(describe<P>(q));
  const std::vector<Rational> ps = P::polys(q);
  const int want = P::answer(ps);
  ++t.cases;
  if (want == 0) ++t.zero;
  check_entries(as_entries(std::apply(P::approx, q)), ps, "Point3 approx");
  const auto fq = std::apply(P::filter, q);
  if (fq) {
    EXPECT_EQ(int(*fq), want) << "Point3 filter";
  } else {
    ++t.filter_declined;
  }
  EXPECT_EQ(int(std::apply(P::exact, q)), want) << "Point3 exact";
  const std::uint64_t before = fallbacks_now<P>();
  EXPECT_EQ(int(std::apply(P::pub, q)), want) << "Point3 public";
  const std::uint64_t fell = fallbacks_now<P>() - before;
  EXPECT_EQ(fell, fq ? 0u : 1u);
  t.stats_fallbacks += fell;
}

template <class P>
void report(const char* category, const Tally& t) {
  std::ostringstream os;
  os << std::left << std::setw(24) << P::name << std::setw(26) << category << std::right
     << std::setw(7) << t.stats_fallbacks << " / " << std::setw(7) << t.cases << " fallbacks ("
     << std::fixed << std::setprecision(2) << 100.0 * t.ratio()
     << "%), exact zero/false: " << t.zero;
  std::cout << "[ filter   ] " << os.str() << std::endl;
  ::testing::Test::RecordProperty(std::string(P::name) + "." + category + ".fallback_ratio",
                                  std::to_string(t.ratio()));
}

// ---------------------------------------------------------------------------
// Input builders.

template <std::size_t N>
std::array<Vec3d, N> to_doubles(const std::array<IV, N>& iv, int exp2, const IV& shift,
                                const bool (&translate)[N]) {
  std::array<Vec3d, N> v;
  for (std::size_t i = 0; i < N; ++i) {
    const IV p = translate[i] ? iv[i] + shift : iv[i];
    v[i] = {std::ldexp(double(p.x), exp2), std::ldexp(double(p.y), exp2),
            std::ldexp(double(p.z), exp2)};
  }
  return v;
}

// One ulp up or down on one coordinate.
template <std::size_t N>
void perturb(std::array<Vec3d, N>& v, Gen& g) {
  Vec3d& p = v[g.integer(0, N - 1)];
  double& c = g.integer(0, 2) == 0 ? p.x : (g.coin() ? p.y : p.z);
  c = std::nextafter(c, g.coin() ? HUGE_VAL : -HUGE_VAL);
}

// Exponents for the exact power-of-two scaling of degenerate configurations:
// ordinary, ±2^500 (≈1e±150), ±2^990 (≈1e±300) and the subnormal range.
constexpr int kScales[] = {0, 0, 0, -20, 30, -500, 500, -990, 950, -1060, -1074};

// Runs `count` cases produced by make(gen) and reports the tally.
template <class P, class Make>
Tally run_doubles(const char* category, std::uint64_t seed, int count, Make&& make) {
  Tally t;
  Gen g(seed);
  for (int i = 0; i < count && !::testing::Test::HasFatalFailure(); ++i) {
    SCOPED_TRACE("category " + std::string(category) + ", seed " + std::to_string(seed) +
                 ", case " + std::to_string(i));
    check_doubles<P>(make(g), t);
  }
  report<P>(category, t);
  return t;
}

template <class P>
class PredicateTest : public ::testing::Test {};

using AllPredicates =
    ::testing::Types<Orient3d, SupportCompare, EdgeFacet, ArcSide, NormalsDot, NormalsParallel,
                     NormalsSameDirection, DotSign, CompareAlong, EdgeNormalSide>;
class PredicateNames {
 public:
  template <class P>
  static std::string GetName(int) {
    return P::name;
  }
};
TYPED_TEST_SUITE(PredicateTest, AllPredicates, PredicateNames);

constexpr std::uint64_t kSeed = 20240611;

// ---------------------------------------------------------------------------
// Random inputs: the filter decides (almost) everything.

TYPED_TEST(PredicateTest, RandomUniform) {
  using P = TypeParam;
  const Tally t = run_doubles<P>("random uniform [-1,1]", kSeed + 1, 20000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v) p = g.uvec();
    return v;
  });
  // Random configurations are far from degenerate: a few in ten thousand at most.
  EXPECT_LT(t.ratio(), 0.01);
}

TYPED_TEST(PredicateTest, RandomSmallIntegers) {
  using P = TypeParam;
  // Small integer grids are full of exact degeneracies (repeated points,
  // coplanar quadruples): each must give exactly 0 / false.
  run_doubles<P>("small integers [-3,3]", kSeed + 2, 20000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v)
      p = {double(g.integer(-3, 3)), double(g.integer(-3, 3)), double(g.integer(-3, 3))};
    return v;
  });
}

TYPED_TEST(PredicateTest, RandomWideExponents) {
  using P = TypeParam;
  // Every coordinate with its own exponent in [-1074, 1023]: subnormals,
  // DBL_MAX-sized values, overflowing differences.
  run_doubles<P>("exponents [-1074,1023]", kSeed + 3, 3000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v) p = g.wvec();
    return v;
  });
  run_doubles<P>("exponents [-60,60]", kSeed + 4, 5000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v) p = g.wvec(-60, 60);
    return v;
  });
}

TYPED_TEST(PredicateTest, ExtremeMagnitudes) {
  using P = TypeParam;
  // Clusters of points at one magnitude: the filter rescales by powers of two
  // and still decides them.
  for (double s : {1e150, 1e-150, 1e300, 1e-300, 1e-310, 1e-320, 5e-324 * 1e6, 1e308}) {
    std::ostringstream cat;
    cat << "cluster " << s;
    const Tally t = run_doubles<P>(cat.str().c_str(), kSeed + 5, 1000, [s](Gen& g) {
      std::array<Vec3d, P::N> v;
      for (auto& p : v) p = g.uvec(s);
      return v;
    });
    if (s >= 1e-310 && s <= 1e300) {
      EXPECT_LT(t.ratio(), 0.02) << "cluster " << s;
    }
  }
  // Subnormal lattice points: coordinates k · 5e-324.
  run_doubles<P>("subnormal lattice", kSeed + 6, 3000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v)
      p = {g.integer(-9, 9) * 5e-324, g.integer(-9, 9) * 5e-324, g.integer(-9, 9) * 5e-324};
    return v;
  });
  // Mixed magnitudes: each point 1e150 or 1e-150 or 1 in size.
  run_doubles<P>("mixed 1e150/1e-150/1", kSeed + 7, 5000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v) {
      const double s[] = {1e150, 1e-150, 1.0};
      p = g.uvec(s[g.integer(0, 2)]);
    }
    return v;
  });
  // Mixed within one point.
  run_doubles<P>("mixed coordinates", kSeed + 8, 5000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    const double s[] = {1e150, 1e-150, 1.0, 1e300, 1e-310};
    for (auto& p : v)
      p = {s[g.integer(0, 4)] * g.uniform(-1, 1), s[g.integer(0, 4)] * g.uniform(-1, 1),
           s[g.integer(0, 4)] * g.uniform(-1, 1)};
    return v;
  });
  // Near DBL_MAX: differences overflow, the filter must decline.
  run_doubles<P>("near DBL_MAX", kSeed + 9, 1000, [](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v)
      p = {g.coin() ? DBL_MAX : -DBL_MAX * g.uniform(0.5, 1), DBL_MAX * g.uniform(-1, 1),
           g.integer(-2, 2) * (DBL_MAX / 2)};
    return v;
  });
}

TYPED_TEST(PredicateTest, LargeIntegersNear2p53) {
  using P = TypeParam;
  const double two53 = 9007199254740992.0;
  run_doubles<P>("integers near 2^53", kSeed + 10, 5000, [two53](Gen& g) {
    std::array<Vec3d, P::N> v;
    for (auto& p : v)
      p = {two53 - double(g.integer(0, 1000)), two53 - double(g.integer(0, 1000)),
           (g.coin() ? -1 : 1) * (two53 - double(g.integer(0, 1000)))};
    return v;
  });
}

// ---------------------------------------------------------------------------
// Degenerate inputs: exact zeros, and one ulp away from them.

template <class P>
std::array<Vec3d, P::N> degenerate_doubles(Gen& g) {
  const int e = kScales[g.integer(0, std::size(kScales) - 1)];
  IV shift{0, 0, 0};
  // Translate (exactly) by up to 2^40 — large offsets, small differences.
  if (g.coin()) shift = g.ivec(std::int64_t(1) << g.integer(0, 40));
  return to_doubles(P::degenerate(g), e, shift, P::translate);
}

TYPED_TEST(PredicateTest, ExactlyDegenerate) {
  using P = TypeParam;
  const Tally t = run_doubles<P>("exactly degenerate", kSeed + 11, 5000,
                                 [](Gen& g) { return degenerate_doubles<P>(g); });
  // Parallel/same-direction configurations are constructed parallel; the rest
  // are constructed with P = 0.
  if constexpr (std::is_same_v<P, NormalsParallel>) {
    EXPECT_EQ(t.zero, 0u);
  } else if constexpr (!std::is_same_v<P, NormalsSameDirection>) {
    EXPECT_EQ(t.zero, t.cases);
  }
}

TYPED_TEST(PredicateTest, OneUlpFromDegenerate) {
  using P = TypeParam;
  const Tally t = run_doubles<P>("one ulp off degenerate", kSeed + 12, 5000, [](Gen& g) {
    auto v = degenerate_doubles<P>(g);
    perturb(v, g);
    return v;
  });
  // A one-ulp perturbation changes P by far less than the filter's bound:
  // most of these must fall back (the rest are perturbations that keep P = 0
  // with a zero difference vector, or cancel in a lucky way).
  // (For normals_same_direction, the opposite-normal configurations stay
  // decided: their ⟨n1, n2⟩ < 0 is far from zero.)
  EXPECT_GT(t.ratio(), (std::is_same_v<P, NormalsSameDirection> ? 0.25 : 0.5))
      << "the filter must decline on near-degenerate input";
  // And the perturbation really moved most cases off the degeneracy.
  if constexpr (!std::is_same_v<P, NormalsParallel> && !std::is_same_v<P, NormalsSameDirection>) {
    EXPECT_LT(t.zero, t.cases);
  }
}

TYPED_TEST(PredicateTest, RandomDoublesNearDegenerate) {
  using P = TypeParam;
  // Non-integer degenerate configurations: a dyadic lattice with a random
  // 30-bit unit, one ulp away.
  run_doubles<P>("dyadic lattice, one ulp", kSeed + 13, 5000, [](Gen& g) {
    auto iv = P::degenerate(g);
    const std::int64_t unit = g.integer(1, std::int64_t(1) << 30);
    for (auto& p : iv) p = unit * p;
    auto v = to_doubles(iv, -int(g.integer(0, 60)), IV{0, 0, 0}, P::translate);
    if (g.coin()) perturb(v, g);
    return v;
  });
}

TYPED_TEST(PredicateTest, DirectedRoundingModes) {
  using P = TypeParam;
  // The bounds are derived for one-ulp rounding errors, so they hold in every
  // IEEE rounding mode: the whole check (bounds included) runs rounding up,
  // down and toward zero.
  struct Restore {
    ~Restore() { std::fesetround(FE_TONEAREST); }
  } restore;
  const std::pair<int, const char*> modes[] = {{FE_UPWARD, "rounding upward"},
                                               {FE_DOWNWARD, "rounding downward"},
                                               {FE_TOWARDZERO, "rounding toward zero"}};
  for (const auto& [mode, label] : modes) {
    ASSERT_EQ(std::fesetround(mode), 0);
    run_doubles<P>(label, kSeed + 14, 3000, [](Gen& g) {
      if (g.coin()) {
        std::array<Vec3d, P::N> v;
        for (auto& p : v) p = g.coin() ? g.uvec() : g.wvec(-60, 60);
        return v;
      }
      auto v = degenerate_doubles<P>(g);
      if (g.coin()) perturb(v, g);
      return v;
    });
    std::fesetround(FE_TONEAREST);
  }
}

// ---------------------------------------------------------------------------
// Rational inputs (Point3 form only).

template <class P, class Make>
Tally run_rationals(const char* category, std::uint64_t seed, int count, Make&& make) {
  Tally t;
  Gen g(seed);
  for (int i = 0; i < count && !::testing::Test::HasFatalFailure(); ++i) {
    SCOPED_TRACE("category " + std::string(category) + ", seed " + std::to_string(seed) +
                 ", case " + std::to_string(i));
    check_rationals<P>(make(g), t);
  }
  report<P>(category, t);
  return t;
}

// x ↦ α x + β (β only on translated points): P is multiplied by α^degree,
// so degeneracies are kept.
template <class P>
std::array<Point3, P::N> rational_image(const std::array<IV, P::N>& iv, const Rational& alpha,
                                        const Point3& beta) {
  std::array<Point3, P::N> q;
  for (std::size_t i = 0; i < P::N; ++i) {
    Point3 p(Rational(static_cast<long>(iv[i].x)), Rational(static_cast<long>(iv[i].y)),
             Rational(static_cast<long>(iv[i].z)));
    p = alpha * p;
    if (P::translate[i]) p = p + beta;
    q[i] = p;
  }
  return q;
}

TYPED_TEST(PredicateTest, Rationals) {
  using P = TypeParam;
  const Tally t = run_rationals<P>("random rationals p/q", kSeed + 20, 5000, [](Gen& g) {
    std::array<Point3, P::N> q;
    for (auto& p : q) p = rational_point(g);
    return q;
  });
  // Small denominators: the rational filter decides (almost) all of them.
  EXPECT_LT(t.ratio(), 0.01);
  // Thirds, sevenths, … with large numerators.
  run_rationals<P>("big rationals", kSeed + 21, 2000, [](Gen& g) {
    std::array<Point3, P::N> q;
    for (auto& p : q) {
      p = rational_point(g);
      p = Rational(mpz_class(static_cast<long>(g.integer(1, 1L << 40))), 3) * p;
    }
    return q;
  });
  // Huge and tiny rationals: beyond the filter's range, exact fallback.
  run_rationals<P>("rationals 1e±400", kSeed + 22, 300, [](Gen& g) {
    mpz_class big;
    mpz_ui_pow_ui(big.get_mpz_t(), 10, 400);
    const Rational s = g.coin() ? Rational(big) : Rational(mpz_class(1), big);
    std::array<Point3, P::N> q;
    for (auto& p : q) p = s * rational_point(g);
    return q;
  });
  // Exactly degenerate rational configurations, and nearly so.
  run_rationals<P>("rational degenerate", kSeed + 23, 3000, [](Gen& g) {
    const Rational alpha = [&] {
      Rational a;
      do a = small_rational(g, 9, 9);
      while (sgn(a) == 0);
      return a;
    }();
    return rational_image<P>(P::degenerate(g), alpha, rational_point(g));
  });
  run_rationals<P>("rational near-degenerate", kSeed + 24, 3000, [](Gen& g) {
    Rational alpha;
    do alpha = small_rational(g, 9, 9);
    while (sgn(alpha) == 0);
    auto q = rational_image<P>(P::degenerate(g), alpha, rational_point(g));
    // Move one coordinate by ±1/(3·2^60).
    Rational eps(mpz_class(1), mpz_class(3) << 60);
    Point3& p = q[g.integer(0, P::N - 1)];
    p[int(g.integer(0, 2))] += g.coin() ? eps : Rational(-eps);
    return q;
  });
}

TYPED_TEST(PredicateTest, RationalsThatAreDoublesAgreeWithVec3d) {
  using P = TypeParam;
  // Point3 built from doubles via exact rational arithmetic (not from the
  // double constructor): the Point3 form must give the Vec3d form's answer.
  Gen g(kSeed + 30);
  for (int i = 0; i < 2000; ++i) {
    std::array<Vec3d, P::N> v;
    std::array<Point3, P::N> q;
    for (std::size_t k = 0; k < P::N; ++k) {
      // Dyadic rationals m / 2^e.
      auto dy = [&](double& d) {
        const long m = long(g.integer(-(1L << 52), 1L << 52));
        const int e = int(g.integer(-100, 100));
        Rational r(m);
        if (e >= 0)
          mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(e));
        else
          mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(-e));
        d = std::ldexp(double(m), -e);
        return r;
      };
      q[k].x = dy(v[k].x);
      q[k].y = dy(v[k].y);
      q[k].z = dy(v[k].z);
    }
    SCOPED_TRACE(describe<P>(v));
    EXPECT_EQ(int(std::apply(P::pub, q)), int(std::apply(P::pub, v)));
    EXPECT_EQ(int(std::apply(P::pub, q)), P::answer(P::polys(q)));
  }
}

// ---------------------------------------------------------------------------
// Hand-picked cases.

TEST(PredicateCases, Orient3dBasics) {
  const Vec3d o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_EQ(orient3d(o, x, y, z), 1);  // z is above the counterclockwise triangle o, x, y
  EXPECT_EQ(orient3d(o, y, x, z), -1);
  EXPECT_EQ(orient3d(o, x, y, Vec3d{0.25, 0.25, 0}), 0);
  EXPECT_EQ(orient3d(o, o, y, z), 0);               // repeated point
  EXPECT_EQ(orient3d(o, x, Vec3d{2, 0, 0}, z), 0);  // collinear a, b, c
  // Points with 1e-300 spacing around 1e-300 — exact despite underflow.
  const Vec3d a{1e-300, 1e-300, 1e-300}, b{2e-300, 1e-300, 1e-300}, c{1e-300, 2e-300, 1e-300},
      d{1e-300, 1e-300, 2e-300};
  EXPECT_EQ(orient3d(a, b, c, d), 1);
  EXPECT_EQ(orient3d(Point3(a.x, a.y, a.z), Point3(b.x, b.y, b.z), Point3(c.x, c.y, c.z),
                     Point3(d.x, d.y, d.z)),
            1);
  // The same config at subnormal scale.
  const double s = 5e-324;
  EXPECT_EQ(orient3d(Vec3d{0, 0, 0}, Vec3d{s, 0, 0}, Vec3d{0, s, 0}, Vec3d{0, 0, s}), 1);
  EXPECT_EQ(orient3d(Vec3d{0, 0, 0}, Vec3d{s, 0, 0}, Vec3d{0, s, 0}, Vec3d{0, 0, -s}), -1);
}

TEST(PredicateCases, Orient3dOneUlpAboveAPlane) {
  // d on the plane x + y + z = 3 through integer points, then one ulp above.
  const Vec3d a{3, 0, 0}, b{0, 3, 0}, c{0, 0, 3};
  const Vec3d on{1, 1, 1};
  const Vec3d above{1, 1, std::nextafter(1.0, 2.0)};
  const Vec3d below{1, 1, std::nextafter(1.0, 0.0)};
  EXPECT_EQ(orient3d(a, b, c, on), 0);
  EXPECT_EQ(orient3d(a, b, c, above), 1);
  EXPECT_EQ(orient3d(a, b, c, below), -1);
  // The filter cannot decide these: the perturbation is below its bound.
  EXPECT_FALSE(detail::orient3d_filter(a, b, c, above).has_value());
  EXPECT_FALSE(detail::orient3d_filter(a, b, c, on).has_value());
}

TEST(PredicateCases, NormalsOfSpecialFacets) {
  const Vec3d a0{0, 0, 0}, a1{1, 0, 0}, a2{0, 1, 0};
  const Vec3d t{5, -7, 3};
  auto add = [](Vec3d p, Vec3d q) { return Vec3d{p.x + q.x, p.y + q.y, p.z + q.z}; };
  // Identical normals.
  EXPECT_TRUE(normals_parallel(a0, a1, a2, add(a0, t), add(a1, t), add(a2, t)));
  EXPECT_TRUE(normals_same_direction(a0, a1, a2, add(a0, t), add(a1, t), add(a2, t)));
  EXPECT_EQ(normals_dot_sign(a0, a1, a2, add(a0, t), add(a1, t), add(a2, t)), 1);
  // Opposite normals.
  EXPECT_TRUE(normals_parallel(a0, a1, a2, a0, a2, a1));
  EXPECT_FALSE(normals_same_direction(a0, a1, a2, a0, a2, a1));
  EXPECT_EQ(normals_dot_sign(a0, a1, a2, a0, a2, a1), -1);
  // Orthogonal normals.
  const Vec3d z{0, 0, 1};
  EXPECT_FALSE(normals_parallel(a0, a1, a2, a0, a1, z));
  EXPECT_EQ(normals_dot_sign(a0, a1, a2, a0, a1, z), 0);
  // A degenerate (collinear) facet has the zero normal: parallel to all,
  // same direction as none.
  const Vec3d c2{2, 0, 0};
  EXPECT_TRUE(normals_parallel(a0, a1, c2, a0, a1, a2));
  EXPECT_FALSE(normals_same_direction(a0, a1, c2, a0, a1, a2));
  EXPECT_FALSE(normals_same_direction(a0, a1, a2, a0, a1, c2));
  EXPECT_EQ(normals_dot_sign(a0, a1, c2, a0, a1, a2), 0);
  // Tilted by one ulp: not parallel any more.
  const Vec3d tilt{0, 1, std::nextafter(0.0, 1.0)};
  EXPECT_FALSE(normals_parallel(a0, a1, a2, a0, a1, tilt));
  EXPECT_FALSE(normals_same_direction(a0, a1, a2, a0, a1, tilt));
  const Vec3d tilt2{0, 1, 0x1p-52};
  EXPECT_FALSE(normals_parallel(a0, a1, a2, a0, a1, tilt2));
}

TEST(PredicateCases, SupportEdgeArcDotAlong) {
  const Vec3d a0{0, 0, 0}, a1{1, 0, 0}, a2{0, 1, 0};  // normal +z
  EXPECT_EQ(support_compare(a0, a1, a2, Vec3d{9, 9, 2}, Vec3d{-4, 0, 1}), 1);
  EXPECT_EQ(support_compare(a0, a1, a2, Vec3d{9, 9, 1}, Vec3d{-4, 0, 1}), 0);
  EXPECT_EQ(support_compare(a0, a1, a2, Vec3d{9, 9, 0}, Vec3d{-4, 0, 1}), -1);
  EXPECT_EQ(edge_facet_sign(Vec3d{0, 0, 0}, Vec3d{0, 0, -1}, a0, a1, a2), -1);
  EXPECT_EQ(edge_facet_sign(Vec3d{3, 3, 3}, Vec3d{4, 5, 3}, a0, a1, a2), 0);
  // e_a = x, e_b = y: e_a × e_b = z; n = +z → +1, n = −z → −1.
  const Vec3d o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0};
  EXPECT_EQ(arc_side(o, x, o, y, a0, a1, a2), 1);
  EXPECT_EQ(arc_side(o, x, o, y, a0, a2, a1), -1);
  EXPECT_EQ(arc_side(o, x, o, x, a0, a1, a2), 0);  // e_a ∥ e_b
  EXPECT_EQ(dot_sign(o, x, o, y), 0);
  EXPECT_EQ(dot_sign(o, x, y, Vec3d{2, 1, 0}), 1);
  EXPECT_EQ(compare_along(Vec3d{0, 0, 1}, Vec3d{5, 5, 2}, Vec3d{-3, 8, 1}), 1);
  EXPECT_EQ(compare_along(Vec3d{0, 0, 0}, Vec3d{5, 5, 2}, Vec3d{-3, 8, 1}), 0);
  EXPECT_EQ(compare_along(Vec3d{1, 1, 0}, Vec3d{1, -1, 7}, Vec3d{0, 0, 0}), 0);
}

TEST(PredicateCases, ThirdsAndSevenths) {
  const Rational third(1, 3), seventh(1, 7);
  // Points on the plane x + y + z = 1 with rational coordinates.
  const Point3 a(third, third, third), b(Rational(1), Rational(0), Rational(0)),
      c(Rational(0), Rational(1), Rational(0)), d(seventh, Rational(2, 7), Rational(4, 7));
  EXPECT_EQ(orient3d(a, b, c, d), 0);
  EXPECT_FALSE(detail::orient3d_filter(a, b, c, d).has_value());
  // Moved off the plane by 1e-30 (not a double), either way.
  const Rational tiny(mpz_class(1), mpz_class("1000000000000000000000000000000"));
  const Point3 up(d.x, d.y, d.z + tiny), down(d.x, d.y, d.z - tiny);
  // n(a, b, c) = (b − a) × (c − a) = (1/3)(1, 1, 1): up is on the positive side.
  const QV n = qcross(qsub(b, a), qsub(c, a));
  ASSERT_TRUE(n.x == Rational(1, 3) && n.y == Rational(1, 3) && n.z == Rational(1, 3));
  EXPECT_EQ(orient3d(a, b, c, up), 1);
  EXPECT_EQ(orient3d(a, b, c, down), -1);
  // The rational filter decides an ordinary configuration.
  const Point3 far(Rational(5), third, seventh);
  EXPECT_TRUE(detail::orient3d_filter(a, b, c, far).has_value());
  // compare_along with an exact rational direction.
  const Point3 dir(third, Rational(-2, 3), seventh);
  EXPECT_EQ(compare_along(dir, a, a), 0);
  EXPECT_EQ(compare_along(dir, Point3(Rational(2, 3), Rational(0), Rational(0)), Point3()), 1);
}

TEST(PredicateCases, OverflowingDifferencesFallBack) {
  const Vec3d a{-DBL_MAX, 0, 0}, b{DBL_MAX, 0, 0}, c{0, DBL_MAX, 0}, d{0, 0, DBL_MAX};
  const Approx ap = detail::orient3d_approx(a, b, c, d);
  EXPECT_EQ(ap.status, Approx::kDecline);
  reset_predicate_stats();
  EXPECT_EQ(orient3d(a, b, c, d), 1);
  EXPECT_EQ(predicate_stats()[PredicateId::orient3d].fallbacks, 1u);
  // Same magnitude without overflowing differences: rescaled, decided.
  const Vec3d e{DBL_MAX / 2, 0, 0}, f{0, DBL_MAX / 2, 0}, h{0, 0, DBL_MAX / 2};
  EXPECT_EQ(detail::orient3d_filter(Vec3d{0, 0, 0}, e, f, h), std::optional<int>(1));
}

// ---------------------------------------------------------------------------
// The constants and the conversion.

TEST(PredicateConstants, DominateTheDerivedBounds) {
  // T · γ_N · (1 + 2^-20) in exact arithmetic, γ_n = n ε / (1 − n ε), ε = 2^-52.
  const Rational u(mpz_class(1), mpz_class(1) << 52);
  const Rational slack = 1 + Rational(mpz_class(1), mpz_class(1) << 20);
  auto gamma = [&](int n) { return Rational(n * u / (1 - n * u)); };
  for (const detail::FilterShape* s : detail::kShapes) {
    SCOPED_TRACE(s->name);
    EXPECT_GE(Rational(s->c_vec), s->terms * gamma(s->ops_vec) * slack);
    EXPECT_GE(Rational(s->c_rat), s->terms * gamma(s->ops_rat) * slack);
    EXPECT_GE(Rational(s->c_dyn), gamma(s->ops_vec) * slack);
    EXPECT_LE(Rational(s->c_dyn), gamma(s->ops_vec) * slack * Rational(1000001, 1000000));
    // The constants are not wastefully large either (within 1e-6 relative).
    EXPECT_LE(Rational(s->c_vec),
              s->terms * gamma(s->ops_vec) * slack * Rational(1000001, 1000000));
    // Range: c lo^K ≥ 2^-1010 (no underflow in the bound, underflow errors
    // negligible) and T · 2 · hi^K ≤ 2^1005 (no overflow).
    Rational lo_k = 1, hi_k = 1;
    for (int k = 0; k < s->degree; ++k) lo_k *= Rational(s->lo), hi_k *= Rational(s->hi);
    Rational two_m1010(mpz_class(1), mpz_class(1) << 1010);
    EXPECT_GE(Rational(s->c_vec) * lo_k, two_m1010);
    EXPECT_GE(Rational(s->c_rat) * lo_k, two_m1010);
    EXPECT_LE(hi_k, Rational(mpz_class(1) << 1000));
  }
  // Monomial and rounding counts, recounted from the expression trees.
  EXPECT_EQ(detail::kShapeDet3.terms, 6);  // 3! signed permutations
  EXPECT_EQ(detail::kShapeDcc.terms, 12);  // 3 coordinates × 2 × 2
  EXPECT_EQ(detail::kShapeCcc.terms, 8);   // 2 × 2 × 2
  EXPECT_EQ(detail::kShapeDot.terms, 3);
  EXPECT_EQ(detail::kShapeDet3.ops_vec, 3 + 2 + 1 + 2);
  EXPECT_EQ(detail::kShapeDcc.ops_vec, 4 + 2 + 2 + 1 + 2);
  EXPECT_EQ(detail::kShapeCcc.ops_vec, 4 + 2 + 2 + 1 + 1);
  EXPECT_EQ(detail::kShapeDot.ops_vec, 2 + 1 + 2);
  EXPECT_EQ(detail::kShapeAlong.ops_vec, 1 + 1 + 2);
}

TEST(PredicateConversion, RationalToFilterDoubleBound) {
  Gen g(kSeed + 40);
  const Rational eps(detail::kConvEps);
  for (int i = 0; i < 20000; ++i) {
    Rational q;
    switch (i % 4) {
      case 0:
        q = small_rational(g, 1000000, 1000000);
        break;
      case 1: {  // random big numerator and denominator
        mpz_class n(static_cast<long>(g.bits() >> 1)), d(static_cast<long>((g.bits() >> 2) | 1));
        n <<= int(g.integer(0, 600));
        d <<= int(g.integer(0, 600));
        q = Rational(n, d);
        if (g.coin()) q = -q;
        q.canonicalize();
        break;
      }
      case 2:
        q = Rational(g.wild(-1021, 1022));
        break;  // exactly a double
      default:
        q = Rational(g.wild(-1074, 1023)) + small_rational(g);
    }
    SCOPED_TRACE(format_exact(q));
    double out = 0;
    bool exact = false;
    if (!detail::rational_to_filter_double(q, out, exact)) {
      // Declined only outside the normal range.
      EXPECT_TRUE(abs(q) < Rational(0x1p-1021) || abs(q) > Rational(0x1p1022));
      continue;
    }
    EXPECT_LE(abs(Rational(out) - q), eps * abs(Rational(out)));
    EXPECT_EQ(exact, Rational(out) == q);
    if (i % 4 == 2) {
      EXPECT_TRUE(exact);
    }
  }
  double out = 1;
  bool exact = false;
  EXPECT_TRUE(detail::rational_to_filter_double(Rational(0), out, exact));
  EXPECT_EQ(out, 0.0);
  EXPECT_TRUE(exact);
}

// ---------------------------------------------------------------------------
// Statistics.

TEST(PredicateStatsTest, CountsCallsAndFallbacks) {
  reset_predicate_stats();
  EXPECT_EQ(predicate_stats().total().calls, 0u);
  const Vec3d a{3, 0, 0}, b{0, 3, 0}, c{0, 0, 3};
  orient3d(a, b, c, Vec3d{5, 5, 5});                         // filter decides
  orient3d(a, b, c, Vec3d{1, 1, std::nextafter(1.0, 2.0)});  // falls back
  orient3d(a, b, c, Vec3d{1, 1, 1});                         // exact zero: falls back
  orient3d(a, a, c, Vec3d{1, 1, 1});                         // zero vector: filter
  dot_sign(a, b, a, c);
  const PredicateStats s = predicate_stats();
  EXPECT_EQ(s[PredicateId::orient3d].calls, 4u);
  EXPECT_EQ(s[PredicateId::orient3d].fallbacks, 2u);
  EXPECT_DOUBLE_EQ(s[PredicateId::orient3d].fallback_ratio(), 0.5);
  EXPECT_EQ(s[PredicateId::dot_sign].calls, 1u);
  EXPECT_EQ(s.total().calls, 5u);
  EXPECT_STREQ(predicate_name(PredicateId::normals_same_direction), "normals_same_direction");
  reset_predicate_stats();
  EXPECT_EQ(predicate_stats().total().calls, 0u);
}

TEST(PredicateStatsTest, CountersArePerThread) {
  reset_predicate_stats();
  std::uint64_t other_calls = 0;
  std::thread worker([&] {
    const Vec3d a{3, 0, 0}, b{0, 3, 0}, c{0, 0, 3};
    for (int i = 0; i < 10; ++i) orient3d(a, b, c, Vec3d{1, 1, 1});
    other_calls = predicate_stats()[PredicateId::orient3d].calls;
  });
  worker.join();
  EXPECT_EQ(other_calls, 10u);
  EXPECT_EQ(predicate_stats()[PredicateId::orient3d].calls, 0u);
}

// ---------------------------------------------------------------------------
// Cost of the stages (reported, not asserted).

TEST(PredicateTiming, Report) {
  Gen g(kSeed + 50);
  const int n = 4096;
  std::vector<std::array<Vec3d, 4>> pts(n);
  std::vector<std::array<Point3, 4>> rat(n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 4; ++k) {
      pts[i][k] = g.uvec();
      rat[i][k] = rational_point(g);
    }
  }
  using clock = std::chrono::steady_clock;
  auto time = [&](const char* what, auto&& f) {
    const int reps = 20;
    long sink = 0;
    const auto t0 = clock::now();
    for (int r = 0; r < reps; ++r)
      for (int i = 0; i < n; ++i) sink += f(i);
    const double ns =
        std::chrono::duration<double, std::nano>(clock::now() - t0).count() / (reps * n);
    std::cout << "[ timing   ] " << std::left << std::setw(44) << what << std::right << std::fixed
              << std::setprecision(1) << std::setw(9) << ns << " ns/call  (" << sink % 2 << ")\n";
  };
  time("orient3d Vec3d (filter)",
       [&](int i) { return orient3d(pts[i][0], pts[i][1], pts[i][2], pts[i][3]); });
  time("orient3d Vec3d exact stage",
       [&](int i) { return detail::orient3d_exact(pts[i][0], pts[i][1], pts[i][2], pts[i][3]); });
  time("orient3d Point3 small rationals (filter)",
       [&](int i) { return orient3d(rat[i][0], rat[i][1], rat[i][2], rat[i][3]); });
  time("orient3d Point3 small rationals exact stage",
       [&](int i) { return detail::orient3d_exact(rat[i][0], rat[i][1], rat[i][2], rat[i][3]); });
  time("orient3d mpq oracle (textbook)", [&](int i) {
    const std::array<Point3, 4>& r = rat[i];
    return sgn(qdet(qsub(r[1], r[0]), qsub(r[2], r[0]), qsub(r[3], r[0])));
  });
  time("arc_side Vec3d (filter)", [&](int i) {
    return arc_side(pts[i][0], pts[i][1], pts[i][2], pts[i][3], pts[i][0], pts[i][2], pts[i][1]);
  });
  time("arc_side Vec3d exact stage", [&](int i) {
    return detail::arc_side_exact(pts[i][0], pts[i][1], pts[i][2], pts[i][3], pts[i][0], pts[i][2],
                                  pts[i][1]);
  });
}

}  // namespace

// Plane::side against the rational value of a·x + b·y + c·z − d: random
// integer planes and points whose three coordinates have different, large
// denominators, points exactly on the plane (made from it), and signs of
// every kind.
TEST(PlaneSide, IsTheSignOfTheRationalValue) {
  std::mt19937_64 rng(40);
  auto big = [&](int limbs) {
    Integer x = 0;
    for (int i = 0; i < limbs; ++i) x = x * Integer("18446744073709551616") + Integer(std::to_string(rng()));
    return (rng() & 1) ? Integer(-x) : x;
  };
  auto positive = [&](int limbs) {
    Integer x = big(limbs);
    x = abs(x) + 1;
    return x;
  };
  int signs[3] = {0, 0, 0};
  for (int round = 0; round < 400; ++round) {
    const int limbs = 1 + round % 5;
    Plane h;
    h.a = big(limbs);
    h.b = big(limbs);
    h.c = big(1 + (round + 2) % 5);
    h.d = big(limbs + 1);
    if (sgn(h.c) == 0) h.c = 1;
    Rational x(big(limbs), positive(limbs)), y(big(limbs + 1), positive(limbs + 2)), z;
    x.canonicalize();
    y.canonicalize();
    if (round % 3 == 0) {
      z = (Rational(h.d) - Rational(h.a) * x - Rational(h.b) * y) / Rational(h.c);  // on the plane
    } else {
      z = Rational(big(limbs), positive(1 + round % 4));
      z.canonicalize();
    }
    const Point3 p(x, y, z);
    const int want = sgn(Rational(h.a) * x + Rational(h.b) * y + Rational(h.c) * z - Rational(h.d));
    ASSERT_EQ(h.side(p), want) << "round " << round;
    ++signs[want + 1];
  }
  EXPECT_GT(signs[0], 0);
  EXPECT_GT(signs[1], 0);
  EXPECT_GT(signs[2], 0);
}
