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
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "proximity/obstacle_geometry.hpp"

namespace minksum {

// ---------------------------------------------------------------------------
// Quotient and QuotientPoint.

Quotient::Quotient(Integer n, Integer d) : num(std::move(n)), den(std::move(d)) {
  if (sgn(den) == 0) throw std::invalid_argument("Quotient: zero denominator");
  if (sgn(den) < 0) mpz_neg(num.get_mpz_t(), num.get_mpz_t()), mpz_neg(den.get_mpz_t(), den.get_mpz_t());
}

Rational Quotient::to_rational() const {
  Rational r;
  mpz_set(r.get_num_mpz_t(), num.get_mpz_t());
  mpz_set(r.get_den_mpz_t(), den.get_mpz_t());
  r.canonicalize();
  return r;
}

namespace {
// to_double(Rational) rounds num/den for any positive den (its paths divide
// the integers as they are); this copies them into a per-thread rational
// without reducing it.
double quotient_to_double(const Integer& num, const Integer& den) {
  thread_local Rational t;
  mpz_set(t.get_num_mpz_t(), num.get_mpz_t());
  mpz_set(t.get_den_mpz_t(), den.get_mpz_t());
  return minksum::to_double(t);
}
// sign(a/b − c/d) for b, d > 0: sign(a·d − c·b).
int cross_cmp(mpz_srcptr a, mpz_srcptr b, mpz_srcptr c, mpz_srcptr d) {
  if (mpz_cmp(b, d) == 0) return mpz_cmp(a, c);
  thread_local Integer l, r;
  mpz_mul(l.get_mpz_t(), a, d);
  mpz_mul(r.get_mpz_t(), c, b);
  return mpz_cmp(l.get_mpz_t(), r.get_mpz_t());
}
int normal_sign(int c) { return (c > 0) - (c < 0); }
}  // namespace

double Quotient::to_double() const { return quotient_to_double(num, den); }
std::string Quotient::to_string() const { return format_exact(to_rational()); }
int cmp(const Quotient& a, const Quotient& b) {
  return normal_sign(cross_cmp(a.num.get_mpz_t(), a.den.get_mpz_t(), b.num.get_mpz_t(), b.den.get_mpz_t()));
}
bool operator==(const Quotient& a, const Rational& b) {
  return cross_cmp(a.num.get_mpz_t(), a.den.get_mpz_t(), b.get_num_mpz_t(), b.get_den_mpz_t()) == 0;
}

Point3 QuotientPoint::to_point() const { return detail::to_point(*this); }
Vec3d QuotientPoint::to_double() const {
  return Vec3d{quotient_to_double(x, w), quotient_to_double(y, w), quotient_to_double(z, w)};
}
bool operator==(const QuotientPoint& a, const QuotientPoint& b) {
  return cross_cmp(a.x.get_mpz_t(), a.w.get_mpz_t(), b.x.get_mpz_t(), b.w.get_mpz_t()) == 0 &&
         cross_cmp(a.y.get_mpz_t(), a.w.get_mpz_t(), b.y.get_mpz_t(), b.w.get_mpz_t()) == 0 &&
         cross_cmp(a.z.get_mpz_t(), a.w.get_mpz_t(), b.z.get_mpz_t(), b.w.get_mpz_t()) == 0;
}
bool operator==(const QuotientPoint& a, const Point3& b) {
  return cross_cmp(a.x.get_mpz_t(), a.w.get_mpz_t(), b.x.get_num_mpz_t(), b.x.get_den_mpz_t()) == 0 &&
         cross_cmp(a.y.get_mpz_t(), a.w.get_mpz_t(), b.y.get_num_mpz_t(), b.y.get_den_mpz_t()) == 0 &&
         cross_cmp(a.z.get_mpz_t(), a.w.get_mpz_t(), b.z.get_num_mpz_t(), b.z.get_den_mpz_t()) == 0;
}

namespace detail {

// ---------------------------------------------------------------------------
// Points over one denominator.  Every function below writes into storage it
// is given (the answer's recycled integers): mpz_mul, mpz_addmul and
// mpz_submul into integers that keep their limbs, no temporaries.

namespace {

// v = m·2^e with m odd (or v = 0, m = 0), read off v's bits: a normal
// double is (2^52 + fraction)·2^(exponent field − 1075), a subnormal one
// fraction·2^−1074, so |m| < 2^53.
void split_double(double v, std::int64_t& m, int& e) {
  const std::uint64_t b = std::bit_cast<std::uint64_t>(v);
  const int field = int((b >> 52) & 0x7ff);
  std::uint64_t mant = b & ((std::uint64_t(1) << 52) - 1);
  if (field == 0 && mant == 0) {
    m = 0, e = 0;
    return;
  }
  if (field == 0) {
    e = -1074;
  } else {
    mant |= std::uint64_t(1) << 52;
    e = field - 1075;
  }
  const int tz = __builtin_ctzll(mant);
  mant >>= tz;
  e += tz;
  m = (b >> 63) ? -std::int64_t(mant) : std::int64_t(mant);
}

void set_ratio(Rational& r, const Integer& num, const Integer& den) {
  mpz_set(r.get_num_mpz_t(), num.get_mpz_t());
  mpz_set(r.get_den_mpz_t(), den.get_mpz_t());
  r.canonicalize();
}

mpz_ptr z(Integer& a) { return a.get_mpz_t(); }
mpz_srcptr z(const Integer& a) { return a.get_mpz_t(); }

// r = a ± b; r may be a, not b.
void combine(HomPoint& r, const HomPoint& a, const HomPoint& b, bool subtract) {
  const Integer* ac[3] = {&a.x, &a.y, &a.z};
  const Integer* bc[3] = {&b.x, &b.y, &b.z};
  Integer* rc[3] = {&r.x, &r.y, &r.z};
  const bool same = mpz_cmp(z(a.w), z(b.w)) == 0;
  for (int i = 0; i < 3; ++i) {
    mpz_ptr o = z(*rc[i]);
    if (same) {
      if (subtract) mpz_sub(o, z(*ac[i]), z(*bc[i]));
      else mpz_add(o, z(*ac[i]), z(*bc[i]));
      continue;
    }
    mpz_mul(o, z(*ac[i]), z(b.w));
    if (subtract) mpz_submul(o, z(*bc[i]), z(a.w));
    else mpz_addmul(o, z(*bc[i]), z(a.w));
  }
  if (!same) mpz_mul(z(r.w), z(a.w), z(b.w));
  else if (&r != &a) mpz_set(z(r.w), z(a.w));
}
void add(HomPoint& r, const HomPoint& a, const HomPoint& b) { combine(r, a, b, false); }
void sub(HomPoint& r, const HomPoint& a, const HomPoint& b) { combine(r, a, b, true); }
void set(HomPoint& r, const HomPoint& a) {
  mpz_set(z(r.x), z(a.x)), mpz_set(z(r.y), z(a.y)), mpz_set(z(r.z), z(a.z)), mpz_set(z(r.w), z(a.w));
}
void set_zero(HomPoint& r) {
  mpz_set_ui(z(r.x), 0), mpz_set_ui(z(r.y), 0), mpz_set_ui(z(r.z), 0), mpz_set_ui(z(r.w), 1);
}
// r = the dot product of the numerators.
void dot_num(Integer& r, const HomPoint& a, const HomPoint& b) {
  mpz_mul(z(r), z(a.x), z(b.x));
  mpz_addmul(z(r), z(a.y), z(b.y));
  mpz_addmul(z(r), z(a.z), z(b.z));
}
// r = ⟨n, numerators of a⟩ (n's a, b, c).
void plane_dot(Integer& r, const Plane& n, const HomPoint& a) {
  mpz_mul(z(r), z(n.a), z(a.x));
  mpz_addmul(z(r), z(n.b), z(a.y));
  mpz_addmul(z(r), z(n.c), z(a.z));
}
// out = (ka·a ± kb·b on the numerators) / (ka·a.w): a/a.w ± (kb / ka)·b's
// numerators (out aliases none of the arguments).
void scale_add(HomPoint& out, const HomPoint& a, const Integer& ka, const Integer& kb, const HomPoint& b,
               bool subtract) {
  const Integer* ac[3] = {&a.x, &a.y, &a.z};
  const Integer* bc[3] = {&b.x, &b.y, &b.z};
  Integer* oc[3] = {&out.x, &out.y, &out.z};
  for (int i = 0; i < 3; ++i) {
    mpz_mul(z(*oc[i]), z(*ac[i]), z(ka));
    if (subtract) mpz_submul(z(*oc[i]), z(kb), z(*bc[i]));
    else mpz_addmul(z(*oc[i]), z(kb), z(*bc[i]));
  }
  mpz_mul(z(out.w), z(a.w), z(ka));
}
// r = ⟨(a × b), n⟩ for the numerators of a and b and the integer normal n
// (t: scratch).
void cross_dot(Integer& r, const HomPoint& a, const HomPoint& b, const Plane& n, Integer& t) {
  mpz_mul(z(t), z(a.y), z(b.z));
  mpz_submul(z(t), z(a.z), z(b.y));
  mpz_mul(z(r), z(t), z(n.a));
  mpz_mul(z(t), z(a.z), z(b.x));
  mpz_submul(z(t), z(a.x), z(b.z));
  mpz_addmul(z(r), z(t), z(n.b));
  mpz_mul(z(t), z(a.x), z(b.y));
  mpz_submul(z(t), z(a.y), z(b.x));
  mpz_addmul(z(r), z(t), z(n.c));
}
// out = (Σ c_i · pts_i) / d, i.e. the point Σ (c_i / d)·pts_i for integers
// c_i and d > 0 (l, t: scratch; out aliases none of the arguments).  Points
// with one denominator w (the vertices of one polytope) need n products per
// coordinate and the denominator w·d; otherwise each is brought to the
// product of theirs.
void combination(HomPoint& out, const HomPoint* const* pts, const Integer* const* c, int n, const Integer& d,
                 Integer& l, Integer& t) {
  bool same = true;
  for (int i = 1; i < n; ++i) same = same && mpz_cmp(z(pts[i]->w), z(pts[0]->w)) == 0;
  Integer* oc[3] = {&out.x, &out.y, &out.z};
  if (same) {
    for (int k = 0; k < 3; ++k) {
      const Integer HomPoint::*m = k == 0 ? &HomPoint::x : k == 1 ? &HomPoint::y : &HomPoint::z;
      mpz_mul(z(*oc[k]), z(*c[0]), z(pts[0]->*m));
      for (int i = 1; i < n; ++i) mpz_addmul(z(*oc[k]), z(*c[i]), z(pts[i]->*m));
    }
    mpz_mul(z(out.w), z(pts[0]->w), z(d));
    return;
  }
  mpz_set_ui(z(l), 1);
  for (int i = 0; i < n; ++i) mpz_mul(z(l), z(l), z(pts[i]->w));
  for (int k = 0; k < 3; ++k) mpz_set_ui(z(*oc[k]), 0);
  for (int i = 0; i < n; ++i) {
    mpz_divexact(z(t), z(l), z(pts[i]->w));
    mpz_mul(z(t), z(t), z(*c[i]));
    mpz_addmul(z(out.x), z(t), z(pts[i]->x));
    mpz_addmul(z(out.y), z(t), z(pts[i]->y));
    mpz_addmul(z(out.z), z(t), z(pts[i]->z));
  }
  mpz_mul(z(out.w), z(l), z(d));
}

}  // namespace

void hom_point(HomPoint& h, const Vec3d& a) {
  static_assert(sizeof(long) >= sizeof(std::int64_t), "mpz_set_si takes the 53-bit mantissas as long");
  std::int64_t m[3];
  int e[3];
  split_double(a.x, m[0], e[0]);
  split_double(a.y, m[1], e[1]);
  split_double(a.z, m[2], e[2]);
  int k = 0;  // the common denominator 2^−k
  for (int i = 0; i < 3; ++i)
    if (m[i] != 0) k = std::min(k, e[i]);
  Integer* c[3] = {&h.x, &h.y, &h.z};
  for (int i = 0; i < 3; ++i) {
    mpz_set_si(z(*c[i]), long(m[i]));
    if (m[i] != 0) mpz_mul_2exp(z(*c[i]), z(*c[i]), mp_bitcnt_t(e[i] - k));
  }
  mpz_set_ui(z(h.w), 0);
  mpz_setbit(z(h.w), mp_bitcnt_t(-k));
}

void hom_point(HomPoint& h, const Point3& a) {
  mpz_lcm(z(h.w), a.x.get_den_mpz_t(), a.y.get_den_mpz_t());
  mpz_lcm(z(h.w), z(h.w), a.z.get_den_mpz_t());
  const Rational* q[3] = {&a.x, &a.y, &a.z};
  Integer* c[3] = {&h.x, &h.y, &h.z};
  for (int i = 0; i < 3; ++i) {
    mpz_divexact(z(*c[i]), z(h.w), q[i]->get_den_mpz_t());
    mpz_mul(z(*c[i]), z(*c[i]), q[i]->get_num_mpz_t());
  }
}

HomPoint hom_point(const Vec3d& a) {
  HomPoint h;
  hom_point(h, a);
  return h;
}
HomPoint hom_point(const Point3& a) {
  HomPoint h;
  hom_point(h, a);
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
      if (poly.coordinates().is_double(v)) hom_point(out[v], poly.approx(v));
      else hom_point(out[v], poly.point(v));
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

void ObstacleGeometry::m_hom(HomPoint& out, Index v) const {
  sub(out, p_hom[sum.vertex_origin[v].first], q_hom[neg_to_q[sum.vertex_origin[v].second]]);
}
HomPoint ObstacleGeometry::m_hom(Index v) const {
  HomPoint h;
  m_hom(h, v);
  return h;
}

namespace {

// s − x for x the point of the feature `feat` of M closest to s, into out,
// and |s − x|² into d2 (scratch: h[0..2], k[0..2]).
//   vertex v: s − v;
//   edge a→b, r = s − a, e = b − a: (r⟨e,e⟩ − ⟨r,e⟩e) / ⟨e,e⟩, whose
//     squared length is (⟨r,r⟩⟨e,e⟩ − ⟨r,e⟩²) / ⟨e,e⟩;
//   facet n·x = d: t·n with t = (n·s − d) / |n|², squared length
//     (n·s − d)² / |n|².
void closest_offset(const ObstacleGeometry& g, const Feature& feat, const HomPoint& s, Quotient& d2, HomPoint& out,
                    ExactScratch& sc) {
  const ConvexPolytope& mm = g.m();
  switch (feat.dim) {
    case FeatureDim::vertex: {
      g.m_hom(sc.h[0], feat.index);
      sub(out, s, sc.h[0]);
      dot_num(d2.num, out, out);
      mpz_mul(z(d2.den), z(out.w), z(out.w));
      return;
    }
    case FeatureDim::edge: {
      HomPoint &a = sc.h[0], &e = sc.h[1], &r = sc.h[2];
      Integer &ee = sc.k[0], &re = sc.k[1];
      g.m_hom(a, mm.origin(2 * feat.index));
      g.m_hom(e, mm.target(2 * feat.index));
      sub(e, e, a);
      sub(r, s, a);
      dot_num(ee, e, e);
      dot_num(re, r, e);
      dot_num(sc.k[2], r, r);
      mpz_mul(z(d2.num), z(sc.k[2]), z(ee));
      mpz_submul(z(d2.num), z(re), z(re));
      mpz_mul(z(d2.den), z(r.w), z(r.w));
      mpz_mul(z(d2.den), z(d2.den), z(ee));
      scale_add(out, r, ee, re, e, true);
      return;
    }
    case FeatureDim::facet: {
      const Plane& pl = mm.plane(feat.index);
      Integer& t = sc.k[0];
      plane_dot(t, pl, s);
      mpz_submul(z(t), z(pl.d), z(s.w));
      mpz_mul(z(d2.num), z(t), z(t));
      mpz_mul(z(out.w), z(s.w), z(g.n2[feat.index]));
      mpz_mul(z(d2.den), z(out.w), z(s.w));
      mpz_mul(z(out.x), z(t), z(pl.a));
      mpz_mul(z(out.y), z(t), z(pl.b));
      mpz_mul(z(out.z), z(t), z(pl.c));
      return;
    }
  }
  throw std::logic_error("proximity: unknown feature dimension");
}

// The point of P in x = p − q for x in the feature `feat` of M, from x's
// barycentric coordinates in it (an edge: its parameter; a facet: a
// triangle of its fan holding x), as decompose does on rationals, into out
// (scratch: h[0..3], k[0..7]; x is none of them).
void decompose_p(const ObstacleGeometry& g, const Feature& feat, const HomPoint& x, HomPoint& out, ExactScratch& sc) {
  const ConvexPolytope& mm = g.m();
  auto pv = [&](Index v) -> const HomPoint& { return g.p_hom[g.sum.vertex_origin[v].first]; };
  if (feat.dim == FeatureDim::vertex) return set(out, pv(feat.index));
  if (feat.dim == FeatureDim::edge) {
    // t = ⟨x − a, e⟩ / ⟨e, e⟩ = ⟨r, e⟩·w_e / (w_r·⟨e, e⟩) on the numerators;
    // p = pa + t·(pb − pa).
    const Index a = mm.origin(2 * feat.index), b = mm.target(2 * feat.index);
    HomPoint &ha = sc.h[0], &e = sc.h[1], &r = sc.h[2], &dp = sc.h[3];
    Integer &tn = sc.k[0], &td = sc.k[1];
    g.m_hom(ha, a);
    g.m_hom(e, b);
    sub(e, e, ha);
    sub(r, x, ha);
    dot_num(tn, r, e);
    mpz_mul(z(tn), z(tn), z(e.w));
    dot_num(td, e, e);
    mpz_mul(z(td), z(td), z(r.w));
    const HomPoint& pa = pv(a);
    sub(dp, pv(b), pa);
    const HomPoint* pts[2] = {&pa, &dp};
    const Integer* c[2] = {&td, &tn};
    return combination(out, pts, c, 2, td, sc.k[6], sc.k[7]);
  }
  const Plane& n = mm.plane(feat.index);
  // The fan of facet_vertices: vs[0] = origin of the facet's halfedge.
  const Index first = mm.facet_halfedge(feat.index);
  const Index v0 = mm.origin(first);
  HomPoint &w0 = sc.h[0], &r = sc.h[1], &ei = sc.h[2], &ej = sc.h[3];
  Integer &area = sc.k[0], &li = sc.k[1], &lj = sc.k[2], &t = sc.k[3], &l0 = sc.k[4], &tmp = sc.k[5];
  g.m_hom(w0, v0);
  sub(r, x, w0);
  for (Index hi = mm.next(first); mm.next(hi) != first; hi = mm.next(hi)) {
    const Index vi = mm.origin(hi), vj = mm.origin(mm.next(hi));
    g.m_hom(ei, vi);
    sub(ei, ei, w0);
    g.m_hom(ej, vj);
    sub(ej, ej, w0);
    // li = ⟨r × ej, n⟩·w_i / (w_r·A), lj = ⟨ei × r, n⟩·w_j / (w_r·A) with
    // A = ⟨ei × ej, n⟩ (the numerators' area), l0 = 1 − li − lj: all over
    // T = w_r·A, made positive.
    cross_dot(area, ei, ej, n, tmp);
    cross_dot(li, r, ej, n, tmp);
    mpz_mul(z(li), z(li), z(ei.w));
    cross_dot(lj, ei, r, n, tmp);
    mpz_mul(z(lj), z(lj), z(ej.w));
    if (sgn(area) < 0) mpz_neg(z(area), z(area)), mpz_neg(z(li), z(li)), mpz_neg(z(lj), z(lj));
    mpz_mul(z(t), z(r.w), z(area));
    mpz_sub(z(l0), z(t), z(li));
    mpz_sub(z(l0), z(l0), z(lj));
    if (sgn(li) < 0 || sgn(lj) < 0 || sgn(l0) < 0) continue;
    const HomPoint* pts[3] = {&pv(v0), &pv(vi), &pv(vj)};
    const Integer* c[3] = {&l0, &li, &lj};
    return combination(out, pts, c, 3, t, sc.k[6], sc.k[7]);
  }
  throw std::logic_error("proximity: point not in the facet it was attributed to");
}

// The point p of P with x = p − q, q in Q, for x in the face w.m of M (as
// split), into out: a translate of x when Q's face is a vertex, P's vertex
// when P's is, Cramer's rule on two skew edges, else decompose_p.  Cramer's
// rule and decompose_p read x only through ⟨x, e⟩ and ⟨x × e, n⟩ for vectors
// e parallel to w.m and n normal to it, so they are given y instead, any
// point with y − x orthogonal to w.m: for a closest point x of M, s itself
// (s − x lies in w.m's normal cone), whose denominator is far smaller than
// x's.  Scratch: h[0..3], k[0..7] (x and y are none of them).
void split_p(const ObstacleGeometry& g, const Witness& w, const HomPoint& x, const HomPoint& y, HomPoint& out,
             ExactScratch& sc) {
  if (w.q.dim == FeatureDim::vertex) return add(out, x, g.q_hom[w.q.index]);
  if (w.p.dim == FeatureDim::vertex) return set(out, g.p_hom[w.p.index]);
  if (w.p.dim == FeatureDim::edge && w.q.dim == FeatureDim::edge) {
    const Index hp = 2 * w.p.index, hq = 2 * w.q.index;
    const HomPoint& p0 = g.p_hom[g.p.origin(hp)];
    const HomPoint& q0 = g.q_hom[g.q.origin(hq)];
    HomPoint &u = sc.h[0], &v = sc.h[1], &wv = sc.h[2];
    Integer &uv = sc.k[0], &uu = sc.k[1], &vv = sc.k[2], &det = sc.k[3], &num = sc.k[4], &den = sc.k[5];
    sub(u, g.p_hom[g.p.target(hp)], p0);
    sub(v, g.q_hom[g.q.target(hq)], q0);
    dot_num(uv, u, v);
    dot_num(uu, u, u);
    dot_num(vv, v, v);
    mpz_mul(z(det), z(uv), z(uv));
    mpz_submul(z(det), z(uu), z(vv));  // −|u × v|² on the numerators
    if (sgn(det) != 0) {
      // α = (⟨u,v⟩⟨w,v⟩ − ⟨v,v⟩⟨w,u⟩) / det on the numerators of u, v and
      // w = x − p0 + q0, over w's denominator: p = p0 + α·u.
      add(wv, y, q0);
      sub(wv, wv, p0);
      dot_num(sc.k[6], wv, v);
      mpz_mul(z(num), z(uv), z(sc.k[6]));
      dot_num(sc.k[6], wv, u);
      mpz_submul(z(num), z(vv), z(sc.k[6]));
      mpz_mul(z(den), z(wv.w), z(det));
      if (sgn(den) < 0) mpz_neg(z(num), z(num)), mpz_neg(z(den), z(den));
      // p0 + (num / den)·u_numerators = (p0·den + p0.w·num·u) / (p0.w·den)
      Integer& k = sc.k[7];
      mpz_mul(z(k), z(p0.w), z(num));
      return scale_add(out, p0, den, k, u, false);
    }
  }
  decompose_p(g, w.m, y, out, sc);
}

// The common point p = q + s of P and Q + s for s in M (common_point on
// rationals), into out: for s inside M, with c the interior point,
// dir = s − c, f the stabbed facet n·x = d, b = ⟨n, dir⟩ and
// a = d·w_c − ⟨n, c⟩ on the numerators, the exit point is
// y = (c·b + a·dir) / (w_c·b) and s = (1 − λ)·c + λ·y with
// λ = w_c·b / (a·w_dir), so p = ((a·w_dir − w_c·b)·p_c + w_c·b·p_y) / (a·w_dir).
// Scratch: h[4..6], k[8..11], and split_p's.
void common_p(const ObstacleGeometry& g, const Witness& w, ContactStatus status, const HomPoint& s, HomPoint& out,
              ExactScratch& sc) {
  if (status == ContactStatus::touching) return split_p(g, w, s, s, out, sc);
  const HomPoint& c = g.center_hom;
  HomPoint &dir = sc.h[4], &y = sc.h[5], &py = sc.h[6];
  Integer &b = sc.k[8], &a = sc.k[9], &total = sc.k[10], &cb = sc.k[11];
  sub(dir, s, c);
  const Plane& n = g.m().plane(w.facet);
  plane_dot(b, n, dir);
  if (sgn(b) <= 0) return set(out, g.p_center_hom);  // s == c
  plane_dot(a, n, c);
  mpz_neg(z(a), z(a));
  mpz_addmul(z(a), z(n.d), z(c.w));
  scale_add(y, c, b, a, dir, false);
  split_p(g, w, y, y, py, sc);
  mpz_mul(z(total), z(a), z(dir.w));
  mpz_mul(z(cb), z(c.w), z(b));
  mpz_sub(z(a), z(total), z(cb));  // a is not needed any more: the weight of p_c
  const HomPoint* pts[2] = {&g.p_center_hom, &py};
  const Integer* k[2] = {&a, &cb};
  combination(out, pts, k, 2, total, sc.k[6], sc.k[7]);
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
void hom_of(detail::HomPoint& h, const std::shared_ptr<Point3>& exact, const Vec3d& d) {
  if (exact) detail::hom_point(h, *exact);
  else detail::hom_point(h, d);
}
const Quotient& zero_quotient() {
  static const Quotient z;
  return z;
}
const QuotientPoint& zero_quotient_point() {
  static const QuotientPoint z;
  return z;
}
// q in lowest terms, kept in r (computed once: `have`).
const Rational& lowest_terms(const Quotient& q, Rational& r, bool& have) {
  if (!have) detail::set_ratio(r, q.num, q.den), have = true;
  return r;
}
// The nearest double of sqrt(q), kept in d.
double root(const Quotient& q, double& d, bool& have) {
  if (!have) d = std::sqrt(q.to_double()), have = true;
  return d;
}
}  // namespace

const detail::HomPoint& DistanceResult::s_hom(detail::DistanceExact& e) const {
  if (!e.have_s) hom_of(e.s, s_exact_, sd_), e.have_s = true;
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
    detail::set_zero(e.offset);
    mpz_set_ui(e.squared_distance_q.num.get_mpz_t(), 0);
    mpz_set_ui(e.squared_distance_q.den.get_mpz_t(), 1);
  } else {
    detail::closest_offset(*geo_, witness.m, s_hom(e), e.squared_distance_q, e.offset, e.scratch);
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
    detail::set_zero(e.p);
  } else {
    const detail::HomPoint& s = s_hom(e);
    if (status != ContactStatus::separate) {
      detail::common_p(*geo_, witness, status, s, e.p, e.scratch);
    } else if (witness.q.dim == FeatureDim::vertex) {
      detail::sub(e.scratch.h[4], s, e.offset);
      detail::split_p(*geo_, witness, e.scratch.h[4], s, e.p, e.scratch);
    } else {
      detail::split_p(*geo_, witness, s, s, e.p, e.scratch);  // x is not read
    }
    if (e.translated) {
      detail::hom_point(e.scratch.h[4], e.u);
      detail::add(e.p, e.p, e.scratch.h[4]);
    }
  }
  e.have_p = true;
  return e;
}

const Quotient& DistanceResult::squared_distance_quotient() const { return compute_offset().squared_distance_q; }
const Rational& DistanceResult::squared_distance() const {
  detail::DistanceExact& e = compute_offset();
  return lowest_terms(e.squared_distance_q, e.squared_distance, e.have_squared_distance);
}
double DistanceResult::distance() const {
  detail::DistanceExact& e = compute_offset();
  return root(e.squared_distance_q, e.distance, e.have_distance);
}
const QuotientPoint& DistanceResult::direction_quotient() const { return compute_offset().offset; }
const Point3& DistanceResult::direction() const {
  detail::DistanceExact& e = compute_offset();
  if (!e.have_direction) e.direction = detail::to_point(e.offset), e.have_direction = true;
  return e.direction;
}
const QuotientPoint& DistanceResult::point_p_quotient() const { return compute_p().p; }
const QuotientPoint& DistanceResult::point_q_quotient() const {
  detail::DistanceExact& e = compute_p();
  if (!e.have_q) {
    if (status == ContactStatus::separate) detail::add(e.q, e.p, e.offset);
    else detail::set(e.q, e.p);
    e.have_q = true;
  }
  return e.q;
}
const Point3& DistanceResult::point_p() const {
  detail::DistanceExact& e = compute_p();
  if (!e.have_point_p) e.point_p = detail::to_point(e.p), e.have_point_p = true;
  return e.point_p;
}
const Point3& DistanceResult::point_q() const {
  detail::DistanceExact& e = exact();
  if (!e.have_point_q) {
    point_q_quotient();
    e.point_q = status == ContactStatus::separate ? detail::to_point(e.q) : point_p();
    e.have_point_q = true;
  }
  return e.point_q;
}

// ---------------------------------------------------------------------------
// DepthResult.

Point3 DepthResult::point() const { return s_exact_ ? *s_exact_ : Point3(sd_.x, sd_.y, sd_.z); }

// For the witness facet's plane n·x = d and s = S / w: g = d·w − ⟨n, S⟩ > 0,
// the squared depth g² / (w²·|n|²) and the translation −g·n / (w·|n|²);
// their lowest terms when asked for.  Called only on penetrating answers.
detail::DepthExact& DepthResult::exact() const {
  if (!exact_) exact_ = std::make_shared<detail::DepthExact>();
  detail::DepthExact& e = *exact_;
  if (e.have) return e;
  e.have = true;
  const Plane& pl = geo_->m().plane(witness.facet);
  detail::HomPoint& s = e.s;
  hom_of(s, s_exact_, sd_);
  detail::plane_dot(e.gap, pl, s);
  mpz_neg(e.gap.get_mpz_t(), e.gap.get_mpz_t());
  mpz_addmul(e.gap.get_mpz_t(), pl.d.get_mpz_t(), s.w.get_mpz_t());
  mpz_mul(e.w.get_mpz_t(), s.w.get_mpz_t(), geo_->n2[witness.facet].get_mpz_t());
  mpz_mul(e.squared_depth_q.num.get_mpz_t(), e.gap.get_mpz_t(), e.gap.get_mpz_t());
  mpz_mul(e.squared_depth_q.den.get_mpz_t(), e.w.get_mpz_t(), s.w.get_mpz_t());
  return e;
}

// Unless penetrating the values are zeros: no storage is made for them.
const Quotient& DepthResult::squared_depth_quotient() const {
  return status == ContactStatus::penetrating && geo_ ? exact().squared_depth_q : zero_quotient();
}
const Rational& DepthResult::squared_depth() const {
  static const Rational zero(0);
  if (status != ContactStatus::penetrating || !geo_) return zero;
  detail::DepthExact& e = exact();
  return lowest_terms(e.squared_depth_q, e.squared_depth, e.have_squared_depth);
}
double DepthResult::depth() const {
  if (status != ContactStatus::penetrating || !geo_) return 0;
  detail::DepthExact& e = exact();
  return root(e.squared_depth_q, e.depth, e.have_depth);
}
const QuotientPoint& DepthResult::direction_quotient() const {
  if (status != ContactStatus::penetrating || !geo_) return zero_quotient_point();
  detail::DepthExact& e = exact();
  if (!e.have_direction_q) {
    const Plane& pl = geo_->m().plane(witness.facet);
    mpz_mul(e.direction_q.x.get_mpz_t(), e.gap.get_mpz_t(), pl.a.get_mpz_t());
    mpz_mul(e.direction_q.y.get_mpz_t(), e.gap.get_mpz_t(), pl.b.get_mpz_t());
    mpz_mul(e.direction_q.z.get_mpz_t(), e.gap.get_mpz_t(), pl.c.get_mpz_t());
    mpz_neg(e.direction_q.x.get_mpz_t(), e.direction_q.x.get_mpz_t());
    mpz_neg(e.direction_q.y.get_mpz_t(), e.direction_q.y.get_mpz_t());
    mpz_neg(e.direction_q.z.get_mpz_t(), e.direction_q.z.get_mpz_t());
    mpz_set(e.direction_q.w.get_mpz_t(), e.w.get_mpz_t());
    e.have_direction_q = true;
  }
  return e.direction_q;
}
const Point3& DepthResult::direction() const {
  if (status != ContactStatus::penetrating || !geo_) return zero_point();
  detail::DepthExact& e = exact();
  if (!e.have_direction) {
    e.direction = detail::to_point(direction_quotient());
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
