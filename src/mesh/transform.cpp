// Exact rotations by integer quaternions (see transform.hpp).
#include <minksum/error.hpp>
#include <minksum/transform.hpp>

namespace minksum {

Point3 operator*(const Matrix3& r, const Point3& p) {
  Point3 out;
  for (int i = 0; i < 3; ++i) out[i] = r.m[i][0] * p.x + r.m[i][1] * p.y + r.m[i][2] * p.z;
  return out;
}

Matrix3 quaternion_rotation(const Quaternion& q) {
  const Integer &a = q[0], &b = q[1], &c = q[2], &d = q[3];
  if (sgn(a) == 0 && sgn(b) == 0 && sgn(c) == 0 && sgn(d) == 0)
    throw UsageError("a rotation needs a non-zero quaternion, got 0,0,0,0");
  const Integer aa = a * a, bb = b * b, cc = c * c, dd = d * d;
  const Integer n = aa + bb + cc + dd;
  const Integer entries[3][3] = {
      {aa + bb - cc - dd, 2 * (b * c - a * d), 2 * (b * d + a * c)},
      {2 * (b * c + a * d), aa - bb + cc - dd, 2 * (c * d - a * b)},
      {2 * (b * d - a * c), 2 * (c * d + a * b), aa - bb - cc + dd},
  };
  Matrix3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = Rational(entries[i][j], n);
      r.m[i][j].canonicalize();
    }
  return r;
}

Point3 rotate(const Quaternion& q, const Point3& p) { return quaternion_rotation(q) * p; }

ConvexPolytope rotated(const ConvexPolytope& p, const Quaternion& q) {
  const Matrix3 r = quaternion_rotation(q);
  Mesh m = p.to_mesh();
  m.points.transform([&](const Point3& x) { return r * x; });
  return ConvexPolytope::from_mesh(m, "rotated polytope");
}

Quaternion quaternion_product(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

}  // namespace minksum
