// The fixed solids of the catalog: the Platonic, Archimedean and Catalan
// solids, every one with exact rational coordinates and exactly planar facets.
//
// How exact planarity survives the rational approximation of √2, φ and the
// tribonacci constant (docs/catalog.md lists every constant):
//   * a solid whose facets are all triangles is planar whatever the
//     coordinates (icosahedron, triakis-*, tetrakis-*, pentakis-*, disdyakis-*);
//   * symmetry: a polygon mapped to itself by enough symmetries of the point
//     set is planar for every value of the parameter (the octagons of the
//     truncated cube lie in |x| = 1, the squares of the snub cube in |x| = τ);
//   * a planarity condition solved exactly (the dodecahedron's pentagons give
//     s = 2t − t², the icosidodecahedron's give its third coordinate, one
//     snub-dodecahedron pentagon is made planar by moving two vertices);
//   * a Minkowski sum has planar facets (rhombicosidodecahedron =
//     icosahedron ⊕ t·dodecahedron);
//   * the polar dual of any exact polytope has exactly planar facets: the
//     dual vertices of the facets around a vertex v all satisfy <v, y> = 1.
//     Every Catalan solid is the polar dual of its Archimedean solid or the
//     other way round.
// All solids are centred at the origin (which the polar duals need).
#include "catalog/catalog_internal.hpp"

#include <algorithm>
#include <set>

