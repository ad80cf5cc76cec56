// Tests of the catalog of named polytopes: exact counts, exact volumes,
// exact planes, determinism, transforms and spec errors.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/polytope.hpp>

#include "catalog/catalog_internal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace minksum;
namespace cd = minksum::catalog_detail;

namespace minksum {
// Readable failure messages.
void PrintTo(const Point3& p, std::ostream* os) {
  *os << "(" << format_exact(p.x) << ", " << format_exact(p.y) << ", " << format_exact(p.z) << ")";
}
}  // namespace minksum

namespace {

struct Expected {
  const char* name;
  Index v, e, f;
  const char* degrees;  // facet degree histogram "deg:count,..."
};

// Known counts of the Platonic, Archimedean and Catalan solids.
const Expected kSolids[] = {
    {"tetra", 4, 6, 4, "3:4"},
    {"tetrahedron", 4, 6, 4, "3:4"},
    {"cube", 8, 12, 6, "4:6"},
    {"hexahedron", 8, 12, 6, "4:6"},
    {"octahedron", 6, 12, 8, "3:8"},
    {"dodecahedron", 20, 30, 12, "5:12"},
    {"icosahedron", 12, 30, 20, "3:20"},
    {"truncated-tetrahedron", 12, 18, 8, "3:4,6:4"},
    {"cuboctahedron", 12, 24, 14, "3:8,4:6"},
    {"truncated-cube", 24, 36, 14, "3:8,8:6"},
    {"truncated-octahedron", 24, 36, 14, "4:6,6:8"},
    {"rhombicuboctahedron", 24, 48, 26, "3:8,4:18"},
    {"truncated-cuboctahedron", 48, 72, 26, "4:12,6:8,8:6"},
    {"great-rhombicuboctahedron", 48, 72, 26, "4:12,6:8,8:6"},
    {"snub-cube", 24, 60, 38, "3:32,4:6"},
    {"icosidodecahedron", 30, 60, 32, "3:20,5:12"},
    {"truncated-dodecahedron", 60, 90, 32, "3:20,10:12"},
    {"truncated-icosahedron", 60, 90, 32, "5:12,6:20"},
    {"rhombicosidodecahedron", 60, 120, 62, "3:20,4:30,5:12"},
    {"truncated-icosidodecahedron", 120, 180, 62, "4:30,6:20,10:12"},
    {"great-rhombicosidodecahedron", 120, 180, 62, "4:30,6:20,10:12"},
    {"snub-dodecahedron", 60, 150, 92, "3:80,5:12"},
    {"triakis-tetrahedron", 8, 18, 12, "3:12"},
    {"rhombic-dodecahedron", 14, 24, 12, "4:12"},
    {"triakis-octahedron", 14, 36, 24, "3:24"},
    {"tetrakis-hexahedron", 14, 36, 24, "3:24"},
    {"deltoidal-icositetrahedron", 26, 48, 24, "4:24"},
    {"disdyakis-dodecahedron", 26, 72, 48, "3:48"},
    {"pentagonal-icositetrahedron", 38, 60, 24, "5:24"},
    {"rhombic-triacontahedron", 32, 60, 30, "4:30"},
    {"triakis-icosahedron", 32, 90, 60, "3:60"},
    {"pentakis-dodecahedron", 32, 90, 60, "3:60"},
    {"deltoidal-hexecontahedron", 62, 120, 60, "4:60"},
    {"disdyakis-triacontahedron", 62, 180, 120, "3:120"},
    {"pentagonal-hexecontahedron", 92, 150, 60, "5:60"},
};

std::string degree_histogram(const ConvexPolytope& p) {
  std::map<Index, int> h;
  for (Index f = 0; f < p.num_facets(); ++f) ++h[p.facet_degree(f)];
  std::string s;
  for (const auto& [d, n] : h) s += (s.empty() ? "" : ",") + std::to_string(d) + ":" + std::to_string(n);
  return s;
}

std::set<Point3> point_set(const ConvexPolytope& p) { return {p.points().begin(), p.points().end()}; }

void expect_counts(const ConvexPolytope& p, Index v, Index e, Index f, const std::string& what) {
  EXPECT_EQ(p.num_vertices(), v) << what;
  EXPECT_EQ(p.num_edges(), e) << what;
  EXPECT_EQ(p.num_facets(), f) << what;
  EXPECT_EQ(p.check_invariants(), "") << what;
}

std::string usage_error(const std::string& spec) {
  try {
    catalog_polytope(spec);
  } catch (const UsageError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("WRONG EXCEPTION TYPE: ") + e.what();
  }
  return "NO EXCEPTION";
}

}  // namespace

// ---------------------------------------------------------------------------
// Fixed solids.

TEST(CatalogSolids, CountsDegreesAndInvariants) {
  for (const Expected& s : kSolids) {
    SCOPED_TRACE(s.name);
    ASSERT_TRUE(is_catalog_spec(s.name));
    const ConvexPolytope p = catalog_polytope(s.name);
    expect_counts(p, s.v, s.e, s.f, s.name);
    EXPECT_EQ(p.euler_characteristic(), 2);
    EXPECT_EQ(degree_histogram(p), s.degrees);
  }
}

