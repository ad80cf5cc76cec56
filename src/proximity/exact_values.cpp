// The exact values of proximity answers, computed on demand from the
// certified witness (docs/proximity.md): the closest point of M on the
// witness feature, the squared distance or depth, and the split of a point of
// M into a point of P and a point of Q.  The queries themselves decide the
// witness with filtered predicates only; this arithmetic runs when an
// accessor of DistanceResult or DepthResult is first called.
//
// The accessors compute in integers over common denominators (HomPoint):
// P's and Q's vertices are kept so from the rebuild (a double vertex from its
// mantissas and exponents, with shifts), s is read off its doubles the same
// way, every intermediate is an integer polynomial in those numerators and
// denominators (GMP integers, no gcd, no rational normalisation), and each
// output number is reduced once, at the end.  The functions on Point3
// (closest_point, split, decompose, common_point) do the same with a reduced
// rational at every step; they are the reference the fast values are tested
// against (reference_values) and the public decompose's implementation.
#include <minksum/proximity.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "proximity/obstacle_geometry.hpp"

namespace minksum {

namespace detail {

// ---------------------------------------------------------------------------
// Points over one denominator.

namespace {

// v = m·2^e with m odd (or v = 0, m = 0).  Every finite double is such a
// product with |m| < 2^53: frexp's fraction times 2^53 is an integer.
void split_double(double v, std::int64_t& m, int& e) {
  if (v == 0) {
    m = 0, e = 0;
    return;
  }
  int ex = 0;
  const double f = std::frexp(v, &ex);
  m = std::int64_t(std::ldexp(f, 53));
  e = ex - 53;
  const int tz = __builtin_ctzll(std::uint64_t(m));
  m >>= tz;
  e += tz;
}

void set_ratio(Rational& r, const Integer& num, const Integer& den) {
  mpz_set(r.get_num_mpz_t(), num.get_mpz_t());
  mpz_set(r.get_den_mpz_t(), den.get_mpz_t());
  r.canonicalize();
}

// a ± b (products accumulated in place: no temporaries).
HomPoint combine(const HomPoint& a, const HomPoint& b, bool subtract) {
  HomPoint r;
  const Integer* ac[3] = {&a.x, &a.y, &a.z};
  const Integer* bc[3] = {&b.x, &b.y, &b.z};
  Integer* rc[3] = {&r.x, &r.y, &r.z};
  const bool same = a.w == b.w;
  for (int i = 0; i < 3; ++i) {
    mpz_ptr o = rc[i]->get_mpz_t();
    if (same) {
      if (subtract) mpz_sub(o, ac[i]->get_mpz_t(), bc[i]->get_mpz_t());
      else mpz_add(o, ac[i]->get_mpz_t(), bc[i]->get_mpz_t());
      continue;
    }
    mpz_mul(o, ac[i]->get_mpz_t(), b.w.get_mpz_t());
    if (subtract) mpz_submul(o, bc[i]->get_mpz_t(), a.w.get_mpz_t());
    else mpz_addmul(o, bc[i]->get_mpz_t(), a.w.get_mpz_t());
  }
  if (same) r.w = a.w;
  else mpz_mul(r.w.get_mpz_t(), a.w.get_mpz_t(), b.w.get_mpz_t());
  return r;
}
HomPoint operator+(const HomPoint& a, const HomPoint& b) { return combine(a, b, false); }
HomPoint operator-(const HomPoint& a, const HomPoint& b) { return combine(a, b, true); }
// The dot product of the numerators.
Integer dot_num(const HomPoint& a, const HomPoint& b) {
  Integer r;
  mpz_mul(r.get_mpz_t(), a.x.get_mpz_t(), b.x.get_mpz_t());
  mpz_addmul(r.get_mpz_t(), a.y.get_mpz_t(), b.y.get_mpz_t());
  mpz_addmul(r.get_mpz_t(), a.z.get_mpz_t(), b.z.get_mpz_t());
  return r;
}
// a's numerators times k, its denominator times l (k, l > 0 for l).
HomPoint scaled(const HomPoint& a, const Integer& k, const Integer& l) {
  return HomPoint{a.x * k, a.y * k, a.z * k, a.w * l};
}
// ⟨(a × b), n⟩ for the numerators of a and b and the integer normal n.
Integer cross_dot(const HomPoint& a, const HomPoint& b, const Plane& n) {
  return (a.y * b.z - a.z * b.y) * n.a + (a.z * b.x - a.x * b.z) * n.b + (a.x * b.y - a.y * b.x) * n.c;
}

}  // namespace

HomPoint hom_point(const Vec3d& a) {
  static_assert(sizeof(long) >= sizeof(std::int64_t), "mpz_set_si takes the 53-bit mantissas as long");
  std::int64_t m[3];
  int e[3];
  split_double(a.x, m[0], e[0]);
  split_double(a.y, m[1], e[1]);
  split_double(a.z, m[2], e[2]);
  int k = 0;  // the common denominator 2^−k
  for (int i = 0; i < 3; ++i)
    if (m[i] != 0) k = std::min(k, e[i]);
  HomPoint h;
  Integer* c[3] = {&h.x, &h.y, &h.z};
  for (int i = 0; i < 3; ++i) {
    mpz_set_si(c[i]->get_mpz_t(), long(m[i]));
    if (m[i] != 0) mpz_mul_2exp(c[i]->get_mpz_t(), c[i]->get_mpz_t(), mp_bitcnt_t(e[i] - k));
  }
  h.w = 1;
  mpz_mul_2exp(h.w.get_mpz_t(), h.w.get_mpz_t(), mp_bitcnt_t(-k));
  return h;
}

HomPoint hom_point(const Point3& a) {
  HomPoint h;
  mpz_lcm(h.w.get_mpz_t(), a.x.get_den_mpz_t(), a.y.get_den_mpz_t());
  mpz_lcm(h.w.get_mpz_t(), h.w.get_mpz_t(), a.z.get_den_mpz_t());
  const Rational* q[3] = {&a.x, &a.y, &a.z};
  Integer* c[3] = {&h.x, &h.y, &h.z};
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(c[i]->get_mpz_t(), h.w.get_mpz_t(), q[i]->get_den_mpz_t());
    mpz_mul(c[i]->get_mpz_t(), c[i]->get_mpz_t(), q[i]->get_num_mpz_t());
  }
  return h;
}

Point3 to_point(const HomPoint& a) {
  Point3 p;
  set_ratio(p.x, a.x, a.w);
  set_ratio(p.y, a.y, a.w);
  set_ratio(p.z, a.z, a.w);
  return p;
}

void ObstacleGeometry::prepare_exact() {
  // Every vertex of a polytope over one denominator, the lcm of theirs,
  // when it is not much longer than the longest of them (a double polytope
  // whose exponents differ widely keeps one per vertex): differences of
  // vertices (edge vectors) are then differences of numerators.
  auto fill = [](const ConvexPolytope& poly, std::vector<HomPoint>& out) {
    out.resize(poly.num_vertices());
    Integer lcm = 1;
    std::size_t longest = 1;
    for (Index v = 0; v < poly.num_vertices(); ++v) {
      out[v] = poly.coordinates().is_double(v) ? hom_point(poly.approx(v)) : hom_point(poly.point(v));
      mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), out[v].w.get_mpz_t());
      longest = std::max(longest, mpz_sizeinbase(out[v].w.get_mpz_t(), 2));
    }
    if (mpz_sizeinbase(lcm.get_mpz_t(), 2) > longest + 64) return;
    Integer k;
    for (HomPoint& h : out) {
      if (h.w == lcm) continue;
      mpz_divexact(k.get_mpz_t(), lcm.get_mpz_t(), h.w.get_mpz_t());
      h.x *= k, h.y *= k, h.z *= k;
      h.w = lcm;
    }
  };
  fill(p, p_hom);
  fill(q, q_hom);
  center_hom = hom_point(center);
  p_center_hom = hom_point(p_center);
  const ConvexPolytope& mm = m();
  n2.resize(mm.num_facets());
  for (Index f = 0; f < mm.num_facets(); ++f) {
    const Plane& pl = mm.plane(f);
    n2[f] = pl.a * pl.a + pl.b * pl.b + pl.c * pl.c;
  }
}

