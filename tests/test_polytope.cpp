// ConvexPolytope: validation, coplanar merging, half-edge connectivity, hull.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/polytope.hpp>
#include <minksum/predicates.hpp>

#include "mesh/builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

// A point on the unit sphere: a normal-distributed vector, normalised (the
// direction is uniform; the coordinates are rounded doubles of it).
Point3 on_unit_sphere(std::mt19937_64& rng, std::normal_distribution<double>& g) {
  const double x = g(rng), y = g(rng), z = g(rng), r = std::sqrt(x * x + y * y + z * z);
  return Point3(x / r, y / r, z / r);
}

// m with every point divided by 3: the same solid in rationals.
Mesh thirds(const Mesh& m) {
  Mesh t;
  t.faces = m.faces;
  for (const Point3& p : m.points) t.points.push_back(Point3(p.x / 3, p.y / 3, p.z / 3));
  return t;
}

// The error from_mesh(m) throws ("" when none); the polytope in p otherwise.
std::string outcome(const Mesh& m, ConvexPolytope& p) {
  try {
    p = ConvexPolytope::from_mesh(m, "case.off");
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return std::string();
}

// The problem text of the InputError thrown by from_mesh(m), or "" if none.
std::string build_error(const Mesh& m) {
  try {
    ConvexPolytope::from_mesh(m, "case.off");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "case.off");
    return e.what();
  }
  return "";
}

std::string hull_error(const std::vector<Point3>& pts) {
  try {
    ConvexPolytope::hull(pts, "cloud.xyz");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Polytope, CubeCountsPlanesVolume) {
  ConvexPolytope c = ConvexPolytope::from_mesh(cube_mesh(1));
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_edges(), 12u);
  EXPECT_EQ(c.num_facets(), 6u);
  EXPECT_EQ(c.euler_characteristic(), 2);
  EXPECT_EQ(c.volume(), Rational(8));
  std::set<std::tuple<long, long, long, long>> planes;
  for (Index f = 0; f < 6; ++f) {
    const Plane& p = c.plane(f);
    planes.insert({p.a.get_si(), p.b.get_si(), p.c.get_si(), p.d.get_si()});
  }
  std::set<std::tuple<long, long, long, long>> want = {{1, 0, 0, 1},  {-1, 0, 0, 1}, {0, 1, 0, 1},
                                                       {0, -1, 0, 1}, {0, 0, 1, 1},  {0, 0, -1, 1}};
  EXPECT_EQ(planes, want);
  EXPECT_EQ(c.check_invariants(), "");
  EXPECT_TRUE(c.coordinates_are_doubles());
}

// A pyramid over a polygon inscribed in a circle (rational points
// ((m^2 - k^2) / (m^2 + k^2), 2km / (m^2 + k^2), 0)), apex (0, 0, h): volume
// = area * h / 3, the area by the shoelace formula.  Few distinct
// denominators (m = 3, |k| <= 2) take volume()'s path on integers over their
// least common multiple; many (m = 20, |k| <= 19) take the path on the
// rationals themselves.  Both must give the closed form exactly.
TEST(Polytope, VolumeOfRationalCoordinatesIsTheClosedForm) {
  for (const auto& [m, kmax] : {std::pair<long, long>{3, 2}, std::pair<long, long>{20, 19}}) {
    const Rational h(7, 3);
    std::vector<Point3> pts;
    std::vector<std::pair<Rational, Rational>> base;
    for (long k = -kmax; k <= kmax; ++k) {  // counter-clockwise: the angle grows with k
      const Rational den(m * m + k * k);
      base.push_back({Rational(m * m - k * k) / den, Rational(2 * k * m) / den});
      pts.push_back(Point3(base.back().first, base.back().second, Rational(0)));
    }
    pts.push_back(Point3(Rational(0), Rational(0), h));
    Rational twice_area = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
      const auto& [x0, y0] = base[i];
      const auto& [x1, y1] = base[(i + 1) % base.size()];
      twice_area += x0 * y1 - x1 * y0;
    }
    const ConvexPolytope p = ConvexPolytope::hull(pts);
    ASSERT_EQ(p.num_vertices(), base.size() + 1) << "m " << m;
    EXPECT_FALSE(p.coordinates_are_doubles());
    EXPECT_EQ(p.volume(), twice_area / 2 * h / 3) << "m " << m;
    // The same solid translated by a point of other denominators.
    const ConvexPolytope t = p.translated(Point3(Rational(1, 5), Rational(-2, 9), Rational(3, 11)));
    EXPECT_EQ(t.volume(), twice_area / 2 * h / 3) << "m " << m;
  }
}

TEST(Polytope, HalfedgeConventions) {
  ConvexPolytope c = ConvexPolytope::from_mesh(octahedron_mesh());
  ASSERT_EQ(c.num_facets(), 8u);
  for (Index h = 0; h < c.num_halfedges(); ++h) {
    EXPECT_EQ(ConvexPolytope::twin(ConvexPolytope::twin(h)), h);
    EXPECT_EQ(c.origin(ConvexPolytope::twin(h)), c.target(h));
    EXPECT_EQ(c.origin(c.next_around_vertex(h)), c.origin(h));
    EXPECT_EQ(c.facet(c.next(h)), c.facet(h));
    // CCW seen from outside: the turn at target(h) has a positive component
    // along the facet's outward normal.
    Point3 e1 = c.point(c.target(h)) - c.point(c.origin(h));
    Point3 e2 = c.point(c.target(c.next(h))) - c.point(c.target(h));
    EXPECT_GT(sgn(dot(cross(e1, e2), c.plane(c.facet(h)).normal())), 0);
  }
  // Around each vertex: next_around_vertex visits every outgoing halfedge once,
  // counter-clockwise seen from outside.
  for (Index v = 0; v < c.num_vertices(); ++v) {
    EXPECT_EQ(c.vertex_degree(v), 4u);
    auto nb = c.vertex_neighbours(v);
    ASSERT_EQ(nb.size(), 4u);
    Point3 outward = c.point(v);  // the octahedron is centred at the origin
    for (std::size_t i = 0; i < nb.size(); ++i) {
      Point3 d0 = c.point(nb[i]) - c.point(v), d1 = c.point(nb[(i + 1) % nb.size()]) - c.point(v);
      EXPECT_GT(sgn(dot(cross(d0, d1), outward)), 0);
    }
  }
}

TEST(Polytope, InwardMeshIsFlipped) {
  Mesh m = cube_mesh(2);
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  ConvexPolytope c = ConvexPolytope::from_mesh(m);
  EXPECT_EQ(c.num_facets(), 6u);
  EXPECT_EQ(c.volume(), Rational(64));
  for (Index f = 0; f < c.num_facets(); ++f) EXPECT_EQ(sgn(c.plane(f).d), 1);  // origin inside
}

TEST(Polytope, TriangulatedCubeIsMerged) {
  ConvexPolytope c = ConvexPolytope::from_mesh(triangulated(cube_mesh(1)));
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_edges(), 12u);
  EXPECT_EQ(c.num_facets(), 6u);
  for (Index f = 0; f < c.num_facets(); ++f) EXPECT_EQ(c.facet_degree(f), 4u);
  EXPECT_EQ(c.check_invariants(), "");
}

