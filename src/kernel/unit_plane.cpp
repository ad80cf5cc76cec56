// The nearest facet plane through unit normals in doubles
// (<minksum/unit_plane.hpp>).  Derivation (ε = 2^-52; every bound below
// holds in every IEEE rounding mode: one rounding is a factor (1 + θ),
// |θ| ≤ ε, and k such factors, powers ±1, give γ_k = kε/(1 − kε) — Higham,
// Accuracy and Stability of Numerical Algorithms, Lemma 3.1):
//
// Precomputation, u_i = a_i/|n|, e = d/|n|, |n|² = N (exact integer):
//   â_i = to_double(a_i), d̂ likewise (faithful: one factor each); N̂ =
//   to_double(N) (one); q = fl(√N̂) (one: a half power of N̂'s factor
//   counts as at most one); r = fl(1/q) (one); û_i = fl(â_i r), ê = fl(d̂ r)
//   (one).  So û_i = u_i (1 + θ), |θ| ≤ γ_5, and ê = e (1 + θ'), |θ'| ≤ γ_5,
//   provided nothing under- or overflows: usable requires N̂ < 2^1000 and
//   every û_i, ê zero exactly when its integer is, normal otherwise.
//
// Query, ŝ a faithful rounding of s, usable (every coordinate normal or an
// exact zero: ŝ_i = s_i (1 + θ), |θ| ≤ ε):
//   g̃ = fl(ê − ((p_x + p_y) + p_z)),  p_i = fl(û_i ŝ_i),
//   M̃ = fl(|ê| + ((|p_x| + |p_y|) + |p_z|)).
//   The monomial e passes γ_5 and the final subtraction (6 factors); u_i s_i
//   passes γ_5, ŝ, the product, two sums and the subtraction (10).  With
//   at most 3 product underflows of 2^-1074 each,
//     |g̃ − g| ≤ γ_10 M + 4·2^-1074,   M = |e| + Σ|u_i s_i| ≤ (M̃ + 3·2^-1074)/(1 − γ_10).
//   The enclosure of |g| is lo = fl(|g̃| − δ), up = fl(|g̃| + δ) with
//   δ = fl(2^-47 M̃) + 2^-1000: 2^-47 = 32ε covers γ_10 (1 − γ_10)^-1 ≈ 10ε,
//   δ's own rounding, and the two roundings of |g̃| ± δ (each at most
//   ε (|g̃| + δ) ≤ 1.01 ε M̃, since |g̃| ≤ M̃ (1 + γ_4)); 2^-1000 covers the
//   absolute terms.  Range: M̃ < 2^1000 (else decline), so nothing
//   overflows.  The test UnitPlanes.EnclosureHoldsInAllRoundingModes checks
//   lo ≤ |g| ≤ up exactly (squared, in rationals).
#include <minksum/unit_plane.hpp>

#include <cfloat>
#include <cmath>
#include <limits>

#include "kernel/predicates_internal.hpp"