HomPoint ObstacleGeometry::m_hom(Index v) const {
  return p_hom[sum.vertex_origin[v].first] - q_hom[neg_to_q[sum.vertex_origin[v].second]];
}

namespace {

// s − x for x the point of the feature `feat` of M closest to s, and
// |s − x|² = num / den.
//   vertex v: s − v;
//   edge a→b, r = s − a, e = b − a: (r⟨e,e⟩ − ⟨r,e⟩e) / ⟨e,e⟩, whose
//     squared length is (⟨r,r⟩⟨e,e⟩ − ⟨r,e⟩²) / ⟨e,e⟩;
//   facet n·x = d: t·n with t = (n·s − d) / |n|², squared length
//     (n·s − d)² / |n|².
HomPoint closest_offset(const ObstacleGeometry& g, const Feature& feat, const HomPoint& s, Integer& num, Integer& den) {
  const ConvexPolytope& mm = g.m();
  switch (feat.dim) {
    case FeatureDim::vertex: {
      HomPoint r = s - g.m_hom(feat.index);
      num = dot_num(r, r);
      den = r.w * r.w;
      return r;
    }
    case FeatureDim::edge: {
      const HomPoint a = g.m_hom(mm.origin(2 * feat.index));
      const HomPoint e = g.m_hom(mm.target(2 * feat.index)) - a;
      const HomPoint r = s - a;
      const Integer ee = dot_num(e, e), re = dot_num(r, e);
      num = dot_num(r, r) * ee - re * re;
      den = r.w * r.w * ee;
      return HomPoint{r.x * ee - re * e.x, r.y * ee - re * e.y, r.z * ee - re * e.z, r.w * ee};
    }
    case FeatureDim::facet: {
      const Plane& pl = mm.plane(feat.index);
      const Integer t = pl.a * s.x + pl.b * s.y + pl.c * s.z - pl.d * s.w;
      num = t * t;
      den = s.w * s.w * g.n2[feat.index];
      const Integer w = s.w * g.n2[feat.index];
      return HomPoint{t * pl.a, t * pl.b, t * pl.c, w};
    }
  }
  throw std::logic_error("proximity: unknown feature dimension");
}

// The point of P in x = p − q for x in the feature `feat` of M, from x's
// barycentric coordinates in it (an edge: its parameter; a facet: a
// triangle of its fan holding x), as decompose does on rationals.
HomPoint decompose_p(const ObstacleGeometry& g, const Feature& feat, const HomPoint& x) {
  const ConvexPolytope& mm = g.m();
  auto pv = [&](Index v) -> const HomPoint& { return g.p_hom[g.sum.vertex_origin[v].first]; };
  if (feat.dim == FeatureDim::vertex) return pv(feat.index);
  if (feat.dim == FeatureDim::edge) {
    // t = ⟨x − a, e⟩ / ⟨e, e⟩ = ⟨r, e⟩·w_e / (w_r·⟨e, e⟩) on the numerators.
    const Index a = mm.origin(2 * feat.index), b = mm.target(2 * feat.index);
    const HomPoint ha = g.m_hom(a);
    const HomPoint e = g.m_hom(b) - ha;
    const HomPoint r = x - ha;
    const Integer tn = dot_num(r, e) * e.w, td = r.w * dot_num(e, e);
    const HomPoint& pa = pv(a);
    const HomPoint dp = pv(b) - pa;
    // pa + (tn / td)·dp
    return scaled(pa, td, td) + scaled(dp, tn, td);
  }
  const Plane& n = mm.plane(feat.index);
  const std::vector<Index> vs = mm.facet_vertices(feat.index);
  const HomPoint w0 = g.m_hom(vs[0]);
  const HomPoint r = x - w0;
  for (std::size_t i = 1; i + 1 < vs.size(); ++i) {
    const HomPoint ei = g.m_hom(vs[i]) - w0, ej = g.m_hom(vs[i + 1]) - w0;
    // li = ⟨r × ej, n⟩·w_i / (w_r·A), lj = ⟨ei × r, n⟩·w_j / (w_r·A) with
    // A = ⟨ei × ej, n⟩ (the numerators' area), l0 = 1 − li − lj: all over
    // T = w_r·A, made positive.
    Integer area = cross_dot(ei, ej, n);
    Integer li = cross_dot(r, ej, n) * ei.w, lj = cross_dot(ei, r, n) * ej.w;
    if (sgn(area) < 0) area = -area, li = -li, lj = -lj;
    const Integer t = r.w * area;
    const Integer l0 = t - li - lj;
    if (sgn(li) < 0 || sgn(lj) < 0 || sgn(l0) < 0) continue;
    return scaled(pv(vs[0]), l0, t) + scaled(pv(vs[i]), li, t) + scaled(pv(vs[i + 1]), lj, t);
  }
  throw std::logic_error("proximity: point not in the facet it was attributed to");
}

// The point p of P with x = p − q, q in Q, for x in the face w.m of M (as
// split): a translate of x when Q's face is a vertex, P's vertex when P's
// is, Cramer's rule on two skew edges, else decompose_p.  Cramer's rule and
// decompose_p read x only through ⟨x, e⟩ and ⟨x × e, n⟩ for vectors e
// parallel to w.m and n normal to it, so they are given y instead, any point
// with y − x orthogonal to w.m: for a closest point x of M, s itself (s − x
// lies in w.m's normal cone), whose denominator is far smaller than x's.
HomPoint split_p(const ObstacleGeometry& g, const Witness& w, const HomPoint& x, const HomPoint& y) {
  if (w.q.dim == FeatureDim::vertex) return x + g.q_hom[w.q.index];
  if (w.p.dim == FeatureDim::vertex) return g.p_hom[w.p.index];
  if (w.p.dim == FeatureDim::edge && w.q.dim == FeatureDim::edge) {
    const Index hp = 2 * w.p.index, hq = 2 * w.q.index;
    const HomPoint& p0 = g.p_hom[g.p.origin(hp)];
    const HomPoint& q0 = g.q_hom[g.q.origin(hq)];
    const HomPoint u = g.p_hom[g.p.target(hp)] - p0, v = g.q_hom[g.q.target(hq)] - q0;
    const Integer uv = dot_num(u, v), uu = dot_num(u, u), vv = dot_num(v, v);
    const Integer det = uv * uv - uu * vv;  // −|u × v|² on the numerators
    if (sgn(det) != 0) {
      // α = (⟨u,v⟩⟨w,v⟩ − ⟨v,v⟩⟨w,u⟩) / det on the numerators of u, v and
      // w = x − p0 + q0, over w's denominator: p = p0 + α·u.
      const HomPoint wv = (y + q0) - p0;
      Integer num = uv * dot_num(wv, v) - vv * dot_num(wv, u);
      Integer den = wv.w * det;
      if (sgn(den) < 0) num = -num, den = -den;
      // p0 + (num / den)·u_numerators
      return HomPoint{p0.x * den + p0.w * num * u.x, p0.y * den + p0.w * num * u.y, p0.z * den + p0.w * num * u.z,
                      p0.w * den};
    }
  }
  return decompose_p(g, w.m, y);
}

// The common point p = q + s of P and Q + s for s in M (common_point on
// rationals): for s inside M, with c the interior point, dir = s − c, f the
// stabbed facet n·x = d, b = ⟨n, dir⟩ and a = d·w_c − ⟨n, c⟩ on the
// numerators, the exit point is y = (c·b + a·dir) / (w_c·b) and
// s = (1 − λ)·c + λ·y with λ = w_c·b / (a·w_dir), so
// p = ((a·w_dir − w_c·b)·p_c + w_c·b·p_y) / (a·w_dir).
HomPoint common_p(const ObstacleGeometry& g, const Witness& w, ContactStatus status, const HomPoint& s) {
  if (status == ContactStatus::touching) return split_p(g, w, s, s);
  const HomPoint& c = g.center_hom;
  const HomPoint dir = s - c;
  const Plane& n = g.m().plane(w.facet);
  const Integer b = n.a * dir.x + n.b * dir.y + n.c * dir.z;
  if (sgn(b) <= 0) return g.p_center_hom;  // s == c
  const Integer a = n.d * c.w - (n.a * c.x + n.b * c.y + n.c * c.z);
  const HomPoint y{c.x * b + a * dir.x, c.y * b + a * dir.y, c.z * b + a * dir.z, c.w * b};
  const HomPoint py = split_p(g, w, y, y);
  const Integer total = a * dir.w, cb = c.w * b;
  return scaled(g.p_center_hom, total - cb, total) + scaled(py, cb, total);
}

}  // namespace

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

