// The Cubical Gaussian Map: invariants, Table 1 chains, round trips,
// Table-2-style counts, and the overlay's own cases and counters.  The cgm
// sum's agreement with the chms oracle (and its overlay's facet vertices
// against the sum's own CGM) is checked by the conformance suite
// (test_conformance.cpp), the `minksum cgm` command by the command-line
// suite (test_cli.cpp, CgmCli).
#include <minksum/catalog.hpp>
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

std::vector<std::string> round_trip_specs() {
  std::vector<std::string> v;
  for (const auto& e : catalog_entries()) {
    std::string name = e.syntax.substr(0, e.syntax.find(' '));
    if (name.find(':') == std::string::npos && name[0] != '@') v.push_back(name);  // the fixed solids
  }
  for (int l = 1; l <= 4; ++l) v.push_back("sphere:" + std::to_string(l));
  for (const char* r : {"cube@rot:1", "cube@rot:1,1,0,0", "octahedron@rot:3", "tetra@rot:1,0,0,1", "dodecahedron@rot:9",
                        "truncated-cube@rot:5", "rhombicuboctahedron@rot:1,1,1,0", "dioctagonal:17", "dioctagonal:9",
                        "box:1:1:1e-12", "cube@scale:1e150", "zonotope:6:3", "random:30:4"})
    v.push_back(r);
  return v;
}

TEST(Cgm, InvariantsAndRoundTripForEveryCatalogSolid) {
  auto specs = round_trip_specs();
  ASSERT_EQ(specs.size(), 31u + 4u + 13u);
  for (const auto& s : specs) {
    SCOPED_TRACE(s);
    ConvexPolytope p = cat(s);
    auto g = CubicalGaussianMap::from_polytope(p);
    ASSERT_EQ(g.check_invariants(), "");
    Index real = 0, real_edges = 0;
    for (int k = 0; k < 6; ++k) {
      for (const auto& v : g.map(k).vertices)
        if (v.real) {
          ++real;
          EXPECT_EQ(v.plane, p.plane(v.facet));
        }
      real_edges += g.map(k).num_real_edges();
    }
    EXPECT_GE(real, p.num_facets());       // copies on cube edges and corners
    EXPECT_GE(real_edges, p.num_edges());  // an arc is a chain of 1 to 3 segments
    ConvexPolytope back = g.to_polytope();
    ASSERT_TRUE(same_polytope(back, p));
    // CGM -> polytope -> CGM: the same maps (the same vertices, real flags
    // and planes; the numbering follows the polytope's facet order).
    auto g2 = CubicalGaussianMap::from_polytope(back);
    for (int k = 0; k < 6; ++k) {
      auto c1 = g.counts(k), c2 = g2.counts(k);
      EXPECT_EQ(c1.vertices, c2.vertices);
      EXPECT_EQ(c1.halfedges, c2.halfedges);
      EXPECT_EQ(c1.faces, c2.faces);
      auto listing = [](const CubicalGaussianMap::PlanarMap& m) {
        std::vector<std::tuple<Rational, Rational, bool, std::string>> l;
        for (const auto& v : m.vertices)
          l.emplace_back(v.x, v.y, v.real,
                         v.real ? v.plane.a.get_str() + " " + v.plane.b.get_str() + " " + v.plane.c.get_str() + " " +
                                      v.plane.d.get_str()
                                : std::string());
        std::sort(l.begin(), l.end());
        return l;
      };
      EXPECT_EQ(listing(g.map(k)), listing(g2.map(k)));
    }
  }
}

