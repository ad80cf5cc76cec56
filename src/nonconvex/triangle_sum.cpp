// The pieces P ⊕ B of the boundary sweep (docs/nonconvex.md, "Pieces"):
// a convex polygon P of the swept surface (a triangle, or coplanar
// triangles merged: SurfaceCones::merge_coplanar) summed with a convex
// polytope B, built from the two Gaussian maps instead of by a hull or a
// walk.
//
// For a direction u, face_u(P ⊕ B) = face_u(P) + face_u(B), and it is a
// facet exactly when the two faces span a plane.  With the dimensions of
// the two faces:
//   A. face_u(B) a facet f (u = f's normal): the facet f + face_u(P), one per
//      facet of B;
//   B. face_u(P) = P (u = ±n_P) and face_u(B) a vertex or an edge: P plus it;
//   C. face_u(P) an edge e of P and face_u(B) an edge g of B, not parallel:
//      u = ±(e × g), and u must lie in the open normal arcs of both edges:
//      u · (o − a) < 0 for a corner o of P off e (a an end of e; P is
//      strictly convex, on one side of e's line) and
//      u · (w − g0) < 0 for the vertex w off g of each of g's two facets;
//      the facet is the parallelogram e ⊕ g.
// Every other pair of faces sums to a segment or a point.  The three kinds
// have different normals (A: facet normals of B; B: ±n_P, which are not
// facet normals of B there; C: inside open arcs of B's map and not ±n_P), so
// each facet is found once.  Every sign is a kernel predicate on the exact
// points (support_compare and dot_difference_sign, filtered on cached roundings).
// Every plane is lazy (LazyPlane): its doubles, and its exact canonical
// integer plane only for a candidate or when the union asks (build).
#include <minksum/error.hpp>
#include <minksum/parallel.hpp>
#include <minksum/dot_difference.hpp>
#include <minksum/predicates.hpp>

#include "kernel/plane.hpp"
#include "nonconvex/sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace minksum::nonconvex_detail {

SweptPolytope::SweptPolytope(const ConvexPolytope& b, const SurfaceCones* surface) : surface_(surface) {
  points_ = b.points();
  scaled_.reserve(points_.size());
  for (const Point3& p : points_) scaled_.push_back(scaled_point(p));
  approx_.reserve(points_.size());
  for (Index v = 0; v < b.num_vertices(); ++v) approx_.push_back(b.approx(v));
  lo_ = hi_ = points_.front();
  for (const Point3& p : points_)
    for (int k = 0; k < 3; ++k) {
      if (cmp(p[k], lo_[k]) < 0) lo_[k] = p[k];
      if (cmp(p[k], hi_[k]) > 0) hi_[k] = p[k];
    }
  facets_.resize(b.num_facets());
  std::vector<Vec3d> unit;
  for (Index f = 0; f < b.num_facets(); ++f) {
    const Plane& h = b.plane(f);
    Facet& x = facets_[f];
    x.normal = h.normal();
    x.normal_approx = to_double(x.normal);
    Integer g;
    mpz_gcd(g.get_mpz_t(), h.a.get_mpz_t(), h.b.get_mpz_t());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), h.c.get_mpz_t());
    x.primitive_integer[0] = h.a / g;
    x.primitive_integer[1] = h.b / g;
    x.primitive_integer[2] = h.c / g;
    // Their doubles, scaled and truncated towards zero as every lazy
    // plane's (lazy_plane_doubles: faithful, and the same for equal planes
    // of any kind).
    x.scale = lazy_plane_scale(x.primitive_integer);
    x.primitive_usable = true;
    for (int j = 0; j < 3; ++j)
      x.primitive_usable =
          scaled_filter_double(x.primitive_integer[j], x.scale, x.primitive_approx[j]) && x.primitive_usable;
    Rational offset(h.d, g);
    offset.canonicalize();
    x.offset_num = offset.get_num();
    x.offset_den = offset.get_den();
    x.loop = b.facet_vertices(f);
    const double len = std::sqrt(x.normal_approx.x * x.normal_approx.x + x.normal_approx.y * x.normal_approx.y +
                                 x.normal_approx.z * x.normal_approx.z);
    unit.push_back(Vec3d{x.normal_approx.x / len, x.normal_approx.y / len, x.normal_approx.z / len});
  }
  directions_ = DirectionIndex(std::move(unit));
  neighbours_.reserve(b.num_vertices());
  for (Index v = 0; v < b.num_vertices(); ++v) neighbours_.push_back(b.vertex_neighbours(v));
  edges_.reserve(b.num_edges());
  for (Index e = 0; e < b.num_edges(); ++e) {
    const Index h = 2 * e;
    Edge x;
    x.v0 = b.origin(h);
    x.v1 = b.target(h);
    // The next vertex of each facet's loop after the edge is off the edge.
    x.w0 = b.target(b.next(h));
    x.w1 = b.target(b.next(ConvexPolytope::twin(h)));
    x.f0 = b.facet(h);
    x.f1 = b.facet(ConvexPolytope::twin(h));
    scaled_difference(scaled_[x.v0], scaled_[x.v1], x.direction);
    edges_.push_back(std::move(x));
  }
  if (!surface_) return;
  for (Index t = 0; t < surface_->triangles(); ++t) {
    const auto& c = surface_->triangle(t);
    bool meets = true;
    for (int k = 0; k < 3 && meets; ++k) {
      bool below = false, above = false;  // some corner <= hi_, some >= lo_
      for (int j = 0; j < 3; ++j) {
        const Rational& x = surface_->point(c[j])[k];
        below = below || cmp(x, hi_[k]) <= 0;
        above = above || cmp(x, lo_[k]) >= 0;
      }
      meets = below && above;
    }
    if (meets) touching_.push_back(t);
  }
  facet_on_surface_.resize(facets_.size());
  for (std::size_t f = 0; f < facets_.size(); ++f)
    facet_on_surface_[f] = on_surface(facets_[f].loop.front(), RoundedPoint3{facets_[f].normal, facets_[f].normal_approx});
}

