// The harness every Minkowski-sum method is tested with, in one place: the
// methods, the oracle contract a method's result must satisfy (checked
// against the chms oracle, and the oracle itself against facts that need no
// hull), and the families of operand pairs the contract is checked on.  The
// parameterised suite over every method is test_conformance.cpp; the
// per-method suites use the same contract for their own cases.
#pragma once

#include <minksum/catalog.hpp>
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "test_support.hpp"

namespace minksum::testing {

inline ConvexPolytope cat(const std::string& spec) { return catalog_polytope(spec); }

// ---------------------------------------------------------------------------
// The methods and what each records besides the polytope.

// Every method, the oracle last.
inline const std::vector<Method>& all_methods() {
  static const std::vector<Method> methods = {Method::walk,   Method::cvms, Method::essdms,
                                              Method::mssd,   Method::cgm,  Method::chms};
  return methods;
}

// Every method but the oracle records face_A(n) and face_B(n) per facet.
inline bool tracks_provenance(Method m) { return m != Method::chms; }
// The slope-diagram methods record the intersection case of each facet.
inline bool records_facet_cases(Method m) { return m == Method::essdms || m == Method::mssd; }
// cgm counts the facet vertices of its overlay (first counter).
inline bool counts_overlay_vertices(Method m) { return m == Method::cgm; }
// chms makes B ⊕ A as the hull of the same points as A ⊕ B: recomputing it
// checks nothing more.
inline bool commutes_by_construction(Method m) { return m == Method::chms; }
// walk builds its half-edge structure directly, with no validation (the
// others pass theirs through ConvexPolytope's validating builder or hull).
inline bool builds_unvalidated(Method m) { return m == Method::walk; }

// The value of a named counter of a result (a failure if there is none).
inline long long counter(const SumResult& r, const std::string& name) {
  for (const auto& [n, v] : r.counters)
    if (n == name) return v;
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

// Facets per origin (indexed by FacetOrigin) from the recorded provenance.
inline std::array<long, 5> origin_counts(const SumResult& r) {
  std::array<long, 5> c{0, 0, 0, 0, 0};
  for (const auto& p : r.facet_provenance) ++c.at(std::size_t(p.origin()));
  return c;
}

// Facets per slope-diagram intersection case (indexed by facet_case).
inline std::array<long, 4> case_counts(const SumResult& r) {
  std::array<long, 4> c{0, 0, 0, 0};
  for (auto k : r.facet_case) ++c.at(k);
  return c;
}

// The intersection case a facet must come from, given the faces of A and B
// behind it: two coincident facet points, a facet point on an edge arc, two
// crossing edge arcs, or a facet point inside a vertex region.
inline const char* expected_case_name(const FacetProvenance& p) {
  switch (p.origin()) {
    case FacetOrigin::facet_facet: return "two_facet_points";
    case FacetOrigin::facet_edge: return "facet_point_on_edge_arc";
    case FacetOrigin::edge: return "two_edge_arcs";
    default: return "facet_point_in_vertex_region";
  }
}

// ---------------------------------------------------------------------------
// Facts of A ⊕ B that need no hull.

// The support function h_P(n) = max <n, p> over the vertices of P.
inline Rational support(const ConvexPolytope& p, const Point3& n) {
  Rational best = dot(n, p.point(0));
  for (Index i = 1; i < p.num_vertices(); ++i) best = std::max(best, Rational(dot(n, p.point(i))));
  return best;
}

// Every facet normal of A and of B is a facet normal of s, and every facet
// plane <n, x> = d of s has d = h_A(n) + h_B(n).  With every vertex of s a
// sum a_i + b_j (checked by the contract) this makes s exactly A ⊕ B: s lies
// in A ⊕ B, and A ⊕ B lies below every facet plane of s.
// O(F (V_A + V_B)) exact.
inline void expect_supporting_facets(const ConvexPolytope& a, const ConvexPolytope& b, const ConvexPolytope& s) {
  std::set<std::tuple<Integer, Integer, Integer>> normals;
  for (Index f = 0; f < s.num_facets(); ++f) normals.insert(normal_direction(s.plane(f)));
  for (const ConvexPolytope* p : {&a, &b})
    for (Index f = 0; f < p->num_facets(); ++f)
      EXPECT_TRUE(normals.count(normal_direction(p->plane(f)))) << "input facet " << f << " has no parallel facet";
  for (Index f = 0; f < s.num_facets(); ++f) {
    const Plane& pl = s.plane(f);
    const Point3 n = pl.normal();
    EXPECT_EQ(support(a, n) + support(b, n), Rational(pl.d)) << "facet " << f << " is not a supporting plane";
  }
}

// k A + t, made without any Minkowski sum (the hull of the moved points): for
// a positive homothet B = λA + t of A, A ⊕ B = (1 + λ) A + t.
inline ConvexPolytope homothet(const ConvexPolytope& p, const Rational& k, const Point3& t = Point3()) {
  std::vector<Point3> pts;
  for (const Point3& x : p.points()) pts.push_back(k * x + t);
  return ConvexPolytope::hull(pts);
}

// ---------------------------------------------------------------------------
// The oracle contract.

// What the contract checks beyond its always-on part.
struct Checks {
  // O(F (V_A + V_B)) exact work: the recorded facet provenance equal to
  // facet_provenance() (brute force), and, for the oracle when nothing else
  // is known, the facts above.
  bool brute_force = true;
  // Further sums: B ⊕ A with the same method (the same polytope, the same
  // facet cases) and cgm's cross-check of its overlay against the sum's own
  // cubical Gaussian map.
  bool recompute = true;
};

// The result r = m(a, b) against `reference`, the exact sum: chms(a, b) or a
// closed form; null only for m = chms with no closed form, which is then
// checked (on brute_force) against the facts that need no hull.  Always:
//   * r names m;
//   * the counts, the vertex set and the facet planes are the reference's;
//   * V - E + F = 2, and every invariant of ConvexPolytope re-checked from
//     scratch where the method builds its structure without validation (the
//     others' results come out of ConvexPolytope's validating builder);
//   * every vertex v is a.point(i) + b.point(j), (i, j) = vertex_origin[v];
//   * one provenance per facet where the method tracks it, and one
//     intersection case per facet, consistent with the provenance, where it
//     records them.
inline void check_conforms(Method m, const ConvexPolytope& a, const ConvexPolytope& b, const SumResult& r,
                           const ConvexPolytope* reference, Checks checks) {
  SCOPED_TRACE(method_name(m));
  ASSERT_EQ(r.method, m);
  const ConvexPolytope& s = r.polytope;
  if (reference) {
    ASSERT_EQ(s.num_vertices(), reference->num_vertices());
    ASSERT_EQ(s.num_edges(), reference->num_edges());
    ASSERT_EQ(s.num_facets(), reference->num_facets());
    EXPECT_TRUE(same_polytope(s, *reference));
  }
  EXPECT_EQ(s.euler_characteristic(), 2);
  if (builds_unvalidated(m)) { ASSERT_EQ(s.check_invariants(), ""); }
  ASSERT_EQ(r.vertex_origin.size(), s.num_vertices());
  for (Index v = 0; v < s.num_vertices(); ++v) {
    auto [i, j] = r.vertex_origin[v];
    ASSERT_LT(i, a.num_vertices());
    ASSERT_LT(j, b.num_vertices());
    ASSERT_EQ(s.point(v), a.point(i) + b.point(j)) << "vertex " << v;
  }
  if (tracks_provenance(m)) { ASSERT_EQ(r.facet_provenance.size(), s.num_facets()); }
  if (records_facet_cases(m)) {
    ASSERT_EQ(r.facet_case.size(), s.num_facets());
    ASSERT_EQ(r.facet_case_names, (std::vector<std::string>{"two_facet_points", "facet_point_on_edge_arc",
                                                            "two_edge_arcs", "facet_point_in_vertex_region"}));
    for (Index f = 0; f < s.num_facets(); ++f)
      EXPECT_EQ(r.facet_case_names.at(r.facet_case[f]), expected_case_name(r.facet_provenance[f])) << "facet " << f;
  }
  if (checks.brute_force) {
    if (tracks_provenance(m)) { EXPECT_EQ(r.facet_provenance, facet_provenance(a, b, s)); }
    if (!reference) expect_supporting_facets(a, b, s);
  }
  if (checks.recompute && !commutes_by_construction(m)) {
    const SumResult ba = minkowski_sum(b, a, m);
    EXPECT_TRUE(same_polytope(ba.polytope, s)) << "B + A differs from A + B";
    if (records_facet_cases(m)) { EXPECT_EQ(case_counts(ba), case_counts(r)); }
    if (counts_overlay_vertices(m)) {
      // The overlay's facet vertices, with their copies on cube edges and
      // corners, are exactly the real vertices of the sum's own CGM.
      const auto g = CubicalGaussianMap::from_polytope(s);
      EXPECT_EQ(g.check_invariants(), "");
      long long real = 0;
      for (int k = 0; k < 6; ++k) real += g.map(k).num_real_vertices();
      ASSERT_FALSE(r.counters.empty());
      EXPECT_EQ(r.counters.front().first, "overlay_facet_vertices");
      EXPECT_EQ(r.counters.front().second, real);
    }
  }
}

// m(a, b), checked by the contract against `closed_form` when given, else
// against chms(a, b) (computed here; for m = chms itself, against the facts),
// and returned for further checks.
inline SumResult conforming_sum(Method m, const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                                Checks checks = {}, const ConvexPolytope* closed_form = nullptr) {
  SCOPED_TRACE(label);
  SumResult r = minkowski_sum(a, b, m);
  if (closed_form || m == Method::chms) {
    check_conforms(m, a, b, r, closed_form, checks);
  } else {
    const SumResult oracle = minkowski_sum(a, b, Method::chms);
    check_conforms(m, a, b, r, &oracle.polytope, checks);
  }
  return r;
}

inline void expect_conforms(Method m, const ConvexPolytope& a, const ConvexPolytope& b, const std::string& label,
                            Checks checks = {}) {
  conforming_sum(m, a, b, label, checks);
}

inline void expect_conforms(Method m, const std::string& a, const std::string& b, Checks checks = {}) {
  conforming_sum(m, cat(a), cat(b), a + " + " + b, checks);
}

// Every method on one pair against one oracle computation (the oracle's own
// result checked by the same contract, against the facts on brute_force).
inline void expect_all_methods_conform(const ConvexPolytope& a, const ConvexPolytope& b, Checks checks) {
  const SumResult oracle = minkowski_sum(a, b, Method::chms);
  check_conforms(Method::chms, a, b, oracle, nullptr, checks);
  for (Method m : all_methods())
    if (m != Method::chms) check_conforms(m, a, b, minkowski_sum(a, b, m), &oracle.polytope, checks);
}

// ---------------------------------------------------------------------------
// The families of operand pairs.

// Small catalog solids: every pair of them is a test case.
inline const std::vector<std::string>& small_solids() {
  static const std::vector<std::string> solids = {
      "tetra",           "cube",           "octahedron",           "dodecahedron",
      "icosahedron",     "truncated-tetrahedron", "cuboctahedron", "truncated-cube",
      "truncated-octahedron", "rhombicuboctahedron", "triakis-tetrahedron", "rhombic-dodecahedron",
      "triakis-octahedron", "tetrakis-hexahedron", "rhombic-triacontahedron", "icosidodecahedron",
  };
  return solids;
}

// Hull of n random points of the integer lattice [-r, r]^3 (many coplanar
// and collinear points); a flat sample gets more points until it is solid.
inline ConvexPolytope random_lattice_polytope(std::mt19937_64& rng, int n, long r) {
  auto coordinate = [&] { return long(rng() % (2 * r + 1)) - r; };
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(P(coordinate(), coordinate(), coordinate()));
  for (;;) {
    try {
      return ConvexPolytope::hull(pts);
    } catch (const InputError&) {
      pts.push_back(P(coordinate(), coordinate(), coordinate()));
    }
  }
}

// Three pairs per seed, with fixed seeds: two random hulls, two lattice
// polytopes, two exact random rotations of catalog solids.  Calls
// check(a, b, label, seed) for each pair (the label names the pair and the
// seed is in a SCOPED_TRACE, so a failure prints both) and returns how many
// pairs were checked; stops early after a fatal failure.
template <class Check>
int for_each_random_pair(unsigned first_seed, unsigned last_seed, Check check) {
  const std::vector<std::string> solids = {"tetra", "cube", "octahedron", "dodecahedron", "icosahedron",
                                           "cuboctahedron", "truncated-cube", "rhombic-dodecahedron"};
  int done = 0;
  for (unsigned seed = first_seed; seed <= last_seed; ++seed) {
    std::mt19937_64 rng(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    {
      std::string a = "random:" + std::to_string(4 + rng() % 30) + ":" + std::to_string(seed);
      std::string b = "random:" + std::to_string(4 + rng() % 30) + ":" + std::to_string(seed + 1000);
      check(catalog_polytope(a), catalog_polytope(b), a + " + " + b, seed);
    }
    {
      ConvexPolytope a = random_lattice_polytope(rng, 8 + int(rng() % 20), 2);
      ConvexPolytope b = random_lattice_polytope(rng, 8 + int(rng() % 20), 3);
      check(a, b, "lattice pair", seed);
    }
    {
      std::string a = solids[rng() % solids.size()] + "@rot:" + std::to_string(rng() % 100000);
      std::string b = solids[rng() % solids.size()] + "@rot:" + std::to_string(rng() % 100000);
      check(catalog_polytope(a), catalog_polytope(b), a + " + " + b, seed);
    }
    done += 3;
    if (::testing::Test::HasFatalFailure()) break;
  }
  return done;
}

// Consecutive ranges of seeds, one test each: `count` ranges of `size` seeds
// from `first`, named "Seeds<first>To<last>".
struct SeedRange {
  unsigned first = 0, last = 0;
};
inline std::vector<SeedRange> seed_ranges(unsigned first, unsigned size, unsigned count) {
  std::vector<SeedRange> v;
  for (unsigned k = 0; k < count; ++k) v.push_back({first + k * size, first + (k + 1) * size - 1});
  return v;
}
inline std::string seed_range_name(const ::testing::TestParamInfo<SeedRange>& info) {
  return "Seeds" + std::to_string(info.param.first) + "To" + std::to_string(info.param.last);
}
inline void PrintTo(const SeedRange& r, std::ostream* os) { *os << "seeds " << r.first << " to " << r.last; }

// The checks on a random pair, or none when the method skips the pair:
// brute force every tenth seed; B ⊕ A on every seed, but every fifth only for
// cgm (its overlay is the slowest method on these small pairs); the oracle,
// whose result has nothing to be compared with but the facts of the brute
// force, only on the seeds where they are checked.
inline std::optional<Checks> random_pair_checks(Method m, unsigned seed) {
  const bool brute_force = seed % 10 == 0;
  if (m == Method::chms && !brute_force) return std::nullopt;
  return Checks{brute_force, m != Method::cgm || seed % 5 == 0};
}

}  // namespace minksum::testing
