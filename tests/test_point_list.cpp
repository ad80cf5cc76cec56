// The lazy-exact data model: coordinates in their cheapest exact form
// (PointList), exact text and floats printed from doubles' mantissas, the
// exact pairs of a Minkowski sum of double operands, planes and exact points
// computed on demand (also from several threads), and the dyadic volume.
// Every cheap representation is checked against plain GMP rationals.
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gtest/gtest.h>
#include <minksum/half_space_side.hpp>
#include <mpfr.h>

#include <atomic>
#include <cfenv>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <thread>

#include "io/readers.hpp"
#include "kernel/big_array.hpp"
#include "kernel/plane.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

// A double drawn over a wide range of magnitudes and signs, with exact zeros,
// integers and subnormals now and then.
double wild_double(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 9), ex(-1070, 1020), small_ex(-60, 60);
  std::uniform_real_distribution<double> m(1.0, 2.0);
  std::bernoulli_distribution neg(0.5);
  double v;
  switch (kind(rng)) {
    case 0: v = 0.0; break;
    case 1: v = double(std::uniform_int_distribution<long>(-1000000, 1000000)(rng)); break;
    case 2: v = std::ldexp(double(std::uniform_int_distribution<int>(1, 1 << 20)(rng)), -1074); break;  // subnormal
    case 3: v = std::ldexp(m(rng), ex(rng)); break;
    default: v = std::ldexp(m(rng), small_ex(rng)); break;
  }
  return neg(rng) ? -v : v;
}

void two_sum(double x, double y, double& s, double& e) {
  s = x + y;
  const double yv = s - x;
  const double xv = s - yv;
  e = (x - xv) + (y - yv);
}

Rational exact_of(const std::string& text) {
  auto q = parse_number(text);
  EXPECT_TRUE(q.has_value()) << text;
  return q ? *q : Rational(0);
}

}  // namespace

TEST(PointList, FormsFollowTheData) {
  PointList l;
  EXPECT_EQ(l.form(), PointList::Form::doubles);
  l.push_back(Vec3d{1.5, -0.0, 3});
  l.push_back(Point3(Rational(1, 4), Rational(2), Rational(-8)));  // a rational that is a double
  EXPECT_EQ(l.form(), PointList::Form::doubles);
  EXPECT_TRUE(l.all_doubles());
  EXPECT_TRUE(std::signbit(l.approx(0).y) == false) << "zeros are stored unsigned";
  l.push_pair(Vec3d{1.0, 2.0, 3.0}, Vec3d{0x1p-60, 0.0, -0x1p-70});
  EXPECT_EQ(l.form(), PointList::Form::double_pairs);
  EXPECT_FALSE(l.all_doubles());
  EXPECT_FALSE(l.is_double(2));
  EXPECT_TRUE(l.is_double(1));
  EXPECT_EQ(l.exact(2).x, Rational(1) + Rational(0x1p-60));
  EXPECT_EQ(l.exact(2).z, Rational(3) - Rational(0x1p-70));
  l.push_back(Point3(Rational(1, 3), Rational(0), Rational(0)));
  EXPECT_EQ(l.form(), PointList::Form::rationals);
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l.exact(0), Point3(Rational(3, 2), Rational(0), Rational(3)));
  EXPECT_EQ(l.exact(2).x, Rational(1) + Rational(0x1p-60));  // promotion kept every point exactly
  EXPECT_EQ(l.exact_ref(3).x, Rational(1, 3));
  EXPECT_EQ(l.approx(3).x, to_double(Rational(1, 3)));
  // set() back to doubles everywhere: the count of non-doubles follows.
  l.set(2, P(1, 2, 3));
  l.set(3, P(0, 0, 0));
  EXPECT_TRUE(l.all_doubles());
  PointList d{P(1, 0, 0), P(0, 2, 0)};
  d.negate();
  EXPECT_EQ(d.exact(1), P(0, -2, 0));
  EXPECT_FALSE(std::signbit(d.approx(0).y));
}

TEST(PointList, EqualityAcrossForms) {
  PointList a{P(1, 2, 3), Q("1/3", "0", "1")};
  PointList b;
  b.push_back(Point3(1.0, 2.0, 3.0));
  b.push_back(Point3(Rational(1, 3), Rational(0), Rational(1)));
  EXPECT_TRUE(a == b);
  b.set(1, Q("1/3", "0", "2"));
  EXPECT_FALSE(a == b);
}

TEST(ExactText, DyadicMatchesRationalOnRandomDoublesAndPairs) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 500; ++i) {
      const double x = wild_double(rng), y = wild_double(rng);
      std::string one;
      append_exact_dyadic(one, x);
      ASSERT_EQ(one, format_exact(Rational(x))) << "seed " << seed << " x " << x;
      double hi, lo;
      two_sum(x, y, hi, lo);
      if (!std::isfinite(hi)) continue;
      std::string two;
      append_exact_dyadic(two, hi, lo);
      ASSERT_EQ(two, format_exact(Rational(x) + Rational(y))) << "seed " << seed << " x " << x << " y " << y;
      ASSERT_EQ(exact_of(two), Rational(x) + Rational(y)) << "seed " << seed;
    }
  }
  std::string s;
  append_exact_dyadic(s, -0.0);
  EXPECT_EQ(s, "0");
  s.clear();
  append_exact_dyadic(s, std::numeric_limits<double>::max());
  EXPECT_EQ(s, format_exact(Rational(std::numeric_limits<double>::max())));
  s.clear();
  append_exact_dyadic(s, std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(s, format_exact(Rational(std::numeric_limits<double>::denorm_min())));
}

TEST(ExactText, NearestFloatOfPairsAtFloatMidpoints) {
  // hi exactly halfway between two floats: lo decides; elsewhere hi's nearest float.
  for (float f : {1.0f, 3.5f, 1e-40f, -7.25e20f, 1.17549435e-38f}) {
    const float g = std::nextafter(f, std::numeric_limits<float>::infinity());
    const double mid = (double(f) + double(g)) / 2;
    for (double lo : {0x1p-80 * std::fabs(mid), -0x1p-80 * std::fabs(mid), 0.0}) {
      if (lo != 0 && std::fabs(lo) >= std::fabs(mid) * 0x1p-54) continue;
      PointList l;
      l.push_pair(Vec3d{mid, 1.0, 1.0}, Vec3d{lo, 0.0, 0.0});
      const Rational exact = Rational(mid) + Rational(lo);
      EXPECT_EQ(io_detail::coordinate_float(l, 0, 0), io_detail::checked_float(exact)) << f << " lo " << lo;
    }
  }
  std::mt19937_64 rng(7);
  for (int i = 0; i < 5000; ++i) {
    const double x = std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng), int(rng() % 200) - 100);
    const double y = std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng), int(rng() % 200) - 100);
    double hi, lo;
    two_sum(x, y, hi, lo);
    PointList l;
    l.push_pair(Vec3d{hi, 0.0, 0.0}, Vec3d{lo, 0.0, 0.0});
    ASSERT_EQ(io_detail::coordinate_float(l, 0, 0), io_detail::checked_float(Rational(x) + Rational(y)))
        << "seed 7, case " << i;
  }
}

