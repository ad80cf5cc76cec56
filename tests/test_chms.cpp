// CHMS, the oracle: checked against facts known independently of any hull.
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope poly(const Mesh& m) { return ConvexPolytope::from_mesh(m); }

// Facts every Minkowski sum satisfies, whatever the operands.
void expect_sum_facts(const ConvexPolytope& a, const ConvexPolytope& b, const SumResult& r) {
  const ConvexPolytope& s = r.polytope;
  EXPECT_EQ(s.euler_characteristic(), 2);
  EXPECT_EQ(s.check_invariants(), "");
  // Every vertex is the sum of the recorded pair of input vertices.
  ASSERT_EQ(r.vertex_origin.size(), s.num_vertices());
  for (Index v = 0; v < s.num_vertices(); ++v) {
    auto [i, j] = r.vertex_origin[v];
    EXPECT_EQ(s.point(v), a.point(i) + b.point(j));
  }
  // Every facet normal of A and of B is a facet normal of the sum.
  std::set<std::tuple<Integer, Integer, Integer>> normals;
  for (Index f = 0; f < s.num_facets(); ++f) normals.insert(normal_direction(s.plane(f)));
  for (const ConvexPolytope* p : {&a, &b})
    for (Index f = 0; f < p->num_facets(); ++f)
      EXPECT_TRUE(normals.count(normal_direction(p->plane(f)))) << "input facet " << f;
  // Every facet of the sum supports it: all vertices of A ⊕ B (pairwise
  // sums, checked directly) lie on or below each facet plane.
  for (Index f = 0; f < s.num_facets(); ++f) {
    const Plane& pl = s.plane(f);
    Point3 n = pl.normal();
    Rational best_a = dot(n, a.point(0)), best_b = dot(n, b.point(0));
    for (Index i = 1; i < a.num_vertices(); ++i) best_a = std::max(best_a, Rational(dot(n, a.point(i))));
    for (Index j = 1; j < b.num_vertices(); ++j) best_b = std::max(best_b, Rational(dot(n, b.point(j))));
    EXPECT_EQ(best_a + best_b, Rational(pl.d)) << "facet " << f << " is not a supporting plane";
  }
}

}  // namespace

TEST(Chms, BoxPlusBoxIsABox) {
  ConvexPolytope a = poly(box_mesh(0, 1, 0, 2, 0, 3));
  ConvexPolytope b = poly(box_mesh(Rational(-1, 3), Rational(11, 3), -5, 0, Rational(1, 7), Rational(43, 7)));
  SumResult r = minkowski_sum_chms(a, b);
  expect_sum_facts(a, b, r);
  ConvexPolytope want = poly(box_mesh(Rational(-1, 3), Rational(14, 3), -5, 2, Rational(1, 7), Rational(64, 7)));
  EXPECT_TRUE(same_polytope(r.polytope, want));
  EXPECT_EQ(r.polytope.volume(), Rational(5) * 7 * 9);
}

TEST(Chms, CubePlusCubeIsTwiceTheCube) {
  ConvexPolytope c = poly(cube_mesh(1));
  SumResult r = minkowski_sum_chms(c, c);
  expect_sum_facts(c, c, r);
  EXPECT_TRUE(same_polytope(r.polytope, poly(cube_mesh(2))));
}

TEST(Chms, TetraPlusNegatedTetraIsCuboctahedron) {
  // T ⊕ (-T) for the regular tetrahedron is the cuboctahedron with vertices
  // the permutations of (±2, ±2, 0): 12 V, 24 E, 14 F (8 triangles, 6
  // squares); edge length 2√2, volume (5√2/3)(2√2)^3 = 160/3.
  ConvexPolytope t = poly(tetra_mesh());
  ConvexPolytope n = t.negated();
  SumResult r = minkowski_sum_chms(t, n);
  expect_sum_facts(t, n, r);
  const ConvexPolytope& s = r.polytope;
  EXPECT_EQ(s.num_vertices(), 12u);
  EXPECT_EQ(s.num_edges(), 24u);
  EXPECT_EQ(s.num_facets(), 14u);
  EXPECT_EQ(s.volume(), Rational(160, 3));
  int triangles = 0, squares = 0;
  for (Index f = 0; f < s.num_facets(); ++f) (s.facet_degree(f) == 3 ? triangles : squares)++;
  EXPECT_EQ(triangles, 8);
  EXPECT_EQ(squares, 6);
  for (const auto& p : s.points()) {
    int zeros = (p.x == 0) + (p.y == 0) + (p.z == 0);
    EXPECT_EQ(zeros, 1);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(p[i] == 0 || abs(p[i]) == 2);
  }
}

