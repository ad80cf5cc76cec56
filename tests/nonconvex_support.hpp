// Helpers of the non-convex sum suites (test_nonconvex*.cpp).
#pragma once

#include <minksum/nonconvex.hpp>
#include <minksum/polytope.hpp>

#include "kernel/plane.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace minksum::testing {

// The canonical planes of the faces of a mesh (each face exactly planar;
// its normal by Newell's formula, exact).
inline std::set<Plane> face_planes(const Mesh& m) {
  std::set<Plane> s;
  for (const auto& f : m.faces) {
    Point3 n(Rational(0), Rational(0), Rational(0));
    for (std::size_t i = 0; i < f.size(); ++i) n = n + cross(m.points[f[i]], m.points[f[(i + 1) % f.size()]]);
    s.insert(canonical_plane(n, m.points[f[0]]));
  }
  return s;
}

// The surfaces of a and b as one mesh, b's faces reversed when `flip`.
inline Mesh join(Mesh a, const Mesh& b, bool flip = false) {
  const Index offset = Index(a.points.size());
  for (std::size_t i = 0; i < b.points.size(); ++i) a.points.push_back(b.points[i]);
  for (auto f : b.faces) {
    if (flip) std::reverse(f.begin(), f.end());
    for (auto& v : f) v += offset;
    a.faces.push_back(f);
  }
  return a;
}

// Hollow cube: [-2,2]^3 with the cavity [-1,1]^3 (inner shell facing in).
inline Mesh hollow_cube() { return join(cube_mesh(2), cube_mesh(1), true); }

inline std::set<Point3> vertex_set(const Mesh& m) {
  std::set<Point3> s;
  for (std::size_t i = 0; i < m.points.size(); ++i) s.insert(m.points[i]);
  return s;
}

// Every directed edge is matched by as many opposite ones (closed, oriented,
// non-manifold edges included), every face is exactly planar and the volume
// is the one reported.
inline void expect_closed_oriented(const NonconvexSum& r) {
  std::map<std::pair<Index, Index>, int> d;
  for (const auto& f : r.mesh.faces) {
    ASSERT_GE(f.size(), 3u);
    for (std::size_t i = 0; i < f.size(); ++i) ++d[{f[i], f[(i + 1) % f.size()]}];
    Point3 n(Rational(0), Rational(0), Rational(0));
    for (std::size_t i = 0; i < f.size(); ++i) n = n + cross(r.mesh.points[f[i]], r.mesh.points[f[(i + 1) % f.size()]]);
    ASSERT_FALSE(is_zero(n));
    for (Index v : f) EXPECT_EQ(sgn(dot(n, r.mesh.points[v] - r.mesh.points[f[0]])), 0);
  }
  for (const auto& [e, c] : d) EXPECT_EQ(c, (d.count({e.second, e.first}) ? d.at({e.second, e.first}) : 0));
  EXPECT_EQ(mesh_volume(r.mesh), r.volume);
  EXPECT_GT(sgn(r.volume), 0);
}

// No vertex of the mesh lies strictly inside one of its edges (every
// T-junction resolved), and no face uses a vertex twice.
inline void expect_no_vertex_inside_an_edge(const Mesh& m) {
  std::set<std::pair<Index, Index>> edges;
  for (const auto& f : m.faces) {
    EXPECT_EQ(std::set<Index>(f.begin(), f.end()).size(), f.size());
    for (std::size_t i = 0; i < f.size(); ++i)
      edges.insert({std::min(f[i], f[(i + 1) % f.size()]), std::max(f[i], f[(i + 1) % f.size()])});
  }
  for (const auto& [a, b] : edges) {
    const Point3 d = m.points[b] - m.points[a];
    for (Index v = 0; v < m.points.size(); ++v) {
      if (v == a || v == b) continue;
      const Point3 av = m.points[v] - m.points[a];
      if (!is_zero(cross(d, av))) continue;
      const Rational t = dot(av, d);
      EXPECT_FALSE(sgn(t) > 0 && t < dot(d, d)) << "vertex " << v << " inside edge " << a << "-" << b;
    }
  }
}

}  // namespace minksum::testing