// Binary STL's floats are the nearest floats of the exact coordinates in
// every rounding mode (the double -> float conversion rounds in the current
// mode, so a directed mode gave the float beside the nearest one).
TEST(ExactText, NearestFloatInEveryRoundingMode) {
  std::mt19937_64 rng(11);
  std::vector<double> xs = {0x1.000001p0, -0x1.000003p0, 0x1.0000018p-130, 3.4028234663852886e38, 1e-45, 0.1};
  for (int i = 0; i < 2000; ++i)
    xs.push_back(std::ldexp(std::uniform_real_distribution<double>(-2, 2)(rng), int(rng() % 270) - 150));
  for (const double x : xs) {
    const float want = static_cast<float>(x);  // to nearest: the mode of the tests
    PointList doubles, pairs, rationals;
    doubles.push_back(Vec3d{x, 0.0, 0.0});
    pairs.push_pair(Vec3d{x, 1.0, 1.0}, Vec3d{0.0, 0.0, 0.0});
    rationals.push_back(Point3(Rational(1, 3), Rational(0), Rational(0)));  // the list holds rationals
    rationals.push_back(Point3(Rational(x), Rational(0), Rational(0)));
    for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      struct Mode {  // restored even when a conversion throws
        int old;
        explicit Mode(int m) : old(std::fegetround()) { std::fesetround(m); }
        ~Mode() { std::fesetround(old); }
      };
      float a, b, c, d;
      {
        const Mode directed(mode);
        a = io_detail::coordinate_float(doubles, 0, 0);
        b = io_detail::coordinate_float(pairs, 0, 0);
        c = io_detail::coordinate_float(rationals, 1, 0);
        d = to_float(Rational(x));
      }
      ASSERT_EQ(a, want) << "seed 11, x " << x << ", mode " << mode;
      ASSERT_EQ(b, want) << "seed 11, x " << x << ", mode " << mode;
      ASSERT_EQ(c, want) << "seed 11, x " << x << ", mode " << mode;
      ASSERT_EQ(d, want) << "seed 11, x " << x << ", mode " << mode;
    }
  }
}

TEST(ReadCoordinate, CheapFormAgreesWithParseNumber) {
  const char* tokens[] = {"0",      "-0",     "-0.0",      "12",   "123456789012345", "9007199254740993",
                          "-9007199254740993",  "1e-400",    "5e-324", "0.1",   "-2.5e-3",
                          "1/3",    "4/-8",     "0x1.8p-3",  "+7",   "1E300", ".5",   "5.",
                          "12345678901234567890123"};
  for (const char* t : tokens) {
    io_detail::Coordinate c = io_detail::read_coordinate(t, "test", 1);
    const Rational want = *parse_number(t);
    if (c.exact) {
      EXPECT_EQ(*c.exact, want) << t;
      EXPECT_FALSE(is_double(want)) << t << " is a double but was kept as a rational";
    } else {
      EXPECT_EQ(Rational(c.d), want) << t;
    }
  }
}

TEST(SumCoordinates, DoublePairsAreTheExactSums) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    PointList a, b;
    for (int i = 0; i < 50; ++i) {
      a.push_back(Vec3d{wild_double(rng), wild_double(rng), wild_double(rng)});
      b.push_back(Vec3d{wild_double(rng), wild_double(rng), wild_double(rng)});
    }
    std::vector<std::pair<Index, Index>> pairs;
    for (Index i = 0; i < 50; ++i)
      for (Index j = 0; j < 50; j += 7) pairs.emplace_back(i, j);
    const PointList s = sum_coordinates(pairs, a, b);
    ASSERT_EQ(s.size(), pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Point3 want = a.exact(pairs[k].first) + b.exact(pairs[k].second);
      ASSERT_EQ(s.exact(k), want) << "seed " << seed << " pair " << k;
      ASSERT_EQ(s.approx(k).x, to_double(want.x)) << "seed " << seed << ": approx must be the nearest double";
      ASSERT_EQ(s.is_double(k), is_double(want)) << "seed " << seed;
    }
  }
}

TEST(SumCoordinates, OverflowAndDirectedRoundingFallBackToRationals) {
  PointList a{Point3(1e308, 1.0, 0.0)}, b{Point3(1e308, 0x1p-80, 0.0)};
  const PointList s = sum_coordinates({{0, 0}}, a, b);
  EXPECT_EQ(s.form(), PointList::Form::rationals);
  EXPECT_EQ(s.exact(0).x, Rational(1e308) * 2);
  EXPECT_EQ(s.exact(0).y, Rational(1) + Rational(0x1p-80));
  // TwoSum needs round-to-nearest: in any other mode the exact path is taken.
  PointList c{Point3(1.0, 0.1, 3.0)}, d{Point3(0x1p-70, 0.2, 0.0)};
  const int old = std::fegetround();
  std::fesetround(FE_UPWARD);
  const PointList u = sum_coordinates({{0, 0}}, c, d);
  std::fesetround(old);
  EXPECT_EQ(u.form(), PointList::Form::rationals);
  EXPECT_EQ(u.exact(0), c.exact(0) + d.exact(0));
}

// Every form of polytope: its lazily computed planes equal the canonical
// plane of an exact normal computed here from the exact points.
TEST(LazyPlanes, AgreeWithExactPlanesInEveryForm) {
  const ConvexPolytope dbl = catalog_polytope("sphere:3");
  const ConvexPolytope rat = catalog_polytope("cube@rot:7");
  const SumResult sum = minkowski_sum(catalog_polytope("dodecahedron"), catalog_polytope("sphere:2@scale:1/1024"),
                                      Method::walk);
  ASSERT_EQ(dbl.coordinates().form(), PointList::Form::doubles);
  ASSERT_EQ(rat.coordinates().form(), PointList::Form::rationals);
  ASSERT_EQ(sum.polytope.coordinates().form(), PointList::Form::double_pairs);
  for (const ConvexPolytope* p : {&dbl, &rat, &sum.polytope}) {
    for (Index f = 0; f < p->num_facets(); ++f) {
      const auto vs = p->facet_vertices(f);
      const Point3 n = cross(p->point(vs[1]) - p->point(vs[0]), p->point(vs[2]) - p->point(vs[0]));
      ASSERT_EQ(p->plane(f), canonical_plane(n, p->point(vs[0]))) << "facet " << f;
      for (Index v : vs) ASSERT_EQ(p->plane(f).side(p->point(v)), 0);
    }
    EXPECT_EQ(p->check_invariants(), "");
  }
}

