// The sign predicates: a floating-point filter with a proven error bound,
// then exact evaluation with GMP integers.
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
// |x̂ − x| ≤ κ |x̂|, κ = 4ε (convert_rational below; a coordinate that is zero
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
// product in B is ≥ 2^-1012, so B does not underflow.
#include <algorithm>
#include <bit>
#include <cassert>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>

#include "kernel/predicates_internal.hpp"

#if defined(__FAST_MATH__)
#error "the filters' error bounds need IEEE 754 arithmetic: do not build with -ffast-math"
#endif
#if FLT_EVAL_METHOD != 0
#error "the predicate filters' error bounds assume double evaluation (FLT_EVAL_METHOD == 0)"
#endif

namespace minksum {

// ---------------------------------------------------------------------------
// Statistics.

namespace {
thread_local PredicateStats t_stats;

inline void count_call(PredicateId id) { ++t_stats.counters[int(id)].calls; }
inline void count_fallback(PredicateId id) { ++t_stats.counters[int(id)].fallbacks; }
}  // namespace

PredicateStats predicate_stats() { return t_stats; }
void reset_predicate_stats() { t_stats = PredicateStats{}; }

const char* predicate_name(PredicateId id) {
  switch (id) {
    case PredicateId::orient3d:
      return "orient3d";
    case PredicateId::support_compare:
      return "support_compare";
    case PredicateId::edge_facet_sign:
      return "edge_facet_sign";
    case PredicateId::arc_side:
      return "arc_side";
    case PredicateId::normals_dot_sign:
      return "normals_dot_sign";
    case PredicateId::normals_parallel:
      return "normals_parallel";
    case PredicateId::normals_same_direction:
      return "normals_same_direction";
    case PredicateId::dot_sign:
      return "dot_sign";
    case PredicateId::compare_along:
      return "compare_along";
  }
  return "?";
}

namespace detail {

namespace {
inline std::optional<int> sign_if_above(double value, double bound) {
  if (value > bound) return 1;
  if (value < -bound) return -1;
  return std::nullopt;
}
}  // namespace

std::optional<int> certified_sign(const Approx& a) {
  if (a.status == Approx::kZero) return 0;
  if (a.status != Approx::kOk) return std::nullopt;
  if (auto s = sign_if_above(a.value, a.bound)) return s;
  if (a.has_dynamic) return sign_if_above(a.dynamic_value, a.dynamic_bound);
  return std::nullopt;
}

std::optional<int> certified_sign(const Approx3& a, int i) {
  if (a.status == Approx::kZero) return 0;
  if (a.status != Approx::kOk) return std::nullopt;
  if (auto s = sign_if_above(a.value[i], a.bound)) return s;
  if (a.has_dynamic) return sign_if_above(a.dynamic_value[i], a.dynamic_bound[i]);
  return std::nullopt;
}

namespace {

// ===========================================================================
// Floating-point stage.

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

// The five shapes: value and permanent on group vectors.
struct Det3 {  // ⟨e, u × v⟩
  static constexpr const FilterShape& shape = kShapeDet3;
  static double eval(const std::array<V, 3>& g) { return eval_dot(g[0], eval_cross(g[1], g[2])); }
  static double perm(const std::array<V, 3>& g) {
    return eval_dot(vabs(g[0]), perm_cross(vabs(g[1]), vabs(g[2])));
  }
};
struct Dcc {  // ⟨a × b, c × d⟩
  static constexpr const FilterShape& shape = kShapeDcc;
  static double eval(const std::array<V, 4>& g) {
    return eval_dot(eval_cross(g[0], g[1]), eval_cross(g[2], g[3]));
  }
  static double perm(const std::array<V, 4>& g) {
    return eval_dot(perm_cross(vabs(g[0]), vabs(g[1])), perm_cross(vabs(g[2]), vabs(g[3])));
  }
};
struct Ccc {  // (a × b) × (c × d)
  static constexpr const FilterShape& shape = kShapeCcc;
  static V eval(const std::array<V, 4>& g) {
    return eval_cross(eval_cross(g[0], g[1]), eval_cross(g[2], g[3]));
  }
  static V perm(const std::array<V, 4>& g) {
    return perm_cross(perm_cross(vabs(g[0]), vabs(g[1])), perm_cross(vabs(g[2]), vabs(g[3])));
  }
};
template <const FilterShape& S>
struct Dot {  // ⟨a, b⟩
  static constexpr const FilterShape& shape = S;
  static double eval(const std::array<V, 2>& g) { return eval_dot(g[0], g[1]); }
  static double perm(const std::array<V, 2>& g) { return eval_dot(vabs(g[0]), vabs(g[1])); }
};
using DotD = Dot<kShapeDot>;
using Along = Dot<kShapeAlong>;

// Multiplies the group vector g by 2^-e, e = ilogb(m), bringing its maximum
// m into [1, 2); returns e.
inline int rescale(V& g, double& m) {
  const int e = std::ilogb(m);
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

// Scalar shapes on Vec3d groups.  `lazy`: skip the dynamic step when the
// semi-static bound already decides (the filter); otherwise run both (tests).
template <class Shape, std::size_t K>
Approx approx_vec(std::array<V, K> g, bool lazy) {
  std::array<double, K> m;
  Approx a;
  a.status = prepare_vec(g, m, a.scale, Shape::shape);
  if (a.status != Approx::kOk) return a;
  a.value = Shape::eval(g);
  a.bound = product_bound(Shape::shape.c_vec, m);
  if (lazy && std::fabs(a.value) > a.bound) return a;
  a.has_dynamic = true;
  a.dynamic_scale = a.scale;
  rescale_all(g, m, a.dynamic_scale);
  a.dynamic_value = Shape::eval(g);
  a.dynamic_bound = Shape::shape.c_dyn * Shape::perm(g) + kDynamicAbsolute;
  return a;
}

Approx3 approx_vec_ccc(std::array<V, 4> g, bool lazy) {
  std::array<double, 4> m;
  Approx3 a;
  a.status = prepare_vec(g, m, a.scale, kShapeCcc);
  if (a.status != Approx::kOk) return a;
  a.value = Ccc::eval(g);
  a.bound = product_bound(kShapeCcc.c_vec, m);
  if (lazy) {
    // One certified non-zero coordinate settles "parallel?" (no).
    for (double x : a.value)
      if (std::fabs(x) > a.bound) return a;
  }
  a.has_dynamic = true;
  a.dynamic_scale = a.scale;
  rescale_all(g, m, a.dynamic_scale);
  a.dynamic_value = Ccc::eval(g);
  const V p = Ccc::perm(g);
  for (int i = 0; i < 3; ++i) a.dynamic_bound[i] = kShapeCcc.c_dyn * p[i] + kDynamicAbsolute;
  return a;
}

// ---------------------------------------------------------------------------
// Rational coordinates for the filter.

// Converts q for the rational filter.  Returns false when q's double would
// not be in the normal range (the filter then declines).  Otherwise
// |out − q| ≤ κ |out| with κ = 4ε = 2^-50, and `exact` tells whether out = q.
//
// Derivation: q = n/d in lowest terms, d > 0.  mpz_get_d_2exp truncates (it
// works on the bits; the FPU rounding mode plays no part):
// fn = n 2^-en (1 − δn), fd = d 2^-ed (1 − δd), 0 ≤ δn, δd < ε,
// |fn|, fd ∈ [1/2, 1).  r = fl(fn / fd) = (fn / fd)(1 + δ), |δ| ≤ ε, |r| ∈ [1/2, 2],
// and out = r · 2^(en − ed) is exact when normal.  out / q =
// (1 − δn)(1 + δ)/(1 − δd) ∈ [(1 − ε)², (1 + ε)/(1 − ε)], so
// |out − q| ≤ 2ε/(1 − ε) |q| ≤ 2ε/(1 − 3ε) |out| < 4ε |out|.
// Range: 2^(e−1) < |q| < 2^(e+1) with e = en − ed; −1021 ≤ e ≤ 1022 keeps out
// in [2^-1022, 2^1023].  Exactness: q is a double iff d is a power of two
// and n has at most 53 significant bits; then fn, fd, r and out are exact.
inline bool convert_rational(const Rational& q, double& out, bool& exact) {
  if (sgn(q) == 0) {
    out = 0;
    exact = true;
    return true;
  }
  mpz_srcptr n = q.get_num_mpz_t();
  mpz_srcptr d = q.get_den_mpz_t();
  long en = 0, ed = 0;
  const double fn = mpz_get_d_2exp(&en, n);
  const double fd = mpz_get_d_2exp(&ed, d);
  const long e = en - ed;
  if (e < -1021 || e > 1022) return false;
  out = std::ldexp(fn / fd, int(e));
  const std::size_t nbits = mpz_sizeinbase(n, 2);
  const std::size_t dbits = mpz_sizeinbase(d, 2);
  exact = mpz_scan1(d, 0) + 1 == dbits && nbits - mpz_scan1(n, 0) <= 53;
  return true;
}

// Converts points; returns 0 when every coordinate is exactly a double,
// 1 when all are usable by the rational filter, 2 when the filter must
// decline.
enum Converted { kAllDoubles = 0, kRationals = 1, kUnusable = 2 };
template <std::size_t N>
Converted convert_points(const std::array<const Point3*, N>& pts, std::array<Vec3d, N>& out) {
  Converted status = kAllDoubles;
  for (std::size_t i = 0; i < N; ++i) {
    double c[3];
    for (int j = 0; j < 3; ++j) {
      bool exact = false;
      if (!convert_rational((*pts[i])[j], c[j], exact)) return kUnusable;
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

constexpr double kEpsSlack = 0x1.00001p-52;       // ε (1 + 2^-20), exact
constexpr double kConvSlack = kConvEps * kSlack;  // κ (1 + 2^-20), exact

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

template <class Shape, std::size_t K>
Approx approx_rat(const std::array<QGroup, K>& in) {
  std::array<V, K> g;
  std::array<double, K> D, rho;
  Approx a;
  if (!prepare_rat(in, g, D, rho, Shape::shape)) return a;
  a.status = Approx::kOk;
  a.value = Shape::eval(g);
  a.bound = rational_bound(D, rho, Shape::shape);
  return a;
}
Approx3 approx_rat_ccc(const std::array<QGroup, 4>& in) {
  std::array<V, 4> g;
  std::array<double, 4> D, rho;
  Approx3 a;
  if (!prepare_rat(in, g, D, rho, kShapeCcc)) return a;
  a.status = Approx::kOk;
  a.value = Ccc::eval(g);
  a.bound = rational_bound(D, rho, kShapeCcc);
  return a;
}

// ===========================================================================
// Exact stage.  Every predicate is multilinear in its group vectors, so each
// group may be multiplied by any positive number without changing the sign:
// each group is scaled to an integer vector (a power of two for doubles, the
// lcm of the denominators for rationals) and the polynomial is evaluated
// with mpz, in a per-thread workspace so that no call allocates once the
// workspace has grown.

struct Workspace {
  mpz_t g[4][3];  // group vectors
  mpz_t c[3][3];  // cross products
  mpz_t s, t, l;  // scalars
  Workspace() {
    for (auto& v : g)
      for (auto& x : v) mpz_init(x);
    for (auto& v : c)
      for (auto& x : v) mpz_init(x);
    mpz_init(s);
    mpz_init(t);
    mpz_init(l);
  }
  ~Workspace() {
    for (auto& v : g)
      for (auto& x : v) mpz_clear(x);
    for (auto& v : c)
      for (auto& x : v) mpz_clear(x);
    mpz_clear(s);
    mpz_clear(t);
    mpz_clear(l);
  }
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;
};
Workspace& workspace() {
  thread_local Workspace ws;
  return ws;
}

inline bool finite(const Vec3d& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// x = m · 2^e with m odd (or x = 0, e = INT_MAX), read from the bits.
struct Dyadic {
  std::int64_t m;
  int e;
};
inline Dyadic decompose(double x) {
  assert(std::isfinite(x));
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  const int biased = int((bits >> 52) & 0x7ff);
  std::uint64_t mant = bits & ((std::uint64_t(1) << 52) - 1);
  int e = -1074;  // subnormal: x = mant · 2^-1074
  if (biased != 0) {
    mant |= std::uint64_t(1) << 52;
    e = biased - 1075;
  } else if (mant == 0) {
    return {0, INT_MAX};
  }
  const int tz = std::countr_zero(mant);
  const std::int64_t m = std::int64_t(mant >> tz);
  return {(bits >> 63) ? -m : m, e + tz};
}
inline void set_shifted(mpz_t out, const Dyadic& d, int base) {
  mpz_set_si(out, long(d.m));
  if (d.m != 0) mpz_mul_2exp(out, out, mp_bitcnt_t(d.e - base));
}

#if GMP_LIMB_BITS == 64 && defined(__SIZEOF_INT128__)
// out = v, for |v| < 2^127.
inline void set_int128(mpz_t out, __int128 v) {
  const unsigned __int128 a = v < 0 ? -static_cast<unsigned __int128>(v) : v;
  const std::uint64_t lo = std::uint64_t(a), hi = std::uint64_t(a >> 64);
  if (hi == 0) {
    mpz_set_ui(out, lo);
  } else {
    mp_limb_t* limbs = mpz_limbs_write(out, 2);
    limbs[0] = lo;
    limbs[1] = hi;
    mpz_limbs_finish(out, 2);
  }
  if (v < 0) mpz_neg(out, out);
}
#endif

// out = (a − b) · 2^-base, where a, b are dyadics with exponents ≥ base.
inline void set_diff(mpz_t out, const Dyadic& a, const Dyadic& b, int base, mpz_t tmp) {
#if GMP_LIMB_BITS == 64 && defined(__SIZEOF_INT128__)
  // Shifts up to 70 bits keep both terms below 2^123: 128-bit arithmetic.
  const int sa = a.m ? a.e - base : 0, sb = b.m ? b.e - base : 0;
  if (sa <= 70 && sb <= 70) {
    set_int128(out, static_cast<__int128>(a.m) * (static_cast<__int128>(1) << sa) -
                        static_cast<__int128>(b.m) * (static_cast<__int128>(1) << sb));
    return;
  }
#endif
  set_shifted(out, a, base);
  set_shifted(tmp, b, base);
  mpz_sub(out, out, tmp);
}

// out = (p − q) · 2^-E, E the smallest exponent among the six coordinates.
void load_diff(mpz_t* out, const Vec3d& p, const Vec3d& q, mpz_t tmp) {
  const Dyadic c[6] = {decompose(p.x), decompose(p.y), decompose(p.z),
                       decompose(q.x), decompose(q.y), decompose(q.z)};
  int base = INT_MAX;
  for (const auto& d : c) base = std::min(base, d.e);
  for (int i = 0; i < 3; ++i) {
    if (base == INT_MAX)
      mpz_set_ui(out[i], 0);
    else
      set_diff(out[i], c[i], c[i + 3], base, tmp);
  }
}
// out = d · 2^-E.
void load_vec(mpz_t* out, const Vec3d& d) {
  const Dyadic c[3] = {decompose(d.x), decompose(d.y), decompose(d.z)};
  const int base = std::min(c[0].e, std::min(c[1].e, c[2].e));
  for (int i = 0; i < 3; ++i) {
    if (base == INT_MAX)
      mpz_set_ui(out[i], 0);
    else
      set_shifted(out[i], c[i], base);
  }
}
// out = (p − q) · L, L the lcm of the six denominators (or 1).
void load_diff(mpz_t* out, const Point3& p, const Point3& q, Workspace& w) {
  bool integral = true;
  for (int i = 0; i < 3; ++i)
    integral = integral && mpz_cmp_ui(p[i].get_den_mpz_t(), 1) == 0 &&
               mpz_cmp_ui(q[i].get_den_mpz_t(), 1) == 0;
  if (integral) {
    for (int i = 0; i < 3; ++i) mpz_sub(out[i], p[i].get_num_mpz_t(), q[i].get_num_mpz_t());
    return;
  }
  mpz_set_ui(w.l, 1);
  for (int i = 0; i < 3; ++i) {
    mpz_lcm(w.l, w.l, p[i].get_den_mpz_t());
    mpz_lcm(w.l, w.l, q[i].get_den_mpz_t());
  }
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(w.t, w.l, p[i].get_den_mpz_t());
    mpz_mul(out[i], w.t, p[i].get_num_mpz_t());
    mpz_divexact(w.t, w.l, q[i].get_den_mpz_t());
    mpz_submul(out[i], w.t, q[i].get_num_mpz_t());
  }
}
// out = d · L.
void load_vec(mpz_t* out, const Point3& d, Workspace& w) {
  mpz_set_ui(w.l, 1);
  for (int i = 0; i < 3; ++i) mpz_lcm(w.l, w.l, d[i].get_den_mpz_t());
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(w.t, w.l, d[i].get_den_mpz_t());
    mpz_mul(out[i], w.t, d[i].get_num_mpz_t());
  }
}

// out = a × b (out distinct from a and b).
void icross(mpz_t* out, mpz_t* a, mpz_t* b) {
  mpz_mul(out[0], a[1], b[2]);
  mpz_submul(out[0], a[2], b[1]);
  mpz_mul(out[1], a[2], b[0]);
  mpz_submul(out[1], a[0], b[2]);
  mpz_mul(out[2], a[0], b[1]);
  mpz_submul(out[2], a[1], b[0]);
}
int sign_idot(mpz_t* a, mpz_t* b, mpz_t s) {
  mpz_mul(s, a[0], b[0]);
  mpz_addmul(s, a[1], b[1]);
  mpz_addmul(s, a[2], b[2]);
  return mpz_sgn(s);
}
bool is_zero(mpz_t* a) { return mpz_sgn(a[0]) == 0 && mpz_sgn(a[1]) == 0 && mpz_sgn(a[2]) == 0; }

// Loads the groups: pairs (p, q) → p − q; (p, nullptr) → p.
template <class Pt, std::size_t K>
Workspace& load(const std::array<std::array<const Pt*, 2>, K>& groups) {
  Workspace& w = workspace();
  for (std::size_t k = 0; k < K; ++k) {
    const Pt* p = groups[k][0];
    const Pt* q = groups[k][1];
    if constexpr (std::is_same_v<Pt, Vec3d>) {
      assert(finite(*p) && (!q || finite(*q)));
      if (q)
        load_diff(w.g[k], *p, *q, w.t);
      else
        load_vec(w.g[k], *p);
    } else {
      if (q)
        load_diff(w.g[k], *p, *q, w);
      else
        load_vec(w.g[k], *p, w);
    }
  }
  return w;
}

// The exact shapes on loaded groups.
int exact_det3(Workspace& w) {
  icross(w.c[0], w.g[1], w.g[2]);
  return sign_idot(w.g[0], w.c[0], w.s);
}
int exact_dcc(Workspace& w) {
  icross(w.c[0], w.g[0], w.g[1]);
  icross(w.c[1], w.g[2], w.g[3]);
  return sign_idot(w.c[0], w.c[1], w.s);
}
// n1 = c[0], n2 = c[1], n1 × n2 = c[2].
bool exact_parallel(Workspace& w) {
  icross(w.c[0], w.g[0], w.g[1]);
  icross(w.c[1], w.g[2], w.g[3]);
  icross(w.c[2], w.c[0], w.c[1]);
  return is_zero(w.c[2]);
}
bool exact_same_direction(Workspace& w) {
  return exact_parallel(w) && sign_idot(w.c[0], w.c[1], w.s) > 0;
}
int exact_dot(Workspace& w) { return sign_idot(w.g[0], w.g[1], w.s); }

}  // namespace

bool rational_to_filter_double(const Rational& q, double& out, bool& exact) {
  return convert_rational(q, out, exact);
}

// ===========================================================================
// The predicates.  Each block states the polynomial, its degree, the shape
// and the constants: T monomials, N roundings on the longest monomial path
// (Vec3d form: differences included; rational form: N' without them).
//
// Each predicate has a Vec3d form and a Point3 form of its three stages; the
// Point3 forms convert the coordinates (convert_points) and use the Vec3d
// filter when they are all doubles, the rational filter otherwise.

namespace {
// The Point3 approximation: Vec3d filter on exact doubles, rational filter
// on other rationals, nothing out of range.
template <std::size_t N, class VecF, class RatF>
auto point3_approx(const std::array<const Point3*, N>& pts, VecF&& vec, RatF&& rat)
    -> decltype(vec(std::declval<std::array<Vec3d, N>&>())) {
  std::array<Vec3d, N> v;
  switch (convert_points(pts, v)) {
    case kAllDoubles:
      return vec(v);
    case kRationals:
      return rat(v);
    default:
      return {};
  }
}
}  // namespace

// ---------------------------------------------------------------------------
// 1. orient3d = sign det[b − a; c − a; d − a] = sign ⟨u, v × w⟩,
//    u = b − a, v = c − a, w = d − a.  Degree 3, shape det3.
//    Evaluation: (v × w)_x = v_y w_z − v_z w_y (and cyclically), then
//    P = (u_x (v×w)_x + u_y (v×w)_y) + u_z (v×w)_z.
//    T = 6 monomials.  Path of u_x v_y w_z: 3 differences, v_y·w_z, −, u_x·(),
//    two + : N = 8 (N' = 5).
//    Semi-static: |value − P| ≤ 6 γ_8 (1 + 2^-20) M_u M_v M_w
//                 ≤ 0x1.80002p-47 · M_u M_v M_w   (≈ 1.07e-14 · M_u M_v M_w;
//    with round-to-nearest only, u = ε/2 would give 5.33e-15, next to
//    Shewchuk's orient3d (7u + 56u²) · permanent and CGAL's semi-static
//    5.11e-15 · max_x max_y max_z).  Per-vector maxima keep the bound tight
//    when one difference is much shorter than the others.
//    Dynamic: γ_8 (1 + 2^-20) ≤ 0x1.00002p-49 times the permanent
//    Σ |u_i v_j w_k| over the 6 terms, + 2^-1000.
//    Rational form: c_rat = 6 γ_5 (1 + 2^-20) ≤ 0x1.e0002p-48, plus the
//    perturbation term.

namespace {
Approx orient3d_point3(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                       bool lazy) {
  return point3_approx<4>(
      {&a, &b, &c, &d},
      [&](std::array<Vec3d, 4>& v) {
        return approx_vec<Det3, 3>({vsub(v[1], v[0]), vsub(v[2], v[0]), vsub(v[3], v[0])}, lazy);
      },
      [&](std::array<Vec3d, 4>& v) {
        return approx_rat<Det3, 3>({{{&v[1], &v[0]}, {&v[2], &v[0]}, {&v[3], &v[0]}}});
      });
}
}  // namespace

Approx orient3d_approx(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return approx_vec<Det3, 3>({vsub(b, a), vsub(c, a), vsub(d, a)}, false);
}
Approx orient3d_approx(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return orient3d_point3(a, b, c, d, false);
}
std::optional<int> orient3d_filter(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return certified_sign(approx_vec<Det3, 3>({vsub(b, a), vsub(c, a), vsub(d, a)}, true));
}
std::optional<int> orient3d_filter(const Point3& a, const Point3& b, const Point3& c,
                                   const Point3& d) {
  return certified_sign(orient3d_point3(a, b, c, d, true));
}
int orient3d_exact(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return exact_det3(load<Vec3d, 3>({{{&b, &a}, {&c, &a}, {&d, &a}}}));
}
int orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return exact_det3(load<Point3, 3>({{{&b, &a}, {&c, &a}, {&d, &a}}}));
}

// ---------------------------------------------------------------------------
// 2. support_compare = sign ⟨bi − bj, (a1 − a0) × (a2 − a0)⟩.  Degree 3,
//    shape det3 with e = bi − bj, u = a1 − a0, v = a2 − a0: the same tree,
//    T = 6, N = 8, semi-static bound 0x1.80002p-47 · M_e M_u M_v, dynamic
//    0x1.00002p-49 · permanent + 2^-1000 (rational: 0x1.e0002p-48 · Π D +
//    the perturbation term).

namespace {
Approx support_compare_point3(const Point3& a0, const Point3& a1, const Point3& a2,
                              const Point3& bi, const Point3& bj, bool lazy) {
  return point3_approx<5>(
      {&a0, &a1, &a2, &bi, &bj},
      [&](std::array<Vec3d, 5>& v) {
        return approx_vec<Det3, 3>({vsub(v[3], v[4]), vsub(v[1], v[0]), vsub(v[2], v[0])}, lazy);
      },
      [&](std::array<Vec3d, 5>& v) {
        return approx_rat<Det3, 3>({{{&v[3], &v[4]}, {&v[1], &v[0]}, {&v[2], &v[0]}}});
      });
}
}  // namespace

Approx support_compare_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                              const Vec3d& bj) {
  return approx_vec<Det3, 3>({vsub(bi, bj), vsub(a1, a0), vsub(a2, a0)}, false);
}
Approx support_compare_approx(const Point3& a0, const Point3& a1, const Point3& a2,
                              const Point3& bi, const Point3& bj) {
  return support_compare_point3(a0, a1, a2, bi, bj, false);
}
std::optional<int> support_compare_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                          const Vec3d& bi, const Vec3d& bj) {
  return certified_sign(approx_vec<Det3, 3>({vsub(bi, bj), vsub(a1, a0), vsub(a2, a0)}, true));
}
std::optional<int> support_compare_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                          const Point3& bi, const Point3& bj) {
  return certified_sign(support_compare_point3(a0, a1, a2, bi, bj, true));
}
int support_compare_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                          const Vec3d& bj) {
  return exact_det3(load<Vec3d, 3>({{{&bi, &bj}, {&a1, &a0}, {&a2, &a0}}}));
}
int support_compare_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& bi,
                          const Point3& bj) {
  return exact_det3(load<Point3, 3>({{{&bi, &bj}, {&a1, &a0}, {&a2, &a0}}}));
}