namespace {
detail::HomPoint hom_of(const std::shared_ptr<Point3>& exact, const Vec3d& d) {
  return exact ? detail::hom_point(*exact) : detail::hom_point(d);
}
}  // namespace

const detail::HomPoint& DistanceResult::s_hom(detail::DistanceExact& e) const {
  if (!e.have_s) e.s = hom_of(s_exact_, sd_), e.have_s = true;
  return e.s;
}

detail::DistanceExact& DistanceResult::exact() const {
  if (!exact_) exact_ = std::make_shared<detail::DistanceExact>();
  return *exact_;
}

detail::DistanceExact& DistanceResult::compute_offset() const {
  detail::DistanceExact& e = exact();
  if (e.have_offset) return e;
  if (status != ContactStatus::separate || !geo_) {
    e.offset = detail::HomPoint{0, 0, 0, 1};
    e.squared_distance = 0;
    e.distance = 0;
  } else {
    Integer num, den;
    e.offset = detail::closest_offset(*geo_, witness.m, s_hom(e), num, den);
    detail::set_ratio(e.squared_distance, num, den);
    e.distance = std::sqrt(to_double(e.squared_distance));
  }
  e.have_offset = true;
  return e;
}

// p − q = x = s − offset; the closest point of Q + w is q + s = p + offset
// (p itself when the bodies touch or overlap).
detail::DistanceExact& DistanceResult::compute_p() const {
  detail::DistanceExact& e = compute_offset();
  if (e.have_p) return e;
  if (!geo_) {
    e.p = detail::HomPoint{0, 0, 0, 1};
  } else {
    const detail::HomPoint& s = s_hom(e);
    if (status != ContactStatus::separate) e.p = detail::common_p(*geo_, witness, status, s);
    else if (witness.q.dim == FeatureDim::vertex) e.p = detail::split_p(*geo_, witness, detail::operator-(s, e.offset), s);
    else e.p = detail::split_p(*geo_, witness, s, s);  // x is not read
    if (e.translated) e.p = detail::operator+(e.p, detail::hom_point(e.u));
  }
  e.have_p = true;
  return e;
}