TEST(Polytope, VertexInTheMiddleOfAnEdgeIsDropped) {
  // Split the edge (0,0,0)-(2,0,0) of the box [0,2]^3 at (1,0,0): both
  // adjacent quads become pentagons through the midpoint.
  Mesh m = box_mesh(0, 2, 0, 2, 0, 2);
  m.points.push_back(P(1, 0, 0));  // index 8, between vertices 0 and 1
  // faces {0,2,3,1} (z=0) and {0,1,5,4} (y=0) contain edge 0-1 / 1-0.
  m.faces[0] = {0, 2, 3, 1, 8};
  m.faces[2] = {0, 8, 1, 5, 4};
  ConvexPolytope c = ConvexPolytope::from_mesh(m);
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_edges(), 12u);
  EXPECT_EQ(c.num_facets(), 6u);
}

TEST(Polytope, VertexInsideAFacetIsDropped) {
  // The top facet z=2 of [0,2]^3 split into four triangles around (1,1,2),
  // and the side y=0 into triangles too.
  Mesh m = box_mesh(0, 2, 0, 2, 0, 2);
  m.points.push_back(P(1, 1, 2));  // 8
  // top face {4,5,7,6}
  m.faces[1] = {4, 5, 8};
  m.faces.push_back({5, 7, 8});
  m.faces.push_back({7, 6, 8});
  m.faces.push_back({6, 4, 8});
  ConvexPolytope c = ConvexPolytope::from_mesh(triangulated(m));
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_facets(), 6u);
  EXPECT_EQ(c.volume(), Rational(8));
}

TEST(Polytope, RationalAndExtremeCoordinates) {
  Mesh m = tetra_mesh();
  m.points.transform([](const Point3& p) { return Rational(1, 3) * p; });
  ConvexPolytope t = ConvexPolytope::from_mesh(m);
  EXPECT_FALSE(t.coordinates_are_doubles());
  EXPECT_EQ(t.volume(), Rational(8, 3) / 27);  // regular tetra of volume 8/3, scaled by 1/3
  for (Index f = 0; f < 4; ++f) {
    const Plane& p = t.plane(f);
    Integer g;
    mpz_gcd(g.get_mpz_t(), p.a.get_mpz_t(), p.b.get_mpz_t());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), p.c.get_mpz_t());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), p.d.get_mpz_t());
    EXPECT_EQ(g, 1);  // canonical: primitive integers
  }
  for (double s : {1e150, 1e-150, 1e300, 4.9406564584124654e-322}) {
    Mesh c = cube_mesh(1);
    c.points.transform([&](const Point3& p) { return Rational(s) * p; });
    ConvexPolytope k = ConvexPolytope::from_mesh(c, "scaled");
    EXPECT_EQ(k.num_facets(), 6u) << s;
    EXPECT_EQ(k.volume(), Rational(8) * Rational(s) * Rational(s) * Rational(s)) << s;
  }
}

TEST(Polytope, TranslatedAndNegated) {
  ConvexPolytope t = ConvexPolytope::from_mesh(tetra_mesh());
  ConvexPolytope n = t.negated();
  EXPECT_EQ(n.volume(), t.volume());
  for (Index v = 0; v < 4; ++v) EXPECT_EQ(n.point(v), -t.point(v));
  ConvexPolytope m = t.translated(Q("1/2", "-3", "7/5"));
  EXPECT_EQ(m.volume(), t.volume());
  EXPECT_EQ(m.check_invariants(), "");
}

// ---- bad meshes: each must be rejected with a message naming the problem ----

TEST(PolytopeBad, Empty) {
  EXPECT_NE(build_error(Mesh{}).find("no vertices"), std::string::npos);
  Mesh pts;
  pts.points = {P(0, 0, 0), P(1, 0, 0)};
  EXPECT_NE(build_error(pts).find("--hull"), std::string::npos);
}

TEST(PolytopeBad, IndexOutOfRangeAndShortFacet) {
  Mesh m = cube_mesh();
  m.faces[3][1] = 99;
  EXPECT_NE(build_error(m).find("refers to vertex 99"), std::string::npos);
  m = cube_mesh();
  m.faces[2] = {0, 1};
  EXPECT_NE(build_error(m).find("facet 2: has 2 vertices"), std::string::npos);
  m = cube_mesh();
  m.faces[2] = {0, 1, 5, 1};
  EXPECT_NE(build_error(m).find("twice"), std::string::npos);
}

TEST(PolytopeBad, OpenMesh) {
  Mesh m = cube_mesh();
  m.faces.pop_back();
  EXPECT_NE(build_error(m).find("open mesh"), std::string::npos);
}

TEST(PolytopeBad, FlippedFacet) {
  Mesh m = cube_mesh();
  std::reverse(m.faces[4].begin(), m.faces[4].end());
  EXPECT_NE(build_error(m).find("inconsistent orientation"), std::string::npos);
}

TEST(PolytopeBad, NonManifoldEdge) {
  // Two tetrahedra glued along one edge: that edge has four facets.
  Mesh m = tetra_mesh();
  Mesh t2 = tetra_mesh();
  // Second tetra shares vertices 0 and 1; its other two vertices are moved away.
  Index base = Index(m.points.size());
  m.points.push_back(P(5, 1, 1) + P(0, 2, 0));
  m.points.push_back(P(5, -1, 1));
  for (auto f : t2.faces) {
    for (auto& v : f) v = (v <= 1) ? v : base + (v - 2);
    m.faces.push_back(f);
  }
  EXPECT_NE(build_error(m).find("non-manifold edge"), std::string::npos);
}

TEST(PolytopeBad, NonPlanarFacet) {
  Mesh m = cube_mesh();
  m.points.set(7, P(1, 1, 2));  // lift one corner of the top quad
  EXPECT_NE(build_error(m).find("not planar"), std::string::npos);
}

TEST(PolytopeBad, NonConvexLPrism) {
  // L-shaped prism: the L polygon (0,0),(2,0),(2,1),(1,1),(1,2),(0,2), height 1.
  Mesh m;
  std::vector<std::pair<long, long>> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (auto [x, y] : l) m.points.push_back(P(x, y, 0));
  for (auto [x, y] : l) m.points.push_back(P(x, y, 1));
  m.faces.push_back({5, 4, 3, 2, 1, 0});  // bottom, CW from above = CCW from below
  m.faces.push_back({6, 7, 8, 9, 10, 11});
  for (Index i = 0; i < 6; ++i) m.faces.push_back({i, Index((i + 1) % 6), Index((i + 1) % 6 + 6), Index(i + 6)});
  std::string e = build_error(m);
  EXPECT_NE(e.find("not convex"), std::string::npos) << e;
}

TEST(PolytopeBad, TwoComponents) {
  Mesh m = cube_mesh(1);
  Mesh c2 = box_mesh(5, 6, 5, 6, 5, 6);
  Index base = 8;
  for (const Point3& p : c2.points) m.points.push_back(p);
  for (auto f : c2.faces) {
    for (auto& v : f) v += base;
    m.faces.push_back(f);
  }
  EXPECT_NE(build_error(m).find("more than one connected component"), std::string::npos);
}

