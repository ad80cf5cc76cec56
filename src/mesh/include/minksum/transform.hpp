// minksum — exact transforms of points and polytopes.
//
// A rotation is given by a non-zero integer quaternion q = a + b i + c j + d k:
//   R = (1/|q|²) [[a²+b²−c²−d², 2(bc−ad),     2(bd+ac)],
//                 [2(bc+ad),     a²−b²+c²−d², 2(cd−ab)],
//                 [2(bd−ac),     2(cd+ab),     a²−b²−c²+d²]],
// an exact rational orthogonal matrix of determinant 1.  The catalog's
// "@rot:A,B,C,D" transform and the proximity queries use the same matrix.
#pragma once

#include <minksum/polytope.hpp>

#include <array>

namespace minksum {

struct Matrix3 {
  std::array<std::array<Rational, 3>, 3> m;
};
// r p, exactly.
Point3 operator*(const Matrix3& r, const Point3& p);

using Quaternion = std::array<Integer, 4>;
// The rotation of q; throws UsageError for the zero quaternion.
Matrix3 quaternion_rotation(const Quaternion& q);
Point3 rotate(const Quaternion& q, const Point3& p);
// The polytope rotated by q (validated again: the rotated coordinates are
// rationals, the structure is that of p).
ConvexPolytope rotated(const ConvexPolytope& p, const Quaternion& q);
// Hamilton product a·b: rotating by b then by a equals rotating by a·b.
Quaternion quaternion_product(const Quaternion& a, const Quaternion& b);

}  // namespace minksum
