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
#include <atomic>
#include <cfloat>
#include <cmath>
#include <unordered_map>

#include "kernel/plane.hpp"
#include "kernel/predicates_internal.hpp"
#include "mesh/support.hpp"
#include "proximity/obstacle_geometry.hpp"
#include "proximity/obstacle_state.hpp"

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

detail::ObstacleState::ObstacleState(ConvexPolytope p, ConvexPolytope q, Method method) : method_(method) {
  rebuild(std::move(p), std::move(q));
}
detail::ObstacleState::ObstacleState(ConvexPolytope p, ConvexPolytope q, Method method,
                             const SumOptions& options)
    : method_(method) {
  rebuild(std::move(p), std::move(q), options);
}

// The operand kept by a rebuild: moved out of the current geometry when no
// answer shares it, copied otherwise.
void detail::ObstacleState::set_p(ConvexPolytope p) {
  rebuild(std::move(p), g_.use_count() == 1 ? std::move(g_->q) : g_->q);
}
void detail::ObstacleState::set_q(ConvexPolytope q) {
  rebuild(g_.use_count() == 1 ? std::move(g_->p) : g_->p, std::move(q));
}
void detail::ObstacleState::set_operands(ConvexPolytope p, ConvexPolytope q) { rebuild(std::move(p), std::move(q)); }

const ConvexPolytope& detail::ObstacleState::p() const { return g_->p; }
const ConvexPolytope& detail::ObstacleState::q() const { return g_->q; }
const ConvexPolytope& detail::ObstacleState::obstacle() const { return g_->sum.polytope; }
const SumResult& detail::ObstacleState::sum() const { return g_->sum; }
const Point3& detail::ObstacleState::interior_point() const { return g_->center; }

void detail::ObstacleState::rebuild(ConvexPolytope p, ConvexPolytope q, const SumOptions& options) {
  // A new geometry: the answers given so far keep the one they were answered on.
  auto g = std::make_shared<detail::ObstacleGeometry>();
  g->p = std::move(p);
  g->q = std::move(q);
  g->neg_q = g->q.negated();
  std::unordered_map<Point3, Index, Point3Hash> q_index;
  for (Index v = 0; v < g->q.num_vertices(); ++v) q_index.emplace(g->q.point(v), v);
  g->neg_to_q.assign(g->neg_q.num_vertices(), kNoIndex);
  for (Index v = 0; v < g->neg_q.num_vertices(); ++v) g->neg_to_q[v] = q_index.at(-g->neg_q.point(v));
  g->sum = minkowski_sum(g->p, g->neg_q, method_, options);
  const ConvexPolytope& m = g->sum.polytope;
  const Index nf = m.num_facets();
  g->normal.resize(nf);
  g->offset.resize(nf);
  g->norm2.resize(nf);
  plane_approx_.resize(nf);
  normal_approx_.resize(nf);
  unit_plane_.resize(nf);
  plane_ptr_.resize(nf);
  for (Index f = 0; f < nf; ++f) {
    // M's planes, with their unit planes, cost more than the sum itself on
    // large operands: progress and cancellation here too.
    if ((f & 1023) == 0) options.report("planes", double(f) / double(nf));
    const Plane& pl = m.plane(f);
    g->normal[f] = pl.normal();
    g->offset[f] = Rational(pl.d);
    g->norm2[f] = squared_norm(g->normal[f]);
    plane_approx_[f] = {to_double(Rational(pl.a)), to_double(Rational(pl.b)), to_double(Rational(pl.c)),
                        to_double(g->offset[f])};
    normal_approx_[f] = Vec3d{plane_approx_[f][0], plane_approx_[f][1], plane_approx_[f][2]};
    unit_plane_[f] = unit_plane(pl);
    plane_ptr_[f] = &pl;
  }
  // avg(P) − avg(Q) is strictly inside M and has the obvious decomposition.
  g->p_center = average(g->p.points());
  g->q_center = average(g->q.points());
  g->center = g->p_center - g->q_center;
  options.report("planes", 1.0);
  g->prepare_exact();
  center_approx_ = to_double(g->center);
  facet_features_.assign(nf, {});
  facet_features_known_.assign(nf, 0);
  edge_features_.assign(m.num_edges(), {});
  edge_features_known_.assign(m.num_edges(), 0);
  center_plane_.assign(2 * std::size_t(m.num_edges()), Plane{});
  center_plane_approx_.resize(2 * std::size_t(m.num_edges()));
  center_plane_known_.assign(2 * std::size_t(m.num_edges()), 0);
  last_stab_ = last_exit_ = last_depth_ = 0;
  last_closest_.reset();  // the first distance walk starts at the stabbed facet
  last_separate_ = false;
  g_ = std::move(g);
  ++stats_.rebuilds;
}

