// Exact proximity queries on M = P ⊕ (−Q): every answer of TranslationalObstacle
// is checked against brute force over all features of M, on query points that
// lie exactly on facets, edges and vertices of M, just inside and just outside
// them, and on a rational grid; and against certificates computed on P and Q
// translated directly.  Plus the `minksum query` and `minksum simulate`
// commands.
#include <gtest/gtest.h>

#include <cctype>

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/predicates.hpp>
#include <minksum/proximity.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <regex>
#include <string>

#include "proximity/obstacle_geometry.hpp"  // detail::reference_values
#include "test_support.hpp"

using namespace minksum;
using minksum::testing::P;
namespace fs = std::filesystem;

namespace {

Point3 R(const char* x, const char* y, const char* z) { return Point3(Rational(x), Rational(y), Rational(z)); }
// p/q in lowest terms (mpq_class arithmetic requires canonical operands).
Rational frac(long p, long q) {
  Rational r(p, q);
  r.canonicalize();
  return r;
}
Point3 zero() { return Point3(Rational(0), Rational(0), Rational(0)); }

// ---------------------------------------------------------------------------
// Brute force on M, independent of the library's walks.

ContactStatus brute_status(const ConvexPolytope& m, const Point3& s) {
  int worst = -1;
  for (Index f = 0; f < m.num_facets(); ++f) worst = std::max(worst, m.plane(f).side(s));
  return worst > 0 ? ContactStatus::separate : worst == 0 ? ContactStatus::touching : ContactStatus::penetrating;
}

// Squared distance from s to M, over every vertex, edge and facet.
Rational brute_distance2(const ConvexPolytope& m, const Point3& s) {
  if (brute_status(m, s) != ContactStatus::separate) return 0;
  Rational best = -1;
  auto take = [&](const Rational& d2) {
    if (best < 0 || d2 < best) best = d2;
  };
  for (Index v = 0; v < m.num_vertices(); ++v) take(dot(s - m.point(v), s - m.point(v)));
  for (Index e = 0; e < m.num_edges(); ++e) {
    const Point3& a = m.point(m.origin(2 * e));
    const Point3& b = m.point(m.target(2 * e));
    const Rational t = dot(s - a, b - a) / dot(b - a, b - a);
    if (t > 0 && t < 1) {
      const Point3 x = a + t * (b - a);
      take(dot(s - x, s - x));
    }
  }
  for (Index f = 0; f < m.num_facets(); ++f) {
    const Point3 n = m.plane(f).normal();
    const Rational t = (dot(n, s) - Rational(m.plane(f).d)) / dot(n, n);
    const Point3 x = s - t * n;
    bool inside = true;  // x within the facet's polygon: inside every edge's outward plane
    const Index h0 = m.facet_halfedge(f);
    Index h = h0;
    do {
      const Point3& a = m.point(m.origin(h));
      if (sgn(dot(x - a, cross(m.point(m.target(h)) - a, n))) > 0) inside = false;
      h = m.next(h);
    } while (h != h0);
    if (inside) take(dot(s - x, s - x));
  }
  return best;
}

Rational brute_depth2(const ConvexPolytope& m, const Point3& s) {
  if (brute_status(m, s) != ContactStatus::penetrating) return 0;
  Rational best = -1;
  for (Index f = 0; f < m.num_facets(); ++f) {
    const Point3 n = m.plane(f).normal();
    const Rational gap = Rational(m.plane(f).d) - dot(n, s);
    const Rational d2 = gap * gap / dot(n, n);
    if (best < 0 || d2 < best) best = d2;
  }
  return best;
}

Rational brute_alpha(const ConvexPolytope& m, const Point3& s, const Point3& d) {
  if (brute_status(m, s) != ContactStatus::penetrating) return 0;
  Rational best = -1;
  for (Index f = 0; f < m.num_facets(); ++f) {
    const Point3 n = m.plane(f).normal();
    const Rational along = -dot(n, d);
    if (sgn(along) <= 0) continue;
    const Rational a = (Rational(m.plane(f).d) - dot(n, s)) / along;
    if (best < 0 || a < best) best = a;
  }
  return best;
}

// Vertex set of a feature.
std::vector<Index> feature_vertices(const ConvexPolytope& p, const Feature& f) {
  std::vector<Index> v;
  if (f.dim == FeatureDim::vertex) v = {f.index};
  else if (f.dim == FeatureDim::edge) v = {p.origin(2 * f.index), p.target(2 * f.index)};
  else v = p.facet_vertices(f.index);
  std::sort(v.begin(), v.end());
  return v;
}

// Vertices of `p` maximising <x, n>.
std::vector<Index> support_set(const ConvexPolytope& p, const Point3& n) {
  Rational best;
  std::vector<Index> out;
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Rational h = dot(p.point(v), n);
    if (out.empty() || h > best) best = h, out = {v};
    else if (h == best) out.push_back(v);
  }
  return out;
}

bool point_in_feature(const ConvexPolytope& m, const Feature& f, const Point3& x) {
  if (f.dim == FeatureDim::vertex) return m.point(f.index) == x;
  if (f.dim == FeatureDim::edge) {
    const Point3& a = m.point(m.origin(2 * f.index));
    const Point3& b = m.point(m.target(2 * f.index));
    if (!is_zero(cross(b - a, x - a))) return false;
    const Rational t = dot(x - a, b - a) / dot(b - a, b - a);
    return t > 0 && t < 1;
  }
  if (m.plane(f.index).side(x) != 0) return false;
  for (Index g = 0; g < m.num_facets(); ++g)
    if (m.plane(g).side(x) > 0) return false;
  // Relative interior: not on any edge of the facet.
  for (Index v : m.facet_vertices(f.index))
    if (m.point(v) == x) return false;
  return true;
}

// The features of P and Q behind a feature of M are face_P(n) and face_Q(−n)
// for a normal n of the feature (the facet normal, or the sum of the normals
// of the facets around it).
void check_operand_features(const TranslationalObstacle& ob, const Witness& w) {
  const ConvexPolytope& m = ob.obstacle();
  Point3 n = zero();
  if (w.m.dim == FeatureDim::facet) n = m.plane(w.m.index).normal();
  else if (w.m.dim == FeatureDim::edge)
    n = m.plane(m.facet(2 * w.m.index)).normal() + m.plane(m.facet(2 * w.m.index + 1)).normal();
  else {
    const Index h0 = m.vertex_halfedge(w.m.index);
    Index h = h0;
    do {
      n = n + m.plane(m.facet(h)).normal();
      h = m.next_around_vertex(h);
    } while (h != h0);
  }
  std::vector<Index> sp = support_set(ob.p(), n), sq = support_set(ob.q(), -n);
  std::sort(sp.begin(), sp.end());
  std::sort(sq.begin(), sq.end());
  EXPECT_EQ(feature_vertices(ob.p(), w.p), sp);
  EXPECT_EQ(feature_vertices(ob.q(), w.q), sq);
}

// Query points: every vertex, edge midpoint and facet centroid of M, and
// points on the segments from M's interior point through them at k/4 of the
// way (k = 4: on the feature; k < 4 inside; k > 4 outside), and a grid.
std::vector<Point3> query_points(const TranslationalObstacle& ob, bool grid) {
  const ConvexPolytope& m = ob.obstacle();
  std::vector<Point3> base;
  for (Index v = 0; v < m.num_vertices(); ++v) base.push_back(m.point(v));
  for (Index e = 0; e < m.num_edges(); ++e)
    base.push_back(Rational(1, 2) * (m.point(m.origin(2 * e)) + m.point(m.target(2 * e))));
  for (Index f = 0; f < m.num_facets(); ++f) {
    auto vs = m.facet_vertices(f);
    Point3 c = zero();
    for (Index v : vs) c = c + m.point(v);
    base.push_back(frac(1, long(vs.size())) * c);
  }
  const Point3 o = ob.interior_point();
  std::vector<Point3> out;
  for (const auto& b : base)
    for (int k : {1, 3, 4, 5, 9}) out.push_back(o + frac(k, 4) * (b - o));
  // Just inside / just outside vertices and edges.
  for (const auto& b : base) {
    out.push_back(o + (Rational(1) - Rational(1, 1000000)) * (b - o));
    out.push_back(o + (Rational(1) + Rational(1, 1000000)) * (b - o));
  }
  if (grid)
    for (int x = -6; x <= 6; x += 2)
      for (int y = -6; y <= 6; y += 3)
        for (int z = -6; z <= 6; z += 4) out.emplace_back(frac(x, 3), frac(y, 3), frac(z, 3));
  return out;
}

