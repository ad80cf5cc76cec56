// TranslationalObstacle: exact collision, separation distance, penetration
// depth and directional penetration depth on M = P ⊕ (−Q) (Fogel and Halperin 2006, §4).
//
// Walks (docs/proximity.md):
//   * stab(): the facet of M hit by a ray from a point strictly inside M — a
//     visibility walk over M's facets (cross the edge whose plane through the
//     apex separates the facet's cone from the ray), starting from the last
//     answer; the edge tried first rotates pseudo-randomly so the walk cannot
//     cycle forever; after F + 16 moves it gives up for a scan of all facets.
//     Tests: orient3d (degree 3, filtered, exact).
//   * closest_feature(): the Lin–Canny style descent over vertices, edges and
//     facets for a point outside M.  Each move strictly decreases the
//     distance to the current feature or keeps it and lowers the dimension,
//     so no feature is visited twice; a stop at a vertex or an edge is the
//     global optimum (s − x lies in the normal cone).  The only local trap is a
//     facet whose plane does not have s strictly above it while s projects
//     into it; there the walk falls back to a scan of the facets s sees.
//   * penetration depth: the kernel's nearest_plane over all facet planes
//     (unit normals in doubles with a derived error bound, then exact
//     comparisons among the candidates).
#include <minksum/error.hpp>
#include <minksum/predicates.hpp>
#include <minksum/proximity.hpp>
#include <minksum/unit_plane.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

#include "mesh/support.hpp"

