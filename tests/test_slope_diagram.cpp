// The slope-diagram methods, ESSDMS and the improved 3D-MSSD (Wu et al.),
// what only they have: the intersection case of every facet and the
// operation counters (facet-point tests, arc-pair tests, point-in-polygon
// queries, contributing-vertex tests, pruned arcs), the pruning of ESSDMS
// against MSSD, and the degree-3 forms of eq. 8-9, eq. 12 and the
// point-in-spherical-polygon test equal to the paper's expressions on exact
// facet normals.  Their agreement with the chms oracle, their provenance and
// the consistency of each facet's case with its provenance are checked by
// the conformance suite (test_conformance.cpp).
#include <minksum/catalog.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <map>

#include "sum/slope_diagram.hpp"
#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

TEST(SlopeDiagram, IdenticalSpheres) {
  // A = B: every facet point of A coincides with one of B, every edge arc of
  // A lies on one of B (parallel, no crossing).
  const ConvexPolytope s = cat("sphere:3");
  for (Method m : {Method::essdms, Method::mssd}) {
    SCOPED_TRACE(method_name(m));
    SumResult r = minkowski_sum(s, s, m);
    EXPECT_EQ(r.polytope.num_facets(), 320u);
    EXPECT_EQ(case_counts(r), (std::array<long, 4>{320, 0, 0, 0}));
    // Case 1 stops at the first coincidence and skips the facet points of B
    // already matched: with both facet lists in the same order, facet f of A
    // is tested against facet f of B only.
    EXPECT_EQ(counter(r, "facet_point_tests"), 320);
    EXPECT_EQ(counter(r, "facet_point_arc_tests"), 0);
    EXPECT_EQ(counter(r, "point_in_polygon_queries"), 0);
    if (m == Method::essdms) {
      // Property 1: the two facets of every edge share the edge's ends as
      // contributing vertices, so every arc is pruned.
      EXPECT_EQ(counter(r, "edge_arcs_pruned"), 2L * 480);
      EXPECT_EQ(counter(r, "arc_pair_tests"), 0);
    } else {
      EXPECT_EQ(counter(r, "edge_arcs_pruned"), 0);
      EXPECT_EQ(counter(r, "arc_pair_tests"), 480L * 480);
    }
  }
}

TEST(SlopeDiagram, IdenticalSolidsAreAllFacetPlusFacet) {
  for (const std::string& x : small_solids()) {
    SCOPED_TRACE(x);
    const ConvexPolytope p = cat(x);
    for (Method m : {Method::essdms, Method::mssd}) {
      SumResult r = minkowski_sum(p, p, m);
      EXPECT_EQ(case_counts(r), (std::array<long, 4>{long(p.num_facets()), 0, 0, 0}));
    }
  }
}

TEST(SlopeDiagram, RotatedIdenticalSolidsNeedTheExactFallback) {
  // Rational coordinates: coincident facet points and facet points on arcs
  // cannot be certified by the interval enclosures, only by the exact
  // predicates behind them.
  for (const char* x : {"dodecahedron@rot:3", "cuboctahedron@rot:17", "sphere:2@rot:5"}) {
    SCOPED_TRACE(x);
    const ConvexPolytope p = cat(x);
    ASSERT_FALSE(p.coordinates_are_doubles());
    for (Method m : {Method::essdms, Method::mssd}) {
      SumResult r = minkowski_sum(p, p, m);
      EXPECT_EQ(case_counts(r), (std::array<long, 4>{long(p.num_facets()), 0, 0, 0}));
      EXPECT_GT(counter(r, "interval_exact_fallbacks"), 0);
    }
  }
}

