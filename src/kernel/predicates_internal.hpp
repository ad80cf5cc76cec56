// minksum — the two stages of every predicate, exposed separately.
//
// Internal header for the kernel and its tests: the public predicates in
// <minksum/predicates.hpp> are `filter, then exact when the filter declines`.
// Here each stage can be run on its own, so tests can check that the stages
// agree, that the filter's error bound really holds, and that the filter
// declines where it must.
//
// Stage 1, the approximation, in two steps:
//  * semi-static: the polynomial P evaluated in double precision on the
//    difference vectors (rescaled by powers of two when their magnitudes are
//    out of range), with a bound from the vectors' largest coordinates:
//        |value − P · 2^scale| ≤ bound                       (status kOk)
//  * dynamic (only for Vec3d inputs, and only when the first step cannot
//    decide): every vector rescaled to a largest coordinate in [1, 2), P
//    re-evaluated, and a bound from the permanent (the same expression on
//    absolute values, Σ|monomials|), tight also for very unequal coordinates:
//        |dynamic_value − P · 2^dynamic_scale| ≤ dynamic_bound
// P is the exact value of the predicate's polynomial on the exact inputs.
// status kZero means P = 0 is known exactly (a difference vector is exactly
// zero); kDecline means the filter cannot give a bound (a difference
// overflows, or rationals outside the filter's range).
//
// Stage 1', the filter: the certified sign, i.e. sign(value) when
// |value| > bound, else sign(dynamic_value) when |dynamic_value| >
// dynamic_bound, else nothing.
//
// Stage 2, exact: the sign of P computed with GMP integers.
#pragma once

#include <array>
#include <minksum/predicates.hpp>
#include <optional>

namespace minksum::detail {

struct Approx {
  enum Status : unsigned char { kOk, kZero, kDecline };
  Status status = kDecline;
  double value = 0;  // approximates P · 2^scale
  double bound = 0;  // |value − P · 2^scale| ≤ bound
  int scale = 0;
  bool has_dynamic = false;  // the dynamic step ran (Vec3d forms)
  double dynamic_value = 0;  // approximates P · 2^dynamic_scale
  double dynamic_bound = 0;  // |dynamic_value − P · 2^dynamic_scale| ≤ dynamic_bound
  int dynamic_scale = 0;
};

// The three coordinates of a vector-valued polynomial (n1 × n2): one
// semi-static bound for all three, one dynamic bound per coordinate.
struct Approx3 {
  Approx::Status status = Approx::kDecline;
  std::array<double, 3> value{};
  double bound = 0;
  int scale = 0;
  bool has_dynamic = false;
  std::array<double, 3> dynamic_value{};
  std::array<double, 3> dynamic_bound{};
  int dynamic_scale = 0;
};

// The sign the bounds prove (0 for kZero), or nothing.
std::optional<int> certified_sign(const Approx& a);
// Per coordinate of an Approx3: the proven sign of coordinate i, or nothing.
std::optional<int> certified_sign(const Approx3& a, int i);

// ---------------------------------------------------------------------------
// The filter constants (derivation: src/kernel/predicates.cpp and
// docs/kernel.md).  Each predicate polynomial is evaluated as one of five
// expression shapes on difference vectors:
//   det3  ⟨e, u × v⟩            (orient3d, support_compare, edge_facet_sign)
//   dcc   ⟨a × b, c × d⟩        (arc_side, normals_dot_sign)
//   ccc   (a × b) × (c × d)     (normals_parallel, normals_same_direction)
//   dot   ⟨a, b⟩, a and b differences           (dot_sign)
//   along ⟨d, e⟩, d exact, e a difference       (compare_along)
struct FilterShape {
  const char* name;
  int degree;     // K: number of vector factors in each monomial
  int terms;      // T: monomials of the evaluation tree, expanded
  int ops_vec;    // N: roundings on a monomial's path, Vec3d inputs (with the differences)
  int ops_rat;    // N': the same without the differences (rational inputs)
  double c_vec;   // ≥ T·γ_N·(1 + 2^-20),  γ_n = n·ε/(1 − n·ε),  ε = 2^-52
  double c_rat;   // ≥ T·γ_N'·(1 + 2^-20)
  double c_dyn;   // ≥ γ_N·(1 + 2^-20)  (multiplies the permanent)
  double lo, hi;  // every group maximum must lie in [lo, hi] (else rescale / decline)
};

inline constexpr FilterShape kShapeDet3{
    "det3", 3, 6, 8, 5, 0x1.80002p-47, 0x1.e0002p-48, 0x1.00002p-49, 0x1p-320, 0x1p333};
inline constexpr FilterShape kShapeDcc{
    "dcc", 4, 12, 11, 7, 0x1.08002p-45, 0x1.50002p-46, 0x1.60002p-49, 0x1p-240, 0x1p250};
inline constexpr FilterShape kShapeCcc{
    "ccc", 4, 8, 10, 6, 0x1.40002p-46, 0x1.80002p-47, 0x1.40002p-49, 0x1p-240, 0x1p250};
inline constexpr FilterShape kShapeDot{
    "dot", 2, 3, 5, 3, 0x1.e0002p-49, 0x1.20002p-49, 0x1.40002p-50, 0x1p-480, 0x1p500};
inline constexpr FilterShape kShapeAlong{
    "along", 2, 3, 4, 3, 0x1.80002p-49, 0x1.20002p-49, 0x1.00002p-50, 0x1p-480, 0x1p500};
inline constexpr std::array<const FilterShape*, 5> kShapes{&kShapeDet3, &kShapeDcc, &kShapeCcc,
                                                           &kShapeDot, &kShapeAlong};
// The absolute term of the dynamic bound (covers underflow, see the .cpp).
inline constexpr double kDynamicAbsolute = 0x1p-1000;

// The slack factor folded into every constant.
inline constexpr double kSlack = 1 + 0x1p-20;
// Relative error bound κ of the rational → double conversion used by the
// Point3 filters (2ε/(1 − 3ε), rounded up to 4ε = 2^-50).
inline constexpr double kConvEps = 0x1p-50;

// The rational → double conversion of the Point3 filters.  Returns false
// when q's double would not lie in the normal range [2^-1022, 2^1023] (the
// filter then declines); otherwise |out − q| ≤ kConvEps · |out|, and `exact`
// tells whether out = q (q is a double).  Zero converts exactly.
bool rational_to_filter_double(const Rational& q, double& out, bool& exact);

// ---------------------------------------------------------------------------
// Stage functions, one set per predicate and input type.

Approx orient3d_approx(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
Approx orient3d_approx(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
std::optional<int> orient3d_filter(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
std::optional<int> orient3d_filter(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d);
int orient3d_exact(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
int orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

Approx support_compare_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                              const Vec3d& bj);
Approx support_compare_approx(const Point3& a0, const Point3& a1, const Point3& a2,
                              const Point3& bi, const Point3& bj);
std::optional<int> support_compare_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                          const Vec3d& bi, const Vec3d& bj);
std::optional<int> support_compare_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                          const Point3& bi, const Point3& bj);
int support_compare_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                          const Vec3d& bj);
int support_compare_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& bi,
                          const Point3& bj);

