// walk, what only the walk has: its choice by auto, its half-edge structure
// and work counters (arc crossings, region steps, predicates and the ones the
// filter could not decide).  Its agreement with the chms oracle on every
// shared family and degenerate case — including the regression cases of
// reflections, zonotopes, equal rounded differences and scales below the
// normal double range — is checked by the conformance suite
// (test_conformance.cpp), with every invariant of the structure re-checked
// from scratch; here, by the same contract, the pairs only the walk is
// checked on: copies (its zero certificates) and a large random pair.
#include <minksum/catalog.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gtest/gtest.h>

#include "method_families.hpp"
#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

TEST(Walk, IsTheAutomaticChoice) {
  EXPECT_TRUE(method_available(Method::walk));
  const SumResult r = minkowski_sum(cat("cube"), cat("octahedron"));
  EXPECT_EQ(r.method, Method::walk);
  EXPECT_EQ(r.polytope.num_vertices(), 24u);
  EXPECT_EQ(r.polytope.num_edges(), 48u);
  EXPECT_EQ(r.polytope.num_facets(), 26u);
}

TEST(Walk, CubeOctahedronProvenance) {
  // 6 translated + 8 corner + 12 edge facets; the 12 edge facets are the
  // 12 crossings of the cube's arcs with the octahedron's.
  const WalkSum w = minkowski_walk(cat("cube"), cat("octahedron"));
  EXPECT_EQ(w.num_facets(), 26u);
  long edge_facets = 0;
  for (const auto& p : w.provenance) edge_facets += p.origin() == FacetOrigin::edge;
  EXPECT_EQ(edge_facets, 12);
  EXPECT_EQ(w.crossings, 12u);
  // The result reports the same count.
  EXPECT_EQ(counter(minkowski_sum(cat("cube"), cat("octahedron"), Method::walk), "crossings"), 12);
}

// to_polytope(std::move(w), ...) takes w's half-edges instead of copying
// them: the same polytope as from a copy, array for array.
TEST(Walk, ToPolytopeFromAMovedWalkSumIsTheSame) {
  const ConvexPolytope a = cat("cube@rot:2"), b = cat("sphere:2");
  WalkSum w = minkowski_walk(a, b);
  const ConvexPolytope copied = to_polytope(w, a, b);
  const std::vector<std::pair<Index, Index>> origin = w.vertex_origin;
  const ConvexPolytope moved = to_polytope(std::move(w), a, b);
  EXPECT_EQ(w.vertex_origin, origin);  // kept
  ASSERT_EQ(moved.num_vertices(), copied.num_vertices());
  ASSERT_EQ(moved.num_halfedges(), copied.num_halfedges());
  ASSERT_EQ(moved.num_facets(), copied.num_facets());
  for (Index h = 0; h < moved.num_halfedges(); ++h) {
    ASSERT_EQ(moved.origin(h), copied.origin(h)) << h;
    ASSERT_EQ(moved.next(h), copied.next(h)) << h;
    ASSERT_EQ(moved.prev(h), copied.prev(h)) << h;
    ASSERT_EQ(moved.facet(h), copied.facet(h)) << h;
  }
  for (Index v = 0; v < moved.num_vertices(); ++v) ASSERT_EQ(moved.point(v), copied.point(v)) << v;
  for (Index f = 0; f < moved.num_facets(); ++f) ASSERT_EQ(moved.plane(f), copied.plane(f)) << f;
  EXPECT_EQ(moved.check_invariants(), "");
}

TEST(Walk, IdenticalOperands) {
  // A = B: every facet of A meets its parallel twin, every arc runs along an
  // arc of B (the walk's overlap state all the way): no crossing.
  const WalkSum w = minkowski_walk(cat("sphere:3"), cat("sphere:3"));
  EXPECT_EQ(w.num_facets(), 320u);
  EXPECT_EQ(w.crossings, 0u);
  for (const auto& p : w.provenance) EXPECT_EQ(p.origin(), FacetOrigin::facet_facet);
  for (const char* x : {"cube", "dodecahedron@rot:3", "random:40:7"}) {
    const ConvexPolytope a = cat(x);
    const WalkSum v = minkowski_walk(a, a);
    EXPECT_EQ(v.num_facets(), a.num_facets()) << x;
    EXPECT_EQ(v.crossings, 0u) << x;
  }
}

