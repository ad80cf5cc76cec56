// minksum — exact signs on points placed by affine maps x ↦ A x + t: the
// predicates of proximity under rigid motion (proximity/rigid.cpp,
// docs/proximity.md "Rigid motion").
//
// A placement is exact: A and t have rational entries (a rotation by an
// integer quaternion is the rational matrix of transform.hpp; a 3×3 matrix of
// doubles is taken exactly as given, each double a dyadic rational).  The
// placed point A p + t of an exact vertex p is never rounded: every sign below
// is the sign of an exact polynomial in the entries of A, t, p and of the
// direction n (a double vector, taken exactly).
//
// Filters.  Two stages before rationals.
//
// Stage 1, doubles (the common case: A, t, n and the points all doubles, as
// for a double rotation matrix and vertices read from a mesh file), with a
// derived error bound.  u = 2^-52 bounds the relative error of one IEEE 754
// operation in ANY rounding mode when its result is normal (and an addition
// whose result is subnormal is exact); γ_k = k u / (1 − k u).  Every input
// must be zero or of magnitude in [2^-240, 2^240) (checked; else stage 2):
// then every product of two or three inputs lies in [2^-720, 2^720), every
// non-zero difference of two inputs is at least 2^-292, and no operation
// below overflows or leaves the normal range except exact additions.
//  * Climb sign S = Σ_c u_c (b_c − a_c), u_c = Σ_r A_rc n_r (exact).  The
//    doubles û_c = fl(Σ_r A_rc n_r) (three products, two additions, at most
//    four roundings per term: |û_c − u_c| ≤ γ_3 U_c with U_c = Σ_r |A_rc||n_r|),
//    d̂_c = fl(b_c − a_c) (|d̂_c − d_c| ≤ u |d_c| ≤ u D_c, D_c = |a_c| + |b_c|)
//    and ŝ = fl(Σ_c û_c d̂_c) give
//      |ŝ − S| ≤ Σ_c |û_c d̂_c − u_c d_c| + γ_3 Σ_c |û_c d̂_c|
//              ≤ [γ_3 (1 + u) + u + γ_3 (1 + γ_3)(1 + u)] Σ_c U_c D_c < 7.01 u B
//    with B = Σ_c U_c D_c.  The bound computed, B̂, is the same expression on
//    the absolute values: at most seven roundings of non-negative normal
//    doubles on any path, so B̂ ≥ (1 − u)^7 B.  The test 2^49 |ŝ| > B̂ (the
//    scaling is exact) means |ŝ| > 8 u B̂ ≥ 8 (1 − u)^7 u B > 7.01 u B ≥
//    |ŝ − S|, so sign ŝ = sign S.  B̂ = 0 only when every U_c D_c is 0 (no
//    product of inputs in range rounds to 0): then every term of S is 0.
//  * Gap sign G = Σ_r n_r (x_r − y_r), x = A_q q + t_q, y = A_p p + t_p.  x̂_r
//    = fl(Σ_c A_q,rc q_c + t_q,r) (four terms, at most four roundings each:
//    |x̂_r − x_r| ≤ γ_4 X_r^q with X_r^q the sum of the terms' absolute
//    values), ŷ_r likewise, the difference one rounding more, and ĝ =
//    fl(Σ_r n_r fl(x̂_r − ŷ_r)):
//      |ĝ − G| ≤ (1 + γ_3)(γ_4 + u (1 + γ_4)) Σ_r |n_r| X_r + γ_3 (1 + γ_4)(1 + u) Σ_r |n_r| X_r
//              < 8.01 u B,   B = Σ_r |n_r| X_r, X_r = X_r^q + X_r^p.
//    B̂ takes at most eight roundings: B̂ ≥ (1 − u)^8 B, and the test
//    2^48 |ĝ| > B̂ gives |ĝ| > 16 (1 − u)^8 u B > |ĝ − G|.
//  * The analysis holds if the compiler contracts a product and a sum into
//    an FMA (one rounding fewer); not under -ffast-math, which the kernel
//    refuses.
//
// Stage 2 (any input: rationals, or out of stage 1's range): each sign is
// evaluated in interval arithmetic
// (CGAL::Interval_nt, every operation rounded outward under a guard that sets
// the rounding mode upward and restores the caller's), on enclosures of the
// exact inputs (Bounds: the two doubles around a rational, a point interval
// when it is a double).  Interval arithmetic is an inclusion: the computed
// interval contains the exact value of the polynomial, whatever the caller's
// rounding mode, through overflow (bounds go to ±∞) and underflow (directed
// rounding); so an interval that excludes 0 gives the exact sign, [0, 0]
// proves the value 0, and anything else falls back to the same polynomial in
// GMP rationals — or, for the climb sign with A and the points doubles, in
// GMP integers: u_c = Σ_r A_rc n_r is a sum of products of two doubles
// m 2^e, hence an integer U_c over 2^eu (eu the least e_A + e_n of its
// non-zero products), b_c − a_c an integer B_c over 2^eb (eb the least
// exponent of the six coordinates), and S = 2^(eu + eb) Σ_c U_c B_c
// exactly.  No bound to derive, and none to get wrong: the enclosure is
// the proof (R. E. Moore, "Interval Analysis", Prentice-Hall 1966; the
// technique of CGAL's filtered predicates, S. Pion, "Interval arithmetic: an
// efficient implementation and an application to computational geometry",
// Workshop on Applications of Interval Analysis to Systems and Control, 1999).
// The tests (PlacedPredicates.*) check every sign against the rational
// evaluation in all four rounding modes, on and near zero, with inputs in
// and out of stage 1's range.
#pragma once