// ---------------------------------------------------------------------------
// 3. edge_facet_sign = sign ⟨p1 − p0, (a1 − a0) × (a2 − a0)⟩.  Degree 3,
//    shape det3 with e = p1 − p0: T = 6, N = 8, bounds as for 2.

namespace {
Approx edge_facet_sign_point3(const Point3& p0, const Point3& p1, const Point3& a0,
                              const Point3& a1, const Point3& a2, bool lazy) {
  return point3_approx<5>(
      {&p0, &p1, &a0, &a1, &a2},
      [&](std::array<Vec3d, 5>& v) {
        return approx_vec<Det3, 3>({vsub(v[1], v[0]), vsub(v[3], v[2]), vsub(v[4], v[2])}, lazy);
      },
      [&](std::array<Vec3d, 5>& v) {
        return approx_rat<Det3, 3>({{{&v[1], &v[0]}, {&v[3], &v[2]}, {&v[4], &v[2]}}});
      });
}
}  // namespace

Approx edge_facet_sign_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                              const Vec3d& a2) {
  return approx_vec<Det3, 3>({vsub(p1, p0), vsub(a1, a0), vsub(a2, a0)}, false);
}
Approx edge_facet_sign_approx(const Point3& p0, const Point3& p1, const Point3& a0,
                              const Point3& a1, const Point3& a2) {
  return edge_facet_sign_point3(p0, p1, a0, a1, a2, false);
}
std::optional<int> edge_facet_sign_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0,
                                          const Vec3d& a1, const Vec3d& a2) {
  return certified_sign(approx_vec<Det3, 3>({vsub(p1, p0), vsub(a1, a0), vsub(a2, a0)}, true));
}
std::optional<int> edge_facet_sign_filter(const Point3& p0, const Point3& p1, const Point3& a0,
                                          const Point3& a1, const Point3& a2) {
  return certified_sign(edge_facet_sign_point3(p0, p1, a0, a1, a2, true));
}
int edge_facet_sign_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                          const Vec3d& a2) {
  return exact_det3(load<Vec3d, 3>({{{&p1, &p0}, {&a1, &a0}, {&a2, &a0}}}));
}
int edge_facet_sign_exact(const Point3& p0, const Point3& p1, const Point3& a0, const Point3& a1,
                          const Point3& a2) {
  return exact_det3(load<Point3, 3>({{{&p1, &p0}, {&a1, &a0}, {&a2, &a0}}}));
}