// The integer construction of the sweep's planes (triangle_sum.cpp) against
// the rational one: the plane with normal n through p + q, and the positive
// multiple of q - p; random rationals with small and large denominators,
// doubles included.
TEST(CanonicalPlane, ThroughSumInIntegersEqualsRational) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    auto rational = [&]() -> Rational {
      switch (rng() % 3) {
        case 0: return Rational(long(rng() % 2001) - 1000);
        case 1: return Rational(wild_double(rng));
        default: {
          Rational r(long(rng() % 200001) - 100000, long(rng() % 9999) + 1);
          r.canonicalize();
          return r;
        }
      }
    };
    auto point = [&] { return Point3(rational(), rational(), rational()); };
    for (int i = 0; i < 200; ++i) {
      const Point3 p = point(), q = point(), r = point();
      const ScaledPoint sp = scaled_point(p), sq = scaled_point(q), sr = scaled_point(r);
      for (int k = 0; k < 3; ++k) {
        Rational x(sp.num[k], sp.den);
        x.canonicalize();
        ASSERT_EQ(x, p[k]) << "seed " << seed << ", case " << i;
      }
      Integer d[3];
      scaled_difference(sp, sq, d);
      const Point3 qp = q - p;
      if (is_zero(qp)) continue;
      // A positive multiple: d = k (q - p) with k > 0.
      const Point3 dd{Rational(d[0]), Rational(d[1]), Rational(d[2])};
      ASSERT_TRUE(is_zero(cross(dd, qp))) << "seed " << seed << ", case " << i;
      ASSERT_GT(sgn(dot(dd, qp)), 0) << "seed " << seed << ", case " << i;
      ASSERT_EQ(canonical_plane_through_sum(d, sq, sr), canonical_plane(qp, q + r)) << "seed " << seed << ", case " << i;
    }
  }
}

// truncated_ratio is a faithful rounding towards zero of X / W: never
// beyond the quotient, within relative 2^-52 of it, over numerators and
// denominators from 1 to 700 bits and quotients from 2^-700 to 2^700.
TEST(TruncatedRatio, FaithfulTowardsZero) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(seed);
    gmp_randclass gen(gmp_randinit_default);
    gen.seed(seed);
    for (int i = 0; i < 2000; ++i) {
      const unsigned bx = 1 + unsigned(rng() % 700), bw = 1 + unsigned(rng() % 700);
      Integer X = gen.get_z_bits(bx), W = gen.get_z_bits(bw) + 1;
      if (rng() % 2) X = -X;
      if (rng() % 7 == 0) X = 0;
      const double r = truncated_ratio(X, W);
      Rational q(X, W);
      q.canonicalize();
      if (sgn(q) == 0) {
        ASSERT_EQ(r, 0.0) << "seed " << seed << ", case " << i;
        continue;
      }
      if (!(std::fabs(r) >= 0x1p-1022) || !std::isfinite(r)) continue;  // outside the normal range
      const Rational rr(r);
      ASSERT_EQ(sgn(rr), sgn(q)) << "seed " << seed << ", case " << i;
      ASSERT_LE(cmp(abs(rr), abs(q)), 0) << "seed " << seed << ", case " << i;  // towards zero
      const Rational err = abs(Rational(q - rr));
      ASSERT_LT(cmp(err, abs(q) * Rational(1, Integer(1) << 52)), 0) << "seed " << seed << ", case " << i;
    }
  }
}

// plane_filter_doubles: the doubles are faithful roundings towards zero of
// one positive multiple 2^-k of the plane's integers (the same k for all
// four), below 2^480 whatever the integers' length (up to 3 000 bits here),
// and the half-space filter on them never contradicts the exact side of the
// plane itself; on points well off the plane it decides.  Planes through
// points of a thousand bits and more are what an erosion's vertices give.
TEST(PlaneFilterDoubles, AScaledPlaneKeepsTheSideAndTheFilterDecides) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937_64 rng(seed);
    gmp_randclass gen(gmp_randinit_default);
    gen.seed(seed);
    int decided = 0, off = 0;
    for (int i = 0; i < 1500; ++i) {
      const unsigned bits = 1 + unsigned(rng() % 3000);
      Integer c[4];
      for (Integer& x : c) {
        x = gen.get_z_bits(bits - unsigned(rng() % std::min<unsigned>(bits, 40)));
        if (rng() % 2) x = -x;
        if (rng() % 11 == 0) x = 0;
      }
      if (sgn(c[0]) == 0 && sgn(c[1]) == 0 && sgn(c[2]) == 0) c[2] = 1;
      double out[4];
      const bool usable = plane_filter_doubles(c[0], c[1], c[2], c[3], out);
      // One common scale 2^-k, k >= 0, each double a truncation of c_i 2^-k.
      std::size_t top = 0;
      for (const Integer& x : c)
        if (sgn(x) != 0) top = std::max(top, mpz_sizeinbase(x.get_mpz_t(), 2));
      const long k = top >= 480 ? long(top) - 470 : 0;
      for (int j = 0; j < 4; ++j) {
        ASSERT_TRUE(std::isfinite(out[j])) << "seed " << seed << ", case " << i;
        ASSERT_LT(std::fabs(out[j]), 0x1p480) << "seed " << seed << ", case " << i;
        if (sgn(c[j]) == 0) {
          ASSERT_EQ(out[j], 0.0) << "seed " << seed << ", case " << i;
          continue;
        }
        if (out[j] == 0.0) {
          ASSERT_FALSE(usable) << "seed " << seed << ", case " << i;
          continue;
        }
        Rational scaled(c[j]);
        mpq_div_2exp(scaled.get_mpq_t(), scaled.get_mpq_t(), mp_bitcnt_t(k));
        const Rational r(out[j]);
        ASSERT_EQ(sgn(r), sgn(c[j])) << "seed " << seed << ", case " << i;
        ASSERT_LE(cmp(abs(r), abs(scaled)), 0) << "seed " << seed << ", case " << i;
        ASSERT_LT(cmp(abs(Rational(scaled - r)), abs(scaled) * Rational(1, Integer(1) << 52)), 0)
            << "seed " << seed << ", case " << i;
        if (usable) {
          ASSERT_GE(std::fabs(out[j]), 0x1p-480) << "seed " << seed << ", case " << i;
        }
      }
      if (!usable) continue;
      // Points: on the plane (a rational solution), and moved off it along the
      // normal by a relative 2^-30 (or -2^-30), or at random.
      Point3 p;
      int axis = sgn(c[0]) != 0 ? 0 : sgn(c[1]) != 0 ? 1 : 2;
      Rational coord[3] = {Rational(gen.get_z_bits(64)) / Rational(gen.get_z_bits(40) + 1),
                           Rational(gen.get_z_bits(64)) / Rational(gen.get_z_bits(40) + 1),
                           Rational(gen.get_z_bits(64)) / Rational(gen.get_z_bits(40) + 1)};
      Rational rest = c[3];
      for (int j = 0; j < 3; ++j)
        if (j != axis) rest -= c[j] * coord[j];
      coord[axis] = rest / c[axis];
      const int kind = int(rng() % 3);
      if (kind == 1 || kind == 2) {
        // 2^-30 of the terms' magnitudes, so the value is well above the
        // filter's bound (2^-48 of them).
        Rational terms = abs(Rational(c[3]));
        for (int j = 0; j < 3; ++j) terms += abs(Rational(c[j] * coord[j]));
        const Rational shift = terms / (abs(Rational(c[axis])) * Rational(Integer(1) << 30));
        coord[axis] += (kind == 1 ? shift : -shift) * sgn(c[axis]);
        ++off;
      }
      p = Point3{coord[0], coord[1], coord[2]};
      const int exact = sgn(Rational(c[0] * p.x + c[1] * p.y + c[2] * p.z - c[3]));
      const Vec3d pd = to_double(p);
      if (!half_space_filter_usable(pd.x, p.x) || !half_space_filter_usable(pd.y, p.y) ||
          !half_space_filter_usable(pd.z, p.z))
        continue;
      const auto s = half_space_side_filter(out[0], out[1], out[2], out[3], pd.x, pd.y, pd.z);
      if (s) {
        ASSERT_EQ(*s, exact) << "seed " << seed << ", case " << i;
        if (kind != 0) ++decided;
      }
      if (kind == 0) {
        ASSERT_EQ(exact, 0) << "seed " << seed << ", case " << i;
      }
    }
    // The points off the plane by a relative 2^-30 are decided by the doubles.
    EXPECT_GE(decided * 10, off * 9) << "seed " << seed;
  }
}

