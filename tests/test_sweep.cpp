// Sweeps: points, segments and flat convex polygons as operands
// (docs/sweeps.md).  The sets themselves (validation, hulls of any
// dimension), the catalog's names, files, the sums against the chms oracle
// and closed forms (volume of a sweep, independent 2D sums), and the command.
#include <gtest/gtest.h>

#include "shell.hpp"

#include <minksum/catalog.hpp>
#include <minksum/convex_set.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/operand.hpp>
#include <minksum/sweep.hpp>
#include <minksum/sweep_proximity.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace minksum;
using minksum::testing::P;

namespace {

ConvexSet cat(const std::string& spec) { return catalog_convex_set(spec); }

// vol(A ⊕ [0, d]) = vol(A) + (area of A's projection along d) · |d|
// = vol(A) + Σ over facets f with N_f·d > 0 of N_f·d, where N_f is the
// facet's area vector (½ Σ v_i × v_{i+1}): exact, no square root.
Rational sweep_volume(const ConvexPolytope& a, const Point3& d) {
  Rational extra(0);
  for (Index f = 0; f < a.num_facets(); ++f) {
    const std::vector<Index> loop = a.facet_vertices(f);
    Point3 n(Rational(0), Rational(0), Rational(0));
    for (std::size_t i = 0; i < loop.size(); ++i) n = n + cross(a.point(loop[i]), a.point(loop[(i + 1) % loop.size()]));
    const Rational s = dot(n, d) / 2;
    if (sgn(s) > 0) extra += s;
  }
  return a.volume() + extra;
}

// The 2D Minkowski sum of two convex polygons of the plane z = c1, z = c2
// (vertices counter-clockwise seen from +z), by merging their edges in
// angular order from their lowest vertices — independent of the hull.
std::vector<Point3> sum_2d(std::vector<Point3> a, std::vector<Point3> b) {
  auto lowest_first = [](std::vector<Point3>& p) {
    auto lower = [](const Point3& u, const Point3& v) {
      const int c = cmp(u.y, v.y);
      return c != 0 ? c < 0 : cmp(u.x, v.x) < 0;
    };
    std::rotate(p.begin(), std::min_element(p.begin(), p.end(), lower), p.end());
  };
  lowest_first(a);
  lowest_first(b);
  auto edge = [](const std::vector<Point3>& p, std::size_t i) { return p[(i + 1) % p.size()] - p[i % p.size()]; };
  std::vector<Point3> out;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    out.push_back(a[i % a.size()] + b[j % b.size()]);
    const Point3 ea = edge(a, i), eb = edge(b, j);
    const int turn = sgn(ea.x * eb.y - ea.y * eb.x);
    if (j == b.size() || (i < a.size() && turn > 0)) ++i;
    else if (i == a.size() || turn < 0) ++j;
    else ++i, ++j;
  }
  // Points in the middle of an edge (parallel edges of the two) go.
  std::vector<Point3> strict;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Point3 &p = out[(k + out.size() - 1) % out.size()], &q = out[k], &r = out[(k + 1) % out.size()];
    if (sgn((q.x - p.x) * (r.y - q.y) - (q.y - p.y) * (r.x - q.x)) != 0) strict.push_back(q);
  }
  return strict;
}

std::string describe(const ConvexSet& s) {
  std::ostringstream o;
  o << dimension_name(s.dimension()) << " with " << s.num_vertices() << " vertices:";
  for (const Point3& p : s.vertices()) o << " (" << p.x << ", " << p.y << ", " << p.z << ")";
  return o.str();
}

// The walk's sweep and the chms oracle give the same set.
void expect_walk_equals_chms(const ConvexSet& a, const ConvexSet& b, const std::string& what) {
  const SetSumResult w = minkowski_sum_sets(a, b, Method::walk);
  const SetSumResult c = minkowski_sum_sets(a, b, Method::chms);
  EXPECT_TRUE(same_set(w.set, c.set)) << what << "\n walk: " << describe(w.set) << "\n chms: " << describe(c.set);
  if (w.set.full()) {
    EXPECT_EQ(w.set.polytope().check_invariants(), "") << what;
  }
  // Commutative.
  const SetSumResult r = minkowski_sum_sets(b, a, Method::walk);
  EXPECT_TRUE(same_set(w.set, r.set)) << what << " (reversed)";
}

