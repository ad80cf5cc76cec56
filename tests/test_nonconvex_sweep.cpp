// The boundary sweep of the non-convex sum (docs/nonconvex.md, "Method"):
// the same exact boundary as Hachenberger's decomposition method on every
// case (equal exact volume, vertex set, face planes, face, shell and
// non-manifold edge counts), the normal-cone culling, the pockets of the
// sweep dropped inside A + b, the local cones themselves and the exact
// point-in-solid test.  The CGAL minkowski_sum_3 oracle runs on the default
// (sweep) method in test_nonconvex_oracle.cpp.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include "nonconvex/sweep.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <set>

using namespace minksum;
using namespace minksum::testing;

namespace {

Solid solid(const std::string& spec) { return validate_solid(catalog_mesh(spec), spec); }

// [-2,2]^3 with the cavity [-1,1]^3.
Solid hollow_solid() { return validate_solid(hollow_cube(), "hollow"); }

void expect_same_as_decomposition(const Solid& a, const Solid& b, const std::string& name) {
  SCOPED_TRACE(name);
  const NonconvexSum s = minkowski_sum_nonconvex(a, b, {}, 0, Method::walk, NonconvexMethod::sweep);
  const NonconvexSum d = minkowski_sum_nonconvex(a, b, {}, 0, Method::walk, NonconvexMethod::decomposition);
  EXPECT_STREQ(s.method, "sweep");
  EXPECT_STREQ(d.method, "decomposition");
  expect_closed_oriented(s);
  expect_no_vertex_inside_an_edge(s.mesh);
  EXPECT_EQ(s.volume, d.volume);
  EXPECT_EQ(vertex_set(s.mesh), vertex_set(d.mesh));
  EXPECT_EQ(face_planes(s.mesh), face_planes(d.mesh));
  EXPECT_EQ(s.mesh.faces.size(), d.mesh.faces.size());
  EXPECT_EQ(s.shells, d.shells);
  EXPECT_EQ(s.non_manifold_edges, d.non_manifold_edges);
}

void expect_same_as_decomposition(const std::string& a, const std::string& b) {
  expect_same_as_decomposition(solid(a), solid(b), a + " + " + b);
}

}  // namespace

// ---------------------------------------------------------------------------
// The same boundary as the decomposition method.

TEST(NonconvexSweep, TubePlusRotatedCube) { expect_same_as_decomposition("tube", "cube@scale:1/4@rot:3"); }
TEST(NonconvexSweep, LShapePlusOctahedron) { expect_same_as_decomposition("lshape", "octahedron@scale:1/3"); }
TEST(NonconvexSweep, HoleThatClosesExactly) { expect_same_as_decomposition("tube", "box:1:1:1"); }
TEST(NonconvexSweep, HoleThatAlmostCloses) { expect_same_as_decomposition("tube", "box:1:1:1@scale:9/10"); }
TEST(NonconvexSweep, StarPlusIcosahedron) { expect_same_as_decomposition("star:5", "sphere:1@scale:1/4"); }
TEST(NonconvexSweep, RingPlusTetrahedron) { expect_same_as_decomposition("ring:6", "tetra@scale:1/8"); }
TEST(NonconvexSweep, GearPlusCylinder) { expect_same_as_decomposition("gear:6", "prism:8@scale:1/8"); }
TEST(NonconvexSweep, ConvexOperandFirst) { expect_same_as_decomposition("cube@scale:1/4@rot:3", "tube"); }
TEST(NonconvexSweep, NonConvexPlusNonConvex) { expect_same_as_decomposition("tube", "lshape@scale:1/4@rot:7"); }
TEST(NonconvexSweep, NonConvexPlusLargerNonConvex) { expect_same_as_decomposition("lshape@scale:1/4", "tube"); }
TEST(NonconvexSweep, TorusPlusBall) { expect_same_as_decomposition("torus:8:6", "sphere:1@scale:1/5"); }
TEST(NonconvexSweep, TorusPlusLargeBallClosesTheHole) {
  expect_same_as_decomposition("torus:8:6", "sphere:1@scale:3/4");
}
TEST(NonconvexSweep, AxisAlignedContactsOfTheLShape) { expect_same_as_decomposition("lshape", "box:1:1:1"); }

TEST(NonconvexSweep, CavityKeptShrinksAndVanishes) {
  const Solid h = hollow_solid();
  for (const char* b : {"box:1/2:1/2:1/2", "box:1:1:1", "box:2:2:2", "sphere:1@scale:1/2", "cube@rot:3@scale:1/3"})
    expect_same_as_decomposition(h, solid(b), std::string("hollow + ") + b);
}

// ---------------------------------------------------------------------------
// Culling and the pockets inside A + b.