TEST(LazyVolume, DyadicEqualsRational) {
  const SumResult sum = minkowski_sum(catalog_polytope("cube"), catalog_polytope("sphere:2@scale:1/1024"), Method::walk);
  const ConvexPolytope& s = sum.polytope;
  ASSERT_EQ(s.coordinates().form(), PointList::Form::double_pairs);
  Rational six = 0;
  const Point3& o = s.point(0);
  for (Index f = 0; f < s.num_facets(); ++f) {
    auto vs = s.facet_vertices(f);
    for (std::size_t i = 1; i + 1 < vs.size(); ++i)
      six += dot(s.point(vs[0]) - o, cross(s.point(vs[i]) - o, s.point(vs[i + 1]) - o));
  }
  EXPECT_EQ(s.volume(), six / 6);
  const ConvexPolytope big = catalog_polytope("cube@scale:1e300");
  EXPECT_EQ(big.volume(), Rational(8) * Rational(1e300) * Rational(1e300) * Rational(1e300));
}

// sum_volume (mixed volumes from the operands and the facets' provenance)
// against the sum's own volume, for every method's provenance: pairs with
// parallel facets (facet ⊕ facet), parallel edges, translated facets and
// corners; random hulls of doubles at scales 2^-40 to 2^30; and operands
// with rational coordinates (it returns the sum's own volume then).  Fixed
// seed.
TEST(LazyVolume, SumVolumeByMixedVolumesEqualsTheSumsOwn) {
  std::mt19937_64 rng(20261124);
  std::normal_distribution<double> g;
  auto random_hull = [&](int n, int scale) {
    PointList pts;
    for (int i = 0; i < n; ++i)
      pts.push_back(Vec3d{std::ldexp(g(rng), scale), std::ldexp(g(rng), scale), std::ldexp(g(rng), scale)});
    return ConvexPolytope::hull(pts);
  };
  std::vector<std::pair<ConvexPolytope, ConvexPolytope>> pairs = {
      {catalog_polytope("cube"), catalog_polytope("cube")},
      {catalog_polytope("cube"), catalog_polytope("octahedron")},
      {catalog_polytope("tetrahedron"), catalog_polytope("tetrahedron").negated()},
      {catalog_polytope("cube"), catalog_polytope("sphere:3")},
      {catalog_polytope("box:1:2:3"), catalog_polytope("sphere:2@translate:5,-7,1")},
      {catalog_polytope("cube"), catalog_polytope("box:1:2:3@rot:1")},
      {catalog_polytope("sphere:2"), catalog_polytope("sphere:2@rot:1")},
  };
  for (int i = 0; i < 6; ++i) pairs.push_back({random_hull(10 + i * 7, -40 + 14 * i), random_hull(30, 2 * i)});
  int fast = 0, with_provenance = 0;
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    const auto& [a, b] = pairs[n];
    const bool doubles = a.coordinates().all_doubles() && b.coordinates().all_doubles();
    for (Method m : {Method::walk, Method::chms, Method::cvms, Method::essdms, Method::mssd, Method::cgm}) {
      const SumResult r = minkowski_sum(a, b, m);
      const bool tracked = r.facet_provenance.size() == r.polytope.num_facets();
      with_provenance += tracked;
      fast += tracked && doubles;
      EXPECT_EQ(sum_volume(a, b, r), r.polytope.volume()) << "pair " << n << ", " << method_name(m);
    }
  }
  EXPECT_GE(with_provenance, int(2 * pairs.size()));  // walk's and at least one other method's
  EXPECT_GE(fast, 20);
  // Without provenance: the sum's own volume.
  SumResult r = minkowski_sum(pairs[3].first, pairs[3].second);
  r.facet_provenance.clear();
  EXPECT_EQ(sum_volume(pairs[3].first, pairs[3].second, r), r.polytope.volume());
}

// release(v) frees v's buffer; `v = {}` would not (it picks the
// initializer_list assignment, which keeps the capacity): the case of the
// edge-sorting array that validation meant to free before making the
// half-edge arrays, and held to the end instead.
TEST(BigArray, ReleaseFreesTheBufferWhereAssigningBracesDoesNot) {
  std::vector<Index> v = big_array<Index>(100000, 7);
  v = {};
  EXPECT_TRUE(v.empty());
  EXPECT_GE(v.capacity(), 100000u);  // still held
  release(v);
  EXPECT_EQ(v.capacity(), 0u);
}

// The array of plane slots is made on the first plane asked for: a
// polytope copied before any plane, then asked from both copies at once.
TEST(LazyCache, PlanesFirstAskedFromTwoCopiesAtOnce) {
  const ConvexPolytope p = catalog_polytope("sphere:3@rot:2"), q = p;
  std::vector<Plane> planes[2];
  std::thread t([&] {
    for (Index f = 0; f < q.num_facets(); ++f) planes[1].push_back(q.plane(f));
  });
  for (Index f = 0; f < p.num_facets(); ++f) planes[0].push_back(p.plane(f));
  t.join();
  EXPECT_EQ(planes[0], planes[1]);
  const ConvexPolytope fresh = catalog_polytope("sphere:3@rot:2");
  for (Index f = 0; f < fresh.num_facets(); ++f) ASSERT_EQ(planes[0][f], fresh.plane(f)) << f;
}

