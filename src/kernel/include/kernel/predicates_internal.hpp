// minksum — the predicates' descriptors, the generic stages, and each
// predicate's stages exposed separately.
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
// Layout of src/kernel/ (one file per stage):
//   filter.hpp/.cpp   the shapes, their bounds and the approximation (stage 1)
//   exact.hpp/.cpp    the GMP evaluation of the shapes (stage 2)
//   this header       one descriptor per predicate and the generic stages
//   predicates.cpp    the generic filtered predicate (count, filter, fall
//                     back to exact) behind the public functions, and the
//                     statistics
#pragma once

#include <cmath>
#include <cfloat>

#include <array>
#include <concepts>
#include <cstddef>
#include <minksum/predicates.hpp>
#include <optional>
#include <type_traits>
#include <vector>

#include "kernel/exact.hpp"
#include "kernel/filter.hpp"

namespace minksum::detail {

// ===========================================================================
// The generic stages.  A descriptor D names
//   id       its PredicateId (statistics),
//   arity    how many points it reads,
//   Shape    its expression shape (filter.hpp), with Shape::K group vectors,
//   groups   each group as point indices {p, q}: points[p] − points[q], or
//            the exact vector points[p] when q = kVector,
//   exact    the exact shape on the loaded groups (exact.hpp),
//   decide   the answer the filter's approximation proves, if any;
// or, instead of Shape/groups/decide, its own filter(points).

struct GroupIndex {
  int p, q;
};
inline constexpr int kVector = -1;

template <class Pt>
concept KernelPoint = std::same_as<Pt, Vec3d> || std::same_as<Pt, Point3>;

template <class D, class Pt>
using PointsOf = std::array<const Pt*, D::arity>;

// The group vectors of D on exact doubles (rounded differences).
template <class D>
[[gnu::always_inline]] inline std::array<V, D::Shape::K> groups_vec(const PointsOf<D, Vec3d>& p) {
  std::array<V, D::Shape::K> g;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const GroupIndex i = D::groups[k];
    g[k] = i.q == kVector ? vof(*p[i.p]) : vsub(*p[i.p], *p[i.q]);
  }
  return g;
}

// Stage 1 on exact doubles.
template <class D>
ApproxOf<typename D::Shape> approx_points(const PointsOf<D, Vec3d>& p, bool lazy) {
  return approx_vec<typename D::Shape>(groups_vec<D>(p), lazy);
}

// Stage 1 on rationals: the Vec3d form when every coordinate is a double,
// the rational filter on the rounded coordinates otherwise, nothing out of
// range.
template <class D>
ApproxOf<typename D::Shape> approx_points(const PointsOf<D, Point3>& p, bool lazy) {
  std::array<Vec3d, D::arity> v;
  switch (convert_points(p, v)) {
    case kAllDoubles: {
      PointsOf<D, Vec3d> pv;
      for (std::size_t i = 0; i < pv.size(); ++i) pv[i] = &v[i];
      return approx_points<D>(pv, lazy);
    }
    case kRationals: {
      std::array<QGroup, D::Shape::K> g;
      for (std::size_t k = 0; k < g.size(); ++k) {
        const GroupIndex i = D::groups[k];
        g[k] = {&v[i.p], i.q == kVector ? nullptr : &v[i.q]};
      }
      return approx_rat<typename D::Shape>(g);
    }
    default:
      return {};
  }
}

struct SignPredicate;

// Stage 1': the answer the approximation certifies.  For a sign predicate on
// doubles, the semi-static step runs first on its own (semi_static_sign,
// filter.hpp: the same value and bound as approx_vec's first step, without
// building an Approx); only what it leaves undecided goes through approx_vec.
// (The semi-static step is inlined into the caller, the rest is not: most
// calls end there, and a call saved is a good part of their cost.)
template <class D, KernelPoint Pt>
[[gnu::noinline]] auto filter_points_rest(const PointsOf<D, Pt>& p) {
  return D::decide(approx_points<D>(p, true));
}
template <class D, KernelPoint Pt>
[[gnu::always_inline]] inline auto filter_points(const PointsOf<D, Pt>& p) {
  if constexpr (requires { D::filter(p); }) {
    return D::filter(p);
  } else {
    if constexpr (std::same_as<Pt, Vec3d> && std::is_base_of_v<SignPredicate, D> &&
                  std::same_as<typename D::Shape::Value, double>) {
      if (const int s = semi_static_sign<typename D::Shape>(groups_vec<D>(p)))
        return std::optional<int>(s);
    }
    return filter_points_rest<D>(p);
  }
}