// ---------------------------------------------------------------------------
// 4. arc_side = sign det[e_a; e_b; n] = sign ⟨e_a × e_b, u × v⟩ with
//    e_a = p1 − p0, e_b = q1 − q0, u = r1 − r0, v = r2 − r0 (n = u × v).
//    Degree 4, shape dcc: w = e_a × e_b and n = u × v, each coordinate as
//    w_x = e_a,y e_b,z − e_a,z e_b,y, then P = (w_x n_x + w_y n_y) + w_z n_z.
//    T = 12 monomials (4 per coordinate).  Path: 4 differences, × and − in w,
//    × and − in n, the product, two + : N = 11 (N' = 7).
//    Semi-static: |value − P| ≤ 12 γ_11 (1 + 2^-20) Π M
//                 ≤ 0x1.08002p-45 · M_ea M_eb M_u M_v   (≈ 2.93e-14).
//    Dynamic: γ_11 (1 + 2^-20) ≤ 0x1.60002p-49 times the permanent, + 2^-1000.
//    Rational form: c_rat = 12 γ_7 (1 + 2^-20) ≤ 0x1.50002p-46.

namespace {
Approx arc_side_point3(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1, const Point3& r2, bool lazy) {
  return point3_approx<7>(
      {&p0, &p1, &q0, &q1, &r0, &r1, &r2},
      [&](std::array<Vec3d, 7>& v) {
        return approx_vec<Dcc, 4>(
            {vsub(v[1], v[0]), vsub(v[3], v[2]), vsub(v[5], v[4]), vsub(v[6], v[4])}, lazy);
      },
      [&](std::array<Vec3d, 7>& v) {
        return approx_rat<Dcc, 4>(
            {{{&v[1], &v[0]}, {&v[3], &v[2]}, {&v[5], &v[4]}, {&v[6], &v[4]}}});
      });
}
}  // namespace

