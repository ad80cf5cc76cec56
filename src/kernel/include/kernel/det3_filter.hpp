// minksum — the det3 filter with a cached facet normal: the sign of
//     ⟨x − y, (f1 − f0) × (f2 − f0)⟩
// for many differences x − y against one facet (f0, f1, f2), the normal and
// the facet's part of the error bound computed once per facet.  The walk
// method (src/sum/walk.cpp) decides every step with it.
//
// Internal header of src/kernel/.  It is the kernel's det3 predicate
// (filter.hpp, shape kShapeDet3, groups e = x − y, u = f1 − f0, v = f2 − f0)
// with the evaluation split between the facet and the difference; the
// analysis of filter.hpp applies unchanged:
//  * The expression tree.  value = (e_x n_x + e_y n_y) + e_z n_z with
//    n = (u_y v_z − u_z v_y, u_z v_x − u_x v_z, u_x v_y − u_y v_x), the
//    differences rounded: exactly Det3::eval (eval_dot of e and
//    eval_cross(u, v)), so T = 6 monomials, N = 8 roundings on a path with
//    the differences, N' = 5 without.
//  * Exact doubles (both operands' coordinates are doubles).  With D_e, D_u,
//    D_v the largest |coordinate| of the rounded e, u, v, all in [lo, hi] of
//    kShapeDet3, the semi-static bound (2) gives
//        |value − P| ≤ c_vec D_e D_u D_v,
//    computed as fl(fl(c_vec D_u D_v) D_e): three roundings of positive
//    factors, each at least (1 − ε) times exact in any rounding mode, which
//    the factor (1 − ε)^-2K folded into c_vec covers for any product order.
//    D_e = 0 means x = y (fl(p − q) = 0 iff p = q): P = 0 exactly.
//  * Rounded rationals (otherwise).  Each coordinate is its nearest double,
//    with |x̂ − x| ≤ κ|x̂|: the caller guarantees a rounded coordinate is
//    zero only when the coordinate is, and is normal otherwise (its
//    `filterable`).  Per group ρ = ε(1 + 2^-20)(D + 8C), C the largest
//    |coordinate| of the group's two points (prepare_rat's ρ), and the
//    rational bound of filter.hpp
//        B = c_rat D_e D_u D_v + T (1 + 2^-20) Σ_k ρ_k Π_{h≠k} (D_h + ρ_h),
//    computed as kr D_e + T (1 + 2^-20) (ρ_e a1 + (D_e + ρ_e) a2) with the
//    facet's kr = c_rat D_u D_v, a1 = (D_u + ρ_u)(D_v + ρ_v),
//    a2 = ρ_u (D_v + ρ_v) + ρ_v (D_u + ρ_u): the same sum regrouped, fewer
//    than 4K + 4 roundings of positive terms, covered by the slack.  Range:
//    every D in [lo, hi] and every C ≤ hi, no rescaling.
//  * A facet out of range gets NaN coefficients, so that no comparison with
//    its bound succeeds: the filter then answers 2 (undecided), as for a
//    difference out of range.  Under −ffast-math the analysis fails;
//    filter.hpp refuses it.
// tests/test_predicates.cpp (Det3Filter.*) checks on random and
// near-degenerate inputs, in every rounding mode, that every sign decided
// is the exact one.
#pragma once

#include "kernel/filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace minksum::detail {

// What the filter reads of a facet: the rounded normal and the facet's
// factors of the bound (NaN when the facet is out of the filter's range).
struct Det3Facet {
  double nx, ny, nz;  // fl((f1 − f0) × (f2 − f0)) on the rounded coordinates
  double kv, kr, a1, a2;
};

// The facet of corners f0, f1, f2 (rounded coordinates; c0, c1, c2 the
// largest |coordinate| of each).  `filterable`: the operand's rounded
// coordinates meet the assumptions above.  Returns whether the facet is in
// range (its bound coefficients are not NaN).
inline bool make_det3_facet(const Vec3d& a, const Vec3d& b, const Vec3d& c, double c0, double c1, double c2,
                            bool filterable, Det3Facet& g) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  g.nx = uy * vz - uz * vy;
  g.ny = uz * vx - ux * vz;
  g.nz = ux * vy - uy * vx;
  const double lo = kShapeDet3.lo, hi = kShapeDet3.hi;
  const double du = std::max({std::fabs(ux), std::fabs(uy), std::fabs(uz)});
  const double dv = std::max({std::fabs(vx), std::fabs(vy), std::fabs(vz)});
  const double cu = std::max(c0, c1), cv = std::max(c0, c2);
  const double ru = kEpsSlack * (du + 8 * cu), rv = kEpsSlack * (dv + 8 * cv);
  const bool ok = filterable && du >= lo && du <= hi && dv >= lo && dv <= hi && cu <= hi && cv <= hi;
  if (ok) {
    g.kv = kShapeDet3.c_vec * du * dv;
    g.kr = kShapeDet3.c_rat * du * dv;
    g.a1 = (du + ru) * (dv + rv);
    g.a2 = ru * (dv + rv) + rv * (du + ru);
  } else {
    g.kv = g.kr = g.a1 = g.a2 = std::numeric_limits<double>::quiet_NaN();
  }
  return ok;
}

// A difference x − y, rounded, with its largest |coordinate| and the
// largest |coordinate| of x and y (cx, cy).
struct Det3Diff {
  double ex, ey, ez, de, ce;
};
inline Det3Diff make_det3_diff(const Vec3d& p, const Vec3d& q, double cp, double cq) {
  Det3Diff d;
  d.ex = p.x - q.x, d.ey = p.y - q.y, d.ez = p.z - q.z;
  d.de = std::max({std::fabs(d.ex), std::fabs(d.ey), std::fabs(d.ez)});
  d.ce = std::max(cp, cq);
  return d;
}

// The sign of ⟨x − y, n(facet)⟩, or 2 when the filter cannot decide.
// `doubles`: every coordinate of both operands is exactly a double;
// `filterable`: the difference's operand meets the assumptions above.
inline int det3_filter(const Det3Facet& g, bool doubles, bool filterable, const Det3Diff& d) {
  if (!filterable) return 2;
  const double value = (d.ex * g.nx + d.ey * g.ny) + d.ez * g.nz;
  if (doubles) {
    if (d.de == 0) return 0;  // the same point
    if (d.de >= kShapeDet3.lo && d.de <= kShapeDet3.hi) {
      const double bound = g.kv * d.de;
      if (value > bound) return 1;
      if (value < -bound) return -1;
    }
  } else if (d.de >= kShapeDet3.lo && d.de <= kShapeDet3.hi && d.ce <= kShapeDet3.hi) {
    const double re = kEpsSlack * (d.de + 8 * d.ce);
    const double bound = g.kr * d.de + (kShapeDet3.terms * kSlack) * (re * g.a1 + (d.de + re) * g.a2);
    if (value > bound) return 1;
    if (value < -bound) return -1;
  }
  return 2;
}

}  // namespace minksum::detail
