// Internal: exact canonical planes (see Plane in polytope.hpp).
#pragma once

#include <minksum/polytope.hpp>

namespace minksum {

// The canonical plane with (unnormalised, nonzero) normal n through p.
Plane canonical_plane(const Point3& n, const Point3& p);

// The canonical plane through the triangle (a, b, c), normal (b-a) x (c-a),
// for coordinates that are exactly doubles: computed in integers after
// scaling every coordinate by one power of two (no rational arithmetic).
// Precondition: the triangle has nonzero area; all coordinates finite.
Plane canonical_plane_of_double_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace minksum