TEST(NonconvexSweep, CullsTheFacetsOutsideTheNormalCones) {
  const NonconvexSum r = minkowski_sum_nonconvex(solid("torus:8:6"), solid("sphere:2@scale:1/10"));
  // 2 * 8 * 6 triangles swept as 80 convex polygons: the flat rings at the
  // top and the bottom (16 triangles each) as 8 trapezoids each.
  EXPECT_EQ(r.pieces_a, 80u);
  EXPECT_EQ(r.pieces_b, 1u);
  EXPECT_EQ(r.swept, 'a');
  EXPECT_EQ(r.candidate_facets + r.culled_facets, r.pair_facets);
  // A triangle's piece has about 90 facets; at most the triangle itself, a few
  // edge facets and those of its vertices' cones can be on the boundary.
  EXPECT_GT(r.culled_facets, 4 * r.candidate_facets);
  EXPECT_EQ(r.shells, 1u);
}

// [-2,2]^3 with the cavity [-1,1]^3, plus [-1/4,1/4]^3: the sweep of the
// cavity's surface and of the outer surface leave between them the pocket
// 5/4 <= |x|_inf <= 7/4, inside A + b.  The cavity's reflex corners keep a
// few facets of the box as candidates (their cones are over-approximated);
// they bound that pocket and are dropped with it.
TEST(NonconvexSweep, PocketInsideTheSolidIsDropped) {
  const NonconvexSum r = minkowski_sum_nonconvex(hollow_solid(), solid("box:1/2:1/2:1/2"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(9 * 9 * 9 - 3 * 3 * 3) / 8);
  EXPECT_EQ(r.mesh.faces.size(), 12u);
  EXPECT_EQ(r.mesh.points.size(), 16u);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_GE(r.dropped_components, 1u);
}

// ---------------------------------------------------------------------------
// The local cones and the point-in-solid test.

TEST(NonconvexSweep, ConesOfACube) {
  const Solid c = validate_solid(cube_mesh(1), "cube");
  const nonconvex_detail::SurfaceCones cones(c.triangles);
  auto p = [](int x, int y, int z) { return Point3(Rational(x), Rational(y), Rational(z)); };
  for (Index t = 0; t < cones.triangles(); ++t) {
    // A triangle's outward normal is in its own cone, the opposite one not.
    const auto& tri = cones.triangle(t);
    const Point3 n = cross(cones.point(tri[1]) - cones.point(tri[0]), cones.point(tri[2]) - cones.point(tri[0]));
    EXPECT_TRUE(cones.candidate(t, n));
    EXPECT_FALSE(cones.candidate(t, -n));
  }
  // Directions into the cube from a face are never candidates; the diagonal
  // (1,1,1) is one only for the triangles at the corner (1,1,1).
  std::size_t with_corner = 0, diagonal = 0;
  for (Index t = 0; t < cones.triangles(); ++t) {
    const auto& tri = cones.triangle(t);
    bool corner = false;
    for (Index v : tri) corner |= cones.point(v) == p(1, 1, 1);
    with_corner += corner;
    const bool cand = cones.candidate(t, p(1, 1, 1));
    diagonal += cand;
    if (cand) {
      EXPECT_TRUE(corner);
    }
  }
  EXPECT_EQ(diagonal, with_corner);
  EXPECT_GT(diagonal, 0u);
}

TEST(NonconvexSweep, ReflexEdgeHasNoConeOfItsOwn) {
  // The L's reflex edge runs along z at (0, 0), between its faces on y = 0
  // (normal +y) and x = 0 (normal +x).  Perpendicular to it, (-1, 1, 0) puts
  // the edge at the top of the triangles on y = 0 and (1, -1, 0) at the top of
  // those on x = 0: the edge's own cone is empty and its end vertices' cones
  // hold neither direction.
  const Solid l = solid("lshape");
  const nonconvex_detail::SurfaceCones cones(l.triangles);
  const Point3 u(Rational(-1), Rational(1), Rational(0));
  std::size_t at_edge = 0;
  for (Index t = 0; t < cones.triangles(); ++t) {
    const auto& tri = cones.triangle(t);
    int on_axis = 0;
    for (Index v : tri) on_axis += sgn(cones.point(v).x) == 0 && sgn(cones.point(v).y) == 0;
    if (on_axis == 2) {
      ++at_edge;
      EXPECT_FALSE(cones.candidate(t, u)) << "triangle " << t;
      EXPECT_FALSE(cones.candidate(t, -u)) << "triangle " << t;
    }
  }
  EXPECT_EQ(at_edge, 2u);
}

// The ray test skips the triangles whose boxes the ray's line provably
// misses (kernel/line_box.hpp): the same answers as testing every triangle,
// at points inside, outside and near the surface of a torus (grid points,
// many on the planes and lines of the rays through the surface's points).
TEST(NonconvexSweep, PointInSolidBoxesChangeNoAnswer) {
  const Solid t = solid("torus:16:8");
  const nonconvex_detail::SurfaceCones cones(t.triangles);
  std::vector<Point3> pts;
  std::vector<std::array<Index, 3>> tris;
  for (Index v = 0; v < Index(t.triangles.points.size()); ++v) pts.push_back(t.triangles.points[v]);
  for (const auto& f : t.triangles.faces) tris.push_back({f[0], f[1], f[2]});
  std::size_t inside = 0, cases = 0;
  for (int i = -12; i <= 12; ++i)
    for (int j = -12; j <= 12; j += 3)
      for (int k = -4; k <= 4; ++k) {
        const Point3 q(Rational(i, 8), Rational(j, 8), Rational(k, 9));
        bool plain = false, on = false;
        try {
          plain = nonconvex_detail::strictly_inside(q, pts, tris);
        } catch (const std::logic_error&) {
          on = true;
        }
        if (on) {
          EXPECT_THROW(cones.strictly_inside(q), std::logic_error);
          continue;
        }
        ++cases;
        inside += plain;
        EXPECT_EQ(cones.strictly_inside(q), plain) << i << " " << j << " " << k;
      }
  EXPECT_GT(inside, 20u);
  EXPECT_GT(cases - inside, 20u);
}

TEST(NonconvexSweep, PointInSolidIsExact) {
  const Solid h = hollow_solid();
  const nonconvex_detail::SurfaceCones cones(h.triangles);
  auto p = [](Rational x, Rational y, Rational z) { return Point3(x, y, z); };
  EXPECT_FALSE(cones.strictly_inside(p(0, 0, 0)));                      // in the cavity
  EXPECT_TRUE(cones.strictly_inside(p(Rational(3, 2), 0, 0)));          // in the wall
  EXPECT_TRUE(cones.strictly_inside(p(Rational(3, 2), Rational(3, 2), Rational(3, 2))));  // on many rays' planes
  EXPECT_FALSE(cones.strictly_inside(p(3, 0, 0)));                      // outside
  EXPECT_TRUE(cones.strictly_inside(p(Rational(-199, 100), Rational(199, 100), 0)));  // near an edge
  EXPECT_FALSE(cones.strictly_inside(p(Rational(201, 100), Rational(2), Rational(2))));
  EXPECT_THROW(cones.strictly_inside(p(2, 0, 0)), std::logic_error);    // on the surface
}

// ---------------------------------------------------------------------------
// The pieces t ⊕ B from the Gaussian maps (triangle_sum.cpp) against the
// exact hull of the nine or more sums t_i + b_j: the same facet planes, the
// same candidates (SurfaceCones::candidate on the hull's facets) and the
// same vertex loops, on triangles with small integer coordinates, which are
// often parallel to B's facets and edges or perpendicular to its normals.

namespace {

// A closed surface holding the triangle t as its triangle 0: the
// tetrahedron of t and an apex below it.
Mesh tetrahedron_on(const std::array<Point3, 3>& t) {
  const Point3 n = cross(t[1] - t[0], t[2] - t[0]);
  const Point3 apex = Rational(1, 3) * (t[0] + t[1] + t[2]) - n;
  Mesh m;
  for (const Point3& p : t) m.points.push_back(p);
  m.points.push_back(apex);
  m.faces = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  return m;
}

// Loops compared up to rotation.
std::vector<Point3> rotated_to_smallest(std::vector<Point3> loop) {
  auto less = [](const Point3& a, const Point3& b) {
    for (int k = 0; k < 3; ++k)
      if (int c = cmp(a[k], b[k])) return c < 0;
    return false;
  };
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end(), less), loop.end());
  return loop;
}