TEST(Walk, IdenticalOperandsNeedNoExactStage) {
  // A ⊕ A with facets not axis-aligned: almost every degenerate sign is
  // <an edge of one copy, n(the facet of the other copy carrying the same
  // edge)> = 0, or two equal edge vectors in the facet merge, certified by
  // the exact equality of the difference vectors (no GMP).  The few left
  // are nonzero signs too close for the filter.
  const ConvexPolytope a = cat("sphere:4");
  const WalkSum w = minkowski_walk(a, a);
  EXPECT_EQ(w.num_vertices(), 642u);
  EXPECT_EQ(w.num_edges(), 1920u);
  EXPECT_EQ(w.num_facets(), 1280u);
  EXPECT_LT(100 * w.exact_predicates, w.predicates) << w.exact_predicates << " of " << w.predicates;
  // The sum is 2A exactly.
  const ConvexPolytope twice = homothet(a, 2);
  conforming_sum(Method::walk, a, a, "sphere:4 + sphere:4", {false, true}, &twice);
}

TEST(Walk, CopiesTranslatedScaledReflected) {
  // The zero certificates of the walk (an edge vector equal or opposite to an
  // edge of the other operand's facet, decided without GMP) against copies
  // whose edge vectors are equal (translates by exact doubles or by
  // rationals), opposite (point reflections), scaled by a power of two (no
  // equal difference), and scaled by 3 (rounded).  A ⊕ (λA + t) = (1 + λ) A + t.
  // The other methods meet copies in the conformance suite's
  // IdenticalOperands and PointReflections.
  const ConvexPolytope sphere = cat("sphere:3"), icosahedron = cat("icosahedron@rot:3"), random = cat("random:60:5");
  const Point3 t = Q("1/2", "-3", "1/4"), tiny(1e-20, 0, 0), r = Q("1/8", "1/16", "-2");
  struct Copy {
    const ConvexPolytope& a;
    std::string b;
    ConvexPolytope sum;
    Checks checks;
  };
  const Copy copies[] = {
      {sphere, "sphere:3@translate:1/2,-3,1/4", homothet(sphere, 2, t), {}},
      {sphere, "sphere:3@translate:1e-20,0,0", homothet(sphere, 2, tiny), Checks{false, true}},
      {sphere, "sphere:3@scale:2", homothet(sphere, 3), {}},
      {sphere, "sphere:3@scale:3", homothet(sphere, 4), Checks{false, true}},
      {icosahedron, "icosahedron@rot:3", homothet(icosahedron, 2), {}},
      {random, "random:60:5@translate:1/8,1/16,-2", homothet(random, 2, r), {}},
  };
  for (const Copy& c : copies) conforming_sum(Method::walk, c.a, cat(c.b), "copy " + c.b, c.checks, &c.sum);
  // Point reflections: no closed form, the oracle (once: a translate of the
  // first operand shifts the sum).
  const ConvexPolytope reflected = cat("sphere:3@neg");
  const SumResult oracle = minkowski_sum(sphere, reflected, Method::chms);
  const ConvexPolytope shifted = oracle.polytope.translated(P(5, 0, 0));
  conforming_sum(Method::walk, sphere, reflected, "sphere:3 + sphere:3@neg", {}, &oracle.polytope);
  conforming_sum(Method::walk, cat("sphere:3@translate:5,0,0"), reflected, "sphere:3@translate:5,0,0 + sphere:3@neg",
                 {}, &shifted);
  expect_conforms(Method::walk, "sphere:2@rot:1", "sphere:2@rot:1@neg");
  expect_conforms(Method::walk, "random:60:5", "random:60:5@neg");
}

TEST(Walk, LargeRandomHulls) {
  // 300 + 300 vertices: the oracle's hull of 90 000 sums is the cost here
  // (the walk itself takes about a millisecond), so only the walk, which
  // auto chooses, is checked on this pair.
  expect_conforms(Method::walk, "random:300:1", "random:300:2", {false, true});
}

TEST(Walk, WorkIsOutputSensitive) {
  // The walk does work proportional to the input and output, not to their
  // product: sphere:5 ⊕ sphere:5@rot:1 (2562 × 2562 vertices) takes a few
  // steps per feature.
  const ConvexPolytope a = cat("sphere:5"), b = cat("sphere:5@rot:1");
  const WalkSum w = minkowski_walk(a, b);
  EXPECT_EQ(w.num_vertices(), 10740u);
  EXPECT_EQ(w.num_edges(), 26596u);
  EXPECT_EQ(w.num_facets(), 15858u);
  EXPECT_LT(double(w.steps), 3.0 * double(w.features(a, b)));
  EXPECT_LT(double(w.predicates), 12.0 * double(w.features(a, b)));
  EXPECT_EQ(w.crossings, w.num_facets() - a.num_facets() - b.num_facets());
}
