// Erosion, opening and closing of solids by convex polytopes
// (docs/nonconvex.md, "Erosion, opening, closing"): against CGAL's Nef
// polyhedra through complements (reference_erosion), closed forms, and
// properties.
#include <minksum/catalog.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex/morphology.hpp"
#include "nonconvex/union.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace minksum;
using namespace minksum::testing;

namespace {

Solid solid(const std::string& spec) { return validate_solid(catalog_mesh(spec), spec); }

Rational R(const char* s) { return Rational(s); }

ConvexPolytope box(const char* x0, const char* x1, const char* y0, const char* y1, const char* z0, const char* z1) {
  return ConvexPolytope::from_mesh(box_mesh(R(x0), R(x1), R(y0), R(y1), R(z0), R(z1)), "box");
}

// The union of boxes as a validated solid (minksum's exact union).
Solid union_solid(const std::vector<ConvexPolytope>& parts) {
  NonconvexSum u;
  nonconvex_detail::union_boundary(parts, {}, u);
  return validate_solid(u.mesh, "union");
}

// The same solid: exact volume, vertex set and face planes (faces merged).
void expect_same(const Mesh& got, const Mesh& want) {
  EXPECT_EQ(mesh_volume(got), mesh_volume(want));
  EXPECT_EQ(face_planes(got), face_planes(want));
  EXPECT_EQ(vertex_set(got), vertex_set(want));
}

void expect_like_oracle(const std::string& a, const std::string& b) {
  SCOPED_TRACE(a + " eroded by " + b);
  const Solid sa = solid(a), sb = solid(b);
  const NonconvexSum r = erode(sa, sb);
  const Mesh o = reference_erosion(sa, sb);
  EXPECT_EQ(r.volume, mesh_volume(o));
  EXPECT_EQ(face_planes(r.mesh), face_planes(o));
  if (!r.mesh.faces.empty()) expect_closed_oriented(r);
}

}  // namespace

// --- against CGAL: A minus minkowski_sum_3(box - A, -B) ----------------------

TEST(ErosionOracle, LShapeByOctahedron) { expect_like_oracle("lshape", "octahedron@scale:1/5"); }
TEST(ErosionOracle, TubeByRotatedCube) { expect_like_oracle("tube", "cube@scale:1/8@rot:3"); }
TEST(ErosionOracle, StarByIcosahedron) { expect_like_oracle("star:5", "sphere:1@scale:1/12"); }
TEST(ErosionOracle, BallOffCentre) { expect_like_oracle("lshape@rot:5", "sphere:1@scale:1/10@translate:1/7,0,1/9"); }
TEST(ErosionOracle, CubeOffCentre) { expect_like_oracle("lshape", "cube@scale:1/10@translate:1/8,0,0"); }
TEST(ErosionOracle, ConvexA) { expect_like_oracle("sphere:1", "tetra@scale:1/5"); }