TEST(CatalogSolids, EveryTableEntryIsTestedAndMatchesItsDeclaredCounts) {
  std::set<std::string> tested;
  for (const Expected& s : kSolids) tested.insert(s.name);
  for (const cd::FixedSolid& s : cd::fixed_solids()) {
    EXPECT_TRUE(tested.count(s.name)) << s.name << " has no expected counts in this test";
    for (const std::string& a : s.aliases) EXPECT_TRUE(tested.count(a)) << a;
    const ConvexPolytope p = catalog_polytope(s.name);
    EXPECT_EQ(p.num_vertices(), s.vertices) << s.name;
    EXPECT_EQ(p.num_edges(), s.edges) << s.name;
    EXPECT_EQ(p.num_facets(), s.facets) << s.name;
  }
}

TEST(CatalogSolids, BuildsAreDeterministic) {
  // Same spec, same vertex order and same facet loops (the catalog renumbers
  // hull output canonically).
  for (const char* spec : {"truncated-icosahedron", "snub-dodecahedron", "pentagonal-hexecontahedron",
                           "random:300:5", "zonotope:1,0,0:0,1,0:1,1,0:0,0,1", "cube@rot:3"}) {
    const ConvexPolytope a = catalog_polytope(spec), b = catalog_polytope(spec);
    EXPECT_TRUE(a.points() == b.points()) << spec;
    ASSERT_EQ(a.num_facets(), b.num_facets()) << spec;
    for (Index f = 0; f < a.num_facets(); ++f) EXPECT_EQ(a.facet_vertices(f), b.facet_vertices(f)) << spec;
  }
  // random: vertices in the order the points were drawn.
  const auto pts = cd::random_sphere_points(300, 5);
  const ConvexPolytope r = catalog_polytope("random:300:5");
  ASSERT_EQ(r.num_vertices(), 300u);
  EXPECT_TRUE(r.points() == pts);
}

TEST(CatalogSolids, AliasesGiveTheSameSolid) {
  EXPECT_EQ(point_set(catalog_polytope("tetra")), point_set(catalog_polytope("tetrahedron")));
  EXPECT_EQ(point_set(catalog_polytope("cube")), point_set(catalog_polytope("hexahedron")));
}

TEST(CatalogSolids, CubeHasTheSixExactPlanes) {
  const ConvexPolytope p = catalog_polytope("cube");
  std::set<std::vector<long>> planes;
  for (Index f = 0; f < p.num_facets(); ++f) {
    const Plane& pl = p.plane(f);
    planes.insert({pl.a.get_si(), pl.b.get_si(), pl.c.get_si(), pl.d.get_si()});
  }
  const std::set<std::vector<long>> expected = {{1, 0, 0, 1},  {-1, 0, 0, 1}, {0, 1, 0, 1},
                                                {0, -1, 0, 1}, {0, 0, 1, 1},  {0, 0, -1, 1}};
  EXPECT_EQ(planes, expected);
  for (const Point3& v : p.points())
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(v[i] == 1 || v[i] == -1);
}

TEST(CatalogSolids, ExactVolumes) {
  EXPECT_EQ(catalog_polytope("cube").volume(), Rational(8));
  EXPECT_EQ(catalog_polytope("tetra").volume(), Rational(8, 3));
  EXPECT_EQ(catalog_polytope("octahedron").volume(), Rational(4, 3));
  EXPECT_EQ(catalog_polytope("cuboctahedron").volume(), Rational(20, 3));
  EXPECT_EQ(catalog_polytope("truncated-octahedron").volume(), Rational(32));
  // Dual of the cuboctahedron scaled by its midradius² 3/2: (±3/2, 0, 0) and
  // (±3/4, ±3/4, ±3/4), volume 2·(3/2)³.
  EXPECT_EQ(catalog_polytope("rhombic-dodecahedron").volume(), Rational(27, 4));
  // Truncated cube: the cube [-1,1]^3 minus 8 corner tetrahedra with legs 1 - ξ.
  const Rational xi = Rational(23726566, 1 << 24) - 1;
  const Rational leg = 1 - xi;
  Rational expected = 8 - 8 * leg * leg * leg / 6;
  expected.canonicalize();
  EXPECT_EQ(catalog_polytope("truncated-cube").volume(), expected);
}

TEST(CatalogSolids, TruncatedCubeOctagonsLieInTheCubeFaces) {
  const ConvexPolytope p = catalog_polytope("truncated-cube");
  int octagons = 0;
  for (Index f = 0; f < p.num_facets(); ++f) {
    if (p.facet_degree(f) != 8) continue;
    ++octagons;
    const Plane& pl = p.plane(f);
    EXPECT_EQ(abs(pl.a) + abs(pl.b) + abs(pl.c), 1);
    EXPECT_EQ(pl.d, 1);
  }
  EXPECT_EQ(octagons, 6);
}