namespace minksum {

const char* contact_status_name(ContactStatus s) {
  switch (s) {
    case ContactStatus::separate: return "separate";
    case ContactStatus::touching: return "touching";
    case ContactStatus::penetrating: return "penetrating";
  }
  return "?";
}

namespace {

Rational squared_norm(const Point3& v) { return dot(v, v); }

Point3 average(const std::vector<Point3>& pts) {
  Point3 s(Rational(0), Rational(0), Rational(0));
  for (const auto& p : pts) s = s + p;
  return Rational(1, long(pts.size())) * s;
}

}  // namespace

TranslationalObstacle::TranslationalObstacle(ConvexPolytope p, ConvexPolytope q, Method method)
    : p_(std::move(p)), q_(std::move(q)), method_(method) {
  rebuild();
}

void TranslationalObstacle::set_p(ConvexPolytope p) {
  p_ = std::move(p);
  rebuild();
}
void TranslationalObstacle::set_q(ConvexPolytope q) {
  q_ = std::move(q);
  rebuild();
}
void TranslationalObstacle::set_operands(ConvexPolytope p, ConvexPolytope q) {
  p_ = std::move(p);
  q_ = std::move(q);
  rebuild();
}

void TranslationalObstacle::rebuild() {
  neg_q_ = q_.negated();
  std::unordered_map<Point3, Index, Point3Hash> q_index;
  for (Index v = 0; v < q_.num_vertices(); ++v) q_index.emplace(q_.point(v), v);
  neg_to_q_.assign(neg_q_.num_vertices(), kNoIndex);
  for (Index v = 0; v < neg_q_.num_vertices(); ++v) neg_to_q_[v] = q_index.at(-neg_q_.point(v));
  sum_ = minkowski_sum(p_, neg_q_, method_);
  const ConvexPolytope& m = sum_.polytope;
  const Index nf = m.num_facets();
  normal_.resize(nf);
  offset_.resize(nf);
  norm2_.resize(nf);
  plane_approx_.resize(nf);
  normal_approx_.resize(nf);
  unit_plane_.resize(nf);
  plane_ptr_.resize(nf);
  for (Index f = 0; f < nf; ++f) {
    const Plane& pl = m.plane(f);
    normal_[f] = pl.normal();
    offset_[f] = Rational(pl.d);
    norm2_[f] = squared_norm(normal_[f]);
    plane_approx_[f] = {to_double(Rational(pl.a)), to_double(Rational(pl.b)), to_double(Rational(pl.c)),
                        to_double(offset_[f])};
    normal_approx_[f] = Vec3d{plane_approx_[f][0], plane_approx_[f][1], plane_approx_[f][2]};
    unit_plane_[f] = unit_plane(pl);
    plane_ptr_[f] = &pl;
  }
  // avg(P) − avg(Q) is strictly inside M and has the obvious decomposition.
  p_center_ = average(p_.points());
  q_center_ = average(q_.points());
  center_ = p_center_ - q_center_;
  center_approx_ = to_double(center_);
  facet_features_.assign(nf, {});
  facet_features_known_.assign(nf, 0);
  last_stab_ = last_exit_ = last_depth_ = 0;
  last_closest_.reset();  // the first distance walk starts at the stabbed facet
  ++stats_.rebuilds;
}

// ---------------------------------------------------------------------------
// Witness helpers.

Feature TranslationalObstacle::feature_on_facet(Index f, const Point3& x) const {
  const ConvexPolytope& m = sum_.polytope;
  const Index h0 = m.facet_halfedge(f);
  Index h = h0;
  do {
    if (m.point(m.origin(h)) == x) return Feature::vertex(m.origin(h));
    h = m.next(h);
  } while (h != h0);
  // x lies in the facet: it is on the edge a→b exactly when it is on the
  // edge's line, ⟨x − a, (b − a) × n⟩ = 0 (kernel: edge_normal_side, filtered
  // on the roundings; only a zero is decided exactly).
  const Vec3d xd = to_double(x);
  const RoundedPoint3 rx{x, xd}, rn{normal_[f], normal_approx_[f]};
  h = h0;
  do {
    const Index a = m.origin(h), b = m.target(h);
    if (edge_normal_side(RoundedPoint3{m.point(a), m.approx(a)}, RoundedPoint3{m.point(b), m.approx(b)}, rn, rx) == 0)
      return Feature::edge(ConvexPolytope::edge(h));
    h = m.next(h);
  } while (h != h0);
  return Feature::facet(f);
}

void TranslationalObstacle::fill_operand_features(Witness& w) const {
  const ConvexPolytope& m = sum_.polytope;
  if (w.m.dim == FeatureDim::facet && facet_features_known_[w.m.index]) {
    w.p = facet_features_[w.m.index][0];
    w.q = facet_features_[w.m.index][1];
    return;
  }
  std::vector<Index> pv, qv;
  for (Index v : feature_vertices(m, w.m)) {
    pv.push_back(sum_.vertex_origin[v].first);
    qv.push_back(neg_to_q_[sum_.vertex_origin[v].second]);
  }
  std::sort(pv.begin(), pv.end());
  pv.erase(std::unique(pv.begin(), pv.end()), pv.end());
  std::sort(qv.begin(), qv.end());
  qv.erase(std::unique(qv.begin(), qv.end()), qv.end());
  w.p = feature_of_vertices(p_, pv);
  w.q = feature_of_vertices(q_, qv);
  if (w.m.dim == FeatureDim::facet) {
    facet_features_[w.m.index] = {w.p, w.q};
    facet_features_known_[w.m.index] = 1;
  }
}

std::pair<Point3, Point3> TranslationalObstacle::decompose(const Feature& feat, const Point3& x) const {
  const ConvexPolytope& m = sum_.polytope;
  auto pq = [&](Index v) -> std::pair<Point3, Point3> {
    return {p_.point(sum_.vertex_origin[v].first), q_.point(neg_to_q_[sum_.vertex_origin[v].second])};
  };
  if (feat.dim == FeatureDim::vertex) return pq(feat.index);
  if (feat.dim == FeatureDim::edge) {
    const Index a = m.origin(2 * feat.index), b = m.target(2 * feat.index);
    const Point3 e = m.point(b) - m.point(a);
    const Rational t = dot(x - m.point(a), e) / dot(e, e);
    auto [pa, qa] = pq(a);
    auto [pb, qb] = pq(b);
    return {pa + t * (pb - pa), qa + t * (qb - qa)};
  }
  const std::vector<Index> vs = m.facet_vertices(feat.index);
  const Point3& n = normal_[feat.index];
  const Point3& w0 = m.point(vs[0]);
  for (std::size_t i = 1; i + 1 < vs.size(); ++i) {
    const Point3& wi = m.point(vs[i]);
    const Point3& wj = m.point(vs[i + 1]);
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

// ---------------------------------------------------------------------------
// Ray stabbing.

struct TranslationalObstacle::RayApprox {
  Vec3d apex, through;
};

// orient3d(apex, m[a], m[b], through) on the cached roundings of M's
// vertices, the apex and the ray point (kernel: orient3d on RoundedPoint3).
int TranslationalObstacle::orient_filtered(const Point3& apex, Index a, Index b, const Point3& through,
                                           const RayApprox& ra) const {
  const ConvexPolytope& m = sum_.polytope;
  return orient3d(RoundedPoint3{apex, ra.apex}, RoundedPoint3{m.point(a), m.approx(a)},
                  RoundedPoint3{m.point(b), m.approx(b)}, RoundedPoint3{through, ra.through});
}

// The side of s with respect to facet f's plane, filtered on the plane's
// cached roundings (kernel: plane_side).
int TranslationalObstacle::side_filtered(Index f, const Point3& s) const {
  const Vec3d sd = to_double(s);
  return plane_side(sum_.polytope.plane(f), plane_approx_[f], RoundedPoint3{s, sd});
}

bool TranslationalObstacle::in_cone(Index f, const Point3& apex, const Point3& through, const RayApprox& ra,
                                    Index* exit) {
  const ConvexPolytope& m = sum_.polytope;
  Index h0 = m.facet_halfedge(f);
  rng_ ^= rng_ << 13, rng_ ^= rng_ >> 7, rng_ ^= rng_ << 17;
  for (std::uint64_t k = rng_ % 4; k > 0; --k) h0 = m.next(h0);
  Index h = h0;
  do {
    if (orient_filtered(apex, m.origin(h), m.target(h), through, ra) < 0) {
      *exit = h;
      return false;
    }
    h = m.next(h);
  } while (h != h0);
  return true;
}

Index TranslationalObstacle::stab_scan(const Point3& apex, const Point3& through) const {
  const ConvexPolytope& m = sum_.polytope;
  for (Index f = 0; f < m.num_facets(); ++f) {
    bool inside = true;
    const Index h0 = m.facet_halfedge(f);
    Index h = h0;
    do {
      if (orient3d(apex, m.point(m.origin(h)), m.point(m.target(h)), through) < 0) {
        inside = false;
        break;
      }
      h = m.next(h);
    } while (h != h0);
    if (inside) return f;
  }
  throw std::logic_error("proximity: no facet of M is hit by the ray");
}

Index TranslationalObstacle::stab(const Point3& apex, const Point3& through, Index start) {
  const ConvexPolytope& m = sum_.polytope;
  Index f = start < m.num_facets() ? start : 0;
  const std::uint64_t limit = std::uint64_t(m.num_facets()) + 16;
  const RayApprox ra{&apex == &center_ ? center_approx_ : to_double(apex), to_double(through)};
  for (std::uint64_t steps = 0; steps <= limit; ++steps) {
    Index exit;
    if (in_cone(f, apex, through, ra, &exit)) return f;
    f = m.facet(ConvexPolytope::twin(exit));
    ++stats_.walk_steps;
  }
  ++stats_.full_scans;
  return stab_scan(apex, through);
}

// ---------------------------------------------------------------------------
// Collision.

CollisionResult TranslationalObstacle::collide_point(const Point3& s) {
  ++stats_.queries;
  CollisionResult r;
  const ConvexPolytope& m = sum_.polytope;
  if (s == center_) {
    r.status = ContactStatus::penetrating;
    r.witness.facet = last_stab_ < m.num_facets() ? last_stab_ : 0;
    r.witness.m = Feature::facet(r.witness.facet);
    fill_operand_features(r.witness);
    return r;
  }
  const Index f = stab(center_, s, last_stab_);
  last_stab_ = f;
  const int side = side_filtered(f, s);
  r.status = side > 0 ? ContactStatus::separate : side == 0 ? ContactStatus::touching : ContactStatus::penetrating;
  r.witness.facet = f;
  r.witness.m = side == 0 ? feature_on_facet(f, s) : Feature::facet(f);
  fill_operand_features(r.witness);
  return r;
}

CollisionResult TranslationalObstacle::collide(const Point3& u, const Point3& w) { return collide_point(w - u); }

// ---------------------------------------------------------------------------
// Separation distance.

namespace {
struct Closest {
  Rational d2;
  Point3 x;
  Feature feat;
};
// Closest point of segment [a, b] to s.
Closest segment_closest(const Point3& s, const Point3& a, const Point3& b, Index ia, Index ib, Index edge) {
  const Point3 e = b - a;
  const Rational t = dot(s - a, e) / dot(e, e);
  Closest c;
  if (sgn(t) <= 0) {
    c.x = a, c.feat = Feature::vertex(ia);
  } else if (cmp(t, 1) >= 0) {
    c.x = b, c.feat = Feature::vertex(ib);
  } else {
    c.x = a + t * e, c.feat = Feature::edge(edge);
  }
  c.d2 = squared_norm(s - c.x);
  return c;
}
// Whether s lies strictly outside the prism over facet f of m (n its outer
// normal): beyond the plane through one of its edges orthogonal to f.
bool beyond_an_edge(const ConvexPolytope& m, Index f, const Point3& n, const Point3& s) {
  const Index h0 = m.facet_halfedge(f);
  Index h = h0;
  do {
    const Point3& a = m.point(m.origin(h));
    if (sgn(dot(s - a, cross(m.point(m.target(h)) - a, n))) > 0) return true;
    h = m.next(h);
  } while (h != h0);
  return false;
}
// The point of the boundary of facet f of m closest to s (the first of
// equally close ones along the loop).
Closest boundary_closest(const ConvexPolytope& m, Index f, const Point3& s) {
  const Index h0 = m.facet_halfedge(f);
  Closest best;
  bool have = false;
  Index h = h0;
  do {
    Closest c = segment_closest(s, m.point(m.origin(h)), m.point(m.target(h)), m.origin(h), m.target(h),
                                ConvexPolytope::edge(h));
    if (!have || c.d2 < best.d2) best = std::move(c), have = true;
    h = m.next(h);
  } while (h != h0);
  return best;
}
}  // namespace

Rational TranslationalObstacle::squared_distance_by_scan(const Point3& s) const {
  const ConvexPolytope& m = sum_.polytope;
  for (Index f = 0; f < m.num_facets(); ++f)
    if (m.plane(f).side(s) > 0) {
      Point3 x;
      Rational d2;
      Index facet;
      closest_feature_scan(s, x, d2, facet);
      return d2;
    }
  return 0;
}

Feature TranslationalObstacle::closest_feature_scan(const Point3& s, Point3& x, Rational& d2, Index& facet) const {
  const ConvexPolytope& m = sum_.polytope;
  bool found = false;
  Feature best = Feature::facet(0);
  for (Index f = 0; f < m.num_facets(); ++f) {
    if (m.plane(f).side(s) <= 0) continue;  // the closest point lies on a facet s sees
    const Point3& n = normal_[f];
    Closest c;
    if (!beyond_an_edge(m, f, n, s)) {
      const Rational t = (dot(n, s) - offset_[f]) / norm2_[f];
      c.x = s - t * n;
      c.d2 = t * t * norm2_[f];
      c.feat = Feature::facet(f);
    } else {
      c = boundary_closest(m, f, s);
    }
    if (!found || c.d2 < d2) {
      d2 = c.d2, x = c.x, best = c.feat, facet = f;
      found = true;
    }
  }
  if (!found) throw std::logic_error("proximity: distance query on a point inside M");
  return best;
}

// The Voronoi walk on M with the kernel's filtered predicates.  Every move
// and the final certificate are signs of exact polynomials in s and M's
// rational vertices and facet normals, filtered on their cached roundings
// (RoundedPoint3: no rational arithmetic unless a filter cannot decide):
//   vertex v: s − v in v's normal cone ⇔ ⟨s − v, w − v⟩ ≤ 0 for every
//             neighbour w (dot_sign); else move to the first edge v→w with
//             ⟨s − v, w − v⟩ > 0;
//   edge a→b (facets f1 left, f2 right): ⟨s − a, b − a⟩ > 0 and
//             ⟨s − b, a − b⟩ > 0 (the projection x lies inside the edge),
//             ⟨s − a, (b − a) × n1⟩ ≥ 0 and ⟨s − b, (a − b) × n2⟩ ≥ 0
//             (edge_normal_side: s − x in the cone of n1 and n2); else move
//             to the vertex or facet whose test failed;
//   facet f:  ⟨s − a, (b − a) × n⟩ ≤ 0 for every edge a→b of f (the
//             projection lies in the closed polygon) and n·s > d
//             (plane_side); else move to an edge s lies strictly beyond
//             (the one whose segment is nearest to s in double precision:
//             a choice, not a decision).  Below the plane (a local trap of
//             the descent: s projects into f from inside M) the walk
//             restarts once from `facet` on entry, a facet s sees (the
//             stabbed one), then scans.
// A certified feature contains the closest point x (for a facet, x lies on
// the edges whose test is exactly 0, on their common vertex for two).  The
// walk is bounded; beyond the bound it scans all facets exactly.
Feature TranslationalObstacle::closest_feature(const Point3& s, std::optional<Feature> start, Point3& dir, Rational& d2,
                                              Index& facet) {
  const ConvexPolytope& m = sum_.polytope;
  const std::uint64_t limit = 2 * (std::uint64_t(m.num_vertices()) + m.num_edges() + m.num_facets()) + 16;
  auto valid = [&](const Feature& f) {
    switch (f.dim) {
      case FeatureDim::vertex: return f.index < m.num_vertices();
      case FeatureDim::edge: return f.index < m.num_edges();
      case FeatureDim::facet: return f.index < m.num_facets();
    }
    return false;
  };
  const Vec3d sd = to_double(s);
  const RoundedPoint3 rs{s, sd};
  auto rv = [&](Index v) { return RoundedPoint3{m.point(v), m.approx(v)}; };
  auto rn = [&](Index f) { return RoundedPoint3{normal_[f], normal_approx_[f]}; };
  auto sees = [&](Index f) { return plane_side(m.plane(f), plane_approx_[f], rs) > 0; };
  const Index stabbed = facet < m.num_facets() ? facet : 0;
  bool restarted = false;
  Feature cur = start && valid(*start) ? *start : Feature::facet(stabbed);
  for (std::uint64_t steps = 0; steps < limit; ++steps) {
    if (cur.dim == FeatureDim::vertex) {
      const Index v = cur.index;
      const Index h0 = m.vertex_halfedge(v);
      Index h = h0, move = kNoIndex;
      do {
        if (dot_sign(rv(v), rs, rv(v), rv(m.target(h))) > 0) {
          move = h;
          break;
        }
        h = m.next_around_vertex(h);
      } while (h != h0);
      if (move == kNoIndex) {
        dir = s - m.point(v);
        d2 = squared_norm(dir);
        h = h0;
        facet = m.facet(h0);
        do {  // a facet through v that s sees
          if (sees(m.facet(h))) {
            facet = m.facet(h);
            break;
          }
          h = m.next_around_vertex(h);
        } while (h != h0);
        ++stats_.certified;
        return cur;
      }
      cur = Feature::edge(ConvexPolytope::edge(move));
    } else if (cur.dim == FeatureDim::edge) {
      const Index h = 2 * cur.index;
      const Index ia = m.origin(h), ib = m.target(h);
      const Index f1 = m.facet(h), f2 = m.facet(ConvexPolytope::twin(h));
      if (dot_sign(rv(ia), rs, rv(ia), rv(ib)) <= 0) {
        cur = Feature::vertex(ia);
      } else if (dot_sign(rv(ib), rs, rv(ib), rv(ia)) <= 0) {
        cur = Feature::vertex(ib);
      } else if (edge_normal_side(rv(ia), rv(ib), rn(f1), rs) < 0) {
        cur = Feature::facet(f1);
      } else if (edge_normal_side(rv(ib), rv(ia), rn(f2), rs) < 0) {
        cur = Feature::facet(f2);
      } else {
        const Point3& a = m.point(ia);
        const Point3 e = m.point(ib) - a;
        const Point3 sa = s - a;
        dir = sa - (dot(sa, e) / dot(e, e)) * e;
        d2 = squared_norm(dir);
        facet = sees(f1) ? f1 : f2;
        ++stats_.certified;
        return cur;
      }
    } else {
      const Index f = cur.index;
      const Index h0 = m.facet_halfedge(f);
      Index h = h0, beyond = kNoIndex, on_first = kNoIndex, on_second = kNoIndex;
      double beyond_d2 = 0;
      do {
        const int side = edge_normal_side(rv(m.origin(h)), rv(m.target(h)), rn(f), rs);
        if (side > 0) {
          // Choose the edge nearest to s (in doubles; any edge s lies beyond
          // is a valid move).
          const Vec3d& a = m.approx(m.origin(h));
          const Vec3d& b = m.approx(m.target(h));
          const double ex = b.x - a.x, ey = b.y - a.y, ez = b.z - a.z;
          const double px = sd.x - a.x, py = sd.y - a.y, pz = sd.z - a.z;
          const double ee = ex * ex + ey * ey + ez * ez;
          double t = ee > 0 ? (px * ex + py * ey + pz * ez) / ee : 0;
          t = t < 0 ? 0 : t > 1 ? 1 : t;
          const double dx = px - t * ex, dy = py - t * ey, dz = pz - t * ez;
          const double dd = dx * dx + dy * dy + dz * dz;
          if (beyond == kNoIndex || dd < beyond_d2) beyond = h, beyond_d2 = dd;
        } else if (side == 0) {
          (on_first == kNoIndex ? on_first : on_second) = h;
        }
        h = m.next(h);
      } while (h != h0);
      if (beyond != kNoIndex) {
        cur = Feature::edge(ConvexPolytope::edge(beyond));
      } else {
        if (!sees(f)) {  // local trap: restart once from the stabbed facet (s sees it), then scan
          if (restarted) break;
          restarted = true;
          cur = Feature::facet(stabbed);
          ++stats_.walk_steps;
          continue;
        }
        const Rational side = dot(normal_[f], s) - offset_[f];
        const Rational t = side / norm2_[f];
        dir = t * normal_[f];
        d2 = t * side;
        facet = f;
        ++stats_.certified;
        if (on_second != kNoIndex)  // x on two edges of f: their common vertex
          return Feature::vertex(m.next(on_first) == on_second ? m.origin(on_second) : m.origin(on_first));
        if (on_first != kNoIndex) return Feature::edge(ConvexPolytope::edge(on_first));
        return cur;
      }
    }
    ++stats_.walk_steps;
  }
  ++stats_.full_scans;
  Point3 x;
  const Feature scanned = closest_feature_scan(s, x, d2, facet);
  dir = s - x;
  return scanned.dim == FeatureDim::facet ? feature_on_facet(facet, x) : scanned;
}

DistanceResult TranslationalObstacle::distance_point(const Point3& s) {
  DistanceResult r;
  distance_into(s, r);
  return r;
}

// The distance query written into r (its rationals assigned, not rebuilt).
void TranslationalObstacle::distance_into(const Point3& s, DistanceResult& r) {
  CollisionResult c = collide_point(s);
  r.status = c.status;
  r.distance = 0;
  r.squared_distance = 0;
  if (c.status != ContactStatus::separate) {
    r.witness = c.witness;
    Point3 p, q;
    if (c.status == ContactStatus::touching) {
      std::tie(p, q) = split(c.witness, s);
    } else {
      // s = (1 − λ) c + λ y with y the exit point of the ray from c through s.
      const Index f = c.witness.facet;
      const Point3 dir = s - center_;
      const Rational along = dot(normal_[f], dir);
      if (sgn(along) <= 0) {  // s == center_
        p = p_center_, q = q_center_;
      } else {
        const Rational mu = (offset_[f] - dot(normal_[f], center_)) / along;  // >= 1
        const Point3 y = center_ + mu * dir;
        auto [py, qy] = split(c.witness, y);  // y lies in the stabbed facet f = c.witness.m
        const Rational lambda = 1 / mu;
        p = (1 - lambda) * p_center_ + lambda * py;
        q = (1 - lambda) * q_center_ + lambda * qy;
      }
    }
    r.point_p = p;
    r.point_q = q + s;
    r.direction.x = 0, r.direction.y = 0, r.direction.z = 0;
    return;
  }
  Index facet = c.witness.facet;
  const Feature feat = closest_feature(s, last_closest_, r.direction, r.squared_distance, facet);
  r.distance = std::sqrt(to_double(r.squared_distance));
  r.witness = Witness{};
  r.witness.facet = facet;
  r.witness.m = feat;
  last_closest_ = r.witness.m;
  fill_operand_features(r.witness);
  auto [p, q] = split(r.witness, s - r.direction);
  r.point_p = std::move(p);
  r.point_q = q + s;
}

// x = p − q with p in the face w.p of P and q in the face w.q of Q, for a
// point x of the face w.m = w.p ⊕ (−w.q) of M (or of any face of M whose
// faces of P and Q are w.p and w.q).  When one of them is a vertex the other
// point is x translated by it; for two non-parallel edges p0 + α·u and
// q0 + β·v (the generic facet of M), x − (p0 − q0) = α·u − β·v and Cramer's
// rule on the normal equations gives
//   α = (⟨u,v⟩⟨w,v⟩ − ⟨v,v⟩⟨w,u⟩) / (⟨u,v⟩² − ⟨u,u⟩⟨v,v⟩),  w = x − p0 + q0;
// otherwise x's barycentric coordinates in w.m (decompose).
std::pair<Point3, Point3> TranslationalObstacle::split(const Witness& w, const Point3& x) const {
  if (w.q.dim == FeatureDim::vertex) {
    const Point3& q = q_.point(w.q.index);
    return {x + q, q};
  }
  if (w.p.dim == FeatureDim::vertex) {
    const Point3& p = p_.point(w.p.index);
    return {p, p - x};
  }
  if (w.p.dim == FeatureDim::edge && w.q.dim == FeatureDim::edge) {
    const Index hp = 2 * w.p.index, hq = 2 * w.q.index;
    const Point3& p0 = p_.point(p_.origin(hp));
    const Point3& q0 = q_.point(q_.origin(hq));
    const Point3 u = p_.point(p_.target(hp)) - p0, v = q_.point(q_.target(hq)) - q0;
    const Rational uv = dot(u, v);
    const Rational det = uv * uv - dot(u, u) * dot(v, v);  // −|u × v|²
    if (sgn(det) != 0) {
      const Point3 wv = x - p0 + q0;
      const Point3 p = p0 + ((uv * dot(wv, v) - dot(v, v) * dot(wv, u)) / det) * u;
      return {p, p - x};
    }
  }
  return decompose(w.m, x);
}

void TranslationalObstacle::collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = collide_point(s[i]);
}

void TranslationalObstacle::distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) distance_into(s[i], out[i]);
}