// `scaled` counts the piece's lazy planes whose doubles are scaled.
void expect_piece_is_the_hull(const std::array<Point3, 3>& t, const ConvexPolytope& b, const std::string& trace,
                              std::size_t& scaled) {
  SCOPED_TRACE(trace);
  const Mesh surface = tetrahedron_on(t);
  const nonconvex_detail::SurfaceCones cones(surface);
  const nonconvex_detail::SweptPolytope swept(b);
  const nonconvex_detail::Piece piece = swept.sum(cones, 0);
  std::vector<Point3> sums;
  for (const Point3& p : t)
    for (const Point3& q : b.points()) sums.push_back(p + q);
  const ConvexPolytope hull = ConvexPolytope::hull(sums, "hull");
  // Planes: the same set, each once.
  std::vector<Plane> built, expected;
  for (Index k = 0; k < piece.num_planes(); ++k) built.push_back(piece.plane(k));
  for (Index f = 0; f < hull.num_facets(); ++f) expected.push_back(hull.plane(f));
  // Every plane is lazy (the facets of B moved, t plus a vertex or an edge
  // of B, an edge of t plus an edge of B).  Its doubles: the primitive
  // normal's and the offset along it, times 2^-k (k = 0 unless the normal
  // has 480 bits or more, then its longest integer becomes 470 bits long),
  // each rounded towards zero from the built plane's own value (mpq_get_d
  // truncates), so that equal planes have equal doubles (the union's key
  // for them), usable in the filter however long the integers; a
  // candidate's held plane is the one its tag and code build.
  EXPECT_TRUE(piece.planes.empty());
  for (Index k = 0; k < piece.lazy.size(); ++k) {
    const Plane& h = built[k];
    Integer g;
    mpz_gcd(g.get_mpz_t(), h.a.get_mpz_t(), h.b.get_mpz_t());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), h.c.get_mpz_t());
    const Integer m[3] = {h.a / g, h.b / g, h.c / g};
    std::size_t longest = 0;
    for (const Integer& x : m) longest = std::max(longest, mpz_sizeinbase(x.get_mpz_t(), 2));
    const long scale = longest >= 480 ? long(longest) - 470 : 0;
    EXPECT_EQ(nonconvex_detail::lazy_plane_scale(m), scale) << "lazy plane " << k;
    scaled += scale > 0;
    auto truncated = [&](const Rational& x) {
      Rational y = x;
      mpq_div_2exp(y.get_mpq_t(), y.get_mpq_t(), mp_bitcnt_t(scale));
      return mpq_get_d(y.get_mpq_t());
    };
    const nonconvex_detail::LazyPlane& l = piece.lazy[k];
    EXPECT_EQ(l.a, truncated(Rational(m[0]))) << "lazy plane " << k;
    EXPECT_EQ(l.b, truncated(Rational(m[1]))) << "lazy plane " << k;
    EXPECT_EQ(l.c, truncated(Rational(m[2]))) << "lazy plane " << k;
    EXPECT_EQ(l.d, truncated(Rational(h.d, g))) << "lazy plane " << k;
    EXPECT_TRUE(l.filtered) << "lazy plane " << k;
    EXPECT_EQ(swept.build(piece, k), h) << "lazy plane " << k;
  }
  EXPECT_GE(piece.lazy.size(), b.num_facets());
  std::sort(built.begin(), built.end());
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(built, expected);
  // Candidates and their loops.
  std::vector<std::pair<Plane, std::vector<Point3>>> got, want;
  for (std::size_t c = 0; c < piece.candidates.size(); ++c)
    got.emplace_back(piece.plane(piece.candidates[c]), rotated_to_smallest(piece.loops[c]));
  for (Index f = 0; f < hull.num_facets(); ++f) {
    const Plane& h = hull.plane(f);
    if (!cones.candidate(0, Point3(Rational(h.a), Rational(h.b), Rational(h.c)))) continue;
    std::vector<Point3> loop;
    for (Index v : hull.facet_vertices(f)) loop.push_back(hull.point(v));
    want.emplace_back(h, rotated_to_smallest(loop));
  }
  auto by_plane = [](const auto& x, const auto& y) { return x.first < y.first; };
  std::sort(got.begin(), got.end(), by_plane);
  std::sort(want.begin(), want.end(), by_plane);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].first, want[i].first);
    EXPECT_EQ(got[i].second, want[i].second) << "candidate " << i;
  }
  // The box holds every point.
  for (const Point3& s : sums) {
    const Vec3d d = to_double(s);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(piece.lo[k], d[k]);
      EXPECT_GE(piece.hi[k], d[k]);
    }
  }
}

}  // namespace

