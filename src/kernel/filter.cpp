// The non-template parts of the floating-point stage (kernel/filter.hpp):
// the certified sign and the rational → double conversion.
#include "kernel/filter.hpp"

#include <cmath>

namespace minksum::detail {

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
bool rational_to_filter_double(const Rational& q, double& out, bool& exact) {
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

}  // namespace minksum::detail