// The facet named is the first one (in input order) not connected to facet
// 0, wherever the components' facets are listed.
TEST(PolytopeBad, TwoComponentsNameTheFirstFacetNotConnectedToTheFirst) {
  const Mesh a = cube_mesh(1), b = box_mesh(5, 6, 5, 6, 5, 6);
  for (std::size_t at : {1, 3, 6}) {
    Mesh m = a;
    for (const Point3& p : b.points) m.points.push_back(p);
    std::vector<std::vector<Index>> moved = b.faces;
    for (auto& f : moved)
      for (auto& v : f) v += 8;
    m.faces.insert(m.faces.begin() + long(at), moved.begin(), moved.end());
    EXPECT_EQ(build_error(m), "case.off: facet " + std::to_string(at) +
                                  ": the mesh has more than one connected component (this facet is not connected "
                                  "to facet 0)");
  }
}

TEST(PolytopeBad, FlatBackToBack) {
  Mesh m;
  m.points = {P(0, 0, 0), P(1, 0, 0), P(0, 1, 0)};
  m.faces = {{0, 1, 2}, {0, 2, 1}};
  std::string e = build_error(m);
  EXPECT_TRUE(e.find("zero volume") != std::string::npos || e.find("back to back") != std::string::npos) << e;
}

TEST(PolytopeBad, DoubleCoveredOctahedronIsNotASphere) {
  // Each octant facet used twice would be non-manifold; instead check the
  // genus test with a torus-like square frame: a prism over a square annulus.
  Mesh m;
  std::vector<std::pair<long, long>> outer = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  std::vector<std::pair<long, long>> inner = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  for (int z = 0; z < 2; ++z) {
    for (auto [x, y] : outer) m.points.push_back(P(x, y, z));
    for (auto [x, y] : inner) m.points.push_back(P(x, y, z));
  }
  auto o = [](int i, int z) { return Index(z * 8 + i % 4); };
  auto in = [](int i, int z) { return Index(z * 8 + 4 + i % 4); };
  for (int i = 0; i < 4; ++i) {
    m.faces.push_back({o(i, 0), o(i + 1, 0), o(i + 1, 1), o(i, 1)});      // outer walls
    m.faces.push_back({in(i + 1, 0), in(i, 0), in(i, 1), in(i + 1, 1)});  // inner walls
    m.faces.push_back({o(i, 1), o(i + 1, 1), in(i + 1, 1), in(i, 1)});    // top ring
    m.faces.push_back({o(i + 1, 0), o(i, 0), in(i, 0), in(i + 1, 0)});    // bottom ring
  }
  std::string e = build_error(m);
  EXPECT_NE(e.find("not a topological sphere"), std::string::npos) << e;
}

// ---- hull ----

TEST(Hull, LatticeCubeWithCoplanarPoints) {
  std::vector<Point3> pts;
  for (long x = 0; x <= 3; ++x)
    for (long y = 0; y <= 3; ++y)
      for (long z = 0; z <= 3; ++z) pts.push_back(P(x, y, z));
  ConvexPolytope c = ConvexPolytope::hull(pts, "lattice");
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_edges(), 12u);
  EXPECT_EQ(c.num_facets(), 6u);
  EXPECT_EQ(c.volume(), Rational(27));
  for (Index v = 0; v < 8; ++v) EXPECT_EQ(pts[c.source_vertex(v)], c.point(v));
}

TEST(Hull, OctahedronWithInteriorPoints) {
  std::vector<Point3> pts = octahedron_mesh().points.to_points();
  std::mt19937_64 rng(12345);
  for (int i = 0; i < 200; ++i) {
    long a = long(rng() % 7) - 3, b = long(rng() % 7) - 3, c = long(rng() % 7) - 3;
    if (std::abs(a) + std::abs(b) + std::abs(c) <= 4) pts.push_back(Point3(Rational(a, 4), Rational(b, 4), Rational(c, 4)));
  }
  ConvexPolytope o = ConvexPolytope::hull(pts);
  EXPECT_EQ(o.num_vertices(), 6u);
  EXPECT_EQ(o.num_facets(), 8u);
  EXPECT_EQ(o.volume(), Rational(4, 3));
}

TEST(Hull, DegenerateSetsAreNamed) {
  EXPECT_NE(hull_error({}).find("no points"), std::string::npos);
  EXPECT_NE(hull_error({P(1, 2, 3), P(1, 2, 3)}).find("coincide"), std::string::npos);
  EXPECT_NE(hull_error({P(0, 0, 0), P(1, 1, 1), P(2, 2, 2), P(-5, -5, -5)}).find("collinear"), std::string::npos);
  EXPECT_NE(hull_error({P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(3, 7, 0), P(1, 1, 0)}).find("coplanar"),
            std::string::npos);
  // One ulp off the plane is a solid.
  std::vector<Point3> thin = {P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), Point3(0.5, 0.5, 4.9406564584124654e-324)};
  EXPECT_EQ(hull_error(thin), "");
}

TEST(Polytope, CollapsedSliversAfterWeldingAreDropped) {
  // A triangulated cube whose soup repeats corner coordinates under new
  // indices, plus two slivers that collapse to a segment once welded.
  Mesh m = triangulated(cube_mesh(1));
  m.points.push_back(m.points[0]);  // 8 == 0
  m.points.push_back(m.points[6]);  // 9 == 6
  m.faces[0][0] = m.faces[0][0] == 0 ? 8 : m.faces[0][0];
  m.faces.push_back({0, 8, 6});  // collapses to segment 0-6
  m.faces.push_back({6, 9, 0});  // same segment, other way
  ConvexPolytope c = ConvexPolytope::from_mesh(m);
  EXPECT_EQ(c.num_vertices(), 8u);
  EXPECT_EQ(c.num_facets(), 6u);
  EXPECT_EQ(c.volume(), Rational(8));
}

TEST(Hull, OutputIsCanonicalWhateverTheTriangulation) {
  // Coplanar points on every facet: the hull triangulates them in some order,
  // the polytope must come out the same every time (regression: catalog
  // builds were not deterministic).
  std::vector<Point3> pts;
  for (long x = -2; x <= 2; ++x)
    for (long y = -2; y <= 2; ++y)
      for (long z = -2; z <= 2; ++z)
        if (std::abs(x) == 2 || std::abs(y) == 2 || std::abs(z) == 2) pts.push_back(P(x, y, z));
  const ConvexPolytope first = ConvexPolytope::hull(pts);
  for (int run = 0; run < 20; ++run) {
    const ConvexPolytope again = ConvexPolytope::hull(pts);
    ASSERT_EQ(again.num_facets(), first.num_facets());
    for (Index f = 0; f < first.num_facets(); ++f) {
      EXPECT_EQ(again.facet_vertices(f), first.facet_vertices(f)) << "run " << run << " facet " << f;
      EXPECT_EQ(again.plane(f), first.plane(f));
    }
  }
  EXPECT_EQ(first.check_invariants(), "");
  for (Index f = 0; f < first.num_facets(); ++f) {
    auto loop = first.facet_vertices(f);
    EXPECT_EQ(loop.front(), *std::min_element(loop.begin(), loop.end()));
  }
}