Point3 random_point(std::mt19937_64& rng, long range) {
  std::uniform_int_distribution<long> d(-range, range);
  return P(d(rng), d(rng), d(rng));
}

}  // namespace

// ---------------------------------------------------------------------------
// The sets.

TEST(ConvexSet, HullFindsTheDimensionThePointsSpan) {
  EXPECT_EQ(ConvexSet::hull(std::vector<Point3>{P(1, 2, 3), P(1, 2, 3)}).dimension(), 0);
  const ConvexSet seg = ConvexSet::hull(std::vector<Point3>{P(1, 1, 1), P(3, 3, 3), P(0, 0, 0), P(2, 2, 2)});
  ASSERT_EQ(seg.dimension(), 1);
  EXPECT_TRUE(same_set(seg, ConvexSet::segment(P(0, 0, 0), P(3, 3, 3))));
  // A square with its centre and the middles of two edges: 4 vertices.
  const ConvexSet sq = ConvexSet::hull(std::vector<Point3>{P(0, 0, 5), P(2, 0, 5), P(2, 2, 5), P(0, 2, 5), P(1, 1, 5), P(1, 0, 5), P(0, 1, 5)});
  ASSERT_EQ(sq.dimension(), 2);
  EXPECT_EQ(sq.num_vertices(), 4u);
  EXPECT_EQ(sq.area_squared(), Rational(16));
  EXPECT_EQ(ConvexSet::hull(std::vector<Point3>{P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(0, 0, 1)}).dimension(), 3);
  EXPECT_THROW(ConvexSet::hull(std::vector<Point3>{}), InputError);
}

TEST(ConvexSet, PolygonIsValidatedExactly) {
  // Welded duplicates and a point in the middle of an edge.
  const ConvexSet p = ConvexSet::polygon({P(0, 0, 0), P(1, 0, 0), P(2, 0, 0), P(2, 0, 0), P(2, 2, 0), P(0, 2, 0)});
  EXPECT_EQ(p.num_vertices(), 4u);
  EXPECT_EQ(p.area_squared(), Rational(16));
  // Clockwise loops are polygons too.
  EXPECT_EQ(ConvexSet::polygon({P(0, 2, 0), P(2, 2, 0), P(2, 0, 0), P(0, 0, 0)}).num_vertices(), 4u);
  // Not planar, reflex, winding twice (a pentagram), collinear, spiking back.
  EXPECT_THROW(ConvexSet::polygon({P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 1)}), InputError);
  EXPECT_THROW(ConvexSet::polygon({P(0, 0, 0), P(4, 0, 0), P(2, 1, 0), P(2, 4, 0)}), InputError);
  EXPECT_THROW(ConvexSet::polygon({P(0, 10, 0), P(6, -8, 0), P(-10, 3, 0), P(10, 3, 0), P(-6, -8, 0)}), InputError);
  EXPECT_THROW(ConvexSet::polygon({P(0, 0, 0), P(1, 1, 1), P(2, 2, 2)}), InputError);
  EXPECT_THROW(ConvexSet::polygon({P(0, 0, 0), P(2, 0, 0), P(1, 0, 0), P(1, 1, 0)}), InputError);
}

TEST(ConvexSet, ZeroLengthSegmentIsRefused) {
  EXPECT_THROW(ConvexSet::segment(P(1, 2, 3), P(1, 2, 3), "s"), InputError);
  EXPECT_THROW(cat("segment:1,2,3:1,2,3"), UsageError);
  EXPECT_THROW(cat("segment:0,0,0:1,1,1@scale:0"), UsageError);  // scale must be > 0 anyway
}