namespace minksum::catalog_detail {

namespace {

// ---------------------------------------------------------------------------
// Constants: each irrational constant c is replaced by round(c·2^24)/2^24.
Rational grid(long n) {
  Rational q(n, 1L << 24);
  q.canonicalize();
  return q;
}
const Rational& phi() {  // golden ratio 1.6180339887...
  static const Rational v = grid(27146106);
  return v;
}
const Rational& sqrt2() {  // 1.4142135623...
  static const Rational v = grid(23726566);
  return v;
}
const Rational& tribonacci() {  // real root of x³ − x² − x − 1, 1.8392867552...
  static const Rational v = grid(30858111);
  return v;
}

Point3 P(const Rational& x, const Rational& y, const Rational& z) { return Point3(x, y, z); }
Point3 G(long x, long y, long z) { return Point3(grid(x), grid(y), grid(z)); }  // n/2^24 each

// Orbits under groups of signed coordinate permutations.
enum class Perms { cyclic, all };
enum class Signs {
  all,           // every sign change
  even_minus,    // an even number of coordinates negated
  snub,          // even permutations with an odd number of minus signs, odd
                 // permutations with an even number (the snub cube's rule)
};

void add_orbit(std::vector<Point3>& out, const Point3& rep, Perms perms, Signs signs) {
  static const int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  const int nperm = perms == Perms::cyclic ? 3 : 6;
  std::set<Point3> seen(out.begin(), out.end());
  for (int pi = 0; pi < nperm; ++pi) {
    const bool odd_perm = pi >= 3;
    for (int s = 0; s < 8; ++s) {
      const int minus = (s & 1) + ((s >> 1) & 1) + ((s >> 2) & 1);
      if (signs == Signs::even_minus && minus % 2 != 0) continue;
      if (signs == Signs::snub && (minus % 2 == 0) != odd_perm) continue;
      Point3 q;
      for (int i = 0; i < 3; ++i) {
        q[i] = rep[kPerm[pi][i]];
        if (s & (1 << i)) q[i] = -q[i];
      }
      if (seen.insert(q).second) out.push_back(q);
    }
  }
}
std::vector<Point3> orbit(const Point3& rep, Perms perms, Signs signs) {
  std::vector<Point3> v;
  add_orbit(v, rep, perms, signs);
  return v;
}
// The pyritohedral group (cyclic permutations, all signs): the symmetry of
// the icosahedral solids that survives a rational φ.
std::vector<Point3> pyrito(std::initializer_list<Point3> reps) {
  std::vector<Point3> v;
  for (const Point3& r : reps) add_orbit(v, r, Perms::cyclic, Signs::all);
  return v;
}
std::vector<Point3> octa(const Point3& rep) { return orbit(rep, Perms::all, Signs::all); }

ConvexPolytope hull(const std::vector<Point3>& pts, const std::string& source) { return exact_hull(pts, source); }

// ---------------------------------------------------------------------------
// Platonic.

ConvexPolytope tetrahedron(const std::string& src) {
  return hull(orbit(P(1, 1, 1), Perms::all, Signs::even_minus), src);
}
ConvexPolytope cube(const std::string& src) { return make_box(2, 2, 2, src); }
ConvexPolytope octahedron(const std::string& src) { return hull(octa(P(1, 0, 0)), src); }
ConvexPolytope icosahedron(const std::string& src) { return make_sphere(1, src); }

// The dodecahedron dual to the icosahedron cyc(0, ±1, ±t): (±1, ±1, ±1) and
// cyc(0, ±t, ±s) with s = 2t − t² (= 1/φ when t = φ).  Its pentagon through
// (0, t, ±s), (1, 1, ±1)... lies in one plane exactly when s = 2t − t².
std::vector<Point3> dodecahedron_points() {
  const Rational& t = phi();
  const Rational s = 2 * t - t * t;
  std::vector<Point3> v = octa(P(1, 1, 1));
  add_orbit(v, P(0, t, s), Perms::cyclic, Signs::all);
  return v;
}
ConvexPolytope dodecahedron(const std::string& src) { return hull(dodecahedron_points(), src); }

// ---------------------------------------------------------------------------
// Archimedean.

ConvexPolytope truncated_tetrahedron(const std::string& src) {
  return hull(orbit(P(3, 1, 1), Perms::all, Signs::even_minus), src);
}
ConvexPolytope cuboctahedron(const std::string& src) { return hull(octa(P(1, 1, 0)), src); }
ConvexPolytope truncated_cube(const std::string& src) {
  return hull(octa(P(sqrt2() - 1, 1, 1)), src);  // octagons in |x| = 1, |y| = 1, |z| = 1
}
ConvexPolytope truncated_octahedron(const std::string& src) { return hull(octa(P(0, 1, 2)), src); }
ConvexPolytope rhombicuboctahedron(const std::string& src) {
  return hull(octa(P(1, 1, 1 + sqrt2())), src);
}
ConvexPolytope truncated_cuboctahedron(const std::string& src) {
  return hull(octa(P(1, 1 + sqrt2(), 1 + 2 * sqrt2())), src);
}
// Even permutations of (±1, ±1/τ, ±τ) with an even number of plus signs and
// odd permutations with an odd number, scaled by τ: (τ, 1, τ²).
ConvexPolytope snub_cube(const std::string& src) {
  const Rational& t = tribonacci();
  return hull(orbit(P(t, 1, t * t), Perms::all, Signs::snub), src);
}
// Twice the canonical coordinates: cyc(0, 0, ±2φ) and cyc(±φ, ±1, ±φ²).
// Exact version: cyc(0, 0, ±2t), cyc(±a, ±1, ±(1 + t)) with a = 1 + 2t − t²
// (≈ φ), the value that makes the pentagon through (0, 0, 2t),
// (±a, 1, 1 + t), (±1, 1 + t, a) planar: 2t = (a·1 − (1+t)²) / (1 − (1+t)).
ConvexPolytope icosidodecahedron(const std::string& src) {
  const Rational& t = phi();
  const Rational a = 1 + 2 * t - t * t;
  return hull(pyrito({P(0, 0, 2 * t), P(a, 1, 1 + t)}), src);
}
// The Minkowski sum of the icosahedron cyc(0, ±1, ±t) and t times the dual
// dodecahedron (edge lengths 2 and 2ts ≈ 2): 20 triangles, 12 pentagons and
// 30 (nearly square) parallelograms, all exactly planar.
ConvexPolytope rhombicosidodecahedron(const std::string& src) {
  const Rational& t = phi();
  const std::vector<Point3> ico = pyrito({P(0, 1, t)});
  const std::vector<Point3> dod = dodecahedron_points();
  std::vector<Point3> sums;
  for (const Point3& a : ico)
    for (const Point3& b : dod) sums.push_back(a + t * b);
  return hull(sums, src);
}

// ---------------------------------------------------------------------------
// Catalan solids given by rounded coordinates (all facets triangles), with
// midradius 1 before rounding; orbit representatives n/2^24 under the
// pyritohedral group.  Their duals are the three truncated icosahedral solids.

ConvexPolytope triakis_icosahedron(const std::string& src) {
  return hull(pyrito({G(0, 10368890, 16777216), G(9733784, 9733784, 9733784), G(0, 15749593, 6015809)}), src);
}
ConvexPolytope pentakis_dodecahedron(const std::string& src) {
  return hull(pyrito({G(0, 9197807, 14882364), G(10368890, 10368890, 10368890), G(0, 16777216, 6408326)}), src);
}
ConvexPolytope disdyakis_triacontahedron(const std::string& src) {
  return hull(pyrito({G(0, 9662159, 15633702), G(9952572, 9952572, 9952572), G(0, 16103599, 6151027),
                      G(16926794, 0, 0), G(8463397, 5230667, 13694064)}),
              src);
}
ConvexPolytope truncated_dodecahedron(const std::string& src) { return polar_dual(triakis_icosahedron(src), src); }
ConvexPolytope truncated_icosahedron(const std::string& src) { return polar_dual(pentakis_dodecahedron(src), src); }
ConvexPolytope truncated_icosidodecahedron(const std::string& src) {
  return polar_dual(disdyakis_triacontahedron(src), src);
}

// The snub dodecahedron (midradius 1): the five vertices of the pentagon
// around the axis (0, 1, φ), rounded to n/2^24, then v3 and v4 moved along z
// onto the plane of v0, v1, v2 so that the pentagon is exactly planar; the
// other 55 vertices are their images under the 12 rotations (x, y, z) ->
// cyclic permutations with an even number of sign changes, which permute the
// 12 pentagons.  The 80 triangles are planar anyway.
ConvexPolytope snub_dodecahedron(const std::string& src) {
  Point3 v[5] = {G(5144478, 4541936, 15823452), G(5826954, 11322653, 11632738), G(-1543222, 13970145, 9996498),
                 G(-6780718, 8825668, 13175960), G(-2647492, 2998714, 16777216)};
  const Point3 n = cross(v[1] - v[0], v[2] - v[0]);
  const Rational d = dot(n, v[0]);
  for (int i = 3; i < 5; ++i) v[i].z = (d - n.x * v[i].x - n.y * v[i].y) / n.z;
  std::vector<Point3> pts;
  for (const Point3& r : v) add_orbit(pts, r, Perms::cyclic, Signs::even_minus);
  return hull(pts, src);
}

// ---------------------------------------------------------------------------
// Catalan solids as duals of exact Archimedean solids: the polar dual with
// respect to the sphere of radius m, where m² = the smallest |edge midpoint|²
// of the Archimedean solid (its midradius²) rounded to a multiple of 1/64 to
// keep the numbers small.  The dual vertex of facet plane n·x = d is m²·n/d.
// When m² is a multiple of 1/64 (every solid with integer coordinates) the
// pair forms the canonical compound exactly (same midradius, edges crossing
// at right angles), otherwise up to the rounding.

ConvexPolytope canonical_dual(const ConvexPolytope& p, const std::string& source) {
  Rational m2 = -1;
  for (Index e = 0; e < p.num_edges(); ++e) {
    const Point3 mid = Rational(1, 2) * (p.point(p.origin(2 * e)) + p.point(p.target(2 * e)));
    const Rational r2 = dot(mid, mid);
    if (m2 < 0 || r2 < m2) m2 = r2;
  }
  {
    // round(m2 * 64) / 64, exactly: floor((128 num + den) / (2 den)).
    Integer q;
    const Integer num = 128 * m2.get_num() + m2.get_den(), den = 2 * m2.get_den();
    mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    m2 = Rational(q, 64);
    m2.canonicalize();
  }
  std::vector<Point3> pts;
  pts.reserve(p.num_facets());
  for (Index f = 0; f < p.num_facets(); ++f) {
    const Plane& pl = p.plane(f);
    const Rational k = m2 / Rational(pl.d);  // d > 0: the solids are centred
    pts.emplace_back(k * Rational(pl.a), k * Rational(pl.b), k * Rational(pl.c));
  }
  return exact_hull(pts, source);
}

ConvexPolytope triakis_tetrahedron(const std::string& s) { return canonical_dual(truncated_tetrahedron(s), s); }
ConvexPolytope rhombic_dodecahedron(const std::string& s) { return canonical_dual(cuboctahedron(s), s); }
ConvexPolytope triakis_octahedron(const std::string& s) { return canonical_dual(truncated_cube(s), s); }
ConvexPolytope tetrakis_hexahedron(const std::string& s) { return canonical_dual(truncated_octahedron(s), s); }
ConvexPolytope deltoidal_icositetrahedron(const std::string& s) { return canonical_dual(rhombicuboctahedron(s), s); }
ConvexPolytope disdyakis_dodecahedron(const std::string& s) { return canonical_dual(truncated_cuboctahedron(s), s); }
ConvexPolytope pentagonal_icositetrahedron(const std::string& s) { return canonical_dual(snub_cube(s), s); }
ConvexPolytope rhombic_triacontahedron(const std::string& s) { return canonical_dual(icosidodecahedron(s), s); }
ConvexPolytope deltoidal_hexecontahedron(const std::string& s) { return canonical_dual(rhombicosidodecahedron(s), s); }
ConvexPolytope pentagonal_hexecontahedron(const std::string& s) { return canonical_dual(snub_dodecahedron(s), s); }

}  // namespace

ConvexPolytope exact_hull(const std::vector<Point3>& points, const std::string& source) {
  // ConvexPolytope::hull numbers vertices in input order and sorts facets,
  // so a spec gives the same polytope on every run.
  return ConvexPolytope::hull(points, source);
}

ConvexPolytope polar_dual(const ConvexPolytope& p, const std::string& source) {
  std::vector<Point3> pts;
  pts.reserve(p.num_facets());
  for (Index f = 0; f < p.num_facets(); ++f) {
    const Plane& pl = p.plane(f);
    if (sgn(pl.d) <= 0)
      throw InputError(source, "", "polar dual needs the origin strictly inside the polytope");
    const Rational d(pl.d);
    pts.emplace_back(Rational(pl.a) / d, Rational(pl.b) / d, Rational(pl.c) / d);
  }
  return exact_hull(pts, source);
}

const std::vector<FixedSolid>& fixed_solids() {
  static const std::vector<FixedSolid> solids = {
      // Platonic.
      {"tetra", {"tetrahedron"}, "regular tetrahedron (1,1,1) (1,-1,-1) (-1,1,-1) (-1,-1,1)", 4, 6, 4, tetrahedron},
      {"cube", {"hexahedron"}, "cube [-1,1]^3 (volume 8)", 8, 12, 6, cube},
      {"octahedron", {}, "regular octahedron (±1,0,0), (0,±1,0), (0,0,±1)", 6, 12, 8, octahedron},
      {"dodecahedron", {}, "regular dodecahedron, φ ≈ 27146106/2^24, pentagons exactly planar", 20, 30, 12,
       dodecahedron},
      {"icosahedron", {}, "regular icosahedron in the unit sphere (identical to sphere:1)", 12, 30, 20, icosahedron},
      // Archimedean.
      {"truncated-tetrahedron", {}, "Archimedean: permutations of (3,1,1), even number of minus signs", 12, 18, 8,
       truncated_tetrahedron},
      {"cuboctahedron", {}, "Archimedean: permutations of (±1,±1,0)", 12, 24, 14, cuboctahedron},
      {"truncated-cube", {}, "Archimedean: permutations of (±ξ,±1,±1), ξ = 23726566/2^24 − 1 ≈ √2−1", 24, 36, 14, truncated_cube},
      {"truncated-octahedron", {}, "Archimedean: permutations of (0,±1,±2)", 24, 36, 14, truncated_octahedron},
      {"rhombicuboctahedron", {}, "Archimedean: permutations of (±1,±1,±(1+√2)), √2 ≈ 23726566/2^24", 24, 48, 26,
       rhombicuboctahedron},
      {"truncated-cuboctahedron", {"great-rhombicuboctahedron"},
       "Archimedean: permutations of (±1,±(1+√2),±(1+2√2)), √2 ≈ 23726566/2^24", 48, 72, 26, truncated_cuboctahedron},
      {"snub-cube", {}, "Archimedean (chiral): tribonacci constant ≈ 30858111/2^24, squares exactly planar", 24, 60, 38,
       snub_cube},
      {"icosidodecahedron", {}, "Archimedean: φ ≈ 27146106/2^24, pentagons made exactly planar", 30, 60, 32,
       icosidodecahedron},
      {"truncated-dodecahedron", {}, "Archimedean: polar dual of triakis-icosahedron", 60, 90, 32,
       truncated_dodecahedron},
      {"truncated-icosahedron", {}, "Archimedean (soccer ball): polar dual of pentakis-dodecahedron", 60, 90, 32,
       truncated_icosahedron},
      {"rhombicosidodecahedron", {}, "Archimedean: icosahedron ⊕ φ·dodecahedron (exact Minkowski sum), φ ≈ 27146106/2^24", 60, 120, 62,
       rhombicosidodecahedron},
      {"truncated-icosidodecahedron", {"great-rhombicosidodecahedron"},
       "Archimedean: polar dual of disdyakis-triacontahedron", 120, 180, 62, truncated_icosidodecahedron},
      {"snub-dodecahedron", {}, "Archimedean (chiral): rounded, one pentagon orbit made exactly planar", 60, 150, 92,
       snub_dodecahedron},
      // Catalan.
      {"triakis-tetrahedron", {}, "Catalan: canonical dual (same midsphere) of truncated-tetrahedron", 8, 18, 12, triakis_tetrahedron},
      {"rhombic-dodecahedron", {}, "Catalan: canonical dual (same midsphere) of cuboctahedron", 14, 24, 12, rhombic_dodecahedron},
      {"triakis-octahedron", {}, "Catalan: canonical dual (same midsphere) of truncated-cube", 14, 36, 24, triakis_octahedron},
      {"tetrakis-hexahedron", {}, "Catalan: canonical dual (same midsphere) of truncated-octahedron", 14, 36, 24, tetrakis_hexahedron},
      {"deltoidal-icositetrahedron", {}, "Catalan: canonical dual (same midsphere) of rhombicuboctahedron", 26, 48, 24,
       deltoidal_icositetrahedron},
      {"disdyakis-dodecahedron", {}, "Catalan: canonical dual (same midsphere) of truncated-cuboctahedron", 26, 72, 48,
       disdyakis_dodecahedron},
      {"pentagonal-icositetrahedron", {}, "Catalan (chiral): canonical dual of snub-cube", 38, 60, 24,
       pentagonal_icositetrahedron},
      {"rhombic-triacontahedron", {}, "Catalan: canonical dual (same midsphere) of icosidodecahedron", 32, 60, 30,
       rhombic_triacontahedron},
      {"triakis-icosahedron", {}, "Catalan: canonical coordinates rounded to multiples of 2^-24", 32, 90, 60,
       triakis_icosahedron},
      {"pentakis-dodecahedron", {}, "Catalan: canonical coordinates rounded to multiples of 2^-24", 32, 90, 60,
       pentakis_dodecahedron},
      {"deltoidal-hexecontahedron", {}, "Catalan: canonical dual (same midsphere) of rhombicosidodecahedron", 62, 120, 60,
       deltoidal_hexecontahedron},
      {"disdyakis-triacontahedron", {}, "Catalan: canonical coordinates rounded to multiples of 2^-24", 62, 180, 120,
       disdyakis_triacontahedron},
      {"pentagonal-hexecontahedron", {}, "Catalan (chiral): canonical dual of snub-dodecahedron", 92, 150, 60,
       pentagonal_hexecontahedron},
  };
  return solids;
}

const FixedSolid* find_fixed_solid(const std::string& name) {
  for (const FixedSolid& s : fixed_solids()) {
    if (s.name == name) return &s;
    for (const std::string& a : s.aliases)
      if (a == name) return &s;
  }
  return nullptr;
}

}  // namespace minksum::catalog_detail
