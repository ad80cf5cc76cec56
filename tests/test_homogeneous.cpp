// Homogeneous integer points: the filtered side of a plane through three of
// them (kernel/homogeneous.hpp) against its exact determinant, and the
// exact hull of such points (mesh/homogeneous_hull.hpp) against CGAL's hull
// of the same points as rationals.
#include <minksum/polytope.hpp>

#include "kernel/homogeneous.hpp"
#include "mesh/homogeneous_hull.hpp"

#include <CGAL/FPU.h>
#include <gtest/gtest.h>

#include <optional>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace minksum {
namespace {

using detail::HomogeneousPoint;

// A random integer of `bits` bits, of either sign (fixed generator).
Integer random_integer(std::mt19937_64& rng, int bits) {
  Integer z = 0;
  for (int b = 0; b < bits; b += 32) z = z * (Integer(1) << 32) + Integer(static_cast<unsigned long>(rng() >> 32));
  z >>= std::max(0, ((bits + 31) / 32) * 32 - bits);
  return (rng() & 1) ? Integer(-z) : z;
}

// The point (x, y, z) given as (x w, y w, z w, w).
HomogeneousPoint scaled_point(const Integer& x, const Integer& y, const Integer& z, const Integer& w) {
  return detail::homogeneous_point(Integer(x * w), Integer(y * w), Integer(z * w), w);
}

TEST(HomogeneousSide, BeyondIsTheSideSeenCounterClockwise) {
  CGAL::Protect_FPU_rounding<true> upward;
  // (0,0,0), (1,0,0), (0,1,0) counter-clockwise seen from +z.
  const HomogeneousPoint a = scaled_point(0, 0, 0, 3), b = scaled_point(1, 0, 0, 5), c = scaled_point(0, 1, 0, 7);
  const detail::HomogeneousPlane h = detail::homogeneous_plane(a, b, c);
  EXPECT_EQ(detail::side(h, a, b, c, scaled_point(0, 0, 1, 2)), 1);
  EXPECT_EQ(detail::side(h, a, b, c, scaled_point(0, 0, -1, 11)), -1);
  EXPECT_EQ(detail::side(h, a, b, c, scaled_point(5, -3, 0, 13)), 0);
  EXPECT_THROW(detail::homogeneous_point(1, 2, 3, 0), std::invalid_argument);
}

// Every sign the filter decides is the exact determinant's, on random
// points of short and long coordinates, on points made coplanar exactly
// (the filter cannot decide those: the exact plane answers 0) and on points
// one unit off that plane (nonzero, near zero: where an enclosure rounded
// the wrong way would show).  The filter decides nearly every random case.
TEST(HomogeneousSide, FilterAgreesWithTheExactDeterminant) {
  CGAL::Protect_FPU_rounding<true> upward;
  for (int bits : {8, 60, 200, 700}) {
    const unsigned seed = 1000u + unsigned(bits);
    std::mt19937_64 rng(seed);
    int zeros = 0, random_decided = 0, near_decided = 0;
    for (int trial = 0; trial < 600; ++trial) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
      auto point = [&] {
        Integer w = random_integer(rng, bits / 2 + 1);
        if (sgn(w) < 0) w = -w;
        return detail::homogeneous_point(random_integer(rng, bits), random_integer(rng, bits),
                                         random_integer(rng, bits), Integer(w + 1));
      };
      const HomogeneousPoint a = point(), b = point(), c = point();
      HomogeneousPoint x = point();
      const int kind = trial % 3;  // 0 random, 1 on the plane, 2 one unit off it
      if (kind != 0) {
        // x = a + (b - a) s + (c - a) t in Cartesian terms, with integers:
        // x w = a_c wb wc + ... written over the common w = wa wb wc.
        const Integer s = random_integer(rng, 6), t = random_integer(rng, 6);
        std::array<Integer, 4> xc;
        const Integer& wa = a.c[3];
        const Integer& wb = b.c[3];
        const Integer& wc = c.c[3];
        for (int k = 0; k < 3; ++k)
          xc[k] = a.c[k] * wb * wc + s * (b.c[k] * wa * wc - a.c[k] * wb * wc) + t * (c.c[k] * wa * wb - a.c[k] * wb * wc);
        xc[3] = wa * wb * wc;
        if (kind == 2) xc[trial % 2] += 1;
        x = detail::homogeneous_point(xc[0], xc[1], xc[2], xc[3]);
      }
      const detail::HomogeneousPlane h = detail::homogeneous_plane(a, b, c);
      const int exact = detail::side_exact(a, b, c, x);
      const int filtered = detail::side_filter(h, x);
      if (filtered != kUncertain) {
        ASSERT_EQ(filtered, exact);
      }
      ASSERT_EQ(detail::side(h, a, b, c, x), exact);
      if (kind == 1) {
        ASSERT_EQ(exact, 0);
      }
      if (kind == 2) {
        ASSERT_NE(exact, 0);
      }
      zeros += exact == 0;
      random_decided += kind == 0 && filtered != kUncertain;
      near_decided += kind == 2 && filtered != kUncertain;
    }
    EXPECT_EQ(zeros, 200) << bits << " bits";
    EXPECT_GE(random_decided, 195) << bits << " bits";  // of 200
    std::printf("%d bits: the filter decided %d of 200 random and %d of 200 near-coplanar signs\n", bits,
                random_decided, near_decided);
  }
}