void check_all_queries(TranslationalObstacle& ob, const std::vector<Point3>& points) {
  const ConvexPolytope& m = ob.obstacle();
  const Point3 dirs[] = {P(1, 0, 0), P(0, -1, 0), R("1/3", "-2/7", "5/11"), P(1, 1, 1)};
  int k = 0;
  for (const Point3& s : points) {
    SCOPED_TRACE("s = (" + format_exact(s.x) + ", " + format_exact(s.y) + ", " + format_exact(s.z) + ")");
    const ContactStatus want = brute_status(m, s);
    // Collision: status and the stabbed facet.
    CollisionResult c = ob.collide_point(s);
    ASSERT_EQ(c.status, want);
    ASSERT_LT(c.witness.facet, m.num_facets());
    if (!(s == ob.interior_point())) {
      const Point3 dir = s - ob.interior_point();
      const Point3 n = m.plane(c.witness.facet).normal();
      const Rational along = dot(n, dir);
      ASSERT_GT(along, 0);
      const Point3 y = ob.interior_point() + ((Rational(m.plane(c.witness.facet).d) - dot(n, ob.interior_point())) / along) * dir;
      EXPECT_EQ(brute_status(m, y), ContactStatus::touching) << "stabbed facet does not hold the exit point";
    }
    if (want == ContactStatus::touching) {
      EXPECT_TRUE(point_in_feature(m, c.witness.m, s)) << "touching feature dim " << int(c.witness.m.dim);
    }
    check_operand_features(ob, c.witness);

    // Distance.
    DistanceResult d = ob.distance_point(s);
    EXPECT_EQ(d.status, want);
    EXPECT_EQ(d.squared_distance(), brute_distance2(m, s));
    EXPECT_EQ(dot(d.point_q() - d.point_p(), d.point_q() - d.point_p()), d.squared_distance());
    EXPECT_NE(brute_status(ob.p(), d.point_p()), ContactStatus::separate);
    EXPECT_NE(brute_status(ob.q().translated(s), d.point_q()), ContactStatus::separate);
    if (want == ContactStatus::separate) {
      EXPECT_TRUE(point_in_feature(m, d.witness.m, d.point_p() - (d.point_q() - s)));
      check_operand_features(ob, d.witness);
    }

    // Penetration depth.
    DepthResult p = ob.penetration_depth_point(s);
    EXPECT_EQ(p.status, want);
    EXPECT_EQ(p.squared_depth(), brute_depth2(m, s));
    EXPECT_EQ(dot(p.direction(), p.direction()), p.squared_depth());
    if (want == ContactStatus::penetrating) {
      EXPECT_EQ(brute_status(m, s - p.direction()), ContactStatus::touching);
      EXPECT_TRUE(point_in_feature(m, p.witness.m, s - p.direction()));
      check_operand_features(ob, p.witness);
    }

    // Directional penetration depth.
    const Point3& dd = dirs[k++ % 4];
    DirectionalDepthResult r = ob.directional_depth_point(s, dd);
    EXPECT_EQ(r.status, want);
    EXPECT_EQ(r.t, brute_alpha(m, s, dd));
    if (want == ContactStatus::penetrating) {
      EXPECT_EQ(brute_status(m, s - r.translation), ContactStatus::touching);
      EXPECT_TRUE(point_in_feature(m, r.witness.m, s - r.translation));
      check_operand_features(ob, r.witness);
    }
  }
}

struct Pair {
  const char* p;
  const char* q;
};

class ProximityPairs : public ::testing::TestWithParam<Pair> {};

TEST_P(ProximityPairs, AllQueriesMatchBruteForce) {
  const Pair pr = GetParam();
  TranslationalObstacle ob(catalog_polytope(pr.p), catalog_polytope(pr.q));
  ASSERT_EQ(ob.obstacle().check_invariants(), "");
  check_all_queries(ob, query_points(ob, true));
}

