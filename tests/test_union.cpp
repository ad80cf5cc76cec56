// minksum's exact union of convex polytopes (src/nonconvex/union.cpp, the
// third step of the non-convex sum; docs/nonconvex.md "Method"): closed
// forms of contacts, overlaps, nesting and cavities, and random unions
// checked against CGAL's Nef union (nef_union_boundary): equal exact volume,
// equal sets of vertices and of canonical face planes, equal counts of
// non-manifold edges and shells.
#include <minksum/nonconvex.hpp>

#include "nonconvex/nef.hpp"
#include "nonconvex/union.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <CGAL/assertions_behaviour.h>
#include <CGAL/exceptions.h>
#include <gtest/gtest.h>

#include <random>

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope box(const Rational& x0, const Rational& x1, const Rational& y0, const Rational& y1, const Rational& z0,
                   const Rational& z1) {
  return ConvexPolytope::from_mesh(box_mesh(x0, x1, y0, y1, z0, z1), "box");
}

NonconvexSum ours(const std::vector<ConvexPolytope>& parts, unsigned threads = 0) {
  NonconvexSum r;
  nonconvex_detail::union_boundary(parts, {}, r, threads);
  r.volume = mesh_volume(r.mesh);
  return r;
}

NonconvexSum nef(const std::vector<ConvexPolytope>& parts) {
  NonconvexSum r;
  nonconvex_detail::nef_union_boundary(parts, {}, r);
  r.volume = mesh_volume(r.mesh);
  return r;
}

// The vertices of a that are not vertices of b, as text.
std::vector<std::string> points_only_in(const Mesh& a, const Mesh& b) {
  const std::set<Point3> in_b = vertex_set(b);
  std::vector<std::string> out;
  for (const Point3& p : vertex_set(a))
    if (!in_b.count(p)) out.push_back(format_exact(p.x) + " " + format_exact(p.y) + " " + format_exact(p.z));
  return out;
}

// The union is a valid closed boundary and agrees with the Nef union: its
// exact volume, vertices, face planes, non-manifold edges and volumes.  On
// some non-manifold unions CGAL's conversion of the Nef boundary to polygons
// throws or loses volume; there the Nef union's exact volume, by its convex
// pieces, is the check.
NonconvexSum expect_like_nef(const std::vector<ConvexPolytope>& parts) {
  const NonconvexSum r = ours(parts);
  expect_closed_oriented(r);
  expect_no_vertex_inside_an_edge(r.mesh);
  NonconvexSum o;
  try {
    o = nef(parts);
  } catch (const CGAL::Assertion_exception&) {
    EXPECT_EQ(r.volume, nonconvex_detail::nef_union_volume(parts));
    return r;
  }
  if (o.volume != r.volume) {  // which one is wrong: the Nef union's exact volume decides
    const Rational volume = nonconvex_detail::nef_union_volume(parts);
    EXPECT_EQ(r.volume, volume);
    EXPECT_NE(o.volume, volume);
    return r;
  }
  EXPECT_EQ(points_only_in(r.mesh, o.mesh), std::vector<std::string>{});
  EXPECT_EQ(points_only_in(o.mesh, r.mesh), std::vector<std::string>{});
  EXPECT_EQ(face_planes(r.mesh), face_planes(o.mesh));
  EXPECT_EQ(r.non_manifold_edges, o.non_manifold_edges);
  EXPECT_EQ(r.shells, o.shells);
  return r;
}

}  // namespace

// [0,1]^3 and [1,2]x[0,1]^2: the contact face disappears from both sides.
TEST(Union, TwoCubesFaceToFace) {
  const NonconvexSum r = expect_like_nef({box(0, 1, 0, 1, 0, 1), box(1, 2, 0, 1, 0, 1)});
  EXPECT_EQ(r.volume, Rational(2));
  EXPECT_EQ(r.mesh.points.size(), 8u);
  EXPECT_EQ(r.mesh.faces.size(), 6u);
  EXPECT_EQ(r.shells, 1u);
  EXPECT_EQ(r.clips, 2u);  // each contact facet, by the other cube
}

// Shifted by 1/2 along y: the contact keeps a strip on each side.
TEST(Union, TwoCubesFaceToFaceShifted) {
  const NonconvexSum r = expect_like_nef({box(0, 1, 0, 1, 0, 1), box(1, 2, Rational(1, 2), Rational(3, 2), 0, 1)});
  EXPECT_EQ(r.volume, Rational(2));
  EXPECT_EQ(r.mesh.points.size(), 16u);
  // Bottom and top are one octagon each; x = 0, x = 2, y = 0, y = 1/2, y = 1,
  // y = 3/2 and the two strips left of the contact (x = 1, facing +x and -x).
  EXPECT_EQ(r.mesh.faces.size(), 10u);
}