// Random unions of boxes with small integer corners (those that are solids:
// no two boxes touching along an edge only) eroded by random small convex
// polytopes (hulls of a few points of a grid of 1/4, off the origin):
// against CGAL.
TEST(ErosionOracle, RandomBoxUnionsByRandomPolytopes) {
  int checked = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coord(0, 4), count(1, 3), quarter(-3, 3), points(4, 7);
    std::vector<ConvexPolytope> parts;
    for (int n = count(rng); int(parts.size()) < n;) {
      int c[6];
      for (int& x : c) x = coord(rng);
      if (c[0] == c[1] || c[2] == c[3] || c[4] == c[5]) continue;
      parts.push_back(ConvexPolytope::from_mesh(
          box_mesh(Rational(std::min(c[0], c[1])), Rational(std::max(c[0], c[1])), Rational(std::min(c[2], c[3])),
                   Rational(std::max(c[2], c[3])), Rational(std::min(c[4], c[5])), Rational(std::max(c[4], c[5]))),
          "box"));
    }
    std::optional<ConvexPolytope> b;
    while (!b) {
      std::vector<Point3> p;
      for (int k = points(rng); int(p.size()) < k;)
        p.emplace_back(Rational(quarter(rng), 4), Rational(quarter(rng), 4), Rational(quarter(rng), 4));
      try {
        b = ConvexPolytope::hull(p, "random");
      } catch (const InputError&) {  // flat: draw again
      }
    }
    Solid a;
    try {
      a = union_solid(parts);
    } catch (const InputError&) {  // boxes touching along an edge: not a solid
      continue;
    }
    const Solid sb = solid_of(*b);
    const NonconvexSum r = erode(a, sb);
    const Mesh o = reference_erosion(a, sb);
    EXPECT_EQ(r.volume, mesh_volume(o));
    EXPECT_EQ(face_planes(r.mesh), face_planes(o));
    if (!r.mesh.faces.empty()) expect_closed_oriented(r);
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

// --- closed forms ------------------------------------------------------------

TEST(Erosion, BoxByBoxIsABox) {
  const Solid a = solid("box:4:6:8"), b = solid("box:1:2:3@translate:1/2,0,-1/4");
  const NonconvexSum r = erode(a, b);
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(3 * 4 * 5));
  EXPECT_EQ(r.shells, 1u);
  // A = [-2,2] x [-3,3] x [-4,4], B = [0,1] x [-1,1] x [-7/4,5/4]: each of
  // A's faces moved in by B's support along its normal.
  expect_same(r.mesh, box_mesh(R("-2"), R("1"), R("-2"), R("2"), R("-9/4"), R("11/4")));
  EXPECT_EQ(r.operation, std::string("erosion"));
}

TEST(Erosion, ConvexAIsItsFacetsMovedBySupport) {
  // A ⊖ B for convex A: the half-spaces a.x <= d - h_B(a) of A's facets.
  const Solid a = solid("sphere:2"), b = solid("cube@scale:1/40@rot:4");
  const NonconvexSum r = erode(a, b);
  expect_closed_oriented(r);
  const ConvexPolytope e = ConvexPolytope::from_mesh(r.mesh, "erosion");  // convex
  std::set<Plane> moved;
  for (Index f = 0; f < a.convex->num_facets(); ++f) {
    const Plane& h = a.convex->plane(f);
    Rational support = dot(h.normal(), b.convex->points().front());
    for (const Point3& p : b.convex->points()) support = std::max(support, Rational(dot(h.normal(), p)));
    moved.insert(canonical_plane(h.normal(), Rational(Rational(h.d) - support) / dot(h.normal(), h.normal()) * h.normal()));
  }
  for (Index f = 0; f < e.num_facets(); ++f) EXPECT_TRUE(moved.count(e.plane(f))) << "facet " << f;
  EXPECT_LT(e.volume(), a.volume);
}

// The erosion of a convex A is the same polytope, vertex for vertex and
// facet for facet, whatever the heap looks like: CGAL lists the dual hull in
// an order that follows memory addresses, and halfspace_erosion numbers it
// by its input.  (Python's opening of a dodecahedron by a ball wrote one of
// two triangulations of the same faces, call after call.)  Blocks of
// various sizes are allocated between the calls, and each call is made on
// fresh copies of the operands.
TEST(Erosion, ConvexErosionDoesNotDependOnTheHeap) {
  const Solid a0 = solid("dodecahedron"), b0 = solid("sphere:2@scale:1/10");
  auto loops = [](const ConvexPolytope& p) {
    std::vector<std::vector<Index>> out;
    for (Index f = 0; f < p.num_facets(); ++f) out.push_back(p.facet_vertices(f));
    return out;
  };
  const ConvexPolytope first = *nonconvex_detail::halfspace_erosion(*a0.convex, *b0.convex);
  std::vector<std::unique_ptr<char[]>> noise;
  for (int i = 0; i < 24; ++i) {
    for (int k = 0; k <= i % 5; ++k) noise.push_back(std::make_unique<char[]>(std::size_t(48 + 40 * k * i)));
    const Solid a = a0, b = b0;
    const std::optional<ConvexPolytope> e = nonconvex_detail::halfspace_erosion(*a.convex, *b.convex);
    ASSERT_TRUE(e);
    ASSERT_EQ(e->points(), first.points()) << "call " << i;
    ASSERT_EQ(loops(*e), loops(first)) << "call " << i;
    const NonconvexSum o = opening(a, b);
    ASSERT_TRUE(o.convex);
    if (i % 3 == 0) noise.erase(noise.begin(), noise.begin() + std::ptrdiff_t(noise.size() / 2));
  }
}