bool SweptPolytope::on_surface(Index x, const RoundedPoint3& u) const {
  if (!surface_) return true;
  const RoundedPoint3 base = at(x);
  for (Index t : touching_) {
    const auto& c = surface_->triangle(t);
    bool at_top[3], any = false, above = false;
    for (int k = 0; k < 3 && !above; ++k) {
      const int s = dot_difference_sign(u, base, surface_->rounded(c[k]));
      above = s > 0;
      at_top[k] = s == 0;
      any = any || at_top[k];
    }
    if (!above && any && surface_->candidate(t, u, at_top)) return true;
  }
  return false;
}

namespace {

// The convex hull of `pts` (points of one plane with outward normal u),
// counter-clockwise seen from outside, without collinear points: Andrew's
// monotone chain on two exact coordinates (those of the frame that drops
// the coordinate of u's largest component).
std::vector<Point3> plane_hull(std::vector<Point3> pts, const Point3& u) {
  int k = 2;
  for (int i = 0; i < 3; ++i)
    if (cmp(abs(u[i]), abs(u[k])) > 0) k = i;
  int iu = (k + 1) % 3, iv = (k + 2) % 3;
  if (sgn(u[k]) < 0) std::swap(iu, iv);
  std::sort(pts.begin(), pts.end(), [&](const Point3& a, const Point3& b) {
    if (int c = cmp(a[iu], b[iu])) return c < 0;
    return cmp(a[iv], b[iv]) < 0;
  });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  auto turn = [&](const Point3& a, const Point3& b, const Point3& c) {
    return sgn((b[iu] - a[iu]) * (c[iv] - a[iv]) - (b[iv] - a[iv]) * (c[iu] - a[iu]));
  };
  std::vector<Point3> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = hull.size();
    for (std::size_t j = 0; j < pts.size(); ++j) {
      const Point3& p = pass == 0 ? pts[j] : pts[pts.size() - 1 - j];
      while (hull.size() >= start + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();  // the last point starts the other chain
  }
  return hull;
}

// out = x × y.
void cross_integers(const Integer x[3], const Integer y[3], Integer out[3]) {
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3, l = (j + 2) % 3;
    mpz_mul(out[j].get_mpz_t(), x[k].get_mpz_t(), y[l].get_mpz_t());
    mpz_submul(out[j].get_mpz_t(), x[l].get_mpz_t(), y[k].get_mpz_t());
  }
}

// The plane with normal a positive multiple of n (not zero) through p + q:
// its primitive normal m = n / gcd(n) and its offset along m, num / den
// with den = p.den q.den and num = m . (p.num q.den + q.num p.den) (the
// fraction not reduced).
struct SumPlane {
  Integer m[3], num, den;
};

void sum_plane(const Integer n[3], const ScaledPoint& p, const ScaledPoint& q, SumPlane& out) {
  Integer& g = out.num;  // (scratch until the offset)
  mpz_gcd(g.get_mpz_t(), n[0].get_mpz_t(), n[1].get_mpz_t());
  mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), n[2].get_mpz_t());
  for (int j = 0; j < 3; ++j) {
    if (mpz_cmp_ui(g.get_mpz_t(), 1) != 0) mpz_divexact(out.m[j].get_mpz_t(), n[j].get_mpz_t(), g.get_mpz_t());
    else out.m[j] = n[j];
  }
  mpz_mul(out.den.get_mpz_t(), p.den.get_mpz_t(), q.den.get_mpz_t());
  mpz_set_ui(out.num.get_mpz_t(), 0);
  thread_local Integer t;
  for (const auto& [x, other] : {std::pair<const ScaledPoint*, const ScaledPoint*>{&p, &q}, {&q, &p}}) {
    mpz_mul(t.get_mpz_t(), out.m[0].get_mpz_t(), x->num[0].get_mpz_t());
    mpz_addmul(t.get_mpz_t(), out.m[1].get_mpz_t(), x->num[1].get_mpz_t());
    mpz_addmul(t.get_mpz_t(), out.m[2].get_mpz_t(), x->num[2].get_mpz_t());
    mpz_addmul(out.num.get_mpz_t(), t.get_mpz_t(), other->den.get_mpz_t());
  }
}