namespace {
// The three hulls of points that are all doubles agree with the hull of the
// same points as rationals (Epeck), vertex for vertex (source vertices
// included) and facet for facet, planes included; degenerate sets get the
// same messages: quickhull on doubles (ConvexPolytope::hull of a PointList)
// and the incremental triangulation (PolytopeBuilder::hull_of_extreme_points).
void expect_same_hulls(const std::vector<Point3>& pts, const std::string& what) {
  SCOPED_TRACE(what);
  const PointList list(pts);
  ASSERT_TRUE(list.all_doubles());
  auto error_of = [](auto build, ConvexPolytope& out) {
    try {
      out = build();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ConvexPolytope a, b, c;
  const std::string rational_error = error_of([&] { return ConvexPolytope::hull(pts, "cloud"); }, a);
  const std::string double_error = error_of([&] { return ConvexPolytope::hull(list, "cloud"); }, b);
  const std::string extreme_error =
      error_of([&] { return PolytopeBuilder::hull_of_extreme_points(list, "cloud"); }, c);
  ASSERT_EQ(double_error, rational_error);
  ASSERT_EQ(extreme_error, rational_error);
  if (!rational_error.empty()) return;
  for (const ConvexPolytope* q : {&b, &c}) {
    SCOPED_TRACE(q == &b ? "quickhull on doubles" : "incremental triangulation");
    ASSERT_EQ(q->num_vertices(), a.num_vertices());
    ASSERT_EQ(q->num_facets(), a.num_facets());
    EXPECT_EQ(q->check_invariants(), "");
    for (Index v = 0; v < a.num_vertices(); ++v) {
      EXPECT_EQ(q->point(v), a.point(v));
      EXPECT_EQ(q->source_vertex(v), a.source_vertex(v));
    }
    for (Index f = 0; f < a.num_facets(); ++f) {
      EXPECT_EQ(q->facet_vertices(f), a.facet_vertices(f));
      EXPECT_EQ(q->plane(f), a.plane(f));
    }
  }
}
}  // namespace

// Fixed seeds; sets with many coplanar and duplicate points, extreme
// magnitudes and points one ulp off a plane.
TEST(Hull, DoublesAgreeWithRationals) {
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<Point3> pts;
    const int n = 4 + int(rng() % 300);
    const double scale = std::ldexp(1.0, int(rng() % 2000) - 1000);
    for (int i = 0; i < n; ++i) {
      switch (rng() % 4) {
        case 0:  // on a small lattice: many coplanar and duplicate points
          pts.push_back(Point3(double(long(rng() % 5) - 2) * scale, double(long(rng() % 5) - 2) * scale,
                               double(long(rng() % 5) - 2) * scale));
          break;
        case 1:  // one ulp off a lattice plane
          pts.push_back(Point3(std::nextafter(2.0 * scale, 3.0 * scale), double(long(rng() % 5) - 2) * scale,
                               double(long(rng() % 5) - 2) * scale));
          break;
        default: {
          std::normal_distribution<double> g;
          pts.push_back(Point3(g(rng) * scale, g(rng) * scale, g(rng) * scale));
        }
      }
    }
    expect_same_hulls(pts, "seed " + std::to_string(seed));
  }
  expect_same_hulls({}, "empty");
  expect_same_hulls({P(1, 2, 3), P(1, 2, 3)}, "coincide");
  expect_same_hulls({P(0, 0, 0), P(1, 1, 1), P(2, 2, 2), P(-5, -5, -5)}, "collinear");
  expect_same_hulls({P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(3, 7, 0), P(1, 1, 0)}, "coplanar");
  expect_same_hulls({P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), Point3(0.5, 0.5, 4.9406564584124654e-324)}, "one ulp thick");
}

// The incremental triangulation on the sets it is meant for (points spread
// over a sphere, nearly all extreme) and on the boundary cases where its
// triangulated surface has vertices quickhull never makes: points inside the
// facets and edges of the hull, repeated points, cospherical points with
// many coplanar ones.  Fixed seeds.
TEST(Hull, ExtremePointsPathAgreesOnSpheresAndBoundaryPoints) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<Point3> pts;
    const int n = 4 + int(rng() % 1500);
    for (int i = 0; i < n; ++i) {
      pts.push_back(on_unit_sphere(rng, g));
      if (seed % 3 == 0 && i % 7 == 0) pts.push_back(pts[rng() % pts.size()]);  // repeats
    }
    if (seed % 4 == 0) pts.push_back(P(0, 0, 0));  // the centre, inside
    expect_same_hulls(pts, "sphere, seed " + std::to_string(seed));
  }
  // The integer points of the sphere of radius 5 and of radius^2 50 (the
  // latter: 12 + 24 + 48 points, with coplanar sets on many facets).
  for (long r2 : {25L, 50L}) {
    std::vector<Point3> pts;
    for (long x = -7; x <= 7; ++x)
      for (long y = -7; y <= 7; ++y)
        for (long z = -7; z <= 7; ++z)
          if (x * x + y * y + z * z == r2) pts.push_back(P(x, y, z));
    expect_same_hulls(pts, "integer sphere " + std::to_string(r2));
  }
  // A cube with points in the middle of every edge and facet, and inside:
  // the triangulated surface has the edge and facet points as vertices.
  std::vector<Point3> cube;
  for (long x = -2; x <= 2; x += 2)
    for (long y = -2; y <= 2; y += 2)
      for (long z = -2; z <= 2; z += 2) cube.push_back(P(x, y, z));
  cube.push_back(P(1, 1, 1));
  expect_same_hulls(cube, "cube with edge and facet midpoints");
  std::reverse(cube.begin(), cube.end());
  expect_same_hulls(cube, "the same, reversed");
  // An octahedron whose first points are repeated at the end.
  std::vector<Point3> octa = {P(1, 0, 0), P(-1, 0, 0), P(0, 1, 0), P(0, -1, 0), P(0, 0, 1), P(0, 0, -1)};
  for (int i = 0; i < 6; ++i) octa.push_back(octa[i]);
  expect_same_hulls(octa, "octahedron, every point twice");
  // Sets that are flat after the first points, or flat except one point
  // coming last.
  expect_same_hulls({P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(1, 1, 0), P(2, 3, 0), P(1, 1, 1)}, "apex last");
  expect_same_hulls({P(0, 0, 0), P(0, 0, 0), P(0, 0, 0), P(1, 0, 0)}, "a segment with repeats");
}