TEST(LazyCache, ConcurrentReadersGetTheSameAnswers) {
  const SumResult sum = minkowski_sum(catalog_polytope("sphere:3"), catalog_polytope("sphere:3@rot:1"), Method::walk);
  const ConvexPolytope copy = sum.polytope;  // copies share the cache
  std::vector<Plane> planes[4];
  std::vector<Point3> points[4];
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      const ConvexPolytope& p = t % 2 ? copy : sum.polytope;
      for (Index f = 0; f < p.num_facets(); ++f) planes[t].push_back(p.plane((f * 7 + Index(t)) % p.num_facets()));
      for (Index v = 0; v < p.num_vertices(); ++v) points[t].push_back(p.point(v));
    });
  for (auto& th : threads) th.join();
  for (int t = 1; t < 4; ++t) EXPECT_EQ(points[t], points[0]);
  for (int t = 0; t < 4; ++t)
    for (Index f = 0; f < copy.num_facets(); ++f)
      ASSERT_EQ(planes[t][f], copy.plane((f * 7 + Index(t)) % copy.num_facets()));
}

TEST(Writers, ExactOutputOfPairsReadsBackExactly) {
  const SumResult sum = minkowski_sum(catalog_polytope("octahedron@scale:1/3"), catalog_polytope("sphere:2"), Method::walk);
  ASSERT_EQ(sum.polytope.coordinates().form(), PointList::Form::rationals);  // 1/3 is not a double
  const SumResult pairs = minkowski_sum(catalog_polytope("icosahedron@scale:1/1024"), catalog_polytope("sphere:2"),
                                        Method::walk);
  ASSERT_EQ(pairs.polytope.coordinates().form(), PointList::Form::double_pairs);
  for (const ConvexPolytope* p : {&sum.polytope, &pairs.polytope})
    for (Format f : {Format::off, Format::obj, Format::wrl}) {
      std::stringstream s;
      WriteOptions w;
      w.exact = true;
      write_mesh(s, p->to_mesh(), f, w);
      const Mesh back = read_mesh(s, f, "memory");
      EXPECT_TRUE(back.points == p->coordinates()) << format_name(f);
      const ConvexPolytope q = ConvexPolytope::from_mesh(back);
      EXPECT_EQ(q.num_facets(), p->num_facets());
    }
}

// Regression for the welding shortcut: points are welded by their bits, so
// -0.0 and 0.0 must be stored alike.
TEST(Welding, SignedZerosWeld) {
  Mesh m = octahedron_mesh();  // vertex 4 is (0, 0, 1)
  m.points.push_back(Vec3d{-0.0, -0.0, 1.0});  // the same point, zeros signed
  int moved = 0;
  for (auto& f : m.faces)
    for (Index& v : f)
      if (v == 4 && moved++ % 2 == 0) v = 6;  // half of the apex's facets use the copy
  ASSERT_GT(moved, 1);
  const ConvexPolytope c = ConvexPolytope::from_mesh(m, "octahedron");
  EXPECT_EQ(c.num_vertices(), 6u);
  EXPECT_EQ(c.num_facets(), 8u);
  EXPECT_EQ(c.volume(), Rational(4, 3));
}

// The builder's interval filters run under their own upward-rounding guard
// and sum_coordinates needs round-to-nearest: whatever mode the caller left
// the FPU in, validation and sums give the same exact polytope.
TEST(RoundingModes, ValidationAndSumsDoNotDependOnTheCallersMode) {
  // (The operands are made before: the catalog's spheres are computed in
  // floating point in the current mode.)
  const ConvexPolytope a = catalog_polytope("sphere:3"), b = catalog_polytope("cube@rot:3");
  const ConvexPolytope c = catalog_polytope("sphere:2");
  const Mesh m = catalog_polytope("sphere:3@scale:1/1024").to_mesh();
  const SumResult ref = minkowski_sum(a, c, Method::walk);
  const ConvexPolytope vref = ConvexPolytope::from_mesh(m);
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO, FE_TONEAREST}) {
    const int old = std::fegetround();
    std::fesetround(mode);
    const ConvexPolytope v = ConvexPolytope::from_mesh(m);
    const SumResult s = minkowski_sum(a, c, Method::walk);
    const SumResult r = minkowski_sum(a, b, Method::walk);
    const int after = std::fegetround();
    std::fesetround(old);
    EXPECT_EQ(after, mode) << "the FPU mode must be restored";
    EXPECT_TRUE(v.coordinates() == vref.coordinates()) << mode;
    EXPECT_EQ(v.num_facets(), vref.num_facets()) << mode;
    EXPECT_TRUE(s.polytope.coordinates() == ref.polytope.coordinates()) << mode;
    EXPECT_EQ(s.polytope.num_facets(), ref.polytope.num_facets()) << mode;
    EXPECT_EQ(s.polytope.volume(), ref.polytope.volume()) << mode;
    EXPECT_EQ(r.polytope.check_invariants(), "") << mode;
  }
}

// write_polytope's direct OFF path writes exactly what write_mesh writes for
// the mesh of the polytope it writes (writable_polytope: the polytope itself
// when exact or when nothing is rounded), in every coordinate form.
TEST(Writers, PolytopeOffEqualsMeshOff) {
  const std::string dir = ::testing::TempDir();
  const SumResult pairs = minkowski_sum(catalog_polytope("cube"), catalog_polytope("sphere:2@scale:1/1024"), Method::walk);
  const ConvexPolytope rat = catalog_polytope("dodecahedron@rot:3");
  const ConvexPolytope big = catalog_polytope("dioctagonal:1025");  // a facet of 1024 vertices
  for (const ConvexPolytope* p : {&pairs.polytope, &rat, &big})
    for (bool exact : {false, true}) {
      WriteOptions w;
      w.exact = exact;
      write_polytope(dir + "direct.off", *p, w);
      write_mesh(dir + "mesh.off", writable_polytope(*p, Format::off, w).to_mesh(), w);
      std::ifstream a(dir + "direct.off"), b(dir + "mesh.off");
      std::stringstream sa, sb;
      sa << a.rdbuf();
      sb << b.rdbuf();
      EXPECT_EQ(sa.str(), sb.str()) << "exact " << exact;
      EXPECT_GT(sa.str().size(), 100u);
    }
}

// to_double is the correctly rounded nearest double (ties to even, gradual
// underflow, overflow to infinity) of any rational: checked against MPFR on
// random rationals of every size, exact ties and the ends of the range.
namespace {
// The nearest value of q with `precision` bits and exponents of the IEEE
// format (double: 53, -1073, 1024; float: 24, -148, 128), as a double.
double mpfr_nearest(const Rational& q, int precision = 53, mpfr_exp_t lo = -1073, mpfr_exp_t hi = 1024) {
  const mpfr_exp_t emin = mpfr_get_emin(), emax = mpfr_get_emax();
  mpfr_set_emin(lo);
  mpfr_set_emax(hi);
  mpfr_t x;
  mpfr_init2(x, precision);
  int t = mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  t = mpfr_subnormalize(x, t, MPFR_RNDN);
  (void)t;
  const double d = mpfr_get_d(x, MPFR_RNDN);
  mpfr_clear(x);
  mpfr_set_emin(emin);
  mpfr_set_emax(emax);
  return d;
}
Integer random_integer(std::mt19937_64& rng, int bits) {
  Integer z = 0;
  for (int b = 0; b < bits; b += 32) {
    z <<= 32;
    z += static_cast<unsigned long>(rng() & 0xffffffffu);
  }
  if (bits % 32) z >>= (32 - bits % 32);
  return z == 0 ? Integer(1) : z;
}
}  // namespace