#include <minksum/kernel.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace minksum {

// An interval of doubles [lo, hi] that contains an exact rational.
struct Bounds {
  double lo = 0, hi = 0;
};
struct PointBounds {
  Bounds x, y, z;
  // Each coordinate is a double (lo = hi), zero or of magnitude in
  // [2^-240, 2^240): the point may enter the doubles stage (set by
  // point_bounds).
  bool doubles = false;
};
// The smallest such interval around q (lo = hi = q when q is a double).
Bounds rational_bounds(const Rational& q);
PointBounds point_bounds(const Point3& p);

// x ↦ A x + t with exact rational entries, kept in their cheapest exact
// form: doubles when the caller gave doubles (no GMP number is made for them
// until an exact stage needs one), rationals otherwise.
class PlacedMap {
 public:
  // The identity.
  PlacedMap();
  // A matrix of doubles (row-major) and a translation of doubles, each taken
  // exactly as given.  The constructors throw UsageError for a non-finite
  // entry and unless det A > 0 (decided exactly): an invertible map that
  // keeps orientation maps a convex polytope onto one with the same faces
  // and the same outward sides.
  PlacedMap(const std::array<double, 9>& a, const Vec3d& t);
  PlacedMap(const std::array<double, 9>& a, const Point3& t);
  // A rational matrix and translation.
  PlacedMap(const std::array<std::array<Rational, 3>, 3>& a, const Point3& t);
  // The rotation of the non-zero integer quaternion q = (a, b, c, d) (the
  // matrix of transform.hpp) followed by the translation t.
  static PlacedMap rotation(const std::array<Integer, 4>& q, const Point3& t);
  // The same with a translation of doubles taken exactly (throws UsageError
  // unless finite).
  static PlacedMap rotation(const std::array<Integer, 4>& q, const Vec3d& t);
  // The same for machine-integer components (a batch of poses from numpy's
  // int64 arrays: no GMP number is made for components of at most 2^25).
  // Its own name: rotation({1, 2, 3, 4}, t) stays unambiguous.
  static PlacedMap rotation64(const std::array<std::int64_t, 4>& q, const Vec3d& t);

