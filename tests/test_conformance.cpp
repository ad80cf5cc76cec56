// Conformance: every Minkowski-sum method (walk, cvms, essdms, mssd, cgm and
// the chms oracle itself) on the same families of operand pairs, each result
// checked by the oracle contract of method_families.hpp — the vertex set and
// facet planes of chms, every vertex a sum a_i + b_j as recorded, V - E + F
// = 2 (and every invariant of ConvexPolytope for the walk, whose structure
// skips validation), the recorded facet provenance equal to the brute-force
// one, B ⊕ A equal to A ⊕ B.  Where the sum is known
// in closed form (boxes, A ⊕ A = 2A, T ⊕ −T, cube ⊕ octahedron and others),
// the closed form is the reference of every method, the oracle included,
// with its exact counts, coordinates, volume and provenance.  The oracle is
// also checked against facts that need no hull: every facet plane supports
// A ⊕ B.  Random pairs use fixed seeds; a failure prints the method, the pair
// and the seed.  What only one method records (its counters, its own data
// structures) is tested in that method's suite.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <random>

#include "method_families.hpp"
#include "test_support.hpp"

namespace minksum {
// Test parameters print as the method's name.
void PrintTo(Method m, std::ostream* os) { *os << method_name(m); }
}  // namespace minksum

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope poly(const Mesh& m) { return ConvexPolytope::from_mesh(m); }

class Conformance : public ::testing::TestWithParam<Method> {
 protected:
  Method method() const { return GetParam(); }
  SumResult sum(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, Checks checks = {},
                const ConvexPolytope* closed_form = nullptr) {
    return conforming_sum(method(), a, b, label, checks, closed_form);
  }
  // A sum known in closed form: the contract, the facts that need no hull,
  // and the known counts.
  SumResult closed_form_sum(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, Index v, Index e,
                            Index f) {
    SumResult r = sum(a, b, label);
    expect_supporting_facets(a, b, r.polytope);
    EXPECT_EQ(r.polytope.num_vertices(), v);
    EXPECT_EQ(r.polytope.num_edges(), e);
    EXPECT_EQ(r.polytope.num_facets(), f);
    return r;
  }
  void expect(const std::string& a, const std::string& b, Checks checks = {}) {
    expect_conforms(method(), a, b, checks);
  }
  void expect(const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, Checks checks = {}) {
    expect_conforms(method(), a, b, label, checks);
  }
};

constexpr Checks kNoBruteForce{false, true};

}  // namespace

INSTANTIATE_TEST_SUITE_P(Methods, Conformance, ::testing::ValuesIn(all_methods()),
                         [](const ::testing::TestParamInfo<Method>& info) { return std::string(method_name(info.param)); });

TEST_P(Conformance, DispatchAndCommutativity) {
  // Built, named, dispatched: the result says which method made it.
  ASSERT_TRUE(method_available(method()));
  EXPECT_EQ(parse_method(method_name(method())), method());
  expect("dodecahedron", "cube@rot:2");
}

// ---------------------------------------------------------------------------
// Sums known in closed form.

TEST_P(Conformance, BoxPlusBoxIsABox) {
  ConvexPolytope a = poly(box_mesh(0, 1, 0, 2, 0, 3));
  ConvexPolytope b = poly(box_mesh(Rational(-1, 3), Rational(11, 3), -5, 0, Rational(1, 7), Rational(43, 7)));
  SumResult r = closed_form_sum(a, b, "box + box", 8, 12, 6);
  ConvexPolytope want = poly(box_mesh(Rational(-1, 3), Rational(14, 3), -5, 2, Rational(1, 7), Rational(64, 7)));
  EXPECT_TRUE(same_polytope(r.polytope, want));
  EXPECT_EQ(r.polytope.volume(), Rational(5) * 7 * 9);
  // Six facets, each a facet of A ⊕ the parallel facet of B.
  if (tracks_provenance(method())) { EXPECT_EQ(origin_counts(r), (std::array<long, 5>{0, 0, 0, 0, 6})); }
}

TEST_P(Conformance, CubePlusCubeIsTwiceTheCube) {
  ConvexPolytope c = poly(cube_mesh(1));
  SumResult r = closed_form_sum(c, c, "cube + cube", 8, 12, 6);
  EXPECT_TRUE(same_polytope(r.polytope, poly(cube_mesh(2))));
}