// The erosion of a convex A swept (A's convex polytope left out of the
// Solid, so that erode takes the sweep of any A).
NonconvexSum swept_erosion(Solid a, const Solid& b) {
  a.convex.reset();
  return erode(a, b);
}

// erode's result for a convex A (the half-space intersection, halfspace_erosion)
// against the sweep and against convex_erosion (CGAL's
// halfspace_intersection_3 on exact points): the same polytope exactly, the
// result a valid polytope (every invariant re-checked from scratch).
void expect_three_ways(const Solid& sa, const Solid& sb) {
  const std::optional<ConvexPolytope> fast = nonconvex_detail::halfspace_erosion(*sa.convex, *sb.convex);
  ASSERT_TRUE(fast);
  EXPECT_EQ(fast->check_invariants(), "");
  const NonconvexSum r = erode(sa, sb), swept = swept_erosion(sa, sb);
  ASSERT_TRUE(r.convex);
  expect_closed_oriented(r);
  expect_closed_oriented(swept);
  expect_same(r.mesh, fast->to_mesh());
  expect_same(r.mesh, swept.mesh);
  EXPECT_EQ(r.volume, swept.volume);
  EXPECT_EQ(r.volume, fast->volume());
  const std::optional<ConvexPolytope> oracle = nonconvex_detail::convex_erosion(*sa.convex, *sb.convex);
  ASSERT_TRUE(oracle);
  expect_same(r.mesh, oracle->to_mesh());
}

// For convex A, the intersection of A's facet half-spaces moved by B's
// support, three ways: the same polytope exactly.
TEST(Erosion, ConvexAIsTheIntersectionOfTheMovedHalfSpaces) {
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"sphere:2", "cube@scale:1/9@rot:4"},
           {"dodecahedron", "tetra@scale:1/5@translate:1/3,1/7,0"},
           {"dodecahedron", "sphere:2@scale:1/7"},
           {"box:4:6:8", "cube@rot:3@scale:1/2"},
           {"cube", "sphere:1@scale:1/3"},
           {"octahedron@rot:2", "octahedron@scale:1/2"}}) {
    SCOPED_TRACE(a + " eroded by " + b);
    expect_three_ways(solid(a), solid(b));
  }
  // Empty, and exactly the size of A (a point): no point strictly inside.
  EXPECT_FALSE(nonconvex_detail::convex_erosion(catalog_polytope("cube"), catalog_polytope("cube@scale:2")));
  EXPECT_FALSE(nonconvex_detail::convex_erosion(catalog_polytope("cube"), catalog_polytope("cube")));
}

// Random convex polytopes (hulls of points of a grid of 1/8, fixed seeds)
// eroded by a small ball: three ways, the same polytope.
TEST(Erosion, RandomConvexPolytopeByASmallBall) {
  const Solid ball = solid("sphere:2@scale:1/16@translate:1/32,-1/64,0");
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> eighth(-8, 8);
    std::vector<Point3> p;
    while (p.size() < 40) p.emplace_back(Rational(eighth(rng), 8), Rational(eighth(rng), 8), Rational(eighth(rng), 8));
    expect_three_ways(solid_of(ConvexPolytope::hull(p, "random")), ball);
  }
}