TEST(ToDouble, NearestAgainstMpfr) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 2000; ++i) {
      const int nb = 1 + int(rng() % 400), db = 1 + int(rng() % 400);
      Rational q(random_integer(rng, nb), random_integer(rng, db));
      q.canonicalize();
      if (rng() & 1) q = -q;
      const int shift = int(rng() % 2200) - 1100;  // reach subnormals and overflow too
      if (shift > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(shift));
      else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-shift));
      const double want = mpfr_nearest(q), got = to_double(q);
      ASSERT_TRUE(got == want || (std::isinf(got) && std::isinf(want) && got == want))
          << "seed " << seed << " case " << i << ": " << format_exact(q);
    }
  }
  // Exact ties between two doubles (55- and 56-bit dyadic numerators), and
  // ties broken by a tiny excess, at several exponents.
  for (int e : {-1000, -60, -1, 0, 1, 52, 900}) {
    for (std::uint64_t m : {(std::uint64_t(1) << 54) + 1, (std::uint64_t(1) << 54) + 3, (std::uint64_t(1) << 55) + 2,
                            (std::uint64_t(1) << 55) + 6, (std::uint64_t(1) << 55) - 2}) {
      Rational q{Integer(static_cast<unsigned long>(m))};
      if (e > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(e));
      else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-e));
      EXPECT_EQ(to_double(q), mpfr_nearest(q)) << m << " * 2^" << e;
      Rational above = q + Rational(Integer(1), Integer(1) << 3000);
      EXPECT_EQ(to_double(above), mpfr_nearest(above)) << m << " * 2^" << e << " + tiny";
      Rational below = q - Rational(Integer(1), Integer(1) << 3000);
      EXPECT_EQ(to_double(below), mpfr_nearest(below)) << m << " * 2^" << e << " - tiny";
    }
  }
}

// The one-limb path (numerator below 2^53 over a one-limb power of two):
// every numerator size up to and past 2^53 and every denominator 2^0..2^63,
// and the next limb, against MPFR.
TEST(ToDouble, OneLimbDyadicsAgainstMpfr) {
  std::mt19937_64 rng(7);
  for (int k = 0; k <= 65; ++k)
    for (int nb = 1; nb <= 56; ++nb)
      for (int rep = 0; rep < 3; ++rep) {
        Integer num = random_integer(rng, nb);
        if (rep == 1) num = (Integer(1) << (nb - 1));  // a power of two itself
        Rational q(num, Integer(1) << k);
        q.canonicalize();
        if (rng() & 1) q = -q;
        ASSERT_EQ(to_double(q), mpfr_nearest(q)) << "seed 7: " << format_exact(q);
      }
}

// Regression (to_double leaked its per-thread scratch integers): the GMP
// memory a thread's to_double takes is given back when the thread ends.
namespace {
std::atomic<long> g_gmp_live{0};
void* counting_alloc(std::size_t n) {
  ++g_gmp_live;
  return std::malloc(n);
}
void* counting_realloc(void* p, std::size_t, std::size_t n) { return std::realloc(p, n); }
void counting_free(void* p, std::size_t) {
  --g_gmp_live;
  std::free(p);
}
}  // namespace

TEST(ToDouble, ThreadScratchFreedWhenTheThreadEnds) {
  // The values exist before the allocator is swapped; the thread converts
  // them (the one-division path: neither short dyadic nor extreme).
  std::vector<Rational> values;
  for (int i = 1; i <= 50; ++i) values.emplace_back(Integer(i) * 1000003, Integer(7) * 1000033 + i);
  void* (*old_alloc)(std::size_t);
  void* (*old_realloc)(void*, std::size_t, std::size_t);
  void (*old_free)(void*, std::size_t);
  mp_get_memory_functions(&old_alloc, &old_realloc, &old_free);
  mp_set_memory_functions(counting_alloc, counting_realloc, counting_free);
  double sum = 0;
  std::thread worker([&] {
    for (const Rational& q : values) sum += to_double(q);
  });
  worker.join();
  const long live = g_gmp_live.load();
  mp_set_memory_functions(old_alloc, old_realloc, old_free);
  EXPECT_EQ(live, 0) << "GMP blocks still allocated after the thread ended";
  EXPECT_GT(sum, 0);
}

// to_float likewise against MPFR with float's precision and range: random
// rationals of every size (subnormal floats and overflow included), exact ties.
TEST(ToFloat, NearestAgainstMpfr) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 2000; ++i) {
      const int nb = 1 + int(rng() % 200), db = 1 + int(rng() % 200);
      Rational q(random_integer(rng, nb), random_integer(rng, db));
      q.canonicalize();
      if (rng() & 1) q = -q;
      const int shift = int(rng() % 340) - 170;
      if (shift > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(shift));
      else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-shift));
      const double want = mpfr_nearest(q, 24, -148, 128);
      const float got = to_float(q);
      ASSERT_EQ(double(got), want) << "seed " << seed << " case " << i << ": " << format_exact(q);
    }
  }
  for (int e : {-170, -149, -30, 0, 23, 100}) {
    for (std::uint64_t m : {(std::uint64_t(1) << 25) + 1, (std::uint64_t(1) << 25) + 3, (std::uint64_t(1) << 26) + 2,
                            (std::uint64_t(1) << 26) - 2}) {
      Rational q{Integer(static_cast<unsigned long>(m))};
      if (e > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(e));
      else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-e));
      for (const Rational& x : {q, Rational(q + Rational(Integer(1), Integer(1) << 600)),
                                Rational(q - Rational(Integer(1), Integer(1) << 600))})
        EXPECT_EQ(double(to_float(x)), mpfr_nearest(x, 24, -148, 128)) << format_exact(x);
    }
  }
}

// to_float goes through the nearest double unless that double is the
// boundary between two floats' roundings: rationals on either side of each
// kind of boundary, close enough that their nearest double is the boundary
// itself (a float midpoint, a subnormal midpoint, FLT_MAX + half its ulp).
TEST(ToFloat, RationalsWhoseNearestDoubleIsARoundingBoundary) {
  const Rational tiny(Integer(1), Integer(1) << 700);
  const Rational boundaries[] = {
      Rational(Integer((1 << 24) + 1), Integer(1) << 24),       // 1 + 2^-24: midpoint of 1 and 1 + 2^-23
      Rational(Integer(3), Integer(1) << 150),                  // midpoint of two subnormal floats
      Rational(Integer(1), Integer(1) << 150),                  // midpoint of 0 and the least subnormal
      Rational((Integer(1) << 128) - (Integer(1) << 103)),      // FLT_MAX + half its ulp
      Rational((Integer(1) << 128) - (Integer(1) << 103) * 3),  // midpoint below FLT_MAX
  };
  for (const Rational& m : boundaries)
    for (const Rational& x : {m, Rational(m + m * tiny), Rational(m - m * tiny)})
      for (const Rational& y : {x, Rational(-x)}) {
        ASSERT_EQ(to_double(y), to_double(m) * sgn(y)) << format_exact(y);  // the nearest double is the boundary
        EXPECT_EQ(double(to_float(y)), mpfr_nearest(y, 24, -148, 128)) << format_exact(y);
      }
}

