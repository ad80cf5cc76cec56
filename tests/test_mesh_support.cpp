// mesh/support: the support face of a direction by hill climbing and by a
// scan, and the face spanned by a vertex set.  Facts: on the cube [-1,1]^3
// the axis directions select the facet in that plane, the directions
// (±1,±1,0) an edge, (±1,±1,±1) a vertex; on catalog polytopes (geodesic
// spheres, random hulls, zonotopes, rotated copies with rational
// coordinates) a facet normal selects its facet, the sum of the normals
// beside an edge that edge, the sum of the normals around a vertex that
// vertex, and hill climbing from every start vertex agrees with the scan.
#include <minksum/catalog.hpp>
#include <minksum/predicates.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mesh/support.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

Index vertex_at(const ConvexPolytope& p, const Point3& x) {
  for (Index v = 0; v < p.num_vertices(); ++v)
    if (p.point(v) == x) return v;
  ADD_FAILURE() << "no vertex at the point";
  return kNoIndex;
}

std::vector<Index> sorted(std::vector<Index> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// The outer normal of facet f, from its canonical plane.
Point3 normal(const ConvexPolytope& p, Index f) { return p.plane(f).normal(); }

// The support face of n found by the scan, as a Feature.
Feature scanned(const ConvexPolytope& p, const Point3& n) { return feature_of_vertices(p, support_vertices(p, n)); }

TEST(MeshSupport, CubeAxisDirectionsGiveTheFacetInThatPlane) {
  const ConvexPolytope cube = catalog_polytope("cube");
  for (int axis = 0; axis < 3; ++axis)
    for (int s : {1, -1}) {
      Point3 n = P(0, 0, 0);
      n[axis] = s;
      // The facet is the one whose canonical plane is x_axis = s, i.e. s·x_axis = 1.
      Index want = kNoIndex;
      for (Index f = 0; f < cube.num_facets(); ++f)
        if (cube.plane(f).normal() == n && cube.plane(f).d == 1) want = f;
      ASSERT_NE(want, kNoIndex);
      std::vector<Index> top;
      for (Index v = 0; v < cube.num_vertices(); ++v)
        if (cube.point(v)[axis] == s) top.push_back(v);
      ASSERT_EQ(top.size(), 4u);
      EXPECT_EQ(support_vertices(cube, n), top);
      EXPECT_EQ(feature_of_vertices(cube, top), Feature::facet(want));
      EXPECT_EQ(sorted(feature_vertices(cube, Feature::facet(want))), top);
      for (Index start = 0; start < cube.num_vertices(); ++start) {
        const Support sup = support(cube, n, start);
        EXPECT_EQ(sup.face, Feature::facet(want)) << "axis " << axis << " sign " << s << " start " << start;
        EXPECT_TRUE(std::find(top.begin(), top.end(), sup.vertex) != top.end());
      }
    }
}

TEST(MeshSupport, CubeDiagonalsOfAFaceGiveAnEdge) {
  const ConvexPolytope cube = catalog_polytope("cube");
  for (int zero_axis = 0; zero_axis < 3; ++zero_axis)
    for (int sa : {1, -1})
      for (int sb : {1, -1}) {
        const int a = (zero_axis + 1) % 3, b = (zero_axis + 2) % 3;
        Point3 n = P(0, 0, 0);
        n[a] = sa, n[b] = sb;  // e.g. (1, 1, 0)
        Point3 x0 = n, x1 = n;
        x0[zero_axis] = -1, x1[zero_axis] = 1;
        const Index v0 = vertex_at(cube, x0), v1 = vertex_at(cube, x1);
        const Feature f = feature_of_vertices(cube, {v0, v1});
        ASSERT_EQ(f.dim, FeatureDim::edge);
        EXPECT_EQ(sorted(feature_vertices(cube, f)), sorted({v0, v1}));
        EXPECT_EQ(feature_of_vertices(cube, {v1, v0}), f);
        EXPECT_EQ(support_vertices(cube, n), sorted({v0, v1}));
        for (Index start = 0; start < cube.num_vertices(); ++start) EXPECT_EQ(support(cube, n, start).face, f);
      }
}

TEST(MeshSupport, CubeDiagonalsGiveAVertex) {
  const ConvexPolytope cube = catalog_polytope("cube");
  for (int s = 0; s < 8; ++s) {
    const Point3 n = P(s & 1 ? -1 : 1, s & 2 ? -1 : 1, s & 4 ? -1 : 1);  // e.g. (1, 1, 1)
    const Index v = vertex_at(cube, n);
    EXPECT_EQ(support_vertices(cube, n), std::vector<Index>{v});
    for (Index start = 0; start < cube.num_vertices(); ++start) {
      const Support sup = support(cube, n, start);
      EXPECT_EQ(sup.vertex, v);
      EXPECT_EQ(sup.face, Feature::vertex(v));
    }
  }
}

// The templates with another exact predicate: the kernel's compare_along on
// the double coordinates (exact for a double polytope and an integer
// direction), counting the calls.
TEST(MeshSupport, TemplatesTakeAnyExactComparison) {
  const ConvexPolytope cube = catalog_polytope("cube");
  ASSERT_TRUE(cube.coordinates_are_doubles());
  const Vec3d d{1, 1, 0};
  long calls = 0;
  auto higher = [&](Index x, Index y) {
    ++calls;
    return compare_along(d, cube.approx(x), cube.approx(y));
  };
  const Index top = climb(cube, vertex_at(cube, P(-1, -1, -1)), higher);
  EXPECT_EQ(cube.approx(top).x, 1);
  EXPECT_EQ(cube.approx(top).y, 1);
  EXPECT_GT(calls, 0);
  calls = 0;
  const std::optional<Feature> face = support_face_at(cube, top, higher);
  EXPECT_EQ(calls, 3);  // each neighbour once
  ASSERT_TRUE(face);
  EXPECT_EQ(*face, feature_of_vertices(cube, {vertex_at(cube, P(1, 1, -1)), vertex_at(cube, P(1, 1, 1))}));
  // A vertex below the top: nothing, and the scan stops at the first higher
  // neighbour (along (1, 1, 1) every neighbour of (-1, -1, -1) is higher).
  long up_calls = 0;
  auto up = [&](Index x, Index y) {
    ++up_calls;
    return compare_along(Vec3d{1, 1, 1}, cube.approx(x), cube.approx(y));
  };
  EXPECT_FALSE(support_face_at(cube, vertex_at(cube, P(-1, -1, -1)), up));
  EXPECT_EQ(up_calls, 1);
  EXPECT_FALSE(support_face_at(cube, vertex_at(cube, P(-1, -1, -1)), higher));
  calls = 0;
  EXPECT_EQ(support_scan(cube, higher), support_vertices(cube, P(1, 1, 0)));
  EXPECT_EQ(calls, long(cube.num_vertices()) - 1);
  std::vector<Index> among;
  support_among(std::vector<Index>{vertex_at(cube, P(1, -1, 1)), vertex_at(cube, P(-1, 1, 1))}, higher, among);
  EXPECT_EQ(among.size(), 2u);  // tied: both, in the given order
  EXPECT_EQ(among[0], vertex_at(cube, P(1, -1, 1)));
}

const char* const kSolids[] = {"sphere:3",       "sphere:2",          "sphere:2@rot:5",
                               "random:150:1",   "random:120:7@rot:3", "zonotope:7:2",
                               "dioctagonal:17", "truncated-cube",    "snub-cube",
                               "icosidodecahedron", "box:1:2:3@rot:1,2,3,4", "tetra"};

// Facet normals select their facet, normals summed beside an edge that edge,
// around a vertex that vertex (interior points of the normal cones); the
// climb, from the first and the last vertex, and the scan agree.
TEST(MeshSupport, NormalConesSelectTheirFace) {
  for (const char* spec : kSolids) {
    SCOPED_TRACE(spec);
    const ConvexPolytope p = catalog_polytope(spec);
    const Index last = p.num_vertices() - 1;
    auto check = [&](const Point3& n, const Feature& want) {
      EXPECT_EQ(support(p, n, 0).face, want);
      EXPECT_EQ(support(p, n, last).face, want);
      EXPECT_EQ(scanned(p, n), want);
    };
    for (Index f = 0; f < p.num_facets(); ++f) check(normal(p, f), Feature::facet(f));
    for (Index e = 0; e < p.num_edges(); ++e)
      check(normal(p, p.facet(2 * e)) + normal(p, p.facet(2 * e + 1)), Feature::edge(e));
    for (Index v = 0; v < p.num_vertices(); ++v) {
      Point3 n = P(0, 0, 0);
      const Index h0 = p.vertex_halfedge(v);
      Index h = h0;
      do {
        n = n + normal(p, p.facet(h));
        h = p.next_around_vertex(h);
      } while (h != h0);
      check(n, Feature::vertex(v));
    }
  }
}

// Random integer directions (fixed seed), small ones so that ties happen,
// and hill climbing from every start vertex.
TEST(MeshSupport, ClimbFromEveryVertexAgreesWithTheScan) {
  std::mt19937_64 rng(20240611);
  std::uniform_int_distribution<int> small(-2, 2), large(-1000000, 1000000);
  for (const char* spec : kSolids) {
    SCOPED_TRACE(spec);
    const ConvexPolytope p = catalog_polytope(spec);
    for (int k = 0; k < 12; ++k) {
      auto& dist = k < 6 ? small : large;
      Point3 n = P(dist(rng), dist(rng), dist(rng));
      if (is_zero(n)) n = P(0, 0, 1);
      const std::vector<Index> top = support_vertices(p, n);
      const Feature want = feature_of_vertices(p, top);
      EXPECT_EQ(sorted(feature_vertices(p, want)), top);
      for (Index start = 0; start < p.num_vertices(); ++start) {
        const Support s = support(p, n, start);
        ASSERT_EQ(s.face, want) << "direction " << k << " start " << start;
        ASSERT_TRUE(std::binary_search(top.begin(), top.end(), s.vertex));
      }
    }
  }
}

// Every vertex, edge and facet from its vertex set (in any order), and back.
TEST(MeshSupport, FeatureOfVerticesIsTheFaceTheySpan) {
  for (const char* spec : {"cube", "sphere:2", "truncated-cube", "dioctagonal:17", "random:60:4"}) {
    SCOPED_TRACE(spec);
    const ConvexPolytope p = catalog_polytope(spec);
    for (Index v = 0; v < p.num_vertices(); ++v) {
      EXPECT_EQ(feature_of_vertices(p, {v}), Feature::vertex(v));
      EXPECT_EQ(feature_vertices(p, Feature::vertex(v)), std::vector<Index>{v});
    }
    for (Index e = 0; e < p.num_edges(); ++e) {
      const Index a = p.origin(2 * e), b = p.target(2 * e);
      EXPECT_EQ(feature_of_vertices(p, {a, b}), Feature::edge(e));
      EXPECT_EQ(feature_of_vertices(p, {b, a}), Feature::edge(e));
      EXPECT_EQ(feature_vertices(p, Feature::edge(e)), (std::vector<Index>{a, b}));
    }
    for (Index f = 0; f < p.num_facets(); ++f) {
      std::vector<Index> vs = p.facet_vertices(f);
      EXPECT_EQ(feature_vertices(p, Feature::facet(f)), vs);
      EXPECT_EQ(feature_of_vertices(p, vs), Feature::facet(f));
      std::reverse(vs.begin(), vs.end());
      EXPECT_EQ(feature_of_vertices(p, vs), Feature::facet(f));
      std::sort(vs.begin(), vs.end());
      EXPECT_EQ(feature_of_vertices(p, vs), Feature::facet(f));
    }
  }
}

TEST(MeshSupport, FeatureOfVerticesRejectsSetsThatAreNoFace) {
  const ConvexPolytope cube = catalog_polytope("cube");
  const Index a = vertex_at(cube, P(1, 1, 1)), b = vertex_at(cube, P(-1, -1, 1)), c = vertex_at(cube, P(1, -1, 1)),
              d = vertex_at(cube, P(-1, -1, -1));
  EXPECT_THROW(feature_of_vertices(cube, {}), std::logic_error);
  EXPECT_THROW(feature_of_vertices(cube, {a, b}), std::logic_error);     // a diagonal of a facet
  EXPECT_THROW(feature_of_vertices(cube, {a, c, b}), std::logic_error);  // three of a facet's four
  EXPECT_THROW(feature_of_vertices(cube, {a, c, d}), std::logic_error);  // on no common facet
}

TEST(MeshSupport, ShareAVertex) {
  EXPECT_TRUE(share_a_vertex({1, 4, 9}, {2, 4}));
  EXPECT_FALSE(share_a_vertex({1, 4, 9}, {2, 5, 10}));
  EXPECT_FALSE(share_a_vertex({}, {2}));
  EXPECT_TRUE(share_a_vertex({7}, {0, 3, 7}));
}

}  // namespace