TEST(ConvexSet, CatalogNames) {
  const ConvexSet pt = cat("point:1,2,3@translate:1,1,1");
  ASSERT_EQ(pt.dimension(), 0);
  EXPECT_EQ(pt.vertices()[0], P(2, 3, 4));
  const ConvexSet seg = cat("segment:0,0,0:1,0,0@rot:1,2,3,4");
  ASSERT_EQ(seg.dimension(), 1);
  EXPECT_EQ(dot(seg.vertices()[1] - seg.vertices()[0], seg.vertices()[1] - seg.vertices()[0]), Rational(1));
  const ConvexSet sq = cat("square");
  ASSERT_EQ(sq.dimension(), 2);
  EXPECT_EQ(sq.area_squared(), Rational(1));
  EXPECT_EQ(sgn(sq.normal().z), 1);
  for (int n : {3, 5, 12, 1000}) {
    const ConvexSet g = cat("polygon:" + std::to_string(n));
    ASSERT_EQ(g.dimension(), 2) << n;
    EXPECT_EQ(g.num_vertices(), Index(n));
    EXPECT_EQ(g.num_edges(), Index(n));
    EXPECT_EQ(g.num_facets(), 1u);
  }
  EXPECT_EQ(cat("polygon:6@rot:7@scale:3").dimension(), 2);
  EXPECT_THROW(cat("polygon:2"), UsageError);
  EXPECT_THROW(cat("point:1,2"), UsageError);
  EXPECT_THROW(cat("square:3"), UsageError);
  // Commands that take solids only say so.
  EXPECT_THROW(catalog_polytope("square"), UsageError);
  EXPECT_TRUE(is_catalog_spec("segment:0,0,0:1,1,1"));
  EXPECT_EQ(cat("cube").dimension(), 3);
}

TEST(ConvexSet, FilesWithOneFaceOrLowerDimensionalPoints) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sweep_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string tri = (dir / "tri.off").string(), line = (dir / "line.off").string();
  std::ofstream(tri) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 1\n3 0 1 2\n";
  std::ofstream(line) << "OFF\n3 0 0\n0 0 0\n2 2 2\n1 1 1\n";
  const ConvexSet t = load_convex_set(tri);
  EXPECT_EQ(t.dimension(), 2);
  EXPECT_EQ(t.num_vertices(), 3u);
  const ConvexSet s = load_convex_set(line, true);
  ASSERT_EQ(s.dimension(), 1);
  EXPECT_TRUE(same_set(s, ConvexSet::segment(P(0, 0, 0), P(2, 2, 2))));
  EXPECT_THROW(load_convex_set(line), InputError);  // no faces, no --hull
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------
// Sums with a polytope: closed forms and the oracle.

TEST(Sweep, BoxAlongASegmentHasTheClosedFormVolume) {
  // box X×Y×Z ⊕ [0, d]: XYZ + |dx| YZ + |dy| XZ + |dz| XY.
  const ConvexSet box = cat("box:2:3:5");
  std::mt19937_64 rng(20);
  for (int trial = 0; trial < 40; ++trial) {
    Point3 d = random_point(rng, 6);
    if (trial < 3) d = P(trial == 0 ? 4 : 0, trial == 1 ? -3 : 0, trial == 2 ? 7 : 0);  // along an edge: parallel to facets
    if (trial == 3) d = P(1, 1, 0);                                                    // parallel to a facet only
    if (is_zero(d)) continue;
    const ConvexSet seg = ConvexSet::segment(P(1, -2, 3), P(1, -2, 3) + d);
    const SetSumResult r = minkowski_sum_sets(box, seg);
    ASSERT_EQ(r.set.dimension(), 3) << "seed 20 trial " << trial;
    EXPECT_STREQ(r.route, "sweep");
    const Rational expected = Rational(30) + abs(d.x) * 15 + abs(d.y) * 10 + abs(d.z) * 6;
    EXPECT_EQ(r.set.volume(), expected) << "seed 20 trial " << trial << " d " << d.x << "," << d.y << "," << d.z;
    EXPECT_EQ(r.set.volume(), sweep_volume(box.polytope(), d)) << "seed 20 trial " << trial;
  }
}