TEST(Cgm, CornerChainsFollowTable1) {
  // Table 1 of Fogel and Halperin (2006): for map k and corner c, the (map, corner) next in the
  // clockwise cyclic chain of the three copies of that cube corner.
  const int next[6][4][2] = {
      {{1, 0}, {2, 2}, {5, 0}, {4, 2}}, {{2, 0}, {0, 2}, {3, 0}, {5, 2}}, {{0, 0}, {1, 2}, {4, 0}, {3, 2}},
      {{2, 1}, {1, 3}, {4, 1}, {5, 3}}, {{0, 1}, {2, 3}, {5, 1}, {3, 3}}, {{1, 1}, {0, 3}, {3, 1}, {4, 3}},
  };
  auto g = CubicalGaussianMap::from_polytope(cat("tetra"));
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 4; ++c) {
      const auto& link = g.map(k).vertices[g.map(k).corner[c]].link;
      EXPECT_EQ(link.map, next[k][c][0]) << "map " << k << " corner " << c;
      EXPECT_EQ(link.vertex, g.map(next[k][c][0]).corner[next[k][c][1]]) << "map " << k << " corner " << c;
    }
  // The 2D axes of Table 1, X x Y = the outer normal of the cube face.
  const int axes[6][2] = {{2, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {0, 1}};
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(CubicalGaussianMap::axis_x(k), axes[k][0]);
    EXPECT_EQ(CubicalGaussianMap::axis_y(k), axes[k][1]);
    Point3 X, Y;
    X[axes[k][0]] = 1;
    Y[axes[k][1]] = 1;
    Point3 n = cross(X, Y);
    EXPECT_EQ(n[CubicalGaussianMap::axis(k)], CubicalGaussianMap::sign(k));
  }
}

TEST(Cgm, EdgePairsAndBoundaryTraversal) {
  // rhombicuboctahedron: 12 facet normals on the midpoints of the cube edges
  // (pairs), 8 on the corners (triplets), 6 on the face centres.
  auto g = CubicalGaussianMap::from_polytope(cat("rhombicuboctahedron"));
  int pairs = 0, triplets = 0, interior = 0;
  for (int k = 0; k < 6; ++k)
    for (Index v = 0; v < g.map(k).vertices.size(); ++v) {
      const auto& x = g.map(k).vertices[v];
      if (!x.real) continue;
      auto ch = g.chain(k, v);
      if (x.location == CgmLocation::edge) {
        ++pairs;
        EXPECT_EQ(ch.size(), 2u);
      }
      if (x.location == CgmLocation::corner) {
        ++triplets;
        EXPECT_EQ(ch.size(), 3u);
      }
      if (x.location == CgmLocation::interior) {
        ++interior;
        EXPECT_EQ(ch.size(), 1u);
      }
    }
  EXPECT_EQ(pairs, 24);     // 12 normals, 2 copies each
  EXPECT_EQ(triplets, 24);  // 8 normals, 3 copies each
  EXPECT_EQ(interior, 6);
  for (int k = 0; k < 6; ++k) {
    const auto& m = g.map(k);
    for (int s = 0; s < 4; ++s) {
      // Each side: corner, edge midpoint, corner; both pieces real (arcs on cube edges).
      ASSERT_EQ(m.side[s].size(), 2u);
      for (Index h : m.side[s]) EXPECT_TRUE(m.halfedges[h].real);
    }
  }
  // Facets whose normals project onto cube edges: the rhombic dodecahedron's.
  auto r = CubicalGaussianMap::from_polytope(cat("rhombic-dodecahedron"));
  EXPECT_EQ(r.check_invariants(), "");
}

TEST(Cgm, Table2CountsTetrahedron) {
  // tetra = (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1).  The facet opposite v
  // has outer normal -v, a cube corner; each cube face holds two of the four
  // normals at opposite corners.  Each of the 6 edges joins two facets, whose
  // normals are opposite corners of exactly one cube face: its arc is that
  // face's diagonal.  Per map: V = 4 corners (2 real), E = 4 sides + 1
  // diagonal = 5, so HE = 10, and F = E - V + 2 = 3 (two triangles, the
  // duals of the two tetra vertices on that side, and the unbounded face).
  auto g = CubicalGaussianMap::from_polytope(cat("tetra"));
  for (int k = 0; k < 6; ++k) {
    auto c = g.counts(k);
    EXPECT_EQ(c.vertices, 4u);
    EXPECT_EQ(c.halfedges, 10u);
    EXPECT_EQ(c.faces, 3u);
    EXPECT_EQ(g.map(k).num_real_vertices(), 2u);
    EXPECT_EQ(g.map(k).num_real_edges(), 1u);
  }
}

