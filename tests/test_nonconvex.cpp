// Sums of non-convex solids (src/nonconvex, docs/nonconvex.md): validation,
// convex decomposition, closed forms and properties of A ⊕ B, the catalog's
// non-convex solids.  The CGAL minkowski_sum_3 oracle is in
// test_nonconvex_oracle_long.cpp.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/parallel.hpp>
#include <minksum/transform.hpp>

#include "nonconvex/nef.hpp"
#include "nonconvex_support.hpp"
#include "test_support.hpp"

#include <CGAL/Exact_rational.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>
#include <set>

using namespace minksum;
using namespace minksum::testing;

namespace {

Solid solid(const std::string& spec) { return validate_solid(catalog_mesh(spec), spec); }

// The problem of the InputError that validating `m` throws ("" if none).
std::string problem(const Mesh& m) {
  try {
    validate_solid(m, "m.off");
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return "";
}

NonconvexSum sum(const std::string& a, const std::string& b) {
  Solid sa = solid(a), sb = solid(b);
  return minkowski_sum_nonconvex(sa, sb);
}

}  // namespace

// ---------------------------------------------------------------------------
// Validation.

TEST(NonconvexValidation, TubeIsAGenusOneSolid) {
  const Solid s = solid("tube");
  EXPECT_FALSE(s.convex);
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.faces, 16u);
  EXPECT_EQ(s.volume, Rational(6));  // 8 - 1 * 1 * 2
  // Euler characteristic of the triangulated surface: 2 - 2g = 0.
  EXPECT_EQ(long(s.triangles.points.size()) - long(s.triangles.faces.size()) * 3 / 2 + long(s.triangles.faces.size()), 0);
}

TEST(NonconvexValidation, ConvexMeshKeepsTheConvexPath) {
  const Solid s = validate_solid(cube_mesh(), "cube");
  ASSERT_TRUE(s.convex);
  EXPECT_EQ(s.convex->num_facets(), 6u);
  EXPECT_EQ(s.volume, Rational(8));
}

// solid_of without its volume (what the sums ask for: they do not read it)
// leaves the volume 0 and gives the same sum, exactly.
TEST(NonconvexValidation, ConvexSolidWithoutItsVolumeSumsTheSame) {
  const ConvexPolytope b = catalog_polytope("sphere:1@scale:1/4");
  const Solid with = solid_of(b), without = solid_of(b, false);
  EXPECT_EQ(with.volume, b.volume());
  EXPECT_EQ(without.volume, Rational(0));
  const Solid a = solid("lshape");
  const NonconvexSum r1 = minkowski_sum_nonconvex(a, with), r2 = minkowski_sum_nonconvex(a, without);
  EXPECT_EQ(r1.mesh.faces, r2.mesh.faces);
  EXPECT_EQ(mesh_volume(r1.mesh), mesh_volume(r2.mesh));
  EXPECT_GT(mesh_volume(r1.mesh), Rational(3));  // the L's volume, and more
}

TEST(NonconvexValidation, OpenMeshIsRefused) {
  Mesh m = catalog_mesh("tube");
  m.faces.pop_back();
  EXPECT_NE(problem(m).find("open mesh: the edge belongs to facet "), std::string::npos) << problem(m);
}

TEST(NonconvexValidation, InvertedMeshIsRefused) {
  Mesh m = catalog_mesh("lshape");
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  EXPECT_NE(problem(m).find("oriented inwards"), std::string::npos) << problem(m);
}

TEST(NonconvexValidation, OneFlippedFaceIsRefused) {
  Mesh m = catalog_mesh("tube");
  std::reverse(m.faces[3].begin(), m.faces[3].end());
  EXPECT_NE(problem(m).find("inconsistent orientation: facet "), std::string::npos) << problem(m);
}

TEST(NonconvexValidation, SelfIntersectingMeshIsRefused) {
  // Two overlapping cubes as one surface.
  const Mesh m = join(cube_mesh(2), box_mesh(1, 3, 1, 3, 1, 3));
  const std::string p = problem(m);
  EXPECT_NE(p.find("intersect (the surface intersects itself)"), std::string::npos) << p;
  EXPECT_EQ(p.rfind("m.off: facet ", 0), 0u) << p;
}