TEST(Sweep, SegmentsAgainstChmsAndTheProjectionFormula) {
  const std::uint64_t seed = 2026;
  std::mt19937_64 rng(seed);
  const char* solids[] = {"cube", "tetra", "octahedron", "icosahedron", "cuboctahedron@rot:3", "sphere:2",
                          "random:40:5", "dioctagonal:9", "zonotope:4:1", "truncated-octahedron"};
  for (const char* name : solids) {
    const ConvexSet a = cat(name);
    for (int trial = 0; trial < 6; ++trial) {
      Point3 d = random_point(rng, 5);
      if (is_zero(d)) continue;
      const ConvexSet seg = ConvexSet::segment(random_point(rng, 3), random_point(rng, 3) + d);
      const Point3 dir = seg.vertices()[1] - seg.vertices()[0];
      const std::string what = std::string(name) + " seed " + std::to_string(seed) + " trial " + std::to_string(trial);
      expect_walk_equals_chms(a, seg, what);
      EXPECT_EQ(minkowski_sum_sets(a, seg).set.volume(), sweep_volume(a.polytope(), dir)) << what;
    }
    // Along every edge of the solid (parallel to an edge and to its facets).
    const ConvexPolytope& p = a.polytope();
    for (Index e = 0; e < std::min<Index>(p.num_edges(), 12); ++e) {
      const Point3 d = p.point(p.target(2 * e)) - p.point(p.origin(2 * e));
      const ConvexSet seg = ConvexSet::segment(P(0, 0, 0), d);
      const std::string what = std::string(name) + " along edge " + std::to_string(e);
      expect_walk_equals_chms(a, seg, what);
      EXPECT_EQ(minkowski_sum_sets(a, seg).set.volume(), sweep_volume(p, d)) << what;
    }
  }
}

TEST(Sweep, PolygonsAgainstChms) {
  const std::uint64_t seed = 77;
  std::mt19937_64 rng(seed);
  const char* solids[] = {"cube", "tetra", "dodecahedron", "sphere:2", "random:30:2@rot:4", "box:1:2:3"};
  const char* polygons[] = {"square", "polygon:3", "polygon:7@rot:9", "square@rot:1,1,0,0", "polygon:5@scale:1/3,2,1",
                            // coplanar with the cube's top facet, and inside it
                            "square@scale:2@translate:0,0,1", "square@translate:0,0,1"};
  for (const char* s : solids)
    for (const char* g : polygons) expect_walk_equals_chms(cat(s), cat(g), std::string(s) + " ⊕ " + g);
  // Random triangles (fixed seed), some in a plane of the cube's facets.
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Point3> t{random_point(rng, 4), random_point(rng, 4), random_point(rng, 4)};
    if (trial % 4 == 0)
      for (Point3& p : t) p.z = 1;
    if (is_zero(cross(t[1] - t[0], t[2] - t[0]))) continue;
    expect_walk_equals_chms(cat("cube"), ConvexSet::polygon(t), "cube ⊕ triangle, seed 77 trial " + std::to_string(trial));
  }
}

TEST(Sweep, PointIsATranslation) {
  const SetSumResult r = minkowski_sum_sets(cat("icosahedron"), cat("point:1/3,2,-5"));
  EXPECT_STREQ(r.route, "translation");
  EXPECT_TRUE(same_set(r.set, ConvexSet(catalog_polytope("icosahedron@translate:1/3,2,-5"))));
  expect_walk_equals_chms(cat("icosahedron"), cat("point:1/3,2,-5"), "icosahedron ⊕ point");
}

TEST(Sweep, PrismVolumeOfAPolygonSweptOutOfItsPlane) {
  // square (area 1, z = 0) ⊕ segment (0,0,0)-(1,2,3): a prism of volume 1 · 3.
  const SetSumResult r = minkowski_sum_sets(cat("square"), cat("segment:0,0,0:1,2,3"));
  ASSERT_EQ(r.set.dimension(), 3);
  EXPECT_EQ(r.set.volume(), Rational(3));
  EXPECT_EQ(r.set.num_vertices(), 8u);
}

// ---------------------------------------------------------------------------
// Lower-dimensional ⊕ lower-dimensional.

TEST(Sweep, SegmentPlusSegment) {
  // Skew directions: a parallelogram of area |d1 × d2|.
  const SetSumResult par = minkowski_sum_sets(cat("segment:0,0,0:1,2,3"), cat("segment:5,5,5:4,7,5"));
  ASSERT_EQ(par.set.dimension(), 2);
  EXPECT_EQ(par.set.num_vertices(), 4u);
  const Point3 c = cross(P(1, 2, 3), P(-1, 2, 0));
  EXPECT_EQ(par.set.area_squared(), dot(c, c));
  // Collinear: a segment, the ends summed.
  const SetSumResult col = minkowski_sum_sets(cat("segment:0,0,0:1,1,1"), cat("segment:3,3,3:1,1,1"));
  ASSERT_EQ(col.set.dimension(), 1);
  EXPECT_TRUE(same_set(col.set, ConvexSet::segment(P(1, 1, 1), P(4, 4, 4))));
  // Three independent segments: a parallelepiped of volume |det|.
  const SetSumResult box = minkowski_sum_sets(par.set, cat("segment:0,0,0:0,1,7"));
  ASSERT_EQ(box.set.dimension(), 3);
  EXPECT_EQ(box.set.volume(), abs(dot(c, P(0, 1, 7))));
  expect_walk_equals_chms(cat("segment:0,0,0:1,2,3"), cat("segment:5,5,5:4,7,5"), "skew segments");
  // A point and a segment.
  EXPECT_EQ(minkowski_sum_sets(cat("point:1,1,1"), cat("segment:0,0,0:0,0,1")).set.dimension(), 1);
  EXPECT_EQ(minkowski_sum_sets(cat("point:1,1,1"), cat("point:2,2,2")).set.vertices()[0], P(3, 3, 3));
}