TEST(Cgm, Table2CountsDioctagonalPyramid) {
  // dioctagonal:9: a regular octagon base (circumradius 1, z = 0) under the
  // apex (0, 0, 1/8); 9 facets, 16 edges, 9 vertices.  The base normal
  // (0,0,-1) is the centre of map 2.  A side facet's normal is about
  // (cos φ / 8, sin φ / 8, cos 22.5°) with φ = 22.5° + 45° j: all eight
  // project inside map 5, on a small octagon.  The 8 apex edges join
  // neighbouring side facets: 8 segments inside map 5.  The 8 base edges
  // join a side facet to the base: the arc runs radially out of map 5 at
  // angle φ, crosses the cube edge into the side face of the dominant axis
  // (|cos φ| > |sin φ| for φ = ±22.5°: x = +1, ...; two arcs per side face),
  // runs straight down it and enters map 2 to end at its centre.
  //   map 5: V = 4 + 8 real + 8 exit points (2 per side) = 20;
  //          E = 8 + 8 radial + 4 sides x 3 pieces = 28, HE = 56;
  //          F = 28 - 20 + 2 = 10 (apex octagon, 8 base-vertex wedges, unbounded).
  //   map 2: V = 4 + 1 + 8 = 13; E = 8 radial + 12 pieces = 20, HE = 40;
  //          F = 20 - 13 + 2 = 9.
  //   maps 0, 1, 3, 4: V = 4 + 2 top + 2 bottom = 8; E = 2 + (3 + 3 + 1 + 1) = 10,
  //          HE = 20; F = 10 - 8 + 2 = 4 (three strips, unbounded).
  ConvexPolytope p = cat("dioctagonal:9");
  ASSERT_EQ(p.num_facets(), 9u);
  auto g = CubicalGaussianMap::from_polytope(p);
  const Index V[6] = {8, 8, 13, 8, 8, 20}, HE[6] = {20, 20, 40, 20, 20, 56}, F[6] = {4, 4, 9, 4, 4, 10};
  const Index realV[6] = {0, 0, 1, 0, 0, 8};
  for (int k = 0; k < 6; ++k) {
    SCOPED_TRACE(k);
    auto c = g.counts(k);
    EXPECT_EQ(c.vertices, V[k]);
    EXPECT_EQ(c.halfedges, HE[k]);
    EXPECT_EQ(c.faces, F[k]);
    EXPECT_EQ(g.map(k).num_real_vertices(), realV[k]);
  }
}

TEST(Cgm, OctahedronNormalsOnTheEightCubeCorners) {
  // Fig. 8 of Fogel and Halperin (2006): every normal on a cube corner, every arc on a cube edge.
  auto g = CubicalGaussianMap::from_polytope(cat("octahedron"));
  for (int k = 0; k < 6; ++k) {
    const auto& m = g.map(k);
    EXPECT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.num_real_vertices(), 4u);
    EXPECT_EQ(m.num_real_edges(), 4u);
    EXPECT_EQ(m.faces.size(), 2u);
  }
}

TEST(CgmSum, NormalsOnCubeEdgesAndOverlappingSegments) {
  // rhombicuboctahedron / truncated cuboctahedron: normals on cube edges, and
  // pairs of parallel neighbouring facets, so arcs of both operands overlap
  // (on cube edges and inside the faces).  The sum itself is checked with
  // every method by the conformance suite.
  SumResult r = minkowski_sum(cat("rhombicuboctahedron"), cat("truncated-cuboctahedron"), Method::cgm);
  EXPECT_GT(counter(r, "edge_overlap"), 0);
}

TEST(CgmSum, EveryOverlayCaseOccurs) {
  // Over a few pairs, each overlay case of Fogel and Halperin 2006, §3 is met at least once.
  std::map<std::string, long long> total;
  for (auto [x, y] : std::vector<std::pair<const char*, const char*>>{{"cube", "octahedron"},
                                                                      {"rhombicuboctahedron", "truncated-cuboctahedron"},
                                                                      {"sphere:2", "sphere:2@rot:3"},
                                                                      {"cube", "sphere:2"},
                                                                      {"tetra", "tetra@rot:4"}}) {
    SumResult r = minkowski_sum(cat(x), cat(y), Method::cgm);
    for (const auto& [name, value] : r.counters) total[name] += value;
  }
  for (const char* c : {"vertex_vertex", "vertex_a_on_edge_b", "vertex_b_on_edge_a", "vertex_a_in_face_b",
                        "vertex_b_in_face_a", "edge_crossing", "edge_overlap", "edge_a_in_face_b", "edge_b_in_face_a",
                        "face_overlap"})
    EXPECT_GT(total[c], 0) << c;
}
