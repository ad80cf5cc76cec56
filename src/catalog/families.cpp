// Parameterised catalog families: sphere:L, dioctagonal:N, random:N:SEED,
// zonotope:N:SEED (and explicit generators), box:X:Y:Z, ball:N, prism:N.
//
// Floating point here is limited to + - * / and sqrt, one operation per
// statement where a sum meets a product, so the results are bit-identical on
// every IEEE-754 platform (see catalog_internal.hpp).
#include "catalog/catalog_internal.hpp"
#include "mesh/builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace minksum::catalog_detail {

namespace {

using Vec = std::array<double, 3>;

// v / |v| in double precision.
Vec normalised(const Vec& v) {
  const double xx = v[0] * v[0];
  const double yy = v[1] * v[1];
  const double zz = v[2] * v[2];
  double s = xx + yy;
  s = s + zz;
  const double n = std::sqrt(s);
  return {v[0] / n, v[1] / n, v[2] / n};
}

Point3 to_point(const Vec& v) { return Point3(v[0], v[1], v[2]); }

// The icosahedron inscribed in the unit sphere: the cyclic permutations of
// (0, ±A, ±B) with A = fl(1/sqrt(1+φ²)), B = fl(φ/sqrt(1+φ²)) (B/A = φ to
// within 2e-16).  These are the doubles the normalisation above gives for
// (0, 1, φ) with φ = fl((1+sqrt 5)/2); they are written out so that nothing
// depends on a compiler's constant folding.
constexpr double kIcoA = 0x1.0d2ca0da1530dp-1;  // 0.5257311121191336
constexpr double kIcoB = 0x1.b38880b4603e5p-1;  // 0.85065080835204

std::vector<Vec> icosahedron_vertices() {
  std::vector<Vec> v;
  for (int c = 0; c < 3; ++c)            // cyclic permutation
    for (int sa = 1; sa >= -1; sa -= 2)  // sign of A
      for (int sb = 1; sb >= -1; sb -= 2) {
        Vec p{0.0, sa * kIcoA, sb * kIcoB};  // (0, ±A, ±B)
        Vec q;
        for (int i = 0; i < 3; ++i) q[(i + c) % 3] = p[i];
        v.push_back(q);
      }
  return v;
}

// The icosahedron's 20 triangles on those vertices, counter-clockwise seen
// from outside: the triples whose plane has the nine other vertices strictly
// below it, found once exactly (test CatalogSphere.
// SubdivisionMeshIsExactlyConvexWithoutFallback checks them) and written
// out, so that a process making any sphere does not repeat the 2 000 exact
// sign tests (about 5 ms: the ball of every rounding).
constexpr std::array<std::array<Index, 3>, 20> kIcosahedronFaces = {{
    {0, 2, 4},  {0, 5, 2},  {0, 4, 8},  {0, 10, 5}, {0, 8, 10}, {1, 6, 3},  {1, 3, 7},
    {1, 8, 6},  {1, 7, 10}, {1, 10, 8}, {2, 9, 4},  {2, 5, 11}, {2, 11, 9}, {3, 6, 9},
    {3, 11, 7}, {3, 9, 11}, {4, 6, 8},  {4, 9, 6},  {5, 10, 7}, {5, 7, 11}}};

}  // namespace

// ---------------------------------------------------------------------------
// sphere:L