// A coordinate far shorter than its point's longest (w of 1 200 bits, x of
// one): its scaled interval is the one around 0 of width 2^-999, still an
// enclosure, and the signs stay exact.
TEST(HomogeneousSide, TinyScaledCoordinatesStayEnclosed) {
  CGAL::Protect_FPU_rounding<true> upward;
  const Integer big = Integer(1) << 1200;
  // (0,0,0), (1,0,0), (0,1,0) and x = (1, 1, ±1) / 2^1200 + ... as homogeneous rows.
  const HomogeneousPoint a = detail::homogeneous_point(0, 0, 0, 1), b = detail::homogeneous_point(1, 0, 0, 1),
                         c = detail::homogeneous_point(0, 1, 0, 1);
  const detail::HomogeneousPlane h = detail::homogeneous_plane(a, b, c);
  for (int z : {-1, 0, 1}) {
    const HomogeneousPoint x = detail::homogeneous_point(1, 1, z, big);
    EXPECT_LE(x.s[0].sup(), std::ldexp(1.0, -1000));
    EXPECT_GE(x.s[0].inf(), -std::ldexp(1.0, -1000));
    EXPECT_EQ(detail::side(h, a, b, c, x), z) << z;
    EXPECT_EQ(detail::side_exact(a, b, c, x), z) << z;
  }
}

// The builder takes the points the triangles use, renumbered.
ConvexPolytope polytope_of(const HomogeneousHull& h, const std::vector<Point3>& cartesian) {
  std::vector<Index> used(cartesian.size(), kNoIndex);
  Mesh m;
  for (const auto& t : h.triangles) {
    std::vector<Index> f;
    for (Index v : t) {
      if (used[v] == kNoIndex) {
        used[v] = Index(m.points.size());
        m.points.push_back(cartesian[v]);
      }
      f.push_back(used[v]);
    }
    m.faces.push_back(std::move(f));
  }
  return ConvexPolytope::from_mesh(m, "homogeneous hull");
}

std::set<Point3> vertex_set(const ConvexPolytope& p) {
  std::set<Point3> s;
  for (Index v = 0; v < p.num_vertices(); ++v) s.insert(p.point(v));
  return s;
}

