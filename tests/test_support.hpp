// Small helpers shared by the test suites: hand-built meshes whose facts are
// known in closed form, exact comparison of polytopes, and the size from
// which minksum's loops run on threads, set for a scope.
#pragma once

#include <minksum/parallel.hpp>
#include <minksum/polytope.hpp>

#include <algorithm>
#include <regex>
#include <string>
#include <set>
#include <vector>

namespace minksum::testing {

// parallel_items() set for the scope: a small value runs the threaded loops
// of validation, of the rounding certificate, of the OFF reader and of the
// text writers on inputs small enough for a test.
class ParallelItems {
 public:
  explicit ParallelItems(std::size_t items) : old_(parallel_items()) { set_parallel_items(items); }
  ~ParallelItems() { set_parallel_items(old_); }
  ParallelItems(const ParallelItems&) = delete;
  ParallelItems& operator=(const ParallelItems&) = delete;

 private:
  std::size_t old_;
};

inline Point3 P(long x, long y, long z) { return Point3(Rational(x), Rational(y), Rational(z)); }
inline Point3 Q(const char* x, const char* y, const char* z) {
  return Point3(Rational(x), Rational(y), Rational(z));
}

// Axis-aligned box [x0,x1] x [y0,y1] x [z0,z1] as six CCW quads (seen from outside).
inline Mesh box_mesh(const Rational& x0, const Rational& x1, const Rational& y0, const Rational& y1,
                     const Rational& z0, const Rational& z1) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.points.emplace_back((i & 1) ? x1 : x0, (i & 2) ? y1 : y0, (i & 4) ? z1 : z0);
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}
inline Mesh cube_mesh(long h = 1) {
  return box_mesh(Rational(-h), Rational(h), Rational(-h), Rational(h), Rational(-h), Rational(h));
}

// Regular tetrahedron with vertices (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1).
inline Mesh tetra_mesh() {
  Mesh m;
  m.points = {P(1, 1, 1), P(1, -1, -1), P(-1, 1, -1), P(-1, -1, 1)};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

// Octahedron with vertices (±1,0,0), (0,±1,0), (0,0,±1).
inline Mesh octahedron_mesh() {
  Mesh m;
  m.points = {P(1, 0, 0), P(-1, 0, 0), P(0, 1, 0), P(0, -1, 0), P(0, 0, 1), P(0, 0, -1)};
  // Facet for each sign pattern (sx, sy, sz), CCW seen from outside.
  for (int s = 0; s < 8; ++s) {
    Index x = (s & 1) ? 1 : 0, y = (s & 2) ? 3 : 2, z = (s & 4) ? 5 : 4;
    int neg = ((s & 1) != 0) + ((s & 2) != 0) + ((s & 4) != 0);
    if (neg % 2 == 0) m.faces.push_back({x, y, z});
    else m.faces.push_back({x, z, y});
  }
  return m;
}

// Fan-triangulate every face.
inline Mesh triangulated(const Mesh& in) {
  Mesh m;
  m.points = in.points;
  for (const auto& f : in.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) m.faces.push_back({f[0], f[i], f[i + 1]});
  return m;
}

inline std::vector<Plane> sorted_planes(const ConvexPolytope& p) {
  std::vector<Plane> v;
  for (Index f = 0; f < p.num_facets(); ++f) v.push_back(p.plane(f));
  std::sort(v.begin(), v.end());
  return v;
}

inline std::vector<Point3> sorted_points(const ConvexPolytope& p) {
  std::vector<Point3> v = p.points();
  std::sort(v.begin(), v.end());
  return v;
}

// Same polytope: same vertex set and same facet planes.
inline bool same_polytope(const ConvexPolytope& a, const ConvexPolytope& b) {
  return a.num_edges() == b.num_edges() && sorted_points(a) == sorted_points(b) &&
         sorted_planes(a) == sorted_planes(b);
}

// Primitive integer direction of a plane's normal (for "same normal" tests).
inline std::tuple<Integer, Integer, Integer> normal_direction(const Plane& p) {
  Integer g;
  mpz_gcd(g.get_mpz_t(), p.a.get_mpz_t(), p.b.get_mpz_t());
  mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), p.c.get_mpz_t());
  return {p.a / g, p.b / g, p.c / g};
}

// A message without the coordinates that locate its place (" from (x, y,
// z) to (x, y, z)", " at (x, y, z)"): to compare the verdicts on a mesh and
// on a scaled copy.
inline std::string without_coordinates(const std::string& message) {
  static const std::regex located(R"( from \([^)]*\) to \([^)]*\)| at \([^)]*\))");
  return std::regex_replace(message, located, "");
}

}  // namespace minksum::testing