// ---------------------------------------------------------------------------
// Witness helpers.

Feature detail::ObstacleState::feature_on_facet(Index f, const Point3& x) const {
  const ConvexPolytope& m = obstacle();
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
  const RoundedPoint3 rx{x, xd}, rn{g_->normal[f], normal_approx_[f]};
  h = h0;
  do {
    const Index a = m.origin(h), b = m.target(h);
    if (edge_normal_side(RoundedPoint3{m.point(a), m.approx(a)}, RoundedPoint3{m.point(b), m.approx(b)}, rn, rx) == 0)
      return Feature::edge(ConvexPolytope::edge(h));
    h = m.next(h);
  } while (h != h0);
  return Feature::facet(f);
}

// The foot x = s + t·n of s on facet f's plane lies in the facet (the
// nearest plane of a point inside M, or a facet that certified a distance).
// ⟨x − a, (b − a) × n⟩ = ⟨s − a, (b − a) × n⟩ since n ⟂ (b − a) × n, so x
// lies on the edge a→b exactly when edge_normal_side(a, b, n, s) = 0: the
// face is read off s itself, with no rational point formed.  Two such edges
// meet at x's vertex.
Feature detail::ObstacleState::foot_feature(Index f, const Point3& s, const Vec3d& sd) const {
  const ConvexPolytope& m = obstacle();
  const RoundedPoint3 rs{s, sd}, rn{g_->normal[f], normal_approx_[f]};
  const Index h0 = m.facet_halfedge(f);
  Index h = h0, on_first = kNoIndex, on_second = kNoIndex;
  do {
    const Index a = m.origin(h), b = m.target(h);
    if (edge_normal_side(RoundedPoint3{m.point(a), m.approx(a)}, RoundedPoint3{m.point(b), m.approx(b)}, rn, rs) == 0)
      (on_first == kNoIndex ? on_first : on_second) = h;
    h = m.next(h);
  } while (h != h0);
  if (on_second != kNoIndex)  // x on two edges of f: their common vertex
    return Feature::vertex(m.next(on_first) == on_second ? m.origin(on_second) : m.origin(on_first));
  if (on_first != kNoIndex) return Feature::edge(ConvexPolytope::edge(on_first));
  return Feature::facet(f);
}

void detail::ObstacleState::fill_operand_features(Witness& w) const {
  const detail::ObstacleGeometry& g = *g_;
  if (w.m.dim == FeatureDim::vertex) {  // a vertex of M is a vertex of P plus a vertex of −Q
    w.p = Feature::vertex(g.sum.vertex_origin[w.m.index].first);
    w.q = Feature::vertex(g.neg_to_q[g.sum.vertex_origin[w.m.index].second]);
    return;
  }
  auto& cache = w.m.dim == FeatureDim::facet ? facet_features_ : edge_features_;
  auto& known = w.m.dim == FeatureDim::facet ? facet_features_known_ : edge_features_known_;
  if (known[w.m.index]) {
    w.p = cache[w.m.index][0];
    w.q = cache[w.m.index][1];
    return;
  }
  std::vector<Index> pv, qv;
  for (Index v : feature_vertices(g.m(), w.m)) {
    pv.push_back(g.sum.vertex_origin[v].first);
    qv.push_back(g.neg_to_q[g.sum.vertex_origin[v].second]);
  }
  std::sort(pv.begin(), pv.end());
  pv.erase(std::unique(pv.begin(), pv.end()), pv.end());
  std::sort(qv.begin(), qv.end());
  qv.erase(std::unique(qv.begin(), qv.end()), qv.end());
  w.p = feature_of_vertices(g.p, pv);
  w.q = feature_of_vertices(g.q, qv);
  cache[w.m.index] = {w.p, w.q};
  known[w.m.index] = 1;
}