const Rational& DistanceResult::squared_distance() const { return compute_offset().squared_distance; }
double DistanceResult::distance() const { return compute_offset().distance; }
const Point3& DistanceResult::direction() const {
  detail::DistanceExact& e = compute_offset();
  if (!e.have_direction) e.direction = detail::to_point(e.offset), e.have_direction = true;
  return e.direction;
}
const Point3& DistanceResult::point_p() const {
  detail::DistanceExact& e = compute_p();
  if (!e.have_point_p) e.point_p = detail::to_point(e.p), e.have_point_p = true;
  return e.point_p;
}
const Point3& DistanceResult::point_q() const {
  detail::DistanceExact& e = compute_p();
  if (!e.have_point_q) {
    e.point_q = status == ContactStatus::separate ? detail::to_point(detail::operator+(e.p, e.offset)) : point_p();
    e.have_point_q = true;
  }
  return e.point_q;
}

// ---------------------------------------------------------------------------
// DepthResult.

Point3 DepthResult::point() const { return s_exact_ ? *s_exact_ : Point3(sd_.x, sd_.y, sd_.z); }

// For the witness facet's plane n·x = d and s = S / w: g = d·w − ⟨n, S⟩ > 0,
// the squared depth g² / (w²·|n|²) and the translation −g·n / (w·|n|²),
// each reduced when first asked for.
detail::DepthExact& DepthResult::exact() const {
  if (!exact_) exact_ = std::make_shared<detail::DepthExact>();
  detail::DepthExact& e = *exact_;
  if (e.have) return e;
  e.have = true;
  if (status != ContactStatus::penetrating || !geo_) {
    e.squared_depth = 0;
    e.depth = 0;
    e.gap = 0;
    e.w = 1;
    return e;
  }
  const Plane& pl = geo_->m().plane(witness.facet);
  const detail::HomPoint s = s_exact_ ? detail::hom_point(*s_exact_) : detail::hom_point(sd_);
  e.gap = pl.d * s.w;
  mpz_submul(e.gap.get_mpz_t(), pl.a.get_mpz_t(), s.x.get_mpz_t());
  mpz_submul(e.gap.get_mpz_t(), pl.b.get_mpz_t(), s.y.get_mpz_t());
  mpz_submul(e.gap.get_mpz_t(), pl.c.get_mpz_t(), s.z.get_mpz_t());
  e.w = s.w * geo_->n2[witness.facet];
  detail::set_ratio(e.squared_depth, Integer(e.gap * e.gap), Integer(e.w * s.w));
  e.depth = std::sqrt(to_double(e.squared_depth));
  return e;
}