// Stage 2.
template <class D, KernelPoint Pt>
auto exact_points(const PointsOf<D, Pt>& p) {
  std::array<std::array<const Pt*, 2>, D::Shape::K> g;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const GroupIndex i = D::groups[k];
    g[k] = {p[i.p], i.q == kVector ? nullptr : p[i.q]};
  }
  return D::exact(load(g.data(), g.size()));
}

// ===========================================================================
// The descriptors.  Constants and derivations: filter.hpp (shapes) and
// docs/kernel.md (per predicate).

struct SignPredicate {
  static std::optional<int> decide(const Approx& a) { return certified_sign(a); }
};

// 1. orient3d = sign ⟨b − a, (c − a) × (d − a)⟩.  Shape det3: T = 6, N = 8
//    (N' = 5); semi-static 0x1.80002p-47 · M_u M_v M_w (≈ 1.07e-14; with
//    round-to-nearest only, ε/2 would give 5.33e-15, next to Shewchuk's
//    (7u + 56u²) · permanent and CGAL's semi-static 5.11e-15 · Π max).
struct Orient3dPred : SignPredicate {
  static constexpr PredicateId id = PredicateId::orient3d;
  static constexpr std::size_t arity = 4;  // a, b, c, d
  using Shape = Det3;
  static constexpr std::array<GroupIndex, 3> groups{{{1, 0}, {2, 0}, {3, 0}}};
  static int exact(Workspace& w) { return exact_det3(w); }
};

// 2. support_compare = sign ⟨bi − bj, (a1 − a0) × (a2 − a0)⟩.  Shape det3.
struct SupportComparePred : SignPredicate {
  static constexpr PredicateId id = PredicateId::support_compare;
  static constexpr std::size_t arity = 5;  // a0, a1, a2, bi, bj
  using Shape = Det3;
  static constexpr std::array<GroupIndex, 3> groups{{{3, 4}, {1, 0}, {2, 0}}};
  static int exact(Workspace& w) { return exact_det3(w); }
};

// 3. edge_facet_sign = sign ⟨p1 − p0, (a1 − a0) × (a2 − a0)⟩.  Shape det3.
struct EdgeFacetSignPred : SignPredicate {
  static constexpr PredicateId id = PredicateId::edge_facet_sign;
  static constexpr std::size_t arity = 5;  // p0, p1, a0, a1, a2
  using Shape = Det3;
  static constexpr std::array<GroupIndex, 3> groups{{{1, 0}, {3, 2}, {4, 2}}};
  static int exact(Workspace& w) { return exact_det3(w); }
};

// 4. arc_side = sign ⟨(p1 − p0) × (q1 − q0), (r1 − r0) × (r2 − r0)⟩.
//    Shape dcc: T = 12, N = 11 (N' = 7); semi-static 0x1.08002p-45 · Π M.
struct ArcSidePred : SignPredicate {
  static constexpr PredicateId id = PredicateId::arc_side;
  static constexpr std::size_t arity = 7;  // p0, p1, q0, q1, r0, r1, r2
  using Shape = Dcc;
  static constexpr std::array<GroupIndex, 4> groups{{{1, 0}, {3, 2}, {5, 4}, {6, 4}}};
  static int exact(Workspace& w) { return exact_dcc(w); }
};

// 5a. normals_dot_sign = sign ⟨n1, n2⟩, n1 = (a1 − a0) × (a2 − a0),
//     n2 = (b1 − b0) × (b2 − b0).  Shape dcc.
struct NormalsDotPred : SignPredicate {
  static constexpr PredicateId id = PredicateId::normals_dot_sign;
  static constexpr std::size_t arity = 6;  // a0, a1, a2, b0, b1, b2
  using Shape = Dcc;
  static constexpr std::array<GroupIndex, 4> groups{{{1, 0}, {2, 0}, {4, 3}, {5, 3}}};
  static int exact(Workspace& w) { return exact_dcc(w); }
};