  // The nearest doubles of A (row-major) and t: for the searches, never for
  // a decision.
  const std::array<double, 9>& approx_a() const { return approx_a_; }
  const Vec3d& approx_t() const { return approx_t_; }
  const std::array<Bounds, 9>& bounds_a() const { return bounds_a_; }
  const PointBounds& bounds_t() const { return bounds_t_; }
  // The exact entries (made on each call when they are doubles: the exact
  // stages only).
  Rational a(int row, int col) const;
  Point3 t() const;
  // True when A's entries and t's coordinates are all doubles.
  bool doubles() const { return !exact_a_ && !small_rotation_ && !exact_t_; }
  // True when A's entries are all doubles (t may be any rational).
  bool linear_doubles() const { return !exact_a_ && !small_rotation_; }
  // A p + t and A p, exactly.
  Point3 apply(const Point3& p) const;
  Point3 apply_linear(const Point3& p) const;

 private:
  void set_rational_a(const std::array<std::array<Rational, 3>, 3>& a);
  void set_rotation(const std::array<Integer, 4>& q);  // the matrix of rotation(q, t)
  bool set_small_rotation(const std::array<std::int64_t, 4>& q);  // its machine-integer path, when it applies
  void set_rotation_gmp(const std::array<Integer, 4>& q);          // and its GMP path
  void set_double_a(const std::array<double, 9>& a);
  void set_t(const Point3& t);
  void set_double_t(const Vec3d& t);  // throws UsageError unless finite
  void check_determinant() const;
  void set_fast();
  std::array<double, 9> approx_a_{};
  Vec3d approx_t_;
  std::array<Bounds, 9> bounds_a_{};
  PointBounds bounds_t_;
  // The exact values when they are not the doubles above.
  std::shared_ptr<const std::array<std::array<Rational, 3>, 3>> exact_a_;
  std::shared_ptr<const Point3> exact_t_;
  // Or A is the rotation of this quaternion, components of at most 2^25 in
  // magnitude (rotation()): a() makes its exact entries.
  std::array<std::int64_t, 4> quaternion_{};
  bool small_rotation_ = false;
  // Stage 1 may read approx_a_ and approx_t_: they are the exact entries,
  // each zero or of magnitude in [2^-240, 2^240).
  bool fast_ = false;

 public:
  bool filter_ready() const { return fast_; }
};

