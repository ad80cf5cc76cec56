// Proximity with points, segments and flat polygons (see sweep_proximity.hpp):
// exact scans of M = P ⊕ (−Q).
#include <minksum/error.hpp>
#include <minksum/sweep_proximity.hpp>

#include <optional>

namespace minksum {

namespace {

Rational norm2(const Point3& v) { return dot(v, v); }

// Squared distance from x to the segment [a, b] (a may equal b).
Rational segment_distance2(const Point3& x, const Point3& a, const Point3& b) {
  const Point3 d = b - a;
  const Rational len2 = norm2(d);
  if (sgn(len2) == 0) return norm2(x - a);
  Rational t = dot(x - a, d) / len2;
  if (sgn(t) < 0) t = 0;
  if (cmp(t, Rational(1)) > 0) t = 1;
  return norm2(x - (a + t * d));
}

// Squared distance from x to the convex polygon `loop`, counter-clockwise
// seen from the tip of n.
Rational polygon_distance2(const Point3& x, const std::vector<Point3>& loop, const Point3& n) {
  const Rational h = dot(n, x - loop[0]);
  const Rational nn = norm2(n);
  const Point3 foot = x - (h / nn) * n;  // the projection onto the plane
  bool inside = true;
  for (std::size_t i = 0; i < loop.size() && inside; ++i)
    inside = sgn(dot(n, cross(loop[(i + 1) % loop.size()] - loop[i], foot - loop[i]))) >= 0;
  if (inside) return h * h / nn;
  std::optional<Rational> best;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    Rational d2 = segment_distance2(x, loop[i], loop[(i + 1) % loop.size()]);
    if (!best || cmp(d2, *best) < 0) best = std::move(d2);
  }
  return *best;
}

}  // namespace

SetObstacle::SetObstacle(const ConvexSet& p, const ConvexSet& q, Method method)
    : m_(minkowski_sum_sets(p, q.negated(), method).set) {
  if (m_.full())
    for (Index f = 0; f < m_.polytope().num_facets(); ++f) planes_.push_back(m_.polytope().plane(f));
}

ContactStatus SetObstacle::contact(const Point3& s) const {
  if (m_.full()) {
    int worst = -1;
    for (const Plane& pl : planes_) worst = std::max(worst, pl.side(s));
    return worst > 0 ? ContactStatus::separate : worst == 0 ? ContactStatus::touching : ContactStatus::penetrating;
  }
  return sgn(squared_distance(s)) == 0 ? ContactStatus::touching : ContactStatus::separate;
}

Rational SetObstacle::squared_distance(const Point3& s) const {
  const std::vector<Point3>& v = m_.vertices();
  switch (m_.dimension()) {
    case 0: return norm2(s - v[0]);
    case 1: return segment_distance2(s, v[0], v[1]);
    case 2: return polygon_distance2(s, v, m_.normal());
    default: break;
  }
  // The closest point lies on a facet whose plane s is above.
  const ConvexPolytope& m = m_.polytope();
  std::optional<Rational> best;
  for (Index f = 0; f < m.num_facets(); ++f) {
    if (planes_[f].side(s) <= 0) continue;
    std::vector<Point3> loop;
    for (Index i : m.facet_vertices(f)) loop.push_back(m.point(i));
    Rational d2 = polygon_distance2(s, loop, planes_[f].normal());
    if (!best || cmp(d2, *best) < 0) best = std::move(d2);
  }
  return best ? *best : Rational(0);
}

Rational SetObstacle::squared_depth(const Point3& s) const {
  if (contact(s) != ContactStatus::penetrating) return Rational(0);
  // Inside: the nearest facet plane.
  std::optional<Rational> best;
  for (const Plane& pl : planes_) {
    const Point3 n = pl.normal();
    const Rational h = dot(n, s) - Rational(pl.d);
    Rational d2 = h * h / norm2(n);
    if (!best || cmp(d2, *best) < 0) best = std::move(d2);
  }
  return *best;
}

Rational SetObstacle::directional_depth(const Point3& s, const Point3& d) const {
  if (is_zero(d)) throw UsageError("the direction of a directional depth must not be the zero vector");
  if (contact(s) != ContactStatus::penetrating) return Rational(0);
  // s − t·d leaves M through the first facet plane it crosses: n·(s − t d) = c
  // for the facets with n·d < 0, at t = (n·s − c) / (n·d).
  std::optional<Rational> best;
  for (const Plane& pl : planes_) {
    const Point3 n = pl.normal();
    const Rational nd = dot(n, d);
    if (sgn(nd) >= 0) continue;
    Rational t = (dot(n, s) - Rational(pl.d)) / nd;
    if (!best || cmp(t, *best) < 0) best = std::move(t);
  }
  return *best;
}

}  // namespace minksum