TEST(NonconvexSweep, GaussianMapPiecesAreTheHullsOfTheSums) {
  const char* operands[] = {"cube",   "box:1:2:3@rot:3", "octahedron", "tetra",
                            "sphere:1", "prism:6",       "random:12:5", "cube@scale:1/10"};
  std::size_t scaled_short = 0, scaled_long = 0;
  for (const char* spec : operands) {
    const ConvexPolytope b = catalog_polytope(spec);
    for (std::uint64_t seed = 1; seed <= 60; ++seed) {
      std::mt19937_64 rng(seed);
      std::uniform_int_distribution<int> coordinate(-2, 2);
      std::array<Point3, 3> t;
      for (;;) {
        for (Point3& p : t) p = Point3(Rational(coordinate(rng)), Rational(coordinate(rng)), Rational(coordinate(rng)));
        if (!is_zero(cross(t[1] - t[0], t[2] - t[0]))) break;
      }
      if (seed % 3 == 0)  // rational coordinates too
        for (Point3& p : t) p = Rational(2, 7) * p;
      if (seed % 5 == 0) {
        // Coordinates of several hundred bits, as an erosion's vertices have:
        // each corner moved by its own tiny rational, so that the edge
        // directions, and the normals of t's edges plus B's edges, have
        // integers of 480 bits and more (their doubles scaled).
        for (std::size_t c = 0; c < 3; ++c) {
          const Rational tiny(Integer(1), (Integer(1) << 301) + Integer(2 * c + 3) * (Integer(1) << 150) + 1);
          t[c] = t[c] + Point3(tiny * (c + 1), tiny * (c + 2), tiny * (c + 3));
        }
      }
      std::size_t& count = seed % 5 == 0 ? scaled_long : scaled_short;
      expect_piece_is_the_hull(t, b, std::string(spec) + ", seed " + std::to_string(seed), count);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  // Doubles are scaled exactly where the normals are long: never for small
  // coordinates, for many planes of the long ones.
  EXPECT_EQ(scaled_short, 0u);
  EXPECT_GT(scaled_long, 100u);
}

// Each candidate facet once over a whole surface (SurfaceCones::keeps): the
// candidates of all the pieces t ⊕ B, as (plane, loop), are the facets of
// the exact hulls of the sums t + B that SurfaceCones::candidate accepts, as
// a set, and no two pieces hold the same one.  Before, the two triangles of
// a convex edge both kept its edge ⊕ edge and facet ⊕ edge facets, and every
// triangle at a vertex its facet ⊕ vertex facets.
TEST(NonconvexSweep, EachCandidateFacetIsBuiltOnce) {
  const std::pair<const char*, const char*> cases[] = {{"torus:8:6", "sphere:1@scale:1/5"},
                                                       {"lshape", "box:1:1:1"},
                                                       {"tube", "cube@scale:1/4@rot:3"},
                                                       {"star:5", "sphere:1@scale:1/4"},
                                                       {"gear:6", "prism:8@scale:1/8"}};
  for (const auto& [a, b] : cases) {
    SCOPED_TRACE(std::string(a) + " + " + b);
    const Solid s = solid(a);
    const ConvexPolytope p = catalog_polytope(b);
    const nonconvex_detail::SurfaceCones cones(s.triangles);
    const nonconvex_detail::SweptPolytope swept(p);
    std::vector<std::pair<Plane, std::vector<Point3>>> got;
    std::set<std::pair<Plane, std::vector<Point3>>> want;
    for (Index t = 0; t < s.triangles.faces.size(); ++t) {
      const nonconvex_detail::Piece piece = swept.sum(cones, t);
      for (std::size_t c = 0; c < piece.candidates.size(); ++c)
        got.emplace_back(piece.plane(piece.candidates[c]), rotated_to_smallest(piece.loops[c]));
      std::vector<Point3> sums;
      for (Index v : s.triangles.faces[t])
        for (const Point3& q : p.points()) sums.push_back(s.triangles.points[v] + q);
      const ConvexPolytope hull = ConvexPolytope::hull(sums, "hull");
      for (Index f = 0; f < hull.num_facets(); ++f) {
        const Plane& h = hull.plane(f);
        if (!cones.candidate(t, Point3(Rational(h.a), Rational(h.b), Rational(h.c)))) continue;
        std::vector<Point3> loop;
        for (Index v : hull.facet_vertices(f)) loop.push_back(hull.point(v));
        want.emplace(h, rotated_to_smallest(loop));
      }
    }
    const std::set<std::pair<Plane, std::vector<Point3>>> distinct(got.begin(), got.end());
    EXPECT_EQ(distinct.size(), got.size()) << "a candidate facet held by two pieces";
    EXPECT_EQ(distinct, want);
  }
}

// SurfaceCones::merge_coplanar: every triangle in exactly one polygon, whose
// corners include its triangles' corners; each polygon strictly convex,
// counter-clockwise seen from outside and in its triangles' common plane
// (their primitive normals equal), and exactly the union of its triangles
// (the sum of their cross products is the polygon's: the same area, and the
// triangles do not overlap); every edge of a polygon is the edge of the
// triangle it names.  Exact counts: the cube's 12 triangles as its 6
// squares, the torus:8:6's 96 as 80 (the flat rings at the top and the
// bottom, 16 triangles each, as 8 trapezoids each), the hollow cube's 24 as
// 12 squares.  Before merging, polygon g is triangle g.
TEST(NonconvexSweep, CoplanarTrianglesMergeIntoStrictlyConvexPolygons) {
  struct Case {
    const char* name;
    Solid solid;
    std::size_t polygons;  // 0: not asserted
  };
  const Case cases[] = {{"cube", solid("cube"), 6},      {"torus:8:6", solid("torus:8:6"), 80},
                        {"hollow", hollow_solid(), 12},  {"lshape", solid("lshape"), 0},
                        {"tube", solid("tube"), 0},      {"gear:6", solid("gear:6"), 0}};
  const Point3 zero(Rational(0), Rational(0), Rational(0));
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    nonconvex_detail::SurfaceCones cones(c.solid.triangles);
    ASSERT_EQ(cones.polygons(), cones.triangles());
    for (Index t = 0; t < cones.triangles(); ++t)
      EXPECT_EQ(cones.polygon(t).corners, std::vector<Index>(cones.triangle(t).begin(), cones.triangle(t).end()));
    cones.merge_coplanar();
    if (c.polygons) {
      EXPECT_EQ(cones.polygons(), c.polygons);
    }
    EXPECT_LT(cones.polygons(), cones.triangles());
    std::vector<Point3> area(cones.polygons(), zero);
    for (Index t = 0; t < cones.triangles(); ++t) {
      const Index g = cones.polygon_of(t);
      ASSERT_LT(g, cones.polygons());
      const auto& corners = cones.polygon(g).corners;
      const auto& q = cones.triangle(t);
      for (Index v : q) EXPECT_NE(std::find(corners.begin(), corners.end(), v), corners.end()) << "triangle " << t;
      EXPECT_EQ(cones.normal(t), cones.normal(cones.polygon(g).edge_triangle[0])) << "triangle " << t;
      area[g] = area[g] + cross(cones.point(q[1]) - cones.point(q[0]), cones.point(q[2]) - cones.point(q[0]));
    }
    for (Index g = 0; g < cones.polygons(); ++g) {
      const auto& p = cones.polygon(g);
      const std::size_t m = p.corners.size();
      ASSERT_GE(m, 3u);
      ASSERT_LE(m, nonconvex_detail::SurfaceCones::kMaxCorners);
      const Point3& n = cones.normal(p.edge_triangle[0]);
      const Point3& o = cones.point(p.corners[0]);
      Point3 fan = zero;
      for (std::size_t k = 0; k < m; ++k) {
        const Point3& a = cones.point(p.corners[k]);
        const Point3& b = cones.point(p.corners[(k + 1) % m]);
        const Point3& d = cones.point(p.corners[(k + 2) % m]);
        EXPECT_EQ(sgn(dot(n, a - o)), 0) << "polygon " << g << " corner " << k;
        EXPECT_GT(sgn(dot(n, cross(b - a, d - b))), 0) << "polygon " << g << " corner " << (k + 1) % m;
        const auto& tri = cones.triangle(p.edge_triangle[k]);
        const int j = p.edge_index[k];
        EXPECT_EQ(tri[j], p.corners[k]) << "polygon " << g << " edge " << k;
        EXPECT_EQ(tri[(j + 1) % 3], p.corners[(k + 1) % m]) << "polygon " << g << " edge " << k;
        EXPECT_EQ(cones.polygon_of(p.edge_triangle[k]), g);
        if (k >= 1 && k + 1 < m) fan = fan + cross(a - o, b - o);
      }
      EXPECT_EQ(fan, area[g]) << "polygon " << g;
    }
  }
}

// The pieces P ⊕ B of merged polygons (the sweep's pieces): every plane
// once, and they are the facets of the exact hull of P's corners plus B's
// vertices, each built from its tag and code; the box holds every point;
// over a whole surface the candidates are the hull facets that
// polygon_candidate accepts, each held by one piece only (polygon_keeps).
TEST(NonconvexSweep, MergedPolygonPiecesAreTheHullsOfTheirSums) {
  const std::pair<const char*, const char*> cases[] = {{"cube", "sphere:1@scale:1/4"},
                                                       {"lshape", "box:1:1:1"},
                                                       {"torus:8:6", "sphere:1@scale:1/5"},
                                                       {"tube", "cube@scale:1/4@rot:3"},
                                                       {"gear:6", "prism:8@scale:1/8"}};
  for (const auto& [a, b] : cases) {
    SCOPED_TRACE(std::string(a) + " + " + b);
    const Solid s = solid(a);
    nonconvex_detail::SurfaceCones cones(s.triangles);
    cones.merge_coplanar();
    const ConvexPolytope p = catalog_polytope(b);
    const nonconvex_detail::SweptPolytope swept(p);
    std::vector<std::pair<Plane, std::vector<Point3>>> got;
    std::set<std::pair<Plane, std::vector<Point3>>> want;
    std::size_t larger = 0;  // polygons of more than 3 corners
    for (Index g = 0; g < cones.polygons(); ++g) {
      SCOPED_TRACE("polygon " + std::to_string(g));
      const auto& polygon = cones.polygon(g);
      larger += polygon.corners.size() > 3;
      const nonconvex_detail::Piece piece = swept.sum(cones, g);
      std::vector<Point3> sums;
      for (Index v : polygon.corners)
        for (const Point3& q : p.points()) sums.push_back(cones.point(v) + q);
      const ConvexPolytope hull = ConvexPolytope::hull(sums, "hull");
      std::vector<Plane> built, expected;
      for (Index k = 0; k < piece.num_planes(); ++k) {
        built.push_back(piece.plane(k));
        EXPECT_EQ(swept.build(piece, k), built.back()) << "plane " << k;
      }
      for (Index f = 0; f < hull.num_facets(); ++f) expected.push_back(hull.plane(f));
      std::sort(built.begin(), built.end());
      std::sort(expected.begin(), expected.end());
      ASSERT_EQ(built, expected);
      for (std::size_t c = 0; c < piece.candidates.size(); ++c)
        got.emplace_back(piece.plane(piece.candidates[c]), rotated_to_smallest(piece.loops[c]));
      for (Index f = 0; f < hull.num_facets(); ++f) {
        const Plane& h = hull.plane(f);
        const Point3 u(Rational(h.a), Rational(h.b), Rational(h.c));
        const Vec3d ua = to_double(u);
        if (!cones.polygon_candidate(g, RoundedPoint3{u, ua})) continue;
        std::vector<Point3> loop;
        for (Index v : hull.facet_vertices(f)) loop.push_back(hull.point(v));
        want.emplace(h, rotated_to_smallest(loop));
      }
      for (const Point3& x : sums) {
        const Vec3d d = to_double(x);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(piece.lo[k], d[k]);
          EXPECT_GE(piece.hi[k], d[k]);
        }
      }
    }
    EXPECT_GT(larger, 0u);
    const std::set<std::pair<Plane, std::vector<Point3>>> distinct(got.begin(), got.end());
    EXPECT_EQ(distinct.size(), got.size()) << "a candidate facet held by two pieces";
    EXPECT_EQ(distinct, want);
  }
}