TEST(Hull, DoublePointsOneUlpFromAFacetAreDecidedExactly) {
  // All coordinates doubles: the hull runs on doubles with exact orientation
  // signs.  A point one ulp above the top facet's centre is a vertex, one on
  // it is not, one ulp below is inside; the same points scaled by 1/3 (not
  // doubles: the exact-kernel path) give the same counts.
  const double one = 1.0, above = std::nextafter(one, 2.0), below = std::nextafter(one, 0.0);
  for (const double top : {above, one, below}) {
    std::vector<Point3> pts;
    for (long x = 0; x <= 1; ++x)
      for (long y = 0; y <= 1; ++y)
        for (long z = 0; z <= 1; ++z) pts.push_back(P(x, y, z));
    pts.push_back(Point3(Rational(0.5), Rational(0.5), Rational(top)));
    std::vector<Point3> thirds;
    for (const Point3& p : pts) thirds.push_back(Point3(p.x / 3, p.y / 3, p.z / 3));
    for (const auto* set : {&pts, &thirds}) {
      SCOPED_TRACE(set == &pts ? "doubles" : "thirds");
      const ConvexPolytope h = ConvexPolytope::hull(*set);
      EXPECT_EQ(h.num_vertices(), top == above ? 9u : 8u);
      EXPECT_EQ(h.num_facets(), top == above ? 9u : 6u);
      EXPECT_EQ(h.coordinates_are_doubles(), set == &pts);
      EXPECT_EQ(h.check_invariants(), "");
      const Rational apex = Rational(top) - 1;  // the pyramid on the top facet
      const Rational volume = top == above ? 1 + apex / 3 : Rational(1);
      EXPECT_EQ(h.volume(), set == &pts ? volume : volume / 27);
    }
  }
}

namespace {

// The first edge error, as link reports it: every edge used by three or
// more facets first, then edges traversed twice in one direction, then
// edges of one facet; within a kind, the edge whose first use comes first
// in facet order; named by its endpoints (smaller first) and its first two
// facets, located by their coordinates.  A plain reference (an ordered map of edges), to check the
// sort-based matching.
std::string reference_edge_error(const Mesh& m) {
  struct Edge {
    Index u, w, count = 0, f0 = 0, f1 = 0;
    int same_direction = 0;
    Index first_origin = 0;
  };
  std::vector<Edge> edges;  // in order of first use
  std::map<std::pair<Index, Index>, std::size_t> index;
  for (Index f = 0; f < m.faces.size(); ++f) {
    const auto& poly = m.faces[f];
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Index a = poly[i], b = poly[(i + 1) % poly.size()];
      const Index u = std::min(a, b), w = std::max(a, b);
      const auto [slot, fresh] = index.emplace(std::make_pair(u, w), edges.size());
      if (fresh) {
        edges.push_back({u, w, 1, f, 0, 0, a});
        continue;
      }
      const auto it = edges.begin() + long(slot->second);
      if (it->count == 1) {
        it->f1 = f;
        it->same_direction = a == it->first_origin;
      }
      ++it->count;
    }
  }
  auto name = [&m](const Edge& e) {
    return "case.off: edge " + std::to_string(e.u) + "-" + std::to_string(e.w) + " from " + format_point(m.points[e.u]) +
           " to " + format_point(m.points[e.w]) + ": ";
  };
  for (const Edge& e : edges)
    if (e.count > 2) return name(e) + "non-manifold edge shared by " + std::to_string(e.count) + " facets";
  for (const Edge& e : edges)
    if (e.count == 2 && e.same_direction)
      return name(e) + "inconsistent orientation: facet " + std::to_string(e.f0) + " and facet " +
             std::to_string(e.f1) + " traverse this edge in the same direction";
  for (const Edge& e : edges)
    if (e.count == 1) return name(e) + "open mesh: the edge belongs to facet " + std::to_string(e.f0) + " only";
  return "";
}

// One to four random changes: a facet dropped, repeated or reversed (a
// mesh left without facets gets one triangle back).
void drop_repeat_or_reverse_facets(Mesh& m, std::mt19937_64& rng) {
  const std::size_t changes = 1 + rng() % 4;
  for (std::size_t c = 0; c < changes; ++c) {
    const std::size_t f = rng() % m.faces.size();
    switch (rng() % 3) {
      case 0: m.faces.erase(m.faces.begin() + long(f)); break;
      case 1: m.faces.push_back(m.faces[f]); break;
      default: std::reverse(m.faces[f].begin(), m.faces[f].end());
    }
    if (m.faces.empty()) m.faces.push_back({0, 1, 2});
  }
}

// For seeds 1..seeds: the mesh of make(rng), changed by
// drop_repeat_or_reverse_facets; where the reference finds an edge error,
// from_mesh must report that one.  Returns how many meshes had one.
template <class Make>
int compare_first_edge_errors(std::uint64_t seeds, Make&& make) {
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    Mesh m = make(rng);
    drop_repeat_or_reverse_facets(m, rng);
    const std::string expected = reference_edge_error(m);
    if (expected.empty()) continue;
    EXPECT_EQ(build_error(m), expected);
    ++compared;
  }
  return compared;
}

}  // namespace

// Soups of triangles and quadrilaterals on a few distinct points, with
// facets dropped, repeated and reversed: from_mesh's first topological error
// is the reference's (several errors of each kind in one soup, so the order
// matters).  Fixed seeds.
TEST(PolytopeBad, EdgeErrorsNameTheEdgeThatAppearsFirst) {
  const int compared = compare_first_edge_errors(400, [](std::mt19937_64& rng) {
    return rng() % 2 ? triangulated(octahedron_mesh()) : cube_mesh();
  });
  EXPECT_GT(compared, 300);
}

// The same in a mesh large enough for the edge matching, the linking and
// the fan test to run in blocks (6 000 facets), on threads (from 4096
// facets here): the error named is still the one on the edge (or vertex)
// that appears first.
TEST(PolytopeBad, EdgeErrorsInBlocksNameTheEdgeThatAppearsFirst) {
  const ParallelItems threads(4096);
  std::mt19937_64 cloud_rng(7);
  std::normal_distribution<double> g;
  std::vector<Point3> cloud;
  for (int i = 0; i < 3000; ++i) cloud.push_back(on_unit_sphere(cloud_rng, g));
  const Mesh big = triangulated(ConvexPolytope::hull(cloud).to_mesh());
  ASSERT_GT(big.faces.size(), 4096u);
  EXPECT_EQ(ConvexPolytope::from_mesh(big, "case.off").num_facets(), big.faces.size());
  const int compared = compare_first_edge_errors(60, [&](std::mt19937_64&) { return big; });
  EXPECT_GT(compared, 50);
}