// Points of a small grid (many coplanar, collinear and repeated-direction
// points: the degenerate hulls of the erosion's dual points), each with its
// own w, and points of long coordinates: the same polytope as CGAL's exact
// hull of the rationals, and every flat flag the exact coplanarity of the
// two triangles.
TEST(HomogeneousHull, SameAsTheExactHullOfTheRationals) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const bool grid = seed <= 8;
    const int count = grid ? 30 + int(seed) * 20 : 200;
    std::vector<Point3> cartesian;
    std::vector<HomogeneousPoint> points;
    std::set<Point3> seen;
    std::optional<CGAL::Protect_FPU_rounding<true>> upward(std::in_place);  // for the points and the hull only
    while (int(points.size()) < count) {
      Integer x, y, z, w;
      if (grid) {
        std::uniform_int_distribution<int> g(-3, 3);
        x = g(rng), y = g(rng), z = g(rng);
        w = Integer(1 + int(rng() % 5));
        x *= w, y *= w, z *= w;
      } else {
        x = random_integer(rng, 120), y = random_integer(rng, 120), z = random_integer(rng, 120);
        w = random_integer(rng, 90);
        if (sgn(w) <= 0) w = -w + 1;
      }
      Point3 p(Rational(x, w), Rational(y, w), Rational(z, w));
      for (int k = 0; k < 3; ++k) p[k].canonicalize();
      if (!seen.insert(p).second) continue;  // distinct points, as the dual points are
      cartesian.push_back(p);
      points.push_back(detail::homogeneous_point(x, y, z, w));
    }
    const HomogeneousHull h = homogeneous_hull(points);
    upward.reset();
    const ConvexPolytope mine = polytope_of(h, cartesian);
    const ConvexPolytope cgal = ConvexPolytope::hull(cartesian, "cgal");
    EXPECT_EQ(vertex_set(mine), vertex_set(cgal));
    EXPECT_EQ(mine.num_facets(), cgal.num_facets());
    EXPECT_EQ(mine.volume(), cgal.volume());
    // Outward: every point on or beneath every triangle.
    for (const auto& tri : h.triangles)
      for (const HomogeneousPoint& x : points)
        ASSERT_LE(detail::side_exact(points[tri[0]], points[tri[1]], points[tri[2]], x), 0);
    // Neighbours are mutual, and flat is the exact coplanarity.
    for (Index t = 0; t < h.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const Index u = h.neighbour[t][k];
        const Index p = h.triangles[t][k], q = h.triangles[t][(k + 1) % 3];
        int back = -1;
        for (int j = 0; j < 3; ++j)
          if (h.triangles[u][j] == q && h.triangles[u][(j + 1) % 3] == p) back = j;
        ASSERT_GE(back, 0) << "triangle " << t << " edge " << k;
        ASSERT_EQ(h.neighbour[u][back], t);
        Index off = kNoIndex;
        for (Index v : h.triangles[u])
          if (v != p && v != q) off = v;
        const auto& tri = h.triangles[t];
        EXPECT_EQ(h.flat[t][k], detail::side_exact(points[tri[0]], points[tri[1]], points[tri[2]], points[off]) == 0);
      }
  }
}

// Repeated points (the same point with other w's) take no part, even when
// the start's two far points are copies of each other.
TEST(HomogeneousHull, RepeatedPointsAreOnePoint) {
  CGAL::Protect_FPU_rounding<true> upward;
  const Integer big = Integer(1) << 80;
  std::vector<HomogeneousPoint> points;
  // The corner (B, B, B) three times (w = 1, 3, 7), then the unit offsets.
  for (int w : {1, 3, 7}) points.push_back(scaled_point(big, big, big, w));
  points.push_back(scaled_point(Integer(big + 1), big, big, 2));
  points.push_back(scaled_point(big, Integer(big + 1), big, 5));
  points.push_back(scaled_point(big, big, Integer(big + 1), 1));
  const HomogeneousHull h = homogeneous_hull(points);
  ASSERT_EQ(h.triangles.size(), 4u);
  std::set<Index> used;
  for (const auto& t : h.triangles) used.insert(t.begin(), t.end());
  EXPECT_EQ(used.size(), 4u);
  EXPECT_EQ(used.count(3), 1u);
  EXPECT_EQ(used.count(4), 1u);
  EXPECT_EQ(used.count(5), 1u);
}

TEST(HomogeneousHull, PointsThatSpanNoVolumeAreRefused) {
  CGAL::Protect_FPU_rounding<true> upward;
  std::vector<HomogeneousPoint> flat;
  for (int i = 0; i < 10; ++i) flat.push_back(detail::homogeneous_point(i, i * i, 0, 1 + i));
  EXPECT_THROW(homogeneous_hull(flat), std::invalid_argument);
  std::vector<HomogeneousPoint> three;
  for (int i = 0; i < 3; ++i) three.push_back(detail::homogeneous_point(i, 1, 2, 1));
  EXPECT_THROW(homogeneous_hull(three), std::invalid_argument);
  std::vector<HomogeneousPoint> line, copies;
  for (int i = 0; i < 8; ++i) line.push_back(scaled_point(i, 2 * i, -i, 1 + i));
  EXPECT_THROW(homogeneous_hull(line), std::invalid_argument);
  for (int i = 0; i < 8; ++i) copies.push_back(scaled_point(3, 4, 5, 1 + i));
  EXPECT_THROW(homogeneous_hull(copies), std::invalid_argument);
}

TEST(HomogeneousHull, RefusedWithoutTheRoundingGuard) {
  std::vector<HomogeneousPoint> points;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    for (int i = 0; i < 4; ++i) points.push_back(detail::homogeneous_point(i == 1, i == 2, i == 3, 1));
  }
  EXPECT_THROW(homogeneous_hull(points), std::logic_error);
}

}  // namespace
}  // namespace minksum