TEST(Chms, CubePlusOctahedronIsRhombicuboctahedral) {
  // [-1,1]^3 ⊕ conv(±e_i): vertices are the 24 permutations of (±2, ±1, ±1);
  // 6 + 8 + 12 facets (translated, corner, edge): 24 V, 48 E, 26 F.
  ConvexPolytope c = poly(cube_mesh(1)), o = poly(octahedron_mesh());
  SumResult r = minkowski_sum_chms(c, o);
  expect_sum_facts(c, o, r);
  const ConvexPolytope& s = r.polytope;
  EXPECT_EQ(s.num_vertices(), 24u);
  EXPECT_EQ(s.num_edges(), 48u);
  EXPECT_EQ(s.num_facets(), 26u);
  for (const auto& p : s.points()) {
    std::vector<Rational> a = {abs(p.x), abs(p.y), abs(p.z)};
    std::sort(a.begin(), a.end());
    EXPECT_EQ(a, (std::vector<Rational>{1, 1, 2}));
  }
  // Volume by mixed volumes: vol(C ⊕ O) = V(C) + 3 V(C,C,O) + 3 V(C,O,O) + V(O)
  // with V(C,C,O) = 1/3 Σ_{facets F of C} h_O(n_F) area(F) = 1/3 · 6 · 1 · 4 = 8 and
  // V(C,O,O) = 1/3 Σ_{facets F of O} h_C(n_F) area(F) = 1/3 · 8 · √3 · (√3/2) = 4:
  // 8 + 24 + 12 + 4/3 = 136/3.
  EXPECT_EQ(s.volume(), Rational(136, 3));
}

TEST(Chms, CommutativeAndTranslationCovariant) {
  ConvexPolytope t = poly(tetra_mesh()), o = poly(octahedron_mesh());
  SumResult ab = minkowski_sum_chms(t, o), ba = minkowski_sum_chms(o, t);
  EXPECT_TRUE(same_polytope(ab.polytope, ba.polytope));
  Point3 shift = Q("1/3", "-2", "5/7");
  SumResult moved = minkowski_sum_chms(t.translated(shift), o);
  EXPECT_TRUE(same_polytope(moved.polytope, ab.polytope.translated(shift)));
}

TEST(Chms, RandomIntegerPolytopesSatisfyTheFacts) {
  // Hulls of random lattice points (many coplanar and collinear points).
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    auto cloud = [&](int n, long r) {
      std::vector<Point3> pts;
      for (int i = 0; i < n; ++i)
        pts.push_back(P(long(rng() % (2 * r + 1)) - r, long(rng() % (2 * r + 1)) - r, long(rng() % (2 * r + 1)) - r));
      return ConvexPolytope::hull(pts);
    };
    ConvexPolytope a = cloud(30, 3), b = cloud(20, 2);
    SumResult r = minkowski_sum_chms(a, b);
    expect_sum_facts(a, b, r);
    EXPECT_TRUE(same_polytope(r.polytope, minkowski_sum_chms(b, a).polytope));
  }
}

TEST(Chms, DispatchRefusesMethodsNotBuilt) {
  ConvexPolytope c = poly(cube_mesh(1));
  EXPECT_NO_THROW(minkowski_sum(c, c, Method::chms));
  EXPECT_NO_THROW(minkowski_sum(c, c, Method::automatic));
  for (Method m : {Method::walk, Method::cvms, Method::essdms, Method::mssd, Method::cgm}) {
    if (method_available(m)) continue;
    try {
      minkowski_sum(c, c, m);
      ADD_FAILURE() << method_name(m) << " should be refused";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(method_name(m)), std::string::npos);
    }
  }
}

TEST(Chms, AutoPicksWalkAndSaysWhich) {
  // auto is the output-sensitive walk for double and rational operands; the
  // result is the oracle's either way.
  ConvexPolytope c = poly(cube_mesh(1)), o = poly(octahedron_mesh());
  SumResult small = minkowski_sum(c, o, Method::automatic);
  EXPECT_EQ(small.method, Method::walk);
  EXPECT_TRUE(same_polytope(small.polytope, minkowski_sum_chms(c, o).polytope));
  ConvexPolytope t = poly(tetra_mesh()).translated(Q("1/3", "0", "0"));
  SumResult rational = minkowski_sum(t, o, Method::automatic);
  EXPECT_EQ(rational.method, Method::walk);
  EXPECT_TRUE(same_polytope(rational.polytope, minkowski_sum_chms(t, o).polytope));
}