// A mesh of triangles with double coordinates is validated without stored
// intervals (one orient3d per edge, a vertex test on doubles first); the
// same mesh scaled by 1/3 has rational coordinates and takes the general
// path, while every sign is the same.  Both must give the same polytope
// (vertex for vertex, facet for facet) or the same error.  Random convex
// meshes (fixed seeds) with one change each: none, a vertex pushed in or
// out, a facet reversed or dropped or repeated, every facet reversed, two
// points made equal, a vertex put on a neighbour's plane (a merge), a
// lattice with coplanar triangles (merges and dropped vertices).  Every
// twentieth mesh has some 18 000 vertices (36 000 facets), so that the
// loops over facets, edges and vertices run in several blocks on threads
// (from 4096 facets here): the same polytope and the same first error as
// the rational mesh.
TEST(Polytope, TrianglesOnDoublesAgreeWithRationals) {
  const ParallelItems threads(4096);
  std::map<std::string, int> seen;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::vector<Point3> cloud;
    const bool lattice = seed % 6 == 0;
    const bool big = seed % 20 == 3;
    const int n = big ? 17000 + int(rng() % 2000) : 8 + int(rng() % 60);
    std::normal_distribution<double> g;
    for (int i = 0; i < n; ++i) {
      const double x = g(rng), y = g(rng), z = g(rng), r = big ? std::sqrt(x * x + y * y + z * z) : 1.0;
      cloud.push_back(lattice ? P(long(rng() % 4), long(rng() % 4), long(rng() % 4)) : Point3(x / r, y / r, z / r));
    }
    Mesh m = triangulated(ConvexPolytope::hull(cloud).to_mesh());
    const Index nv = Index(m.points.size());
    const Index v = Index(rng() % nv);
    const Index f = Index(rng() % m.faces.size());
    switch (lattice ? 0 : rng() % 9) {
      case 0: break;
      case 1: m.points.set(v, Point3(m.points.approx(v).x * 0.5, m.points.approx(v).y * 0.5, m.points.approx(v).z * 0.5)); break;
      case 2: m.points.set(v, Point3(m.points.approx(v).x * 1.5, m.points.approx(v).y * 1.5, m.points.approx(v).z * 1.5)); break;
      case 3: std::reverse(m.faces[f].begin(), m.faces[f].end()); break;
      case 4: m.faces.erase(m.faces.begin() + f); break;
      case 5: m.faces.push_back(m.faces[f]); break;
      case 6:
        for (auto& poly : m.faces) std::reverse(poly.begin(), poly.end());
        break;
      case 7: m.points.set(m.faces[f][0], m.points.exact(m.faces[f][1])); break;
      default: {
        // The apex of f's neighbour across f's first edge moved onto f's
        // plane, along f's normal (exactly: a rational point, so this mesh
        // is rational; its doubles counterpart is the rounded point).
        const auto& poly = m.faces[f];
        const Point3 a = m.points.exact(poly[0]), b = m.points.exact(poly[1]), c = m.points.exact(poly[2]);
        Index apex = kNoIndex;
        for (const auto& o : m.faces)
          for (std::size_t i = 0; i < 3; ++i)
            if (o[i] == poly[1] && o[(i + 1) % 3] == poly[0]) apex = o[(i + 2) % 3];
        ASSERT_NE(apex, kNoIndex);
        const Point3 n = cross(b - a, c - a), d = m.points.exact(apex);
        const Rational t = dot(n, d - a) / dot(n, n);
        const Point3 on(d.x - t * n.x, d.y - t * n.y, d.z - t * n.z);
        m.points.set(apex, Point3(to_double(on.x), to_double(on.y), to_double(on.z)));
      }
    }
    ASSERT_TRUE(m.points.all_doubles());
    const Mesh t = thirds(m);
    ASSERT_EQ(t.points.form(), PointList::Form::rationals);
    ConvexPolytope a, b;
    // The same verdict, the place's coordinates aside (they scale).
    const std::string double_error = without_coordinates(outcome(m, a)),
                      rational_error = without_coordinates(outcome(t, b));
    ASSERT_EQ(double_error, rational_error);
    ++seen[double_error.empty() ? "valid" : double_error.substr(double_error.rfind(": ") + 2, 20)];
    if (big) ++seen[double_error.empty() ? "big valid" : "big error"];
    if (!double_error.empty()) continue;
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_facets(), b.num_facets());
    EXPECT_EQ(a.check_invariants(), "");
    for (Index i = 0; i < a.num_vertices(); ++i) {
      EXPECT_EQ(Point3(a.point(i).x / 3, a.point(i).y / 3, a.point(i).z / 3), b.point(i));
      EXPECT_EQ(a.source_vertex(i), b.source_vertex(i));
    }
    for (Index i = 0; i < a.num_facets(); ++i) EXPECT_EQ(a.facet_vertices(i), b.facet_vertices(i));
  }
  // The changes reach valid meshes and several kinds of error.
  std::string kinds;
  for (const auto& [k, n] : seen) kinds += k + " x" + std::to_string(n) + "; ";
  EXPECT_GE(seen.size(), 5u) << kinds;
  EXPECT_GE(seen["valid"], 30) << kinds;
  EXPECT_GE(seen["big valid"], 1) << kinds;
  EXPECT_GE(seen["big error"], 1) << kinds;
}

// Polygons on doubles against the same meshes scaled by 1/3 (rationals):
// the planarity test decides an exactly planar polygon on doubles at once
// (its first three corners not collinear, every other corner on their
// plane by orient3d) and every other polygon vertex by vertex as on
// rationals.  Untriangulated hulls of lattice points (exactly planar
// polygons), with: the start of every polygon rotated; an edge's midpoint
// inserted into both its facets (three collinear corners, first in some
// polygons); one vertex lifted off its facets' planes by 1/4 or by 2^-30
// (the error names the same vertex); the Minkowski sum of two such hulls
// (parallelograms).  Fixed seeds.
TEST(Polytope, PolygonsOnDoublesAgreeWithRationals) {
  auto lattice_hull = [](std::mt19937_64& rng) {
    std::vector<Point3> cloud;
    const int n = 8 + int(rng() % 40);
    for (int i = 0; i < n; ++i) cloud.push_back(P(long(rng() % 5), long(rng() % 5), long(rng() % 5)));
    return ConvexPolytope::hull(cloud);
  };
  std::map<std::string, int> seen;
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const int change = int(seed % 5);
    Mesh m = change == 4 ? minkowski_sum(lattice_hull(rng), lattice_hull(rng)).polytope.to_mesh()
                         : lattice_hull(rng).to_mesh();
    std::size_t polygons = 0;
    for (const auto& poly : m.faces) polygons += poly.size() > 3;
    if (change == 2) {  // a midpoint into both facets of an edge of the first polygon
      std::size_t f = 0;
      while (m.faces[f].size() < 4 && f + 1 < m.faces.size()) ++f;
      const Index a = m.faces[f][0], b = m.faces[f][1];
      const Index mid = Index(m.points.size());
      m.points.push_back(Point3((m.points.exact(a).x + m.points.exact(b).x) / 2,
                                (m.points.exact(a).y + m.points.exact(b).y) / 2,
                                (m.points.exact(a).z + m.points.exact(b).z) / 2));
      for (auto& poly : m.faces)
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Index u = poly[i], w = poly[(i + 1) % poly.size()];
          if ((u == a && w == b) || (u == b && w == a)) {
            poly.insert(poly.begin() + std::ptrdiff_t(i + 1), mid);
            break;
          }
        }
    }
    if (change == 1 || change == 2)
      for (auto& poly : m.faces) std::rotate(poly.begin(), poly.begin() + std::ptrdiff_t(rng() % poly.size()), poly.end());
    if (change == 3) {
      const Index v = Index(rng() % m.points.size());
      const Vec3d a = m.points.approx(v);
      m.points.set(v, Point3(a.x, a.y, a.z + (seed % 2 ? 0.25 : std::ldexp(1.0, -30))));
    }
    ASSERT_TRUE(m.points.all_doubles());
    ConvexPolytope a, b;
    const std::string double_error = outcome(m, a), rational_error = outcome(thirds(m), b);
    ASSERT_EQ(double_error, rational_error);
    ++seen[double_error.empty() ? (polygons ? "valid with polygons" : "valid")
                                : double_error.substr(double_error.rfind(": ") + 2, 16)];
    if (!double_error.empty()) continue;
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_facets(), b.num_facets());
    for (Index i = 0; i < a.num_facets(); ++i) EXPECT_EQ(a.facet_vertices(i), b.facet_vertices(i));
  }
  std::string kinds;
  for (const auto& [k, n] : seen) kinds += k + " x" + std::to_string(n) + "; ";
  EXPECT_GE(seen["valid with polygons"], 60) << kinds;
  EXPECT_GE(seen["is not planar (v"], 10) << kinds;
}