// The self-intersection test runs on CGAL's kernel of exact predicates on
// doubles when every coordinate is a double, on the exact kernel otherwise:
// both decide a gap or an overlap of one unit in the last place, and a
// rational overlap of 1/3^40.
TEST(NonconvexValidation, SelfIntersectionDecidedExactlyOnDoublesAndRationals) {
  const Rational ulp(mpz_class(1), mpz_class(1) << 52);  // 1 + ulp is a double
  const Mesh apart = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1 + ulp, 2, 0, 1, 0, 1));
  ASSERT_TRUE(apart.points.all_doubles());
  EXPECT_EQ(problem(apart), "");
  const Mesh overlap = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1 - ulp / 2, 2, 0, 1, 0, 1));
  ASSERT_TRUE(overlap.points.all_doubles());
  EXPECT_NE(problem(overlap).find("the surface intersects itself"), std::string::npos) << problem(overlap);
  Rational third(1, 1);
  for (int i = 0; i < 40; ++i) third /= 3;
  const Mesh rational_apart = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1 + third, 2, 0, 1, 0, 1));
  ASSERT_FALSE(rational_apart.points.all_doubles());
  EXPECT_EQ(problem(rational_apart), "");
  const Mesh rational_overlap = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1 - third, 2, 0, 1, 0, 1));
  EXPECT_NE(problem(rational_overlap).find("the surface intersects itself"), std::string::npos)
      << problem(rational_overlap);
}

namespace {
// The pair of triangles that CGAL's Polygon_mesh_processing::self_intersections
// reports first on `m` (triangles), on a Surface_mesh of points of kernel GK.
template <class GK>
std::optional<std::pair<Index, Index>> cgal_first_pair(const Mesh& m) {
  using SM = CGAL::Surface_mesh<typename GK::Point_3>;
  std::vector<typename GK::Point_3> points;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = m.points.exact(i);
    auto ft = [](const Rational& q) {
      if constexpr (std::is_same_v<typename GK::FT, double>)
        return q.get_d();  // exact: such a mesh's coordinates are doubles
      else
        return typename GK::FT(q.get_mpq_t());
    };
    points.emplace_back(ft(p.x), ft(p.y), ft(p.z));
  }
  std::vector<std::vector<std::size_t>> faces;
  for (const auto& f : m.faces) faces.emplace_back(f.begin(), f.end());
  SM sm;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, sm);
  std::vector<std::pair<typename SM::Face_index, typename SM::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  if (pairs.empty()) return std::nullopt;
  const Index a = Index(pairs[0].first), b = Index(pairs[0].second);
  return std::make_pair(std::min(a, b), std::max(a, b));
}
}  // namespace

// The self-intersection test of validation reports the pair that CGAL's
// self_intersections reports first, on one thread and with its pairs tested
// on threads (every loop threaded), on doubles (the tori moved by 1/2) and
// on rationals (moved by 1/3), for tori that cross, tori apart and one
// torus.
TEST(NonconvexValidation, SelfIntersectionReportsCgalsFirstPairOnThreads) {
  const std::size_t items = parallel_items();
  for (const char* move : {"@translate:1/2,0,0", "@translate:1/3,1/3,0", "@translate:3,0,0", ""}) {
    const Mesh one = catalog_mesh("torus:24:12");
    const Mesh m = *move ? join(one, catalog_mesh(std::string("torus:16:8") + move)) : one;
    using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
    using EK = CGAL::Simple_cartesian<CGAL::Exact_rational>;
    const auto expected = m.points.all_doubles() ? cgal_first_pair<IK>(m) : cgal_first_pair<EK>(m);
    EXPECT_EQ(expected.has_value(), std::string(move).find("1/") != std::string::npos) << move;
    for (std::size_t threaded : {items, std::size_t(1)}) {
      set_parallel_items(threaded);
      EXPECT_EQ(nonconvex_detail::first_self_intersection(m), expected) << move << " " << threaded;
    }
  }
  set_parallel_items(items);
}

namespace {
// m with every coordinate divided by 3 (rationals that are not doubles).
Mesh divided_by_three(const Mesh& m) {
  Mesh r;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = m.points.exact(i);
    r.points.push_back(Point3(p.x / 3, p.y / 3, p.z / 3));
  }
  r.faces = m.faces;
  return r;
}
// A message without its parenthesised parts (the coordinates).
std::string without_parentheses(const std::string& s) {
  std::string out;
  int depth = 0;
  for (char c : s) {
    depth += c == '(';
    if (!depth) out += c;
    depth -= c == ')' && depth > 0;
  }
  return out;
}
}  // namespace