// The canonical plane of s: (m den, num) / gcd(den, num), whose
// coefficients have the gcd gcd(den gcd(m), num) = gcd(den, num) (m is
// primitive).  Changes s.
Plane canonical_plane(SumPlane& s) {
  thread_local Integer g;
  mpz_gcd(g.get_mpz_t(), s.den.get_mpz_t(), s.num.get_mpz_t());
  if (mpz_cmp_ui(g.get_mpz_t(), 1) != 0) {
    mpz_divexact(s.den.get_mpz_t(), s.den.get_mpz_t(), g.get_mpz_t());
    mpz_divexact(s.num.get_mpz_t(), s.num.get_mpz_t(), g.get_mpz_t());
  }
  Plane out;
  mpz_mul(out.a.get_mpz_t(), s.m[0].get_mpz_t(), s.den.get_mpz_t());
  mpz_mul(out.b.get_mpz_t(), s.m[1].get_mpz_t(), s.den.get_mpz_t());
  mpz_mul(out.c.get_mpz_t(), s.m[2].get_mpz_t(), s.den.get_mpz_t());
  mpz_swap(out.d.get_mpz_t(), s.num.get_mpz_t());
  return out;
}

// The canonical plane with normal a positive multiple of n (not zero)
// through p + q, as canonical_plane_through_sum gives it, with smaller
// gcds: n made primitive first (numbers the size of n), then one gcd of the
// offset's fraction instead of three with numbers the size of n M.
Plane plane_through_sum(const Integer n[3], const ScaledPoint& p, const ScaledPoint& q) {
  SumPlane s;
  sum_plane(n, p, q, s);
  return canonical_plane(s);
}

}  // namespace

namespace {

// The usable range of a lazy plane's offset in the union's half-space
// filter (<minksum/half_space_side.hpp>): zero with the exact value, or of
// magnitude in [2^-480, 2^480).
constexpr double kLazyFilterMin = 0x1p-480;
constexpr double kLazyFilterMax = 0x1p+480;

// The doubles of s as a lazy plane (the key B's facets moved have too).
void lazy_of(const SumPlane& s, LazyPlane& out) { lazy_plane_doubles(s.m, s.num, s.den, out); }

// The tags of the lazy planes of P ⊕ B (LazyPlane::tag; P a polygon of at
// most kMaxCorners = SurfaceCones::kMaxCorners corners), with their codes:
//   A. facet k of B (plane k) moved to corner `tag` (0 .. kMaxCorners − 1)
//      of P, the first one at its top;
//   B. kBFacet + side: P + vertex `code` of B, normal n_P (side 0) or −n_P
//      (side 1);
//   C. kCFacet + k + kMaxCorners (σ < 0): P's edge k (from corner k to
//      k + 1) ⊕ edge `code` of B, normal σ (b − a) × (g1 − g0).
constexpr std::size_t kMaxCorners = SurfaceCones::kMaxCorners;
constexpr std::uint8_t kBFacet = kMaxCorners, kCFacet = kMaxCorners + 2;
static_assert(kCFacet + 2 * kMaxCorners <= 256, "the tags fit in a byte");

}  // namespace