TEST(CatalogSolids, CoordinatesAreDoublesWhereDocumented) {
  for (const char* name : {"tetra", "cube", "octahedron", "dodecahedron", "icosahedron", "truncated-tetrahedron",
                           "cuboctahedron", "truncated-cube", "truncated-octahedron", "rhombicuboctahedron",
                           "truncated-cuboctahedron", "snub-cube", "icosidodecahedron", "triakis-icosahedron",
                           "pentakis-dodecahedron", "disdyakis-triacontahedron"})
    EXPECT_TRUE(catalog_polytope(name).coordinates_are_doubles()) << name;
}

TEST(CatalogSolids, PolarDualIsAnInvolution) {
  for (const char* name : {"cube", "truncated-cube", "snub-cube", "icosidodecahedron", "dodecahedron"}) {
    const ConvexPolytope p = catalog_polytope(name);
    const ConvexPolytope d = cd::polar_dual(p, name);
    EXPECT_EQ(d.num_vertices(), p.num_facets()) << name;
    EXPECT_EQ(d.num_facets(), p.num_vertices()) << name;
    EXPECT_EQ(point_set(cd::polar_dual(d, name)), point_set(p)) << name;
  }
}

TEST(CatalogSolids, ExactCatalanDualsFormTheCanonicalCompound) {
  // For the Archimedean solids with integer coordinates the Catalan dual is
  // scaled to the same midsphere: every edge midpoint of the Archimedean
  // solid lies on an edge of its dual.
  auto on_segment = [](const Point3& x, const Point3& a, const Point3& b) {
    if (!is_zero(cross(b - a, x - a))) return false;
    const Rational t = dot(x - a, b - a);
    return t > 0 && t < dot(b - a, b - a);
  };
  for (const auto& [arch, cat] : std::vector<std::pair<std::string, std::string>>{
           {"truncated-tetrahedron", "triakis-tetrahedron"},
           {"cuboctahedron", "rhombic-dodecahedron"},
           {"truncated-octahedron", "tetrakis-hexahedron"}}) {
    const ConvexPolytope a = catalog_polytope(arch), c = catalog_polytope(cat);
    for (Index e = 0; e < a.num_edges(); ++e) {
      const Point3 mid = Rational(1, 2) * (a.point(a.origin(2 * e)) + a.point(a.target(2 * e)));
      bool found = false;
      for (Index f = 0; f < c.num_edges() && !found; ++f)
        found = on_segment(mid, c.point(c.origin(2 * f)), c.point(c.target(2 * f)));
      EXPECT_TRUE(found) << arch << " edge " << e;
    }
  }
}

TEST(CatalogSolids, DodecahedronIsDualAlignedWithTheIcosahedron) {
  // Every facet normal of the dodecahedron points at a vertex of the
  // icosahedron cyc(0, ±A, ±B): same direction up to the ~1e-8 difference of
  // the two approximations of φ.
  const ConvexPolytope d = catalog_polytope("dodecahedron");
  const ConvexPolytope ico = catalog_polytope("icosahedron");
  for (Index f = 0; f < d.num_facets(); ++f) {
    const Vec3d n = to_double(d.plane(f).normal());
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    double best = -2;
    for (Index v = 0; v < ico.num_vertices(); ++v) {
      const Vec3d& q = ico.approx(v);
      best = std::max(best, (n.x * q.x + n.y * q.y + n.z * q.z) / len);
    }
    EXPECT_GT(best, 1 - 1e-12);
  }
}

// ---------------------------------------------------------------------------
// sphere:L

TEST(CatalogSphere, CountsUnitLengthAndInvariants) {
  for (int level = 1; level <= 6; ++level) {
    SCOPED_TRACE(level);
    const Index q = Index(1) << (2 * (level - 1));  // 4^(L-1)
    const ConvexPolytope p = catalog_polytope("sphere:" + std::to_string(level));
    expect_counts(p, 10 * q + 2, 30 * q, 20 * q, "sphere");
    EXPECT_EQ(degree_histogram(p), "3:" + std::to_string(20 * q));
    EXPECT_TRUE(p.coordinates_are_doubles());
    // The generator normalises in double precision: a tolerance is right here
    // (it checks the generator, it makes no geometric decision).
    for (Index v = 0; v < p.num_vertices(); ++v) {
      const Vec3d& a = p.approx(v);
      EXPECT_NEAR(std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z), 1.0, 4e-16);
    }
  }
}

TEST(CatalogSphere, LevelOneIsTheIcosahedron) {
  EXPECT_EQ(point_set(catalog_polytope("sphere:1")), point_set(catalog_polytope("icosahedron")));
}