// A surface of doubles (such as a rounded output) is checked on its
// doubles, any other on rationals: both name the same defect at the same
// place (the first edge of each kind in the order of first use, the first
// degenerate facet, the first vertex of several fans).
TEST(NonconvexValidation, DoublesAndRationalsNameTheSameDefect) {
  std::vector<std::pair<std::string, Mesh>> cases;
  {
    Mesh m = catalog_mesh("tube");
    std::reverse(m.faces[3].begin(), m.faces[3].end());
    cases.push_back({"inconsistent orientation: facet ", m});
  }
  {
    Mesh m = catalog_mesh("torus:8:4");
    m.faces.erase(m.faces.begin() + 5);
    cases.push_back({"open mesh: the edge belongs to facet ", m});
  }
  {
    Mesh m = catalog_mesh("torus:8:4");
    m.faces[7] = {m.faces[7][0], m.faces[7][1], m.faces[7][0]};
    cases.push_back({"uses a vertex twice", m});
  }
  {
    Mesh m = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 1, 2));
    cases.push_back({"non-manifold vertex: its facets form more than one fan", m});
  }
  {
    Mesh m = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 0, 1, 0, 1));
    cases.push_back({"non-manifold edge shared by 4 facets", m});
  }
  {
    // Facet 1 is collinear: (0,0,0), (1,0,0), (2,0,0).
    Mesh m;
    for (const auto& [x, y] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 0}, {0, 1}})
      m.points.push_back(Point3(Rational(x), Rational(y), Rational(0)));
    m.faces = {{0, 1, 3}, {0, 1, 2}};
    cases.push_back({"m.off: facet 1: has zero area (its vertices are collinear)", m});
  }
  for (const auto& [expected, m] : cases) {
    ASSERT_TRUE(m.points.all_doubles()) << expected;
    const Mesh r = divided_by_three(m);
    const std::string on_doubles = problem(m), on_rationals = problem(r);
    EXPECT_NE(on_doubles.find(expected), std::string::npos) << on_doubles;
    EXPECT_EQ(without_parentheses(on_doubles), without_parentheses(on_rationals)) << on_doubles << "\n" << on_rationals;
  }
}

// Vertices of high degree: a double pyramid over a star polygon of 1 200
// corners (each apex on 1 200 triangles; coordinates doubles) is a solid;
// with one triangle flipped, the first inconsistent edge in the order of
// first use is named, between the two facets that use it the same way.
TEST(NonconvexValidation, HighDegreeVerticesAreCheckedEdgeByEdge) {
  const Index n = 1200, top = n, bottom = n + 1;
  Mesh m;
  for (Index i = 0; i < n; ++i) {
    const double r = i % 2 ? 0.5 : 1.0, a = 2 * M_PI * double(i) / double(n);
    m.points.push_back(Point3(Rational(r * std::cos(a)), Rational(r * std::sin(a)), Rational(0)));
  }
  m.points.push_back(Point3(Rational(0), Rational(0), Rational(1)));
  m.points.push_back(Point3(Rational(0), Rational(0), Rational(-1)));
  for (Index i = 0; i < n; ++i) {
    const Index j = (i + 1) % n;
    m.faces.push_back({i, j, top});
    m.faces.push_back({j, i, bottom});
  }
  ASSERT_TRUE(m.points.all_doubles());
  EXPECT_EQ(problem(m), "");
  EXPECT_EQ(validate_solid(m, "m.off").vertices, std::size_t(n + 2));
  // Facet 10 (5 -> 6 -> top) flipped to 6 -> 5 -> top: its edge 5 -> top
  // is facet 8's (4 -> 5 -> top) too, which uses it first.
  Mesh flipped = m;
  std::swap(flipped.faces[10][0], flipped.faces[10][1]);
  const std::string p = problem(flipped);
  EXPECT_EQ(p.rfind("m.off: edge 5-1200 from ", 0), 0u) << p;
  EXPECT_NE(p.find(": inconsistent orientation: facet 8 and facet 10 traverse this edge in the same direction"),
            std::string::npos)
      << p;
  // And a vertex of two fans: the two apexes merged into one.
  Mesh pinched = m;
  for (auto& f : pinched.faces)
    for (Index& v : f)
      if (v == bottom) v = top;
  EXPECT_NE(problem(pinched).find("non-manifold"), std::string::npos) << problem(pinched);
}