Mesh sphere_mesh(int level) {
  std::vector<Vec> pts = icosahedron_vertices();
  std::vector<std::array<Index, 3>> tris(kIcosahedronFaces.begin(), kIcosahedronFaces.end());
  for (int l = 1; l < level; ++l) {
    std::unordered_map<std::uint64_t, Index> midpoint;
    midpoint.reserve(tris.size() * 2);
    pts.reserve(pts.size() + tris.size() * 3 / 2);
    auto mid = [&](Index a, Index b) -> Index {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      // p + q is symmetric in (p, q), so the rounded midpoint does not depend
      // on which face reaches the edge first.
      const Vec s{pts[a][0] + pts[b][0], pts[a][1] + pts[b][1], pts[a][2] + pts[b][2]};
      const Index m = static_cast<Index>(pts.size());
      pts.push_back(normalised(s));
      midpoint.emplace(key, m);
      return m;
    };
    std::vector<std::array<Index, 3>> next;
    next.reserve(tris.size() * 4);
    for (const auto& t : tris) {
      const Index ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  Mesh m;
  m.points.reserve(pts.size());
  for (const Vec& v : pts) m.points.push_back(to_point(v));
  m.faces.reserve(tris.size());
  for (const auto& t : tris) m.faces.push_back({t[0], t[1], t[2]});
  return m;
}

ConvexPolytope make_sphere(int level, const std::string& source) {
  Mesh m = sphere_mesh(level);
  try {
    return ConvexPolytope::from_mesh(m, source);
  } catch (const InputError&) {
    // Never observed for levels 1..9: every vertex is far (relative to the
    // rounding of its coordinates) outside the planes of the other facets.
    // Should a rounding ever make a facet pair reflex or coplanar, the exact
    // hull of the same points is the honest answer.
    return exact_hull(m.points.to_points(), source);
  }
}

// ---------------------------------------------------------------------------
// box:X:Y:Z

ConvexPolytope make_box(const Rational& x, const Rational& y, const Rational& z, const std::string& source) {
  Mesh m;
  const Rational hx = x / 2, hy = y / 2, hz = z / 2;
  // Vertex index = i + 2j + 4k: the sign of x (i), y (j), z (k), 1 = +.
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.points.emplace_back(i ? hx : Rational(-hx), j ? hy : Rational(-hy), k ? hz : Rational(-hz));
  m.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  return ConvexPolytope::from_mesh(m, source);
}

// ---------------------------------------------------------------------------
// dioctagonal:N

namespace {

// (−1)^k / (2k+1)! and (−1)^k / (2k)!, k = 0..9: Taylor coefficients of sin
// and cos; on [0, π/4] the truncation error is below 1e-22.
constexpr std::array<double, 10> taylor(bool odd) {
  std::array<double, 10> c{};
  double f = 1.0;  // (2k)! or (2k+1)!
  int n = odd ? 1 : 0;
  for (int k = 0; k < 10; ++k) {
    if (k > 0) {
      f *= double(n + 1) * double(n + 2);
      n += 2;
    }
    c[k] = (k % 2 ? -1.0 : 1.0) / f;
  }
  return c;
}
constexpr std::array<double, 10> kSin = taylor(true);
constexpr std::array<double, 10> kCos = taylor(false);

double poly_x2(const std::array<double, 10>& c, double x2) {
  double p = c[9];
  for (int k = 8; k >= 0; --k) {
    p = p * x2;
    p = p + c[k];
  }
  return p;
}

// cos and sin of (π/4)·num/den, 0 <= num <= den.
std::array<double, 2> cos_sin_octant(std::uint64_t num, std::uint64_t den) {
  const std::uint64_t g = std::gcd(num, den);
  if (g != 0) {
    num /= g;
    den /= g;
  }
  // At exactly π/4 cos = sin: use the double nearest to sqrt(1/2) for both,
  // so the polygon keeps its mirror symmetry across the diagonals.
  if (num == den) return {0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bcdp-1};
  constexpr double kPiOver4 = 0x1.921fb54442d18p-1;
  const double f = double(num) / double(den);
  const double x = kPiOver4 * f;
  const double x2 = x * x;
  const double s = x * poly_x2(kSin, x2);
  const double c = poly_x2(kCos, x2);
  return {c, s};
}

}  // namespace

std::array<double, 2> unit_circle_point(std::uint64_t k, std::uint64_t n) {
  // 2πk/n = (π/4)(8k/n): octant o, remainder r in [0, n).
  const std::uint64_t eight_k = 8 * k;
  const std::uint64_t o = eight_k / n, r = eight_k - o * n;
  // Even octants measure the angle from the octant's start, odd octants from
  // its end, so mirror-image angles evaluate the very same polynomial.
  const auto cs = (o % 2 == 0) ? cos_sin_octant(r, n) : cos_sin_octant(n - r, n);
  const double c = cs[0], s = cs[1];
  switch (o) {
    case 0: return {c, s};
    case 1: return {s, c};
    case 2: return {-s, c};
    case 3: return {-c, s};
    case 4: return {-c, -s};
    case 5: return {-s, -c};
    case 6: return {s, -c};
    default: return {c, -s};
  }
}

ConvexPolytope make_dioctagonal(std::uint64_t facets, const std::string& source) {
  const std::uint64_t m = facets - 1;  // base vertices
  Mesh mesh;
  mesh.points.reserve(m + 1);
  for (std::uint64_t k = 0; k < m; ++k) {
    const auto p = unit_circle_point(k, m);
    mesh.points.emplace_back(Rational(p[0]), Rational(p[1]), Rational(0));
  }
  mesh.points.emplace_back(Rational(0), Rational(0), Rational(1, 8));  // the low apex
  const Index apex = static_cast<Index>(m);
  std::vector<Index> base;
  for (std::uint64_t k = m; k-- > 0;) base.push_back(static_cast<Index>(k));  // seen from below
  mesh.faces.push_back(std::move(base));
  for (std::uint64_t k = 0; k < m; ++k)
    mesh.faces.push_back({static_cast<Index>(k), static_cast<Index>((k + 1) % m), apex});
  return ConvexPolytope::from_mesh(mesh, source);
}

// ---------------------------------------------------------------------------
// ball:N and prism:N: rings of the regular polygon unit_circle_point(k, m),
// each scaled exactly by its radius.  Two rings of the same polygon bound
// quadrilaterals whose top and bottom edges are exactly parallel (both are
// multiples of the same vector), so every side facet is exactly planar.

namespace {

// The ring of `m` points r·unit_circle_point(k, m) at height z (exact products).
void add_ring(Mesh& mesh, std::uint64_t m, const Rational& r, const Rational& z) {
  for (std::uint64_t k = 0; k < m; ++k) {
    const auto p = unit_circle_point(k, m);
    mesh.points.emplace_back(Rational(p[0]) * r, Rational(p[1]) * r, z);
  }
}

// The quadrilaterals between the ring starting at `lo` and the ring above it
// starting at `hi` (m points each), counter-clockwise seen from outside.
void add_band(Mesh& mesh, std::uint64_t m, Index lo, Index hi) {
  for (std::uint64_t k = 0; k < m; ++k) {
    const Index j = static_cast<Index>((k + 1) % m), i = static_cast<Index>(k);
    mesh.faces.push_back({lo + i, lo + j, hi + j, hi + i});
  }
}

}  // namespace

ConvexPolytope make_ball(std::uint64_t bands, const std::string& source) {
  // Latitude j·π/N from the south pole: the point (sin, −cos) of the meridian,
  // i.e. unit_circle_point(j, 2N) = (cos, sin) read as (−z, radius).
  const std::uint64_t m = 2 * bands;  // meridians
  Mesh mesh;
  mesh.points.emplace_back(Rational(0), Rational(0), Rational(-1));  // south pole: 0
  for (std::uint64_t j = 1; j < bands; ++j) {
    const auto q = unit_circle_point(j, m);
    add_ring(mesh, m, Rational(q[1]), Rational(-q[0]));  // ring j: 1 + (j − 1)·m ...
  }
  const Index north = static_cast<Index>(mesh.points.size());
  mesh.points.emplace_back(Rational(0), Rational(0), Rational(1));
  const auto ring = [&](std::uint64_t j) { return static_cast<Index>(1 + (j - 1) * m); };
  for (std::uint64_t k = 0; k < m; ++k) {
    const Index i = static_cast<Index>(k), n = static_cast<Index>((k + 1) % m);
    mesh.faces.push_back({0, ring(1) + n, ring(1) + i});
    mesh.faces.push_back({ring(bands - 1) + i, ring(bands - 1) + n, north});
  }
  for (std::uint64_t j = 1; j + 1 < bands; ++j) add_band(mesh, m, ring(j), ring(j + 1));
  return ConvexPolytope::from_mesh(mesh, source);
}

ConvexPolytope make_prism(std::uint64_t sides, const std::string& source) {
  Mesh mesh;
  add_ring(mesh, sides, Rational(1), Rational(-1));
  add_ring(mesh, sides, Rational(1), Rational(1));
  add_band(mesh, sides, 0, static_cast<Index>(sides));
  std::vector<Index> bottom, top;
  for (std::uint64_t k = 0; k < sides; ++k) {
    bottom.push_back(static_cast<Index>(sides - 1 - k));  // seen from below
    top.push_back(static_cast<Index>(sides + k));
  }
  mesh.faces.push_back(std::move(bottom));
  mesh.faces.push_back(std::move(top));
  return ConvexPolytope::from_mesh(mesh, source);
}

// ---------------------------------------------------------------------------
// random:N:SEED

std::vector<Vec3d> random_sphere_directions(std::uint64_t n, std::uint64_t seed) {
  SplitMix64 rng = make_rng(seed, kStreamRandomPoints);
  std::vector<Vec3d> pts;
  pts.reserve(n);
  while (pts.size() < n) {
    // Uniform in the cube [-1, 1)^3 (exact: 2u - 1 of a multiple of 2^-53),
    // kept inside the unit ball (away from its centre), then projected: a
    // uniformly distributed direction.
    const double x = 2.0 * rng.uniform01() - 1.0;
    const double y = 2.0 * rng.uniform01() - 1.0;
    const double z = 2.0 * rng.uniform01() - 1.0;
    const double xx = x * x;
    const double yy = y * y;
    const double zz = z * z;
    double r2 = xx + yy;
    r2 = r2 + zz;
    if (r2 > 1.0 || r2 < 1.0 / 64.0) continue;
    const Vec u = normalised({x, y, z});
    pts.push_back({u[0], u[1], u[2]});
  }
  return pts;
}

std::vector<Point3> random_sphere_points(std::uint64_t n, std::uint64_t seed) {
  std::vector<Point3> pts;
  for (const Vec3d& v : random_sphere_directions(n, seed)) pts.emplace_back(v.x, v.y, v.z);
  return pts;
}

ConvexPolytope make_random(std::uint64_t n, std::uint64_t seed, const std::string& source) {
  PointList pts;
  for (const Vec3d& v : random_sphere_directions(n, seed)) pts.push_back(v);
  return PolytopeBuilder::hull_of_extreme_points(pts, source);
}

// ---------------------------------------------------------------------------
// zonotope:N:SEED

std::vector<std::array<std::int64_t, 3>> zonotope_generators(std::uint64_t n, std::uint64_t seed) {
  using G = std::array<std::int64_t, 3>;
  SplitMix64 rng = make_rng(seed, kStreamZonotope);
  const std::int64_t range = std::int64_t(n) + 2;  // coordinates in [-range, range]
  std::vector<G> gens;
  auto crossv = [](const G& a, const G& b) {
    return G{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  auto dotv = [](const G& a, const G& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  while (gens.size() < n) {
    G g{rng.uniform_int(-range, range), rng.uniform_int(-range, range), rng.uniform_int(-range, range)};
    if (g[0] == 0 && g[1] == 0 && g[2] == 0) continue;
    bool ok = true;
    for (std::size_t i = 0; ok && i < gens.size(); ++i) {
      const G c = crossv(gens[i], g);
      if (c[0] == 0 && c[1] == 0 && c[2] == 0) ok = false;  // parallel
      for (std::size_t j = i + 1; ok && j < gens.size(); ++j)
        if (dotv(c, gens[j]) == 0) ok = false;  // three linearly dependent
    }
    if (ok) gens.push_back(g);
  }
  return gens;
}

ConvexPolytope make_zonotope(std::uint64_t n, std::uint64_t seed, const std::string& source) {
  using G = std::array<std::int64_t, 3>;
  const std::vector<G> g = zonotope_generators(n, seed);
  // Z = sum of the segments [-g_k, g_k].  With the generators in general
  // position every facet is a parallelogram: for each pair i < j and each
  // sign of n = g_i x g_j, the facet with outward normal ±n is
  // c ± g_i ± g_j with c = sum over k != i, j of sign(<g_k, ±n>) g_k.
  Mesh mesh;
  std::map<G, Index> index;
  auto vertex = [&](const G& p) {
    auto [it, fresh] = index.emplace(p, static_cast<Index>(mesh.points.size()));
    if (fresh) mesh.points.emplace_back(Rational(static_cast<long>(p[0])), Rational(static_cast<long>(p[1])),
                                        Rational(static_cast<long>(p[2])));
    return it->second;
  };
  const std::size_t N = g.size();
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i + 1; j < N; ++j) {
      const G nrm{g[i][1] * g[j][2] - g[i][2] * g[j][1], g[i][2] * g[j][0] - g[i][0] * g[j][2],
                  g[i][0] * g[j][1] - g[i][1] * g[j][0]};
      G c{0, 0, 0};
      for (std::size_t k = 0; k < N; ++k) {
        if (k == i || k == j) continue;
        const std::int64_t s = nrm[0] * g[k][0] + nrm[1] * g[k][1] + nrm[2] * g[k][2];
        for (int a = 0; a < 3; ++a) c[a] += (s > 0 ? g[k][a] : -g[k][a]);
      }
      for (int side = 1; side >= -1; side -= 2) {
        // Facet with outward normal side*nrm has centre side*c; walking
        // +g_i then +g_j turns counter-clockwise around +nrm.
        G q[4];
        const int ei[4] = {-1, 1, 1, -1}, ej[4] = {-1, -1, 1, 1};
        for (int v = 0; v < 4; ++v)
          for (int a = 0; a < 3; ++a) q[v][a] = side * c[a] + ei[v] * g[i][a] + ej[v] * g[j][a];
        std::vector<Index> face;
        for (int v = 0; v < 4; ++v) face.push_back(vertex(q[v]));
        if (side < 0) std::reverse(face.begin(), face.end());
        mesh.faces.push_back(std::move(face));
      }
    }
  return ConvexPolytope::from_mesh(mesh, source);
}

ConvexPolytope make_zonotope(const std::vector<Point3>& generators, const std::string& source) {
  std::set<Point3> sums{Point3(Rational(0), Rational(0), Rational(0))};
  for (const Point3& g : generators) {
    std::set<Point3> next;
    for (const Point3& p : sums) {
      next.insert(p + g);
      next.insert(p - g);
    }
    sums.swap(next);
  }
  try {
    return exact_hull(std::vector<Point3>(sums.begin(), sums.end()), source);
  } catch (const InputError&) {
    throw UsageError("catalog spec '" + source +
                     "': the zonotope's generators do not span 3 dimensions (it would be flat)");
  }
}

}  // namespace minksum::catalog_detail