Approx arc_side_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1,
                       const Vec3d& r0, const Vec3d& r1, const Vec3d& r2) {
  return approx_vec<Dcc, 4>({vsub(p1, p0), vsub(q1, q0), vsub(r1, r0), vsub(r2, r0)}, false);
}
Approx arc_side_approx(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1, const Point3& r2) {
  return arc_side_point3(p0, p1, q0, q1, r0, r1, r2, false);
}
std::optional<int> arc_side_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0,
                                   const Vec3d& q1, const Vec3d& r0, const Vec3d& r1,
                                   const Vec3d& r2) {
  return certified_sign(
      approx_vec<Dcc, 4>({vsub(p1, p0), vsub(q1, q0), vsub(r1, r0), vsub(r2, r0)}, true));
}
std::optional<int> arc_side_filter(const Point3& p0, const Point3& p1, const Point3& q0,
                                   const Point3& q1, const Point3& r0, const Point3& r1,
                                   const Point3& r2) {
  return certified_sign(arc_side_point3(p0, p1, q0, q1, r0, r1, r2, true));
}
int arc_side_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1,
                   const Vec3d& r0, const Vec3d& r1, const Vec3d& r2) {
  return exact_dcc(load<Vec3d, 4>({{{&p1, &p0}, {&q1, &q0}, {&r1, &r0}, {&r2, &r0}}}));
}
int arc_side_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                   const Point3& r0, const Point3& r1, const Point3& r2) {
  return exact_dcc(load<Point3, 4>({{{&p1, &p0}, {&q1, &q0}, {&r1, &r0}, {&r2, &r0}}}));
}

