// minksum — the floating-point stage of the predicates: the expression
// shapes, their error bounds, and the approximation that every filter runs.
//
// Internal header of src/kernel/.  A predicate is described (predicates_internal.hpp)
// by the points it reads, the group vectors it forms from them (differences
// p − q, or exact vectors), and one of the five shapes below; this file turns
// such a description into an Approx (value, bound, and the dynamic value and
// bound), for Vec3d inputs (exact doubles) and for rounded rational inputs.
//
// ===========================================================================
// Error analysis shared by all filters (docs/kernel.md has the long version)
// ===========================================================================
//
// Model.  ε = 2^-52 (one ulp, relative).  For doubles x, y and ∘ ∈ {+, −, ×},
// when the result does not overflow, in EVERY IEEE 754 rounding mode,
//     fl(x ∘ y) = (x ∘ y)(1 + δ) + η,   |δ| ≤ ε,  |η| ≤ η0 = 2^-1074,  δ·η = 0,
// and η = 0 for + and − (a sum of doubles in the subnormal range is exact).
// (Round-to-nearest would allow ε/2; using ε keeps the predicates correct
// when called while the FPU rounds upwards, e.g. inside interval-arithmetic
// code, at the price of bounds twice as wide as necessary.)
// γ_n = n·ε / (1 − n·ε).
//
// Lemma (tree monomials).  Evaluate a polynomial P by an expression tree of
// +, −, × whose leaves are rounded differences x̃ = fl(p − q) = x(1 + δ_x) of
// input doubles (or exact doubles, with no δ).  Expand the tree without
// collecting terms: P = Σ_j t_j, T monomials.  Ignoring η,
//     fl(P) = Σ_j t_j · Π_{i ∈ path(j)} (1 + δ_i),
// where path(j) is the set of rounding operations monomial j passes through
// (a + or − node multiplies both operands' monomials by its (1 + δ); a × node
// multiplies the monomials of its two operands and adds its own (1 + δ); the
// leaf differences count).  With |path(j)| ≤ N, each product is 1 + θ_j with
// |θ_j| ≤ γ_N (Higham, Accuracy and Stability of Numerical Algorithms,
// Lemma 3.1), hence
//     |fl(P) − P| ≤ γ_N · Σ_j |t_j|                                     (1)
//                 ≤ T · γ_N · M_1 ⋯ M_K,                                (2)
// because every monomial is ± one coordinate of each of the K group vectors
// (each predicate is multilinear in its difference vectors) and M_k is the
// largest |coordinate| of group k.
//
// Semi-static bound, from (2).  The code knows the maxima M̃_k of the
// rounded coordinates: M_k ≤ M̃_k / (1 − ε); it computes the bound as
// B = fl(c · M̃_1 ⋯ M̃_K) ≥ c · Π M̃_k · (1 − ε)^K.  So c ≥ T γ_N (1 − ε)^-2K
// suffices.  Filter test: |value| > B  ⇒  |value − P| < |value|  ⇒  same sign.
//
// Underflow and overflow.  The group maxima must lie in [lo, hi] with
// c · lo^K ≥ 2^-1010 and hi^K ≤ 2^1000 (per shape, predicates_internal.hpp).
//  * Overflow: every intermediate is ≤ T (1 + γ_N) hi^K ≤ 2^1005 < DBL_MAX.
//  * Underflow: an η0 born at a × node reaches the result multiplied by at
//    most (1 + ε)^N times the magnitude of its cofactor, Π_{k ∉ node} M_k;
//    relative to c Π_k M_k that is ≤ 2 η0 / (c Π_{k ∈ node} M_k)
//    ≤ 2^-1073 / 2^-1010 = 2^-63 per node, < 2^-57 over all nodes.  B itself
//    is a product of factors ≥ c · lo^K ≥ 2^-1010: normal, no underflow.
//  * Out of range: P is homogeneous of degree 1 in each group vector, so
//    multiplying group k by 2^-e_k, e_k = ilogb(M̃_k), multiplies P by 2^-e_k
//    > 0 and brings M̃_k into [1, 2) ⊂ [lo, hi].  The rescaled coordinates are
//    exact unless they become subnormal, when they carry an absolute error
//    ≤ η0 ≤ 2^-1074 · M̃_k; relative to c Π M that adds < T 2^-1074 2^K / c
//    < 2^-1000.  Only a difference that overflows (coordinates of opposite
//    signs near DBL_MAX) makes the Vec3d filter decline.
//  * A group whose rounded maximum is 0 is exactly the zero vector
//    (fl(p − q) = 0 iff p = q), so P = 0 exactly: the filter answers 0.
//
// The constants.  All the small factors above ((1 − ε)^-2K ≤ 1 + 9ε, the
// underflow terms < 2^-50) are covered by one slack factor:
//     c = T · γ_N · (1 + 2^-20), rounded up to a short hexadecimal constant
// (tests/test_predicates.cpp recomputes T γ_N (1 + 2^-20) in exact rational
// arithmetic and checks each constant is not below it).
//
// Dynamic bound, from (1), used only when the semi-static bound cannot
// decide.  Every group is rescaled to a maximum in [1, 2) (as above; exact up
// to an absolute η0 per coordinate) and P is re-evaluated, giving value'.
// The permanent Σ_j |t_j| is evaluated by the same tree on the absolute
// values of the rescaled coordinates, − replaced by +: no cancellation, so
// perm' = fl(...) ≥ Σ_j |t_j(ĝ)| (1 − ε)^N' minus underflow terms, and
// |g| ≤ (|ĝ| + η0)/(1 − ε).  With every factor below 2 in magnitude, all the
// absolute underflow terms together (at most T per leaf and one per node,
// each ≤ η0 · 2^K · (1 + γ_N)) stay below 2^-1050.  Hence
//     |value' − P 2^scale'| ≤ γ_N (1 − ε)^-(K + N') perm' + 2^-1050
//                          ≤ c_dyn · perm' + 2^-1000,    c_dyn = γ_N (1 + 2^-20),
// computed as fl(fl(c_dyn · perm') + 2^-1000), whose roundings the slack and
// the generous absolute term cover.  For the vector-valued ccc shape each
// coordinate has its own permanent and bound.
//
// The analysis holds as well if the compiler contracts a·b + c into an FMA
// (one rounding fewer on some paths); it does not hold under -ffast-math
// (reassociation), which is refused below.
//
// Rational inputs (Point3 forms).  When every coordinate is exactly a double
// the Vec3d path is used.  Otherwise each coordinate x is converted to x̂ with
// |x̂ − x| ≤ κ |x̂|, κ = 4ε (rational_to_filter_double, filter.cpp; a coordinate that is zero
// converts exactly; one whose double is not in the normal range makes the
// filter decline).  Group vectors are ĝ = fl(p̂ − q̂) (or d̂ for an exact
// vector), so per coordinate
//     |ĝ − g| ≤ ρ := ε D / (1 − ε) + 2κ C     (ρ := κ D for an exact vector)
// with D = max|ĝ|, C = max(|p̂|, |q̂|).  The filter evaluates P at ĝ, whose
// coordinates are now exact leaves:
//     |fl(P(ĝ)) − P(ĝ)| ≤ T γ_N' Π D_k                (N' = N minus the differences)
//     |P(ĝ) − P(g)|     ≤ T (Π (D_k + ρ_k) − Π D_k)
//                       ≤ T Σ_k ρ_k Π_{h≠k} (D_h + ρ_h)       (telescoping)
// and B = c_rat Π D_k + T(1 + 2^-20) Σ_k ρ_k Π_{h≠k} (D_h + ρ_h), computed
// with fewer than 4K + 4 roundings of positive terms, covered by the slack.
// Range: D_k ∈ [lo, hi] and C_k ≤ hi (no rescaling); ρ_k ≥ ε·lo and every
#pragma once

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <minksum/kernel.hpp>
#include <optional>
#include <type_traits>