TEST(Sweep, PolygonsInOnePlaneEqualTheIndependent2DSum) {
  const std::uint64_t seed = 4242;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Point3> pa, pb;
    for (int i = 0; i < 7; ++i) pa.push_back(random_point(rng, 9));
    for (int i = 0; i < 5; ++i) pb.push_back(random_point(rng, 9));
    for (Point3& p : pa) p.z = 2;
    for (Point3& p : pb) p.z = -1;
    const ConvexSet a = ConvexSet::hull(pa), b = ConvexSet::hull(pb);
    if (a.dimension() != 2 || b.dimension() != 2) continue;
    // Counter-clockwise seen from +z, as sum_2d wants.
    auto ccw = [](const ConvexSet& s) {
      std::vector<Point3> v = s.vertices();
      if (sgn(s.normal().z) < 0) std::reverse(v.begin(), v.end());
      return v;
    };
    const ConvexSet expected = ConvexSet::polygon(sum_2d(ccw(a), ccw(b)));
    const SetSumResult r = minkowski_sum_sets(a, b);
    EXPECT_TRUE(same_set(r.set, expected)) << "seed 4242 trial " << trial << "\n got " << describe(r.set)
                                           << "\n 2D sum " << describe(expected);
    EXPECT_TRUE(same_set(minkowski_sum_sets(a, b, Method::chms).set, expected)) << "seed 4242 trial " << trial;
  }
  // Regular polygons: square ⊕ square is the square scaled by 2; polygon:6 ⊕
  // itself the hexagon scaled by 2 (exact doubles times 2).
  EXPECT_TRUE(same_set(minkowski_sum_sets(cat("square"), cat("square")).set, cat("square@scale:2")));
  EXPECT_TRUE(same_set(minkowski_sum_sets(cat("polygon:6"), cat("polygon:6")).set, cat("polygon:6@scale:2")));
  // Rotated into another plane, still a polygon.
  EXPECT_EQ(minkowski_sum_sets(cat("polygon:5@rot:3"), cat("square@rot:3")).set.dimension(), 2);
  // Non-parallel planes: a polytope.
  const SetSumResult cross_planes = minkowski_sum_sets(cat("square"), cat("square@rot:1,1,0,0"));
  EXPECT_EQ(cross_planes.set.dimension(), 3);
  expect_walk_equals_chms(cat("square"), cat("square@rot:1,1,0,0"), "square ⊕ square in a perpendicular plane");
}

