// round_solid (src/nonconvex/round.cpp, docs/nonconvex.md "Output"): an exact
// solid written in doubles or floats as a valid solid, points that round
// together merged, degenerate triangles removed with the surface kept
// closed, the largest displacement reported, and clear refusals.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex/validate.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

namespace {

// `m` scaled by s, exactly equal points welded (as in a sum's mesh).
Mesh welded(const Mesh& m, const Rational& s) {
  Mesh out;
  std::map<Point3, Index> id;
  std::vector<Index> to(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = s * m.points[i];
    auto [it, fresh] = id.emplace(p, Index(out.points.size()));
    if (fresh) out.points.push_back(p);
    to[i] = it->second;
  }
  for (auto f : m.faces) {
    for (Index& v : f) v = to[v];
    out.faces.push_back(f);
  }
  return out;
}

// The closed surface's shells (connected by edges).
std::size_t shells(const Mesh& m) {
  std::vector<Index> parent(m.points.size());
  for (Index i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : m.faces)
    for (Index v : f) parent[find(v)] = find(f[0]);
  std::size_t n = 0;
  for (Index i = 0; i < parent.size(); ++i) n += find(i) == i;
  return n;
}

// Checks every property round_solid promises of r (from `exact`, whose
// surface has area below `area`): a valid solid of doubles (floats), its
// volume within area times the displacement of the exact one.
void expect_valid_rounding(const RoundedSolid& r, const Mesh& exact, bool floats, double area) {
  const Solid s = validate_solid(r.mesh, "rounded");
  for (std::size_t i = 0; i < r.mesh.points.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double d = to_double(r.mesh.points[i][k]);
      EXPECT_EQ(Rational(floats ? double(float(d)) : d), r.mesh.points[i][k]);
    }
  EXPECT_LE(std::fabs(to_double(s.volume - mesh_volume(exact))), area * r.max_displacement);
}

}  // namespace

// Two boxes sharing the edge x = y = 1/3 (scaled by 1/3 so that rounding is
// needed): the edge belongs to four faces, which no valid solid file holds.
// The surface is cut apart along it, each box keeping its own copy of the
// edge, moved a few spacings into its own box: two shells that no longer
// touch.
TEST(RoundSolid, SurfaceTouchingItselfAlongAnEdgeIsCutApart) {
  const Mesh m = welded(join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 0, 1)), Rational(1, 3));
  ASSERT_EQ(m.points.size(), 14u);
  for (bool floats : {false, true}) {
    const RoundedSolid r = round_solid(m, floats, "m.off");
    EXPECT_GT(r.rounded_coordinates, 0u);
    EXPECT_EQ(r.mesh.points.size(), 16u);
    EXPECT_EQ(r.mesh.faces.size(), 24u);
    EXPECT_EQ(shells(r.mesh), 2u);
    EXPECT_GT(r.max_displacement, 0.0);
    // A few spacings at 2/3.
    EXPECT_LE(r.max_displacement, 8 * std::ldexp(1.0, floats ? -24 : -53));
    expect_valid_rounding(r, m, floats, 5);
  }
}

// The same with integer coordinates: nothing needs rounding, but the edge
// of four faces still has to be cut apart for a valid solid.
TEST(RoundSolid, SurfaceTouchingItselfWithoutRoundingIsCutApart) {
  const Mesh m = welded(join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 0, 1)), Rational(1));
  const RoundedSolid r = round_solid(m, false, "m.off");
  EXPECT_EQ(r.rounded_coordinates, 0u);
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(shells(r.mesh), 2u);
  EXPECT_GT(r.max_displacement, 0.0);
  EXPECT_LE(r.max_displacement, 8 * std::ldexp(1.0, -52));
  expect_valid_rounding(r, m, false, 13);
}

// Two boxes touching at the corner (1,1,1)/3 only: the vertex has two fans,
// each gets its own point.
TEST(RoundSolid, SurfaceTouchingItselfAtAVertexIsCutApart) {
  const Mesh m = welded(join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 1, 2)), Rational(1, 3));
  ASSERT_EQ(m.points.size(), 15u);
  const RoundedSolid r = round_solid(m, true, "m.stl");
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(shells(r.mesh), 2u);
  expect_valid_rounding(r, m, true, 5);
}

