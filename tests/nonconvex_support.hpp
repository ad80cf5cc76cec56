// Helpers of the non-convex sum suites (test_nonconvex*.cpp).
#pragma once

#include <minksum/polytope.hpp>

#include "kernel/plane.hpp"

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

}  // namespace minksum::testing
