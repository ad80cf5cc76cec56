// The Cubical Gaussian Map: invariants, Table 1 chains, round trips,
// Table-2-style counts, and the overlay sum equal to the chms oracle.
#include <minksum/catalog.hpp>
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <random>
#include <tuple>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {
ConvexPolytope cat(const std::string& s) { return catalog_polytope(s); }

// cgm(A, B) == chms(A, B) == cgm(B, A); vertex origins and (when asked) the
// facet provenance checked against brute force; the overlay's facet vertices
// (with their copies on cube edges and corners) are exactly the real vertices
// of the sum's own CGM.
void expect_matches_oracle(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                           bool check_provenance = true, bool check_all = true) {
  SCOPED_TRACE(label);
  SumResult oracle = minkowski_sum_chms(a, b);
  SumResult ab = minkowski_sum_cgm(a, b);
  ASSERT_EQ(ab.method, Method::cgm);
  ASSERT_EQ(ab.polytope.num_vertices(), oracle.polytope.num_vertices());
  ASSERT_EQ(ab.polytope.num_edges(), oracle.polytope.num_edges());
  ASSERT_EQ(ab.polytope.num_facets(), oracle.polytope.num_facets());
  EXPECT_TRUE(same_polytope(ab.polytope, oracle.polytope));
  for (Index v = 0; v < ab.polytope.num_vertices(); ++v) {
    auto [i, j] = ab.vertex_origin[v];
    ASSERT_EQ(ab.polytope.point(v), a.point(i) + b.point(j));
  }
  ASSERT_EQ(ab.facet_provenance.size(), ab.polytope.num_facets());
  if (check_provenance) {
    EXPECT_EQ(ab.facet_provenance, facet_provenance(a, b, ab.polytope));
  }
  if (!check_all) return;
  auto gs = CubicalGaussianMap::from_polytope(ab.polytope);
  EXPECT_EQ(gs.check_invariants(), "");
  long long real = 0;
  for (int k = 0; k < 6; ++k) real += gs.map(k).num_real_vertices();
  EXPECT_EQ(ab.counters.at(0).first, "overlay_facet_vertices");
  EXPECT_EQ(ab.counters.at(0).second, real);
  SumResult ba = minkowski_sum_cgm(b, a);
  EXPECT_TRUE(same_polytope(ba.polytope, ab.polytope));
}

void expect_matches_oracle(const std::string& a, const std::string& b, bool check_provenance = true) {
  expect_matches_oracle(cat(a), cat(b), a + " + " + b, check_provenance);
}

}  // namespace

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
  // Seed 001 Table 1: for map k and corner c, the (map, corner) next in the
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
  // Seed 001 Fig. 8: every normal on a cube corner, every arc on a cube edge.
  auto g = CubicalGaussianMap::from_polytope(cat("octahedron"));
  for (int k = 0; k < 6; ++k) {
    const auto& m = g.map(k);
    EXPECT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.num_real_vertices(), 4u);
    EXPECT_EQ(m.num_real_edges(), 4u);
    EXPECT_EQ(m.faces.size(), 2u);
  }
}

TEST(CgmSum, AllPairsOfSmallSolids) {
  for (const std::string& x : small_solids())
    for (const std::string& y : small_solids())
      if (x <= y) expect_matches_oracle(x, y);
}

TEST(CgmSum, CubePlusGeodesicSpheres) {
  for (int level = 1; level <= 5; ++level)
    expect_matches_oracle("cube", "sphere:" + std::to_string(level), level <= 3);
}

TEST(CgmSum, IdenticalPolytopes) {
  // A = B: every vertex, edge and face of one map coincides with the other's.
  SumResult r = minkowski_sum_cgm(cat("sphere:3"), cat("sphere:3"));
  EXPECT_EQ(r.polytope.num_facets(), 320u);
  for (const auto& p : r.facet_provenance) EXPECT_EQ(p.origin(), FacetOrigin::facet_facet);
  expect_matches_oracle("sphere:3", "sphere:3");
  for (const char* s : {"tetra", "cube", "octahedron", "rhombicuboctahedron", "truncated-cube", "dioctagonal:17"})
    expect_matches_oracle(s, s);
}

TEST(CgmSum, SphereAndRotatedSphere) { expect_matches_oracle("sphere:3", "sphere:3@rot:5", false); }

TEST(CgmSum, OctahedronNormalsOnCubeCorners) {
  // Seed 001 Fig. 8: the octahedron's eight normals sit on the cube corners
  // and its arcs on the cube edges.  6 translated + 8 corner + 12 edge facets.
  SumResult r = minkowski_sum_cgm(cat("cube"), cat("octahedron"));
  int count[5] = {0, 0, 0, 0, 0};
  for (const auto& p : r.facet_provenance) ++count[int(p.origin())];
  EXPECT_EQ(count[int(FacetOrigin::translated)], 6);
  EXPECT_EQ(count[int(FacetOrigin::corner)], 8);
  EXPECT_EQ(count[int(FacetOrigin::edge)], 12);
  expect_matches_oracle("octahedron", "cube");
  expect_matches_oracle("octahedron", "octahedron@rot:1,1,0,0");
  expect_matches_oracle("octahedron", "cuboctahedron");
}

