// The exact values of proximity answers, computed on demand from the
// certified witness (docs/proximity.md): the closest point of M on the
// witness feature, the squared distance or depth, and the split of a point of
// M into a point of P and a point of Q.  The queries themselves decide the
// witness with filtered predicates only; these rational operations run when
// an accessor of DistanceResult or DepthResult is first called.
#include <minksum/proximity.hpp>

#include <cmath>
#include <stdexcept>

#include "proximity/obstacle_geometry.hpp"

namespace minksum {

namespace detail {

Point3 ObstacleGeometry::closest_point(const Feature& feat, const Point3& s) const {
  const ConvexPolytope& mm = m();
  switch (feat.dim) {
    case FeatureDim::vertex: return mm.point(feat.index);
    case FeatureDim::edge: {
      const Point3& a = mm.point(mm.origin(2 * feat.index));
      const Point3 e = mm.point(mm.target(2 * feat.index)) - a;
      return a + (dot(s - a, e) / dot(e, e)) * e;
    }
    case FeatureDim::facet: {
      const Point3& n = normal[feat.index];
      return s - ((dot(n, s) - offset[feat.index]) / norm2[feat.index]) * n;
    }
  }
  throw std::logic_error("proximity: unknown feature dimension");
}

std::pair<Point3, Point3> ObstacleGeometry::decompose(const Feature& feat, const Point3& x) const {
  const ConvexPolytope& mm = m();
  auto pq = [&](Index v) -> std::pair<Point3, Point3> {
    return {p.point(sum.vertex_origin[v].first), q.point(neg_to_q[sum.vertex_origin[v].second])};
  };
  if (feat.dim == FeatureDim::vertex) return pq(feat.index);
  if (feat.dim == FeatureDim::edge) {
    const Index a = mm.origin(2 * feat.index), b = mm.target(2 * feat.index);
    const Point3 e = mm.point(b) - mm.point(a);
    const Rational t = dot(x - mm.point(a), e) / dot(e, e);
    auto [pa, qa] = pq(a);
    auto [pb, qb] = pq(b);
    return {pa + t * (pb - pa), qa + t * (qb - qa)};
  }
  const std::vector<Index> vs = mm.facet_vertices(feat.index);
  const Point3& n = normal[feat.index];
  const Point3& w0 = mm.point(vs[0]);
  for (std::size_t i = 1; i + 1 < vs.size(); ++i) {
    const Point3& wi = mm.point(vs[i]);
    const Point3& wj = mm.point(vs[i + 1]);
    const Rational area = dot(cross(wi - w0, wj - w0), n);
    const Rational li = dot(cross(x - w0, wj - w0), n) / area;
    const Rational lj = dot(cross(wi - w0, x - w0), n) / area;
    const Rational l0 = 1 - li - lj;
    if (sgn(li) < 0 || sgn(lj) < 0 || sgn(l0) < 0) continue;
    auto [p0, q0] = pq(vs[0]);
    auto [pi, qi] = pq(vs[i]);
    auto [pj, qj] = pq(vs[i + 1]);
    return {l0 * p0 + li * pi + lj * pj, l0 * q0 + li * qi + lj * qj};
  }
  throw std::logic_error("proximity: point not in the facet it was attributed to");
}

// When one of the faces behind x is a vertex the other point is x
// translated by it; for two non-parallel edges p0 + α·u and q0 + β·v (the
// generic facet of M), x − (p0 − q0) = α·u − β·v and Cramer's rule on the
// normal equations gives
//   α = (⟨u,v⟩⟨w,v⟩ − ⟨v,v⟩⟨w,u⟩) / (⟨u,v⟩² − ⟨u,u⟩⟨v,v⟩),  w = x − p0 + q0;
// otherwise x's barycentric coordinates in w.m (decompose).
std::pair<Point3, Point3> ObstacleGeometry::split(const Witness& w, const Point3& x) const {
  if (w.q.dim == FeatureDim::vertex) {
    const Point3& qv = q.point(w.q.index);
    return {x + qv, qv};
  }
  if (w.p.dim == FeatureDim::vertex) {
    const Point3& pv = p.point(w.p.index);
    return {pv, pv - x};
  }
  if (w.p.dim == FeatureDim::edge && w.q.dim == FeatureDim::edge) {
    const Index hp = 2 * w.p.index, hq = 2 * w.q.index;
    const Point3& p0 = p.point(p.origin(hp));
    const Point3& q0 = q.point(q.origin(hq));
    const Point3 u = p.point(p.target(hp)) - p0, v = q.point(q.target(hq)) - q0;
    const Rational uv = dot(u, v);
    const Rational det = uv * uv - dot(u, u) * dot(v, v);  // −|u × v|²
    if (sgn(det) != 0) {
      const Point3 wv = x - p0 + q0;
      const Point3 pp = p0 + ((uv * dot(wv, v) - dot(v, v) * dot(wv, u)) / det) * u;
      return {pp, pp - x};
    }
  }
  return decompose(w.m, x);
}

std::pair<Point3, Point3> ObstacleGeometry::common_point(const Witness& w, ContactStatus status,
                                                         const Point3& s) const {
  if (status == ContactStatus::touching) return split(w, s);
  // s = (1 − λ) c + λ y with y the exit point of the ray from c through s.
  const Index f = w.facet;
  const Point3 dir = s - center;
  const Rational along = dot(normal[f], dir);
  if (sgn(along) <= 0) return {p_center, q_center};  // s == center
  const Rational mu = (offset[f] - dot(normal[f], center)) / along;  // >= 1
  const Point3 y = center + mu * dir;
  auto [py, qy] = split(w, y);  // y lies in the stabbed facet f = w.m
  const Rational lambda = 1 / mu;
  return {(1 - lambda) * p_center + lambda * py, (1 - lambda) * q_center + lambda * qy};
}

}  // namespace detail

namespace {
const Point3& zero_point() {
  static const Point3 z(Rational(0), Rational(0), Rational(0));
  return z;
}
}  // namespace

// ---------------------------------------------------------------------------
// DistanceResult.

Point3 DistanceResult::point() const { return s_exact_ ? *s_exact_ : Point3(sd_.x, sd_.y, sd_.z); }

detail::DistanceExact& DistanceResult::exact() const {
  if (!exact_) exact_ = std::make_shared<detail::DistanceExact>();
  return *exact_;
}

void DistanceResult::compute_distance() const {
  detail::DistanceExact& e = exact();
  if (e.have_distance) return;
  e.have_distance = true;
  if (status != ContactStatus::separate || !geo_) {
    e.squared_distance = 0;
    e.distance = 0;
    e.direction = zero_point();
    return;
  }
  const Point3 s = point();
  e.direction = s - geo_->closest_point(witness.m, s);
  e.squared_distance = dot(e.direction, e.direction);
  e.distance = std::sqrt(to_double(e.squared_distance));
}

void DistanceResult::compute_points() const {
  detail::DistanceExact& e = exact();
  if (e.have_points) return;
  e.have_points = true;
  if (!geo_) {
    e.point_p = e.point_q = zero_point();
    return;
  }
  std::pair<Point3, Point3> pq;
  const Point3 s = point();
  if (status == ContactStatus::separate) {
    compute_distance();
    pq = geo_->split(witness, s - e.direction);
  } else {
    pq = geo_->common_point(witness, status, s);
  }
  e.point_p = std::move(pq.first);
  e.point_q = pq.second + s;
  if (e.translated) {
    e.point_p = e.point_p + e.u;
    e.point_q = e.point_q + e.u;
  }
}

const Rational& DistanceResult::squared_distance() const {
  compute_distance();
  return exact_->squared_distance;
}
double DistanceResult::distance() const {
  compute_distance();
  return exact_->distance;
}
const Point3& DistanceResult::direction() const {
  compute_distance();
  return exact_->direction;
}
const Point3& DistanceResult::point_p() const {
  compute_points();
  return exact_->point_p;
}
const Point3& DistanceResult::point_q() const {
  compute_points();
  return exact_->point_q;
}

// ---------------------------------------------------------------------------
// DepthResult.

Point3 DepthResult::point() const { return s_exact_ ? *s_exact_ : Point3(sd_.x, sd_.y, sd_.z); }

detail::DepthExact& DepthResult::exact() const {
  if (!exact_) exact_ = std::make_shared<detail::DepthExact>();
  detail::DepthExact& e = *exact_;
  if (e.have) return e;
  e.have = true;
  if (status != ContactStatus::penetrating || !geo_) {
    e.squared_depth = 0;
    e.depth = 0;
    e.direction = zero_point();
    return e;
  }
  const Index f = witness.facet;
  const Point3& n = geo_->normal[f];
  const Rational gap = geo_->offset[f] - dot(n, point());  // d − n·s > 0 for s inside
  const Rational t = gap / geo_->norm2[f];              // s + t n lies on the facet plane
  e.squared_depth = t * gap;
  e.depth = std::sqrt(to_double(e.squared_depth));
  e.direction = (-t) * n;
  return e;
}

const Rational& DepthResult::squared_depth() const { return exact().squared_depth; }
double DepthResult::depth() const { return exact().depth; }
const Point3& DepthResult::direction() const { return exact().direction; }

}  // namespace minksum
