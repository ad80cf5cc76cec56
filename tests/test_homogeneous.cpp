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
// points of short and long coordinates, and on points made coplanar exactly
// (the filter cannot decide those: the exact plane answers 0).
TEST(HomogeneousSide, FilterAgreesWithTheExactDeterminant) {
  CGAL::Protect_FPU_rounding<true> upward;
  for (int bits : {8, 60, 200, 700}) {
    const unsigned seed = 1000u + unsigned(bits);
    std::mt19937_64 rng(seed);
    int zeros = 0;
    for (int trial = 0; trial < 400; ++trial) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
      auto point = [&] {
        Integer w = random_integer(rng, bits / 2 + 1);
        if (sgn(w) < 0) w = -w;
        return detail::homogeneous_point(random_integer(rng, bits), random_integer(rng, bits),
                                         random_integer(rng, bits), Integer(w + 1));
      };
      const HomogeneousPoint a = point(), b = point(), c = point();
      HomogeneousPoint x = point();
      if (trial % 2 == 1) {
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
        x = detail::homogeneous_point(xc[0], xc[1], xc[2], xc[3]);
      }
      const detail::HomogeneousPlane h = detail::homogeneous_plane(a, b, c);
      const int exact = detail::side_exact(a, b, c, x);
      ASSERT_EQ(detail::side(h, a, b, c, x), exact);
      if (trial % 2 == 1) {
        ASSERT_EQ(exact, 0);
      }
      zeros += exact == 0;
    }
    EXPECT_EQ(zeros, 200) << bits << " bits";
  }
}

// The hull as a polytope: its triangles through the validating builder
// (which merges coplanar triangles and drops vertices inside facets).
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
      const Point3 p(Rational(x, w), Rational(y, w), Rational(z, w));
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

TEST(HomogeneousHull, PointsThatSpanNoVolumeAreRefused) {
  CGAL::Protect_FPU_rounding<true> upward;
  std::vector<HomogeneousPoint> flat;
  for (int i = 0; i < 10; ++i) flat.push_back(detail::homogeneous_point(i, i * i, 0, 1 + i));
  EXPECT_THROW(homogeneous_hull(flat), std::invalid_argument);
  std::vector<HomogeneousPoint> three;
  for (int i = 0; i < 3; ++i) three.push_back(detail::homogeneous_point(i, 1, 2, 1));
  EXPECT_THROW(homogeneous_hull(three), std::invalid_argument);
}

}  // namespace
}  // namespace minksum