// Degenerate duals.  The cube [-1,1]^3 with its corner (1,1,1) cut off by
// x + y + z <= 5/2, eroded by the octahedron of radius 1/4: each face moves
// in by 1/4, the cut too (B's support along (1,1,1) is 1/4), so the cut's
// moved plane x + y + z = 9/4 touches the eroded cube [-3/4,3/4]^3 at its
// corner only (a redundant plane whose dual point lies inside a facet of the
// dual hull).  And the octahedron eroded by the octahedron of half its size:
// the support ties along every facet normal, the result is the octahedron
// of radius 1/2 with its vertices of degree 4 (dual facets of four points).
TEST(Erosion, DegenerateDualHullsOnTheHalfSpacePath) {
  std::vector<Point3> p;
  for (int x : {-1, 1})
    for (int y : {-1, 1})
      for (int z : {-1, 1})
        if (x + y + z < 3) p.emplace_back(Rational(x), Rational(y), Rational(z));
  p.emplace_back(R("1"), R("1"), R("1/2"));
  p.emplace_back(R("1"), R("1/2"), R("1"));
  p.emplace_back(R("1/2"), R("1"), R("1"));
  const Solid cut = solid_of(ConvexPolytope::hull(p, "cut cube")), b = solid("octahedron@scale:1/4");
  expect_three_ways(cut, b);
  const NonconvexSum r = erode(cut, b);
  expect_same(r.mesh, box_mesh(R("-3/4"), R("3/4"), R("-3/4"), R("3/4"), R("-3/4"), R("3/4")));
  EXPECT_EQ(r.pair_facets, 7u);
  EXPECT_EQ(r.candidate_facets, 6u);
  const Solid o = solid("octahedron"), half = solid("octahedron@scale:1/2");
  expect_three_ways(o, half);
  expect_same(erode(o, half).mesh, half.convex->to_mesh());
}

// A cube eroded by a smaller box: the box of the closed form, on the
// half-space path (one pair, no union), with its exact volume.
TEST(Erosion, CubeBySmallBoxIsTheBoxOnTheHalfSpacePath) {
  // cube = [-1,1]^3, B = [-1/8,1/8] x [-1/4,1/4] x [-1/2,1/2] + (1/4, 0, -1/8).
  const Solid a = solid("cube"), b = solid("box:1/4:1/2:1@translate:1/4,0,-1/8");
  const NonconvexSum r = erode(a, b);
  ASSERT_TRUE(r.convex);
  expect_same(r.mesh, box_mesh(R("-9/8"), R("5/8"), R("-3/4"), R("3/4"), R("-3/8"), R("5/8")));
  EXPECT_EQ(r.volume, Rational(21, 8));
  EXPECT_EQ(r.operation, std::string("erosion"));
  EXPECT_EQ(std::string(r.method), "decomposition");
  EXPECT_EQ(r.pairs, 1u);
  EXPECT_EQ(r.pair_facets, 6u);       // the moved half-spaces
  EXPECT_EQ(r.candidate_facets, 6u);  // the erosion's facets
  EXPECT_EQ(r.clips, 0u);
  EXPECT_EQ(r.shells, 1u);
}

// B exactly as wide as A in one direction (a flat erosion), in two (a
// segment), in three (a point), or wider (nothing): no point strictly inside,
// so the sweep decides, and the regularised erosion is empty.
TEST(Erosion, ExactlyFittingOrTooWideBOnAConvexAIsEmpty) {
  const Solid a = solid("box:4:6:8");
  for (const char* b : {"box:4:1:1", "box:4:6:1", "box:4:6:8", "box:5:1:1", "cube@scale:4"}) {
    SCOPED_TRACE(b);
    const Solid sb = solid(b);
    EXPECT_FALSE(nonconvex_detail::halfspace_erosion(*a.convex, *sb.convex));
    const NonconvexSum r = erode(a, sb);
    EXPECT_TRUE(r.mesh.faces.empty());
    EXPECT_EQ(r.volume, Rational(0));
    EXPECT_FALSE(r.convex);
    const NonconvexSum swept = swept_erosion(a, sb);
    EXPECT_EQ(r.mesh.faces, swept.mesh.faces);
    EXPECT_EQ(r.dropped_components, swept.dropped_components);
    EXPECT_TRUE(opening(a, sb).mesh.faces.empty());
  }
  // Just narrower than A: a thin box, on the half-space path.
  const NonconvexSum thin = erode(a, solid("box:4:6:8@scale:999/1000"));
  ASSERT_TRUE(thin.convex);
  EXPECT_EQ(thin.volume, Rational(4 * 6 * 8) / Rational(1000 * 1000 * 1000));
}