// work[0] / work[1] (work[1] > 0) = the offset of f moved to q = Q / D along
// f's primitive normal: (offset_num D + offset_den S) / (offset_den D), S =
// primitive · Q.
void SweptPolytope::offset_along(const Facet& f, const ScaledPoint& q, Integer work[3]) {
  const Integer* Q = q.num;
  mpz_mul(work[0].get_mpz_t(), f.primitive_integer[0].get_mpz_t(), Q[0].get_mpz_t());
  mpz_addmul(work[0].get_mpz_t(), f.primitive_integer[1].get_mpz_t(), Q[1].get_mpz_t());
  mpz_addmul(work[0].get_mpz_t(), f.primitive_integer[2].get_mpz_t(), Q[2].get_mpz_t());  // S
  mpz_mul(work[1].get_mpz_t(), f.offset_den.get_mpz_t(), q.den.get_mpz_t());  // den
  mpz_mul(work[0].get_mpz_t(), work[0].get_mpz_t(), f.offset_den.get_mpz_t());
  mpz_addmul(work[0].get_mpz_t(), f.offset_num.get_mpz_t(), q.den.get_mpz_t());  // num
}

// The canonical plane primitive · x = work[0] / work[1]: (primitive den,
// num) / gcd(num, den), primitive as the primitive normal's gcd is 1.
// Changes work.
Plane SweptPolytope::canonical_from_offset(const Facet& f, Integer work[3]) {
  Plane out;
  mpz_gcd(work[2].get_mpz_t(), work[0].get_mpz_t(), work[1].get_mpz_t());
  if (mpz_cmp_ui(work[2].get_mpz_t(), 1) != 0) {
    mpz_divexact(work[0].get_mpz_t(), work[0].get_mpz_t(), work[2].get_mpz_t());
    mpz_divexact(work[1].get_mpz_t(), work[1].get_mpz_t(), work[2].get_mpz_t());
  }
  mpz_mul(out.a.get_mpz_t(), f.primitive_integer[0].get_mpz_t(), work[1].get_mpz_t());
  mpz_mul(out.b.get_mpz_t(), f.primitive_integer[1].get_mpz_t(), work[1].get_mpz_t());
  mpz_mul(out.c.get_mpz_t(), f.primitive_integer[2].get_mpz_t(), work[1].get_mpz_t());
  mpz_swap(out.d.get_mpz_t(), work[0].get_mpz_t());
  return out;
}

// The doubles of the lazy plane primitive · x = work[0] / work[1]: the
// offset scaled by 2^-f.scale and rounded towards zero (lazy_plane_doubles),
// and whether the union's filter may use them.
void SweptPolytope::lazy_doubles(const Facet& f, const Integer work[3], double& d, bool& filtered) {
  if (f.scale == 0) {
    d = truncated_ratio(work[0], work[1]);
  } else {
    Integer scaled_den;
    mpz_mul_2exp(scaled_den.get_mpz_t(), work[1].get_mpz_t(), mp_bitcnt_t(f.scale));
    d = truncated_ratio(work[0], scaled_den);
  }
  filtered = f.primitive_usable && std::isfinite(d) && std::fabs(d) < kLazyFilterMax &&
             (d == 0 ? sgn(work[0]) == 0 : std::fabs(d) >= kLazyFilterMin);
}

void SweptPolytope::prepare(const SurfaceCones& cones, unsigned threads) {
  const std::size_t nv = cones.points(), nf = facets_.size();
  offset_d_.assign(nv * nf, 0.0);
  offset_ok_.assign(nv * nf, 0);
  parallel_for(nv, parallel_threads(threads, nv / 64 + 1), [&](std::size_t v) {
    const ScaledPoint& q = cones.scaled(Index(v));
    Integer work[3];
    for (std::size_t fi = 0; fi < nf; ++fi) {
      offset_along(facets_[fi], q, work);
      bool ok = false;
      lazy_doubles(facets_[fi], work, offset_d_[v * nf + fi], ok);
      offset_ok_[v * nf + fi] = ok ? 1 : 0;
    }
  });
  rise_.clear();
  const std::size_t ne = cones.edges();
  if (ne * nf <= (std::size_t(1) << 24)) {
    rise_.assign(ne * nf, 0);
    parallel_for(ne, parallel_threads(threads, ne / 64 + 1), [&](std::size_t e) {
      const auto& ends = cones.edge_ends(e);
      const RoundedPoint3 p = cones.rounded(ends[0]), q = cones.rounded(ends[1]);
      for (std::size_t fi = 0; fi < nf; ++fi)
        rise_[e * nf + fi] = static_cast<signed char>(
            dot_difference_sign(RoundedPoint3{facets_[fi].normal, facets_[fi].normal_approx}, p, q));
    });
  }
  below_.assign(nv * nf, -1);
  prepared_ = &cones;
}