TEST(CatalogSphere, MeshIsDeterministicAndKeepsCoarserVerticesFirst) {
  const Mesh a = cd::sphere_mesh(4), b = cd::sphere_mesh(4), c = cd::sphere_mesh(3);
  ASSERT_EQ(a.points.size(), 642u);
  EXPECT_TRUE(a.points == b.points);
  EXPECT_TRUE(a.faces == b.faces);
  for (std::size_t i = 0; i < c.points.size(); ++i) EXPECT_EQ(a.points[i], c.points[i]);
  // Golden value (bit-exact determinism across platforms): the last vertex
  // of level 3, a normalised midpoint that rounds differently from the
  // icosahedron's own coordinates.
  const Mesh m3 = cd::sphere_mesh(3);
  ASSERT_EQ(m3.points.size(), 162u);
  EXPECT_EQ(m3.points[m3.points.size() - 1], Point3(-0x1.b38880b4603e4p-1, -0x1.0d2ca0da1530ep-1, 0.0));
}

TEST(CatalogSphere, SubdivisionMeshIsExactlyConvexWithoutFallback) {
  // from_mesh accepts the subdivided mesh as it is: every level is exactly
  // convex, the hull fallback is not needed.  Level 1, the icosahedron,
  // whose triangles the generator has as a table: each is a facet of the
  // hull, counter-clockwise seen from outside (the nine other vertices
  // strictly below its plane, exactly), and they are all the facets.
  const Mesh ico = cd::sphere_mesh(1);
  ASSERT_EQ(ico.points.size(), 12u);
  ASSERT_EQ(ico.faces.size(), 20u);
  std::set<std::set<Index>> distinct;
  for (const auto& f : ico.faces) {
    ASSERT_EQ(f.size(), 3u);
    distinct.insert({f[0], f[1], f[2]});
    const Point3 a = ico.points.exact(f[0]);
    const Point3 n = cross(ico.points.exact(f[1]) - a, ico.points.exact(f[2]) - a);
    for (Index v = 0; v < 12; ++v) {
      if (v == f[0] || v == f[1] || v == f[2]) continue;
      EXPECT_LT(sgn(dot(n, ico.points.exact(v) - a)), 0) << v;
    }
  }
  EXPECT_EQ(distinct.size(), 20u);
  for (int level = 1; level <= 6; ++level) {
    const Mesh m = cd::sphere_mesh(level);
    const ConvexPolytope p = ConvexPolytope::from_mesh(m, "sphere");
    EXPECT_EQ(p.num_facets(), m.faces.size());
    EXPECT_EQ(p.num_vertices(), m.points.size());
  }
}

// ---------------------------------------------------------------------------
// box, transforms.

TEST(CatalogBox, VolumeAndTinySides) {
  const ConvexPolytope b = catalog_polytope("box:2:3:5");
  expect_counts(b, 8, 12, 6, "box:2:3:5");
  EXPECT_EQ(b.volume(), Rational(30));
  const ConvexPolytope t = catalog_polytope("box:1:1/3:1e-12");
  EXPECT_EQ(t.volume(), Rational(1, 3) * Rational(1e-12));
  EXPECT_EQ(point_set(catalog_polytope("box:2:2:2")), point_set(catalog_polytope("cube")));
}

TEST(CatalogTransforms, RotationMatricesAreExactlyOrthogonal) {
  for (const auto& q : {std::array<long, 4>{1, 2, 3, 4}, {1, 1, 0, 0}, {-7, 3, 0, 11}, {0, 0, 0, 5}}) {
    const Matrix3 r = quaternion_rotation({q[0], q[1], q[2], q[3]});
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Rational s = 0;
        for (int k = 0; k < 3; ++k) s += r.m[i][k] * r.m[j][k];
        EXPECT_EQ(s, Rational(i == j ? 1 : 0));
      }
    const auto& m = r.m;
    const Rational det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    EXPECT_EQ(det, Rational(1));
  }
  // (1, 1, 0, 0) is the quarter turn about x: y -> z.
  const Matrix3 r = quaternion_rotation({1, 1, 0, 0});
  EXPECT_EQ(r * Point3(Rational(0), Rational(1), Rational(0)),
            Point3(Rational(0), Rational(0), Rational(1)));
}

TEST(CatalogTransforms, RotationPreservesCountsAndVolumeExactly) {
  for (const char* base : {"cube", "dodecahedron", "truncated-cube", "snub-cube", "sphere:3", "dioctagonal:17",
                           "zonotope:6:2", "box:1:1/3:1e-12", "rhombic-triacontahedron"}) {
    const ConvexPolytope p = catalog_polytope(base);
    for (const char* rot : {"@rot:7", "@rot:1,2,3,4", "@rot:12345678901234567890"}) {
      const std::string spec = std::string(base) + rot;
      SCOPED_TRACE(spec);
      const ConvexPolytope r = catalog_polytope(spec);
      expect_counts(r, p.num_vertices(), p.num_edges(), p.num_facets(), spec);
      EXPECT_EQ(r.volume(), p.volume());
      EXPECT_EQ(degree_histogram(r), degree_histogram(p));
    }
  }
  EXPECT_FALSE(catalog_polytope("cube@rot:7").coordinates_are_doubles());
}

