// minksum — exact numbers and the points built from them.
//
// Every coordinate minksum stores is an exact rational.  A coordinate read as
// a decimal token or a binary double is the exact value of that double (a
// dyadic rational); a coordinate read as `p/q` or as a long integer is that
// rational.  Nothing is rounded on the way in.  Lists of points keep each
// coordinate in its cheapest exact form — a double, an exact pair of doubles,
// or a GMP rational (mpq_class, the Rational below) — see
// <minksum/point_list.hpp>; Point3 is the general exact point.
//
// Geometric decisions are signs of exact polynomials; the predicates live in
// <minksum/predicates.hpp>.  This header has the number type, the point type,
// the small exact vector algebra the library needs, and number parsing and
// printing.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace minksum {

using Rational = mpq_class;
using Integer = mpz_class;

// A point (or vector) with exact rational coordinates.
struct Point3 {
  Rational x, y, z;

  Point3() = default;
  Point3(Rational x_, Rational y_, Rational z_)
      : x(std::move(x_)), y(std::move(y_)), z(std::move(z_)) {}
  // Exact: every finite double is a rational.  Precondition: finite.
  Point3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  const Rational& operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  Rational& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  friend bool operator==(const Point3& a, const Point3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  }
  // Lexicographic order (x, then y, then z).
  friend bool operator<(const Point3& a, const Point3& b) {
    int c = cmp(a.x, b.x);
    if (c != 0) return c < 0;
    c = cmp(a.y, b.y);
    if (c != 0) return c < 0;
    return cmp(a.z, b.z) < 0;
  }
};

// A double triple: the nearest doubles to an exact point, for filters,
// printing and conveniences.  Never used for a decision on its own.
struct Vec3d {
  double x = 0, y = 0, z = 0;
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

Point3 operator+(const Point3& a, const Point3& b);
Point3 operator-(const Point3& a, const Point3& b);
Point3 operator-(const Point3& a);
Point3 operator*(const Rational& s, const Point3& a);
Rational dot(const Point3& a, const Point3& b);
Point3 cross(const Point3& a, const Point3& b);
bool is_zero(const Point3& a);

// Nearest double of a rational (round to nearest, ties to even), and of a point.
double to_double(const Rational& q);
Vec3d to_double(const Point3& p);
// The nearest double hi of q and the rest: a double lo near q − hi and a
// bound err ≥ |q − hi − lo| (err = 0: q = hi + lo exactly; lo = err = 0
// exactly when q is a double; err = +inf, lo = 0 when hi overflows).  One
// division of scratch integers for the usual magnitudes.  In every rounding
// mode hi is the nearest double and the bound holds.
void to_double_rest(const Rational& q, double& hi, double& lo, double& err);
// Nearest float (round to nearest, ties to even; +-inf beyond the float
// range), as binary STL stores coordinates.
float to_float(const Rational& q);
// True when q is exactly a finite double.
bool is_double(const Rational& q);
bool is_double(const Point3& p);

// Hash of an exact point (equal points hash equal).
std::size_t hash_value(const Point3& p);
struct Point3Hash {
  std::size_t operator()(const Point3& p) const { return hash_value(p); }
};

// An oriented plane a*x + b*y + c*z = d with outward normal (a, b, c).
// Canonical form: integers with gcd(a, b, c, d) = 1, so two facets lie in the
// same oriented plane if and only if their Plane compares equal.
struct Plane {
  Integer a, b, c, d;
  friend bool operator==(const Plane&, const Plane&) = default;
  // Sign of a*x + b*y + c*z - d: > 0 outside (above), 0 on, < 0 inside.
  int side(const Point3& p) const;
  Point3 normal() const { return Point3(Rational(a), Rational(b), Rational(c)); }
};
bool operator<(const Plane& p, const Plane& q);  // lexicographic (a, b, c, d)

// ---------------------------------------------------------------------------
// Parsing.  `parse_number` accepts
//   * integers of any length:        -12, 340282366920938463463374607431768211456
//   * exact rationals p/q (q != 0):  1/3, -22/7, 4/-8
//   * decimal / scientific tokens:   0.1, -2.5e-3, 1E300, .5, 5.  -> the nearest
//     double (as strtod), then that double exactly
//   * hexadecimal floats:            0x1.8p-3 -> exact
// It rejects nan, inf, empty tokens, trailing garbage, q = 0, and decimal
// tokens whose magnitude overflows a double.  On failure it returns nullopt
// and, if `why` is given, a short reason ("not a number", "NaN", "infinite",
// "zero denominator", "out of double range").
std::optional<Rational> parse_number(std::string_view token, std::string* why = nullptr);

// Printing.
// Shortest "%.17g"-style text that reads back to the same double.
std::string format_double(double v);
// "(x, y, z)", each coordinate format_double of its nearest double: where a
// message locates a point of the user's file (an STL has no vertex numbers).
std::string format_point(const Point3& p);
// Exact text: an integer ("-3") or "p/q" in lowest terms.
std::string format_exact(const Rational& q);
// The same text for the exact value hi + lo of two finite doubles (lo = 0:
// one double), appended to `out`, computed from the mantissas: machine
// integers when they suffice, GMP integers (never rationals) otherwise.
void append_exact_dyadic(std::string& out, double hi, double lo = 0.0);
// The coordinate as written by minksum's writers: exact text when `exact`,
// else format_double(to_double(q)).
std::string format_coordinate(const Rational& q, bool exact);

}  // namespace minksum