void SweptPolytope::release() {
  prepared_ = nullptr;
  std::vector<double>().swap(offset_d_);
  std::vector<char>().swap(offset_ok_);
  std::vector<signed char>().swap(rise_);
  std::vector<signed char>().swap(below_);
}

Plane SweptPolytope::build(const Piece& piece, Index k) const {
  const LazyPlane& l = piece.lazy[k];
  Integer n[3];
  if (k < facets_.size()) {
    offset_along(facets_[k], *piece.scaled_corner[l.tag], n);
    return canonical_from_offset(facets_[k], n);
  }
  const std::vector<const ScaledPoint*>& s = piece.scaled_corner;
  const std::size_t m = s.size();
  if (l.tag < kCFacet) {
    Integer e1[3], e2[3];
    scaled_difference(*s[0], *s[1], e1);
    scaled_difference(*s[0], *s[2], e2);
    cross_integers(e1, e2, n);  // a positive multiple of n_P (P strictly convex, counter-clockwise)
    if (l.tag != kBFacet)
      for (Integer& x : n) mpz_neg(x.get_mpz_t(), x.get_mpz_t());
    return plane_through_sum(n, *s[0], scaled_[l.code]);
  }
  const std::size_t edge = (l.tag - kCFacet) % kMaxCorners;
  const Edge& g = edges_[l.code];
  Integer e[3];
  scaled_difference(*s[edge], *s[(edge + 1) % m], e);
  cross_integers(e, g.direction, n);
  if (l.tag >= kCFacet + kMaxCorners)
    for (Integer& x : n) mpz_neg(x.get_mpz_t(), x.get_mpz_t());
  return plane_through_sum(n, *s[edge], scaled_[g.v0]);
}

bool SweptPolytope::contains(const Piece& piece, Index k, std::uint64_t label) const {
  const Index m = Index(label >> 32), v = Index(label & 0xffffffffu);
  const LazyPlane& l = piece.lazy[k];
  const std::vector<Index>& id = piece.corner_id;
  if (k < facets_.size()) {  // f + p_top: holds p_top + b for every vertex b of f
    const std::vector<Index>& loop = facets_[k].loop;
    return m == id[l.tag] && std::find(loop.begin(), loop.end(), v) != loop.end();
  }
  if (l.tag < kCFacet)  // P + b_code (and more), normal ±n_P: holds every corner plus b_code
    return v == l.code && std::find(id.begin(), id.end(), m) != id.end();
  // e ⊕ g: holds both ends of P's edge plus both ends of g.
  const std::size_t e = (l.tag - kCFacet) % kMaxCorners;
  const Edge& g = edges_[l.code];
  return (v == g.v0 || v == g.v1) && (m == id[e] || m == id[(e + 1) % id.size()]);
}

// The vertices of B highest along sign · n_t (n_t the normal of
// p0 p1 p2, three corners of a polygon), ascending.  B is convex, so a vertex with no strictly higher
// neighbour is highest of all, and the highest vertices (a vertex, an edge
// or a facet of B) are connected by edges of B whose ends are equally high:
// climb from the vertex highest by the doubles (`na`, the nearest doubles of
// n_t; only a guess: the climb decides, by the exact support_compare), then
// gather the equally high neighbours.  The same set as comparing every
// vertex with the highest so far, in far fewer exact comparisons.
void SweptPolytope::extreme_face(const RoundedPoint3 p[3], const Vec3d& na, int sign, std::vector<Index>& face) const {
  Index v = 0;
  double best = -HUGE_VAL;
  for (Index w = 0; w < approx_.size(); ++w) {
    const double h = sign * (na.x * approx_[w].x + na.y * approx_[w].y + na.z * approx_[w].z);
    if (h > best) {
      best = h;
      v = w;
    }
  }
  for (bool moved = true; moved;) {
    moved = false;
    for (Index w : neighbours_[v])
      if (support_compare(p[0], p[1], p[2], at(w), at(v)) * sign > 0) {
        v = w;
        moved = true;
        break;
      }
  }
  face.assign(1, v);
  for (std::size_t i = 0; i < face.size(); ++i)
    for (Index w : neighbours_[face[i]])
      if (std::find(face.begin(), face.end(), w) == face.end() &&
          support_compare(p[0], p[1], p[2], at(w), at(face[i])) == 0)
        face.push_back(w);
  std::sort(face.begin(), face.end());
}