std::pair<Point3, Point3> detail::ObstacleState::decompose(const Feature& feat, const Point3& x) const {
  return g_->decompose(feat, x);
}

// ---------------------------------------------------------------------------
// Ray stabbing.

struct detail::ObstacleState::RayApprox {
  Vec3d apex, through;
  bool through_usable = false;  // detail::rounded_usable of the ray point's rounding
};

// orient3d(apex, m[a], m[b], through) on the cached roundings of M's
// vertices, the apex and the ray point (kernel: orient3d on RoundedPoint3).
int detail::ObstacleState::orient_filtered(const Point3& apex, Index a, Index b, const Point3& through,
                                           const RayApprox& ra) const {
  const ConvexPolytope& m = obstacle();
  return orient3d(RoundedPoint3{apex, ra.apex}, RoundedPoint3{m.point(a), m.approx(a)},
                  RoundedPoint3{m.point(b), m.approx(b)}, RoundedPoint3{through, ra.through});
}

// The side of s with respect to facet f's plane, filtered on the plane's
// cached roundings (kernel: plane_side).
int detail::ObstacleState::side_filtered(Index f, const Point3& s, const Vec3d& sd) const {
  return plane_side(obstacle().plane(f), plane_approx_[f], RoundedPoint3{s, sd});
}

bool detail::ObstacleState::in_cone(Index f, const Point3& apex, const Point3& through, const RayApprox& ra,
                                    Index* exit) {
  const ConvexPolytope& m = obstacle();
  Index h0 = m.facet_halfedge(f);
  rng_ ^= rng_ << 13, rng_ ^= rng_ >> 7, rng_ ^= rng_ << 17;
  for (std::uint64_t k = rng_ % 4; k > 0; --k) h0 = m.next(h0);
  Index h = h0;
  const bool from_center = &apex == &g_->center;
  do {
    const int side = from_center ? center_side(h, through, ra.through, ra.through_usable)
                                 : orient_filtered(apex, m.origin(h), m.target(h), through, ra);
    if (side < 0) {
      *exit = h;
      return false;
    }
    h = m.next(h);
  } while (h != h0);
  return true;
}

// orient3d(c, a, b, s) for the interior point c and the halfedge a→b is the
// side of s of the plane through c, a and b with normal (a − c) × (b − c)
// (non-zero: the line of a boundary edge of M misses its interior).  That
// plane is computed exactly on the halfedge's first use (canonical integers
// and their roundings) and kept; then each test is the plane_side filter, a
// degree-1 polynomial in s, instead of orient3d's degree 3.
int detail::ObstacleState::center_side(Index h, const Point3& s, const Vec3d& sd, bool usable) {
  if (!center_plane_known_[h]) {
    const ConvexPolytope& m = obstacle();
    const Point3& c = g_->center;
    const Point3 ca = m.point(m.origin(h)) - c;
    center_plane_[h] = canonical_plane(cross(ca, m.point(m.target(h)) - c), c);
    const Plane& pl = center_plane_[h];
    center_plane_approx_[h] = {to_double(Rational(pl.a)), to_double(Rational(pl.b)), to_double(Rational(pl.c)),
                               to_double(Rational(pl.d))};
    const auto& r = center_plane_approx_[h];
    const bool finite = std::fabs(r[0]) <= DBL_MAX && std::fabs(r[1]) <= DBL_MAX && std::fabs(r[2]) <= DBL_MAX &&
                        std::fabs(r[3]) <= DBL_MAX;
    center_plane_known_[h] = finite ? 1 : 2;
  }
  // plane_side's filter with the inputs checked once (the plane here, s per
  // query), then plane_side itself when it does not decide.
  if (usable && center_plane_known_[h] == 1)
    if (const int side = detail::plane_side_sign_usable(center_plane_approx_[h], sd); side != 2) return side;
  return plane_side(center_plane_[h], center_plane_approx_[h], RoundedPoint3{s, sd});
}

