// Internal: points in homogeneous integer coordinates and the side of a
// plane through three of them, filtered on intervals, exact otherwise.
//
// A homogeneous point (x, y, z, w), integers with w > 0, is the point
// (x/w, y/w, z/w): a rational point without a common denominator, so that
// its predicates are determinants of integers — no gcd, no rational.  The
// polar duals of the erosion (the points n / e of nonconvex halfspace
// erosion) are such points: n an integer normal, e = a / b a positive
// rational slack, the point (n b, a).
//
// side(a, b, c; x) is the sign of −det[a; b; c; x], the rows (x, y, z, w):
// positive when x lies strictly beyond the plane of the triangle (a, b, c)
// seen counter-clockwise from x, zero when the four points are coplanar.
// (Rows multiplied by their positive w: the determinant of the Cartesian
// rows (p, 1) times w_a w_b w_c w_x > 0, the same sign.)  Expanded along x's
// row, −det = Σ_k P_k x_k with the plane P = (M_0, −M_1, M_2, −M_3), M_k the
// 3×3 minor of rows a, b, c without column k: P is computed once per
// triangle, each test is then a dot product of four terms.
//
// The filter.  Each point keeps its row scaled by 2^-k (k such that the
// longest coordinate is below 1 in magnitude) as intervals enclosing the
// scaled integers (mpz_get_d_2exp truncates to 53 bits: the integer lies
// between that double and the next one away from zero, both times 2^-k
// exactly in range).  The determinant is multilinear in the rows, so the
// interval plane of the scaled rows, dotted with x's scaled row, encloses
// the exact value times 2^-(k_a + k_b + k_c + k_x) > 0: when the interval
// excludes zero its sign is the exact sign (interval arithmetic rounded
// outward, CGAL::Interval_nt, under a Protect_FPU_rounding<true> guard that
// the caller holds).  Otherwise the exact plane (integers, made once per
// triangle) decides.  tests/test_homogeneous.cpp (HomogeneousSide.*) checks
// every filtered sign against the exact determinant on random and coplanar
// inputs.
#pragma once

#include "kernel/interval.hpp"

#include <array>
#include <memory>

namespace minksum::detail {

struct HomogeneousPoint {
  std::array<Integer, 4> c;        // x, y, z, w (w > 0)
  std::array<FastInterval, 4> s;   // c · 2^-k, enclosed
};

// The point (x/w, y/w, z/w); w must be positive (std::invalid_argument).
// Needs the upward rounding guard.
HomogeneousPoint homogeneous_point(Integer x, Integer y, Integer z, Integer w);

// The plane through three homogeneous points, oriented as side() says.
struct HomogeneousPlane {
  std::array<FastInterval, 4> s;                       // from the scaled rows
  mutable std::unique_ptr<std::array<Integer, 4>> exact;  // made on demand
};

// Needs the upward rounding guard.
HomogeneousPlane homogeneous_plane(const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c);

// +1 beyond, 0 on, −1 beneath the plane of (a, b, c), which made h.  Needs
// the upward rounding guard.
int side(const HomogeneousPlane& h, const HomogeneousPoint& a, const HomogeneousPoint& b,
         const HomogeneousPoint& c, const HomogeneousPoint& x);

// The filter alone: the sign when the intervals decide it, kUncertain
// otherwise.  Needs the upward rounding guard.
int side_filter(const HomogeneousPlane& h, const HomogeneousPoint& x);

// The exact sign, without the filter (for the tests).
int side_exact(const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c,
               const HomogeneousPoint& x);

}  // namespace minksum::detail