INSTANTIATE_TEST_SUITE_P(Catalog, ProximityPairs,
                         ::testing::Values(Pair{"cube", "cube"}, Pair{"cube", "tetra"},
                                           Pair{"octahedron", "cube@rot:1,2,3,4"}, Pair{"tetra", "tetra"},
                                           Pair{"dodecahedron", "tetra@rot:7"}, Pair{"random:8:3", "random:7:4"},
                                           Pair{"icosahedron", "cube@scale:1/2"}, Pair{"box:1:2:3", "octahedron@rot:0,0,1,1"}),
                         [](const ::testing::TestParamInfo<Pair>& info) {
                           // A readable test name: the two specs, non-alphanumerics as '_'.
                           std::string n = std::to_string(info.index) + "_" + std::string(info.param.p) + "_" + info.param.q;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(Proximity, CvmsAndChmsObstaclesAnswerAlike) {
  TranslationalObstacle a(catalog_polytope("cube@rot:3"), catalog_polytope("icosahedron"), Method::cvms);
  TranslationalObstacle b(catalog_polytope("cube@rot:3"), catalog_polytope("icosahedron"), Method::chms);
  for (const Point3& s : query_points(a, false)) {
    EXPECT_EQ(a.collide_point(s).status, b.collide_point(s).status);
    EXPECT_EQ(a.distance_point(s).squared_distance(), b.distance_point(s).squared_distance());
    EXPECT_EQ(a.penetration_depth_point(s).squared_depth(), b.penetration_depth_point(s).squared_depth());
  }
}

// The obstacle's construction reports progress (the sum's phases, then
// M's planes) and stops on SumOptions::cancel: Python's Obstacle() waited
// for the whole construction before Ctrl-C took effect.
TEST(Proximity, ObstacleConstructionReportsProgressAndHonoursCancel) {
  std::vector<std::string> phases;
  SumOptions o;
  o.progress = [&](const char* p, double) {
    if (phases.empty() || phases.back() != p) phases.push_back(p);
  };
  const TranslationalObstacle a(catalog_polytope("sphere:3"), catalog_polytope("sphere:3@rot:1"), Method::walk, o);
  ASSERT_FALSE(phases.empty());
  EXPECT_EQ(phases.back(), "planes");
  const TranslationalObstacle b(catalog_polytope("sphere:3"), catalog_polytope("sphere:3@rot:1"), Method::walk);
  EXPECT_EQ(a.obstacle().num_facets(), b.obstacle().num_facets());
  std::atomic<bool> cancel{true};
  SumOptions c;
  c.cancel = &cancel;
  EXPECT_THROW(TranslationalObstacle(catalog_polytope("cube"), catalog_polytope("cube"), Method::walk, c), Cancelled);
}

// Grazing contacts: two unit cubes side by side, touching along a facet, an
// edge, a vertex; then moved by 10^-40 either way.
TEST(Proximity, GrazingContactsAreExact) {
  TranslationalObstacle ob(catalog_polytope("cube"), catalog_polytope("cube"));
  const Rational tiny("1/10000000000000000000000000000000000000000");
  const Point3 contacts[] = {P(2, 0, 0), P(2, 2, 0), P(2, 2, 2), P(2, 1, -1), R("2", "3/2", "-2")};
  using enum FeatureDim;
  const FeatureDim want_dim[] = {facet, edge, vertex, facet, edge};
  for (int i = 0; i < 5; ++i) {
    const Point3& w = contacts[i];
    CollisionResult c = ob.collide(zero(), w);
    EXPECT_EQ(c.status, ContactStatus::touching);
    EXPECT_EQ(c.witness.m.dim, want_dim[i]);
    const Point3 out = (Rational(1) + tiny) * w, in = (Rational(1) - tiny) * w;
    EXPECT_EQ(ob.collide(zero(), out).status, ContactStatus::separate);
    EXPECT_EQ(ob.collide(zero(), in).status, ContactStatus::penetrating);
    // Translating both by the same amount changes nothing.
    EXPECT_EQ(ob.collide(R("1/3", "1/7", "-5"), w + R("1/3", "1/7", "-5")).status, ContactStatus::touching);
    DistanceResult d = ob.distance(zero(), out);
    EXPECT_EQ(d.status, ContactStatus::separate);
    EXPECT_EQ(d.squared_distance(), brute_distance2(ob.obstacle(), out));
    if (i < 3) {
      EXPECT_EQ(d.squared_distance(), tiny * tiny * dot(w, w));  // facet, edge, vertex: along w
    }
    EXPECT_GT(d.distance(), 0);
    DepthResult p = ob.penetration_depth(zero(), in);
    EXPECT_EQ(p.status, ContactStatus::penetrating);
    EXPECT_GT(p.squared_depth(), 0);
  }
}

// The distance through M equals the distance of P+u and Q+w computed directly:
// the closest points lie in the translated bodies and the plane orthogonal to
// their difference separates them (a certificate that needs no M), and an
// independently computed sum of the translated bodies gives the same value.
TEST(Proximity, DistanceThroughMEqualsDirectDistance) {
  ConvexPolytope p = catalog_polytope("dodecahedron"), q = catalog_polytope("cube@rot:5");
  TranslationalObstacle ob(p, q);
  const Point3 us[] = {R("-3", "1/2", "0"), R("0", "0", "0"), R("1/3", "-4", "2/7"), R("5", "5", "5")};
  const Point3 ws[] = {R("3", "0", "1/5"), R("4", "-1/2", "1"), R("-2", "2", "-3"), R("-1", "1", "2")};
  for (const Point3& u : us)
    for (const Point3& w : ws) {
      DistanceResult d = ob.distance(u, w);
      ConvexPolytope pu = p.translated(u), qw = q.translated(w);
      EXPECT_NE(brute_status(pu, d.point_p()), ContactStatus::separate);
      EXPECT_NE(brute_status(qw, d.point_q()), ContactStatus::separate);
      const Point3 dir = d.point_q() - d.point_p();
      EXPECT_EQ(dot(dir, dir), d.squared_distance());
      if (d.status == ContactStatus::separate) {
        for (Index v = 0; v < pu.num_vertices(); ++v) EXPECT_LE(dot(pu.point(v), dir), dot(d.point_p(), dir));
        for (Index v = 0; v < qw.num_vertices(); ++v) EXPECT_GE(dot(qw.point(v), dir), dot(d.point_q(), dir));
      }
      SumResult direct = minkowski_sum(pu, qw.negated(), Method::chms);
      EXPECT_EQ(d.squared_distance(), brute_distance2(direct.polytope, zero()));
    }
}

// A coherent trajectory: the walks move a few steps per query, never scan.
TEST(Proximity, CoherentTrajectoryWalksLocally) {
  TranslationalObstacle ob(catalog_polytope("random:20:5"), catalog_polytope("cube@rot:2"));
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const Rational t = frac(i - n / 2, n / 8);
    const Point3 s(t, frac(1, 3) + t / 5, frac(-1, 2));
    const ContactStatus want = brute_status(ob.obstacle(), s);
    EXPECT_EQ(ob.collide_point(s).status, want);
    EXPECT_EQ(ob.distance_point(s).squared_distance(), brute_distance2(ob.obstacle(), s));
  }
  EXPECT_EQ(ob.stats().full_scans, 0u);
  EXPECT_LT(ob.stats().walk_steps, std::uint64_t(20 * n));
  EXPECT_GT(ob.stats().certified, 0u);
}

// The distance walk decides with the kernel's filters on the cached
// roundings: on random separate poses (rational s, fixed seed) every query is
// certified by the filtered Voronoi walk (no scan) with exact squared
// distances equal to brute force over all features of M, and the filters
// leave (almost) nothing to GMP.
TEST(Proximity, FilteredDistanceWalkMatchesBruteForceOnRandomPoses) {
  const std::uint64_t seed = 20261123;
  std::mt19937_64 rng(seed);
  TranslationalObstacle ob(catalog_polytope("random:40:11"), catalog_polytope("random:25:12@rot:1,2,3,4"));
  const ConvexPolytope& m = ob.obstacle();
  auto coordinate = [&] {
    return frac(long(std::uniform_int_distribution<int>(-4000, 4000)(rng)),
                long(std::uniform_int_distribution<int>(1, 997)(rng)));
  };
  reset_predicate_stats();
  ob.reset_stats();
  int separate = 0;
  int dims[3][3] = {};  // closest pairs by the dimensions of P's and Q's features
  for (int i = 0; i < 300; ++i) {
    const Point3 s(coordinate(), coordinate(), coordinate());
    SCOPED_TRACE("seed " + std::to_string(seed) + ", query " + std::to_string(i));
    const DistanceResult d = ob.distance_point(s);
    ASSERT_EQ(d.status, brute_status(m, s));
    ASSERT_EQ(d.squared_distance(), brute_distance2(m, s));
    ASSERT_EQ(ob.squared_distance_by_scan(s), d.squared_distance());
    if (d.status != ContactStatus::separate) continue;
    ++separate;
    EXPECT_EQ(dot(d.direction(), d.direction()), d.squared_distance());
    EXPECT_TRUE(point_in_feature(m, d.witness.m, d.point_p() - (d.point_q() - s)));
    EXPECT_GT(m.plane(d.witness.facet).side(s), 0);
    EXPECT_TRUE(point_in_feature(ob.p(), d.witness.p, d.point_p()) ||
                (d.witness.p.dim == FeatureDim::vertex && ob.p().point(d.witness.p.index) == d.point_p()));
    EXPECT_TRUE(point_in_feature(ob.q().translated(s), d.witness.q, d.point_q()) ||
                (d.witness.q.dim == FeatureDim::vertex && ob.q().point(d.witness.q.index) + s == d.point_q()));
    ++dims[int(d.witness.p.dim)][int(d.witness.q.dim)];
  }
  ASSERT_GT(separate, 200);
  // The generic closest pairs all occur: vertex–facet, facet–vertex, edge–edge.
  EXPECT_GT(dims[0][2], 0);
  EXPECT_GT(dims[2][0], 0);
  EXPECT_GT(dims[1][1], 0);
  EXPECT_EQ(ob.stats().full_scans, 0u);
  EXPECT_EQ(ob.stats().certified, std::uint64_t(separate));
  const PredicateStats ps = predicate_stats();
  const std::uint64_t calls = ps[PredicateId::dot_sign].calls + ps[PredicateId::edge_normal_side].calls;
  const std::uint64_t fallbacks =
      ps[PredicateId::dot_sign].fallbacks + ps[PredicateId::edge_normal_side].fallbacks;
  EXPECT_GT(calls, std::uint64_t(separate));
  EXPECT_EQ(fallbacks, 0u) << "of " << calls << " filtered Voronoi tests";
}

// The exact values of an answer (integers over common denominators, one
// reduction per output) equal the reference computed with a reduced rational
// at every step (detail::reference_values), for distance answers (also
// translated by u) and depth answers.
// The unreduced quotients of an answer equal the reference values: by
// exact comparison (cross-multiplication), in lowest terms, and as doubles.
void expect_quotients_match(const DistanceResult& d, const detail::ReferenceDistance& ref) {
  EXPECT_GT(sgn(d.squared_distance_quotient().den), 0);
  EXPECT_TRUE(d.squared_distance_quotient() == ref.squared_distance);
  EXPECT_EQ(d.squared_distance_quotient().to_rational(), ref.squared_distance);
  EXPECT_EQ(d.squared_distance_quotient().to_double(), to_double(ref.squared_distance));
  EXPECT_TRUE(d.direction_quotient() == ref.direction);
  EXPECT_TRUE(d.point_p_quotient() == ref.point_p);
  EXPECT_TRUE(d.point_q_quotient() == ref.point_q);
  EXPECT_EQ(d.point_p_quotient().to_point(), ref.point_p);
  const Vec3d qd = d.point_q_quotient().to_double(), qr = to_double(ref.point_q);
  EXPECT_TRUE(qd.x == qr.x && qd.y == qr.y && qd.z == qr.z);
  for (const QuotientPoint* x : {&d.direction_quotient(), &d.point_p_quotient(), &d.point_q_quotient()})
    EXPECT_GT(sgn(x->w), 0);
}

void expect_values_match_reference(TranslationalObstacle& ob, const Point3& s, const Point3& u) {
  {  // the quotients first, on a fresh answer (no lowest-terms value asked before)
    const DistanceResult d = ob.distance_point(s);
    expect_quotients_match(d, detail::reference_values(d));
    const DepthResult p = ob.penetration_depth_point(s);
    const detail::ReferenceDepth pref = detail::reference_values(p);
    EXPECT_TRUE(p.squared_depth_quotient() == pref.squared_depth);
    EXPECT_TRUE(p.direction_quotient() == pref.direction);
    EXPECT_EQ(p.direction_quotient().to_point(), pref.direction);
    EXPECT_EQ(p.depth(), std::sqrt(to_double(pref.squared_depth)));
  }
  const DistanceResult d = ob.distance_point(s);
  const detail::ReferenceDistance ref = detail::reference_values(d);
  EXPECT_EQ(d.squared_distance(), ref.squared_distance);
  EXPECT_EQ(d.direction(), ref.direction);
  EXPECT_EQ(d.point_p(), ref.point_p);
  EXPECT_EQ(d.point_q(), ref.point_q);
  EXPECT_EQ(d.distance(), std::sqrt(to_double(ref.squared_distance)));
  // Accessors in the other order (point_q first) on a fresh answer.
  const DistanceResult d2 = ob.distance_point(s);
  EXPECT_EQ(d2.point_q(), ref.point_q);
  EXPECT_EQ(d2.direction(), ref.direction);
  const DistanceResult t = ob.distance(u, s + u);
  const detail::ReferenceDistance tref = detail::reference_values(t);
  EXPECT_EQ(t.point_p(), tref.point_p);
  EXPECT_EQ(t.point_q(), tref.point_q);
  EXPECT_EQ(t.point_p(), ref.point_p + u);
  expect_quotients_match(t, tref);
  const DepthResult p = ob.penetration_depth_point(s);
  const detail::ReferenceDepth pref = detail::reference_values(p);
  EXPECT_EQ(p.squared_depth(), pref.squared_depth);
  EXPECT_EQ(p.direction(), pref.direction);
}

// Random poses (fixed seed) around M of pairs with dyadic vertices (doubles:
// M in double pairs), non-dyadic ones (exact rotations) and one of each; s
// with double coordinates (dyadic) and with rational ones (p/q, q odd).
TEST(ProximityExact, FastValuesEqualTheRationalReferenceOnRandomPoses) {
  const std::uint64_t seed = 20261124;
  std::mt19937_64 rng(seed);
  const Pair pairs[] = {{"random:30:5", "random:20:6"},           // dyadic, dyadic
                        {"cube", "cube@rot:3"},                   // dyadic, rational
                        {"sphere:1@rot:1", "dodecahedron@rot:2"},  // rational, rational
                        {"cube", "cube@scale:1/3"}};              // parallel facets: barycentric splits
  for (const Pair& pr : pairs) {
    TranslationalObstacle ob(catalog_polytope(pr.p), catalog_polytope(pr.q));
    int count[3] = {};
    for (int i = 0; i < 150; ++i) {
      SCOPED_TRACE(std::string(pr.p) + " / " + pr.q + ", seed " + std::to_string(seed) + ", pose " +
                   std::to_string(i));
      std::uniform_real_distribution<double> coord(-3, 3);
      Point3 s(coord(rng), coord(rng), coord(rng));
      if (i % 3 == 2)
        s = Point3(frac(std::uniform_int_distribution<long>(-3000, 3000)(rng), 1001),
                   frac(std::uniform_int_distribution<long>(-3000, 3000)(rng), 999), Rational(s.z));
      count[int(ob.collide_point(s).status)]++;
      expect_values_match_reference(ob, s, R("1/3", "-2", "1/2"));
    }
    EXPECT_GT(count[int(ContactStatus::separate)], 10) << pr.p << " / " << pr.q;
    EXPECT_GT(count[int(ContactStatus::penetrating)], 10) << pr.p << " / " << pr.q;
  }
}

// Touching poses (vertices, edge midpoints, facet centroids of M: s on ∂M)
// and poses just inside and outside them.
TEST(ProximityExact, FastValuesEqualTheRationalReferenceOnTouchingPoses) {
  for (const Pair& pr : {Pair{"cube", "cube@rot:3"}, Pair{"random:12:1", "random:9:2"},
                         Pair{"cube", "cube@scale:1/2"}}) {
    TranslationalObstacle ob(catalog_polytope(pr.p), catalog_polytope(pr.q));
    int touching = 0;
    for (const Point3& s : query_points(ob, false)) {
      SCOPED_TRACE(std::string(pr.p) + " / " + pr.q + ", s = (" + format_exact(s.x) + ", " + format_exact(s.y) +
                   ", " + format_exact(s.z) + ")");
      touching += ob.collide_point(s).status == ContactStatus::touching;
      expect_values_match_reference(ob, s, P(1, 2, 3));
    }
    EXPECT_GT(touching, 20) << pr.p << " / " << pr.q;
  }
}

// Degenerate pairs: parallel facets and coincident edges (cube / cube,
// cube / box), a vertex on a facet (tetra / cube), edges crossing edges
// (octahedron / cube): touching poses, poses just inside and outside them and
// poses k/4 of the way from the interior point.
TEST(ProximityExact, FastValuesEqualTheRationalReferenceOnDegeneratePairs) {
  for (const Pair& pr : {Pair{"cube", "cube"}, Pair{"cube", "box:1:2:3"}, Pair{"tetra", "cube"},
                         Pair{"octahedron", "cube@scale:1/2"}}) {
    TranslationalObstacle ob(catalog_polytope(pr.p), catalog_polytope(pr.q));
    int count[3] = {};
    for (const Point3& s : query_points(ob, false)) {
      SCOPED_TRACE(std::string(pr.p) + " / " + pr.q + ", s = (" + format_exact(s.x) + ", " + format_exact(s.y) +
                   ", " + format_exact(s.z) + ")");
      count[int(ob.collide_point(s).status)]++;
      expect_values_match_reference(ob, s, R("1/7", "0", "-5"));
    }
    for (int c : count) EXPECT_GT(c, 10) << pr.p << " / " << pr.q;
  }
}

// Coordinates at the ends of the double range: operands scaled by 2^±500,
// a polytope whose vertices' exponents differ by hundreds (one power of two
// as common denominator, numerators of hundreds of bits), s with subnormal
// and huge coordinates; and a rational polytope whose vertices' denominators
// are distinct primes (their lcm too long to share: one denominator per
// vertex, the general combination of points).
TEST(ProximityExact, FastValuesEqualTheRationalReferenceForLargeAndTinyCoordinates) {
  const std::uint64_t seed = 20261123;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> spread(-300, 300);
  auto cloud = [&](int n, int exponent, bool mixed) {
    std::vector<Point3> pts;
    for (int i = 0; i < n; ++i) {
      const int e = mixed ? spread(rng) : exponent;
      pts.emplace_back(std::ldexp(unit(rng), e), std::ldexp(unit(rng), e), std::ldexp(unit(rng), e));
    }
    return ConvexPolytope::hull(pts);
  };
  struct Case {
    const char* name;
    int exponent;  // the scale of the operands and of s
    bool mixed;    // P's vertices with exponents in [-300, 300]
  };
  auto primes_cloud = [&](int n) {
    std::vector<Point3> pts;
    long prime = 1000003;
    auto next_prime = [&] {
      for (prime += 2;; prime += 2) {
        bool is = true;
        for (long d = 3; d * d <= prime && is; d += 2) is = prime % d != 0;
        if (is) return prime;
      }
    };
    std::uniform_int_distribution<long> num(-1000000, 1000000);
    for (int i = 0; i < n; ++i) {
      const long d = next_prime();
      pts.emplace_back(frac(num(rng), d), frac(num(rng), d), frac(num(rng), d));
    }
    return ConvexPolytope::hull(pts);
  };
  for (const Case& c : {Case{"2^-500", -500, false}, Case{"2^500", 500, false}, Case{"mixed exponents", 0, true},
                        Case{"prime denominators", 0, false}}) {
    const bool primes = std::string(c.name) == "prime denominators";
    const ConvexPolytope p = primes ? primes_cloud(12) : cloud(12, c.exponent, c.mixed);
    const ConvexPolytope q = cloud(9, c.exponent, false);
    TranslationalObstacle ob(p, q);
    const double scale = c.mixed ? std::ldexp(1, 300) : std::ldexp(1, c.exponent);
    int count[3] = {};
    for (int i = 0; i < 40; ++i) {
      SCOPED_TRACE(std::string(c.name) + ", seed " + std::to_string(seed) + ", pose " + std::to_string(i));
      Point3 s(3 * scale * unit(rng), 3 * scale * unit(rng), 3 * scale * unit(rng));
      if (i % 4 == 3) s.z = Rational(std::ldexp(unit(rng), -1060));  // subnormal
      count[int(ob.collide_point(s).status)]++;
      expect_values_match_reference(ob, s, Point3(std::ldexp(1, -1070), 1e300, 0.5));
    }
    for (const Point3& s : query_points(ob, false)) expect_values_match_reference(ob, s, P(0, 0, 1));
    EXPECT_GT(count[int(ContactStatus::separate)], 5) << c.name;
  }
}

// The obstacle hands its spare storage to one answer after another: an
// answer kept alive (or copied) keeps its values while later answers are
// computed in other storage (another spare set, or their own once every set
// is held), and recycled storage forgets a translated answer's u and an
// earlier answer's values.
TEST(ProximityExact, RecycledStorageKeepsLiveAnswersAndForgetsDeadOnes) {
  TranslationalObstacle ob(catalog_polytope("cube"), catalog_polytope("cube@rot:3"));
  const Point3 far = P(5, 1, 2), near = R("5/2", "1/3", "0"), inside = R("1/5", "0", "1/7");
  const DistanceResult kept = ob.distance(P(1, 1, 1), far + P(1, 1, 1));
  const Point3 kept_p = kept.point_p();
  const Quotient kept_d2 = kept.squared_distance_quotient();
  DistanceResult copy;
  for (int i = 0; i < 6; ++i) {
    const Point3& s = i % 3 == 0 ? far : i % 3 == 1 ? near : inside;
    const DistanceResult d = ob.distance_point(s);
    expect_quotients_match(d, detail::reference_values(d));
    if (i == 1) copy = d;  // shares d's storage past d's end
    const DepthResult p = ob.penetration_depth_point(s);
    EXPECT_TRUE(p.squared_depth_quotient() == detail::reference_values(p).squared_depth);
  }
  // More answers kept alive than the obstacle has spare sets: the later ones
  // compute in storage of their own, every one keeps its values.
  std::vector<DistanceResult> alive;
  std::vector<Point3> poses;
  for (int i = 0; i < 7; ++i) {
    poses.push_back(far + Point3(Rational(i), Rational(0), frac(i, 3)));
    alive.push_back(ob.distance_point(poses.back()));
    if (i % 2 == 0) alive.back().point_p_quotient();  // some computed now, some after the others
  }
  for (std::size_t i = 0; i < alive.size(); ++i) {
    expect_quotients_match(alive[i], detail::reference_values(alive[i]));
    EXPECT_EQ(alive[i].squared_distance(), ob.squared_distance_by_scan(poses[i]));
  }
  EXPECT_EQ(kept.point_p(), kept_p);
  EXPECT_TRUE(kept.squared_distance_quotient() == kept_d2);
  EXPECT_EQ(kept.point_p(), detail::reference_values(kept).point_p);
  EXPECT_TRUE(copy.point_q_quotient() == detail::reference_values(copy).point_q);
  EXPECT_EQ(copy.squared_distance(), ob.squared_distance_by_scan(near));
}

// Quotient: sign normalised into the numerator, exact comparisons without
// reduction, lowest terms only in to_rational / to_string, the nearest
// double of num/den as they are.
TEST(ProximityExact, QuotientArithmetic) {
  EXPECT_THROW(Quotient(Integer(1), Integer(0)), std::invalid_argument);
  const Quotient a(Integer(6), Integer(-4));  // −3/2
  EXPECT_EQ(a.num, Integer(-6));
  EXPECT_EQ(a.den, Integer(4));
  EXPECT_EQ(a.sign(), -1);
  EXPECT_EQ(a.to_rational(), Rational(-3, 2));
  EXPECT_EQ(a.to_string(), "-3/2");
  EXPECT_EQ(Quotient(Integer(10), Integer(5)).to_string(), "2");
  EXPECT_TRUE(a == Quotient(Integer(-3), Integer(2)));
  EXPECT_TRUE(a == Rational(-3, 2));
  EXPECT_FALSE(a == Rational(-3, 4));
  EXPECT_TRUE(a < Quotient(Integer(-1), Integer(1)));
  EXPECT_TRUE(Quotient(Integer(-1), Integer(1)) > a);
  EXPECT_TRUE(a <= Quotient(Integer(3), Integer(-2)));
  EXPECT_FALSE(a >= Quotient(Integer(-2), Integer(2)));
  EXPECT_EQ(cmp(Quotient(Integer(2), Integer(6)), Quotient(Integer(1), Integer(3))), 0);
  EXPECT_EQ(cmp(Quotient(Integer(2), Integer(7)), Quotient(Integer(1), Integer(3))), -1);
  EXPECT_EQ(Quotient().sign(), 0);
  // 1/3 as 7/21: the nearest double of 1/3; 2^-1074 as 2/2^1075 (subnormal),
  // a tie between two doubles (1 + 2^-53, ties to even: 1).
  EXPECT_EQ(Quotient(Integer(7), Integer(21)).to_double(), 1.0 / 3);
  Integer big = 1;
  mpz_mul_2exp(big.get_mpz_t(), big.get_mpz_t(), 1075);
  EXPECT_EQ(Quotient(Integer(2), big).to_double(), std::ldexp(1, -1074));
  Integer two53 = 1;
  mpz_mul_2exp(two53.get_mpz_t(), two53.get_mpz_t(), 53);
  const Integer two54 = 2 * two53;
  EXPECT_EQ(Quotient(Integer(two54 + 2), two54).to_double(), 1.0);                         // tie: even
  EXPECT_EQ(Quotient(Integer(two54 + 6), two54).to_double(), 1.0 + std::ldexp(1, -51));   // tie: even
  EXPECT_EQ(Quotient(Integer(two54 + 3), two54).to_double(), 1.0 + std::ldexp(1, -52));   // nearest
  const QuotientPoint x{Integer(2), Integer(-4), Integer(0), Integer(6)};
  EXPECT_EQ(x.to_point(), R("1/3", "-2/3", "0"));
  EXPECT_TRUE(x == (QuotientPoint{Integer(1), Integer(-2), Integer(0), Integer(3)}));
  EXPECT_FALSE(x == (QuotientPoint{Integer(1), Integer(-2), Integer(1), Integer(3)}));
  EXPECT_TRUE(x == R("1/3", "-2/3", "0"));
}

// Degenerate poses: s = x + n with x a vertex, an edge midpoint or a facet
// centroid of M and n a normal on the boundary of x's normal cone, so that s
// is exactly equidistant from two or more features (the tests are exactly 0,
// decided by the exact stage); the witness is the smallest feature holding
// the closest point, and the distance is |n|².
TEST(Proximity, DistanceOnVoronoiRegionBoundaries) {
  for (const char* spec : {"cube@rot:1,2,3,4", "random:30:5", "dodecahedron"}) {
    SCOPED_TRACE(spec);
    TranslationalObstacle ob(catalog_polytope(spec), catalog_polytope("tetra@rot:2"));
    const ConvexPolytope& m = ob.obstacle();
    ob.reset_stats();
    for (Index e = 0; e < m.num_edges(); ++e) {
      const Index h = 2 * e;
      const Point3 x = Rational(1, 2) * (m.point(m.origin(h)) + m.point(m.target(h)));
      for (Index f : {m.facet(h), m.facet(h + 1)}) {
        // s − x along one facet's normal: on the boundary between the edge's
        // region and the facet's region.
        const Point3 n = m.plane(f).normal();
        const Point3 s = x + n;
        const DistanceResult d = ob.distance_point(s);
        ASSERT_EQ(d.status, ContactStatus::separate);
        EXPECT_EQ(d.squared_distance(), dot(n, n));
        EXPECT_EQ(d.witness.m.dim, FeatureDim::edge);
        EXPECT_EQ(d.witness.m.index, e);
        EXPECT_EQ(d.squared_distance(), brute_distance2(m, s));
      }
      // s − x along the edge's outer facet-normal sum, pushed to the edge's
      // end: s projects exactly onto the vertex (edge and vertex regions meet).
      const Point3& a = m.point(m.origin(h));
      const Point3 n = m.plane(m.facet(h)).normal() + m.plane(m.facet(h + 1)).normal();
      const DistanceResult d = ob.distance_point(a + n);
      EXPECT_EQ(d.squared_distance(), brute_distance2(m, a + n));
      EXPECT_TRUE(point_in_feature(m, d.witness.m, d.point_p() - (d.point_q() - (a + n))));
    }
    for (Index v = 0; v < m.num_vertices(); ++v) {
      // Along a facet normal at the vertex: the facet's, its edges' and the
      // vertex's regions all contain s.
      const Index h = m.vertex_halfedge(v);
      const Point3 n = m.plane(m.facet(h)).normal();
      const DistanceResult d = ob.distance_point(m.point(v) + n);
      EXPECT_EQ(d.squared_distance(), dot(n, n));
      EXPECT_EQ(d.witness.m.dim, FeatureDim::vertex);
      EXPECT_EQ(d.witness.m.index, v);
    }
    EXPECT_EQ(ob.stats().full_scans, 0u);
  }
}

// The batch API answers a trajectory as the single queries do (a second
// batch into the same result vector included), and on a coherent trajectory
// certifies every separate pose with a few filtered moves, never scanning.
TEST(Proximity, TrajectoryBatchEqualsSingleQueries) {
  TranslationalObstacle batch(catalog_polytope("random:30:7"), catalog_polytope("icosahedron@rot:1,1,0,2"));
  TranslationalObstacle single(batch.p(), batch.q());
  std::vector<Point3> traj;
  for (int i = 0; i < 160; ++i) {
    const Rational t = frac(i - 80, 16);
    traj.emplace_back(t, frac(1, 3) - t / 7, frac(i % 9 - 4, 5));
  }
  std::vector<DistanceResult> dist;
  std::vector<CollisionResult> col;
  std::vector<DepthResult> depth;
  for (int round = 0; round < 2; ++round) {
    batch.distance_points(traj, dist);
    batch.collide_points(traj, col);
    batch.penetration_depth_points(traj, depth);
    ASSERT_EQ(dist.size(), traj.size());
    for (std::size_t i = 0; i < traj.size(); ++i) {
      SCOPED_TRACE("round " + std::to_string(round) + ", pose " + std::to_string(i));
      const DistanceResult d = single.distance_point(traj[i]);
      EXPECT_EQ(dist[i].status, d.status);
      EXPECT_EQ(dist[i].squared_distance(), d.squared_distance());
      EXPECT_EQ(dist[i].squared_distance(), brute_distance2(batch.obstacle(), traj[i]));
      EXPECT_EQ(dist[i].distance(), d.distance());
      EXPECT_EQ(dist[i].point_p(), d.point_p());
      EXPECT_EQ(dist[i].point_q(), d.point_q());
      EXPECT_EQ(dist[i].direction(), d.direction());
      EXPECT_EQ(dist[i].witness.m.dim, d.witness.m.dim);
      EXPECT_EQ(dist[i].witness.m.index, d.witness.m.index);
      EXPECT_EQ(dist[i].witness.p.index, d.witness.p.index);
      EXPECT_EQ(dist[i].witness.q.index, d.witness.q.index);
      EXPECT_EQ(col[i].status, d.status);
      EXPECT_EQ(depth[i].squared_depth(), single.penetration_depth_point(traj[i]).squared_depth());
    }
  }
  EXPECT_EQ(batch.stats().full_scans, 0u);
  EXPECT_GT(batch.stats().certified, 100u);
}

// The batch answers of a trajectory of double poses (the kind a planner or
// the command line sends: a helix through M, crossing its boundary) equal
// the answers of the same poses asked one by one of a fresh obstacle, which
// has no witness to start from: statuses, features, and every exact value.
TEST(Proximity, TrajectoryBatchEqualsFreshOneByOneAnswers) {
  const ConvexPolytope p = catalog_polytope("sphere:2"), q = catalog_polytope("dodecahedron@rot:1,2,0,1");
  TranslationalObstacle batch(p, q);
  std::vector<Point3> traj;
  for (int i = 0; i < 120; ++i) {
    const double th = 0.09 * i;
    traj.emplace_back(2.6 * std::cos(th), 2.2 * std::sin(th), 0.02 * (i - 60));
  }
  std::vector<DistanceResult> dist;
  std::vector<DepthResult> depth;
  batch.distance_points(traj, dist);
  batch.penetration_depth_points(traj, depth);
  int separate = 0, penetrating = 0;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    SCOPED_TRACE("pose " + std::to_string(i));
    TranslationalObstacle fresh(p, q);
    const DistanceResult d = fresh.distance_point(traj[i]);
    const DepthResult e = fresh.penetration_depth_point(traj[i]);
    ASSERT_EQ(dist[i].status, d.status);
    EXPECT_EQ(dist[i].witness.m, d.witness.m);
    EXPECT_EQ(dist[i].witness.p, d.witness.p);
    EXPECT_EQ(dist[i].witness.q, d.witness.q);
    EXPECT_EQ(dist[i].squared_distance(), d.squared_distance());
    EXPECT_EQ(dist[i].squared_distance(), brute_distance2(fresh.obstacle(), traj[i]));
    EXPECT_EQ(dist[i].point_p(), d.point_p());
    EXPECT_EQ(dist[i].point_q(), d.point_q());
    EXPECT_EQ(dist[i].direction(), d.direction());
    ASSERT_EQ(depth[i].status, e.status);
    EXPECT_EQ(depth[i].witness.facet, e.witness.facet);
    EXPECT_EQ(depth[i].witness.m, e.witness.m);
    EXPECT_EQ(depth[i].squared_depth(), e.squared_depth());
    EXPECT_EQ(depth[i].squared_depth(), brute_depth2(fresh.obstacle(), traj[i]));
    EXPECT_EQ(depth[i].direction(), e.direction());
    separate += d.status == ContactStatus::separate;
    penetrating += d.status == ContactStatus::penetrating;
  }
  EXPECT_GT(separate, 10);  // the helix is outside and inside M
  EXPECT_GT(penetrating, 10);
}