// Collinearity on doubles is decided exactly: (0,0,0), (1 + 2^-52, 1, 0),
// (1, 1 - 2^-53, 0) span 2^-54 - 2^-106 of area, which the doubles' own
// cross product rounds to zero.  The facet is not degenerate, and the open
// surface is refused as open.
TEST(NonconvexValidation, NearlyCollinearFacetOfDoublesIsNotDegenerate) {
  Mesh m;
  m.points.push_back(Point3(Rational(0), Rational(0), Rational(0)));
  m.points.push_back(Point3(Rational(1.0 + 0x1p-52), Rational(1), Rational(0)));
  m.points.push_back(Point3(Rational(1), Rational(1.0 - 0x1p-53), Rational(0)));
  m.faces = {{0, 1, 2}};
  ASSERT_TRUE(m.points.all_doubles());
  const double bx = 1.0 + 0x1p-52, cy = 1.0 - 0x1p-53;
  volatile double product = bx * cy;
  ASSERT_EQ(product, 1.0);  // so a cross product in doubles says zero
  const std::string p = problem(m);
  EXPECT_EQ(p.find("zero area"), std::string::npos) << p;
  EXPECT_NE(p.find("open mesh"), std::string::npos) << p;
}

TEST(NonconvexValidation, CubesTouchingAtAVertexAreNotAManifold) {
  const Mesh m = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(1, 2, 1, 2, 1, 2));
  EXPECT_NE(problem(m).find("non-manifold vertex: its facets form more than one fan"), std::string::npos) << problem(m);
}

TEST(NonconvexValidation, NonPlanarFaceIsRefused) {
  Mesh m = catalog_mesh("lshape");
  Point3 p = m.points[0];
  p.z += Rational(1, 1000);
  m.points.set(0, p);
  EXPECT_NE(problem(m).find("is not planar"), std::string::npos) << problem(m);
}

TEST(NonconvexValidation, DisjointShellsAndCavitiesAreSolids) {
  const Solid h = validate_solid(hollow_cube(), "hollow");
  EXPECT_FALSE(h.convex);
  EXPECT_EQ(h.volume, Rational(56));
}

// Shells whose orientation disagrees with their nesting describe no solid,
// or another one than their volumes say: exit 3 naming the shell.
TEST(NonconvexValidation, NestedCubesBothFacingOutwardsAreRefused) {
  // [0,4]^3 with [1,3]^3 inside it, both facing out (the red team's case:
  // summed as if the inner cube were a cavity).
  const Mesh m = join(box_mesh(0, 4, 0, 4, 0, 4), box_mesh(1, 3, 1, 3, 1, 3));
  const std::string p = problem(m);
  EXPECT_EQ(p, "m.off: the shell of facet 6: faces outwards but lies inside another shell, in the solid (the boundary of "
               "a cavity must face inwards)");
}

TEST(NonconvexValidation, InwardCubeBesideACubeIsRefused) {
  // A 4-cube beside a separate unit cube facing in (signed volume 63).
  const Mesh m = join(box_mesh(0, 4, 0, 4, 0, 4), box_mesh(6, 7, 0, 1, 0, 1), true);
  const std::string p = problem(m);
  EXPECT_EQ(p, "m.off: the shell of facet 6: faces inwards but lies inside no other shell (an outer boundary must face "
               "outwards)");
}

TEST(NonconvexValidation, CavityFacingOutwardsInsideAnInwardShellIsRefused) {
  // Both shells reversed: the outer one faces in, whatever the inner does.
  Mesh m = join(box_mesh(0, 4, 0, 4, 0, 4), box_mesh(1, 3, 1, 3, 1, 3), true);
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  const std::string p = problem(m);
  EXPECT_NE(p.find("m.off: the shell of facet 0: faces inwards but lies inside no other shell"), std::string::npos) << p;
}