void TranslationalObstacle::penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = penetration_depth_point(s[i]);
}

DistanceResult TranslationalObstacle::distance(const Point3& u, const Point3& w) {
  DistanceResult r = distance_point(w - u);
  r.point_p = r.point_p + u;
  r.point_q = r.point_q + u;
  return r;
}

// ---------------------------------------------------------------------------
// Penetration depth.

DepthResult TranslationalObstacle::penetration_depth_point(const Point3& s) {
  CollisionResult c = collide_point(s);
  DepthResult r;
  r.status = c.status;
  r.squared_depth = 0;
  r.direction = Point3(Rational(0), Rational(0), Rational(0));
  r.witness = c.witness;
  if (c.status != ContactStatus::penetrating) return r;
  const ConvexPolytope& m = sum_.polytope;
  const Index nf = m.num_facets();
  // The facet nearest to s, the first on ties (kernel: nearest_plane on unit
  // planes, a filter with a derived bound, then exact comparisons among the
  // facets it cannot rule out).
  const Vec3d sd = to_double(s);
  const Index arg = Index(nearest_plane(plane_ptr_.data(), unit_plane_.data(), nf, RoundedPoint3{s, sd}));
  const Rational arg_gap = offset_[arg] - dot(normal_[arg], s);  // d − n·s (> 0 for s inside)
  last_depth_ = arg;
  const Rational t = arg_gap / norm2_[arg];  // s + t n lies on the facet plane
  r.squared_depth = t * arg_gap;
  r.depth = std::sqrt(to_double(r.squared_depth));
  const Point3 move = t * normal_[arg];
  r.direction = -move;
  const Point3 x = s + move;
  r.witness.facet = arg;
  r.witness.m = feature_on_facet(arg, x);
  fill_operand_features(r.witness);
  return r;
}