// 5b. normals_parallel: n1 × n2 = 0, three polynomials, shape ccc: T = 8,
//     N = 10 (N' = 6); semi-static 0x1.40002p-46 · Π M.  The filter proves
//     "not parallel" (a coordinate certified non-zero) or "a normal is zero"
//     (a zero difference vector); "parallel" otherwise needs the exact stage.
struct NormalsParallelPred {
  static constexpr PredicateId id = PredicateId::normals_parallel;
  static constexpr std::size_t arity = 6;
  using Shape = Ccc;
  static constexpr std::array<GroupIndex, 4> groups = NormalsDotPred::groups;
  static bool exact(Workspace& w) { return exact_parallel(w); }
  static std::optional<bool> decide(const Approx3& c) {
    if (c.status == Approx::kZero) return true;  // n1 = 0 or n2 = 0
    for (int i = 0; i < 3; ++i)
      if (auto s = certified_sign(c, i); s && *s != 0) return false;
    return std::nullopt;
  }
};

// 5c. normals_same_direction: false as soon as the filter proves ⟨n1, n2⟩ ≤ 0
//     (5a) or non-parallel (5b); otherwise exact.
struct NormalsSameDirectionPred {
  static constexpr PredicateId id = PredicateId::normals_same_direction;
  static constexpr std::size_t arity = 6;
  using Shape = Ccc;  // for the exact stage's groups
  static constexpr std::array<GroupIndex, 4> groups = NormalsDotPred::groups;
  static bool exact(Workspace& w) { return exact_same_direction(w); }
  template <KernelPoint Pt>
  static std::optional<bool> filter(const std::array<const Pt*, 6>& p) {
    if (auto s = certified_sign(approx_points<NormalsDotPred>(p, true)); s && *s <= 0) return false;
    if (auto par = NormalsParallelPred::decide(approx_points<NormalsParallelPred>(p, true));
        par && !*par)
      return false;
    return std::nullopt;
  }
};

// 6a. dot_sign = sign ⟨p1 − p0, q1 − q0⟩.  Shape dot: T = 3, N = 5 (N' = 3).
struct DotSignPred : SignPredicate {
  static constexpr PredicateId id = PredicateId::dot_sign;
  static constexpr std::size_t arity = 4;  // p0, p1, q0, q1
  using Shape = Dot;
  static constexpr std::array<GroupIndex, 2> groups{{{1, 0}, {3, 2}}};
  static int exact(Workspace& w) { return exact_dot(w); }
};

// 6b. compare_along = sign ⟨d, p − q⟩, d exact.  Shape along: T = 3, N = 4.
struct CompareAlongPred : SignPredicate {
  static constexpr PredicateId id = PredicateId::compare_along;
  static constexpr std::size_t arity = 3;  // d, p, q
  using Shape = Along;
  static constexpr std::array<GroupIndex, 2> groups{{{0, kVector}, {1, 2}}};
  static int exact(Workspace& w) { return exact_dot(w); }
};

// 7. edge_normal_side = sign ⟨d − a, (b − a) × n⟩, n exact (a facet normal):
//    orient3d(a, b, a + n, d) without forming a + n.  Shape det3 with one
//    exact group (one rounding fewer than orient3d: the det3 constants cover
//    it; the rational filter takes ρ = κ D for the vector, as compare_along).
struct EdgeNormalSidePred : SignPredicate {
  static constexpr PredicateId id = PredicateId::edge_normal_side;
  static constexpr std::size_t arity = 4;  // a, b, n, d
  using Shape = Det3;
  static constexpr std::array<GroupIndex, 3> groups{{{3, 0}, {1, 0}, {2, kVector}}};
  static int exact(Workspace& w) { return exact_det3(w); }
};

// ===========================================================================
// Each predicate's stages, callable on its points (all Vec3d or all Point3)
// as in the public function: orient3d_approx(a, b, c, d), ...
//   *_approx  both steps of stage 1 (not lazy: the dynamic step always runs
//             on Vec3d inputs), for the tests;
//   *_filter  stage 1' (lazy);
//   *_exact   stage 2.

enum class Stage { approx, filter, exact };