TEST(NonconvexValidation, IslandInACavityFacesOutwards) {
  // [0,6]^3, its cavity [1,5]^3 (facing in), an island [2,4]^3 in the cavity.
  const Mesh shell = join(box_mesh(0, 6, 0, 6, 0, 6), box_mesh(1, 5, 1, 5, 1, 5), true);
  const Solid s = validate_solid(join(shell, box_mesh(2, 4, 2, 4, 2, 4)), "island");
  EXPECT_EQ(s.volume, Rational(216 - 64 + 8));
  // The island facing in is refused, named by its first face.
  const std::string p = problem(join(shell, box_mesh(2, 4, 2, 4, 2, 4), true));
  EXPECT_EQ(p, "m.off: the shell of facet 12: faces inwards but lies in a cavity (the boundary of an island in a cavity "
               "must face outwards)");
  // A cavity inside the island faces in again (depth 3).
  const Mesh nested = join(join(shell, box_mesh(2, 4, 2, 4, 2, 4)), box_mesh(Rational(5, 2), Rational(7, 2),
                                                                               Rational(5, 2), Rational(7, 2),
                                                                               Rational(5, 2), Rational(7, 2)),
                           true);
  EXPECT_EQ(validate_solid(nested, "nested").volume, Rational(216 - 64 + 8 - 1));
}

TEST(NonconvexValidation, ShellsSideBySideAndOneInsideAnothersBoxAreSolids) {
  // An L-shaped shell's bounding box holds a cube that lies outside it.
  const Mesh l = catalog_mesh("lshape");
  Rational lo[3], hi[3];
  for (int c = 0; c < 3; ++c) lo[c] = hi[c] = l.points[0][c];
  for (std::size_t i = 0; i < l.points.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      if (l.points[i][c] < lo[c]) lo[c] = l.points[i][c];
      if (hi[c] < l.points[i][c]) hi[c] = l.points[i][c];
    }
  const Solid ls = validate_solid(l, "lshape");
  // The corner of the box opposite the L's inner corner is empty: find a small
  // cube in the box that the L does not hold, by trying the eight corners.
  bool found = false;
  for (int corner = 0; corner < 8 && !found; ++corner) {
    Rational b[3][2];
    for (int c = 0; c < 3; ++c) {
      const Rational w = (hi[c] - lo[c]) / 8;
      b[c][0] = (corner >> c & 1) ? Rational(hi[c] - 2 * w) : Rational(lo[c] + w);
      b[c][1] = b[c][0] + w;
    }
    const Mesh m = join(l, box_mesh(b[0][0], b[0][1], b[1][0], b[1][1], b[2][0], b[2][1]));
    try {
      const Solid s = validate_solid(m, "l+cube");
      EXPECT_EQ(s.volume, ls.volume + (b[0][1] - b[0][0]) * (b[1][1] - b[1][0]) * (b[2][1] - b[2][0]));
      found = true;
    } catch (const InputError&) {
      // This corner is inside the L: the cube is a shell in the solid, refused.
    }
  }
  EXPECT_TRUE(found);
}

// ---------------------------------------------------------------------------
// Decomposition.

TEST(NonconvexDecomposition, PiecesAreConvexAndFillTheSolid) {
  for (const char* spec : {"tube", "lshape", "star:5", "gear:6", "ring:7@rot:3"}) {
    SCOPED_TRACE(spec);
    const Solid s = solid(spec);
    const auto pieces = convex_decomposition(s);
    EXPECT_GE(pieces.size(), 2u);
    Rational v = 0;
    for (const auto& p : pieces) {
      EXPECT_EQ(p.check_invariants(), "");
      v += p.volume();
    }
    EXPECT_EQ(v, s.volume);
  }
  // A cavity stays empty: the pieces of the hollow cube fill its shell only.
  const Solid h = validate_solid(hollow_cube(), "hollow");
  Rational v = 0;
  for (const auto& p : convex_decomposition(h)) v += p.volume();
  EXPECT_EQ(v, Rational(56));
}

// ---------------------------------------------------------------------------
// Sums: closed forms.