// The distance walk runs first from the previous closest feature and skips
// the collision query only when its certificate proves s outside M: poses
// that touch M at the previous feature (a vertex, an edge, a facet of the
// box M = [-2, 2]^3) or lie inside it must still be touching or penetrating,
// as from scratch.
TEST(Proximity, DistanceWalkFirstNeverClaimsATouchingPoseSeparate) {
  const ConvexPolytope cube = catalog_polytope("cube");
  TranslationalObstacle ob(cube, cube);
  const Point3 poses[] = {P(3, 3, 3), P(2, 2, 2), P(3, 3, 3), P(3, 3, 0), P(2, 2, 0), P(3, 1, 0),
                          P(2, 1, 0), P(3, 1, 0), R("1", "1/2", "1/3"), P(3, 1, 0), P(2, 2, 2), P(5, 0, 0)};
  const ContactStatus want[] = {ContactStatus::separate, ContactStatus::touching,    ContactStatus::separate,
                                ContactStatus::separate, ContactStatus::touching,    ContactStatus::separate,
                                ContactStatus::touching, ContactStatus::separate,    ContactStatus::penetrating,
                                ContactStatus::separate, ContactStatus::touching,    ContactStatus::separate};
  for (std::size_t i = 0; i < std::size(poses); ++i) {
    SCOPED_TRACE("pose " + std::to_string(i));
    const DistanceResult d = ob.distance_point(poses[i]);
    TranslationalObstacle fresh(cube, cube);
    const DistanceResult e = fresh.distance_point(poses[i]);
    EXPECT_EQ(d.status, want[i]);
    EXPECT_EQ(e.status, want[i]);
    EXPECT_EQ(d.witness.m, e.witness.m);
    EXPECT_EQ(d.squared_distance(), brute_distance2(ob.obstacle(), poses[i]));
    EXPECT_EQ(d.point_p(), e.point_p());
    EXPECT_EQ(d.point_q(), e.point_q());
  }
}