TEST_P(Conformance, TetraPlusNegatedTetraIsCuboctahedron) {
  // T ⊕ (-T) for the regular tetrahedron is the cuboctahedron with vertices
  // the permutations of (±2, ±2, 0): 12 V, 24 E, 14 F (8 triangles, 6
  // squares); edge length 2√2, volume (5√2/3)(2√2)^3 = 160/3.  The triangles
  // are the 4 facets of T and the 4 of -T translated, the squares the sums of
  // two opposite (perpendicular) edges.
  ConvexPolytope t = poly(tetra_mesh());
  ConvexPolytope n = t.negated();
  SumResult r = closed_form_sum(t, n, "T + (-T)", 12, 24, 14);
  const ConvexPolytope& s = r.polytope;
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
  if (tracks_provenance(method())) { EXPECT_EQ(origin_counts(r), (std::array<long, 5>{4, 4, 6, 0, 0})); }
}

TEST_P(Conformance, CubePlusOctahedronIsRhombicuboctahedral) {
  // [-1,1]^3 ⊕ conv(±e_i): vertices are the 24 permutations of (±2, ±1, ±1);
  // 6 translated + 8 corner + 12 edge facets (the 12 crossings of the cube's
  // arcs with the octahedron's): 24 V, 48 E, 26 F.
  ConvexPolytope c = poly(cube_mesh(1)), o = poly(octahedron_mesh());
  ASSERT_TRUE(same_polytope(c, cat("cube")));
  ASSERT_TRUE(same_polytope(o, cat("octahedron")));
  SumResult r = closed_form_sum(c, o, "cube + octahedron", 24, 48, 26);
  const ConvexPolytope& s = r.polytope;
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
  if (tracks_provenance(method())) { EXPECT_EQ(origin_counts(r), (std::array<long, 5>{6, 8, 12, 0, 0})); }
  // The same with the operands swapped: translated and corner trade places.
  SumResult swapped = sum(o, c, "octahedron + cube");
  if (tracks_provenance(method())) { EXPECT_EQ(origin_counts(swapped), (std::array<long, 5>{8, 6, 12, 0, 0})); }
}

TEST_P(Conformance, CubePlusAxisAlignedTruncatedCube) {
  // The pair on which CGAL 5.5's spherical Gaussian map returns a facet with
  // a wrong offset: the cube's normals coincide with the truncated cube's
  // octagon normals, the triangle normals sit on the cube's corner
  // directions.  The cube's normal fan is coarser than the truncated cube's,
  // so the sum has the truncated cube's combinatorics: 24 V, 36 E, 14 F
  // (6 octagon ⊕ square, 8 triangle ⊕ corner), each facet the support plane
  // of the sum in its normal direction.
  const ConvexPolytope a = cat("cube"), b = cat("truncated-cube");
  SumResult r = closed_form_sum(a, b, "cube + truncated-cube", 24, 36, 14);
  if (tracks_provenance(method())) { EXPECT_EQ(origin_counts(r), (std::array<long, 5>{0, 8, 0, 0, 6})); }
}

TEST_P(Conformance, CommutativeAndTranslationCovariant) {
  ConvexPolytope t = poly(tetra_mesh()), o = poly(octahedron_mesh());
  SumResult ab = sum(t, o, "tetra + octahedron");
  SumResult ba = sum(o, t, "octahedron + tetra");
  EXPECT_TRUE(same_polytope(ab.polytope, ba.polytope));
  const Point3 shift = Q("1/3", "-2", "5/7");
  SumResult moved = sum(t.translated(shift), o, "translated tetra + octahedron");
  EXPECT_TRUE(same_polytope(moved.polytope, ab.polytope.translated(shift)));
  SumResult moved_b = sum(t, o.translated(shift), "tetra + translated octahedron");
  EXPECT_TRUE(same_polytope(moved_b.polytope, ab.polytope.translated(shift)));
}

TEST_P(Conformance, IdenticalOperands) {
  // A ⊕ A = 2A: every facet of A meets its parallel twin (facet ⊕ facet), every
  // arc of A runs along the same arc of the copy.
  std::vector<std::string> solids = {"sphere:3",       "dodecahedron@rot:3", "cuboctahedron@rot:17",
                                     "sphere:2@rot:1", "sphere:2@rot:5",     "random:40:7",
                                     "dioctagonal:17", "truncated-cuboctahedron"};
  solids.insert(solids.end(), small_solids().begin(), small_solids().end());
  for (const std::string& x : solids) {
    const ConvexPolytope a = cat(x);
    const ConvexPolytope twice = homothet(a, 2);
    SumResult r = sum(a, a, x + " twice", {}, &twice);
    EXPECT_EQ(r.polytope.num_facets(), a.num_facets()) << x;
    if (tracks_provenance(method())) {
      EXPECT_EQ(origin_counts(r), (std::array<long, 5>{0, 0, 0, 0, long(a.num_facets())})) << x;
    }
    if (x == "sphere:3") { EXPECT_EQ(r.polytope.num_facets(), 320u); }
    if (HasFatalFailure()) return;
  }
}