// A convex A whose vertex centroid (minus B's) lies outside the erosion: a
// long thin tetrahedron, its erosion by a ball small near the incentre.
// halfspace_erosion finds no point strictly inside, and erode's sweep gives
// the same solid as the CGAL construction.
TEST(Erosion, ConvexAWhoseCentroidIsOutsideTheErosionIsSwept) {
  const Solid a = solid_of(ConvexPolytope::hull(
      std::vector<Point3>{Point3(0.0, 0.0, 0.0), Point3(100.0, 0.0, 0.0), Point3(0.0, 1.0, 0.0),
                          Point3(0.0, 0.0, 1.0)},
      "tetra"));
  const Solid b = solid("sphere:1@scale:1/5");
  EXPECT_FALSE(nonconvex_detail::halfspace_erosion(*a.convex, *b.convex));
  const NonconvexSum r = erode(a, b);
  EXPECT_FALSE(r.convex);
  expect_closed_oriented(r);
  const std::optional<ConvexPolytope> oracle = nonconvex_detail::convex_erosion(*a.convex, *b.convex);
  ASSERT_TRUE(oracle);
  expect_same(r.mesh, oracle->to_mesh());
}

// The closing of a convex A is A ((A ⊕ B) ⊖ B = A for convex A and B), both
// steps convex (the convex path, then the half-space intersection).
TEST(Erosion, ClosingOfAConvexAIsA) {
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"dodecahedron", "sphere:2@scale:1/5"}, {"box:4:6:8@rot:3", "tetra@scale:1/3"}}) {
    SCOPED_TRACE(a + " closed by " + b);
    const Solid sa = solid(a), sb = solid(b);
    const NonconvexSum k = closing(sa, sb);
    ASSERT_TRUE(k.convex);
    expect_same(k.mesh, sa.convex->to_mesh());
    EXPECT_EQ(k.volume, sa.volume);
    EXPECT_EQ(k.operation, std::string("closing"));
    EXPECT_EQ(k.pairs, 2u);  // one pair each step
  }
}

// The opening of a convex A: its erosion is convex (the moved half-spaces),
// and the opening is that polytope ⊕ B, whose facets are the boundary: the
// same solid as the convex sum of the direct erosion, and as the union of
// that one polytope (the non-convex engine's sum of two convex solids).
TEST(Erosion, OpeningOfAConvexAIsTheConvexSumOfItsErosion) {
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"sphere:2", "cube@scale:1/9@rot:4"},
           {"box:4:6:8", "cube@rot:3@scale:1/2"},
           {"cube", "sphere:1@scale:1/3"},
           {"dodecahedron", "tetra@scale:1/5@translate:1/3,1/7,0"}}) {
    SCOPED_TRACE(a + " opened by " + b);
    const Solid sa = solid(a), sb = solid(b);
    const NonconvexSum o = opening(sa, sb);
    const std::optional<ConvexPolytope> e = nonconvex_detail::convex_erosion(*sa.convex, *sb.convex);
    ASSERT_TRUE(e);
    const ConvexPolytope want = minkowski_sum(*e, *sb.convex).polytope;
    expect_closed_oriented(o);
    expect_same(o.mesh, want.to_mesh());
    EXPECT_EQ(o.volume, want.volume());
    EXPECT_EQ(o.shells, 1u);
    EXPECT_EQ(o.non_manifold_edges, 0u);
    expect_same(o.mesh, minkowski_sum_nonconvex(solid_of(*e), sb).mesh);
  }
}

TEST(Erosion, SumThenErosionGivesBackTheSummand) {
  const ConvexPolytope p = catalog_polytope("octahedron@rot:2"), b = catalog_polytope("dodecahedron@scale:1/3");
  const ConvexPolytope s = minkowski_sum(p, b).polytope;
  const NonconvexSum r = erode(solid_of(s), solid_of(b));
  const ConvexPolytope e = ConvexPolytope::from_mesh(r.mesh, "erosion");
  EXPECT_EQ(e.volume(), p.volume());
  std::set<Point3> want, got;
  for (const Point3& q : p.points()) want.insert(q);
  for (const Point3& q : e.points()) got.insert(q);
  EXPECT_EQ(got, want);
}

TEST(Erosion, LShapeOpenedOrClosedByASmallerCubeIsItself) {
  const Solid l = solid("lshape"), c = solid("cube@scale:1/8");
  const Mesh want = solid_faces(l);
  const NonconvexSum o = opening(l, c);
  expect_closed_oriented(o);
  expect_same(o.mesh, want);
  EXPECT_EQ(o.operation, std::string("opening"));
  const NonconvexSum k = closing(l, c);
  expect_closed_oriented(k);
  expect_same(k.mesh, want);
  EXPECT_EQ(k.operation, std::string("closing"));
}