TEST(CatalogTransforms, RandomRotationIsDeterministicAndSeedDependent) {
  EXPECT_EQ(cd::random_quaternion(7), cd::random_quaternion(7));
  EXPECT_NE(cd::random_quaternion(7), cd::random_quaternion(8));
  EXPECT_EQ(point_set(catalog_polytope("cube@rot:7")), point_set(catalog_polytope("cube@rot:7")));
  EXPECT_NE(point_set(catalog_polytope("cube@rot:7")), point_set(catalog_polytope("cube@rot:8")));
  const auto q = cd::random_quaternion(7);
  Integer n2 = 0;
  for (const auto& x : q) n2 += x * x;
  EXPECT_GE(n2, 2500);
  EXPECT_LE(n2, 10000);
}

TEST(CatalogTransforms, ScaleTranslateNegCompose) {
  const ConvexPolytope tiny = catalog_polytope("cube@scale:1e-150");
  const Rational s(1e-150);
  EXPECT_EQ(tiny.volume(), 8 * s * s * s);
  EXPECT_TRUE(tiny.coordinates_are_doubles());
  const ConvexPolytope big = catalog_polytope("cube@scale:1e150@rot:1,2,3,4");
  const Rational b(1e150);
  EXPECT_EQ(big.volume(), 8 * b * b * b);
  expect_counts(big, 8, 12, 6, "big");

  const ConvexPolytope t = catalog_polytope("cube@translate:1,2,-3/7");
  EXPECT_TRUE(point_set(t).count(Point3(Rational(2), Rational(3), Rational(4, 7))));
  EXPECT_EQ(t.volume(), Rational(8));

  const ConvexPolytope a = catalog_polytope("box:2:3:5@scale:1,2,1/5");
  EXPECT_EQ(a.volume(), Rational(12));

  const ConvexPolytope tet = catalog_polytope("tetra");
  const ConvexPolytope neg = catalog_polytope("tetra@neg");
  std::set<Point3> negated;
  for (const Point3& v : tet.points()) negated.insert(-v);
  EXPECT_EQ(point_set(neg), negated);
  EXPECT_EQ(neg.check_invariants(), "");
  EXPECT_EQ(neg.volume(), tet.volume());

  // Order matters: translate then scale scales the translation too.
  const ConvexPolytope ts = catalog_polytope("cube@translate:1,0,0@scale:2");
  EXPECT_TRUE(point_set(ts).count(Point3(Rational(4), Rational(2), Rational(2))));
}

// ---------------------------------------------------------------------------
// dioctagonal:N

TEST(CatalogDioctagonal, CountsAndShape) {
  const ConvexPolytope p = catalog_polytope("dioctagonal:17");
  expect_counts(p, 17, 32, 17, "dioctagonal:17");
  EXPECT_EQ(degree_histogram(p), "3:16,16:1");
  EXPECT_TRUE(p.coordinates_are_doubles());
  int apex = 0, base = 0;
  for (const Point3& v : p.points()) {
    if (v.z == Rational(1, 8)) {
      ++apex;
      EXPECT_EQ(v.x, 0);
      EXPECT_EQ(v.y, 0);
    } else {
      ++base;
      EXPECT_EQ(v.z, 0);
    }
  }
  EXPECT_EQ(apex, 1);
  EXPECT_EQ(base, 16);
  for (Index n : {4u, 5u, 9u, 100u, 1001u}) {
    const ConvexPolytope q = catalog_polytope("dioctagonal:" + std::to_string(n));
    expect_counts(q, n, 2 * (n - 1), n, "dioctagonal");
  }
}

TEST(CatalogDioctagonal, BasePolygonIsExactlySymmetric) {
  // The regular 16-gon: opposite vertices are exact negatives, the vertex at
  // 90° is exactly (0, 1), and mirror images across the diagonal swap x and y.
  const std::uint64_t n = 16;
  for (std::uint64_t k = 0; k < n; ++k) {
    const auto p = cd::unit_circle_point(k, n);
    const auto q = cd::unit_circle_point((k + n / 2) % n, n);
    EXPECT_EQ(p[0], -q[0]);
    EXPECT_EQ(p[1], -q[1]);
    const auto r = cd::unit_circle_point((n / 4 + n - k) % n, n);  // mirror across y = x
    EXPECT_EQ(p[0], r[1]);
    EXPECT_EQ(p[1], r[0]);
    EXPECT_NEAR(std::hypot(p[0], p[1]), 1.0, 4e-16);
  }
  EXPECT_EQ(cd::unit_circle_point(4, 16)[0], 0.0);
  EXPECT_EQ(cd::unit_circle_point(4, 16)[1], 1.0);
  // Compare with the C library on a non-symmetric grid (a check of the
  // polynomial, not a decision).
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const auto p = cd::unit_circle_point(k, 1000);
    EXPECT_NEAR(p[0], std::cos(2 * M_PI * double(k) / 1000), 1e-15);
    EXPECT_NEAR(p[1], std::sin(2 * M_PI * double(k) / 1000), 1e-15);
  }
}

// ---------------------------------------------------------------------------
// ball:N, prism:N