template <class D, Stage S>
struct StageFunction {
  template <KernelPoint Pt, class... More>
    requires(sizeof...(More) + 1 == D::arity && (std::same_as<More, Pt> && ...))
  auto operator()(const Pt& first, const More&... more) const {
    const PointsOf<D, Pt> p{&first, &more...};
    if constexpr (S == Stage::approx)
      return approx_points<D>(p, false);
    else if constexpr (S == Stage::filter)
      return filter_points<D>(p);
    else
      return exact_points<D>(p);
  }
};

inline constexpr StageFunction<Orient3dPred, Stage::approx> orient3d_approx;
inline constexpr StageFunction<Orient3dPred, Stage::filter> orient3d_filter;
inline constexpr StageFunction<Orient3dPred, Stage::exact> orient3d_exact;
inline constexpr StageFunction<SupportComparePred, Stage::approx> support_compare_approx;
inline constexpr StageFunction<SupportComparePred, Stage::filter> support_compare_filter;
inline constexpr StageFunction<SupportComparePred, Stage::exact> support_compare_exact;
inline constexpr StageFunction<EdgeFacetSignPred, Stage::approx> edge_facet_sign_approx;
inline constexpr StageFunction<EdgeFacetSignPred, Stage::filter> edge_facet_sign_filter;
inline constexpr StageFunction<EdgeFacetSignPred, Stage::exact> edge_facet_sign_exact;
inline constexpr StageFunction<ArcSidePred, Stage::approx> arc_side_approx;
inline constexpr StageFunction<ArcSidePred, Stage::filter> arc_side_filter;
inline constexpr StageFunction<ArcSidePred, Stage::exact> arc_side_exact;
inline constexpr StageFunction<NormalsDotPred, Stage::approx> normals_dot_approx;
inline constexpr StageFunction<NormalsDotPred, Stage::filter> normals_dot_sign_filter;
inline constexpr StageFunction<NormalsDotPred, Stage::exact> normals_dot_sign_exact;
// n1 × n2 approximated (the parallel and same-direction tests share it).
inline constexpr StageFunction<NormalsParallelPred, Stage::approx> normals_cross_approx;
inline constexpr StageFunction<NormalsParallelPred, Stage::filter> normals_parallel_filter;
inline constexpr StageFunction<NormalsParallelPred, Stage::exact> normals_parallel_exact;
inline constexpr StageFunction<NormalsSameDirectionPred, Stage::filter> normals_same_direction_filter;
inline constexpr StageFunction<NormalsSameDirectionPred, Stage::exact> normals_same_direction_exact;
inline constexpr StageFunction<DotSignPred, Stage::approx> dot_sign_approx;
inline constexpr StageFunction<DotSignPred, Stage::filter> dot_sign_filter;
inline constexpr StageFunction<DotSignPred, Stage::exact> dot_sign_exact;
inline constexpr StageFunction<CompareAlongPred, Stage::approx> compare_along_approx;
inline constexpr StageFunction<CompareAlongPred, Stage::filter> compare_along_filter;
inline constexpr StageFunction<CompareAlongPred, Stage::exact> compare_along_exact;
inline constexpr StageFunction<EdgeNormalSidePred, Stage::approx> edge_normal_side_approx;
inline constexpr StageFunction<EdgeNormalSidePred, Stage::filter> edge_normal_side_filter;
inline constexpr StageFunction<EdgeNormalSidePred, Stage::exact> edge_normal_side_exact;

// ===========================================================================
// Rounded rational inputs (RoundedPoint3, kernel/rounded.cpp).

// Whether the rational filter may use p.approx: every coordinate's rounding
// is normal, or zero with the exact coordinate zero.  Then, the rounding
// being faithful, |approx − exact| ≤ ε |approx| ≤ κ |approx| coordinatewise,
// the premise of the rational filter (filter.hpp).
// The common case (three normal doubles, no look at the rationals) inline;
// rounded_usable_slow the rest.
bool rounded_usable_slow(const RoundedPoint3& p);
inline bool rounded_usable(const RoundedPoint3& p) {
  const double ax = std::fabs(p.approx.x), ay = std::fabs(p.approx.y), az = std::fabs(p.approx.z);
  if (ax >= DBL_MIN && ax <= DBL_MAX && ay >= DBL_MIN && ay <= DBL_MAX && az >= DBL_MIN && az <= DBL_MAX) return true;
  return rounded_usable_slow(p);
}