namespace minksum {

namespace {
// Zero exactly when `exact` is, else normal and finite.
bool exact_zero_or_normal(double x, const Integer& exact) {
  if (x == 0) return exact == 0;
  return std::fabs(x) >= DBL_MIN && std::fabs(x) <= DBL_MAX;
}
}  // namespace

UnitPlane unit_plane(const Plane& p) {
  UnitPlane out;
  const Integer n2 = p.a * p.a + p.b * p.b + p.c * p.c;
  const double nn = to_double(Rational(n2));
  if (!(nn >= DBL_MIN && nn < 0x1p1000)) return out;
  const double r = 1 / std::sqrt(nn);
  const Integer* coef[3] = {&p.a, &p.b, &p.c};
  for (int i = 0; i < 3; ++i) {
    out.u[i] = to_double(Rational(*coef[i])) * r;
    if (!exact_zero_or_normal(out.u[i], *coef[i])) return out;
  }
  out.e = to_double(Rational(p.d)) * r;
  if (!exact_zero_or_normal(out.e, p.d)) return out;
  out.usable = true;
  return out;
}

namespace detail {

namespace {
// The enclosure for a usable plane and a usable rounding of s (derivation
// above); nothing when the magnitudes are out of range.
inline std::optional<GapEnclosure> enclose(const UnitPlane& p, const Vec3d& s) {
  const double px = p.u[0] * s.x, py = p.u[1] * s.y, pz = p.u[2] * s.z;
  const double mag = std::fabs(p.e) + ((std::fabs(px) + std::fabs(py)) + std::fabs(pz));
  if (!(mag < 0x1p1000)) return std::nullopt;
  const double g = std::fabs(p.e - ((px + py) + pz));
  const double delta = 0x1p-47 * mag + 0x1p-1000;
  return GapEnclosure{g - delta, g + delta};
}
}  // namespace

std::optional<GapEnclosure> unit_gap_enclosure(const UnitPlane& p, const RoundedPoint3& s) {
  if (!p.usable || !rounded_usable(s)) return std::nullopt;
  return enclose(p, s.approx);
}

std::vector<std::size_t> nearest_unit_plane_candidates(const UnitPlane* unit, std::size_t n,
                                                       const RoundedPoint3& s) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<std::size_t> out;
  if (!rounded_usable(s)) {
    for (std::size_t i = 0; i < n; ++i) out.push_back(i);
    return out;
  }
  thread_local std::vector<GapEnclosure> enc;  // reused from query to query
  enc.resize(n);
  double best = inf;
  for (std::size_t i = 0; i < n; ++i) {
    const std::optional<GapEnclosure> e = unit[i].usable ? enclose(unit[i], s.approx) : std::nullopt;
    enc[i] = e ? *e : GapEnclosure{0, inf};
    best = std::min(best, enc[i].up);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!(enc[i].lo > best)) out.push_back(i);
  return out;
}

std::size_t nearest_plane_among(const Plane* const* planes, const std::vector<std::size_t>& candidates,
                                const RoundedPoint3& s) {
  // Every minimiser is a candidate: a single candidate is the answer.
  if (candidates.size() == 1) return candidates[0];
  // s = (X, Y, Z) / W over the lcm W of its denominators: every gap
  // d − n·s is G / W with the integer G = d·W − n·(X, Y, Z), so
  // gap_i² / |n_i|² < gap_j² / |n_j|² ⇔ G_i²·|n_j|² < G_j²·|n_i|² — integer
  // products, no rational normalisation.
  Integer w, x, y, z;
  mpz_lcm(w.get_mpz_t(), s.exact.x.get_den_mpz_t(), s.exact.y.get_den_mpz_t());
  mpz_lcm(w.get_mpz_t(), w.get_mpz_t(), s.exact.z.get_den_mpz_t());
  mpz_divexact(x.get_mpz_t(), w.get_mpz_t(), s.exact.x.get_den_mpz_t());
  mpz_divexact(y.get_mpz_t(), w.get_mpz_t(), s.exact.y.get_den_mpz_t());
  mpz_divexact(z.get_mpz_t(), w.get_mpz_t(), s.exact.z.get_den_mpz_t());
  x *= s.exact.x.get_num();
  y *= s.exact.y.get_num();
  z *= s.exact.z.get_num();
  std::size_t arg = std::size_t(-1);
  Integer arg_gap2, arg_norm2, gap, norm2, lhs, rhs;
  for (std::size_t i : candidates) {
    const Plane& p = *planes[i];
    gap = p.d * w;
    mpz_submul(gap.get_mpz_t(), p.a.get_mpz_t(), x.get_mpz_t());
    mpz_submul(gap.get_mpz_t(), p.b.get_mpz_t(), y.get_mpz_t());
    mpz_submul(gap.get_mpz_t(), p.c.get_mpz_t(), z.get_mpz_t());
    gap *= gap;
    norm2 = p.a * p.a;
    mpz_addmul(norm2.get_mpz_t(), p.b.get_mpz_t(), p.b.get_mpz_t());
    mpz_addmul(norm2.get_mpz_t(), p.c.get_mpz_t(), p.c.get_mpz_t());
    // Strictly smaller: the first index wins ties.
    bool better = arg == std::size_t(-1);
    if (!better) {
      lhs = gap * arg_norm2;
      rhs = arg_gap2 * norm2;
      better = lhs < rhs;
    }
    if (better) {
      arg = i;
      swap(arg_gap2, gap);
      swap(arg_norm2, norm2);
    }
  }
  return arg;
}

}  // namespace detail

std::size_t nearest_plane(const Plane* const* planes, const UnitPlane* unit, std::size_t n,
                          const RoundedPoint3& s) {
  return detail::nearest_plane_among(planes, detail::nearest_unit_plane_candidates(unit, n, s), s);
}

}  // namespace minksum
