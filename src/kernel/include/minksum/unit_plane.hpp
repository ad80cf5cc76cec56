// minksum — the nearest facet plane to a point, filtered on unit normals in
// doubles (the penetration depth's candidate filter; src/kernel/unit_plane.cpp,
// derivation in docs/kernel.md §3 "Unit planes").
//
// nearest_plane (<minksum/predicates.hpp>) encloses each plane's squared
// distance in interval arithmetic; this form precomputes, once per plane, a
// double unit normal û ≈ n/|n| and offset ê ≈ d/|n| with a derived relative
// error, so that a query costs three products and three sums per plane and
// a bound, then exact comparisons among the planes the bound cannot rule out.
// The answer is the same exact first minimiser.
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/predicates.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace minksum {

// The plane a·x + b·y + c·z = d (integers) as doubles: |û_i − a_i/|n|| ≤
// γ_5 |a_i|/|n| and |ê − d/|n|| ≤ γ_5 |d|/|n| (γ_k = kε/(1 − kε), ε = 2^-52,
// any rounding mode).  usable = false when a value would be subnormal, zero
// for a non-zero integer, or |n|² ≥ 2^1000: the filter then always keeps the
// plane for the exact comparison.
struct UnitPlane {
  double u[3] = {0, 0, 0};
  double e = 0;
  bool usable = false;
};
UnitPlane unit_plane(const Plane& p);

// The plane nearest to s: the index i minimising (d_i − n_i·s)² / |n_i|² over
// planes[0..n), the smallest such index on ties (the answer of
// nearest_plane).  unit[i] = unit_plane(*planes[i]).  Precondition: n > 0.
std::size_t nearest_plane(const Plane* const* planes, const UnitPlane* unit, std::size_t n,
                          const RoundedPoint3& s);

namespace detail {
// An enclosure [lo, up] of the distance |d − n·s| / |n| of s to the plane,
// from the unit plane and s's rounding; nothing when s's rounding or the
// plane is unusable or the magnitudes are out of range (|ŝ| products summing
// to 2^1000 or more).  lo may be negative.
struct GapEnclosure {
  double lo, up;
};
std::optional<GapEnclosure> unit_gap_enclosure(const UnitPlane& p, const RoundedPoint3& s);
// The indices whose enclosure's lo is not above the smallest up (every
// minimiser is among them; all indices when the filter declines).
std::vector<std::size_t> nearest_unit_plane_candidates(const UnitPlane* unit, std::size_t n,
                                                       const RoundedPoint3& s);
// The exact stage shared by both nearest_plane forms: the first exact
// minimiser among `candidates` (in increasing order).
std::size_t nearest_plane_among(const Plane* const* planes, const std::vector<std::size_t>& candidates,
                                const RoundedPoint3& s);
}  // namespace detail

}  // namespace minksum