// [0,2]^2 x [0,1] and [1,3]^2 x [0,1]: the caps overlap in the same plane,
// facing the same way, and merge into one octagon each.
TEST(Union, OverlappingCoplanarFacetsOfTheSameOrientation) {
  const NonconvexSum r = expect_like_nef({box(0, 2, 0, 2, 0, 1), box(1, 3, 1, 3, 0, 1)});
  EXPECT_EQ(r.volume, Rational(7));
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(r.mesh.faces.size(), 10u);  // 2 caps (octagons), 8 walls
  for (const auto& f : r.mesh.faces) EXPECT_TRUE(f.size() == 4 || f.size() == 8) << f.size();
}

// Identical pieces: the later copy's facets are all removed by the earlier.
TEST(Union, TheSamePieceTwice) {
  const NonconvexSum r = expect_like_nef({box(0, 1, 0, 1, 0, 1), box(0, 1, 0, 1, 0, 1)});
  EXPECT_EQ(r.mesh.faces.size(), 6u);
  EXPECT_EQ(r.volume, Rational(1));
}

// [0,1]^3 and [1,2]^2 x [0,1] touch along the edge x = y = 1: it is kept,
// with its four faces, and the two cubes are two shells.
TEST(Union, EdgeContact) {
  const NonconvexSum r = expect_like_nef({box(0, 1, 0, 1, 0, 1), box(1, 2, 1, 2, 0, 1)});
  EXPECT_EQ(r.volume, Rational(2));
  EXPECT_EQ(r.mesh.faces.size(), 12u);
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_EQ(r.clips, 0u);  // a contact of zero area cuts nothing
}

// The same edge contact over half of one edge: the longer edge is split where
// the shorter one ends.
TEST(Union, EdgeContactOverPartOfAnEdge) {
  const NonconvexSum r = expect_like_nef({box(0, 1, 0, 1, 0, 2), box(1, 2, 1, 2, 1, 3)});
  EXPECT_EQ(r.volume, Rational(4));
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.mesh.points.size(), 16u);
}

// A tetrahedron whose apex touches the middle of an edge of a cube: the edge
// gets a vertex there.
TEST(Union, PointContactInsideAnEdge) {
  const ConvexPolytope tetra = ConvexPolytope::hull(
      std::vector<Point3>{Point3(1, 2, 2), Point3(0, 3, 3), Point3(2, 3, 3), Point3(1, 4, 2)}, "tetra");
  const NonconvexSum r = expect_like_nef({box(0, 2, 0, 2, 0, 2), tetra});
  EXPECT_EQ(r.volume, Rational(8) + tetra.volume());
  EXPECT_EQ(r.mesh.points.size(), 8u + 4u);
  EXPECT_EQ(r.shells, 2u);  // touching at a point: two volumes
}

// A prism lying on the top of a box along one of its edges, which ends inside
// the top face: the face is triangulated with that edge as one of its edges
// (four faces at it), and the two pieces stay two shells.
TEST(Union, EdgeLyingInsideAFace) {
  const ConvexPolytope prism = ConvexPolytope::hull(
      std::vector<Point3>{Point3(1, 2, 1), Point3(3, 2, 1), Point3(1, 1, 2), Point3(3, 1, 2), Point3(1, 3, 2),
                          Point3(3, 3, 2)},
      "prism");
  const NonconvexSum r = expect_like_nef({box(0, 4, 0, 4, 0, 1), prism});
  EXPECT_EQ(r.volume, Rational(16) + prism.volume());
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_EQ(r.mesh.points.size(), 14u);
}

// The same prism longer than the box: its edge crosses the top face, which
// is split into two faces along it, with new vertices where it leaves the face.
TEST(Union, EdgeLyingAcrossAFace) {
  const ConvexPolytope prism = ConvexPolytope::hull(
      std::vector<Point3>{Point3(-1, 2, 1), Point3(5, 2, 1), Point3(-1, 1, 2), Point3(5, 1, 2), Point3(-1, 3, 2),
                          Point3(5, 3, 2)},
      "prism");
  const NonconvexSum r = expect_like_nef({box(0, 4, 0, 4, 0, 1), prism});
  EXPECT_EQ(r.volume, Rational(16) + prism.volume());
  EXPECT_EQ(r.non_manifold_edges, 1u);  // (0,2,1)-(4,2,1); beyond the box the prism's edge is an ordinary one
  EXPECT_EQ(r.mesh.points.size(), 8u + 6u + 2u);
  std::size_t top = 0;
  for (const auto& f : r.mesh.faces) {
    bool on_top = true;
    for (Index v : f) on_top = on_top && r.mesh.points[v].z == 1 && r.mesh.points[v].x >= 0 && r.mesh.points[v].x <= 4;
    top += on_top;
  }
  EXPECT_EQ(top, 2u);  // the two halves of the box's top
}

