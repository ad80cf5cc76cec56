// Tests of the exact difference comparison (src/kernel/include/kernel/difference.hpp), the
// walk's zero certificate: every answer is checked against exact rational
// subtraction, including the cases the rounded differences alone would get
// wrong (equal roundings of different exact values), overflow, and a
// non-nearest rounding mode.
#include <gtest/gtest.h>

#include <cfenv>
#include <cfloat>
#include <cmath>
#include <minksum/kernel.hpp>
#include <random>
#include <string>

#include "kernel/difference.hpp"

using namespace minksum;
using minksum::detail::same_difference;

namespace {

Point3 exact(const Vec3d& v) { return Point3(v.x, v.y, v.z); }

// The relation from exact rational arithmetic: +1 equal, −1 opposite, 0 neither.
int oracle(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  const Point3 d = exact(p1) - exact(p0), e = exact(q1) - exact(q0);
  if (d == e) return 1;
  if (d == -e) return -1;
  return 0;
}

}  // namespace

TEST(Difference, EqualAndOppositeTranslates) {
  const Vec3d p0{1, 2, 3}, p1{1.5, 2.25, 3}, q0{10, 20, 30}, q1{10.5, 20.25, 30};
  EXPECT_EQ(same_difference(p0, p1, q0, q1, true), 1);
  EXPECT_EQ(same_difference(p0, p1, q1, q0, true), -1);
  EXPECT_EQ(same_difference(p0, p1, q0, Vec3d{10.5, 20.25, 30.5}, true), 0);
  // The zero vector is equal (and opposite) to itself: +1.
  EXPECT_EQ(same_difference(p0, p0, q1, q1, true), 1);
}

TEST(Difference, EqualRoundingsOfDifferentValues) {
  // fl(1 − 2^-60) = 1 = fl(1 − 0): the rounded differences agree, the exact
  // ones do not.
  const Vec3d p0{0x1p-60, 0, 0}, p1{1, 0, 0}, q0{0, 0, 0}, q1{1, 0, 0};
  ASSERT_EQ(p1.x - p0.x, q1.x - q0.x);
  EXPECT_EQ(same_difference(p0, p1, q0, q1, true), 0);
  EXPECT_EQ(same_difference(p0, p1, q1, q0, true), 0);
  // The same error in both: equal.
  const Vec3d r0{5, 0x1p-60, 7}, r1{5, 1, 7}, s0{-3, 0x1p-60, 2}, s1{-3, 1, 2};
  EXPECT_EQ(same_difference(r0, r1, s0, s1, true), 1);
  EXPECT_EQ(same_difference(r0, r1, s1, s0, true), -1);
  // Subnormal differences are exact.
  const Vec3d t0{0, 0, 0x1p-1074}, t1{0, 0, 0x1p-1073}, u0{1, 1, 0}, u1{1, 1, 0x1p-1074};
  EXPECT_EQ(same_difference(t0, t1, u0, u1, true), 1);
}

TEST(Difference, OverflowAndRoundingModeDecideNothing) {
  const Vec3d p0{-DBL_MAX, 0, 0}, p1{DBL_MAX, 0, 0};
  EXPECT_EQ(same_difference(p0, p1, p0, p1, true), 0);
  EXPECT_EQ(same_difference(p0, p1, p1, p0, true), 0);
  const Vec3d a{1, 2, 3}, b{4, 5, 6};
  EXPECT_EQ(same_difference(a, b, a, b, false), 0);
}

TEST(Difference, RandomAgainstRationals) {
  // Fixed seeds; differences built to be equal, opposite, or off by one
  // unit in the last place of a coordinate, over a wide exponent range.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> mant(-1, 1);
    std::uniform_int_distribution<int> ex(-80, 80), kind(0, 3);
    auto coord = [&] { return std::ldexp(mant(rng), ex(rng)); };
    int counts[3] = {0, 0, 0};
    for (int n = 0; n < 2000; ++n) {
      const Vec3d p0{coord(), coord(), coord()}, p1{coord(), coord(), coord()};
      const Vec3d t{std::ldexp(1.0, ex(rng)), 0, std::ldexp(3.0, ex(rng))};
      Vec3d q0{p0.x + t.x, p0.y + t.y, p0.z + t.z}, q1{p1.x + t.x, p1.y + t.y, p1.z + t.z};
      const int k = kind(rng);
      if (k == 1) std::swap(q0, q1);
      if (k == 2) q1.y = std::nextafter(q1.y, INFINITY);
      if (k == 3) q0 = p0, q1 = p1;
      const int want = oracle(p0, p1, q0, q1), got = same_difference(p0, p1, q0, q1, true);
      ++counts[want + 1];
      ASSERT_EQ(got, want) << "seed " << seed << ", case " << n;
      // The rational form certifies only identical point pairs, never wrongly.
      const int r = same_difference(exact(p0), exact(p1), exact(q0), exact(q1));
      if (k == 3) {
        ASSERT_EQ(r, 1) << "seed " << seed << ", case " << n;
      }
      if (r != 0) {
        ASSERT_EQ(r, want) << "seed " << seed << ", case " << n;
      }
    }
    // The three outcomes all occur (translations by t are often exact).
    EXPECT_GT(counts[0], 0) << "seed " << seed;
    EXPECT_GT(counts[1], 0) << "seed " << seed;
    EXPECT_GT(counts[2], 0) << "seed " << seed;
  }
}

TEST(Difference, RationalFormComparesPoints) {
  const Point3 a(Rational(1, 3), Rational(2), Rational(0)), b(Rational(5), Rational(-1, 7), Rational(1));
  const Point3 c(Rational(4), Rational(4), Rational(4));
  EXPECT_EQ(same_difference(a, b, a, b), 1);
  EXPECT_EQ(same_difference(a, b, b, a), -1);
  // Equal differences at other points are not certified (0), never wrong.
  EXPECT_EQ(same_difference(a, b, a + c, b + c), 0);
  EXPECT_EQ(same_difference(a, b, a, c), 0);
}