// The exact values are computed from the witness on first use, on the M the
// answer was given on: an answer read after its obstacle was rotated (M
// recomputed) or destroyed has the values it would have had at once.
TEST(Proximity, AnswersKeepTheirObstacleAcrossRebuilds) {
  const ConvexPolytope p = catalog_polytope("cube"), q = catalog_polytope("tetra");
  const Point3 out = R("7/2", "1/3", "-1/5"), in = R("1/3", "1/5", "0");
  DistanceResult late, late_inside;
  DepthResult late_depth;
  Rational d2, inside_p;
  Point3 pp, dir;
  {
    TranslationalObstacle ob(p, q);
    late = ob.distance_point(out);
    late_inside = ob.distance(P(1, 0, 0), in + P(1, 0, 0));
    late_depth = ob.penetration_depth_point(in);
    TranslationalObstacle twin(p, q);
    d2 = twin.distance_point(out).squared_distance();
    pp = twin.distance_point(out).point_p();
    inside_p = twin.distance(P(1, 0, 0), in + P(1, 0, 0)).point_p().x;
    dir = twin.penetration_depth_point(in).direction();
    ob.set_q(rotated(q, {Integer(1), Integer(2), Integer(3), Integer(4)}));
    EXPECT_NE(ob.distance_point(out).squared_distance(), d2);  // M changed
  }
  EXPECT_EQ(late.squared_distance(), d2);
  EXPECT_EQ(late.squared_distance(), brute_distance2(TranslationalObstacle(p, q).obstacle(), out));
  EXPECT_EQ(late.point_p(), pp);
  EXPECT_EQ(late_inside.point_p().x, inside_p);  // the common point, translated by u
  EXPECT_EQ(late_inside.point_p(), late_inside.point_q());
  EXPECT_EQ(late_depth.direction(), dir);
  EXPECT_EQ(dot(dir, dir), late_depth.squared_depth());
  // A copy shares the values; a default answer has none.
  const DistanceResult copy = late;
  EXPECT_EQ(copy.squared_distance(), d2);
  EXPECT_EQ(DistanceResult{}.squared_distance(), 0);
  EXPECT_EQ(DepthResult{}.depth(), 0);
}