// An edge of a tetrahedron crossing an edge of a cube at its middle: the
// crossing point becomes a vertex of both edges.
TEST(Union, EdgesCrossingAtAPoint) {
  const ConvexPolytope tetra = ConvexPolytope::hull(
      std::vector<Point3>{Point3(1, 1, 3), Point3(1, 3, 1), Point3(0, 3, 3), Point3(2, 3, 3)}, "tetra");
  const NonconvexSum r = expect_like_nef({box(0, 2, 0, 2, 0, 2), tetra});
  EXPECT_EQ(r.volume, Rational(8) + tetra.volume());
  EXPECT_EQ(r.mesh.points.size(), 8u + 4u + 1u);
  EXPECT_EQ(vertex_set(r.mesh).count(Point3(1, 2, 2)), 1u);
  EXPECT_EQ(r.shells, 2u);
}

// A piece inside another, and one inside touching its faces from within.
TEST(Union, APieceInsideAnother) {
  for (const ConvexPolytope& inner : {box(1, 2, 1, 2, 1, 2), box(0, 1, 0, 1, 0, 1), box(0, 3, 1, 2, 0, 3)}) {
    const NonconvexSum r = expect_like_nef({box(0, 3, 0, 3, 0, 3), inner});
    EXPECT_EQ(r.volume, Rational(27));
    EXPECT_EQ(r.mesh.points.size(), 8u);
    EXPECT_EQ(r.mesh.faces.size(), 6u);
    const NonconvexSum s = expect_like_nef({inner, box(0, 3, 0, 3, 0, 3)});
    EXPECT_EQ(s.mesh.faces.size(), 6u);
  }
}

// Six slabs around [1,2]^3 inside [0,3]^3, overlapping at the corners: the
// cavity is an inner shell facing into it.
TEST(Union, Cavity) {
  const NonconvexSum r = expect_like_nef({box(0, 3, 0, 3, 0, 1), box(0, 3, 0, 3, 2, 3), box(0, 1, 0, 3, 0, 3),
                                          box(2, 3, 0, 3, 0, 3), box(0, 3, 0, 1, 0, 3), box(0, 3, 2, 3, 0, 3)});
  EXPECT_EQ(r.volume, Rational(26));
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(r.mesh.faces.size(), 12u);
  EXPECT_EQ(r.shells, 2u);
}

// The cavity [1,2]^3 of [0,3]^3 meets a notch [2,3]^2 x [1,2] open to the
// outside along one edge only: the solid and the cavity are two volumes, so
// two shells, though one surface goes through the edge.
TEST(Union, CavityTouchingTheOutsideAlongAnEdge) {
  std::vector<ConvexPolytope> parts{box(0, 3, 0, 3, 0, 1), box(0, 3, 0, 3, 2, 3)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!(i == 1 && j == 1) && !(i == 2 && j == 2)) parts.push_back(box(i, i + 1, j, j + 1, 1, 2));
  const NonconvexSum r = expect_like_nef(parts);
  EXPECT_EQ(r.volume, Rational(25));
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.shells, 2u);
}

// A square frame of four bars: its top and bottom are squares with a square
// hole, triangulated (8 vertices, one hole: 8 triangles each).
TEST(Union, FaceWithAHoleIsTriangulated) {
  const NonconvexSum r = expect_like_nef(
      {box(0, 3, 0, 1, 0, 1), box(0, 3, 2, 3, 0, 1), box(0, 1, 0, 3, 0, 1), box(2, 3, 0, 3, 0, 1)});
  EXPECT_EQ(r.volume, Rational(8));
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(r.mesh.faces.size(), 4u + 4u + 8u + 8u);
  EXPECT_EQ(r.shells, 1u);
}

// Two squares of a plane touching at a corner ([0,1]^2 and [1,2]^2 as the
// bottoms of two cubes, with a third cube over both): the bottom keeps two
// faces that share a vertex.
TEST(Union, FacesTouchingAtAVertex) {
  expect_like_nef({box(0, 1, 0, 1, 0, 1), box(1, 2, 1, 2, 0, 1), box(0, 2, 0, 2, 1, 2)});
}