TEST(CatalogBall, CountsDegreesUnitLengthAndSymmetry) {
  // 2N(N - 1) + 2 vertices: 26, 114, 266 and 1106 for N = 4, 8, 12, 24.
  for (Index n : {2u, 3u, 4u, 5u, 8u, 12u, 24u}) {
    SCOPED_TRACE(n);
    const ConvexPolytope p = catalog_polytope("ball:" + std::to_string(n));
    expect_counts(p, 2 * n * (n - 1) + 2, 2 * n * (2 * n - 1), 2 * n * n, "ball");
    // Every side quadrilateral stays one facet (exactly planar, not merged).
    EXPECT_EQ(degree_histogram(p),
              n == 2 ? "3:8" : "3:" + std::to_string(4 * n) + ",4:" + std::to_string(2 * n * (n - 2)));
    // Central symmetry, exactly (the rings' angles are symmetric on the grid).
    EXPECT_EQ(point_set(p), point_set(catalog_polytope("ball:" + std::to_string(n) + "@neg")));
    // The products radius * direction are not doubles in general; on the unit
    // sphere to within the rounding of the directions (a check of the
    // generator, not a geometric decision).
    for (Index v = 0; v < p.num_vertices(); ++v) {
      const Vec3d& a = p.approx(v);
      EXPECT_NEAR(std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z), 1.0, 1e-15);
    }
  }
  EXPECT_EQ(catalog_polytope("ball:4").num_vertices(), 26u);
  EXPECT_EQ(catalog_polytope("ball:24").num_vertices(), 1106u);
  EXPECT_EQ(point_set(catalog_polytope("ball:2")), point_set(catalog_polytope("octahedron")));
}

TEST(CatalogPrism, CountsDegreesAndVolume) {
  for (Index n : {3u, 4u, 5u, 16u, 1000u}) {
    SCOPED_TRACE(n);
    const ConvexPolytope p = catalog_polytope("prism:" + std::to_string(n));
    expect_counts(p, 2 * n, 3 * n, n + 2, "prism");
    const std::string caps = std::to_string(n) + ":2", sides = "4:" + std::to_string(n);
    EXPECT_EQ(degree_histogram(p), n == 3 ? "3:2,4:3" : n == 4 ? "4:6" : sides + "," + caps);
    EXPECT_TRUE(p.coordinates_are_doubles());
  }
  // The square of circumradius 1 (exact points (±1, 0), (0, ±1)) times height 2.
  EXPECT_EQ(catalog_polytope("prism:4").volume(), Rational(4));
  EXPECT_EQ(point_set(catalog_polytope("prism:4")), point_set(catalog_polytope("zonotope:1/2,1/2,0:1/2,-1/2,0:0,0,1")));
}

// ---------------------------------------------------------------------------
// random:N:SEED

TEST(CatalogRandom, DeterministicAndSeedDependent) {
  const auto a = cd::random_sphere_points(1000, 42), b = cd::random_sphere_points(1000, 42);
  EXPECT_TRUE(a == b);
  const auto c = cd::random_sphere_points(1000, 43);
  EXPECT_FALSE(a == c);
  // A prefix does not depend on N.
  const auto d = cd::random_sphere_points(10, 42);
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(d[i], a[i]);
  for (const Point3& p : a) {
    const Vec3d v = to_double(p);
    EXPECT_NEAR(std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z), 1.0, 4e-16);
  }
  const ConvexPolytope p = catalog_polytope("random:1000:42");
  const ConvexPolytope q = catalog_polytope("random:1000:42");
  EXPECT_TRUE(p.points() == q.points());
  EXPECT_EQ(p.check_invariants(), "");
  EXPECT_EQ(p.num_vertices(), 1000u);  // every point is extreme for this seed
  EXPECT_EQ(p.num_facets(), 2 * 1000u - 4);  // simplicial
  EXPECT_NE(point_set(p), point_set(catalog_polytope("random:1000:43")));
}

TEST(CatalogRandom, GoldenValues) {
  // splitmix64 and the rejection sampler are fully specified: these values
  // must be the same on every platform.
  cd::SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xe220a8397b1dcdafull);
  EXPECT_EQ(rng.next(), 0x6e789e6aa1b965f4ull);
  const auto pts = cd::random_sphere_points(2, 1);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[0], Point3(0x1.2e6008e28ce22p-1, 0x1.59fe2a2a1d7c8p-1, 0x1.c3ac6ab42f62cp-2));
  EXPECT_EQ(pts[1], Point3(0x1.fc6087d63127p-1, -0x1.2301161caa53fp-4, -0x1.85c12e07fbe56p-4));
  const auto c = cd::unit_circle_point(1, 17);
  EXPECT_EQ(c[0], 0x1.dd6d000370991p-1);
  EXPECT_EQ(c[1], 0x1.71e955d8e7cdcp-2);
  const auto q = cd::random_quaternion(7);
  EXPECT_EQ(q, (std::array<Integer, 4>{-10, 50, -5, -56}));
  const auto g = cd::zonotope_generators(3, 1);
  EXPECT_EQ(g, (std::vector<std::array<std::int64_t, 3>>{{-2, -5, 5}, {5, 3, 2}, {-4, -3, 1}}));
}