// to_double_rest: the nearest double (as MPFR's), and a rest with a bound
// that holds exactly, zero exactly for doubles; random rationals of every
// size, exact ties and near-ties, in every rounding mode.
namespace {
Rational pow2(int e) {
  Rational r(1);
  if (e > 0) mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(e));
  else mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), mp_bitcnt_t(-e));
  return r;
}
// "" when (hi, lo, err) is a valid rest of q, else what is wrong.
std::string rest_problem(const Rational& q, double hi, double lo, double err) {
  if (!(hi == mpfr_nearest(q))) return "hi is not the nearest double";
  if (std::isinf(hi)) return lo == 0 && err == HUGE_VAL ? "" : "overflow without an infinite bound";
  if (!(err >= 0) || std::isnan(lo)) return "bad lo or err";
  if (abs(q - Rational(hi) - Rational(lo)) > Rational(err)) return "|q - hi - lo| > err";
  if ((lo == 0 && err == 0) != is_double(q)) return "lo = err = 0 must say exactly whether q is a double";
  return "";
}
}  // namespace

TEST(ToDoubleRest, BoundHoldsAgainstExactRestInEveryMode) {
  const int modes[] = {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO};
  const int old = std::fegetround();
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 1500; ++i) {
      const int nb = 1 + int(rng() % 300), db = 1 + int(rng() % 300);
      Rational q(random_integer(rng, nb), random_integer(rng, db));
      if (i % 5 == 0) q = Rational(random_integer(rng, nb));  // an integer: dyadic, often more than 53 bits
      if (i % 7 == 0) q = Rational(random_integer(rng, nb), Integer(1) << int(rng() % 200));  // dyadic
      q.canonicalize();
      if (rng() & 1) q = -q;
      const int shift = int(rng() % 2300) - 1150;  // every path: subnormals, overflow, the ±900 window
      q *= pow2(shift);
      for (int mode : modes) {
        std::fesetround(mode);
        double hi, lo, err;
        to_double_rest(q, hi, lo, err);
        std::fesetround(old);
        ASSERT_EQ(rest_problem(q, hi, lo, err), "")
            << "seed " << seed << " case " << i << " mode " << mode << ": " << format_exact(q);
      }
    }
  }
  // Ties (55- and 56-bit odd numerators), a tiny excess either way, doubles
  // stored as rationals, zero; at exponents in and out of the fast window.
  for (int e : {-1100, -1070, -1000, -950, -901, -899, -60, 0, 52, 899, 901, 969}) {
    for (std::uint64_t m : {(std::uint64_t(1) << 54) + 1, (std::uint64_t(1) << 55) + 2, (std::uint64_t(1) << 55) - 2,
                            (std::uint64_t(1) << 53) - 1, std::uint64_t(3)}) {
      const Rational t = Rational(Integer(static_cast<unsigned long>(m))) * pow2(e);
      for (const Rational& q : {t, Rational(t + pow2(e - 3000)), Rational(t - pow2(e - 3000)), Rational(-t)}) {
        double hi, lo, err;
        to_double_rest(q, hi, lo, err);
        EXPECT_EQ(rest_problem(q, hi, lo, err), "") << m << " * 2^" << e;
      }
    }
  }
  double hi = 1, lo = 1, err = 1;
  to_double_rest(Rational(0), hi, lo, err);
  EXPECT_TRUE(hi == 0 && lo == 0 && err == 0 && !std::signbit(hi));
}

// The lazy sums: operands of every form (doubles, exact pairs, rationals,
// and lazy sums themselves) with coordinates chosen to sit on and next to
// the midpoints between doubles, near zero, subnormal and huge.  Each sum's
// approx is the nearest double (MPFR), its rest bound holds, is_double is
// exact, exact() and exact_ref() are the GMP sum, in every rounding mode.
namespace {
// A coordinate for operand lists built to make the sums' roundings hard.
Rational hard_coordinate(std::mt19937_64& rng, double base) {
  const double ulp = std::ldexp(1.0, std::ilogb(base == 0 ? 1.0 : base) - 52);
  switch (rng() % 9) {
    case 0: return Rational(0);
    case 1: return Rational(ulp / 2);  // exactly a half ulp: ties
    case 2: return Rational(-ulp / 2);
    case 3: return Rational(ulp / 2) + pow2(-300);  // just past a tie
    case 4: return Rational(ulp / 2) - pow2(-1200);
    case 5: return Rational(1, 3) * Rational(ulp);
    case 6: return Rational(Integer(long(rng() % 1000000) + 1), Integer(long(rng() % 999983) + 1));
    case 7: return Rational(wild_double(rng));
    default: return Rational(base) + Rational(Integer(1), Integer(3) << int(rng() % 1200));
  }
}
PointList hard_list(std::mt19937_64& rng, int form, const std::vector<double>& bases) {
  PointList l;
  for (std::size_t i = 0; i + 2 < bases.size(); i += 3) {
    Point3 p;
    for (int k = 0; k < 3; ++k) {
      const double b = bases[i + std::size_t(k)];
      if (form == 0) p[k] = Rational(b);
      else p[k] = hard_coordinate(rng, b);
    }
    if (form == 1) {
      double hi[3], lo[3];
      for (int k = 0; k < 3; ++k) two_sum(bases[i + std::size_t(k)], std::ldexp(bases[i + std::size_t(k)], -60), hi[k], lo[k]);
      l.push_pair(Vec3d{hi[0], hi[1], hi[2]}, Vec3d{lo[0], lo[1], lo[2]});
    } else {
      l.push_back(p);
    }
  }
  return l;
}
std::string sum_problem(const PointList& s, std::size_t m, const Point3& want) {
  if (!(s.exact(m) == want)) return "exact() is not the exact sum";
  if (s.is_double(m) != is_double(want)) return "is_double is wrong";
  for (int k = 0; k < 3; ++k) {
    if (!(s.approx(m)[k] == mpfr_nearest(want[k]))) return "approx is not the nearest double";
    if (std::signbit(s.approx(m)[k]) && s.approx(m)[k] == 0) return "a negative zero";
    if (s.form() == PointList::Form::rationals && std::isfinite(s.approx(m)[k]) &&
        abs(want[k] - Rational(s.approx(m)[k]) - Rational(s.low(m)[k])) > Rational(s.low_error(m)[k]))
      return "|exact - approx - low| > low_error";
  }
  return "";
}
}  // namespace