TEST(Erosion, ThatEmptiesTheSolid) {
  const Solid a = solid("cube"), b = solid("cube@scale:3/2");
  const NonconvexSum r = erode(a, b);
  EXPECT_TRUE(r.mesh.faces.empty());
  EXPECT_TRUE(r.mesh.points.empty());
  EXPECT_EQ(r.volume, Rational(0));
  EXPECT_EQ(r.shells, 0u);
  EXPECT_GE(r.dropped_components, 1u);
  // B exactly A's size: the erosion is one point, empty once regularised.
  EXPECT_TRUE(erode(a, solid("cube")).mesh.faces.empty());
  // The opening of nothing is nothing.
  EXPECT_TRUE(opening(solid("lshape"), solid("cube@scale:3/4")).mesh.faces.empty());
}

TEST(Erosion, ThatSplitsTheSolidIntoTwoShells) {
  // Two cubes of side 2 joined by a bar of side 1/2: a cube of side 1 fits
  // in the cubes only.
  const Solid a = union_solid({box("0", "2", "0", "2", "0", "2"), box("2", "4", "3/4", "5/4", "3/4", "5/4"),
                               box("4", "6", "0", "2", "0", "2")});
  const NonconvexSum r = erode(a, solid("cube@scale:1/2"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_EQ(r.volume, Rational(2));
  expect_same(r.mesh, join(box_mesh(R("1/2"), R("3/2"), R("1/2"), R("3/2"), R("1/2"), R("3/2")),
                           box_mesh(R("9/2"), R("11/2"), R("1/2"), R("3/2"), R("1/2"), R("3/2"))));
  // Opened, the bar is gone.
  const NonconvexSum o = opening(a, solid("cube@scale:1/2"));
  EXPECT_EQ(o.volume, Rational(16));
  EXPECT_EQ(o.shells, 2u);
}

TEST(Erosion, WithACavityKeepsAndGrowsIt) {
  // The hollow cube [-2,2]^3 minus [-1,1]^3 eroded by a cube of side 1/2:
  // [-7/4,7/4]^3 minus [-5/4,5/4]^3.
  const Solid a = validate_solid(hollow_cube(), "hollow");
  const NonconvexSum r = erode(a, solid("cube@scale:1/4"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_EQ(r.volume, Rational(343, 8) - Rational(125, 8));
}

TEST(Erosion, OpeningOfErosionTouchingItselfAlongAnEdge) {
  // Two boxes overlapping in a column: eroded by the cube of side 1, two
  // boxes touching along an edge (a non-manifold edge); opened, A itself.
  const Solid a = union_solid({box("0", "2", "0", "2", "0", "2"), box("1", "3", "1", "3", "0", "2")});
  const Solid c = solid("cube@scale:1/2");
  const NonconvexSum e = erode(a, c);
  expect_closed_oriented(e);
  EXPECT_EQ(e.non_manifold_edges, 1u);
  EXPECT_EQ(e.volume, Rational(2));
  const NonconvexSum o = opening(a, c);
  expect_closed_oriented(o);
  expect_same(o.mesh, solid_faces(a));
}

TEST(Erosion, ClosingOfASumTouchingItselfAlongAnEdge) {
  // Two unit cubes diagonal to each other, ⊕ [-1/2,1/2]^3: two boxes
  // touching along the edge x = y = 3/2 (swept reversed, cut apart across
  // the complement); eroded back, the two cubes.
  const Solid a = validate_solid(join(box_mesh(R("0"), R("1"), R("0"), R("1"), R("0"), R("1")),
                                      box_mesh(R("2"), R("3"), R("2"), R("3"), R("0"), R("1"))),
                                 "two cubes");
  const Solid c = solid("cube@scale:1/2");
  EXPECT_EQ(minkowski_sum_nonconvex(a, c).non_manifold_edges, 1u);
  const NonconvexSum k = closing(a, c);
  expect_closed_oriented(k);
  EXPECT_EQ(k.shells, 2u);
  expect_same(k.mesh, solid_faces(a));
}

TEST(Erosion, ClosingFillsTheNotchOfAnL) {
  // The L's reflex edge filled by a ball: more than the L, less than its hull.
  const Solid l = solid("lshape"), b = solid("sphere:1@scale:1/4");
  const NonconvexSum k = closing(l, b);
  expect_closed_oriented(k);
  EXPECT_GT(k.volume, l.volume);
  EXPECT_LT(k.volume, Rational(4));
  const NonconvexSum o = opening(l, b);
  expect_closed_oriented(o);
  EXPECT_LT(o.volume, l.volume);
}

// --- properties ------------------------------------------------------------

TEST(Erosion, OpeningInsideAInsideClosingOnATorus) {
  const Solid t = solid("torus:16:8"), b = solid("sphere:1@scale:1/12");
  const NonconvexSum e = erode(t, b);
  expect_closed_oriented(e);
  EXPECT_EQ(solid_stats(e.mesh).genus, 1u);  // the hole kept
  EXPECT_EQ(e.shells, 1u);
  EXPECT_LT(e.volume, t.volume);
  const NonconvexSum o = opening(t, b), k = closing(t, b);
  expect_closed_oriented(o);
  expect_closed_oriented(k);
  EXPECT_LE(o.volume, t.volume);
  EXPECT_GE(k.volume, t.volume);
  EXPECT_LT(e.volume, o.volume);
  // Opening is idempotent: opening the opening gives it back.
  const Solid os = validate_solid(o.mesh, "opening");
  EXPECT_EQ(opening(os, b).volume, o.volume);
}

TEST(Erosion, TranslationOfBMovesTheErosionBack) {
  const Solid a = solid("tube"), b = solid("octahedron@scale:1/6"), bt = solid("octahedron@scale:1/6@translate:1/3,-1/5,1/7");
  const NonconvexSum r = erode(a, b), rt = erode(a, bt);
  EXPECT_EQ(r.volume, rt.volume);
  std::set<Point3> moved;
  for (const Point3& p : vertex_set(rt.mesh)) moved.insert(p + Point3(R("1/3"), R("-1/5"), R("1/7")));
  EXPECT_EQ(moved, vertex_set(r.mesh));
}

TEST(Erosion, BMustBeConvex) {
  EXPECT_THROW(erode(solid("cube"), solid("lshape")), std::invalid_argument);
  EXPECT_THROW(opening(solid("cube"), solid("lshape")), std::invalid_argument);
  EXPECT_THROW(closing(solid("cube"), solid("lshape")), std::invalid_argument);
}

// SumOptions::volume false: the same boundary, volume left 0, and
// mesh_volume of that boundary is the volume the default computes; for the
// two-step operations the first step's volume is still there for the
// second (the same result as with the volume).
TEST(NonconvexVolumeOption, LeftForTheCallerOnEveryOperation) {
  const Solid a = solid("lshape"), b = solid("sphere:1@scale:1/5");
  SumOptions without;
  without.volume = false;
  auto check = [&](const char* name, const NonconvexSum& with, const NonconvexSum& off) {
    SCOPED_TRACE(name);
    ASSERT_FALSE(with.mesh.faces.empty());
    EXPECT_GT(sgn(with.volume), 0);
    EXPECT_EQ(sgn(off.volume), 0);
    EXPECT_EQ(mesh_volume(off.mesh), with.volume);
    EXPECT_EQ(off.mesh.faces, with.mesh.faces);
    EXPECT_EQ(off.mesh.points.size(), with.mesh.points.size());
    EXPECT_EQ(off.shells, with.shells);
  };
  check("sum", minkowski_sum_nonconvex(a, b), minkowski_sum_nonconvex(a, b, without));
  check("sum by decomposition",
        minkowski_sum_nonconvex(a, b, {}, 0, Method::walk, NonconvexMethod::decomposition),
        minkowski_sum_nonconvex(a, b, without, 0, Method::walk, NonconvexMethod::decomposition));
  check("erosion", erode(a, b), erode(a, b, without));
  check("opening", opening(a, b), opening(a, b, without));
  check("closing", closing(a, b), closing(a, b, without));
}