TEST(CatalogRandom, SmallCases) {
  for (std::uint64_t seed : {0ull, 1ull, 2ull, 18446744073709551615ull}) {
    const ConvexPolytope p = catalog_polytope("random:4:" + std::to_string(seed));
    expect_counts(p, 4, 6, 4, "random:4");
  }
}

// random:N:SEED is the hull of random_sphere_points(N, SEED) as the generic
// exact hull computes it (the points as rationals, CGAL's Epeck kernel): the
// same vertices in the same order with the same source points, the same
// facet loops in the same order, the same planes.  Small N (4: a
// tetrahedron; 5) and the largest seed included.
TEST(CatalogRandom, SameAsTheGenericHullOfItsPoints) {
  const std::pair<std::uint64_t, std::uint64_t> cases[] = {
      {4, 0}, {4, 1}, {4, 18446744073709551615ull}, {5, 0}, {5, 1}, {5, 2}, {5, 3}, {6, 7}, {10, 42}, {300, 5},
      {3000, 7}};
  for (const auto& [n, seed] : cases) {
    const std::string spec = "random:" + std::to_string(n) + ":" + std::to_string(seed);
    SCOPED_TRACE(spec);
    const ConvexPolytope p = catalog_polytope(spec);
    const ConvexPolytope q = ConvexPolytope::hull(cd::random_sphere_points(n, seed), spec);
    ASSERT_EQ(p.num_vertices(), q.num_vertices());
    ASSERT_EQ(p.num_facets(), q.num_facets());
    EXPECT_EQ(p.num_edges(), q.num_edges());
    EXPECT_TRUE(p.coordinates_are_doubles());
    for (Index v = 0; v < q.num_vertices(); ++v) {
      EXPECT_EQ(p.point(v), q.point(v));
      EXPECT_EQ(p.source_vertex(v), q.source_vertex(v));
    }
    for (Index f = 0; f < q.num_facets(); ++f) {
      EXPECT_EQ(p.facet_vertices(f), q.facet_vertices(f));
      EXPECT_EQ(p.plane(f), q.plane(f));
    }
  }
}

// ---------------------------------------------------------------------------
// zonotope

TEST(CatalogZonotope, CountsMatchTheFormula) {
  for (std::uint64_t n = 3; n <= 14; ++n)
    for (std::uint64_t seed : {1ull, 2ull, 99ull}) {
      const std::string spec = "zonotope:" + std::to_string(n) + ":" + std::to_string(seed);
      SCOPED_TRACE(spec);
      const ConvexPolytope p = catalog_polytope(spec);
      const Index N = Index(n);
      expect_counts(p, N * (N - 1) + 2, 2 * N * (N - 1), N * (N - 1), spec);
      EXPECT_EQ(degree_histogram(p), "4:" + std::to_string(N * (N - 1)));
    }
}

TEST(CatalogZonotope, GeneratorsInGeneralPositionAndVolume) {
  const auto g = cd::zonotope_generators(8, 5);
  ASSERT_EQ(g.size(), 8u);
  // Volume of sum [-g_k, g_k] = 8 * sum over triples |det(g_i, g_j, g_k)|.
  Integer vol = 0;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t j = i + 1; j < g.size(); ++j)
      for (std::size_t k = j + 1; k < g.size(); ++k) {
        const auto &a = g[i], &b = g[j], &c = g[k];
        const long det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                         a[2] * (b[0] * c[1] - b[1] * c[0]);
        EXPECT_NE(det, 0);
        vol += std::labs(det);
      }
  EXPECT_EQ(catalog_polytope("zonotope:8:5").volume(), Rational(8 * vol));
  EXPECT_TRUE(catalog_polytope("zonotope:8:5").points() == catalog_polytope("zonotope:8:5").points());
}

TEST(CatalogZonotope, ExplicitGenerators) {
  const ConvexPolytope c = catalog_polytope("zonotope:1,0,0:0,1,0:0,0,1");
  expect_counts(c, 8, 12, 6, "explicit cube");
  EXPECT_EQ(point_set(c), point_set(catalog_polytope("cube")));
  // Parallel generators add up: a box 6 x 2 x 2.
  const ConvexPolytope b = catalog_polytope("zonotope:1,0,0:2,0,0:0,1,0:0,0,1");
  expect_counts(b, 8, 12, 6, "parallel");
  EXPECT_EQ(b.volume(), Rational(24));
  // Four generators, three of them coplanar: a hexagonal prism.
  const ConvexPolytope h = catalog_polytope("zonotope:1,0,0:0,1,0:1,1,0:0,0,1");
  expect_counts(h, 12, 18, 8, "hexagonal prism");
  EXPECT_NE(usage_error("zonotope:1,0,0:0,1,0:1,1,0").find("3 dimensions"), std::string::npos);
}

// ---------------------------------------------------------------------------
// Spec syntax and errors.