TEST_P(Conformance, RandomIntegerPolytopesSatisfyTheFacts) {
  // Hulls of random lattice points (many coplanar and collinear points),
  // checked against the facts that need no hull as well as by the contract;
  // B ⊕ A compared for the oracle too.
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const ConvexPolytope a = random_lattice_polytope(rng, 30, 3), b = random_lattice_polytope(rng, 20, 2);
    SumResult r = sum(a, b, "lattice pair");
    expect_supporting_facets(a, b, r.polytope);
    EXPECT_TRUE(same_polytope(minkowski_sum(b, a, method()).polytope, r.polytope));
    if (HasFatalFailure()) return;
  }
}

// ---------------------------------------------------------------------------
// The shared families.

TEST_P(Conformance, AllPairsOfSmallSolids) {
  for (const std::string& x : small_solids())
    for (const std::string& y : small_solids())
      if (x <= y) expect(x, y);
}

TEST_P(Conformance, CubePlusGeodesicSpheres) {
  for (int level = 1; level <= 5; ++level) expect("cube", "sphere:" + std::to_string(level), {level <= 3, true});
}

TEST_P(Conformance, SphereAndRotatedSphere) { expect("sphere:3", "sphere:3@rot:5", kNoBruteForce); }

TEST_P(Conformance, MixedSolids) {
  expect("truncated-cube", "dodecahedron");
  expect("snub-cube", "truncated-icosahedron", kNoBruteForce);
}

TEST_P(Conformance, DioctagonalPairs) {
  expect("dioctagonal:17", "dioctagonal:17@rot:1,0,0,1");    // 90°: identical pyramids
  expect("dioctagonal:17", "dioctagonal:17@rot:100,0,0,99");  // approximately 90°
  expect("dioctagonal:9", "dioctagonal:9@rot:7");
}

TEST_P(Conformance, ZonotopesWithParallelEdges) {
  expect("zonotope:5:1", "zonotope:5:2");
  expect("zonotope:6:3", "zonotope:6:3");
  expect("zonotope:4:7", "cube");
  expect("zonotope:1,0,0:0,1,0:1,1,0:0,0,1", "zonotope:1,1,0:0,0,1:1,-1,2");
  // Parallel edges everywhere, equal and opposite edge vectors.
  expect("zonotope:6:3", "zonotope:6:3@neg");
  expect("zonotope:6:3", "zonotope:6:3@translate:1/2,1/2,0");
  expect("zonotope:5:1", "zonotope:5:1@scale:2");
}

TEST_P(Conformance, ThinBoxAndExtremeScales) {
  expect("box:1:1:1e-12", "sphere:2");
  expect("box:1e-12:2:3", "box:4:1e-12:5");
  expect("cube@scale:1e150", "octahedron@scale:1e-150");
  expect("sphere:2@scale:1e-150", "dodecahedron@scale:1e-150");
  expect("icosahedron@scale:1e150", "tetra@scale:1e150@rot:3");
  expect("cube@scale:1e-300", "cube@rot:1@scale:1e-300");
  // Rational coordinates below the normal range of doubles: their nearest
  // doubles carry no relative error bound.
  expect("tetra@rot:3@scale:1e-310", "cube@rot:5@scale:1e-310");
  expect("octahedron@rot:2@scale:1e-320", "icosahedron@scale:1e-300");
}

TEST_P(Conformance, PointReflections) {
  // A ⊕ −A (the configuration-space obstacle of A against itself): every arc
  // of A meets the antipodal image of itself.
  expect("tetra", "tetra@neg");
  expect("sphere:2", "sphere:2@neg");
  expect("truncated-tetrahedron@rot:5", "truncated-tetrahedron@rot:5@neg");
  expect("random:30:3", "random:30:3@neg");
  expect("icosahedron", "icosahedron@neg");
  expect("truncated-octahedron@rot:11", "truncated-octahedron@rot:11@neg");
  expect("dodecahedron@rot:3", "dodecahedron@rot:3@neg");
  expect("cuboctahedron@rot:17", "cuboctahedron@rot:17@neg");
  expect("sphere:2@rot:5", "sphere:2@rot:5@neg");
}

