// Exact rotations by integer quaternions for the proximity queries (the same
// matrix as the catalog's "@rot:A,B,C,D" transform).
#include <minksum/error.hpp>
#include <minksum/proximity.hpp>

#include "catalog/catalog_internal.hpp"

namespace minksum {

namespace {
catalog_detail::Matrix3 matrix_of(const Quaternion& q) {
  if (sgn(q[0]) == 0 && sgn(q[1]) == 0 && sgn(q[2]) == 0 && sgn(q[3]) == 0)
    throw UsageError("a rotation needs a non-zero quaternion, got 0,0,0,0");
  return catalog_detail::quaternion_rotation(q[0], q[1], q[2], q[3]);
}
}  // namespace

Point3 rotate(const Quaternion& q, const Point3& p) { return catalog_detail::apply(matrix_of(q), p); }

ConvexPolytope rotated(const ConvexPolytope& p, const Quaternion& q) {
  const catalog_detail::Matrix3 r = matrix_of(q);
  Mesh m = p.to_mesh();
  m.points.transform([&](const Point3& x) { return catalog_detail::apply(r, x); });
  return ConvexPolytope::from_mesh(m, "rotated polytope");
}

Quaternion quaternion_product(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

}  // namespace minksum