TEST(CgmSum, NormalsOnCubeEdgesAndOverlappingSegments) {
  // rhombic dodecahedron / cuboctahedron / rhombicuboctahedron: normals on
  // cube edges; pairs of them have parallel neighbouring facets, so arcs of
  // both operands overlap (on cube edges and inside the faces).
  expect_matches_oracle("rhombic-dodecahedron", "rhombicuboctahedron");
  expect_matches_oracle("rhombic-dodecahedron", "cuboctahedron");
  expect_matches_oracle("rhombicuboctahedron", "truncated-cuboctahedron");
  expect_matches_oracle("truncated-octahedron", "tetrakis-hexahedron");
  SumResult r = minkowski_sum_cgm(cat("rhombicuboctahedron"), cat("truncated-cuboctahedron"));
  long long overlap = 0;
  for (const auto& [name, value] : r.counters)
    if (name == "edge_overlap") overlap = value;
  EXPECT_GT(overlap, 0);
}

TEST(CgmSum, CubePlusAxisAlignedTruncatedCube) {
  // The pair on which CGAL 5.5's spherical Gaussian map returns a facet with
  // a wrong offset: the cube's normals coincide with the truncated cube's
  // octagon normals at the centres of the maps, the triangle normals sit on
  // the cube corners.
  ConvexPolytope a = cat("cube"), b = cat("truncated-cube");
  SumResult r = minkowski_sum_cgm(a, b);
  SumResult o = minkowski_sum_chms(a, b);
  EXPECT_TRUE(same_polytope(r.polytope, o.polytope));
  EXPECT_EQ(r.polytope.num_facets(), 14u);
  // Every facet plane is the support plane of the sum in its normal direction.
  for (Index f = 0; f < r.polytope.num_facets(); ++f) {
    const Plane& pl = r.polytope.plane(f);
    Point3 n = pl.normal();
    Rational ha = dot(n, a.point(0)), hb = dot(n, b.point(0));
    for (Index v = 1; v < a.num_vertices(); ++v) ha = std::max(ha, Rational(dot(n, a.point(v))));
    for (Index v = 1; v < b.num_vertices(); ++v) hb = std::max(hb, Rational(dot(n, b.point(v))));
    EXPECT_EQ(Rational(pl.d), ha + hb);
  }
  expect_matches_oracle("cube", "truncated-cube");
  expect_matches_oracle("truncated-cube", "dodecahedron");
}

TEST(CgmSum, DioctagonalPairs) {
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:1,0,0,1");
  expect_matches_oracle("dioctagonal:17", "dioctagonal:17@rot:100,0,0,99");
  expect_matches_oracle("dioctagonal:9", "dioctagonal:9@rot:7");
}

TEST(CgmSum, ZonotopesWithParallelEdges) {
  expect_matches_oracle("zonotope:5:1", "zonotope:5:2");
  expect_matches_oracle("zonotope:6:3", "zonotope:6:3");
  expect_matches_oracle("zonotope:4:7", "cube");
  expect_matches_oracle("zonotope:1,0,0:0,1,0:1,1,0:0,0,1", "zonotope:1,1,0:0,0,1:1,-1,2");
}

TEST(CgmSum, MixedSolids) { expect_matches_oracle("snub-cube", "truncated-icosahedron", false); }

TEST(CgmSum, ThinBoxAndExtremeScales) {
  expect_matches_oracle("box:1:1:1e-12", "sphere:2");
  expect_matches_oracle("box:1e-12:2:3", "box:4:1e-12:5");
  expect_matches_oracle("cube@scale:1e150", "octahedron@scale:1e-150");
  expect_matches_oracle("sphere:2@scale:1e-150", "dodecahedron@scale:1e-150");
  expect_matches_oracle("icosahedron@scale:1e150", "tetra@scale:1e150@rot:3");
}

TEST(CgmSum, EveryOverlayCaseOccurs) {
  // Over a few pairs, each overlay case of seed 001 §3 is met at least once.
  std::map<std::string, long long> total;
  for (auto [x, y] : std::vector<std::pair<const char*, const char*>>{{"cube", "octahedron"},
                                                                      {"rhombicuboctahedron", "truncated-cuboctahedron"},
                                                                      {"sphere:2", "sphere:2@rot:3"},
                                                                      {"cube", "sphere:2"},
                                                                      {"tetra", "tetra@rot:4"}}) {
    SumResult r = minkowski_sum_cgm(cat(x), cat(y));
    for (const auto& [name, value] : r.counters) total[name] += value;
  }
  for (const char* c : {"vertex_vertex", "vertex_a_on_edge_b", "vertex_b_on_edge_a", "vertex_a_in_face_b",
                        "vertex_b_in_face_a", "edge_crossing", "edge_overlap", "edge_a_in_face_b", "edge_b_in_face_a",
                        "face_overlap"})
    EXPECT_GT(total[c], 0) << c;
}