DepthResult TranslationalObstacle::penetration_depth(const Point3& u, const Point3& w) {
  return penetration_depth_point(w - u);
}

// ---------------------------------------------------------------------------
// Directional penetration depth.

DirectionalDepthResult TranslationalObstacle::directional_depth_point(const Point3& s, const Point3& d) {
  if (is_zero(d)) throw UsageError("the direction of a directional penetration depth must not be zero");
  CollisionResult c = collide_point(s);
  DirectionalDepthResult r;
  r.status = c.status;
  r.t = 0;
  r.translation = Point3(Rational(0), Rational(0), Rational(0));
  r.witness = c.witness;
  if (c.status != ContactStatus::penetrating) return r;
  // s is strictly inside M: shoot the ray s − α d, α >= 0, from s itself.
  const Index f = stab(s, s - d, last_exit_);
  last_exit_ = f;
  const Rational along = -dot(normal_[f], d);  // > 0: the ray leaves through f
  r.t = (offset_[f] - dot(normal_[f], s)) / along;
  r.translation = r.t * d;
  r.depth = std::sqrt(to_double(r.t * r.t * dot(d, d)));
  const Point3 y = s - r.translation;
  r.witness.facet = f;
  r.witness.m = feature_on_facet(f, y);
  fill_operand_features(r.witness);
  return r;
}

DirectionalDepthResult TranslationalObstacle::directional_depth(const Point3& u, const Point3& w, const Point3& d) {
  return directional_depth_point(w - u, d);
}

}  // namespace minksum
