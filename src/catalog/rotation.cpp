// Exact rational rotations from integer quaternions (the rot: transform).
#include "catalog/catalog_internal.hpp"

namespace minksum::catalog_detail {

Matrix3 quaternion_rotation(const Integer& a, const Integer& b, const Integer& c, const Integer& d) {
  const Integer aa = a * a, bb = b * b, cc = c * c, dd = d * d;
  const Integer n = aa + bb + cc + dd;  // > 0 by precondition
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

std::array<Integer, 4> random_quaternion(std::uint64_t seed) {
  SplitMix64 rng = make_rng(seed, kStreamRotation);
  for (;;) {
    std::int64_t q[4];
    std::int64_t norm2 = 0;
    for (auto& x : q) {
      x = rng.uniform_int(-100, 100);
      norm2 += x * x;
    }
    if (norm2 >= 50 * 50 && norm2 <= 100 * 100)
      return {Integer(static_cast<long>(q[0])), Integer(static_cast<long>(q[1])),
              Integer(static_cast<long>(q[2])), Integer(static_cast<long>(q[3]))};
  }
}

Point3 apply(const Matrix3& r, const Point3& p) {
  Point3 out;
  for (int i = 0; i < 3; ++i) out[i] = r.m[i][0] * p.x + r.m[i][1] * p.y + r.m[i][2] * p.z;
  return out;
}

}  // namespace minksum::catalog_detail