Approx edge_facet_sign_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                              const Vec3d& a2);
Approx edge_facet_sign_approx(const Point3& p0, const Point3& p1, const Point3& a0,
                              const Point3& a1, const Point3& a2);
std::optional<int> edge_facet_sign_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0,
                                          const Vec3d& a1, const Vec3d& a2);
std::optional<int> edge_facet_sign_filter(const Point3& p0, const Point3& p1, const Point3& a0,
                                          const Point3& a1, const Point3& a2);
int edge_facet_sign_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                          const Vec3d& a2);
int edge_facet_sign_exact(const Point3& p0, const Point3& p1, const Point3& a0, const Point3& a1,
                          const Point3& a2);

Approx arc_side_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1,
                       const Vec3d& r0, const Vec3d& r1, const Vec3d& r2);
Approx arc_side_approx(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1, const Point3& r2);
std::optional<int> arc_side_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0,
                                   const Vec3d& q1, const Vec3d& r0, const Vec3d& r1,
                                   const Vec3d& r2);
std::optional<int> arc_side_filter(const Point3& p0, const Point3& p1, const Point3& q0,
                                   const Point3& q1, const Point3& r0, const Point3& r1,
                                   const Point3& r2);
int arc_side_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1,
                   const Vec3d& r0, const Vec3d& r1, const Vec3d& r2);
int arc_side_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                   const Point3& r0, const Point3& r1, const Point3& r2);

Approx normals_dot_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                          const Vec3d& b1, const Vec3d& b2);
Approx normals_dot_approx(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                          const Point3& b1, const Point3& b2);
std::optional<int> normals_dot_sign_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                           const Vec3d& b0, const Vec3d& b1, const Vec3d& b2);
std::optional<int> normals_dot_sign_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                           const Point3& b0, const Point3& b1, const Point3& b2);
int normals_dot_sign_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                           const Vec3d& b1, const Vec3d& b2);
int normals_dot_sign_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                           const Point3& b1, const Point3& b2);

// n1 × n2 approximated (the parallel and same-direction tests share it).
Approx3 normals_cross_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                             const Vec3d& b1, const Vec3d& b2);
Approx3 normals_cross_approx(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                             const Point3& b1, const Point3& b2);
std::optional<bool> normals_parallel_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                            const Vec3d& b0, const Vec3d& b1, const Vec3d& b2);
std::optional<bool> normals_parallel_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                            const Point3& b0, const Point3& b1, const Point3& b2);
bool normals_parallel_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                            const Vec3d& b1, const Vec3d& b2);
bool normals_parallel_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                            const Point3& b1, const Point3& b2);
std::optional<bool> normals_same_direction_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                                  const Vec3d& b0, const Vec3d& b1,
                                                  const Vec3d& b2);
std::optional<bool> normals_same_direction_filter(const Point3& a0, const Point3& a1,
                                                  const Point3& a2, const Point3& b0,
                                                  const Point3& b1, const Point3& b2);
bool normals_same_direction_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                  const Vec3d& b0, const Vec3d& b1, const Vec3d& b2);
bool normals_same_direction_exact(const Point3& a0, const Point3& a1, const Point3& a2,
                                  const Point3& b0, const Point3& b1, const Point3& b2);

Approx dot_sign_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1);
Approx dot_sign_approx(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1);
std::optional<int> dot_sign_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0,
                                   const Vec3d& q1);
std::optional<int> dot_sign_filter(const Point3& p0, const Point3& p1, const Point3& q0,
                                   const Point3& q1);
int dot_sign_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1);
int dot_sign_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1);

Approx compare_along_approx(const Vec3d& d, const Vec3d& p, const Vec3d& q);
Approx compare_along_approx(const Point3& d, const Point3& p, const Point3& q);
std::optional<int> compare_along_filter(const Vec3d& d, const Vec3d& p, const Vec3d& q);
std::optional<int> compare_along_filter(const Point3& d, const Point3& p, const Point3& q);
int compare_along_exact(const Vec3d& d, const Vec3d& p, const Vec3d& q);
int compare_along_exact(const Point3& d, const Point3& p, const Point3& q);

}  // namespace minksum::detail