// Unless penetrating the values are zeros: no storage is made for them.
const Rational& DepthResult::squared_depth() const {
  static const Rational zero(0);
  return status == ContactStatus::penetrating && geo_ ? exact().squared_depth : zero;
}
double DepthResult::depth() const { return status == ContactStatus::penetrating && geo_ ? exact().depth : 0; }
const Point3& DepthResult::direction() const {
  if (status != ContactStatus::penetrating || !geo_) return zero_point();
  detail::DepthExact& e = exact();
  if (!e.have_direction) {
    if (sgn(e.gap) == 0) {
      e.direction = zero_point();
    } else {
      const Plane& pl = geo_->m().plane(witness.facet);
      e.direction = detail::to_point(detail::HomPoint{-e.gap * pl.a, -e.gap * pl.b, -e.gap * pl.c, e.w});
    }
    e.have_direction = true;
  }
  return e.direction;
}

// ---------------------------------------------------------------------------
// The reference: rational arithmetic on every step.

namespace detail {

ReferenceDistance reference_values(const DistanceResult& r) {
  ReferenceDistance out;
  const Point3 zero = zero_point();
  if (!r.geo_) {
    out.direction = out.point_p = out.point_q = zero;
    return out;
  }
  const ObstacleGeometry& g = *r.geo_;
  const Point3 s = r.point();
  std::pair<Point3, Point3> pq;
  if (r.status == ContactStatus::separate) {
    out.direction = s - g.closest_point(r.witness.m, s);
    out.squared_distance = dot(out.direction, out.direction);
    pq = g.split(r.witness, s - out.direction);
  } else {
    out.direction = zero;
    pq = g.common_point(r.witness, r.status, s);
  }
  out.point_p = std::move(pq.first);
  out.point_q = pq.second + s;
  if (r.exact_ && r.exact_->translated) {
    out.point_p = out.point_p + r.exact_->u;
    out.point_q = out.point_q + r.exact_->u;
  }
  return out;
}

ReferenceDepth reference_values(const DepthResult& r) {
  ReferenceDepth out;
  out.direction = zero_point();
  if (r.status != ContactStatus::penetrating || !r.geo_) return out;
  const ObstacleGeometry& g = *r.geo_;
  const Index f = r.witness.facet;
  const Point3& n = g.normal[f];
  const Rational gap = g.offset[f] - dot(n, r.point());
  const Rational t = gap / g.norm2[f];
  out.squared_depth = t * gap;
  out.direction = (-t) * n;
  return out;
}

}  // namespace detail

}  // namespace minksum