// ---------------------------------------------------------------------------
// 5a. normals_dot_sign = sign ⟨n1, n2⟩, n1 = u1 × v1, n2 = u2 × v2 with
//     u1 = a1 − a0, v1 = a2 − a0, u2 = b1 − b0, v2 = b2 − b0.  Degree 4,
//     shape dcc: T = 12, N = 11, semi-static 0x1.08002p-45 · M_u1 M_v1 M_u2 M_v2,
//     dynamic 0x1.60002p-49 · permanent + 2^-1000.

namespace {
Approx normals_dot_point3(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                          const Point3& b1, const Point3& b2, bool lazy) {
  return point3_approx<6>(
      {&a0, &a1, &a2, &b0, &b1, &b2},
      [&](std::array<Vec3d, 6>& v) {
        return approx_vec<Dcc, 4>(
            {vsub(v[1], v[0]), vsub(v[2], v[0]), vsub(v[4], v[3]), vsub(v[5], v[3])}, lazy);
      },
      [&](std::array<Vec3d, 6>& v) {
        return approx_rat<Dcc, 4>(
            {{{&v[1], &v[0]}, {&v[2], &v[0]}, {&v[4], &v[3]}, {&v[5], &v[3]}}});
      });
}
}  // namespace

Approx normals_dot_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                          const Vec3d& b1, const Vec3d& b2) {
  return approx_vec<Dcc, 4>({vsub(a1, a0), vsub(a2, a0), vsub(b1, b0), vsub(b2, b0)}, false);
}
Approx normals_dot_approx(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                          const Point3& b1, const Point3& b2) {
  return normals_dot_point3(a0, a1, a2, b0, b1, b2, false);
}
std::optional<int> normals_dot_sign_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                           const Vec3d& b0, const Vec3d& b1, const Vec3d& b2) {
  return certified_sign(
      approx_vec<Dcc, 4>({vsub(a1, a0), vsub(a2, a0), vsub(b1, b0), vsub(b2, b0)}, true));
}
std::optional<int> normals_dot_sign_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                           const Point3& b0, const Point3& b1, const Point3& b2) {
  return certified_sign(normals_dot_point3(a0, a1, a2, b0, b1, b2, true));
}
int normals_dot_sign_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                           const Vec3d& b1, const Vec3d& b2) {
  return exact_dcc(load<Vec3d, 4>({{{&a1, &a0}, {&a2, &a0}, {&b1, &b0}, {&b2, &b0}}}));
}
int normals_dot_sign_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                           const Point3& b1, const Point3& b2) {
  return exact_dcc(load<Point3, 4>({{{&a1, &a0}, {&a2, &a0}, {&b1, &b0}, {&b2, &b0}}}));
}