TEST_P(Conformance, NearlyIdenticalOperandsWithEqualRoundedDifferences) {
  // B is A with one vertex moved by 2^-60 along y: the edges at that vertex
  // differ from A's by 2^-60, below the rounding of their differences
  // (fl(0.5 − 2^-60) = 0.5), so the rounded differences are equal and the
  // exact ones are not.
  const std::vector<Vec3d> pts = {{0.3, 0, 0.7},    {1, 0.3, 0.2},     {-0.7, 1, 0.1},   {0.2, -0.9, 0.8},
                                  {0.1, 0.2, -1},   {-0.5, -0.4, -0.6}, {0.6, 0.7, 0.9},  {-0.8, -0.1, 0.5},
                                  {0.5, -0.5, -0.5}};
  std::vector<Point3> pa, pb;
  for (const Vec3d& v : pts) pa.emplace_back(v.x, v.y, v.z);
  pb = pa;
  pb[0] = Point3(0.3, 0x1p-60, 0.7);
  const ConvexPolytope a = ConvexPolytope::hull(pa), b = ConvexPolytope::hull(pb);
  ASSERT_TRUE(a.coordinates_are_doubles());
  ASSERT_TRUE(b.coordinates_are_doubles());
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  expect(a, b, "A + A with one vertex moved by 2^-60");
  expect(a, a.negated(), "A + -A");
  expect(b, a.negated(), "B + -A");
}

TEST_P(Conformance, QuarterTurnsAndArcsThroughVertices) {
  // Exact quarter turns map facet normals onto facet normals and arcs onto
  // arcs: normals on arcs, arcs through vertices, arcs along arcs.
  expect("cube", "cube@rot:1,1,0,0");
  expect("cube", "octahedron@rot:1,1,0,0");
  expect("octahedron", "octahedron@rot:1,1,0,0");
  expect("cuboctahedron", "rhombic-dodecahedron@rot:1,0,0,1");
  expect("truncated-octahedron", "cube@rot:1,1,1,1");
  expect("dioctagonal:17", "dioctagonal:17@rot:1,1,0,0");
  // Neighbouring facets parallel to the other operand's: arcs overlapping.
  expect("rhombicuboctahedron", "truncated-cuboctahedron");
  // Facet normals on the other operand's arcs, under a common rational rotation.
  expect("cube@rot:9", "rhombic-dodecahedron@rot:9");
}

TEST_P(Conformance, NearlyDegeneratePairs) {
  // Rotations by a tiny angle: arcs cross at very small angles, features
  // nearly coincide.
  expect("cube", "cube@rot:100000,1,0,0");
  expect("cube", "cube@rot:1000000,1,1,1");
  expect("sphere:2", "sphere:2@rot:100000,1,2,3");
  expect("icosahedron", "icosahedron@rot:1000000,0,0,1");
}

TEST_P(Conformance, FarApartOperands) {
  // Translations change no normal: the same structure, shifted.
  expect("cube@translate:1e6,0,0", "octahedron@translate:0,-1e6,3");
  expect("sphere:2@translate:1/3,1/7,1/11", "tetra@translate:-1e-9,0,0");
  expect(cat("truncated-octahedron@rot:11").translated(Q("1/3", "-7/5", "2")), cat("icosahedron"),
         "translated truncated-octahedron@rot:11 + icosahedron");
}

// 1200 pairs with fixed seeds (4 tests of 100 seeds, 3 pairs per seed):
// random hulls, lattice polytopes with many coplanar points, and random exact
// rotations of catalog solids.
void random_pairs(Method m, unsigned first_seed, unsigned last_seed) {
  int checked = for_each_random_pair(
      first_seed, last_seed, [m](const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label, unsigned seed) {
        if (const auto checks = random_pair_checks(m, seed)) expect_conforms(m, a, b, label, *checks);
      });
  EXPECT_EQ(checked, 3 * int(last_seed - first_seed + 1));
}

TEST_P(Conformance, RandomPairsSeeds1To100) { random_pairs(method(), 1, 100); }
TEST_P(Conformance, RandomPairsSeeds101To200) { random_pairs(method(), 101, 200); }
TEST_P(Conformance, RandomPairsSeeds201To300) { random_pairs(method(), 201, 300); }
TEST_P(Conformance, RandomPairsSeeds301To400) { random_pairs(method(), 301, 400); }

// ---------------------------------------------------------------------------

TEST(ConformanceOperands, DegenerateOperandsAreRefusedBeforeAnyMethod) {
  // A flat polygon is not a polytope: no method ever sees one.
  std::vector<Point3> flat = {P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(1, 1, 0)};
  EXPECT_THROW(ConvexPolytope::hull(flat, "flat"), InputError);
}