// tube ⊕ [-s,s]^3: the box [-(1+s), 1+s]^3 with a square hole of side 1 - 2s.
TEST(NonconvexSum, TubePlusCubeClosedForm) {
  const NonconvexSum r = sum("tube", "box:1/2:1/2:1/2");
  expect_closed_oriented(r);
  const Rational s(1, 4), h = 1 - 2 * s, side = 2 + 2 * s;
  EXPECT_EQ(r.volume, side * side * side - h * h * side);
  EXPECT_EQ(r.mesh.points.size(), 16u);
  // 4 outer and 4 inner walls; each cap, a square with a square hole, is
  // triangulated into 8 triangles.
  EXPECT_EQ(r.mesh.faces.size(), 24u);
  EXPECT_EQ(r.shells, 1u);
  EXPECT_EQ(r.pieces_b, 1u);
  EXPECT_EQ(r.pairs, r.pieces_a);
}

// The hole closes exactly when the cube's side equals it: a convex box.
TEST(NonconvexSum, HoleThatClosesExactly) {
  const NonconvexSum r = sum("tube", "box:1:1:1");
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(27));
  EXPECT_EQ(r.mesh.points.size(), 8u);
  EXPECT_EQ(r.mesh.faces.size(), 6u);
  EXPECT_EQ(face_planes(r.mesh).size(), 6u);
}

// The hollow cube's cavity [-1,1]^3 shrinks by the cube [-s,s]^3 and
// vanishes at s = 1.
TEST(NonconvexSum, CavityKeptThenVanishes) {
  const Solid h = validate_solid(hollow_cube(), "hollow");
  {
    const NonconvexSum r = minkowski_sum_nonconvex(h, solid("box:1:1:1"));
    expect_closed_oriented(r);
    EXPECT_EQ(r.volume, Rational(125 - 1));
    EXPECT_EQ(r.mesh.faces.size(), 12u);
    EXPECT_EQ(r.mesh.points.size(), 16u);
  }
  {
    const NonconvexSum r = minkowski_sum_nonconvex(h, solid("box:2:2:2"));
    expect_closed_oriented(r);
    EXPECT_EQ(r.volume, Rational(216));
    EXPECT_EQ(r.mesh.faces.size(), 6u);
  }
}

// L ⊕ [-s,s]^3: the L profile [-1,1]^2 minus (0,1]^2 becomes
// [-1-s,1+s]^2 minus (s,1+s]^2 (the notch keeps its side 1), of height 1 + 2s.
TEST(NonconvexSum, LShapePlusCubeClosedForm) {
  const NonconvexSum r = sum("lshape", "box:1/2:1/2:1/2");
  expect_closed_oriented(r);
  const Rational s(1, 4), side = 2 + 2 * s;
  EXPECT_EQ(r.volume, (side * side - 1) * (1 + 2 * s));
  EXPECT_EQ(r.mesh.points.size(), 12u);
  EXPECT_EQ(r.mesh.faces.size(), 8u);  // the two caps are L-shaped polygons
}

// Two unit cubes one apart along x, each ⊕ [-1/2,1/2]^3: the sums touch in a
// face (a coplanar contact of opposite orientation) and become one box.
TEST(NonconvexSum, TouchingPiecesMergeAcrossACoplanarContact) {
  const Mesh m = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(2, 3, 0, 1, 0, 1));
  const NonconvexSum r = minkowski_sum_nonconvex(validate_solid(m, "two"), solid("box:1:1:1"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(16));
  EXPECT_EQ(r.mesh.points.size(), 8u);
  EXPECT_EQ(r.mesh.faces.size(), 6u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
}

// Two unit cubes diagonal to each other, each ⊕ [-1/2,1/2]^3: the sums touch
// along one edge, which the boundary keeps as a non-manifold edge of four faces.
TEST(NonconvexSum, SumsTouchingAlongAnEdgeKeepANonManifoldEdge) {
  const Mesh m = join(box_mesh(0, 1, 0, 1, 0, 1), box_mesh(2, 3, 2, 3, 0, 1));
  const NonconvexSum r = minkowski_sum_nonconvex(validate_solid(m, "diagonal"), solid("box:1:1:1"));
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, Rational(16));
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_EQ(r.mesh.faces.size(), 12u);
}

// ---------------------------------------------------------------------------
// Sums: properties.