namespace {

// The diagonal cubes [0,1]^3 and [1+g,2+g]^2 x [0,1], each ⊕ [-1/2,1/2]^3,
// scaled by 1/3: for g = 1 the sums touch along an edge, for g a hair more
// they are a hair apart, for g a hair less they overlap in a thin neck.
NonconvexSum diagonal_cubes_sum(const Rational& g) {
  const Mesh two = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1 + g, 2 + g, 1 + g, 2 + g, 0, 1));
  NonconvexSum s = minkowski_sum_nonconvex(validate_solid(two, "diagonal"),
                                           validate_solid(catalog_mesh("box:1:1:1"), "box"));
  PointList third;
  for (std::size_t i = 0; i < s.mesh.points.size(); ++i) third.push_back(Rational(1, 3) * s.mesh.points[i]);
  s.mesh.points = third;
  return s;
}

}  // namespace

// A sum whose two parts touch along an edge (as in
// NonconvexSum.SumsTouchingAlongAnEdgeKeepANonManifoldEdge): written as two
// shells.
TEST(RoundSolid, SumTouchingItselfAlongAnEdgeIsWrittenAsTwoShells) {
  const NonconvexSum s = diagonal_cubes_sum(1);
  ASSERT_EQ(s.non_manifold_edges, 1u);
  for (bool floats : {false, true}) {
    const RoundedSolid r = round_solid(s.mesh, floats, "s.stl");
    EXPECT_EQ(shells(r.mesh), 2u);
    expect_valid_rounding(r, s.mesh, floats, 12);
  }
}

// The parts a hair apart: rounding puts their edges on one line, an edge of
// four faces; the points merged there are pushed apart along their exact
// offsets, which opens the gap again.
TEST(RoundSolid, SumsNearlyTouchingAlongAnEdgeAreKeptApart) {
  const NonconvexSum s = diagonal_cubes_sum(1 + kTiny);
  ASSERT_EQ(s.non_manifold_edges, 0u);
  for (bool floats : {false, true}) {
    const RoundedSolid r = round_solid(s.mesh, floats, "s.stl");
    EXPECT_EQ(r.mesh.faces.size(), 24u);
    EXPECT_EQ(shells(r.mesh), 2u);
    EXPECT_LE(r.max_displacement, 16 * std::ldexp(1.0, floats ? -24 : -53));
    expect_valid_rounding(r, s.mesh, floats, 12);
  }
}

// The parts overlapping in a neck a hair wide: rounding collapses the neck
// onto an edge of four faces; its points are pushed apart along their exact
// offsets, which keeps the neck, a few spacings wide.
TEST(RoundSolid, NeckThinnerThanTheSpacingIsWidened) {
  const NonconvexSum s = diagonal_cubes_sum(1 - kTiny);
  ASSERT_EQ(s.non_manifold_edges, 0u);
  for (bool floats : {false, true}) {
    const RoundedSolid r = round_solid(s.mesh, floats, "s.stl");
    EXPECT_EQ(shells(r.mesh), 1u);
    EXPECT_EQ(r.mesh.faces.size(), 28u);
    EXPECT_LE(r.max_displacement, 16 * std::ldexp(1.0, floats ? -24 : -53));
    expect_valid_rounding(r, s.mesh, floats, 12);
  }
}