// Regression (validating the 10 242-vertex geodesic sphere of `minksum gen
// sphere:6`, double coordinates): the vertex test on doubles looks at each
// vertex's fan along the axis from a reference point, which was the mean
// of the points.  That is the centre of a symmetric solid, on all its mirror
// planes, and so were the fans of the vertices on those planes: 1 669 of
// the test's orient3d calls were nearly zero and went to exact arithmetic.
// The reference point now lies off them and the filter decides every call.
TEST(Polytope, SymmetricSphereVertexTestsNeedNoExactArithmetic) {
  const Mesh m = catalog_polytope("sphere:6").to_mesh();
  ASSERT_TRUE(m.points.all_doubles());
  reset_predicate_stats();
  const ConvexPolytope p = ConvexPolytope::from_mesh(m);
  const PredicateStats stats = predicate_stats();
  EXPECT_EQ(p.num_vertices(), 10242u);
  EXPECT_EQ(p.num_facets(), 20480u);
  EXPECT_GT(stats[PredicateId::orient3d].calls, 3u * 20480u);
  EXPECT_EQ(stats[PredicateId::orient3d].fallbacks, 0u);
}

namespace {
// The answer check_fan must give for directions d in the plane, seen along
// +z: the first step i with d[i] x d[i+1] <= 0, else -1 when the turns add
// up to one full turn and k otherwise.  Integer directions of at most a few
// units: each turn's angle (atan2) is off by far less than the half turn
// that would change the rounded total.
long fan_by_angles(const std::vector<std::array<long, 2>>& d) {
  const std::size_t k = d.size();
  for (std::size_t i = 0; i < k; ++i) {
    const auto &p = d[i], &q = d[(i + 1) % k];
    if (p[0] * q[1] - p[1] * q[0] <= 0) return long(i);
  }
  const double pi = std::acos(-1.0);
  double total = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const auto &p = d[i], &q = d[(i + 1) % k];
    double t = std::atan2(double(q[1]), double(q[0])) - std::atan2(double(p[1]), double(p[0]));
    if (t <= 0) t += 2 * pi;
    total += t;
  }
  return std::lround(total / (2 * pi)) == 1 ? -1 : long(k);
}
}  // namespace

// check_fan (validation's facet and vertex test) against the turns'
// angles, on fans in the plane lifted off it along the axis by random
// amounts and mapped by a random integer matrix of positive determinant:
// neither changes the answer.  Degenerate fans first: parallelograms (the
// facets a Minkowski sum has most of), a side along -(d0 + d1) or landing
// on d0 + d1 (the reference ray the test counts the turns by), stars and
// double turns.  Fixed seed.
TEST(PolytopeFan, CheckFanAgreesWithTheAnglesOfTheTurns) {
  using Fan = std::vector<std::array<long, 2>>;
  std::vector<Fan> fans = {
      {{1, 0}, {0, 1}, {-1, 0}, {0, -1}},
      {{2, 1}, {-1, 3}, {-2, -1}, {1, -3}},
      {{1, 0}, {0, 1}, {-1, -1}},
      {{1, 0}, {1, 1}, {-1, 0}, {-1, -1}},
      {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 0}, {0, -1}},
      {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}},
      {{3, 0}, {-2, 2}, {1, -3}, {1, 3}, {-2, -2}},
      {{1, 0}, {-1, 0}, {0, 1}},
      {{1, 0}, {0, 1}, {-1, 0}, {1, -1}},
  };
  std::mt19937_64 rng(20261124);
  auto small = [&](int r) { return long(rng() % std::uint64_t(2 * r + 1)) - r; };
  for (int n = 0; n < 3000; ++n) {
    const std::size_t k = 3 + rng() % 6;
    Fan d(k);
    for (auto& v : d) do v = {small(4), small(4)}; while (v[0] == 0 && v[1] == 0);
    auto angle = [](const std::array<long, 2>& v) { return std::atan2(double(v[1]), double(v[0])); };
    if (n % 3 != 2) std::sort(d.begin(), d.end(), [&](const auto& p, const auto& q) { return angle(p) < angle(q); });
    if (n % 3 == 1) {  // every second one: a star when k is odd
      Fan e;
      for (std::size_t i = 0; i < k; ++i) e.push_back(d[(2 * i) % k]);
      d = e;
    }
    fans.push_back(d);
  }
  std::map<long, int> answers;
  for (std::size_t n = 0; n < fans.size(); ++n) {
    const Fan& d = fans[n];
    const long expected = fan_by_angles(d);
    ++answers[expected < 0 ? -1 : expected == long(d.size()) ? 1 : 0];
    long m[3][3];
    long det = 0;
    do {
      for (auto& row : m)
        for (long& x : row) x = small(3);
      det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    } while (det <= 0);
    auto map = [&](long x, long y, long z) {
      return Point3(Rational(m[0][0] * x + m[0][1] * y + m[0][2] * z), Rational(m[1][0] * x + m[1][1] * y + m[1][2] * z),
                    Rational(m[2][0] * x + m[2][1] * y + m[2][2] * z));
    };
    std::vector<Point3> lifted;
    for (const auto& v : d) lifted.push_back(map(v[0], v[1], small(3)));
    EXPECT_EQ(check_fan(map(0, 0, 1), lifted), expected) << "fan " << n;
  }
  // Every kind of answer occurs: one turn, a failed step, a wrong winding.
  EXPECT_GT(answers[-1], 100);
  EXPECT_GT(answers[0], 100);
  EXPECT_GT(answers[1], 20);
}