// Whole surfaces swept by convex operands: a curved genus-1 surface, a
// box-like solid with parallel facets, a tube by a rotated cube, a gear by a prism.
const std::pair<const char*, const char*> kWholeSurfaces[] = {{"torus:8:6", "sphere:1@scale:1/5"},
                                                             {"lshape", "box:1:1:1"},
                                                             {"tube", "cube@scale:1/4@rot:3"},
                                                             {"gear:6", "prism:8@scale:1/8"}};

// PlaneBuilder::contains, which the union asks before an exact test: a
// plane said to hold a labelled point (a point of a candidate's loop, the
// sum of a surface point and a vertex of B) holds it exactly, over every
// pair of pieces of whole surfaces; every candidate's own points are said
// to be on its own plane; and neighbouring pieces share many such points.
TEST(NonconvexSweep, ContainsSaysOnlyWhatIsExactlyTrue) {
  for (const auto& [a, b] : kWholeSurfaces)
  for (const bool merged : {false, true}) {  // triangles, then convex polygons (merge_coplanar)
    SCOPED_TRACE(std::string(a) + " + " + b + (merged ? ", polygons" : ", triangles"));
    const Solid s = solid(a);
    nonconvex_detail::SurfaceCones cones(s.triangles);
    if (merged) cones.merge_coplanar();
    const ConvexPolytope p = catalog_polytope(b);
    const nonconvex_detail::SweptPolytope swept(p);
    std::vector<nonconvex_detail::Piece> pieces;
    for (Index g = 0; g < cones.polygons(); ++g) pieces.push_back(swept.sum(cones, g));
    std::vector<std::pair<std::uint64_t, const Point3*>> labelled;
    for (const auto& piece : pieces) {
      ASSERT_EQ(piece.labels.size(), piece.loops.size());
      for (std::size_t c = 0; c < piece.loops.size(); ++c) {
        if (piece.labels[c].empty()) continue;
        ASSERT_EQ(piece.labels[c].size(), piece.loops[c].size());
        for (std::size_t k = 0; k < piece.loops[c].size(); ++k) {
          labelled.emplace_back(piece.labels[c][k], &piece.loops[c][k]);
          EXPECT_TRUE(swept.contains(piece, piece.candidates[c], piece.labels[c][k]));
        }
      }
    }
    ASSERT_FALSE(labelled.empty());
    std::size_t said = 0, elsewhere = 0;
    for (const auto& piece : pieces)
      for (Index k = 0; k < piece.num_planes(); ++k) {
        const Plane h = piece.plane(k);
        for (const auto& [label, point] : labelled) {
          if (!swept.contains(piece, k, label)) continue;
          ++said;
          EXPECT_EQ(h.side(*point), 0) << "plane " << k << ", label " << label;
          elsewhere += std::find(piece.candidates.begin(), piece.candidates.end(), k) == piece.candidates.end();
        }
      }
    EXPECT_GT(said, labelled.size());
    EXPECT_GT(elsewhere, 0u);  // on planes that are not candidates
  }
}