#if defined(__FAST_MATH__)
#error "the filters' error bounds need IEEE 754 arithmetic: do not build with -ffast-math"
#endif
#if FLT_EVAL_METHOD != 0
#error "the predicate filters' error bounds assume double evaluation (FLT_EVAL_METHOD == 0)"
#endif

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
// The filter constants (derivation: the top of this file and
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

// ===========================================================================
// Evaluation.

using V = std::array<double, 3>;

inline V vsub(const Vec3d& p, const Vec3d& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
inline V vof(const Vec3d& p) { return {p.x, p.y, p.z}; }
inline V vabs(const V& a) { return {std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])}; }
inline double maxabs(const V& v) {
  return std::max(std::fabs(v[0]), std::max(std::fabs(v[1]), std::fabs(v[2])));
}

// The expression trees.  The order of operations is part of the error
// analysis: a + b + c is (a + b) + c.
inline V eval_cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double eval_dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// The permanent trees: the same shapes on absolute values, − made +.
inline V perm_cross(const V& a, const V& b) {
  return {a[1] * b[2] + a[2] * b[1], a[2] * b[0] + a[0] * b[2], a[0] * b[1] + a[1] * b[0]};
}

// The five shapes: K group vectors, the value and the permanent.  Value is
// double (one polynomial) or V (three, the ccc shape).
struct Det3 {  // ⟨e, u × v⟩
  static constexpr const FilterShape& shape = kShapeDet3;
  static constexpr std::size_t K = 3;
  using Value = double;
  static double eval(const std::array<V, 3>& g) { return eval_dot(g[0], eval_cross(g[1], g[2])); }
  static double perm(const std::array<V, 3>& g) {
    return eval_dot(vabs(g[0]), perm_cross(vabs(g[1]), vabs(g[2])));
  }
};
struct Dcc {  // ⟨a × b, c × d⟩
  static constexpr const FilterShape& shape = kShapeDcc;
  static constexpr std::size_t K = 4;
  using Value = double;
  static double eval(const std::array<V, 4>& g) {
    return eval_dot(eval_cross(g[0], g[1]), eval_cross(g[2], g[3]));
  }
  static double perm(const std::array<V, 4>& g) {
    return eval_dot(perm_cross(vabs(g[0]), vabs(g[1])), perm_cross(vabs(g[2]), vabs(g[3])));
  }
};
struct Ccc {  // (a × b) × (c × d)
  static constexpr const FilterShape& shape = kShapeCcc;
  static constexpr std::size_t K = 4;
  using Value = V;
  static V eval(const std::array<V, 4>& g) {
    return eval_cross(eval_cross(g[0], g[1]), eval_cross(g[2], g[3]));
  }
  static V perm(const std::array<V, 4>& g) {
    return perm_cross(perm_cross(vabs(g[0]), vabs(g[1])), perm_cross(vabs(g[2]), vabs(g[3])));
  }
};
template <const FilterShape& S>
struct DotShape {  // ⟨a, b⟩
  static constexpr const FilterShape& shape = S;
  static constexpr std::size_t K = 2;
  using Value = double;
  static double eval(const std::array<V, 2>& g) { return eval_dot(g[0], g[1]); }
  static double perm(const std::array<V, 2>& g) { return eval_dot(vabs(g[0]), vabs(g[1])); }
};
using Dot = DotShape<kShapeDot>;      // both factors differences
using Along = DotShape<kShapeAlong>;  // one exact vector, one difference