TEST(Sweep, OtherMethodsRefuseLowerDimensionalOperandsNamingWalk) {
  for (Method m : {Method::cvms, Method::essdms, Method::mssd, Method::cgm}) {
    try {
      minkowski_sum_sets(cat("cube"), cat("segment:0,0,0:1,1,1"), m);
      ADD_FAILURE() << method_name(m) << " accepted a segment";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("'walk'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("segment"), std::string::npos) << e.what();
    }
  }
  // Two polytopes still go to the method asked for.
  EXPECT_EQ(minkowski_sum_sets(cat("cube"), cat("tetra"), Method::cvms).method, Method::cvms);
}

// ---------------------------------------------------------------------------
// Proximity: M = P ⊕ (−Q) with a lower-dimensional operand.

namespace {
// Where the segment a + t (b − a), 0 <= t <= 1, meets the cube [-1, 1]^3,
// clipped exactly coordinate by coordinate (independent of M): penetrating
// when some t has every |x_i| < 1, touching when only |x_i| <= 1 holds.
ContactStatus segment_and_cube(const Point3& a, const Point3& b) {
  auto meets = [&](bool strict) {
    Rational lo(0), hi(1);
    bool lo_open = false, hi_open = false;
    for (int i = 0; i < 3; ++i) {
      const Rational d = b[i] - a[i];
      if (sgn(d) == 0) {
        const int c = cmp(abs(a[i]), Rational(1));
        if (c > 0 || (strict && c == 0)) return false;
        continue;
      }
      Rational t1 = (Rational(-1) - a[i]) / d, t2 = (Rational(1) - a[i]) / d;
      if (cmp(t1, t2) > 0) std::swap(t1, t2);
      if (cmp(t1, lo) > 0 || (cmp(t1, lo) == 0 && strict)) lo = t1, lo_open = lo_open || strict;
      if (cmp(t2, hi) < 0 || (cmp(t2, hi) == 0 && strict)) hi = t2, hi_open = hi_open || strict;
    }
    const int c = cmp(lo, hi);
    return c < 0 || (c == 0 && !lo_open && !hi_open);
  };
  if (meets(true)) return ContactStatus::penetrating;
  return meets(false) ? ContactStatus::touching : ContactStatus::separate;
}
}  // namespace

TEST(SweepProximity, SegmentAgainstACubeInClosedForm) {
  const ConvexSet cube = cat("cube");  // [-1, 1]^3
  const Point3 o = P(0, 0, 0);
  // Beside the cube: distance 2.
  const SetObstacle beside(cube, cat("segment:3,0,0:3,5,0"));
  EXPECT_EQ(beside.contact(o), ContactStatus::separate);
  EXPECT_EQ(beside.squared_distance(o), Rational(4));
  // Through it: M = [-6, 6] x [-1, 1]^2, depth 1, along z t = 1.
  const SetObstacle through(cube, cat("segment:-5,0,0:5,0,0"));
  EXPECT_EQ(through.contact(o), ContactStatus::penetrating);
  EXPECT_EQ(through.squared_distance(o), Rational(0));
  EXPECT_EQ(through.squared_depth(o), Rational(1));
  EXPECT_EQ(through.directional_depth(o, P(0, 0, 2)), Rational(1, 2));
  // Lying on the face x = 1: touching; P moved by u = (-1/2, 0, 0): 1/4 apart.
  const SetObstacle on(cube, cat("segment:1,-3,0:1,3,0"));
  EXPECT_EQ(on.contact(o), ContactStatus::touching);
  EXPECT_EQ(on.squared_distance(P(0, 0, 0) - Point3(Rational(-1, 2), Rational(0), Rational(0))), Rational(1, 4));
  // Two segments: skew at distance 1, crossing (touching: M is a polygon).
  const SetObstacle skew(cat("segment:0,0,0:1,0,0"), cat("segment:0,1,1:0,1,-1"));
  EXPECT_EQ(skew.obstacle().dimension(), 2);
  EXPECT_EQ(skew.squared_distance(o), Rational(1));
  EXPECT_EQ(skew.contact(o), ContactStatus::separate);
  EXPECT_EQ(SetObstacle(cat("segment:0,0,0:1,0,0"), cat("segment:1/2,0,-1:1/2,0,1")).contact(o),
            ContactStatus::touching);
  // A point: the distance to P.
  EXPECT_EQ(SetObstacle(cube, cat("point:2,2,0")).squared_distance(o), Rational(2));
}

TEST(SweepProximity, DoesTheCubeMeetTheSegmentRandomAndDegenerate) {
  const std::uint64_t seed = 31;
  std::mt19937_64 rng(seed);
  const ConvexSet cube = cat("cube");
  for (int trial = 0; trial < 200; ++trial) {
    // Small integer ends: many segments through edges, along faces, ending on them.
    Point3 a = random_point(rng, 3), b = random_point(rng, 3);
    if (a == b) continue;
    const SetObstacle ob(cube, ConvexSet::segment(a, b));
    EXPECT_EQ(ob.contact(P(0, 0, 0)), segment_and_cube(a, b))
        << "seed 31 trial " << trial << ": " << describe(ConvexSet::segment(a, b));
  }
}

TEST(SweepProximity, ScansAgreeWithTheObstacleOnPolytopes) {
  const std::uint64_t seed = 5;
  std::mt19937_64 rng(seed);
  const ConvexPolytope p = catalog_polytope("icosahedron"), q = catalog_polytope("cuboctahedron@rot:2");
  TranslationalObstacle ob(p, q);
  const SetObstacle sets{ConvexSet(p), ConvexSet(q)};
  for (int trial = 0; trial < 60; ++trial) {
    const Point3 s = (trial % 3 == 0 ? Rational(1) : Rational(1, 2)) * random_point(rng, 4);
    const std::string at = "seed 5 trial " + std::to_string(trial);
    EXPECT_EQ(sets.contact(s), ob.collide_point(s).status) << at;
    EXPECT_EQ(sets.squared_distance(s), ob.distance_point(s).squared_distance()) << at;
    EXPECT_EQ(sets.squared_depth(s), ob.penetration_depth_point(s).squared_depth()) << at;
    EXPECT_EQ(sets.directional_depth(s, P(1, 2, 3)), ob.directional_depth_point(s, P(1, 2, 3)).t) << at;
  }
}

// ---------------------------------------------------------------------------
// The command.

namespace {
struct CmdRun {
  int status = -1;
  std::string out, err;
};
CmdRun run(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("minksum_sweep_err_" + std::to_string(::getpid()));
  CmdRun r;
  const ShellOutput o = shell_stdout(std::string(MINKSUM_BIN) + " " + args + " </dev/null 2>" + err.string());
  r.status = o.status;
  r.out = o.out;
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  r.err = s.str();
  fs::remove(err);
  return r;
}
long json_int(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9]+)"))) return -100;
  return std::stol(m[1]);
}
std::size_t lines(const std::string& s) { return std::size_t(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

TEST(SweepCli, JsonReportsTheDimension) {
  CmdRun r = run("sum box:2:3:5 segment:0,0,0:1,1,1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 3);
  EXPECT_NE(r.out.find("\"volume\": \"61\""), std::string::npos) << r.out;  // 30 + 15 + 10 + 6
  EXPECT_NE(r.out.find("\"route\": \"sweep\""), std::string::npos) << r.out;
  r = run("sum square polygon:4 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 2);
  EXPECT_NE(r.out.find("\"kind\": \"polygon\""), std::string::npos) << r.out;
  r = run("sum segment:0,0,0:1,0,0 segment:0,0,0:2,0,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 1);
  r = run("sum cube tetra --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 3);
  // Three operands, left to right: square ⊕ segment ⊕ point.
  r = run("sum square segment:0,0,0:0,0,2 point:1,1,1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"volume\": \"2\""), std::string::npos) << r.out;
}

TEST(SweepCli, ResultsAreWrittenAndReadBack) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sweep_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string flat = (dir / "flat.off").string(), seg = (dir / "seg.off").string(),
                    solid = (dir / "solid.obj").string(), stl = (dir / "flat.stl").string();
  ASSERT_EQ(run("sum square square -o " + flat).status, 0);
  CmdRun r = run("sum " + flat + " point:0,0,0 --json");  // one face: read back as the polygon
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 2);
  EXPECT_EQ(json_int(r.out, "vertices"), 4);
  ASSERT_EQ(run("sum segment:0,0,0:1,1,1 point:1,0,0 -o " + seg).status, 0);
  r = run("sum " + seg + " point:0,0,0 --hull --json");  // points without faces: --hull
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 1);
  ASSERT_EQ(run("sum cube segment:0,0,0:1,2,3 -o " + solid).status, 0);
  r = run("stats " + solid + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const Rational v = minkowski_sum_sets(cat("cube"), cat("segment:0,0,0:1,2,3")).set.volume();
  EXPECT_NE(r.out.find("\"volume\": \"" + format_exact(v) + "\""), std::string::npos) << r.out;
  // STL cannot hold a polygon: exit 1, one line, nothing written.
  r = run("sum square square -o " + stl);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_FALSE(fs::exists(stl));
  // Non-double coordinates of a polygon are never rounded: --exact.
  r = run("sum square@scale:1/3 square -o " + flat);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--exact"), std::string::npos) << r.err;
  EXPECT_EQ(run("sum square@scale:1/3 square --exact -o " + flat).status, 0);
  fs::remove_all(dir);
}

TEST(SweepCli, ErrorsAndExitStatuses) {
  CmdRun r = run("sum cube segment:0,0,0:1,1,1 --method cvms");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'walk'"), std::string::npos) << r.err;
  r = run("sum cube segment:1,1,1:1,1,1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("zero-length"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  r = run("stats square");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("not a solid"), std::string::npos) << r.err;
  // A file with one face that is not convex: exit 3, one line naming it.
  const fs::path bad = fs::temp_directory_path() / ("minksum_sweep_bad_" + std::to_string(::getpid()) + ".off");
  std::ofstream(bad) << "OFF\n4 1 0\n0 0 0\n4 0 0\n2 1 0\n2 4 0\n4 0 1 2 3\n";
  r = run("sum cube " + bad.string());
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
  fs::remove(bad);
}

// minksum view: a polygon is drawn as its loop and the reversed loop with
// opposite planes (a face seen from both sides), a segment as its edge.
TEST(SweepCli, ViewShowsAPolygonFromBothSides) {
  const fs::path page = fs::temp_directory_path() / ("minksum_sweep_view_" + std::to_string(::getpid()) + ".html");
  CmdRun r = run("view square polygon:4@rot:1,0,0,1 -o " + page.string() + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 2) << r.out;
  std::ifstream in(page);
  std::stringstream s;
  s << in.rdbuf();
  const std::string html = s.str();
  // The square [-1/2, 1/2]^2 at z = 0: its two sides z = 0 and -z = 0.
  EXPECT_NE(html.find("\"facets\": [[0,1,2,3],[3,2,1,0]], \"planes\": [\"0 0 1 0\",\"0 0 -1 0\"]"), std::string::npos);
  r = run("view cube segment:0,0,0:1,2,3 -o " + page.string() + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 3) << r.out;
  std::ifstream in2(page);
  std::stringstream s2;
  s2 << in2.rdbuf();
  EXPECT_NE(s2.str().find("\"facets\": [[0,1,0]]"), std::string::npos);
  fs::remove(page);
}

// 'view point:X,Y,Z --json' named the kind twice (one object, one key each).
TEST(SweepCli, ViewJsonOfAPointHasEachKeyOnce) {
  const fs::path page = fs::temp_directory_path() / ("minksum_sweep_point_" + std::to_string(::getpid()) + ".html");
  CmdRun r = run("view point:1,2,3 -o " + page.string() + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 0) << r.out;
  for (const char* key : {"\"kind\"", "\"name\"", "\"vertices\"", "\"output\""}) {
    const std::size_t first = r.out.find(key);
    EXPECT_NE(first, std::string::npos) << key << " in " << r.out;
    EXPECT_EQ(r.out.find(key, first + 1), std::string::npos) << key << " twice in " << r.out;
  }
  EXPECT_NE(r.out.find("\"kind\": \"point\""), std::string::npos) << r.out;
  fs::remove(page);
}

// minksum gen writes a polygon as one face and a segment as its two points;
// both read back as what they were.
TEST(SweepCli, QueryWithASegment) {
  CmdRun r = run("query distance cube segment:3,0,0:3,5,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"squared_distance\": \"4\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"status\": \"separate\""), std::string::npos) << r.out;
  r = run("query collide cube segment:-5,0,0:5,0,0 --translate-p 0,0,1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("touching", 0), 0u) << r.out;
  r = run("query ddepth cube segment:-5,0,0:5,0,0 --direction 0,0,1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"t\": \"1\""), std::string::npos) << r.out;
  r = run("query collide cube segment:-5,0,0:5,0,0 --rotate-p 1,1,0,0");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
}

TEST(SweepCli, GenWritesLowerDimensionalSets) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sweep_gen_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string poly = (dir / "hex.obj").string(), seg = (dir / "seg.ply").string();
  CmdRun r = run("gen polygon:6 -o " + poly);
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("sum " + poly + " point:0,0,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 2);
  EXPECT_EQ(json_int(r.out, "vertices"), 6);
  r = run("gen segment:0,0,0:1,2,3 -o " + seg);
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("sum " + seg + " point:0,0,0 --hull --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "dimension"), 1);
  r = run("gen segment:0,0,0:1,2,3@rot:5 -o " + seg);  // rational coordinates: --exact (not in PLY)
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  fs::remove_all(dir);
}