// The surface's edges are numbered once each (SurfaceCones::edge_of: the two
// triangles at an edge run it opposite ways), and the pieces built with the
// tables of SweptPolytope::prepare (the lazy planes' doubles per point, the
// signs of the edges along B's facet normals, the memo of the vertex cones'
// test) are the pieces built without them: the same planes, lazy doubles,
// tags and codes, candidates, loops and labels.
TEST(NonconvexSweep, PreparedPiecesAreThePiecesWithoutTables) {
  for (const auto& [a, b] : kWholeSurfaces)
  for (const bool merged : {false, true}) {  // triangles, then convex polygons (merge_coplanar)
    SCOPED_TRACE(std::string(a) + " + " + b + (merged ? ", polygons" : ", triangles"));
    const Solid s = solid(a);
    nonconvex_detail::SurfaceCones cones(s.triangles);
    if (merged) cones.merge_coplanar();
    std::map<std::pair<Index, Index>, int> runs;  // directed edge -> uses
    for (Index t = 0; t < cones.triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const Index e = cones.edge_of(t, k);
        ASSERT_LT(e >> 1, cones.edges());
        const auto& ends = cones.edge_ends(e >> 1);
        const auto& c = cones.triangle(t);
        EXPECT_EQ(c[k], ends[e & 1]);
        EXPECT_EQ(c[(k + 1) % 3], ends[1 - (e & 1)]);
        ++runs[{e >> 1, e & 1}];
      }
    EXPECT_EQ(runs.size(), 2 * cones.edges());
    for (const auto& [edge, uses] : runs) EXPECT_EQ(uses, 1);
    const ConvexPolytope p = catalog_polytope(b);
    const nonconvex_detail::SweptPolytope plain(p);
    nonconvex_detail::SweptPolytope prepared(p);
    prepared.prepare(cones, 0);
    for (Index t = 0; t < cones.polygons(); ++t) {
      const nonconvex_detail::Piece x = plain.sum(cones, t), y = prepared.sum(cones, t);
      ASSERT_EQ(x.num_planes(), y.num_planes());
      for (Index k = 0; k < x.num_planes(); ++k) EXPECT_EQ(x.plane(k), y.plane(k)) << t << " " << k;
      ASSERT_EQ(x.lazy.size(), y.lazy.size());
      for (std::size_t k = 0; k < x.lazy.size(); ++k) {
        EXPECT_EQ(x.lazy[k].a, y.lazy[k].a);
        EXPECT_EQ(x.lazy[k].b, y.lazy[k].b);
        EXPECT_EQ(x.lazy[k].c, y.lazy[k].c);
        EXPECT_EQ(x.lazy[k].d, y.lazy[k].d);
        EXPECT_EQ(x.lazy[k].filtered, y.lazy[k].filtered);
        EXPECT_EQ(x.lazy[k].tag, y.lazy[k].tag);
        EXPECT_EQ(x.lazy[k].code, y.lazy[k].code);
        EXPECT_EQ(x.lazy[k].exact, y.lazy[k].exact);
      }
      EXPECT_EQ(x.labels, y.labels);
      EXPECT_EQ(x.candidates, y.candidates);
      EXPECT_EQ(x.loops, y.loops);
    }
  }
}

