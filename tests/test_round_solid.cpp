// round_solid (src/nonconvex/round.cpp, docs/nonconvex.md "Output"): an exact
// solid written in doubles or floats as a valid solid, points that round
// together merged, degenerate triangles removed with the surface kept
// closed, the largest displacement reported, and clear refusals.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace minksum;
using namespace minksum::testing;

namespace {

// The unit cube [0,1]^3 whose top face is a fan of four triangles around
// the point p of the top face (z = 1).
Mesh cube_with_top_point(const Point3& p) {
  Mesh m;
  auto add = [&](long x, long y, long z) { m.points.push_back(Point3(Rational(x), Rational(y), Rational(z))); };
  add(0, 0, 0);  // 0
  add(1, 0, 0);  // 1
  add(1, 1, 0);  // 2
  add(0, 1, 0);  // 3
  add(0, 0, 1);  // 4 a
  add(1, 0, 1);  // 5 b
  add(1, 1, 1);  // 6 c
  add(0, 1, 1);  // 7 d
  m.points.push_back(p);  // 8
  m.faces = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
             {8, 4, 5},    {8, 5, 6},    {8, 6, 7},    {8, 7, 4}};
  return m;
}

// 2^-60 / 3: not a double, far below half an ulp of 1.
const Rational kTiny = Rational(1, 3) / Rational(Integer(1) << 60);

}  // namespace

TEST(RoundSolid, DoublesAreWrittenAsTheyAre) {
  const Mesh m = cube_with_top_point(Point3(Rational(1, 2), Rational(1, 4), Rational(1)));
  const RoundedSolid r = round_solid(m, false, "m.off");
  EXPECT_EQ(r.rounded_coordinates, 0u);
  EXPECT_EQ(r.mesh.faces.size(), m.faces.size());
  EXPECT_EQ(r.max_displacement, 0.0);
}

// p a hair from the corner (1,1,1): it rounds onto the corner, two of the
// fan's triangles get a repeated vertex and go, and the other two close the
// top exactly.
TEST(RoundSolid, PointThatRoundsOntoACornerIsMerged) {
  const Mesh m = cube_with_top_point(Point3(1 - kTiny, 1 - kTiny, Rational(1)));
  ASSERT_NO_THROW(validate_solid(m, "m.off"));
  const RoundedSolid r = round_solid(m, false, "m.off");
  EXPECT_EQ(r.rounded_coordinates, 2u);
  EXPECT_EQ(r.grid, 0.0);
  EXPECT_EQ(r.mesh.points.size(), 8u);
  EXPECT_EQ(r.mesh.faces.size(), 12u);  // 5 quads as 10 triangles, the top as 2
  const Solid s = validate_solid(r.mesh, "r.off");
  EXPECT_EQ(s.volume, Rational(1));
  EXPECT_GT(r.max_displacement, 0.0);
  EXPECT_LE(r.max_displacement, 1e-18);
}