Index detail::ObstacleState::stab_scan(const Point3& apex, const Point3& through) const {
  const ConvexPolytope& m = obstacle();
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

Index detail::ObstacleState::stab(const Point3& apex, const Point3& through, const RayApprox& ra, Index start) {
  const ConvexPolytope& m = obstacle();
  Index f = start < m.num_facets() ? start : 0;
  const std::uint64_t limit = std::uint64_t(m.num_facets()) + 16;
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

CollisionResult detail::ObstacleState::collide_point(const Point3& s) { return collide_rounded(s, to_double(s)); }

CollisionResult detail::ObstacleState::collide_rounded(const Point3& s, const Vec3d& sd) {
  ++stats_.queries;
  CollisionResult r;
  const ConvexPolytope& m = obstacle();
  const Point3& center = g_->center;
  if (sd.x == center_approx_.x && sd.y == center_approx_.y && sd.z == center_approx_.z && s == center) {
    r.status = ContactStatus::penetrating;
    r.witness.facet = last_stab_ < m.num_facets() ? last_stab_ : 0;
    r.witness.m = Feature::facet(r.witness.facet);
    fill_operand_features(r.witness);
    return r;
  }
  const Index f = stab(center, s, RayApprox{center_approx_, sd, detail::rounded_usable(RoundedPoint3{s, sd})}, last_stab_);
  last_stab_ = f;
  const int side = side_filtered(f, s, sd);
  r.status = side > 0 ? ContactStatus::separate : side == 0 ? ContactStatus::touching : ContactStatus::penetrating;
  r.witness.facet = f;
  r.witness.m = side == 0 ? feature_on_facet(f, s) : Feature::facet(f);
  fill_operand_features(r.witness);
  return r;
}

CollisionResult detail::ObstacleState::collide(const Point3& u, const Point3& w) { return collide_point(w - u); }

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

Rational detail::ObstacleState::squared_distance_by_scan(const Point3& s) const {
  const ConvexPolytope& m = obstacle();
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

Feature detail::ObstacleState::closest_feature_scan(const Point3& s, Point3& x, Rational& d2, Index& facet) const {
  const ConvexPolytope& m = obstacle();
  bool found = false;
  Feature best = Feature::facet(0);
  for (Index f = 0; f < m.num_facets(); ++f) {
    if (m.plane(f).side(s) <= 0) continue;  // the closest point lies on a facet s sees
    const Point3& n = g_->normal[f];
    Closest c;
    if (!beyond_an_edge(m, f, n, s)) {
      const Rational t = (dot(n, s) - g_->offset[f]) / g_->norm2[f];
      c.x = s - t * n;
      c.d2 = t * t * g_->norm2[f];
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
Feature detail::ObstacleState::closest_feature(const Point3& s, const Vec3d& sd, std::optional<Feature> start,
                                              Index& facet, bool first) {
  const ConvexPolytope& m = obstacle();
  // The walk before the collision query is short: a pose that moved far
  // (or into M) goes the usual way.
  const std::uint64_t limit =
      first ? 16 : 2 * (std::uint64_t(m.num_vertices()) + m.num_edges() + m.num_facets()) + 16;
  auto valid = [&](const Feature& f) {
    switch (f.dim) {
      case FeatureDim::vertex: return f.index < m.num_vertices();
      case FeatureDim::edge: return f.index < m.num_edges();
      case FeatureDim::facet: return f.index < m.num_facets();
    }
    return false;
  };
  const RoundedPoint3 rs{s, sd};
  auto rv = [&](Index v) { return RoundedPoint3{m.point(v), m.approx(v)}; };
  auto rn = [&](Index f) { return RoundedPoint3{g_->normal[f], normal_approx_[f]}; };
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
        h = h0;
        facet = kNoIndex;
        do {  // a facet through v that s sees
          if (sees(m.facet(h))) {
            facet = m.facet(h);
            break;
          }
          h = m.next_around_vertex(h);
        } while (h != h0);
        if (facet == kNoIndex) {  // none: s = v
          if (first) return Feature::vertex(kNoIndex);
          facet = m.facet(h0);
        }
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
        facet = sees(f1) ? f1 : sees(f2) ? f2 : kNoIndex;
        if (facet == kNoIndex) {  // s on the edge
          if (first) return Feature::vertex(kNoIndex);
          facet = f2;
        }
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
          if (first) return Feature::vertex(kNoIndex);
          if (restarted) break;
          restarted = true;
          cur = Feature::facet(stabbed);
          ++stats_.walk_steps;
          continue;
        }
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
  if (first) return Feature::vertex(kNoIndex);
  ++stats_.full_scans;
  Point3 x;
  Rational d2;
  const Feature scanned = closest_feature_scan(s, x, d2, facet);
  return scanned.dim == FeatureDim::facet ? foot_feature(facet, s, sd) : scanned;
}

void detail::ObstacleState::keep_point(const Point3& s, const Vec3d& sd, Vec3d& kept, std::shared_ptr<Point3>& exact) {
  kept = sd;
  if (is_double(s)) {
    exact.reset();
  } else if (exact.use_count() == 1) {
    *exact = s;
  } else {
    exact = std::make_shared<Point3>(s);
  }
}

namespace {
// The obstacle's spare storage for exact values (a few sets), attached to a
// new answer: a caller that asks for the exact values of one answer at a
// time reuses the same integers, whose limbs are already allocated.  A set
// no answer holds any more is reused; when every set is held, a single query
// (`make`) adds one while there are fewer than spare.size(), else (a batch,
// or answers kept alive) the answer allocates its own on first use: answers
// whose exact values are never asked for allocate at most those few sets.
// use_count() is a relaxed read: the acquire fence orders it after the
// releasing decrement of the last other holder, so that holder's writes
// into the storage happen before this answer's.
template <class E, std::size_t N>
void attach_spare(std::array<std::shared_ptr<E>, N>& spare, std::shared_ptr<E>& out, bool make) {
  std::shared_ptr<E>* empty = nullptr;
  for (std::shared_ptr<E>& e : spare) {
    if (!e) {
      if (!empty) empty = &e;
    } else if (e.use_count() == 1) {
      std::atomic_thread_fence(std::memory_order_acquire);
      e->reset();
      out = e;
      return;
    }
  }
  if (make && empty) {
    *empty = std::make_shared<E>();
    out = *empty;
  }
}
}  // namespace

DistanceResult detail::ObstacleState::distance_point(const Point3& s) {
  DistanceResult r;
  distance_into(s, r, true);
  return r;
}

// The distance query written into r: its status and witness, and what its
// accessors need to compute the exact values (the geometry and s, assigned
// into r's storage; no rational arithmetic).
void detail::ObstacleState::distance_into(const Point3& s, DistanceResult& r, bool single) {
  const Vec3d sd = to_double(s);
  if (r.geo_ != g_) r.geo_ = g_;
  keep_point(s, sd, r.sd_, r.s_exact_);
  if (r.exact_.use_count() == 1) {  // a result of an earlier batch: keep its storage
    r.exact_->reset();
  } else {
    r.exact_.reset();
    attach_spare(spare_distance_, r.exact_, single);
  }
  Index facet = kNoIndex;
  Feature feat = Feature::vertex(kNoIndex);
  if (last_closest_ && last_separate_) {
    // Coherence: the walk from the previous closest feature first.  A
    // certificate whose closest point differs from s proves s outside M
    // (the point of M nearest to a point of M is that point), so the
    // collision query is not needed; otherwise (s in M, or a trap of the
    // descent) the query below decides as from scratch.
    ++stats_.queries;
    feat = closest_feature(s, sd, last_closest_, facet, true);
    if (feat.index != kNoIndex) r.status = ContactStatus::separate;
    else --stats_.queries;
  }
  if (feat.index == kNoIndex) {
    CollisionResult c = collide_rounded(s, sd);
    r.status = c.status;
    if (c.status != ContactStatus::separate) {
      r.witness = c.witness;
      last_separate_ = false;
      return;
    }
    facet = c.witness.facet;
    feat = closest_feature(s, sd, last_closest_, facet, false);
  }
  r.witness = Witness{};
  r.witness.facet = facet;
  r.witness.m = feat;
  last_closest_ = feat;
  last_separate_ = true;
  fill_operand_features(r.witness);
}

void detail::ObstacleState::collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = collide_point(s[i]);
}

void detail::ObstacleState::distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) distance_into(s[i], out[i], false);
}

void detail::ObstacleState::penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out) {
  out.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) depth_into(s[i], out[i], false);
}