// ---------------------------------------------------------------------------
// 5b. normals_parallel: n1 × n2 = 0, three polynomials of degree 4, shape ccc:
//     (n1 × n2)_x = n1_y n2_z − n1_z n2_y with n1_y = u1_z v1_x − u1_x v1_z ...
//     T = 8 monomials per coordinate.  Path: 4 differences, × and − in n1,
//     × and − in n2, the product, the final − : N = 10 (N' = 6).
//     Semi-static: |value_i − P_i| ≤ 8 γ_10 (1 + 2^-20) Π M ≤ 0x1.40002p-46 · Π M
//     (≈ 1.78e-14); dynamic: 0x1.40002p-49 · permanent_i + 2^-1000 per
//     coordinate; rational: 0x1.80002p-47.  The filter can prove "not
//     parallel" (a coordinate certified non-zero) or "a normal is zero" (a
//     zero difference vector); "parallel" otherwise needs the exact stage.
// 5c. normals_same_direction: false as soon as the filter proves
//     ⟨n1, n2⟩ < 0 (5a) or non-parallel (5b), or a normal is zero; otherwise
//     exact.

namespace {
std::optional<bool> parallel_from(const Approx3& c) {
  if (c.status == Approx::kZero) return true;  // n1 = 0 or n2 = 0
  for (int i = 0; i < 3; ++i)
    if (auto s = certified_sign(c, i); s && *s != 0) return false;
  return std::nullopt;
}
std::optional<bool> same_direction_from(const Approx& dot, const Approx3& cross) {
  if (dot.status == Approx::kZero) return false;  // a zero normal
  if (auto s = certified_sign(dot); s && *s < 0) return false;
  if (auto p = parallel_from(cross); p && !*p) return false;
  return std::nullopt;
}
std::array<V, 4> normals_groups(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                                const Vec3d& b1, const Vec3d& b2) {
  return {vsub(a1, a0), vsub(a2, a0), vsub(b1, b0), vsub(b2, b0)};
}
Approx3 normals_cross_point3(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                             const Point3& b1, const Point3& b2, bool lazy) {
  return point3_approx<6>(
      {&a0, &a1, &a2, &b0, &b1, &b2},
      [&](std::array<Vec3d, 6>& v) {
        return approx_vec_ccc(normals_groups(v[0], v[1], v[2], v[3], v[4], v[5]), lazy);
      },
      [&](std::array<Vec3d, 6>& v) {
        return approx_rat_ccc({{{&v[1], &v[0]}, {&v[2], &v[0]}, {&v[4], &v[3]}, {&v[5], &v[3]}}});
      });
}
template <class Pt>
Workspace& load_normals(const Pt& a0, const Pt& a1, const Pt& a2, const Pt& b0, const Pt& b1,
                        const Pt& b2) {
  return load<Pt, 4>({{{&a1, &a0}, {&a2, &a0}, {&b1, &b0}, {&b2, &b0}}});
}
}  // namespace