TEST(NonconvexSum, IsSymmetric) {
  const NonconvexSum ab = sum("star:5", "lshape@scale:1/3"), ba = sum("lshape@scale:1/3", "star:5");
  expect_closed_oriented(ab);
  EXPECT_EQ(ab.volume, ba.volume);
  EXPECT_EQ(vertex_set(ab.mesh), vertex_set(ba.mesh));
  EXPECT_EQ(face_planes(ab.mesh), face_planes(ba.mesh));
}

TEST(NonconvexSum, TranslationMovesTheSum) {
  const NonconvexSum r = sum("tube", "octahedron@scale:1/4"),
                     t = sum("tube@translate:1/3,-1/5,1/7", "octahedron@scale:1/4@translate:1,2,3");
  expect_closed_oriented(r);
  EXPECT_EQ(r.volume, t.volume);
  std::set<Point3> moved;
  for (const Point3& p : vertex_set(r.mesh)) moved.insert(p + Point3(Rational(4, 3), Rational(9, 5), Rational(22, 7)));
  EXPECT_EQ(moved, vertex_set(t.mesh));
}

TEST(NonconvexSum, ScalingBothScalesTheVolume) {
  const NonconvexSum r = sum("gear:5", "cube@scale:1/8"), s = sum("gear:5@scale:2", "cube@scale:1/4");
  expect_closed_oriented(r);
  EXPECT_EQ(s.volume, 8 * r.volume);
  EXPECT_EQ(r.mesh.faces.size(), s.mesh.faces.size());
}

// Non-convex ⊕ non-convex: bounded by the pair sums (at least the largest,
// at most their total) and at least each operand's volume.
TEST(NonconvexSum, NonConvexPlusNonConvex) {
  const Solid a = solid("tube"), b = solid("lshape@scale:1/4");
  const NonconvexSum r = minkowski_sum_nonconvex(a, b);
  expect_closed_oriented(r);
  EXPECT_GT(r.pieces_a, 1u);
  EXPECT_GT(r.pieces_b, 1u);
  EXPECT_EQ(r.pairs, r.pieces_a * r.pieces_b);
  EXPECT_GT(r.volume, a.volume);
  EXPECT_EQ(r.shells, 1u);
  // The tube's hole (side 1) narrowed by the L's extent (1/2) stays open: genus 1.
  std::set<std::pair<Index, Index>> edges;
  for (const auto& f : r.mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i)
      edges.insert({std::min(f[i], f[(i + 1) % f.size()]), std::max(f[i], f[(i + 1) % f.size()])});
  EXPECT_EQ(long(r.mesh.points.size()) - long(edges.size()) + long(r.mesh.faces.size()), 0);
}

TEST(NonconvexSum, ReportsProgressAndHonoursCancel) {
  std::vector<std::string> phases;
  SumOptions o;
  o.progress = [&](const char* p, double) {
    if (phases.empty() || phases.back() != p) phases.push_back(p);
  };
  minkowski_sum_nonconvex(solid("tube"), solid("cube@scale:1/8"), o);
  EXPECT_EQ(phases, (std::vector<std::string>{"decompose", "pairs", "union", "boundary"}));
  // The decompose phase reports a fraction, from 0 to 1, by either method
  // (the progress line showed no fraction there).
  for (const NonconvexMethod how : {NonconvexMethod::sweep, NonconvexMethod::decomposition}) {
    std::vector<double> fractions;
    SumOptions f;
    f.progress = [&](const char* p, double x) {
      if (std::string(p) == "decompose") fractions.push_back(x);
    };
    minkowski_sum_nonconvex(solid("tube"), solid("lshape"), f, 0, Method::automatic, how);
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  }
  std::atomic<bool> cancel{true};
  SumOptions c;
  c.cancel = &cancel;
  EXPECT_THROW(minkowski_sum_nonconvex(solid("tube"), solid("cube"), c), Cancelled);
}

// SumOptions::release: the boundary sweep hands over the union's faces
// before their points are welded, then its pieces, each once and alive (the
// last pointer frees them), and the sum is the same.
TEST(NonconvexSum, ReleaseHandsThePiecesOver) {
  const NonconvexSum plain = minkowski_sum_nonconvex(solid("tube"), solid("cube@scale:1/8"));
  std::vector<std::shared_ptr<void>> handed;
  SumOptions o;
  o.release = [&](std::shared_ptr<void> data) { handed.push_back(std::move(data)); };
  const NonconvexSum kept = minkowski_sum_nonconvex(solid("tube"), solid("cube@scale:1/8"), o);
  ASSERT_EQ(handed.size(), 2u);
  for (const auto& data : handed) {
    EXPECT_NE(data, nullptr);
    EXPECT_EQ(data.use_count(), 1);
  }
  EXPECT_NE(handed[0], handed[1]);
  EXPECT_EQ(kept.volume, plain.volume);
  EXPECT_EQ(kept.mesh.faces, plain.mesh.faces);
  EXPECT_EQ(kept.mesh.points.to_points(), plain.mesh.points.to_points());
}