DistanceResult detail::ObstacleState::distance(const Point3& u, const Point3& w) {
  DistanceResult r = distance_point(w - u);
  detail::DistanceExact& e = r.exact();
  e.u = u;
  e.translated = true;
  return r;
}

// ---------------------------------------------------------------------------
// Penetration depth.

DepthResult detail::ObstacleState::penetration_depth_point(const Point3& s) {
  DepthResult r;
  depth_into(s, r, true);
  return r;
}

void detail::ObstacleState::depth_into(const Point3& s, DepthResult& r, bool single) {
  const Vec3d sd = to_double(s);
  CollisionResult c = collide_rounded(s, sd);
  r.status = c.status;
  r.witness = c.witness;
  if (r.exact_.use_count() == 1) r.exact_->reset();  // keep an earlier batch's storage
  else r.exact_.reset();
  if (c.status != ContactStatus::penetrating) {  // the exact values are zeros: neither M nor s is needed
    r.geo_.reset();
    return;
  }
  if (!r.exact_) attach_spare(spare_depth_, r.exact_, single);
  if (r.geo_ != g_) r.geo_ = g_;
  keep_point(s, sd, r.sd_, r.s_exact_);
  // The facet nearest to s, the first on ties (kernel: nearest_plane on unit
  // planes, a filter with a derived bound, then exact comparisons among the
  // facets it cannot rule out).  The foot x of s on its plane lies in the
  // relative interior of the facet: were x on its boundary, x would lie on
  // the plane of a neighbouring facet g too, and s − x, parallel to this
  // facet's normal, not to g's, would make s strictly nearer to g's plane.
  // So the witness face is the facet itself.  The exact values are the
  // result's, on demand.
  const Index nf = obstacle().num_facets();
  const Index arg = Index(nearest_plane(plane_ptr_.data(), unit_plane_.data(), nf, RoundedPoint3{s, sd}));
  last_depth_ = arg;
  r.witness.facet = arg;
  r.witness.m = Feature::facet(arg);
  fill_operand_features(r.witness);
}