TEST(CatalogSpec, IsCatalogSpec) {
  for (const char* s : {"cube", "tetra", "sphere:6", "sphere:12", "sphere:x", "random:10:3", "box:1:2:3",
                        "cube@rot:7", "sphere:3@rot:7@scale:2", "zonotope:4:1", "dioctagonal:17", "cube@bogus"})
    EXPECT_TRUE(is_catalog_spec(s)) << s;
  for (const char* s : {"foo.off", "./cube", "cube.off", "", "Cube", "/tmp/cube", "data/sphere:3", "spheres:3",
                        "@rot:7", ":cube"})
    EXPECT_FALSE(is_catalog_spec(s)) << s;
}

TEST(CatalogSpec, BadSpecsThrowUsageErrorsThatNameTheSpecAndTheForm) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sphere:12", "sphere:L needs 1 <= L <= 9, got 12"},
      {"sphere:0", "sphere:L needs 1 <= L <= 9, got 0"},
      {"sphere", "sphere:L takes 1 parameter"},
      {"sphere:1:2", "sphere:L takes 1 parameter"},
      {"sphere:x", "sphere:L needs a number L"},
      {"sphere:2.5", "sphere:L needs an integer L"},
      {"dioctagonal:3", "dioctagonal:N needs 4 <= N <= 100000, got 3"},
      {"random:3:1", "random:N:SEED needs 4 <= N"},
      {"random:10", "random:N:SEED takes 2 parameters"},
      {"random:10:-1", "random:N:SEED needs 0 <= SEED"},
      {"random:10:18446744073709551616", "random:N:SEED needs 0 <= SEED"},
      {"zonotope:2:1", "zonotope:N:SEED needs 3 <= N <= 256, got 2"},
      {"zonotope:1,2:0,0,1", "needs each generator as X,Y,Z"},
      {"ball:1", "ball:N needs 2 <= N <= 1000, got 1"},
      {"ball:1001", "ball:N needs 2 <= N <= 1000, got 1001"},
      {"prism:2", "prism:N needs 3 <= N <= 100000, got 2"},
      {"prism", "prism:N takes 1 parameter"},
      {"box:1:2", "box:X:Y:Z takes 3 parameters"},
      {"box:1:0:3", "box:X:Y:Z needs Y > 0, got 0"},
      {"box:1:-2:3", "box:X:Y:Z needs Y > 0"},
      {"box:1:nan:3", "box:X:Y:Z needs a number Y"},
      {"cube:2", "'cube' takes no parameters"},
      {"tetrahedra", "unknown catalog name 'tetrahedra' (did you mean 'tetrahedron'?)"},
      {"foo", "unknown catalog name 'foo'"},
      {"cube@", "empty transform after '@'"},
      {"cube@bogus", "unknown transform 'bogus'"},
      {"cube@rot", "rot needs rot:SEED or rot:A,B,C,D"},
      {"cube@rot:1,2", "rot needs rot:SEED or rot:A,B,C,D"},
      {"cube@rot:0,0,0,0", "non-zero quaternion"},
      {"cube@rot:1,2,3,0.5", "rot:A,B,C,D needs an integer D"},
      {"cube@scale:0", "scale:S needs S > 0, got 0"},
      {"cube@scale:-1", "scale:S needs S > 0"},
      {"cube@scale:1,2", "scale needs scale:S or scale:X,Y,Z"},
      {"cube@translate:1,2", "translate needs translate:X,Y,Z"},
      {"cube@neg:1", "neg takes no parameter"},
      {"", "empty catalog spec"},
  };
  for (const auto& [spec, needle] : cases) {
    const std::string msg = usage_error(spec);
    EXPECT_NE(msg.find(needle), std::string::npos) << spec << " -> " << msg;
    if (!spec.empty()) {
      EXPECT_NE(msg.find("'" + spec + "'"), std::string::npos) << spec << " -> " << msg;
    }
  }
}

TEST(CatalogSpec, TransformsAreCheckedBeforeTheBaseIsBuilt) {
  // A bad transform on an expensive base fails at once (no sphere:9 built).
  EXPECT_NE(usage_error("sphere:9@scale:0").find("scale:S needs S > 0"), std::string::npos);
}

TEST(CatalogSpec, EntriesDescribeEveryNameAndTransform) {
  const auto& entries = catalog_entries();
  auto has = [&](const std::string& syntax_start) {
    for (const auto& e : entries)
      if (e.syntax.rfind(syntax_start, 0) == 0 && !e.description.empty()) return true;
    return false;
  };
  for (const cd::FixedSolid& s : cd::fixed_solids()) EXPECT_TRUE(has(s.name)) << s.name;
  for (const char* s : {"sphere:L", "dioctagonal:N", "random:N:SEED", "zonotope:N:SEED", "zonotope:X,Y,Z",
                        "box:X:Y:Z", "ball:N", "prism:N", "@rot:SEED", "@rot:A,B,C,D", "@scale:S", "@translate:X,Y,Z", "@neg"})
    EXPECT_TRUE(has(s)) << s;
  for (const auto& e : entries) EXPECT_EQ(e.description.find('\n'), std::string::npos) << e.syntax;
}