// The foot of a point strictly inside M on its nearest facet plane lies in
// the relative interior of that facet (were it on the facet's boundary, on
// the plane of a neighbour g too, s would be strictly nearer to g's plane):
// the witness face is the facet, which feature_on_facet confirms for the
// exact foot, also for poses equidistant from several facets.
TEST(Proximity, DepthFootLiesInsideTheNearestFacet) {
  TranslationalObstacle ob(catalog_polytope("cube"), catalog_polytope("cube@rot:3"));
  TranslationalObstacle box(catalog_polytope("cube"), catalog_polytope("cube"));  // M = [-2, 2]^3
  const Point3 poses[] = {R("1", "1", "1/2"), R("3/2", "3/2", "0"), R("3/2", "3/2", "3/2"), R("3/2", "1/2", "1/4"),
                          R("0", "0", "0"),   R("-1", "1", "1"),    R("1/3", "-3/2", "1/2")};
  for (TranslationalObstacle* o : {&ob, &box})
    for (const Point3& s : poses) {
      SCOPED_TRACE(format_exact(s.x) + "," + format_exact(s.y) + "," + format_exact(s.z));
      const DepthResult d = o->penetration_depth_point(s);
      ASSERT_EQ(d.status, ContactStatus::penetrating);
      const Point3 foot = s - d.direction();
      EXPECT_EQ(d.witness.m, Feature::facet(d.witness.facet));
      EXPECT_EQ(d.witness.m, o->feature_on_facet(d.witness.facet, foot));
      EXPECT_EQ(d.squared_depth(), brute_depth2(o->obstacle(), s));
    }
}