// The Approx of a shape: Approx for one polynomial, Approx3 for three.
template <class Shape>
using ApproxOf = std::conditional_t<std::is_same_v<typename Shape::Value, V>, Approx3, Approx>;

// ===========================================================================
// Semi-static and dynamic steps on exact doubles.

// Multiplies the group vector g by 2^-e, e = ilogb(m), bringing its maximum
// m into [1, 2); returns e.  For |e| ≤ 1022 the factor 2^-e is a normal
// double and the product is what ldexp gives (exact, or one rounding when
// the result is subnormal), at the cost of a multiplication instead of a
// library call; beyond, ldexp.
inline int rescale(V& g, double& m) {
  const int e = std::ilogb(m);
  if (e >= -1022 && e <= 1022) {
    const std::uint64_t bits = std::uint64_t(1023 - e) << 52;
    double f;
    std::memcpy(&f, &bits, sizeof f);
    for (double& x : g) x *= f;
    m *= f;
    return e;
  }
  for (double& x : g) x = std::ldexp(x, -e);
  m = std::ldexp(m, -e);
  return e;
}

// Computes the group maxima, answers kZero for an exactly-zero group, and
// rescales by powers of two the groups whose maximum is outside [lo, hi].
// `scale` receives the total exponent: the rescaled P is P · 2^scale.
template <std::size_t K>
Approx::Status prepare_vec(std::array<V, K>& g, std::array<double, K>& m, int& scale,
                           const FilterShape& s) {
  bool in_range = true;
  for (std::size_t k = 0; k < K; ++k) {
    m[k] = maxabs(g[k]);
    if (m[k] == 0) return Approx::kZero;
    in_range = in_range && m[k] >= s.lo && m[k] <= s.hi;
  }
  scale = 0;
  if (in_range) return Approx::kOk;
  for (std::size_t k = 0; k < K; ++k) {
    if (m[k] >= s.lo && m[k] <= s.hi) continue;
    if (!(m[k] <= DBL_MAX)) return Approx::kDecline;  // a difference overflowed
    scale -= rescale(g[k], m[k]);
  }
  return Approx::kOk;
}