// ---------------------------------------------------------------------------
// Catalog.

TEST(NonconvexCatalog, EverySolidIsValidAndNotConvex) {
  struct Case {
    const char* spec;
    long euler;  // of the triangulated surface: 2 - 2 * genus
  };
  for (const Case& c : {Case{"tube", 0}, Case{"tube:1/3", 0}, Case{"lshape", 2}, Case{"ring:8", 0}, Case{"star:5", 2},
                        Case{"gear:12", 0}, Case{"gear:12@rot:5@neg", 0}, Case{"star:7@scale:1/3,2,5", 2}}) {
    SCOPED_TRACE(c.spec);
    const Solid s = solid(c.spec);
    EXPECT_FALSE(s.convex);
    const long v = long(s.triangles.points.size()), f = long(s.triangles.faces.size());
    EXPECT_EQ(v - f * 3 / 2 + f, c.euler);
    EXPECT_THROW(catalog_polytope(c.spec), NotConvexError);
  }
  EXPECT_EQ(solid("tube:1/3").volume, 8 - Rational(2, 9));
  EXPECT_EQ(solid("lshape").volume, Rational(3));
  EXPECT_EQ(solid("lshape@scale:2").volume, Rational(24));
}

TEST(NonconvexCatalog, BadParametersAreUsageErrors) {
  for (const char* spec : {"tube:2", "tube:0", "ring:2", "star:10001", "gear:x", "lshape:3", "ring"}) {
    SCOPED_TRACE(spec);
    EXPECT_THROW(catalog_mesh(spec), UsageError);
  }
  EXPECT_TRUE(is_catalog_spec("gear:12@rot:1"));
  EXPECT_EQ(nonconvex_catalog_entries().size(), 7u);
}

// triangulate ear-clips each face of a valid solid without its rational
// normal (the drop axis from one corner, the orientation from the turn at
// the lexicographically smallest projected vertex): on non-convex faces
// (the L, the star, the gear with its hole's faces, a tube), in every
// orientation the rotations give (faces facing ±x, ±y, ±z and oblique, and the point reflection,
// the smallest vertex at a reflex corner or not), every triangle turns as
// its face does (its normal a positive multiple of the face's Newell
// normal) and the triangles' volume is the faces' exactly.
TEST(NonconvexSum, TriangulatedFacesTurnAsTheirFaces) {
  for (const char* base : {"lshape", "star:5", "gear:4", "tube", "ring:5"})
    for (const char* turn : {"", "@rot:1", "@rot:3", "@rot:7", "@rot:1,2,3,4", "@rot:0,1,0,0", "@neg"}) {
      const std::string spec = std::string(base) + turn;
      SCOPED_TRACE(spec);
      const Mesh m = catalog_mesh(spec);
      const Mesh t = triangulate(m, spec);
      EXPECT_EQ(mesh_volume(t), mesh_volume(m));
      // Each face's triangles follow it in order: match them by plane.
      std::size_t next = 0;
      for (const auto& f : m.faces) {
        Point3 n(Rational(0), Rational(0), Rational(0));
        for (std::size_t i = 0; i < f.size(); ++i) n = n + cross(m.points[f[i]], m.points[f[(i + 1) % f.size()]]);
        for (std::size_t k = 0; k + 2 < f.size(); ++k, ++next) {
          ASSERT_LT(next, t.faces.size());
          const auto& g = t.faces[next];
          const Point3 c = cross(t.points[g[1]] - t.points[g[0]], t.points[g[2]] - t.points[g[0]]);
          EXPECT_TRUE(is_zero(cross(c, n)) && sgn(dot(c, n)) > 0) << "a triangle turning against its face";
        }
      }
      EXPECT_EQ(next, t.faces.size());
    }
}