TEST(SumCoordinates, LazySumsAgreeWithExactOnHardInputs) {
  const int old = std::fegetround();
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<double> bases;
    for (int i = 0; i < 3 * 40; ++i) {
      const int kind = int(rng() % 6);
      bases.push_back(kind == 0 ? 0.0 : kind == 1 ? std::ldexp(1.0, int(rng() % 60) - 30) : wild_double(rng));
    }
    std::vector<double> neg = bases;
    for (double& b : neg) b = -b;  // sums that cancel exactly or nearly
    for (int fa = 0; fa < 3; ++fa)
      for (int fb = 0; fb < 3; ++fb) {
        const PointList a = hard_list(rng, fa, bases), b = hard_list(rng, fb, rng() % 2 ? neg : bases);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        for (std::uint32_t i = 0; i < a.size(); ++i)
          for (std::uint32_t j = 0; j < b.size(); j += 3) pairs.emplace_back(i, (i + j) % std::uint32_t(b.size()));
        for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
          std::fesetround(mode);
          const PointList s = PointList::sums(pairs, a, b);
          std::fesetround(old);
          for (std::size_t m = 0; m < pairs.size(); ++m) {
            const Point3 want = a.exact(pairs[m].first) + b.exact(pairs[m].second);
            ASSERT_EQ(sum_problem(s, m, want), "")
                << "seed " << seed << " forms " << fa << "+" << fb << " mode " << mode << " pair " << m;
          }
          if (s.form() == PointList::Form::rationals) {
            for (std::size_t m = 0; m < pairs.size(); ++m) {
              ASSERT_EQ(s.exact_ref(m), a.exact(pairs[m].first) + b.exact(pairs[m].second)) << "seed " << seed;
            }
          }
          // A sum of sums: the lazy list as an operand.
          if (mode == FE_TONEAREST && s.size() > 7) {
            const std::vector<std::pair<std::uint32_t, std::uint32_t>> again = {{0, 1}, {3, 2}, {5, 5}, {7, 0}};
            const PointList t = PointList::sums(again, s, s);
            for (std::size_t m = 0; m < again.size(); ++m)
              ASSERT_EQ(sum_problem(t, m, s.exact(again[m].first) + s.exact(again[m].second)), "")
                  << "seed " << seed << " sum of sums " << m;
          }
        }
      }
  }
}

// Ties decided by the low parts: a double plus a rational exactly half an
// ulp away rounds to even; a hair more or less decides; zero and -0.0.
TEST(SumCoordinates, TiesAndZerosInLazySums) {
  const double one = 1.0, odd = 1.0 + 0x1p-52;
  struct Case {
    double a;
    Rational b;
  } cases[] = {
      {one, Rational(0x1p-53)},                                  // tie, to even: 1
      {odd, Rational(0x1p-53)},                                  // tie, to even: up
      {one, Rational(0x1p-53) + pow2(-400)},                     // past the tie: up
      {odd, Rational(0x1p-53) - pow2(-1300)},                    // short of it: down
      {one, Rational(-0x1p-54)},                                 // tie below a power of two
      {one, Rational(-0x1p-54) + Rational(1, 3) * pow2(-200)},   // just inside
      {-0.0, Rational(1, 3)},
      {0.0, Rational(0)},
      {-0x1p-1074, Rational(0x1p-1074)},                         // cancels to zero
      {1e300, Rational(1e300) / 3},
      {0x1p-1000, Rational(1, 3) * pow2(-1000)},                 // below the filter's range
  };
  for (const Case& c : cases) {
    PointList a, b;
    a.push_back(Vec3d{c.a, c.a, 0.0});
    b.push_back(Point3(c.b, Rational(1, 7), Rational(1, 5)));
    ASSERT_EQ(b.form(), PointList::Form::rationals);
    const PointList s = PointList::sums({{0, 0}}, a, b);
    const Point3 want = a.exact(0) + b.exact(0);
    EXPECT_EQ(sum_problem(s, 0, want), "") << c.a << " + " << format_exact(c.b);
  }
}

// A lazy list is shared by its copies, and becomes a list of its own when
// changed; concurrent exact_ref()/exact() calls on one list and its copy all
// see the same points.
TEST(SumCoordinates, LazyListCopiesAndConcurrentReaders) {
  const ConvexPolytope a = catalog_polytope("icosahedron"), b = catalog_polytope("sphere:2@rot:1");
  ASSERT_EQ(b.coordinates().form(), PointList::Form::rationals);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < a.num_vertices(); ++i)
    for (std::uint32_t j = 0; j < b.num_vertices(); j += 5) pairs.emplace_back(i, j);
  const PointList s = PointList::sums(pairs, a.coordinates(), b.coordinates());
  ASSERT_EQ(s.form(), PointList::Form::rationals);
  std::vector<Point3> want;
  for (auto [i, j] : pairs) want.push_back(a.point(i) + b.point(j));
  const PointList copy = s;
  std::vector<Point3> got[4];
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      const PointList& l = t % 2 ? copy : s;
      for (std::size_t m = 0; m < l.size(); ++m) got[t].push_back(t < 2 ? l.exact_ref(m) : l.exact(m));
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(got[t], want) << "reader " << t;
  PointList changed = s;
  changed.negate();
  changed.set(1, P(1, 2, 3));
  changed.push_back(Q("1/3", "1", "1"));
  EXPECT_EQ(changed.size(), s.size() + 1);
  EXPECT_EQ(changed.exact(0), -want[0]);
  EXPECT_EQ(changed.exact(1), P(1, 2, 3));
  EXPECT_EQ(changed.approx(0).x, to_double(-want[0].x));
  for (std::size_t m = 0; m < s.size(); ++m) ASSERT_EQ(s.exact_ref(m), want[m]) << "the original is unchanged";
  EXPECT_TRUE(copy == s);
  EXPECT_FALSE(changed == s);
}

// Regression: to_double of a dyadic rational in the subnormal range went
// through ldexp, which rounds in the caller's rounding mode: with FE_DOWNWARD
// it gave the double below the nearest one.
TEST(ToDouble, SubnormalDyadicIsNearestInEveryMode) {
  const Rational q = Rational(Integer(1226299077618285L)) / (Integer(1) << 1120);  // 53 bits, subnormal
  const Rational r = Rational(Integer(3)) / (Integer(1) << 1076);                   // 3/4 of the smallest subnormal
  const double want_q = mpfr_nearest(q), want_r = mpfr_nearest(r);
  const int old = std::fegetround();
  for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    std::fesetround(mode);
    const double got_q = to_double(q), got_r = to_double(r), got_nq = to_double(-q);
    std::fesetround(old);
    EXPECT_EQ(got_q, want_q) << "mode " << mode;
    EXPECT_EQ(got_nq, -want_q) << "mode " << mode;
    EXPECT_EQ(got_r, want_r) << "mode " << mode;
  }
}