TEST(SlopeDiagram, CubeOctahedronCounts) {
  // 6 cube facets and 8 octahedron facets in vertex regions, 12 crossings of
  // edge arcs; no coincidence.
  const ConvexPolytope cube = cat("cube"), octa = cat("octahedron");
  for (Method m : {Method::essdms, Method::mssd}) {
    SCOPED_TRACE(method_name(m));
    SumResult r = minkowski_sum(cube, octa, m);
    EXPECT_EQ(case_counts(r), (std::array<long, 4>{0, 0, 12, 14}));
    EXPECT_EQ(counter(r, "facet_point_tests"), 6 * 8);
    EXPECT_EQ(counter(r, "facet_point_arc_tests"), 6 * 12 + 8 * 12);
    // No edge arc lies in a single vertex region: nothing is pruned.
    EXPECT_EQ(counter(r, "arc_pair_tests"), 12 * 12);
    if (m == Method::essdms) {
      EXPECT_EQ(counter(r, "point_in_polygon_queries"), 0);
      EXPECT_EQ(counter(r, "contributing_vertex_tests"), 6 * (6 - 1) + 8 * (8 - 1));
    } else {
      EXPECT_GE(counter(r, "point_in_polygon_queries"), 14);
      EXPECT_EQ(counter(r, "contributing_vertex_tests"), 0);
    }
  }
}

TEST(SlopeDiagram, CubeRhombicDodecahedronFacetPointsOnArcs) {
  // Every facet point (±1,±1,0), ... of the rhombic dodecahedron lies in the
  // middle of an edge arc of the cube; the cube's facet points lie in the
  // regions of the degree-4 vertices.
  for (Method m : {Method::essdms, Method::mssd}) {
    SCOPED_TRACE(method_name(m));
    SumResult r = minkowski_sum(cat("cube"), cat("rhombic-dodecahedron"), m);
    EXPECT_EQ(case_counts(r), (std::array<long, 4>{0, 12, 0, 6}));
  }
}

TEST(SlopeDiagram, PruningOnlyRemovesArcsThatCrossNothing) {
  // ESSDMS tests a subset of MSSD's arc pairs and finds the same crossings.
  for (auto [x, y] : {std::pair{"cube", "sphere:3"}, {"sphere:2", "sphere:2@rot:7"}, {"dodecahedron", "icosahedron"},
                      {"truncated-cube", "cuboctahedron"}}) {
    SCOPED_TRACE(std::string(x) + " + " + y);
    const ConvexPolytope a = cat(x), b = cat(y);
    SumResult e = minkowski_sum(a, b, Method::essdms), w = minkowski_sum(a, b, Method::mssd);
    EXPECT_EQ(case_counts(e), case_counts(w));
    EXPECT_EQ(counter(w, "arc_pair_tests"), long(a.num_edges()) * long(b.num_edges()));
    EXPECT_LE(counter(e, "arc_pair_tests"), counter(w, "arc_pair_tests"));
    EXPECT_EQ(counter(e, "facet_point_tests"), counter(w, "facet_point_tests"));
    EXPECT_EQ(counter(e, "facet_point_arc_tests"), counter(w, "facet_point_arc_tests"));
  }
}

