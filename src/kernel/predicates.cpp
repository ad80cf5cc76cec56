// The public sign predicates: one generic filtered predicate (count the call,
// run the filter of kernel/filter.hpp, fall back to the exact stage of
// kernel/exact.hpp and count the fallback) applied to each descriptor of
// kernel/predicates_internal.hpp.
#include "kernel/predicates_internal.hpp"

namespace minksum {

// ---------------------------------------------------------------------------
// Statistics.

namespace {
thread_local PredicateStats t_stats;
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
    case PredicateId::edge_normal_side:
      return "edge_normal_side";
  }
  return "?";
}

// ---------------------------------------------------------------------------
// The filtered predicate: filter (semi-static, then dynamic), else exact.

namespace {
template <class D, detail::KernelPoint Pt, class... More>
inline auto filtered(const Pt& first, const More&... more) {
  const detail::PointsOf<D, Pt> p{&first, &more...};
  PredicateCounter& counter = t_stats.counters[int(D::id)];
  ++counter.calls;
  if (auto r = detail::filter_points<D>(p)) return *r;
  ++counter.fallbacks;
  return detail::exact_points<D>(p);
}

// The same for rounded rational points: the rational filter on the cached
// roundings first, then the Point3 form's filter, then exact.
template <class D, class... More>
inline auto filtered(const RoundedPoint3& first, const More&... more) {
  const std::array<const RoundedPoint3*, D::arity> r{&first, &more...};
  PredicateCounter& counter = t_stats.counters[int(D::id)];
  ++counter.calls;
  if (auto a = D::decide(detail::approx_rounded<D>(r))) return *a;
  const detail::PointsOf<D, Point3> p{&first.exact, &more.exact...};
  if (auto a = detail::filter_points<D>(p)) return *a;
  ++counter.fallbacks;
  return detail::exact_points<D>(p);
}
}  // namespace

using namespace detail;

int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return filtered<Orient3dPred>(a, b, c, d);
}
int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return filtered<Orient3dPred>(a, b, c, d);
}
int orient3d(const RoundedPoint3& a, const RoundedPoint3& b, const RoundedPoint3& c,
             const RoundedPoint3& d) {
  return filtered<Orient3dPred>(a, b, c, d);
}
int support_compare(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& bi,
                    const Vec3d& bj) {
  return filtered<SupportComparePred>(a0, a1, a2, bi, bj);
}
int support_compare(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& bi,
                    const Point3& bj) {
  return filtered<SupportComparePred>(a0, a1, a2, bi, bj);
}
int support_compare(const RoundedPoint3& a0, const RoundedPoint3& a1, const RoundedPoint3& a2,
                    const RoundedPoint3& bi, const RoundedPoint3& bj) {
  return filtered<SupportComparePred>(a0, a1, a2, bi, bj);
}
int edge_facet_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& a0, const Vec3d& a1,
                    const Vec3d& a2) {
  return filtered<EdgeFacetSignPred>(p0, p1, a0, a1, a2);
}
int edge_facet_sign(const Point3& p0, const Point3& p1, const Point3& a0, const Point3& a1,
                    const Point3& a2) {
  return filtered<EdgeFacetSignPred>(p0, p1, a0, a1, a2);
}
int arc_side(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1, const Vec3d& r0,
             const Vec3d& r1, const Vec3d& r2) {
  return filtered<ArcSidePred>(p0, p1, q0, q1, r0, r1, r2);
}
int arc_side(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
             const Point3& r0, const Point3& r1, const Point3& r2) {
  return filtered<ArcSidePred>(p0, p1, q0, q1, r0, r1, r2);
}
int arc_side(const RoundedPoint3& p0, const RoundedPoint3& p1, const RoundedPoint3& q0,
             const RoundedPoint3& q1, const RoundedPoint3& r0, const RoundedPoint3& r1,
             const RoundedPoint3& r2) {
  return filtered<ArcSidePred>(p0, p1, q0, q1, r0, r1, r2);
}
int normals_dot_sign(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                     const Vec3d& b1, const Vec3d& b2) {
  return filtered<NormalsDotPred>(a0, a1, a2, b0, b1, b2);
}
int normals_dot_sign(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                     const Point3& b1, const Point3& b2) {
  return filtered<NormalsDotPred>(a0, a1, a2, b0, b1, b2);
}
bool normals_parallel(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                      const Vec3d& b1, const Vec3d& b2) {
  return filtered<NormalsParallelPred>(a0, a1, a2, b0, b1, b2);
}
bool normals_parallel(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                      const Point3& b1, const Point3& b2) {
  return filtered<NormalsParallelPred>(a0, a1, a2, b0, b1, b2);
}
bool normals_same_direction(const Vec3d& a0, const Vec3d& a1, const Vec3d& a2, const Vec3d& b0,
                            const Vec3d& b1, const Vec3d& b2) {
  return filtered<NormalsSameDirectionPred>(a0, a1, a2, b0, b1, b2);
}
bool normals_same_direction(const Point3& a0, const Point3& a1, const Point3& a2, const Point3& b0,
                            const Point3& b1, const Point3& b2) {
  return filtered<NormalsSameDirectionPred>(a0, a1, a2, b0, b1, b2);
}
int dot_sign(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  return filtered<DotSignPred>(p0, p1, q0, q1);
}
int dot_sign(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  return filtered<DotSignPred>(p0, p1, q0, q1);
}
int compare_along(const Vec3d& d, const Vec3d& p, const Vec3d& q) {
  return filtered<CompareAlongPred>(d, p, q);
}
int compare_along(const Point3& d, const Point3& p, const Point3& q) {
  return filtered<CompareAlongPred>(d, p, q);
}
int dot_sign(const RoundedPoint3& p0, const RoundedPoint3& p1, const RoundedPoint3& q0,
             const RoundedPoint3& q1) {
  return filtered<DotSignPred>(p0, p1, q0, q1);
}
int edge_normal_side(const Vec3d& a, const Vec3d& b, const Vec3d& n, const Vec3d& d) {
  return filtered<EdgeNormalSidePred>(a, b, n, d);
}
int edge_normal_side(const Point3& a, const Point3& b, const Point3& n, const Point3& d) {
  return filtered<EdgeNormalSidePred>(a, b, n, d);
}
int edge_normal_side(const RoundedPoint3& a, const RoundedPoint3& b, const RoundedPoint3& n,
                     const RoundedPoint3& d) {
  return filtered<EdgeNormalSidePred>(a, b, n, d);
}

}  // namespace minksum