// The result does not depend on the number of threads.
TEST(Union, SameResultOnOneThread) {
  const std::vector<ConvexPolytope> parts{box(0, 2, 0, 2, 0, 1), box(1, 3, 1, 3, 0, 1), box(1, 2, 0, 3, 1, 2)};
  const NonconvexSum a = ours(parts, 1), b = ours(parts, 0);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  EXPECT_EQ(vertex_set(a.mesh), vertex_set(b.mesh));
}

// Random boxes with small integer corners: every kind of coplanar,
// edge and vertex contact, against the Nef union.
TEST(Union, RandomBoxesAgainstNef) {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coord(0, 4), count(2, 6);
    std::vector<ConvexPolytope> parts;
    for (int n = count(rng); int(parts.size()) < n;) {
      int c[6];
      for (int& x : c) x = coord(rng);
      if (c[0] == c[1] || c[2] == c[3] || c[4] == c[5]) continue;
      parts.push_back(box(std::min(c[0], c[1]), std::max(c[0], c[1]), std::min(c[2], c[3]), std::max(c[2], c[3]),
                          std::min(c[4], c[5]), std::max(c[4], c[5])));
    }
    expect_like_nef(parts);
  }
}

// Random convex polytopes: hulls of a few points with small integer
// coordinates (coplanar facets, shared vertices and edges are common).
TEST(Union, RandomPolytopesAgainstNef) {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coord(0, 4), count(2, 5), points(4, 8);
    std::vector<ConvexPolytope> parts;
    for (int n = count(rng); int(parts.size()) < n;) {
      std::vector<Point3> p;
      for (int k = points(rng); int(p.size()) < k;) p.emplace_back(coord(rng), coord(rng), coord(rng));
      try {
        parts.push_back(ConvexPolytope::hull(p, "random"));
      } catch (const InputError&) {  // flat: draw again
      }
    }
    expect_like_nef(parts);
  }
}

// The cube map of DirectionIndex: each cell's list is the kBest normals of
// largest dot product with the cell's centre, largest first and equal ones
// in index order (the order of a sort of (−dot, index)), for normals with
// many exact ties (a cube's and an octahedron's, repeated) and for random
// ones (seed printed on failure).
TEST(Union, DirectionIndexCellsHoldTheNormalsFacingTheirCentre) {
  using nonconvex_detail::DirectionIndex;
  auto check = [](const std::vector<Vec3d>& normals, const std::string& what) {
    const DirectionIndex index(normals);
    const std::size_t width = std::min(DirectionIndex::kBest, normals.size());
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i < DirectionIndex::kCells; ++i)
        for (int j = 0; j < DirectionIndex::kCells; ++j) {
          const std::array<double, 3> d = DirectionIndex::cell_centre(face, i, j);
          std::vector<std::pair<double, std::size_t>> rank;
          for (std::size_t q = 0; q < normals.size(); ++q)
            rank.push_back({-(normals[q].x * d[0] + normals[q].y * d[1] + normals[q].z * d[2]), q});
          std::sort(rank.begin(), rank.end());
          const std::uint16_t* got = nullptr;
          ASSERT_EQ(index.best(d.data(), got), width) << what;
          for (std::size_t k = 0; k < width; ++k)
            ASSERT_EQ(got[k], rank[k].second) << what << ": face " << face << " cell " << i << "," << j << " rank " << k;
        }
  };
  std::vector<Vec3d> ties;
  for (int rep = 0; rep < 3; ++rep)
    for (int a = 0; a < 3; ++a)
      for (double s : {1.0, -1.0}) ties.push_back(Vec3d{a == 0 ? s : 0.0, a == 1 ? s : 0.0, a == 2 ? s : 0.0});
  const double r = 1 / std::sqrt(3.0);
  for (double x : {r, -r})
    for (double y : {r, -r})
      for (double z : {r, -r}) ties.push_back(Vec3d{x, y, z});
  check(ties, "cube and octahedron normals");
  check(std::vector<Vec3d>(ties.begin(), ties.begin() + 4), "four normals");
  const unsigned seed = 20261207;
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec3d> random;
  for (int k = 0; k < 300; ++k) {
    Vec3d n{g(rng), g(rng), g(rng)};
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    random.push_back(Vec3d{n.x / len, n.y / len, n.z / len});
  }
  check(random, "300 random normals, seed " + std::to_string(seed));
}