// The degree-3 forms used by the methods against the paper's expressions
// evaluated on the exact integer facet normals (degree 2 each).
namespace {

int sgn_of(const Rational& q) { return sgn(q); }

void expect_reductions_hold(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label) {
  SCOPED_TRACE(label);
  using namespace slope_diagram;
  const Diagram da(a), db(b);
  const Geometry g(da, db);
  auto n = [](const ConvexPolytope& p, Index f) { return p.plane(f).normal(); };
  // Eq. 6.
  for (Index f = 0; f < a.num_facets(); ++f)
    for (Index j = 0; j < b.num_facets(); ++j) {
      const Point3 x = n(a, f), y = n(b, j);
      EXPECT_EQ(g.same_facet_point(da, f, db, j), is_zero(cross(x, y)) && sgn_of(dot(x, y)) > 0);
    }
  // Eq. 8-9, both ways.
  auto on_arc = [&](const Diagram& P, Index f, const Diagram& Q, Index e) {
    const Point3 fp = n(P.p, f), s = n(Q.p, Q.p.facet(2 * e)), t = n(Q.p, Q.p.facet(2 * e + 1));
    const Point3 nn = cross(s, t);
    return sgn_of(dot(fp, nn)) == 0 && sgn_of(dot(cross(s, fp), nn)) > 0 && sgn_of(dot(cross(fp, t), nn)) > 0;
  };
  for (Index f = 0; f < a.num_facets(); ++f)
    for (Index e = 0; e < b.num_edges(); ++e) EXPECT_EQ(g.facet_point_on_arc(da, f, db, e), on_arc(da, f, db, e));
  for (Index f = 0; f < b.num_facets(); ++f)
    for (Index e = 0; e < a.num_edges(); ++e) EXPECT_EQ(g.facet_point_on_arc(db, f, da, e), on_arc(db, f, da, e));
  // Eq. 12: x = n × n' on both arcs (eq. 9 for x), or x' = −x.
  auto strictly_on = [&](const Point3& x, const Point3& s, const Point3& t) {
    const Point3 nn = cross(s, t);
    return sgn_of(dot(cross(s, x), nn)) > 0 && sgn_of(dot(cross(x, t), nn)) > 0;
  };
  for (Index ea = 0; ea < a.num_edges(); ++ea)
    for (Index eb = 0; eb < b.num_edges(); ++eb) {
      const Point3 s = n(a, a.facet(2 * ea)), t = n(a, a.facet(2 * ea + 1));
      const Point3 s2 = n(b, b.facet(2 * eb)), t2 = n(b, b.facet(2 * eb + 1));
      const Point3 x = cross(cross(s, t), cross(s2, t2));
      int want = 0;
      if (!is_zero(x)) {
        if (strictly_on(x, s, t) && strictly_on(x, s2, t2)) want = 1;
        else if (strictly_on(-x, s, t) && strictly_on(-x, s2, t2)) want = -1;
      }
      long long tests = 0;
      EXPECT_EQ(g.arcs_cross(ea, eb, tests), want) << ea << " " << eb;
    }
  // Point-in-spherical-polygon: strictly inside iff det(n_i, n_{i+1}, f) < 0
  // for every side, the determinant on exact normals (degree 6).
  for (Index f = 0; f < a.num_facets(); ++f)
    for (Index v = 0; v < b.num_vertices(); ++v) {
      bool inside = true;
      Index h = b.vertex_halfedge(v);
      do {
        if (normals_det_exact(b, b.facet(h), b.facet(h ^ 1u), a, f) >= 0) inside = false;
        h = b.next_around_vertex(h);
      } while (h != b.vertex_halfedge(v));
      long long tests = 0;
      EXPECT_EQ(g.facet_point_in_vertex_region(da, f, db, v, tests), inside) << f << " " << v;
    }
}

}  // namespace

TEST(SlopeDiagram, DegreeThreeFormsEqualThePapersExpressions) {
  expect_reductions_hold(cat("cube"), cat("octahedron"), "cube + octahedron");
  expect_reductions_hold(cat("cube"), cat("rhombic-dodecahedron"), "cube + rhombic-dodecahedron");
  expect_reductions_hold(cat("cube"), cat("cube"), "cube + cube");
  expect_reductions_hold(cat("sphere:1"), cat("sphere:1@rot:3"), "sphere:1 + rotated");
  expect_reductions_hold(cat("dodecahedron"), cat("truncated-tetrahedron@rot:9"), "dodecahedron + rotated");
  expect_reductions_hold(cat("random:12:1"), cat("random:15:2"), "random hulls");
  expect_reductions_hold(cat("zonotope:5:1"), cat("zonotope:5:2"), "zonotopes");
}

TEST(SlopeDiagram, JsonCountersAreNamed) {
  for (Method m : {Method::essdms, Method::mssd}) {
    SumResult r = minkowski_sum(cat("cube"), cat("sphere:2"), m);
    std::map<std::string, long long> c(r.counters.begin(), r.counters.end());
    for (const char* k : {"facet_point_tests", "facet_point_arc_tests", "arc_pair_tests", "point_in_polygon_queries",
                          "contributing_vertex_tests", "edge_arcs_pruned"})
      EXPECT_TRUE(c.count(k)) << k;
  }
}