Approx3 normals_cross_approx(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                             const Vec3d& b1, const Vec3d& b2) {
  return approx_vec_ccc(normals_groups(a0, a1, a2, b0, b1, b2), false);
}
Approx3 normals_cross_approx(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                             const Point3& b1, const Point3& b2) {
  return normals_cross_point3(a0, a1, a2, b0, b1, b2, false);
}
std::optional<bool> normals_parallel_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                            const Vec3d& b0, const Vec3d& b1, const Vec3d& b2) {
  return parallel_from(approx_vec_ccc(normals_groups(a0, a1, a2, b0, b1, b2), true));
}
std::optional<bool> normals_parallel_filter(const Point3& a0, const Point3& a1, const Point3& a2,
                                            const Point3& b0, const Point3& b1, const Point3& b2) {
  return parallel_from(normals_cross_point3(a0, a1, a2, b0, b1, b2, true));
}
bool normals_parallel_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                            const Vec3d& b1, const Vec3d& b2) {
  return exact_parallel(load_normals(a0, a1, a2, b0, b1, b2));
}
bool normals_parallel_exact(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                            const Point3& b1, const Point3& b2) {
  return exact_parallel(load_normals(a0, a1, a2, b0, b1, b2));
}
std::optional<bool> normals_same_direction_filter(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                                  const Vec3d& b0, const Vec3d& b1,
                                                  const Vec3d& b2) {
  const auto g = normals_groups(a0, a1, a2, b0, b1, b2);
  const Approx dot = approx_vec<Dcc, 4>(g, true);
  if (auto s = certified_sign(dot); s && *s <= 0) return false;
  return same_direction_from(dot, approx_vec_ccc(g, true));
}
std::optional<bool> normals_same_direction_filter(const Point3& a0, const Point3& a1,
                                                  const Point3& a2, const Point3& b0,
                                                  const Point3& b1, const Point3& b2) {
  const Approx dot = normals_dot_point3(a0, a1, a2, b0, b1, b2, true);
  if (auto s = certified_sign(dot); s && *s <= 0) return false;
  return same_direction_from(dot, normals_cross_point3(a0, a1, a2, b0, b1, b2, true));
}
bool normals_same_direction_exact(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2,
                                  const Vec3d& b0, const Vec3d& b1, const Vec3d& b2) {
  return exact_same_direction(load_normals(a0, a1, a2, b0, b1, b2));
}
bool normals_same_direction_exact(const Point3& a0, const Point3& a1, const Point3& a2,
                                  const Point3& b0, const Point3& b1, const Point3& b2) {
  return exact_same_direction(load_normals(a0, a1, a2, b0, b1, b2));
}

// ---------------------------------------------------------------------------
// 6a. dot_sign = sign ⟨p1 − p0, q1 − q0⟩.  Degree 2, shape dot:
//     P = (a_x b_x + a_y b_y) + a_z b_z.  T = 3; path: 2 differences, ×, two
//     + : N = 5 (N' = 3).  Semi-static: |value − P| ≤ 3 γ_5 (1 + 2^-20) M_a M_b
//     ≤ 0x1.e0002p-49 · M_a M_b (≈ 3.33e-15); dynamic: 0x1.40002p-50 ·
//     (|a_x b_x| + |a_y b_y| + |a_z b_z|) + 2^-1000; rational: 0x1.20002p-49.

namespace {
Approx dot_sign_point3(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       bool lazy) {
  return point3_approx<4>(
      {&p0, &p1, &q0, &q1},
      [&](std::array<Vec3d, 4>& v) {
        return approx_vec<DotD, 2>({vsub(v[1], v[0]), vsub(v[3], v[2])}, lazy);
      },
      [&](std::array<Vec3d, 4>& v) {
        return approx_rat<DotD, 2>({{{&v[1], &v[0]}, {&v[3], &v[2]}}});
      });
}
}  // namespace

Approx dot_sign_approx(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  return approx_vec<DotD, 2>({vsub(p1, p0), vsub(q1, q0)}, false);
}
Approx dot_sign_approx(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  return dot_sign_point3(p0, p1, q0, q1, false);
}
std::optional<int> dot_sign_filter(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0,
                                   const Vec3d& q1) {
  return certified_sign(approx_vec<DotD, 2>({vsub(p1, p0), vsub(q1, q0)}, true));
}
std::optional<int> dot_sign_filter(const Point3& p0, const Point3& p1, const Point3& q0,
                                   const Point3& q1) {
  return certified_sign(dot_sign_point3(p0, p1, q0, q1, true));
}
int dot_sign_exact(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  return exact_dot(load<Vec3d, 2>({{{&p1, &p0}, {&q1, &q0}}}));
}
int dot_sign_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  return exact_dot(load<Point3, 2>({{{&p1, &p0}, {&q1, &q0}}}));
}

// ---------------------------------------------------------------------------
// 6b. compare_along = sign ⟨d, p − q⟩, d exact.  Degree 2, shape along: the
//     dot tree with one difference leaf: N = 4 (N' = 3), T = 3.
//     Semi-static: |value − P| ≤ 3 γ_4 (1 + 2^-20) M_d M_e ≤ 0x1.80002p-49 · M_d M_e
//     (≈ 2.66e-15); dynamic: 0x1.00002p-50 · permanent + 2^-1000; rational:
//     0x1.20002p-49 plus the perturbation term.

namespace {
Approx compare_along_point3(const Point3& d, const Point3& p, const Point3& q, bool lazy) {
  return point3_approx<3>(
      {&d, &p, &q},
      [&](std::array<Vec3d, 3>& v) {
        return approx_vec<Along, 2>({vof(v[0]), vsub(v[1], v[2])}, lazy);
      },
      [&](std::array<Vec3d, 3>& v) {
        return approx_rat<Along, 2>({{{&v[0], nullptr}, {&v[1], &v[2]}}});
      });
}
}  // namespace