// A box [0,1] x [0,3] x [0,1] whose top is cut into four triangles around
// m = (1/3, 1 - 2^-60/3, 1), a hair below the diagonal y = 3x: the sliver
// (0,0,1) m (1,3,1) is counter-clockwise, but m rounds to (1/3 - 2^-54/3, 1,
// 1), above the diagonal, and the sliver folds over its neighbour across the
// diagonal (the nearest rounding is not a valid solid).  The points of the
// offending triangles are snapped to the grid of the spacing at 3, where m
// is on the right side again.
TEST(RoundSolid, FacesThatRoundingMakesCrossAreSnappedApart) {
  Mesh m;
  auto add = [&](const Rational& x, const Rational& y, const Rational& z) { m.points.push_back(Point3(x, y, z)); };
  add(0, 0, 0);  // 0
  add(1, 0, 0);  // 1
  add(1, 3, 0);  // 2
  add(0, 3, 0);  // 3
  add(0, 0, 1);  // 4 A
  add(1, 0, 1);  // 5 B
  add(1, 3, 1);  // 6 C
  add(0, 3, 1);  // 7 D
  add(Rational(1, 3), 1 - kTiny, 1);  // 8 m
  m.faces = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
             {4, 5, 8},    {5, 6, 8},    {4, 8, 6},    {4, 6, 7}};
  ASSERT_NO_THROW(validate_solid(m, "m.off"));
  // Rounded to the nearest, the sliver crosses its neighbour.
  Mesh nearest = m;
  nearest.points = PointList();
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = m.points[i];
    nearest.points.push_back(Point3(Rational(to_double(p.x)), Rational(to_double(p.y)), Rational(to_double(p.z))));
  }
  ASSERT_EQ(nearest.points[8].y, Rational(1));
  EXPECT_THROW(validate_solid(nearest, "nearest"), InputError);
  const RoundedSolid r = round_solid(m, false, "m.off");
  EXPECT_EQ(r.rounded_coordinates, 2u);
  EXPECT_GT(r.grid, 0.0);
  EXPECT_EQ(r.mesh.points.size(), 9u);
  EXPECT_EQ(r.mesh.faces.size(), 14u);
  const Solid s = validate_solid(r.mesh, "r.off");
  EXPECT_EQ(s.volume, Rational(3));  // every point stays in its face's plane
  EXPECT_LE(r.max_displacement, 4 * std::ldexp(1.0, -51));
}

// Two boxes 2^-60/3 apart, the upper one shifted by half its width: rounding
// puts the lower one's top and the upper one's bottom in one plane, where
// they overlap.  Both are pushed a few spacings into their own box, opening
// the gap again.
TEST(RoundSolid, GapThatRoundingClosesIsPushedOpen) {
  const Rational z(1, 3);
  const Mesh m = join(box_mesh(0, 1, 0, 1, 0, z), box_mesh(Rational(1, 2), Rational(3, 2), 0, 1, z + kTiny, 1));
  ASSERT_NO_THROW(validate_solid(m, "m.off"));
  for (bool floats : {false, true}) {
    const RoundedSolid r = round_solid(m, floats, "m.off");
    EXPECT_EQ(r.mesh.points.size(), 16u);
    EXPECT_EQ(r.mesh.faces.size(), 24u);
    EXPECT_EQ(shells(r.mesh), 2u);
    EXPECT_LE(r.max_displacement, 8 * std::ldexp(1.0, floats ? -24 : -53));
    expect_valid_rounding(r, m, floats, 9);
  }
}

// A slab thinner than the spacing of doubles everywhere collapses: refused.
TEST(RoundSolid, SolidThinnerThanTheSpacingEverywhereIsRefused) {
  const Rational z(1, 3);
  try {
    round_solid(box_mesh(0, 1, 0, 1, z, z + kTiny), false, "slab.off");
    FAIL() << "no RoundingError";
  } catch (const RoundingError& e) {
    EXPECT_STREQ(e.what(),
                 "the rounded surface collapses (every face degenerates: the solid is thinner than the spacing of "
                 "doubles)");
  }
}

// check_surface, the test of the rounded surface before it is written,
// decides the orientation from the sign of the volume on intervals: an
// inward cube is refused as validate_surface refuses it, and so it is at
// 2^-1000 of the size, where the intervals of the volume's terms hold zero
// and the sign is decided exactly.
TEST(RoundSolid, CheckOfTheRoundedSurfaceRefusesInwardFacesFromTheVolumesSign) {
  for (const int e : {0, -1000}) {
    Mesh m = cube_with_top_point(Point3(Rational(1, 2), Rational(1, 4), Rational(1)));
    Mesh scaled;
    const Rational s = e == 0 ? Rational(1) : Rational(Integer(1), Integer(1) << 1000);
    for (std::size_t i = 0; i < m.points.size(); ++i) scaled.points.push_back(s * m.points[i]);
    scaled.faces = m.faces;
    ASSERT_TRUE(scaled.points.all_doubles()) << e;
    EXPECT_NO_THROW(nonconvex_detail::check_surface(scaled, "m.off")) << e;
    for (auto& f : scaled.faces) std::reverse(f.begin(), f.end());
    try {
      nonconvex_detail::check_surface(scaled, "m.off");
      ADD_FAILURE() << "an inward cube passed at 2^" << e;
    } catch (const InputError& err) {
      EXPECT_NE(std::string(err.what()).find("oriented inwards"), std::string::npos) << err.what();
    }
  }
}