// Facets are checked in blocks on threads: of several facets with zero
// area in different blocks, the error names the first in input order (the
// reference: an exact scan of every facet).  Fixed seeds; 36 000 facets,
// on threads from 4096 facets here.
TEST(PolytopeBad, ZeroAreaFacetsInSeveralBlocksNameTheFirst) {
  const ParallelItems threads(4096);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<Point3> cloud;
    for (int i = 0; i < 18000; ++i) cloud.push_back(on_unit_sphere(rng, g));
    Mesh m = triangulated(ConvexPolytope::hull(cloud).to_mesh());
    const std::size_t nf = m.faces.size();
    ASSERT_GT(nf, 32768u);
    // Three facets with no common vertex, made flat: their corners moved
    // onto a line far outside the sphere (exactly collinear doubles).
    std::vector<Index> flat;
    std::set<Index> used;
    while (flat.size() < 3) {
      const Index f = Index(2048 + rng() % (nf - 2048));
      const auto& poly = m.faces[f];
      if (used.count(poly[0]) || used.count(poly[1]) || used.count(poly[2])) continue;
      flat.push_back(f);
      const double x = 10.0 * double(flat.size());
      for (int k = 0; k < 3; ++k) {
        used.insert(poly[k]);
        m.points.set(poly[k], Point3(x + k, x + 2 * k, x + 3 * k));
      }
    }
    Index first = kNoIndex;
    for (Index f = 0; f < nf && first == kNoIndex; ++f) {
      const Point3 a = m.points.exact(m.faces[f][0]);
      if (is_zero(cross(m.points.exact(m.faces[f][1]) - a, m.points.exact(m.faces[f][2]) - a))) first = f;
    }
    ASSERT_EQ(first, *std::min_element(flat.begin(), flat.end()));
    EXPECT_EQ(build_error(m), "case.off: facet " + std::to_string(first) + ": has zero area");
  }
}

// build_if_convex, the probe of the commands that try the convex path first:
// the polytope build makes for a convex mesh; nullopt exactly where build
// refuses a closed 2-manifold surface as not one topological sphere (a
// genus, two components), as coplanar facets around a hole (a boss on a
// face) or as not convex in its last test (a reflex edge, a vertex, an
// L-shaped face: on one thread and, with 4 096 vertices, in parallel
// blocks); the same InputError as build for any other defect.
TEST(PolytopeBuilder, BuildIfConvexAnswersNotConvexWithoutAnError) {
  const Mesh cube = cube_mesh();
  const std::optional<ConvexPolytope> p = PolytopeBuilder::build_if_convex(cube, "cube.off");
  ASSERT_TRUE(p.has_value());
  const ConvexPolytope q = PolytopeBuilder::build(cube, "cube.off");
  EXPECT_EQ(p->num_vertices(), q.num_vertices());
  EXPECT_EQ(p->num_facets(), q.num_facets());
  EXPECT_EQ(p->volume(), q.volume());
  Mesh two = cube_mesh(1);
  const Mesh far = box_mesh(5, 6, 5, 6, 5, 6);
  for (const Point3& x : far.points) two.points.push_back(x);
  for (auto f : far.faces) {
    for (auto& v : f) v += 8;
    two.faces.push_back(f);
  }
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"lshape", "is not a convex polygon"},
      {"star:5", "is not a convex polygon"},
      {"tube", "not a topological sphere"},
      {"torus:8:4", "not a topological sphere"},
      {"torus:64:64", "not a topological sphere"},
      {"two cubes", "more than one connected component"}};
  for (const auto& [spec, why] : refused) {
    const Mesh m = spec == "two cubes" ? two : catalog_mesh(spec);
    EXPECT_FALSE(PolytopeBuilder::build_if_convex(m, spec).has_value()) << spec;
    EXPECT_NE(build_error(m).find(why), std::string::npos) << spec << ": " << build_error(m);
  }
  // A box with a boss on its top face, the top face as four coplanar quads
  // around the boss: one face with a hole, a sphere's topology.
  Mesh boss;
  boss.points = {P(0, 0, 0), P(3, 0, 0), P(3, 3, 0), P(0, 3, 0),   // bottom
                 P(0, 0, 3), P(3, 0, 3), P(3, 3, 3), P(0, 3, 3),   // top, outer
                 P(1, 1, 3), P(2, 1, 3), P(2, 2, 3), P(1, 2, 3),   // top, inner
                 P(1, 1, 4), P(2, 1, 4), P(2, 2, 4), P(1, 2, 4)};  // the boss's top
  boss.faces = {{0, 3, 2, 1},   {0, 1, 5, 4},   {1, 2, 6, 5},     {2, 3, 7, 6},     {3, 0, 4, 7},
                {4, 5, 9, 8},   {5, 6, 10, 9},  {6, 7, 11, 10},   {7, 4, 8, 11},    {8, 9, 13, 12},
                {9, 10, 14, 13}, {10, 11, 15, 14}, {11, 8, 12, 15}, {12, 13, 14, 15}};
  EXPECT_FALSE(PolytopeBuilder::build_if_convex(boss, "boss.off").has_value());
  EXPECT_NE(build_error(boss).find("coplanar facets form a polygon with a hole"), std::string::npos)
      << build_error(boss);
  EXPECT_EQ(mesh_volume(boss), Rational(28));  // still a valid solid: 27 + 1
  // A sphere's topology, not convex: a geodesic sphere of 10 242 vertices
  // (its points as doubles: the validation's parallel blocks of vertices)
  // with one vertex pushed in halfway to the centre.
  const Mesh sphere = catalog_mesh("sphere:5");
  Mesh dimpled;
  dimpled.faces = sphere.faces;
  for (Index v = 0; v < sphere.points.size(); ++v) {
    const Vec3d x = to_double(sphere.points.exact(v));
    dimpled.points.push_back(v == 0 ? Vec3d{x.x / 2, x.y / 2, x.z / 2} : x);
  }
  EXPECT_FALSE(PolytopeBuilder::build_if_convex(dimpled, "dimpled").has_value());
  EXPECT_NE(build_error(dimpled).find("not convex"), std::string::npos) << build_error(dimpled);
  Mesh bent = cube_mesh();
  bent.points.set(7, P(1, 1, 2));  // a quad no longer planar: refused before the last test
  EXPECT_THROW(PolytopeBuilder::build_if_convex(bent, "case.off"), NotConvexError);
  // Surfaces that are not closed 2-manifolds bound no convex polytope
  // either: no error from the probe (writable_polytope probes the rounded
  // surface of a sum, whose vertices may have merged), build's message.
  Mesh open = cube_mesh();
  open.faces.pop_back();
  Mesh flipped = cube_mesh();
  std::reverse(flipped.faces[0].begin(), flipped.faces[0].end());
  Mesh fin = cube_mesh();  // a fin on an edge: three facets on it
  fin.points.push_back(P(3, 3, 3));
  fin.faces.push_back({0, 1, Index(fin.points.size() - 1)});
  Mesh bowtie = cube_mesh(1);  // two cubes touching at (1, 1, 1), welded into one vertex
  const Mesh other = box_mesh(1, 2, 1, 2, 1, 2);
  for (const Point3& x : other.points) bowtie.points.push_back(x);
  for (auto f : other.faces) {
    for (auto& v : f) v += 8;
    bowtie.faces.push_back(f);
  }
  for (const auto& [name, m, why] : std::vector<std::tuple<std::string, Mesh, std::string>>{
           {"open", open, "open mesh"},
           {"flipped", flipped, "inconsistent orientation"},
           {"fin", fin, "non-manifold edge"},
           {"bowtie", bowtie, "non-manifold vertex"}}) {
    EXPECT_FALSE(PolytopeBuilder::build_if_convex(m, name).has_value()) << name;
    EXPECT_NE(build_error(m).find(why), std::string::npos) << name << ": " << build_error(m);
  }
}