Approx compare_along_approx(const Vec3d& d, const Vec3d& p, const Vec3d& q) {
  return approx_vec<Along, 2>({vof(d), vsub(p, q)}, false);
}
Approx compare_along_approx(const Point3& d, const Point3& p, const Point3& q) {
  return compare_along_point3(d, p, q, false);
}
std::optional<int> compare_along_filter(const Vec3d& d, const Vec3d& p, const Vec3d& q) {
  return certified_sign(approx_vec<Along, 2>({vof(d), vsub(p, q)}, true));
}
std::optional<int> compare_along_filter(const Point3& d, const Point3& p, const Point3& q) {
  return certified_sign(compare_along_point3(d, p, q, true));
}
int compare_along_exact(const Vec3d& d, const Vec3d& p, const Vec3d& q) {
  return exact_dot(load<Vec3d, 2>({{{&d, nullptr}, {&p, &q}}}));
}
int compare_along_exact(const Point3& d, const Point3& p, const Point3& q) {
  return exact_dot(load<Point3, 2>({{{&d, nullptr}, {&p, &q}}}));
}

}  // namespace detail

// ===========================================================================
// Public entry points: count, filter, fall back.

namespace {
template <class R, class Filter, class Exact>
inline R run(PredicateId id, Filter&& filter, Exact&& exact) {
  count_call(id);
  if (auto r = filter()) return *r;
  count_fallback(id);
  return exact();
}
}  // namespace

int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return run<int>(
      PredicateId::orient3d, [&] { return detail::orient3d_filter(a, b, c, d); },
      [&] { return detail::orient3d_exact(a, b, c, d); });
}
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return run<int>(
      PredicateId::orient3d, [&] { return detail::orient3d_filter(a, b, c, d); },
      [&] { return detail::orient3d_exact(a, b, c, d); });
}
int support_compare(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                    const Vec3d& bj) {
  return run<int>(
      PredicateId::support_compare,
      [&] { return detail::support_compare_filter(a0, a1, a2, bi, bj); },
      [&] { return detail::support_compare_exact(a0, a1, a2, bi, bj); });
}
int support_compare(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& bi,
                    const Point3& bj) {
  return run<int>(
      PredicateId::support_compare,
      [&] { return detail::support_compare_filter(a0, a1, a2, bi, bj); },
      [&] { return detail::support_compare_exact(a0, a1, a2, bi, bj); });
}
int edge_facet_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                    const Vec3d& a2) {
  return run<int>(
      PredicateId::edge_facet_sign,
      [&] { return detail::edge_facet_sign_filter(p0, p1, a0, a1, a2); },
      [&] { return detail::edge_facet_sign_exact(p0, p1, a0, a1, a2); });
}
int edge_facet_sign(const Point3& p0, const Point3& p1, const Point3& a0, const Point3& a1,
                    const Point3& a2) {
  return run<int>(
      PredicateId::edge_facet_sign,
      [&] { return detail::edge_facet_sign_filter(p0, p1, a0, a1, a2); },
      [&] { return detail::edge_facet_sign_exact(p0, p1, a0, a1, a2); });
}
int arc_side(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1, const Vec3d& r0,
             const Vec3d& r1, const Vec3d& r2) {
  return run<int>(
      PredicateId::arc_side, [&] { return detail::arc_side_filter(p0, p1, q0, q1, r0, r1, r2); },
      [&] { return detail::arc_side_exact(p0, p1, q0, q1, r0, r1, r2); });
}
int arc_side(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
             const Point3& r0, const Point3& r1, const Point3& r2) {
  return run<int>(
      PredicateId::arc_side, [&] { return detail::arc_side_filter(p0, p1, q0, q1, r0, r1, r2); },
      [&] { return detail::arc_side_exact(p0, p1, q0, q1, r0, r1, r2); });
}
int normals_dot_sign(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                     const Vec3d& b1, const Vec3d& b2) {
  return run<int>(
      PredicateId::normals_dot_sign,
      [&] { return detail::normals_dot_sign_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_dot_sign_exact(a0, a1, a2, b0, b1, b2); });
}
int normals_dot_sign(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                     const Point3& b1, const Point3& b2) {
  return run<int>(
      PredicateId::normals_dot_sign,
      [&] { return detail::normals_dot_sign_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_dot_sign_exact(a0, a1, a2, b0, b1, b2); });
}
bool normals_parallel(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                      const Vec3d& b1, const Vec3d& b2) {
  return run<bool>(
      PredicateId::normals_parallel,
      [&] { return detail::normals_parallel_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_parallel_exact(a0, a1, a2, b0, b1, b2); });
}
bool normals_parallel(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                      const Point3& b1, const Point3& b2) {
  return run<bool>(
      PredicateId::normals_parallel,
      [&] { return detail::normals_parallel_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_parallel_exact(a0, a1, a2, b0, b1, b2); });
}
bool normals_same_direction(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                            const Vec3d& b1, const Vec3d& b2) {
  return run<bool>(
      PredicateId::normals_same_direction,
      [&] { return detail::normals_same_direction_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_same_direction_exact(a0, a1, a2, b0, b1, b2); });
}
bool normals_same_direction(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                            const Point3& b1, const Point3& b2) {
  return run<bool>(
      PredicateId::normals_same_direction,
      [&] { return detail::normals_same_direction_filter(a0, a1, a2, b0, b1, b2); },
      [&] { return detail::normals_same_direction_exact(a0, a1, a2, b0, b1, b2); });
}
int dot_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  return run<int>(
      PredicateId::dot_sign, [&] { return detail::dot_sign_filter(p0, p1, q0, q1); },
      [&] { return detail::dot_sign_exact(p0, p1, q0, q1); });
}
int dot_sign(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  return run<int>(
      PredicateId::dot_sign, [&] { return detail::dot_sign_filter(p0, p1, q0, q1); },
      [&] { return detail::dot_sign_exact(p0, p1, q0, q1); });
}
int compare_along(const Vec3d& d, const Vec3d& p, const Vec3d& q) {
  return run<int>(
      PredicateId::compare_along, [&] { return detail::compare_along_filter(d, p, q); },
      [&] { return detail::compare_along_exact(d, p, q); });
}
int compare_along(const Point3& d, const Point3& p, const Point3& q) {
  return run<int>(
      PredicateId::compare_along, [&] { return detail::compare_along_filter(d, p, q); },
      [&] { return detail::compare_along_exact(d, p, q); });
}

}  // namespace minksum