TEST(Proximity, RotationRebuildsM) {
  ConvexPolytope p = catalog_polytope("cube"), q = catalog_polytope("tetra");
  TranslationalObstacle ob(p, q);
  ob.collide_point(P(3, 0, 0));
  const Quaternion quat = {Integer(1), Integer(2), Integer(3), Integer(4)};
  ob.set_q(rotated(q, quat));
  EXPECT_EQ(ob.stats().rebuilds, 2u);
  EXPECT_TRUE(minksum::testing::same_polytope(ob.q(), catalog_polytope("tetra@rot:1,2,3,4")));
  check_all_queries(ob, query_points(ob, false));
  // The product of quaternions composes the rotations.
  const Quaternion a = {Integer(2), Integer(1), Integer(0), Integer(0)}, b = {Integer(1), Integer(0), Integer(3), Integer(1)};
  const Point3 x = R("1/3", "-2", "5");
  EXPECT_EQ(rotate(quaternion_product(a, b), x), rotate(a, rotate(b, x)));
  EXPECT_THROW(rotate({Integer(0), Integer(0), Integer(0), Integer(0)}, x), UsageError);
}

TEST(Proximity, DirectionalDepthIsNotNormalised) {
  TranslationalObstacle ob(catalog_polytope("cube"), catalog_polytope("cube"));
  // s = (1, 0, 0): P must move by 3 along -x (M is [-2,2]^3: exit at x = -2).
  DirectionalDepthResult r = ob.directional_depth(P(0, 0, 0), P(1, 0, 0), P(-2, 0, 0));
  EXPECT_EQ(r.status, ContactStatus::penetrating);
  EXPECT_EQ(r.t, Rational(1, 2));  // P moves by (1/2)(-2,0,0)... s − α d = (1 + 2α) hits 2 at α = 1/2
  EXPECT_DOUBLE_EQ(r.depth, 1.0);
  EXPECT_THROW(ob.directional_depth(zero(), zero(), zero()), UsageError);
}

// ---------------------------------------------------------------------------
// The command line.

struct CmdResult {
  int status;
  std::string out, err;
};