// Rescales the groups not yet in [1, 2) (dynamic step).
template <std::size_t K>
void rescale_all(std::array<V, K>& g, std::array<double, K>& m, int& scale) {
  for (std::size_t k = 0; k < K; ++k)
    if (!(m[k] >= 1 && m[k] < 2)) scale -= rescale(g[k], m[k]);
}

template <std::size_t K>
double product_bound(double c, const std::array<double, K>& m) {
  double b = c;
  for (double x : m) b *= x;
  return b;
}

// Does the semi-static bound already decide?  One polynomial: its sign.
// Three (ccc): one certified non-zero coordinate settles "parallel?" (no).
inline bool semi_static_decides(const Approx& a) { return std::fabs(a.value) > a.bound; }
inline bool semi_static_decides(const Approx3& a) {
  for (double x : a.value)
    if (std::fabs(x) > a.bound) return true;
  return false;
}

// The semi-static step alone, for the common case of a filter call: every
// group maximum already in [lo, hi] (no rescaling) and the value clear of
// the bound.  Returns the certified sign, or 0 when it does not decide
// (a group out of range or exactly zero, or |value| ≤ bound): the caller
// then runs approx_vec, whose first step computes the same value and the same
// bound (same expression tree, same product order), so the answer is the
// one approx_vec would certify.
template <class Shape>
[[gnu::always_inline]] inline int semi_static_sign(const std::array<V, Shape::K>& g) {
  constexpr const FilterShape& s = Shape::shape;
  double bound = s.c_vec;
  for (std::size_t k = 0; k < Shape::K; ++k) {
    const double m = maxabs(g[k]);
    if (!(m >= s.lo && m <= s.hi)) return 0;
    bound *= m;
  }
  const double value = Shape::eval(g);
  if (value > bound) return 1;
  if (value < -bound) return -1;
  return 0;
}

// The approximation on exact-double group vectors.  `lazy`: skip the dynamic
// step when the semi-static bound already decides (the filter); otherwise
// run both (the tests).
template <class Shape>
ApproxOf<Shape> approx_vec(std::array<V, Shape::K> g, bool lazy) {
  constexpr const FilterShape& s = Shape::shape;
  std::array<double, Shape::K> m;
  ApproxOf<Shape> a;
  a.status = prepare_vec(g, m, a.scale, s);
  if (a.status != Approx::kOk) return a;
  a.value = Shape::eval(g);
  a.bound = product_bound(s.c_vec, m);
  if (lazy && semi_static_decides(a)) return a;
  a.has_dynamic = true;
  a.dynamic_scale = a.scale;
  rescale_all(g, m, a.dynamic_scale);
  a.dynamic_value = Shape::eval(g);
  const auto perm = Shape::perm(g);
  if constexpr (std::is_same_v<typename Shape::Value, V>) {
    for (int i = 0; i < 3; ++i) a.dynamic_bound[i] = s.c_dyn * perm[i] + kDynamicAbsolute;
  } else {
    a.dynamic_bound = s.c_dyn * perm + kDynamicAbsolute;
  }
  return a;
}