DepthResult detail::ObstacleState::penetration_depth(const Point3& u, const Point3& w) {
  return penetration_depth_point(w - u);
}

// ---------------------------------------------------------------------------
// Directional penetration depth.

DirectionalDepthResult detail::ObstacleState::directional_depth_point(const Point3& s, const Point3& d) {
  if (is_zero(d)) throw UsageError("the direction of a directional penetration depth must not be zero");
  CollisionResult c = collide_point(s);
  DirectionalDepthResult r;
  r.status = c.status;
  r.t = 0;
  r.translation = Point3(Rational(0), Rational(0), Rational(0));
  r.witness = c.witness;
  if (c.status != ContactStatus::penetrating) return r;
  // s is strictly inside M: shoot the ray s − α d, α >= 0, from s itself.
  const Point3 through = s - d;
  const Index f = stab(s, through, RayApprox{to_double(s), to_double(through)}, last_exit_);
  last_exit_ = f;
  const Rational along = -dot(g_->normal[f], d);  // > 0: the ray leaves through f
  r.t = (g_->offset[f] - dot(g_->normal[f], s)) / along;
  r.translation = r.t * d;
  r.depth = std::sqrt(to_double(r.t * r.t * dot(d, d)));
  const Point3 y = s - r.translation;
  r.witness.facet = f;
  r.witness.m = feature_on_facet(f, y);
  fill_operand_features(r.witness);
  return r;
}