// Stage 1 of descriptor D on rounded points: the rational filter on the
// cached roundings, or nothing (kDecline) when one is unusable.
template <class D>
ApproxOf<typename D::Shape> approx_rounded(const std::array<const RoundedPoint3*, D::arity>& p) {
  for (const RoundedPoint3* q : p)
    if (!rounded_usable(*q)) return {};
  std::array<QGroup, D::Shape::K> g;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const GroupIndex i = D::groups[k];
    g[k] = {&p[i.p]->approx, i.q == kVector ? nullptr : &p[i.q]->approx};
  }
  return approx_rat<typename D::Shape>(g);
}

// plane_side's filter.  value = ((â x̂ + b̂ ŷ) + ĉ ẑ) − d̂ from the roundings;
// bound = c · M̃ + 2^-1000 with M̃ = ((|â x̂| + |b̂ ŷ|) + |ĉ ẑ|) + |d̂|, c = 2^-49:
//  * the inputs: a = â(1 + α), x = x̂(1 + ξ), |α|, |ξ| ≤ ε (faithful, normal
//    or exactly zero), so |a x − â x̂| ≤ (2ε + ε²)|â x̂| and |d − d̂| ≤ ε |d̂|;
//  * the evaluation: monomial paths of at most 4 roundings, γ_4 Σ|terms|,
//    plus 3 product underflows of at most 2^-1074 each;
//  * in all: |value − P| ≤ (γ_4 + 2ε + ε²) M + 4·2^-1074 with M the exact
//    Σ|â_i x̂_i| + |d̂| ≤ (M̃ + 6·2^-1074)(1 − ε)^-4.  c = 8ε covers
//    (γ_4 + 2ε + ε²)(1 − ε)^-6 ≈ 6ε (with the bound's own two roundings), and
//    2^-1000 all the absolute terms.
//  * range: M̃ < 2^1000 (else decline; an overflowed product makes M̃
//    infinite or ≥ DBL_MAX), so nothing overflows.
// status kDecline when a rounding is unusable or M̃ is out of range.
inline constexpr double kPlaneSideFactor = 0x1p-49;
inline constexpr double kPlaneSideAbsolute = 0x1p-1000;
Approx plane_side_approx(const std::array<double, 4>& rounded, const RoundedPoint3& s);
// plane_side_approx's arithmetic on finite roundings r of the plane and a
// usable rounding x of the point (rounded_usable): the value and its bound,
// false when M̃ is out of range.  Inline, for callers that check the inputs
// once for many planes.
inline bool plane_side_value(const std::array<double, 4>& r, const Vec3d& x, double& value, double& bound) {
  const double px = r[0] * x.x, py = r[1] * x.y, pz = r[2] * x.z;
  const double mag = ((std::fabs(px) + std::fabs(py)) + std::fabs(pz)) + std::fabs(r[3]);
  if (!(mag < 0x1p1000)) return false;
  value = ((px + py) + pz) - r[3];
  bound = kPlaneSideFactor * mag + kPlaneSideAbsolute;
  return true;
}
// The sign that bound proves, or 2.
inline int plane_side_sign_usable(const std::array<double, 4>& r, const Vec3d& x) {
  double value, bound;
  if (!plane_side_value(r, x, value, bound)) return 2;
  return value > bound ? 1 : value < -bound ? -1 : 2;
}
std::optional<int> plane_side_filter(const std::array<double, 4>& rounded, const RoundedPoint3& s);
int plane_side_exact(const Plane& plane, const Point3& s);

// nearest_plane's filter: the indices of the planes whose squared distance
// to s an interval evaluation (CGAL::Interval_nt, rounded outward, on the
// one-ulp enclosures of the faithful roundings) cannot prove larger than
// the smallest upper bound.  Every minimiser is among them.
std::vector<std::size_t> nearest_plane_candidates(const std::array<double, 4>* rounded,
                                                  std::size_t n, const RoundedPoint3& s);

}  // namespace minksum::detail