// ===========================================================================
// The filter on rounded rationals.

// Converts points: kAllDoubles when every coordinate is exactly a double,
// kRationals when all are usable by the rational filter, kUnusable when the
// filter must decline.
enum Converted { kAllDoubles = 0, kRationals = 1, kUnusable = 2 };
template <std::size_t N>
Converted convert_points(const std::array<const Point3*, N>& pts, std::array<Vec3d, N>& out) {
  Converted status = kAllDoubles;
  for (std::size_t i = 0; i < N; ++i) {
    double c[3];
    for (int j = 0; j < 3; ++j) {
      bool exact = false;
      if (!rational_to_filter_double((*pts[i])[j], c[j], exact)) return kUnusable;
      if (!exact) status = kRationals;
    }
    out[i] = Vec3d{c[0], c[1], c[2]};
  }
  return status;
}

// A group of the rational filter: p − q, or the vector p itself (q null).
struct QGroup {
  const Vec3d* p;
  const Vec3d* q;
};

inline constexpr double kEpsSlack = 0x1.00001p-52;       // ε (1 + 2^-20), exact
inline constexpr double kConvSlack = kConvEps * kSlack;  // κ (1 + 2^-20), exact

// Builds ĝ, D and ρ for each group (formulas at the top of the file).
template <std::size_t K>
bool prepare_rat(const std::array<QGroup, K>& in, std::array<V, K>& g, std::array<double, K>& D,
                 std::array<double, K>& rho, const FilterShape& s) {
  for (std::size_t k = 0; k < K; ++k) {
    if (in[k].q) {
      g[k] = vsub(*in[k].p, *in[k].q);
      D[k] = maxabs(g[k]);
      const double C = std::max(maxabs(vof(*in[k].p)), maxabs(vof(*in[k].q)));
      if (!(D[k] >= s.lo && D[k] <= s.hi && C <= s.hi)) return false;
      // ρ ≥ ε D/(1 − ε) + 2κ C = ε (D/(1 − ε) + 8C): fl(D + 8C) ≥ (D + 8C)(1 − ε)
      // and the product loses another (1 − ε); (1 + 2^-20)(1 − ε)^3 ≥ 1/(1 − ε).
      rho[k] = kEpsSlack * (D[k] + 8 * C);
    } else {
      g[k] = vof(*in[k].p);
      D[k] = maxabs(g[k]);
      if (!(D[k] >= s.lo && D[k] <= s.hi)) return false;
      rho[k] = kConvSlack * D[k];  // ≥ κ D (one rounding, covered)
    }
  }
  return true;
}

template <std::size_t K>
double rational_bound(const std::array<double, K>& D, const std::array<double, K>& rho,
                      const FilterShape& s) {
  double eval = s.c_rat;
  for (double x : D) eval *= x;
  double pert = 0;
  for (std::size_t k = 0; k < K; ++k) {
    double t = rho[k];
    for (std::size_t h = 0; h < K; ++h)
      if (h != k) t *= D[h] + rho[h];
    pert += t;
  }
  return eval + (s.terms * kSlack) * pert;
}

// The approximation on rounded rationals (no dynamic step).
template <class Shape>
ApproxOf<Shape> approx_rat(const std::array<QGroup, Shape::K>& in) {
  std::array<V, Shape::K> g;
  std::array<double, Shape::K> D, rho;
  ApproxOf<Shape> a;
  if (!prepare_rat(in, g, D, rho, Shape::shape)) return a;
  a.status = Approx::kOk;
  a.value = Shape::eval(g);
  a.bound = rational_bound(D, rho, Shape::shape);
  return a;
}

}  // namespace minksum::detail