CmdResult run(const std::string& args, const std::string& input = "") {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("minksum_prox_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string err = (dir / ("err" + std::to_string(counter))).string();
  const std::string in = (dir / ("in" + std::to_string(counter++))).string();
  std::string cmd = std::string(MINKSUM_BIN) + " " + args + " 2>" + err;
  if (!input.empty()) {
    std::ofstream(in) << input;
    cmd += " <" + in;
  }
  CmdResult r;
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::ifstream e(err);
  r.err.assign(std::istreambuf_iterator<char>(e), {});
  return r;
}

bool has(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

TEST(ProximityCli, CollideDistanceDepthDdepthJson) {
  CmdResult c = run("query collide cube cube --translate-q 2,1/3,0 --json");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_TRUE(has(c.out, "\"status\": \"touching\"")) << c.out;
  EXPECT_TRUE(has(c.out, "\"witness\"")) << c.out;

  CmdResult d = run("query distance cube cube --translate-q 3,1/3,0 --translate-p 0,0,-1/2 --json");
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_TRUE(has(d.out, "\"status\": \"separate\"")) << d.out;
  EXPECT_TRUE(has(d.out, "\"squared_distance\": \"1\"")) << d.out;
  EXPECT_TRUE(has(d.out, "\"distance\": 1")) << d.out;
  EXPECT_TRUE(has(d.out, "\"direction\"")) << d.out;

  CmdResult p = run("query depth cube cube --translate-q 1/3,0,0 --json");
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(has(p.out, "\"status\": \"penetrating\"")) << p.out;
  EXPECT_TRUE(has(p.out, "\"squared_depth\": \"25/9\"")) << p.out;

  CmdResult r = run("query ddepth cube cube --translate-q 1/3,0,0 --direction -1,0,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.out, "\"t\": \"5/3\"")) << r.out;

  CmdResult rot = run("query collide cube cube --rotate-q 1,0,0,1 --translate-q 2,0,0 --json");
  ASSERT_EQ(rot.status, 0) << rot.err;
  EXPECT_TRUE(has(rot.out, "\"status\": \"touching\"")) << rot.out;

  CmdResult text = run("query distance cube tetra --translate-q 5,0,0");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_TRUE(has(text.out, "separate")) << text.out;
}

TEST(ProximityCli, BadVectorsAndUsage) {
  EXPECT_EQ(run("query collide cube cube --translate-q 1,2").status, 2);
  EXPECT_EQ(run("query collide cube cube --translate-q 1,x,2").status, 2);
  EXPECT_EQ(run("query collide cube cube --translate-q 1,nan,2").status, 2);
  EXPECT_EQ(run("query collide cube cube --translate-q 1/0,0,2").status, 2);
  EXPECT_EQ(run("query ddepth cube cube").status, 2);
  EXPECT_EQ(run("query ddepth cube cube --direction 0,0,0").status, 2);
  EXPECT_EQ(run("query collide cube cube --rotate-q 0,0,0,0").status, 2);
  EXPECT_EQ(run("query frobnicate cube cube").status, 2);
  EXPECT_EQ(run("query collide cube").status, 2);
  EXPECT_EQ(run("query --help").status, 0);
}

TEST(ProximityCli, TrajectoryMode) {
  const std::string poses =
      "# P translation, then Q translation\n"
      "0,0,0 3,0,0\n"
      "0,0,0 2,0,0\n"
      "\n"
      "1/2,0,0 2,0,0\n";
  CmdResult r = run("query collide cube cube --trajectory - --json", poses);
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  std::string l1, l2, l3;
  std::getline(lines, l1), std::getline(lines, l2), std::getline(lines, l3);
  EXPECT_TRUE(has(l1, "separate")) << r.out;
  EXPECT_TRUE(has(l2, "touching")) << r.out;
  EXPECT_TRUE(has(l3, "penetrating")) << r.out;

  CmdResult bad = run("query distance cube cube --trajectory -", "0,0,0 1,2\n");
  EXPECT_EQ(bad.status, 3);
  EXPECT_TRUE(has(bad.err, "line 1")) << bad.err;
}

TEST(ProximityCli, SimulateWritesItsPictureAtomically) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sim_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "trail.svg").string();
  CmdResult r = run("simulate --frames 12 -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.out, "touching")) << r.out;
  EXPECT_TRUE(has(r.out, "penetrating")) << r.out;
  std::ifstream f(out);
  std::string svg((std::istreambuf_iterator<char>(f)), {});
  EXPECT_TRUE(has(svg, "<svg")) << svg.substr(0, 200);
  EXPECT_TRUE(has(svg, "</svg>"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  EXPECT_EQ(run("simulate --frames 12 -o " + (dir / "x.txt").string()).status, 2);
  fs::remove_all(dir);
}

// The value of "key" in a one-line JSON object: a string's contents, or a
// bare value as the text holds it ("<missing>" when absent).
std::string json_value(const std::string& json, const std::string& key) {
  std::smatch m;
  if (std::regex_search(json, m, std::regex("\"" + key + "\": \"([^\"]*)\""))) return m[1];
  if (std::regex_search(json, m, std::regex("\"" + key + "\": ([^,}]*)"))) return m[1];
  return "<missing>";
}

// simulate answers its frames on the placed bodies, building no M for a
// turn: for every frame of a robot that turns, the status and the exact
// squared distance or squared depth equal those of `query` on M of the
// turned robot (ROBOT@rot:A,B,C,D with the frame's rotation) at the frame's
// translation, which is how simulate answered before.  The first pass
// grazes the obstacle (a touching frame, none penetrating: the grazing
// height is exact), the second goes through it; only the touching frame
// needs M (certificate exact).
TEST(ProximityCli, SimulateFramesEqualTheQueryOnMOfTheTurnedRobot) {
  struct Case {
    std::string args, robot, obstacle;
    int frames;
  };
  const Case cases[] = {
      {"--frames 12", "cube@scale:1/2", "dodecahedron@scale:2", 12},
      {"--frames 10 --robot tetra@scale:2/3 --obstacle octahedron@scale:3/2 --turn 3,1,2,5", "tetra@scale:2/3",
       "octahedron@scale:3/2", 10},
      {"--frames 9 --robot random:12:5 --obstacle random:20:8 --turn 7,2,-1,3", "random:12:5", "random:20:8", 9},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("simulate " + c.args);
    const CmdResult r = run("simulate " + c.args + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream lines(r.out);
    int n = 0, turned = 0, touching_pass1 = 0, penetrating_pass1 = 0, penetrating_pass2 = 0;
    for (std::string line; std::getline(lines, line); ++n) {
      SCOPED_TRACE(line);
      const std::string status = json_value(line, "status");
      const bool deep = status == "penetrating";
      const std::string key = deep ? "squared_depth" : "squared_distance";
      const std::string rotation = json_value(line, "rotation");
      std::smatch t;
      ASSERT_TRUE(std::regex_search(line, t, std::regex("\"translation\": \\[\"([^\"]*)\", \"([^\"]*)\", \"([^\"]*)\"\\]")));
      const CmdResult q = run(std::string("query ") + (deep ? "depth " : "distance ") + c.robot + "@rot:" + rotation +
                              " " + c.obstacle + " --translate-p " + std::string(t[1]) + "," + std::string(t[2]) +
                              "," + std::string(t[3]) + " --json");
      ASSERT_EQ(q.status, 0) << q.err;
      EXPECT_EQ(status, json_value(q.out, "status")) << q.out;
      EXPECT_EQ(json_value(line, key), json_value(q.out, key)) << q.out;
      // Touching frames (the grazing one) are proved by the feature plane:
      // no frame builds M.
      EXPECT_EQ(json_value(line, "certificate") == "feature_plane", status == "touching");
      EXPECT_EQ(json_value(line, "rebuilt"), "false");
      EXPECT_EQ(json_value(line, "build_seconds"), "0");
      turned += rotation != "1,0,0,0";
      const bool pass1 = n < c.frames / 2;
      touching_pass1 += pass1 && status == "touching";
      penetrating_pass1 += pass1 && deep;
      penetrating_pass2 += !pass1 && deep;
    }
    EXPECT_EQ(n, c.frames);
    EXPECT_GE(turned, c.frames - 2);
    EXPECT_GE(touching_pass1, 1);
    EXPECT_EQ(penetrating_pass1, 0);
    EXPECT_GE(penetrating_pass2, 1);
  }
  const CmdResult text = run("simulate --frames 12");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_TRUE(has(text.out, "12 frames, ")) << text.out;
  EXPECT_TRUE(has(text.out, " µs per query, 12 certified without M, 0 on M built exactly for the pose\n")) << text.out;
  EXPECT_TRUE(has(text.out, "(robot turned)")) << text.out;
  EXPECT_FALSE(has(text.out, "recomputed")) << text.out;
}

// A first pass whose lines of translations lie in the boundary of S (cube
// against a half-size cube, not turned, frames at x = ±3/2): no probe on such
// a line can penetrate, so its top is read off the section of M of that
// orientation; the height, and every frame, equal the answers on M.
TEST(ProximityCli, SimulateGrazingHeightOnALineInTheBoundaryOfS) {
  const std::string args = "--frames 10 --obstacle cube --robot cube@scale:1/2 --turn 1,0,0,0";
  const CmdResult r = run("simulate " + args + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  int n = 0, touching = 0;
  for (std::string line; std::getline(lines, line); ++n) {
    SCOPED_TRACE(line);
    const std::string status = json_value(line, "status");
    const std::string key = status == "penetrating" ? "squared_depth" : "squared_distance";
    std::smatch t;
    ASSERT_TRUE(std::regex_search(line, t, std::regex("\"translation\": \\[\"([^\"]*)\", \"([^\"]*)\", \"([^\"]*)\"\\]")));
    const CmdResult q = run(std::string("query ") + (status == "penetrating" ? "depth" : "distance") +
                            " cube@scale:1/2 cube --translate-p " + std::string(t[1]) + "," + std::string(t[2]) + "," +
                            std::string(t[3]) + " --json");
    EXPECT_EQ(status, json_value(q.out, "status")) << q.out;
    EXPECT_EQ(json_value(line, key), json_value(q.out, key)) << q.out;
    if (n < 5) {
      EXPECT_EQ(std::string(t[2]), "3/2");  // the height: the top face of the obstacle plus 1/2
    }
    touching += status == "touching";
  }
  EXPECT_EQ(n, 10);
  EXPECT_EQ(touching, 5);
  const CmdResult text = run("simulate " + args);
  EXPECT_TRUE(has(text.out, "; the grazing height read off M of 2 orientations\n")) << text.out;
}

// The trail picture was titled "side view" but showed the x-y plane, had no
// legend but a line of text, and its lower part was an empty band: now a top
// view, a legend with the four colours, and the picture cut to what is drawn
// (every side of the view box within 3 units of a drawn point).
TEST(ProximityCli, SimulatePictureIsATopViewWithALegendAndNoEmptyBand) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sim_view_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "trail.svg").string();
  ASSERT_EQ(run("simulate --frames 12 -o " + out).status, 0);
  std::ifstream f(out);
  std::string svg((std::istreambuf_iterator<char>(f)), {});
  EXPECT_FALSE(has(svg, "side view"));
  EXPECT_TRUE(has(svg, "top view"));
  for (const char* label : {"obstacle Q", "robot P separate", "touching", "penetrating"})
    EXPECT_TRUE(has(svg, std::string(">") + label + "<")) << label;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("viewBox=\"([-0-9.e]+) ([-0-9.e]+) ([0-9.e]+) ([0-9.e]+)\"")));
  const double left = std::stod(m[1]), top = std::stod(m[2]), right = left + std::stod(m[3]), bottom = top + std::stod(m[4]);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const std::regex point("(-?[0-9.e]+),(-?[0-9.e]+) ");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), point); it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  ASSERT_LT(x0, x1);
  EXPECT_LE(x0 - left, 3.0);
  EXPECT_LE(right - x1, 3.0);
  EXPECT_LE(y0 - top, 3.0);
  EXPECT_LE(bottom - y1, 3.0);
  fs::remove_all(dir);
}

}  // namespace