// A direction n (doubles, taken exactly) pulled back through the linear part
// of a placement: u = Aᵀ n, so that n · (A x) = u · x.  Built once per
// direction; the signs below read its enclosure and, when it cannot decide,
// the exact u (computed on first use).
class PulledDirection {
 public:
  // Throws UsageError unless n is finite.
  PulledDirection(const PlacedMap& m, const Vec3d& n);
  // sign n · A (b − a) = sign u · (b − a): whether b lies beyond a along n
  // once both are placed (the step of a support climb).  Degree 3 in the
  // entries of n, A and the points.
  int difference_sign(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const {
    const int s = first_stage(ab, bb);
    return s != kOpen ? s : difference_sign_later(a, ab, b, bb);
  }
  // Its first two stages alone (doubles, then intervals): −1, 0 or +1 when
  // they decide, the sign above; kOpen when they do not.
  static constexpr int kOpen = 2;
  int difference_sign_filter(const PointBounds& ab, const PointBounds& bb) const {
    const int s = first_stage(ab, bb);
    return s != kOpen ? s : second_stage(ab, bb);
  }
  const Vec3d& direction() const { return n_; }

 private:
  const PlacedMap* m_;
  Vec3d n_;
  mutable std::array<Bounds, 3> u_{};
  mutable bool enclosure_ = false;
  void make_enclosure() const;
  // Stage 1 (the bound at the top of this header), or kOpen.
  int first_stage(const PointBounds& ab, const PointBounds& bb) const {
    if (fast_ && ab.doubles && bb.doubles) {
      const double ax = ab.x.lo, ay = ab.y.lo, az = ab.z.lo, bx = bb.x.lo, by = bb.y.lo, bz = bb.z.lo;
      const double s = (uf_[0] * (bx - ax) + uf_[1] * (by - ay)) + uf_[2] * (bz - az);
      const double m = (um_[0] * (std::fabs(ax) + std::fabs(bx)) + um_[1] * (std::fabs(ay) + std::fabs(by))) +
                       um_[2] * (std::fabs(az) + std::fabs(bz));
      const double scaled = 0x1p+49 * s;
      if (scaled > m) return 1;
      if (scaled < -m) return -1;
      if (m == 0) return 0;
    }
    return kOpen;
  }
  // Stage 2 (intervals), or kOpen.
  int second_stage(const PointBounds& ab, const PointBounds& bb) const;
  // Stages 2 and 3.
  int difference_sign_later(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  int difference_sign_integers(const PointBounds& ab, const PointBounds& bb) const;
  // Stage 1: û and U (see the top), when A and n are doubles in range.
  bool fast_ = false;
  std::array<double, 3> uf_{}, um_{};
  mutable std::optional<Point3> exact_;
};

// The interval stage of sign N · A (b − a) for an exact rational direction
// N (a plane's normal, of any size: the feature plane's normals on
// PlacedFrame integers exceed the range of doubles).  N 2^−k, with 2^k
// within a factor two of its largest coordinate's magnitude (a positive
// factor: the same sign), is enclosed coordinate by coordinate
// (rational_bounds), pulled back through A's enclosure and dotted with the
// enclosure of b − a, all in interval arithmetic (outward rounding, as in
// stage 2 above): an interval that excludes 0 gives the sign, [0, 0] proves
// 0.  Otherwise kOpen, and the caller evaluates the sign exactly.
class PulledNormalFilter {
 public:
  static constexpr int kOpen = 2;
  PulledNormalFilter(const PlacedMap& m, const Point3& n);
  // −1, 0 or +1, or kOpen (a, b: enclosures of the points).
  int difference_sign(const PointBounds& a, const PointBounds& b) const;

 private:
  std::array<Bounds, 3> u_{};  // an enclosure of Aᵀ N 2^−k
  bool usable_ = false;        // N ≠ 0 and the enclosure finite
};

// sign n · ((A_q q + t_q) − (A_p p + t_p)): the gap along n between the
// placed points p of P and q of Q.  With p the support of placed P along n
// and q the support of placed Q along −n, a positive sign proves that the
// plane normal to n separates them strictly, zero that it touches both.
// Throws UsageError unless n is finite.
int placed_gap_sign(const Vec3d& n, const PlacedMap& mp, const Point3& p, const PointBounds& pb, const PlacedMap& mq,
                    const Point3& q, const PointBounds& qb);
// Its doubles and interval stages alone: −1, 0 or +1 when they decide (the
// sign of placed_gap_sign), kGapOpen when they do not (a gap within
// rounding of 0, as along a plane that touches both bodies: then only the
// exact stage decides).  A caller with a cheaper certificate to try first
// defers that stage.
inline constexpr int kGapOpen = 2;
int placed_gap_filter(const Vec3d& n, const PlacedMap& mp, const PointBounds& pb, const PlacedMap& mq,
                      const PointBounds& qb);

// Whether the origin lies strictly inside the tetrahedron of the four points
// d_k = (A_p p_k + t_p) − (A_q q_k + t_q), points of the Minkowski difference
// of placed P and placed Q: orient3d(d_0, d_1, d_2, d_3) ≠ 0 and each of the
// four orientations with d_k replaced by the origin has its sign (the
// barycentric coordinates of the origin are all positive).  False for a flat
// tetrahedron and for the origin on its boundary.  Degree 3 in the d_k.
bool placed_tetrahedron_holds_origin(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 4>& p,
                                     const std::array<const PointBounds*, 4>& pb, const std::array<const Point3*, 4>& q,
                                     const std::array<const PointBounds*, 4>& qb);
// Its interval stage alone: 1 or 0 when the intervals decide (the answer
// of placed_tetrahedron_holds_origin), kTetrahedronOpen when some volume's
// interval holds 0 (the origin within rounding of the tetrahedron's
// boundary, as on touching poses: then only the exact stage decides).  A
// caller with a cheaper certificate to try first defers that stage.
inline constexpr int kTetrahedronOpen = 2;
int placed_tetrahedron_filter(const PlacedMap& mp, const PlacedMap& mq, const std::array<const PointBounds*, 4>& pb,
                              const std::array<const PointBounds*, 4>& qb);

// The point v nearest the origin of the affine hull of k = 1, 2 or 3 points
// d_j = (A_p p_j + t_p) − (A_q q_j + t_q) of the Minkowski difference of
// placed P and placed Q, with v = Σ λ_j d_j, Σ λ_j = 1: the certificate of a
// separation distance under rigid motion (rigid_proximity.hpp).  Every value
// is a polynomial in the d_j, so every sign below is exact:
//   k = 1: v = d_0, λ_0 = 1;
//   k = 2: e = d_1 − d_0, g = e·e, λ_0 = (d_1·e)/g, λ_1 = −(d_0·e)/g,
//          g v = V = (d_1·e) d_0 − (d_0·e) d_1;
//   k = 3: n = (d_1 − d_0) × (d_2 − d_0), g = n·n, λ_0 = n·(d_1 × d_2)/g,
//          λ_1 = n·(d_2 × d_0)/g, λ_2 = n·(d_0 × d_1)/g (the areas of the
//          triangles the projection of the origin makes), g v = V = (d_0·n) n.
// g > 0 exactly when the d_j are affinely independent.  Signs are evaluated
// on intervals (enclosures of the exact inputs, outward rounding), then in
// rationals when an interval holds 0 — stage 2 and 3 of the top of this
// header.
class PlacedSimplexPoint {
 public:
  // The k pairs (p_j, q_j); the pointers must outlive the object.
  PlacedSimplexPoint(const PlacedMap& mp, const PlacedMap& mq, int k, const std::array<const Point3*, 3>& p,
                     const std::array<const PointBounds*, 3>& pb, const std::array<const Point3*, 3>& q,
                     const std::array<const PointBounds*, 3>& qb);
  ~PlacedSimplexPoint();
  int k() const { return k_; }
  // g > 0: the d_j are affinely independent.
  bool independent() const;
  // The sign of λ_j (requires independent()).
  int lambda_sign(int j) const;
  // v ≠ 0 (requires independent()).
  bool nonzero() const;
  // sign (−v) · A_p (b − a) for points a, b of P (toward_q: whether b lies
  // further than a from placed P towards placed Q along −v), and sign
  // v · A_q (b − a) for points of Q (whether b lies further back along
  // −v).  A vertex of P no neighbour of which has a positive sign maximises
  // −v · x over placed P; one of Q with none minimises it over placed Q.
  int climb_sign_p(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  int climb_sign_q(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  // An enclosure of |v|² (requires independent()).
  Bounds squared_norm_bounds() const;
  // Doubles near λ_j (requires independent()): for the caller's doubles only.
  double lambda_approx(int j) const;
  // The exact values (rational arithmetic; requires independent()).
  Rational squared_norm() const;
  Rational lambda(int j) const;
  // x = Σ λ_j (A_p p_j + t_p) and y = Σ λ_j (A_q q_j + t_q): x − y = v.
  std::pair<Point3, Point3> points() const;

 private:
  struct Exact;
  const Exact& exact() const;
  int climb_sign(bool on_p, const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  const PlacedMap *mp_, *mq_;
  int k_;
  std::array<const Point3*, 3> p_, q_;
  // The exact stage works on integers when the maps and the points are
  // doubles (all dyadic: one common power of two scales them to integers).
  bool dyadic_ = false;
  std::array<const PointBounds*, 3> pb_, qb_;
  // Interval stage: g, the λ numerators l_j (λ_j = l_j / g), V = g v and
  // the pulled directions −A_pᵀ V and A_qᵀ V.
  Bounds g_{}, vv_{};
  std::array<Bounds, 3> l_{}, v_{}, up_{}, uq_{};
  mutable std::unique_ptr<Exact> exact_;
};

// The plane through three points d_j = (A_p p_j + t_p) − (A_q q_j + t_q) of
// the Minkowski difference D of placed P and placed Q, with normal
// n = (d_1 − d_0) × (d_2 − d_0) and offset h = n · d_0 = det(d_0, d_1, d_2):
// the faces of the certificate of a penetration depth under rigid motion
// (rigid_proximity.hpp).  The plane's distance to the origin is
// |h| / |n|.  Signs on intervals, then rationals, as above.
class PlacedTriangle {
 public:
  PlacedTriangle(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 3>& p,
                 const std::array<const PointBounds*, 3>& pb, const std::array<const Point3*, 3>& q,
                 const std::array<const PointBounds*, 3>& qb);
  // The same with the enclosures of the three d_j given (each from
  // placed_difference_bounds of its pair): the faces of one surface share
  // their vertices, whose enclosures are then made once.
  PlacedTriangle(const PlacedMap& mp, const PlacedMap& mq, const std::array<const Point3*, 3>& p,
                 const std::array<const PointBounds*, 3>& pb, const std::array<const Point3*, 3>& q,
                 const std::array<const PointBounds*, 3>& qb, const std::array<const PointBounds*, 3>& d);
  ~PlacedTriangle();
  PlacedTriangle(PlacedTriangle&&) noexcept;
  // sign h = orient(0, d_0, d_1, d_2): positive when the origin lies
  // strictly on the inner side of the plane (n points away from it).
  int offset_sign() const;
  // sign (h_a² |n_b|² − h_b² |n_a|²): whether a's plane is further from the
  // origin than b's (degree 10 in the points).
  friend int compare_distance(const PlacedTriangle& a, const PlacedTriangle& b);
  // sign n · A_p (b − a) for points of P (b further than a along n: the
  // climb to P's maximum of n · x) and sign −n · A_q (b − a) for points of
  // Q (the climb to Q's minimum).
  int climb_sign_p(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  int climb_sign_q(const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  // An enclosure of h² / |n|² (the squared distance of the plane) and the
  // exact value; the point (h / |n|²) n of the plane nearest the origin.
  Bounds squared_distance_bounds() const;
  Rational squared_distance() const;
  Point3 nearest_point() const;
  // Doubles near n / |n| (for the caller's doubles only).
  Vec3d unit_normal() const;
  // The ray {t u : t > 0} and the triangle: sign det(d_i, d_{i+1}, u) for
  // the edge i (i + 1 mod 3), and sign n · u.  With offset_sign() > 0, the
  // ray meets the triangle when n · u > 0 and the three edge signs are ≥ 0.
  int edge_sign(int i, const Point3& u, const PointBounds& ub) const;
  int direction_sign(const Point3& u, const PointBounds& ub) const;
  // h / (n · u): the ray meets the plane at t u (requires n · u ≠ 0).
  Rational ray_parameter(const Point3& u) const;
  Bounds ray_parameter_bounds(const PointBounds& ub) const;  // an enclosure of it

 private:
  struct Exact;
  const Exact& exact() const;
  int climb_sign(bool on_p, const Point3& a, const PointBounds& ab, const Point3& b, const PointBounds& bb) const;
  const PlacedMap *mp_, *mq_;
  std::array<const Point3*, 3> p_, q_;
  std::array<const PointBounds*, 3> pb_, qb_;
  Bounds h_{}, nn_{};
  std::array<Bounds, 3> n_{};
  // The pulled normals A_pᵀ n and −A_qᵀ n, made by the first climb sign.
  mutable std::array<Bounds, 3> up_{}, uq_{};
  mutable bool pulled_ = false;
  std::array<std::array<Bounds, 3>, 3> d_{};
  mutable std::unique_ptr<Exact> exact_;
  void set_from(const std::array<PointBounds, 3>& d);
};

// PlacedTriangle's two filters for every triangle of one surface of D on
// its corners' shared enclosures `d` (each from placed_difference_bounds),
// in one rounding scope: signs[k] = {sign h_k, sign (h_k² |n_f|² −
// h_f² |n_k|²)} for the triangle k of `tris` (indices into d) against the
// triangle f (0 for f itself), each where its interval decides,
// kUndecidedSign where it does not: the exact sign is then PlacedTriangle's
// offset_sign or compare_distance.  The intervals are PlacedTriangle's, so
// a sign decided here is the one its filter decides.
inline constexpr int kUndecidedSign = 2;
void placed_surface_signs(const std::vector<PointBounds>& d, const std::vector<std::array<int, 3>>& tris, int f,
                          std::vector<std::array<int, 2>>& signs);

// An enclosure of A_p p + t_p − (A_q q + t_q) from enclosures of p and q
// (intervals rounded outward): the enclosure of a point of D that
// PlacedTriangle makes for each of its corners.
PointBounds placed_difference_bounds(const PlacedMap& mp, const PointBounds& pb, const PlacedMap& mq,
                                     const PointBounds& qb);

// Two placements' points in one exact frame, for computations that chain
// many signs and products on the same placed points (the feature plane of
// rigid_proximity.hpp: normals as cross products of placed differences,
// climbs and level sets by dot products with them, orientations in a
// plane; and the exact stage of placed_tetrahedron_holds_origin):
//   Z_p(x) = K (A_p x + t_p − t_p) = K A_p x,
//   Z_q(y) = K (A_q y + t_q − t_p),
// one translation and one positive factor K for both, so every sign of a
// polynomial that is invariant under a common translation and homogeneous
// (or every sign of a homogeneous polynomial in the differences
// Z_p − Z_q, which are K times the points of the Minkowski difference) is
// the sign of the same polynomial on the placed points.  The placed point
// is Z / K + t_p.
//
// Integers.  A non-zero double is m 2^e with m an integer, 2^52 ≤ |m| <
// 2^53 (dyadic_exponent gives e; INT_MAX for zero).  When both matrices
// and every point are doubles (the translations may be any rationals),
// each product (A)_rc x_c is an integer multiple of 2^(e_A + e_x), with e_A
// the least exponent over the matrix's non-zero entries and e_x at most
// that of every coordinate of every point the frame will take (the
// caller's bound, per body).  With E = min(e_A,p +
// e_x,p, e_A,q + e_x,q, 0), t_q − t_p = T / D (D > 0 the least common
// denominator of its three rationals, T integers) and K = D 2^−E, every Z
// is an integer vector, computed exactly in GMP integers (no denominators,
// no gcd in the arithmetic that follows).  Otherwise (a rational matrix, a
// quaternion rotation or a rational point) K = 1 and Z are rationals.
int dyadic_exponent(double x);
class PlacedFrame {
 public:
  // `p_doubles`: every point of P the frame will take has double
  // coordinates, `p_exponent` at most dyadic_exponent of each of their
  // non-zero coordinates; likewise for Q.
  PlacedFrame(const PlacedMap& mp, bool p_doubles, int p_exponent, const PlacedMap& mq, bool q_doubles,
              int q_exponent);
  Point3 p(const Point3& x, const PointBounds& xb) const;  // Z_p(x)
  Point3 q(const Point3& y, const PointBounds& yb) const;  // Z_q(y)
  Point3 placed(const Point3& z) const;                    // z / K + t_p
  const Rational& factor() const { return k_; }            // K
  bool integers() const { return integers_; }

 private:
  Point3 linear(int which, const PointBounds& xb) const;
  const PlacedMap *mp_, *mq_;
  bool integers_ = false;
  int e_ = 0;                 // E
  Integer d_{1};              // D
  Rational k_{1};             // K
  Point3 tq_;                 // K (t_q − t_p)
  std::array<std::array<std::int64_t, 9>, 2> am_{};  // the matrices' entries m 2^e (integers mode)
  std::array<std::array<int, 9>, 2> ae_{};
};

// How often the interval stage decided and how often the rationals did, on
// the calling thread since it started (the doubles stage is not counted).
struct PlacedPredicateCounts {
  std::uint64_t filtered = 0, exact = 0;
};
PlacedPredicateCounts placed_predicate_counts();

}  // namespace minksum
