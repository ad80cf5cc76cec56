// minksum — internals of the catalog (src/catalog/), shared by its files and
// its tests.  Nothing here is public API.
//
// Determinism: every pseudo-random or floating-point step of the catalog uses
// only integer arithmetic and the correctly rounded IEEE-754 operations
// + - * / and sqrt, each product and sum in its own statement (so no compiler
// may fuse them into an FMA), so a spec gives bit-identical coordinates on
// every platform.  No libm transcendental function (sin, cos, log...) is used:
// their results differ between C libraries.
#pragma once

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/polytope.hpp>
#include <minksum/transform.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace minksum::catalog_detail {

// splitmix64 (Steele, Lea, Flood 2014): a tiny, well-mixed 64-bit generator
// whose output is fully specified, unlike the std:: distributions.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1), a multiple of 2^-53 (exact).
  double uniform01() { return double(next() >> 11) * 0x1.0p-53; }
  // Uniform integer in [lo, hi] (unbiased, by rejection).  Precondition lo <= hi.
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi) {
    const std::uint64_t range = std::uint64_t(hi - lo) + 1u;
    if (range == 0) return std::int64_t(next());  // full 64-bit range
    const std::uint64_t limit = ~std::uint64_t(0) - (~std::uint64_t(0) % range);
    std::uint64_t x;
    do x = next(); while (x >= limit);
    return lo + std::int64_t(x % range);
  }

 private:
  std::uint64_t state_;
};

// Streams of the generator for the different uses of a seed, so that e.g.
// random:N:7 and rot:7 are unrelated.
inline constexpr std::uint64_t kStreamRandomPoints = 0x72616e646f6d7074ull;  // "randompt"
inline constexpr std::uint64_t kStreamRotation = 0x726f746174696f6eull;      // "rotation"
inline constexpr std::uint64_t kStreamZonotope = 0x7a6f6e6f746f7065ull;      // "zonotope"
inline SplitMix64 make_rng(std::uint64_t seed, std::uint64_t stream) { return SplitMix64(seed ^ stream); }

// ---------------------------------------------------------------------------
// Fixed solids (solids.cpp).
struct FixedSolid {
  std::string name;
  std::vector<std::string> aliases;
  std::string description;
  Index vertices, edges, facets;  // the counts every build must have
  ConvexPolytope (*build)(const std::string& source);
};
const std::vector<FixedSolid>& fixed_solids();
// nullptr if `name` is neither a name nor an alias of a fixed solid.
const FixedSolid* find_fixed_solid(const std::string& name);

// The exact hull of `points`, renumbered canonically: vertices in the order
// of `points`, each facet loop starting at its smallest vertex, facets sorted
// by their loops.  Catalog output then does not depend on the hull code's
// internal order (which may vary from run to run).
ConvexPolytope exact_hull(const std::vector<Point3>& points, const std::string& source);

// Polar dual with respect to the unit sphere: facet plane a*x+b*y+c*z = d
// (d > 0) becomes the vertex (a/d, b/d, c/d).  Its facets are exactly planar
// for any exact input.  Precondition: the origin is strictly inside `p`.
ConvexPolytope polar_dual(const ConvexPolytope& p, const std::string& source);

// ---------------------------------------------------------------------------
// Families (families.cpp).
inline constexpr int kSphereMaxLevel = 9;
inline constexpr std::uint64_t kDioctagonalMax = 100000;
inline constexpr std::uint64_t kRandomMax = 1000000;
inline constexpr std::uint64_t kZonotopeMax = 256;
inline constexpr std::size_t kZonotopeExplicitMax = 16;

// The geodesic sphere as a mesh (level 1 = the icosahedron), before
// validation; vertices are unit vectors rounded to doubles, faces are
// triangles counter-clockwise seen from outside.
Mesh sphere_mesh(int level);
ConvexPolytope make_sphere(int level, const std::string& source);
ConvexPolytope make_box(const Rational& x, const Rational& y, const Rational& z, const std::string& source);
ConvexPolytope make_dioctagonal(std::uint64_t facets, const std::string& source);
// The latitude/longitude ball of N bands and 2N meridians: poles (0, 0, ±1),
// rings at the latitudes jπ/N − π/2 (0 < j < N), V = 2N(N − 1) + 2.
inline constexpr std::uint64_t kBallMax = 1000;
ConvexPolytope make_ball(std::uint64_t bands, const std::string& source);
// The prism over the regular N-gon of unit circumradius, z in [−1, 1].
ConvexPolytope make_prism(std::uint64_t sides, const std::string& source);
std::vector<Vec3d> random_sphere_directions(std::uint64_t n, std::uint64_t seed);
std::vector<Point3> random_sphere_points(std::uint64_t n, std::uint64_t seed);
ConvexPolytope make_random(std::uint64_t n, std::uint64_t seed, const std::string& source);
// Generators of zonotope:N:SEED: N integer vectors, no two parallel and no
// three linearly dependent.
std::vector<std::array<std::int64_t, 3>> zonotope_generators(std::uint64_t n, std::uint64_t seed);
ConvexPolytope make_zonotope(std::uint64_t n, std::uint64_t seed, const std::string& source);
// The zonotope sum of the segments [-g, g] for explicit generators (any
// position; throws UsageError if they do not span 3 dimensions).
ConvexPolytope make_zonotope(const std::vector<Point3>& generators, const std::string& source);

// Deterministic cos and sin of 2*pi*k/n (0 <= k < n) in double precision,
// exactly symmetric under the symmetries of the regular n-gon that map the
// angle grid to itself.
std::array<double, 2> unit_circle_point(std::uint64_t k, std::uint64_t n);

// ---------------------------------------------------------------------------
// Non-convex solids (nonconvex.cpp): meshes, validated by the caller.
inline constexpr std::uint64_t kNonconvexMax = 10000;  // most teeth, points, sides of ring:N, star:N, gear:N
// Cube [-1,1]^3 with a square hole of side `hole` (0 < hole < 2) along z.
Mesh make_tube(const Rational& hole);
// Prism of height 1 over an L of three unit squares.
Mesh make_lshape();
// Prism of height 1/2 over the ring between regular N-gons of radii 1 and 1/2.
Mesh make_ring(std::uint64_t n);
// Prism of height 1/2 over an N-pointed star (radii 1 and 1/2).
Mesh make_star(std::uint64_t n);
// Prism of height 1/2 over a gear of N teeth (radii 3/4 and 1) with a bore of radius 1/4.
Mesh make_gear(std::uint64_t n);
// The torus of core radius 1 and tube radius 1/3, m x n vertices, 2 m n triangles.
Mesh make_torus(std::uint64_t m, std::uint64_t n);

// ---------------------------------------------------------------------------
// Rotations (rotation.cpp; the matrices are in <minksum/transform.hpp>).
// The quaternion of rot:SEED: integers in [-100, 100] drawn until
// 50 <= |q| <= 100 (so the rotation is close to uniformly distributed).
std::array<Integer, 4> random_quaternion(std::uint64_t seed);

}  // namespace minksum::catalog_detail