DirectionalDepthResult detail::ObstacleState::directional_depth(const Point3& u, const Point3& w, const Point3& d) {
  return directional_depth_point(w - u, d);
}

// The obstacle: its state, and every query forwarded to it.
TranslationalObstacle::TranslationalObstacle(ConvexPolytope p, ConvexPolytope q, Method method)
    : s_(std::make_unique<detail::ObstacleState>(std::move(p), std::move(q), method)) {}
TranslationalObstacle::TranslationalObstacle(ConvexPolytope p, ConvexPolytope q, Method method,
                                             const SumOptions& options)
    : s_(std::make_unique<detail::ObstacleState>(std::move(p), std::move(q), method, options)) {}
TranslationalObstacle::TranslationalObstacle(const TranslationalObstacle& o)
    : s_(std::make_unique<detail::ObstacleState>(*o.s_)) {}
TranslationalObstacle::TranslationalObstacle(TranslationalObstacle&&) noexcept = default;
TranslationalObstacle& TranslationalObstacle::operator=(const TranslationalObstacle& o) {
  if (this != &o) s_ = std::make_unique<detail::ObstacleState>(*o.s_);
  return *this;
}
TranslationalObstacle& TranslationalObstacle::operator=(TranslationalObstacle&&) noexcept = default;
TranslationalObstacle::~TranslationalObstacle() = default;

void TranslationalObstacle::set_p(ConvexPolytope p) { s_->set_p(std::move(p)); }
void TranslationalObstacle::set_q(ConvexPolytope q) { s_->set_q(std::move(q)); }
void TranslationalObstacle::set_operands(ConvexPolytope p, ConvexPolytope q) { s_->set_operands(std::move(p), std::move(q)); }
const ConvexPolytope& TranslationalObstacle::p() const { return s_->p(); }
const ConvexPolytope& TranslationalObstacle::q() const { return s_->q(); }
const ConvexPolytope& TranslationalObstacle::obstacle() const { return s_->obstacle(); }
const SumResult& TranslationalObstacle::sum() const { return s_->sum(); }
const Point3& TranslationalObstacle::interior_point() const { return s_->interior_point(); }
CollisionResult TranslationalObstacle::collide(const Point3& u, const Point3& w) { return s_->collide(u, w); }
DistanceResult TranslationalObstacle::distance(const Point3& u, const Point3& w) { return s_->distance(u, w); }
DepthResult TranslationalObstacle::penetration_depth(const Point3& u, const Point3& w) {
  return s_->penetration_depth(u, w);
}
DirectionalDepthResult TranslationalObstacle::directional_depth(const Point3& u, const Point3& w, const Point3& d) {
  return s_->directional_depth(u, w, d);
}
CollisionResult TranslationalObstacle::collide_point(const Point3& s) { return s_->collide_point(s); }
DistanceResult TranslationalObstacle::distance_point(const Point3& s) { return s_->distance_point(s); }
DepthResult TranslationalObstacle::penetration_depth_point(const Point3& s) { return s_->penetration_depth_point(s); }
DirectionalDepthResult TranslationalObstacle::directional_depth_point(const Point3& s, const Point3& d) {
  return s_->directional_depth_point(s, d);
}
void TranslationalObstacle::collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out) {
  s_->collide_points(s, out);
}
void TranslationalObstacle::distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out) {
  s_->distance_points(s, out);
}
void TranslationalObstacle::penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out) {
  s_->penetration_depth_points(s, out);
}
Rational TranslationalObstacle::squared_distance_by_scan(const Point3& s) const { return s_->squared_distance_by_scan(s); }
const ProximityStats& TranslationalObstacle::stats() const { return s_->stats(); }
void TranslationalObstacle::reset_stats() { s_->reset_stats(); }
Feature TranslationalObstacle::feature_on_facet(Index f, const Point3& x) const { return s_->feature_on_facet(f, x); }
void TranslationalObstacle::fill_operand_features(Witness& w) const { s_->fill_operand_features(w); }
std::pair<Point3, Point3> TranslationalObstacle::decompose(const Feature& m, const Point3& x) const {
  return s_->decompose(m, x);
}

}  // namespace minksum