// Two non-convex operands: a facet of t ⊕ O_j (O_j a convex piece of O)
// whose face of O_j cannot touch O's surface with the facet's normal in O's
// local cone there is culled (SweptPolytope::on_surface).  The candidates
// with O's surface are a subset of those without; every facet of O_j whose
// oriented plane holds a triangle of O stays; most of the candidates of the
// pieces' inner cuts go (on torus:8:4 ⊕ a small torus, of coordinates that
// are doubles, as the 1 024 ⊕ 256 row of the benchmark: there 204 616
// candidates without, 5 640 with); the sum is the decomposition method's.
TEST(NonconvexSweep, FacetsOnTheInnerCutsOfTheOtherOperandAreCulled) {
  const Solid s = solid("torus:8:4");
  const Solid o = solid("torus:6:4@scale:1/4");
  const nonconvex_detail::SurfaceCones cones(s.triangles), surface(o.triangles);
  std::set<Plane> triangle_planes;
  for (const auto& f : o.triangles.faces) {
    const Point3& p0 = o.triangles.points[f[0]];
    triangle_planes.insert(
        canonical_plane(cross(o.triangles.points[f[1]] - p0, o.triangles.points[f[2]] - p0), p0));
  }
  std::size_t with = 0, without = 0, surface_facets = 0;
  for (const ConvexPolytope& piece : convex_decomposition(o)) {
    const nonconvex_detail::SweptPolytope culled(piece, &surface), whole(piece);
    for (Index f = 0; f < piece.num_facets(); ++f)
      if (triangle_planes.count(piece.plane(f))) {
        ++surface_facets;
        EXPECT_TRUE(culled.facet_on_surface(f));
      }
    for (Index t = 0; t < s.triangles.faces.size(); ++t) {
      const nonconvex_detail::Piece a = culled.sum(cones, t), b = whole.sum(cones, t);
      std::set<Plane> kept;
      for (Index c : b.candidates) kept.insert(b.plane(c));
      for (Index c : a.candidates) EXPECT_TRUE(kept.count(a.plane(c))) << "a candidate only with the surface";
      with += a.candidates.size();
      without += b.candidates.size();
    }
  }
  EXPECT_GT(surface_facets, 0u);
  EXPECT_LT(3 * with, without);
  expect_same_as_decomposition(s, o, "torus:8:4 + torus:6:4@scale:1/4");
}

