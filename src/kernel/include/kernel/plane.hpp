// Internal: exact canonical planes (see Plane in <minksum/kernel.hpp>).
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/plane.hpp>  // canonical_plane(n, p)

#include <vector>

namespace minksum {

// The canonical plane through the triangle a, b, c with a = hi[0] + lo[0],
// b = hi[1] + lo[1], c = hi[2] + lo[2] (coordinate-wise, exact sums of two
// finite doubles; lo may be null: all low parts zero), normal (b - a) x
// (c - a).  Integer arithmetic on the scaled mantissas; no rational
// arithmetic.  Precondition: the triangle has nonzero area.
Plane canonical_plane_of_dyadic_triangle(const Vec3d hi[3], const Vec3d lo[3]);

// A rational point as integers over one positive common denominator:
// the point is num / den (den the lcm of the coordinates' denominators).
struct ScaledPoint {
  Integer num[3];
  Integer den;
};
ScaledPoint scaled_point(const Point3& p);

// A positive integer multiple of q - p: q.num * p.den - p.num * q.den
// (divided by the gcd of its components).
void scaled_difference(const ScaledPoint& p, const ScaledPoint& q, Integer out[3]);

// The canonical plane with normal n (integers, not all zero) through the
// point p + q, in integer arithmetic: (n p.den q.den, n . (p.num q.den +
// q.num p.den)) made primitive.  The same plane as canonical_plane(n, p + q).
Plane canonical_plane_through_sum(const Integer n[3], const ScaledPoint& p, const ScaledPoint& q);

// X / W for W > 0, truncated towards zero to a double: a faithful rounding
// (within relative 2^-52 of the exact quotient, never beyond it), as the
// half-space filter accepts (<minksum/half_space_side.hpp>), without
// reducing the fraction.  The integer quotient q = trunc(|X| 2^s / W) is
// taken with 56 or 57 bits; mpz_get_d keeps its leading 53, truncating, and
// dropping low bits of an integer part truncates the real quotient as well;
// the scaling by 2^-s is exact in the normal range (outside it the result
// is 0, subnormal or infinite, which the filter's range check refuses).
double truncated_ratio(const Integer& X, const Integer& W);

// The doubles of a positive multiple of the integer plane
// a x + b y + c z = d for the half-space filter
// (<minksum/half_space_side.hpp>): out = 2^-k (a, b, c, d), each truncated
// towards zero, with k = 0 when every coefficient is below 2^480 in
// magnitude, else k = L - 470 for L the largest coefficient's bit length
// (planes through points of several hundred bits, such as the vertices of
// an erosion, have coefficients of thousands of bits).  Returns whether all
// four may enter the filter: each zero exactly when its integer is, or of
// magnitude in [2^-480, 2^480).
// Why the filter's sign is then the plane's own: for every point, 2^-k
// (a x + b y + c z - d) has the sign of a x + b y + c z - d, as 2^-k > 0;
// and each double is a faithful rounding of its scaled coefficient, which
// the filter's bound admits: mpz_get_d_2exp gives the integer's leading 53
// bits, truncated (within relative 2^-52, never beyond the value), as
// m 2^e with 0.5 <= |m| < 1, and ldexp(m, e - k) scales that exactly
// while the result is normal, which the range check above guarantees
// (2^-480 is far above the smallest normal double, 2^-1022).
bool plane_filter_doubles(const Integer& a, const Integer& b, const Integer& c, const Integer& d, double out[4]);

// 2^-k x truncated towards zero into out (the step of plane_filter_doubles
// for one coefficient); whether the filter may use it: zero exactly, or of
// magnitude in [2^-480, 2^480) (else out = 0).
bool scaled_filter_double(const Integer& x, long k, double& out);

// Finite doubles as integers with one common power of two: values[i] =
// value[i] * 2^exponent exactly (exponent = the smallest exponent of the
// nonzero values' last mantissa bits).
struct ScaledIntegers {
  ScaledIntegers(const double* values, std::size_t n);
  // v * 2^(degree * exponent), exactly: the value of a homogeneous
  // polynomial of that degree in the doubles, from its value v on the
  // integers (a determinant of three points: degree 3).
  Rational unscale(const Integer& v, int degree) const;
  std::vector<Integer> value;
  int exponent = 0;
};

}  // namespace minksum