Piece SweptPolytope::sum(const SurfaceCones& cones, Index g) const {
  const SurfaceCones::Polygon& polygon = cones.polygon(g);
  const std::vector<Index>& c = polygon.corners;
  const std::size_t m = c.size();
  std::vector<RoundedPoint3> p;
  p.reserve(m);
  for (Index v : c) p.push_back(cones.rounded(v));
  // A triangle of P: its normal is P's.
  const Index t0 = polygon.edge_triangle[0];
  // The planes, in the thread's buffer (copied out at their final count).
  thread_local std::vector<LazyPlane> buffer;
  std::vector<LazyPlane>& lazy = buffer;
  lazy.assign(facets_.size(), LazyPlane());
  std::vector<Plane> lazy_exact;
  std::vector<Index> candidates;
  std::vector<std::vector<Point3>> loops;
  std::vector<std::vector<std::uint64_t>> labels;  // (contains)
  // The label of the point p_k + b_v (corner k of P, vertex v of B).
  auto label = [&](std::size_t k, Index v) { return std::uint64_t(c[k]) << 32 | v; };
  SumPlane plane;  // the last plane of kind B or C
  // That plane, a candidate: held exactly, with its loop and its points' labels.
  auto hold = [&](LazyPlane& lp, std::vector<Point3> loop, std::vector<std::uint64_t> names) {
    lp.exact = std::int32_t(lazy_exact.size());
    lazy_exact.push_back(canonical_plane(plane));
    candidates.push_back(Index(&lp - lazy.data()));
    loops.push_back(std::move(loop));
    labels.push_back(std::move(names));
  };
  // P's points as integers over a common denominator.
  std::vector<const ScaledPoint*> sp(m);
  for (std::size_t k = 0; k < m; ++k) sp[k] = &cones.scaled(c[k]);
  Integer work[3];
  std::unique_ptr<bool[]> at_top(new bool[m]);

  // A. The facets of B, each moved by the face of P extreme along its normal.
  // rise[f * m + k] = sign n_f · (p_{k+1} − p_k), the sign along f's normal
  // of P's edge k, which also tells the arcs of kind C below.
  std::vector<signed char> rise(facets_.size() * m);
  const bool tabled = prepared_ == &cones && !rise_.empty();  // the edges' signs (prepare)
  for (std::size_t fi = 0; fi < facets_.size(); ++fi) {
    const Facet& f = facets_[fi];
    const RoundedPoint3 u{f.normal, f.normal_approx};
    signed char* r = &rise[fi * m];
    if (tabled) {
      // Edge e run backwards: n_f . (p - q) = -(n_f . (q - p)).
      for (std::size_t k = 0; k < m; ++k) {
        const Index e = cones.edge_of(polygon.edge_triangle[k], polygon.edge_index[k]);
        const signed char x = rise_[std::size_t(e >> 1) * facets_.size() + fi];
        r[k] = static_cast<signed char>(e & 1 ? -x : x);
      }
    } else {
      for (std::size_t k = 0; k < m; ++k) r[k] = static_cast<signed char>(dot_difference_sign(u, p[k], p[(k + 1) % m]));
    }
    // p_k is at the top when neither edge at it rises away from it.
    int count = 0;
    std::size_t top = m;
    for (std::size_t k = 0; k < m; ++k) {
      at_top[k] = r[k] <= 0 && r[(k + m - 1) % m] >= 0;
      if (at_top[k]) {
        ++count;
        if (top == m) top = k;
      }
    }
    const Point3& q = p[top].exact;
    // primitive · x = offset + primitive · q, with q = Q / D in integers:
    // num / den = (offset_num D + offset_den S) / (offset_den D), S =
    // primitive · Q.  The plane is lazy: its doubles now (the offset num /
    // den rounded towards zero), the canonical plane only for a candidate
    // or when the union asks (build).
    LazyPlane& lp = lazy[fi];
    lp.tag = static_cast<std::uint8_t>(top);
    lp.a = f.primitive_approx[0];
    lp.b = f.primitive_approx[1];
    lp.c = f.primitive_approx[2];
    if (prepared_ == &cones) {  // the table (prepare)
      const std::size_t at = std::size_t(c[top]) * facets_.size() + fi;
      lp.d = offset_d_[at];
      lp.filtered = offset_ok_[at] != 0;
    } else {
      offset_along(f, *sp[top], work);
      lazy_doubles(f, work, lp.d, lp.filtered);
    }
    if ((!surface_ || facet_on_surface_[fi]) &&
        cones.polygon_candidate(g, u, at_top.get(),
                                below_.empty() || prepared_ != &cones ? nullptr : &below_[fi], facets_.size()) &&
        cones.polygon_keeps(g, u, at_top.get())) {
      lp.exact = std::int32_t(lazy_exact.size());
      if (prepared_ == &cones) offset_along(f, *sp[top], work);
      lazy_exact.push_back(canonical_from_offset(f, work));
      candidates.push_back(Index(fi));
      std::vector<Point3> loop;
      std::vector<std::uint64_t> names;
      if (count == 1) {
        for (Index v : f.loop) {
          loop.push_back(points_[v] + q);
          names.push_back(label(top, v));
        }
      } else {
        std::vector<Point3> sums;
        for (std::size_t k = 0; k < m; ++k)
          if (at_top[k])
            for (Index v : f.loop) sums.push_back(points_[v] + p[k].exact);
        loop = plane_hull(std::move(sums), f.normal);
      }
      loops.push_back(std::move(loop));
      labels.push_back(std::move(names));
    }
  }

  // B. P plus the face of B extreme along n_P and along −n_P, when that face
  // is a vertex or an edge (a facet's sum is in A).
  {
    std::vector<Index> faces[2];  // the vertices of B highest along n_P, and lowest (ascending)
    for (int side = 0; side < 2; ++side)
      extreme_face(p.data(), cones.normal_approx(t0), side == 0 ? 1 : -1, faces[side]);
    // n_P in integers: the primitive multiple of (p1 - p0) x (p2 - p0)
    // that SurfaceCones keeps for P's triangles.
    Integer n[2][3];
    if (faces[0].size() < 3 || faces[1].size() < 3)
      for (int j = 0; j < 3; ++j) {
        n[0][j] = cones.normal(t0)[j].get_num();
        n[1][j] = -n[0][j];
      }
    for (std::size_t k = 0; k < m; ++k) at_top[k] = true;  // P is face_u(P)
    for (int side = 0; side < 2; ++side) {
      const std::vector<Index>& face = faces[side];
      if (face.size() >= 3) continue;  // a facet of B: in A
      const Point3 u = side == 0 ? cones.normal(t0) : Rational(-1) * cones.normal(t0);
      const Vec3d ua = side == 0 ? cones.normal_approx(t0) : Vec3d{-cones.normal_approx(t0).x,
                                                                    -cones.normal_approx(t0).y,
                                                                    -cones.normal_approx(t0).z};
      LazyPlane& lp = lazy.emplace_back();
      sum_plane(n[side], *sp[0], scaled_[face[0]], plane);
      lazy_of(plane, lp);
      lp.tag = static_cast<std::uint8_t>(kBFacet + side);
      lp.code = face[0];
      if (cones.polygon_candidate(g, RoundedPoint3{u, ua}, at_top.get()) && on_surface(face[0], RoundedPoint3{u, ua})) {
        std::vector<Point3> loop;
        std::vector<std::uint64_t> names;
        if (face.size() == 1) {
          for (std::size_t i = 0; i < m; ++i) {
            const std::size_t k = side == 0 ? i : m - 1 - i;
            loop.push_back(p[k].exact + points_[face[0]]);
            names.push_back(label(k, face[0]));
          }
        } else {
          std::vector<Point3> sums;
          for (std::size_t k = 0; k < m; ++k)
            for (Index v : face) sums.push_back(p[k].exact + points_[v]);
          loop = plane_hull(std::move(sums), u);
        }
        hold(lp, std::move(loop), std::move(names));
      }
    }
  }

  // C. An edge a → b of P and an edge g of B whose open normal arcs cross.
  // The great circle normal to e = b − a crosses the open arc of g exactly
  // when the normals of g's two facets lie strictly on opposite sides of it
  // (rise of opposite non-zero signs); the crossing is ±(e × g), the sign σ
  // that puts it in g's arc (σ u · (w − g0) < 0 for the far vertex w of
  // g's first facet, never zero there), and it lies on P's arc (a half
  // circle) when σ u · (third − a) < 0, `third` any corner of P off the edge
  // (P lies on one side of the edge's line in its plane, strictly convex).
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t j = (k + 1) % m;
    const RoundedPoint3& a = p[k];
    const RoundedPoint3& b = p[j];
    const RoundedPoint3& third = p[(k + 2) % m];
    Integer e[3];  // a positive multiple of b - a
    bool have_e = false;
    for (std::size_t i = 0; i < m; ++i) at_top[i] = i == k || i == j;  // the edge a → b is face_u(P)
    for (const Edge& eb : edges_) {
      const int r0 = rise[eb.f0 * m + k], r1 = rise[eb.f1 * m + k];
      if (r0 * r1 >= 0) continue;
      const RoundedPoint3 g0 = at(eb.v0), g1 = at(eb.v1);
      const int sigma = -support_compare(g0, g1, at(eb.w0), b, a);
      if (sigma == 0) throw std::logic_error("SweptPolytope: a far vertex on the crossing plane");
      // s = sign u · (third − a) for u = (b − a) × (g1 − g0).
      const int s = -support_compare(a, b, third, g1, g0);
      if (sigma * s >= 0) continue;
      if (!have_e) {
        scaled_difference(*sp[k], *sp[j], e);
        have_e = true;
      }
      // u: a positive multiple of σ (b - a) × (g1 - g0), in integers.
      Integer n[3];
      cross_integers(e, eb.direction, n);
      if (sigma < 0)
        for (Integer& x : n) mpz_neg(x.get_mpz_t(), x.get_mpz_t());
      LazyPlane& lp = lazy.emplace_back();
      sum_plane(n, *sp[k], scaled_[eb.v0], plane);
      lazy_of(plane, lp);
      lp.tag = static_cast<std::uint8_t>(kCFacet + k + (sigma < 0 ? kMaxCorners : 0));
      lp.code = Index(&eb - edges_.data());
      const Point3 u{Rational(n[0]), Rational(n[1]), Rational(n[2])};
      // Faithful roundings (mpz_get_d truncates), as the cone tests allow.
      const Vec3d ua{mpz_get_d(n[0].get_mpz_t()), mpz_get_d(n[1].get_mpz_t()), mpz_get_d(n[2].get_mpz_t())};
      if (cones.polygon_candidate(g, RoundedPoint3{u, ua}, at_top.get()) &&
          cones.polygon_keeps(g, RoundedPoint3{u, ua}, at_top.get()) && on_surface(eb.v0, RoundedPoint3{u, ua})) {
        // e ⊕ g with normal e × g is counter-clockwise in the order
        // a + g0, b + g0, b + g1, a + g1; reversed for σ < 0.
        std::vector<Point3> loop = {a.exact + points_[eb.v0], b.exact + points_[eb.v0], b.exact + points_[eb.v1],
                                    a.exact + points_[eb.v1]};
        std::vector<std::uint64_t> names = {label(k, eb.v0), label(j, eb.v0), label(j, eb.v1), label(k, eb.v1)};
        if (sigma < 0) {
          std::reverse(loop.begin(), loop.end());
          std::reverse(names.begin(), names.end());
        }
        hold(lp, std::move(loop), std::move(names));
      }
    }
  }

  // The planes in the order built (facet k of B first, as plane k: the
  // union's directions), all lazy; the candidates ascending.
  Piece piece;
  piece.directions = &directions_;
  piece.builder = this;
  piece.scaled_corner = std::move(sp);
  piece.corner_id = c;
  piece.lazy.assign(lazy.begin(), lazy.end());
  piece.lazy_exact = std::move(lazy_exact);
  piece.candidates = std::move(candidates);
  piece.loops = std::move(loops);
  piece.labels = std::move(labels);
  // The box: P's box plus B's, exactly, then rounded to nearest (monotone,
  // so it holds the nearest doubles of every point of the piece).
  for (int k = 0; k < 3; ++k) {
    const Rational* lo = &p[0].exact[k];
    const Rational* hi = lo;
    for (std::size_t j = 1; j < m; ++j) {
      if (cmp(p[j].exact[k], *lo) < 0) lo = &p[j].exact[k];
      if (cmp(p[j].exact[k], *hi) > 0) hi = &p[j].exact[k];
    }
    piece.lo[k] = to_double(Rational(*lo + lo_[k]));
    piece.hi[k] = to_double(Rational(*hi + hi_[k]));
  }
  return piece;
}

}  // namespace minksum::nonconvex_detail