// ---------------------------------------------------------------------------
// Properties on a larger case (the decomposition would take minutes here).

// torus:32:16 (1 024 triangles) ⊕ a small ball: one closed genus-1 surface
// (V - E + F = 0), the sum contains the torus (larger volume), and
// translating the torus translates the sum exactly.
TEST(NonconvexSweep, LargeTorusPlusBallProperties) {
  const Solid t = solid("torus:32:16");
  const Solid b = solid("sphere:1@scale:1/20");
  const NonconvexSum r = minkowski_sum_nonconvex(t, b);
  expect_closed_oriented(r);
  EXPECT_EQ(r.shells, 1u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  std::set<std::pair<Index, Index>> edges;
  for (const auto& f : r.mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i)
      edges.insert({std::min(f[i], f[(i + 1) % f.size()]), std::max(f[i], f[(i + 1) % f.size()])});
  EXPECT_EQ(long(r.mesh.points.size()) - long(edges.size()) + long(r.mesh.faces.size()), 0L);
  EXPECT_GT(r.volume, t.volume);
  EXPECT_GT(r.culled_facets, 10 * r.candidate_facets);

  const Solid moved = solid("torus:32:16@translate:1/3,-2,5/7");
  const NonconvexSum m = minkowski_sum_nonconvex(moved, b);
  const Point3 shift(Rational(1, 3), Rational(-2), Rational(5, 7));
  std::set<Point3> expected;
  for (const Point3& p : vertex_set(r.mesh)) expected.insert(p + shift);
  EXPECT_EQ(vertex_set(m.mesh), expected);
  EXPECT_EQ(m.volume, r.volume);
}