TEST(CgmSum, DispatchAndCommutativity) {
  ASSERT_TRUE(method_available(Method::cgm));
  ConvexPolytope a = cat("dodecahedron"), b = cat("cube@rot:2");
  SumResult r = minkowski_sum(a, b, Method::cgm);
  EXPECT_EQ(r.method, Method::cgm);
  EXPECT_TRUE(same_polytope(r.polytope, minkowski_sum(b, a, Method::cgm).polytope));
}

// 1200 pairs with fixed seeds, as in the cvms suite (commutativity and the
// sum's own CGM checked on every fifth seed, provenance on every tenth).
void random_pairs(unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(first_seed, last_seed,
                                     [](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                                        unsigned seed) { expect_matches_oracle(a, b, label, seed % 10 == 0, seed % 5 == 0); });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

TEST(CgmSum, RandomPairsSeeds1To100) { random_pairs(1, 100); }
TEST(CgmSum, RandomPairsSeeds101To200) { random_pairs(101, 200); }
TEST(CgmSum, RandomPairsSeeds201To300) { random_pairs(201, 300); }
TEST(CgmSum, RandomPairsSeeds301To400) { random_pairs(301, 400); }

// The command line: minksum cgm P [Q] [--svg OUT] [--stats] [--json].
namespace {
struct CliRun {
  int status = -1;
  std::string out;
};
CliRun run_cli(const std::string& args) {
  std::string cmd = std::string(MINKSUM_BIN) + " " + args + " 2>/dev/null </dev/null";
  CliRun r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  return r;
}
}  // namespace

TEST(CgmCli, StatsOfTheOctahedron) {
  CliRun r = run_cli("cgm octahedron --stats");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("octahedron: 6 vertices, 12 edges, 8 facets"), std::string::npos) << r.out;
  // Every map: 4 vertices (all real, on the corners), 8 halfedges, 2 faces.
  for (const char* plane : {"x=-1", "y=-1", "z=-1", "x=+1", "y=+1", "z=+1"})
    EXPECT_NE(r.out.find(std::string(plane) + "      4     8     2       4       4"), std::string::npos) << plane;
  EXPECT_NE(r.out.find("total         24    48    12"), std::string::npos) << r.out;
  CliRun j = run_cli("cgm tetra --json");
  ASSERT_EQ(j.status, 0);
  EXPECT_NE(j.out.find("{\"id\": 5, \"vertices\": 4, \"halfedges\": 10, \"faces\": 3"), std::string::npos) << j.out;
}

TEST(CgmCli, SvgIsWellFormedAndWrittenAtomically) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("minksum_cgm_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::path out = dir / "sum.svg";
  CliRun r = run_cli("cgm cube octahedron --svg " + out.string());
  ASSERT_EQ(r.status, 0);
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string svg = ss.str();
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  std::size_t groups = 0, open_g = 0, close_g = 0;
  for (std::size_t at = 0; (at = svg.find("<g id=\"map", at)) != std::string::npos; ++at) ++groups;
  for (std::size_t at = 0; (at = svg.find("<g ", at)) != std::string::npos; ++at) ++open_g;
  for (std::size_t at = 0; (at = svg.find("</g>", at)) != std::string::npos; ++at) ++close_g;
  EXPECT_EQ(groups, 6u);
  EXPECT_EQ(open_g, close_g);
  EXPECT_NE(svg.find("#d62728"), std::string::npos);            // first operand's edges
  EXPECT_NE(svg.find("#1f77b4"), std::string::npos);            // second operand's edges
  // Only the finished file is left (no temporary).
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  // The tetrahedron's maps keep their artificial square sides: dashed.
  ASSERT_EQ(run_cli("cgm tetra --svg " + out.string()).status, 0);
  std::ifstream in2(out);
  std::stringstream ss2;
  ss2 << in2.rdbuf();
  EXPECT_NE(ss2.str().find("stroke-dasharray"), std::string::npos);
  // An unwritable destination: status 1, nothing left behind.
  CliRun bad = run_cli("cgm cube --svg " + (dir / "no" / "such" / "x.svg").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_FALSE(fs::exists(dir / "no"));
  fs::remove_all(dir);
}

TEST(CgmCli, UsageAndInputErrors) {
  EXPECT_EQ(run_cli("cgm").status, 2);
  EXPECT_EQ(run_cli("cgm cube cube cube").status, 2);
  EXPECT_EQ(run_cli("cgm cube --bogus").status, 2);
  EXPECT_EQ(run_cli("cgm /nonexistent/missing.off").status, 3);
  EXPECT_EQ(run_cli("cgm --help").status, 0);
}

TEST(CgmCli, SumMethodCgm) {
  CliRun r = run_cli("sum cube octahedron --method cgm --json");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("\"method\": \"cgm\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"facets\": 26"), std::string::npos) << r.out;
}