// p a hair inside the top face from the edge b c (x = 1): it rounds onto
// that edge, the fan's triangle on b c becomes collinear and goes, and the
// side face's triangle across b c is split at the rounded point.
TEST(RoundSolid, PointThatRoundsOntoAnEdgeSplitsTheTriangleAcross) {
  const Mesh m = cube_with_top_point(Point3(1 - kTiny, Rational(1, 2), Rational(1)));
  const RoundedSolid r = round_solid(m, false, "m.off");
  EXPECT_EQ(r.rounded_coordinates, 1u);
  EXPECT_EQ(r.mesh.points.size(), 9u);
  // 10 side and bottom triangles, one split in two; the top: 3 of the fan.
  EXPECT_EQ(r.mesh.faces.size(), 14u);
  const Solid s = validate_solid(r.mesh, "r.off");
  EXPECT_EQ(s.volume, Rational(1));
  for (std::size_t i = 0; i < r.mesh.points.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(is_double(r.mesh.points[i][k]));
}

TEST(RoundSolid, FloatsOfASumReadBackAsTheSameSolid) {
  // tube ⊕ a rotated cube: coordinates with large denominators.
  const Solid a = validate_solid(catalog_mesh("tube"), "tube");
  const Solid b = validate_solid(catalog_mesh("cube@scale:1/4@rot:3"), "cube");
  const NonconvexSum s = minkowski_sum_nonconvex(a, b);
  const RoundedSolid r = round_solid(s.mesh, true, "s.stl");
  EXPECT_GT(r.rounded_coordinates, 0u);
  const Solid back = validate_solid(r.mesh, "s.stl");
  for (std::size_t i = 0; i < r.mesh.points.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double d = to_double(r.mesh.points[i][k]);
      EXPECT_EQ(Rational(double(float(d))), r.mesh.points[i][k]);
    }
  // Every point moved by at most the displacement: the volume moves by at
  // most the area times it (area < 60 here), and floats are within 2^-24.
  EXPECT_LE(r.max_displacement, 3 * 2.0 * std::ldexp(1.0, -24));
  EXPECT_LT(std::fabs(to_double(back.volume - s.volume)), 60 * r.max_displacement);
}

TEST(RoundSolid, BeyondTheRangeOfFloatsIsRefused) {
  const Mesh m = cube_with_top_point(Point3(Rational(1, 3), Rational(1, 3), Rational(1)));
  Mesh big = m;
  PointList pts;
  for (std::size_t i = 0; i < m.points.size(); ++i) pts.push_back(Rational(Integer(1) << 200) * m.points[i]);
  big.points = pts;
  EXPECT_NO_THROW(round_solid(big, false, "big.off"));
  try {
    round_solid(big, true, "big.stl");
    FAIL() << "no RoundingError";
  } catch (const RoundingError& e) {
    EXPECT_STREQ(e.what(), "a coordinate is beyond the range of 32-bit floats");
  }
}

// Below the range: every coordinate rounds to zero (the message had an empty
// "()" where the problem should be), or only some do.
TEST(RoundSolid, BelowTheRangeOfFloatsIsRefusedWithAReason) {
  const Mesh m = cube_with_top_point(Point3(Rational(1, 3), Rational(1, 3), Rational(1)));
  Mesh tiny = m;
  PointList pts;
  for (std::size_t i = 0; i < m.points.size(); ++i) pts.push_back(Rational(1, Integer(1) << 200) * m.points[i]);
  tiny.points = pts;
  EXPECT_NO_THROW(round_solid(tiny, false, "tiny.off"));
  try {
    round_solid(tiny, true, "tiny.stl");
    FAIL() << "no RoundingError";
  } catch (const RoundingError& e) {
    EXPECT_STREQ(e.what(), "every coordinate rounds to zero: the solid is below the range of 32-bit floats");
  }
  // 2^-140: floats are denormal there, with too few bits to keep the solid.
  PointList near;
  for (std::size_t i = 0; i < m.points.size(); ++i) near.push_back(Rational(1, Integer(1) << 148) * m.points[i]);
  tiny.points = near;
  try {
    const RoundedSolid r = round_solid(tiny, true, "tiny.stl");
    EXPECT_NO_THROW(validate_solid(r.mesh, "rounded"));
  } catch (const RoundingError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find("()"), std::string::npos) << what;
    EXPECT_EQ(what.rfind("the rounded surface ", 0), 0u) << what;
  }
}

// Coordinates near 2^877 (as the solid_writer fuzz target found): the
// squared displacement overflowed doubles and the note said "inf".
TEST(RoundSolid, DisplacementOfHugeCoordinatesIsFinite) {
  const Mesh m = cube_with_top_point(Point3(Rational(1, 3), Rational(1, 3), Rational(1)));
  PointList pts;
  for (std::size_t i = 0; i < m.points.size(); ++i) pts.push_back(Rational(Integer(1) << 880, 7) * m.points[i]);
  Mesh huge = m;
  huge.points = pts;
  const RoundedSolid r = round_solid(huge, false, "huge.off");
  ASSERT_GT(r.rounded_coordinates, 0u);
  EXPECT_TRUE(std::isfinite(r.max_displacement));
  // At most half an ulp of 2^880 / 7 in each of the three coordinates.
  EXPECT_GT(r.max_displacement, 0.0);
  EXPECT_LE(r.max_displacement, std::sqrt(3.0) * std::ldexp(1.0, 880 - 53));
}

TEST(RoundSolid, SurfaceTouchingItselfAlongAnEdgeIsRefused) {
  // Two boxes sharing the edge x = y = 1/3, equal points welded (as in a
  // sum's mesh), scaled by 1/3 so that rounding is needed.
  const Mesh joined = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 0, 1));
  Mesh m;
  std::map<Point3, Index> id;
  std::vector<Index> to(joined.points.size());
  for (std::size_t i = 0; i < joined.points.size(); ++i) {
    const Point3 p = Rational(1, 3) * joined.points[i];
    auto [it, fresh] = id.emplace(p, Index(m.points.size()));
    if (fresh) m.points.push_back(p);
    to[i] = it->second;
  }
  for (auto f : joined.faces) {
    for (Index& v : f) v = to[v];
    m.faces.push_back(f);
  }
  ASSERT_EQ(m.points.size(), 14u);
  try {
    round_solid(m, false, "m.off");
    FAIL() << "no RoundingError";
  } catch (const RoundingError& e) {
    EXPECT_NE(std::string(e.what()).find("touches itself along"), std::string::npos) << e.what();
  }
}
