// Collision of two convex polytopes under rigid motion (rigid_proximity.hpp)
// and the placed predicates behind it (placed_predicates.hpp): every answer
// against exact arithmetic.
#include <gtest/gtest.h>

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/placed_predicates.hpp>
#include <minksum/rigid_proximity.hpp>

#include <cfenv>
#include <cstdio>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace minksum;
using minksum::testing::P;

namespace {

// ---------------------------------------------------------------------------
// Exact references.

Point3 pull_exact(const PlacedMap& m, const Vec3d& n) {
  const Point3 e(n.x, n.y, n.z);
  Point3 u;
  for (int c = 0; c < 3; ++c) u[c] = m.a(0, c) * e.x + m.a(1, c) * e.y + m.a(2, c) * e.z;
  return u;
}

int tetra_reference(const std::array<Point3, 4>& d) {
  const auto vol = [](const Point3& a, const Point3& b, const Point3& c, const Point3& e) {
    return sgn(dot(b - a, cross(c - a, e - a)));
  };
  const int total = vol(d[0], d[1], d[2], d[3]);
  if (total == 0) return 0;
  for (int k = 0; k < 4; ++k) {
    auto e = d;
    e[k] = P(0, 0, 0);
    if (vol(e[0], e[1], e[2], e[3]) != total) return 0;
  }
  return 1;
}

// The status by separating axes, exactly: the largest gap
// min over Q' of n·x − max over P' of n·x over the facet normals of both
// placed bodies and the cross products of their edges (every facet normal of
// P' ⊕ (−Q') is one of them, up to sign): > 0 separate, 0 touching, < 0
// penetrating.  O((F + E²)·V) rationals: small bodies only.
ContactStatus sat_status(const ConvexPolytope& a, const PlacedMap& ma, const ConvexPolytope& b, const PlacedMap& mb) {
  std::vector<Point3> pa, pb;
  for (Index v = 0; v < a.num_vertices(); ++v) pa.push_back(ma.apply(a.point(v)));
  for (Index v = 0; v < b.num_vertices(); ++v) pb.push_back(mb.apply(b.point(v)));
  std::vector<Point3> axes;
  const auto facet_normals = [&](const ConvexPolytope& p, const std::vector<Point3>& x) {
    for (Index f = 0; f < p.num_facets(); ++f) {
      const auto vs = p.facet_vertices(f);
      axes.push_back(cross(x[vs[1]] - x[vs[0]], x[vs[2]] - x[vs[0]]));
    }
  };
  facet_normals(a, pa);
  facet_normals(b, pb);
  for (Index e = 0; e < a.num_edges(); ++e)
    for (Index g = 0; g < b.num_edges(); ++g) {
      const Point3 c = cross(pa[a.target(2 * e)] - pa[a.origin(2 * e)], pb[b.target(2 * g)] - pb[b.origin(2 * g)]);
      if (!is_zero(c)) axes.push_back(c);
    }
  int best = -1;
  for (const Point3& n0 : axes)
    for (int sign : {1, -1}) {
      const Point3 n = Rational(sign) * n0;
      Rational maxa = dot(n, pa[0]), minb = dot(n, pb[0]);
      for (const Point3& x : pa) maxa = std::max(maxa, dot(n, x));
      for (const Point3& x : pb) minb = std::min(minb, dot(n, x));
      best = std::max(best, sgn(Rational(minb - maxa)));
      if (best > 0) return ContactStatus::separate;
    }
  return best == 0 ? ContactStatus::touching : ContactStatus::penetrating;
}

// ---------------------------------------------------------------------------
// Random poses.

struct Rng {
  std::mt19937_64 g;
  explicit Rng(std::uint64_t seed) : g(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
  long integer(long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(g); }
};

Quaternion random_quaternion(Rng& r) {
  for (;;) {
    Quaternion q{Integer(r.integer(-9, 9)), Integer(r.integer(-9, 9)), Integer(r.integer(-9, 9)),
                 Integer(r.integer(-9, 9))};
    if (sgn(q[0]) || sgn(q[1]) || sgn(q[2]) || sgn(q[3])) return q;
  }
}

// The doubles of a rotation by a random unit quaternion: near orthogonal,
// not exactly; taken exactly as given.
std::array<double, 9> random_matrix(Rng& r) {
  double a = r.uniform(-1, 1), b = r.uniform(-1, 1), c = r.uniform(-1, 1), d = r.uniform(-1, 1);
  const double l = std::sqrt(a * a + b * b + c * c + d * d);
  a /= l, b /= l, c /= l, d /= l;
  return {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
          2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
          2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d};
}

RigidPose random_pose(Rng& r, double spread, bool quaternion) {
  const Point3 t(r.uniform(-spread, spread), r.uniform(-spread, spread), r.uniform(-spread, spread));
  return quaternion ? RigidPose::quaternion(random_quaternion(r), t) : RigidPose::matrix(random_matrix(r), t);
}

// n poses of P and of Q from the seed: a third of P's and a third of Q's
// by quaternions, the others by matrices.
void random_pose_pairs(std::uint64_t seed, int n, double spread, std::vector<RigidPose>& pp,
                       std::vector<RigidPose>& pq) {
  Rng r(seed);
  for (int i = 0; i < n; ++i) {
    pp.push_back(random_pose(r, spread, i % 3 == 0));
    pq.push_back(random_pose(r, spread, i % 3 == 1));
  }
}

// A random point for the predicates' tests: every third one with rational
// coordinates that are not doubles (thirds, sevenths, fifths), the others
// doubles.
Point3 mixed_point(Rng& r, int k) {
  if (k % 3 == 0) return Point3(Rational(r.integer(-30, 30), 3), Rational(r.integer(-30, 30), 7), Rational(1, 5));
  return Point3(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
}

struct RoundingMode {
  explicit RoundingMode(int m) { std::fesetround(m); }
  ~RoundingMode() { std::fesetround(FE_TONEAREST); }
};

}  // namespace

// ---------------------------------------------------------------------------
// The placed predicates.

TEST(PlacedPredicates, AgreeWithRationalsInAllRoundingModes) {
  const std::uint64_t seed = 3901;
  Rng r(seed);
  int zeros = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    const bool quat = trial % 2 == 0;
    const PlacedMap m = random_pose(r, 3, quat).map();
    const PlacedMap m2 = random_pose(r, 3, !quat).map();
    // Points: doubles, thirds (not doubles), and some on purpose equal.
    const auto point = [&](int k) { return mixed_point(r, k); };
    const Point3 a = point(trial), b = trial % 5 == 0 ? a : point(trial + 1);
    Vec3d n{r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    if (trial % 7 == 0) {
      // n orthogonal to A (b − a) in exact arithmetic where that is a double
      // direction: A the identity.
      n = {0, 0, 1};
    }
    const PlacedMap& mm = trial % 7 == 0 ? PlacedMap() : m;
    const Point3 b2 = trial % 7 == 0 ? Point3(b.x, b.y, a.z) : b;
    const int want_diff = sgn(dot(pull_exact(mm, n), b2 - a));
    const int want_gap = sgn(dot(Point3(n.x, n.y, n.z), m2.apply(b2) - m.apply(a)));
    std::array<Point3, 4> ps{a, b2, point(trial + 2), point(trial + 3)}, qs{point(trial + 4), b2, a, point(trial + 5)};
    std::array<Point3, 4> d;
    for (int k = 0; k < 4; ++k) d[k] = m.apply(ps[k]) - m2.apply(qs[k]);
    const int want_tetra = tetra_reference(d);
    zeros += want_diff == 0;
    for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      RoundingMode guard(mode);
      const PulledDirection u(mm, n);
      EXPECT_EQ(u.difference_sign(a, point_bounds(a), b2, point_bounds(b2)), want_diff) << "mode " << mode;
      EXPECT_EQ(placed_gap_sign(n, m, a, point_bounds(a), m2, b2, point_bounds(b2)), want_gap) << "mode " << mode;
      const int gf = placed_gap_filter(n, m, point_bounds(a), m2, point_bounds(b2));
      EXPECT_TRUE(gf == kGapOpen || gf == want_gap) << "mode " << mode;  // its filters alone: open or right
      std::array<PointBounds, 4> pb, qb;
      std::array<const Point3*, 4> pp, qp;
      std::array<const PointBounds*, 4> pbp, qbp;
      for (int k = 0; k < 4; ++k) {
        pb[k] = point_bounds(ps[k]), qb[k] = point_bounds(qs[k]);
        pp[k] = &ps[k], qp[k] = &qs[k], pbp[k] = &pb[k], qbp[k] = &qb[k];
      }
      EXPECT_EQ(placed_tetrahedron_holds_origin(m, m2, pp, pbp, qp, qbp), want_tetra == 1) << "mode " << mode;
      // The interval stage alone: open, or the same answer.
      const int f = placed_tetrahedron_filter(m, m2, pbp, qbp);
      EXPECT_TRUE(f == kTetrahedronOpen || f == int(want_tetra == 1)) << "mode " << mode;
    }
  }
  EXPECT_GT(zeros, 20);  // the zero cases were exercised
}

TEST(PlacedPredicates, TriangleOnSharedEnclosuresAgreesWithRationals) {
  // PlacedTriangle from its pairs, and from the enclosures of its corners
  // made once (placed_difference_bounds, as EPA's surface shares them),
  // and both as one surface's filters (placed_surface_signs):
  // the same signs, each the sign of the rational polynomial.  Zeros on
  // purpose: the origin on the plane (P and Q placed alike, p_0 = q_0), two
  // triangles of one plane (the corners turned), a climb along no edge.
  const std::uint64_t seed = 3907;
  Rng r(seed);
  int zeros = 0, decided = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    const PlacedMap m = random_pose(r, 3, trial % 2 == 0).map();
    const PlacedMap m2 = trial % 4 == 0 ? m : random_pose(r, 3, trial % 2 == 1).map();
    const auto point = [&](int k) { return mixed_point(r, k); };
    std::array<Point3, 3> ps{point(trial), point(trial + 1), point(trial + 2)};
    std::array<Point3, 3> qs{trial % 4 == 0 ? ps[0] : point(trial + 3), point(trial + 4), point(trial + 5)};
    std::array<PointBounds, 3> pb, qb, db;
    std::array<const Point3*, 3> pp, qp, pp2, qp2;
    std::array<const PointBounds*, 3> pbp, qbp, dbp, pbp2, qbp2, dbp2;
    std::array<Point3, 3> d;
    for (int j = 0; j < 3; ++j) {
      pb[j] = point_bounds(ps[j]), qb[j] = point_bounds(qs[j]);
      d[j] = m.apply(ps[j]) - m2.apply(qs[j]);
    }
    const Point3 n = cross(d[1] - d[0], d[2] - d[0]);
    const Rational h = dot(n, d[0]), nn = dot(n, n);
    // The second triangle: the same corners turned (the same plane), or
    // the first two with a new third pair.
    const bool same_plane = trial % 3 == 0;
    const Point3 p3 = point(trial + 6), q3 = point(trial + 7);
    const PointBounds p3b = point_bounds(p3), q3b = point_bounds(q3);
    const Point3 d3 = m.apply(p3) - m2.apply(q3);
    const Point3 n2 = same_plane ? n : cross(d[1] - d[0], d3 - d[0]);
    const Rational h2 = dot(n2, d[0]), nn2 = dot(n2, n2);
    const Point3 x = point(trial + 8), y = trial % 5 == 0 ? x : point(trial + 9);
    const int want_offset = sgn(h), want_compare = sgn(h * h * nn2 - h2 * h2 * nn);
    const int want_p = sgn(dot(n, m.apply_linear(y - x))), want_q = sgn(-dot(n, m2.apply_linear(y - x)));
    zeros += (want_offset == 0) + (want_compare == 0) + (want_p == 0);
    for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      RoundingMode guard(mode);
      for (int j = 0; j < 3; ++j) {
        db[j] = placed_difference_bounds(m, pb[j], m2, qb[j]);
        pp[j] = &ps[j], qp[j] = &qs[j], pbp[j] = &pb[j], qbp[j] = &qb[j], dbp[j] = &db[j];
      }
      for (int j = 0; j < 3; ++j) {
        const int k = same_plane ? (j + 1) % 3 : j;  // turned, or the new third pair
        pp2[j] = pp[k], qp2[j] = qp[k], pbp2[j] = pbp[k], qbp2[j] = qbp[k], dbp2[j] = dbp[k];
      }
      PointBounds d3b;
      if (!same_plane) {
        d3b = placed_difference_bounds(m, p3b, m2, q3b);
        pp2[2] = &p3, qp2[2] = &q3, pbp2[2] = &p3b, qbp2[2] = &q3b, dbp2[2] = &d3b;
      }
      const PlacedTriangle full(m, m2, pp, pbp, qp, qbp), shared(m, m2, pp, pbp, qp, qbp, dbp);
      const PlacedTriangle other(m, m2, pp2, pbp2, qp2, qbp2, dbp2);
      // The same two triangles as one surface's (placed_surface_signs, f
      // the second): each decided sign is the rational one.
      const std::vector<PointBounds> corners{db[0], db[1], db[2], same_plane ? db[0] : d3b};
      const std::vector<std::array<int, 3>> tris{{0, 1, 2}, same_plane ? std::array{1, 2, 0} : std::array{0, 1, 3}};
      std::vector<std::array<int, 2>> signs;
      placed_surface_signs(corners, tris, 1, signs);
      ASSERT_EQ(signs.size(), 2u);
      const std::array<int, 4> want{want_offset, want_compare, sgn(h2), 0};
      const std::array<int, 4> got{signs[0][0], signs[0][1], signs[1][0], signs[1][1]};
      for (int i = 0; i < 4; ++i) {
        EXPECT_TRUE(got[i] == kUndecidedSign || got[i] == want[i]) << "mode " << mode << ", sign " << i;
        decided += got[i] != kUndecidedSign;
      }
      for (const PlacedTriangle* t : {&full, &shared}) {
        EXPECT_EQ(t->offset_sign(), want_offset) << "mode " << mode;
        EXPECT_EQ(compare_distance(*t, other), want_compare) << "mode " << mode;
        EXPECT_EQ(compare_distance(other, *t), -want_compare) << "mode " << mode;
        EXPECT_EQ(t->climb_sign_p(x, point_bounds(x), y, point_bounds(y)), want_p) << "mode " << mode;
        EXPECT_EQ(t->climb_sign_q(x, point_bounds(x), y, point_bounds(y)), want_q) << "mode " << mode;
        if (sgn(nn) > 0) {
          const Bounds b = t->squared_distance_bounds();
          const Rational sq = h * h / nn;
          EXPECT_TRUE(Rational(b.lo) <= sq && sq <= Rational(b.hi)) << "mode " << mode;
          EXPECT_EQ(t->squared_distance(), sq) << "mode " << mode;
        }
      }
    }
  }
  EXPECT_GT(zeros, 100);  // the zero cases were exercised
  std::printf("surface signs decided: %d of %d\n", decided, 300 * 4 * 4);
  EXPECT_GT(decided, 300 * 4 * 2);  // the filters decide most signs (f against itself: 0)
}

TEST(PlacedPredicates, NearZeroFallsBackToRationals) {
  // b − a = (1, 2^-60, 0) against n = (2^-60, −1, 0) under the identity:
  // n·(b − a) = 2^-60 − 2^-60 = 0 exactly, and (2^-60, −1 + 2^-52, 0) a
  // hair away.  The interval cannot always decide; the sign is exact.
  const Point3 a = P(0, 0, 0), b(1.0, std::ldexp(1.0, -60), 0.0);
  const PlacedMap id;
  const auto before = placed_predicate_counts();
  EXPECT_EQ(PulledDirection(id, Vec3d{std::ldexp(1.0, -60), -1, 0}).difference_sign(a, point_bounds(a), b, point_bounds(b)), 0);
  EXPECT_EQ(PulledDirection(id, Vec3d{std::ldexp(1.0, -60), -1 + std::ldexp(1.0, -52), 0})
                .difference_sign(a, point_bounds(a), b, point_bounds(b)),
            1);
  // A rotation by thirds: the intervals are wide, the zero is exact.
  const PlacedMap third({{{Rational(1, 3), Rational(2, 3), Rational(2, 3)},
                          {Rational(2, 3), Rational(1, 3), Rational(-2, 3)},
                          {Rational(-2, 3), Rational(2, 3), Rational(-1, 3)}}},
                        P(0, 0, 0));
  // Row 0 of the matrix is (1, 2, 2)/3: n = (1, 0, 0) pulls back to it, and
  // b − a = (2, −1, 0) is orthogonal.
  EXPECT_EQ(PulledDirection(third, Vec3d{1, 0, 0}).difference_sign(a, point_bounds(a), P(2, -1, 0), point_bounds(P(2, -1, 0))), 0);
  EXPECT_GT(placed_predicate_counts().exact, before.exact);
  // Out of the doubles stage's range (2^-300, 2^250): the later stages answer.
  const Point3 tiny(std::ldexp(1.0, -300), 0.0, 0.0), huge(std::ldexp(1.0, 250), 1.0, 0.0);
  EXPECT_EQ(PulledDirection(id, Vec3d{1, 0, 0}).difference_sign(a, point_bounds(a), tiny, point_bounds(tiny)), 1);
  EXPECT_EQ(PulledDirection(id, Vec3d{-1, 0, 0}).difference_sign(a, point_bounds(a), huge, point_bounds(huge)), -1);
  EXPECT_EQ(placed_gap_sign(Vec3d{0, 1, 0}, id, huge, point_bounds(huge), id, a, point_bounds(a)), -1);
  EXPECT_EQ(placed_gap_sign(Vec3d{1, 0, 0}, id, a, point_bounds(a), id, tiny, point_bounds(tiny)), 1);
  // The doubles stage on an exact zero it cannot see as zero: 0.1 + 0.2 − 0.3
  // style cancellations are decided exactly (1 · (2^53 + 1) − (2^53 + 1)).
  const double big = std::ldexp(1.0, 53);
  const PlacedMap shear(std::array<double, 9>{1, 1, 0, 0, 1, 0, 0, 0, 1}, Vec3d{0, 0, 0});
  const Point3 c(big, 1.0, 0.0), e(0.0, 0.0, 0.0);
  // n · A (c − e) with n = (1, −(2^53 + 2), 0): (2^53 + 1) − (2^53 + 2) = −1.
  EXPECT_EQ(PulledDirection(shear, Vec3d{1, -(big + 2), 0}).difference_sign(e, point_bounds(e), c, point_bounds(c)), -1);
}

// PlacedFrame: Z_p(x) = K A_p x and Z_q(y) = K (A_q y + t_q − t_p), integers
// when the matrices and the points are doubles, whatever the translations
// (rationals of large denominators: the touching poses of the rotation
// benchmark); each against the rational placed point.
TEST(PlacedFrame, PointsAreTheScaledPlacedPointsExactly) {
  const std::uint64_t seed = 3902;
  Rng r(seed);
  int integers = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    // Translations: doubles, or rationals with denominators of ~100 bits.
    const auto translation = [&](int k) {
      if (k % 2 == 0) return Point3(r.uniform(-3, 3), r.uniform(-3, 3), r.uniform(-3, 3));
      const Integer den = (Integer(r.integer(1, 1L << 40)) << 60) + 1;
      Point3 t(Rational(Integer(r.integer(-(1L << 50), 1L << 50)), den), Rational(r.integer(-9, 9), 7),
               Rational(Integer(r.integer(-(1L << 50), 1L << 50)), den + 2));
      for (int c = 0; c < 3; ++c) t[c].canonicalize();
      return t;
    };
    // Matrices: doubles (some with tiny and huge entries), or a quaternion.
    const auto map = [&](int k) {
      if (k % 5 == 4) return PlacedMap::rotation(random_quaternion(r), translation(k));
      std::array<double, 9> a = random_matrix(r);
      if (k % 5 == 3) a = {std::ldexp(1.0, -400), 0, std::ldexp(3.0, -600), 0, 1.5, 0, 0, 0, std::ldexp(1.0, 500)};
      return PlacedMap(a, translation(k));
    };
    const PlacedMap mp = map(trial), mq = map(trial / 5 + 1);
    // Points: doubles of mixed exponents (zero, subnormal, 2^-300, 2^200),
    // or rationals (thirds) on some trials.
    const bool rational_points = trial % 7 == 0;
    const auto coordinate = [&]() -> double {
      switch (r.integer(0, 5)) {
        case 0: return 0.0;
        case 1: return std::ldexp(r.uniform(-1, 1), -1060);  // subnormal
        case 2: return std::ldexp(r.uniform(-1, 1), -300);
        case 3: return std::ldexp(r.uniform(-1, 1), 200);
        default: return r.uniform(-4, 4);
      }
    };
    std::vector<Point3> ps, qs;
    for (int k = 0; k < 4; ++k) {
      ps.emplace_back(coordinate(), coordinate(), coordinate());
      qs.emplace_back(coordinate(), coordinate(), coordinate());
    }
    if (rational_points) ps[1] = Point3(Rational(1, 3), Rational(-2, 3), Rational(5));
    const auto scan = [](const std::vector<Point3>& pts, bool& doubles, int& e) {
      for (const Point3& x : pts) {
        const PointBounds b = point_bounds(x);
        for (const Bounds& c : {b.x, b.y, b.z}) doubles = doubles && c.lo == c.hi, e = std::min(e, dyadic_exponent(c.lo));
      }
    };
    bool pd = true, qd = true;
    int pe = std::numeric_limits<int>::max(), qe = pe;
    scan(ps, pd, pe), scan(qs, qd, qe);
    const PlacedFrame frame(mp, pd, pe, mq, qd, qe);
    const bool want_integers = pd && qd && mp.linear_doubles() && mq.linear_doubles();
    EXPECT_EQ(frame.integers(), want_integers);
    integers += frame.integers();
    EXPECT_GT(frame.factor(), 0);
    for (int k = 0; k < 4; ++k) {
      const Point3 zp = frame.p(ps[k], point_bounds(ps[k])), zq = frame.q(qs[k], point_bounds(qs[k]));
      EXPECT_EQ(frame.placed(zp), mp.apply(ps[k])) << "point " << k;
      EXPECT_EQ(frame.placed(zq), mq.apply(qs[k])) << "point " << k;
      EXPECT_EQ(zp, frame.factor() * (mp.apply(ps[k]) - mp.t())) << "point " << k;
      if (frame.integers())
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(zp[c].get_den(), 1) << "point " << k;
          EXPECT_EQ(zq[c].get_den(), 1) << "point " << k;
        }
    }
  }
  EXPECT_GT(integers, 100);
  EXPECT_LT(integers, 300);
  EXPECT_EQ(dyadic_exponent(0.0), std::numeric_limits<int>::max());
  EXPECT_EQ(dyadic_exponent(1.0), -52);
  EXPECT_EQ(dyadic_exponent(0.75), -53);
  EXPECT_EQ(dyadic_exponent(std::ldexp(1.0, -1074)), -1126);  // the least subnormal: 2^52 · 2^-1126
}

// The tetrahedron's exact stage on PlacedFrame integers, with the origin
// exactly on the tetrahedron's boundary (a vertex, an edge, a face: never
// strictly inside), just inside, and outside, by translations t_q that are
// rationals of large denominators (the intervals cannot decide a zero).
TEST(PlacedPredicates, TetrahedronOnItsBoundaryWithRationalTranslations) {
  const std::uint64_t seed = 3903;
  Rng r(seed);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    const PlacedMap mp0(random_matrix(r), Vec3d{r.uniform(-1, 1), 0, 0});
    const std::array<double, 9> aq = random_matrix(r);
    std::array<Point3, 4> ps, qs;
    std::array<PointBounds, 4> pb, qb;
    for (int k = 0; k < 4; ++k) {
      ps[k] = Point3(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
      qs[k] = Point3(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
      pb[k] = point_bounds(ps[k]), qb[k] = point_bounds(qs[k]);
    }
    // d_k = A_p p_k + t_p − A_q q_k − t_q; with t_q = 0 they are e_k, and
    // t_q = Σ w_k e_k (Σ w = 1) puts the origin at barycentric weights w.
    const PlacedMap mq0(aq, Vec3d{0, 0, 0});
    std::array<Point3, 4> e;
    for (int k = 0; k < 4; ++k) e[k] = mp0.apply(ps[k]) - mq0.apply(qs[k]);
    const Rational small(1, (Integer(1) << 100) + 7);
    std::array<Rational, 4> w;
    switch (trial % 5) {
      case 0: w = {Rational(1), Rational(0), Rational(0), Rational(0)}; break;               // a vertex
      case 1: w = {Rational(1, 3), Rational(2, 3), Rational(0), Rational(0)}; break;         // an edge
      case 2: w = {Rational(1, 3) + small, Rational(1, 3), Rational(1, 3) - small, Rational(0)}; break;  // a face
      case 3: w = {Rational(1, 4) - small, Rational(1, 4), Rational(1, 4), Rational(1, 4) + small}; break;  // inside
      default: w = {-small, Rational(1, 3), Rational(1, 3), Rational(1, 3) + small}; break;                 // outside
    }
    Point3 t(0, 0, 0);
    for (int k = 0; k < 4; ++k) t = t + w[k] * e[k];
    const PlacedMap mq(aq, t);
    std::array<Point3, 4> d;
    for (int k = 0; k < 4; ++k) d[k] = mp0.apply(ps[k]) - mq.apply(qs[k]);
    const bool want = tetra_reference(d) == 1;
    EXPECT_EQ(want, trial % 5 == 3 && sgn(dot(e[1] - e[0], cross(e[2] - e[0], e[3] - e[0]))) != 0);
    std::array<const Point3*, 4> pp, qp;
    std::array<const PointBounds*, 4> pbp, qbp;
    for (int k = 0; k < 4; ++k) pp[k] = &ps[k], qp[k] = &qs[k], pbp[k] = &pb[k], qbp[k] = &qb[k];
    EXPECT_EQ(placed_tetrahedron_holds_origin(mp0, mq, pp, pbp, qp, qbp), want);
    // The interval stage alone never claims a boundary origin inside (a
    // vertex, an edge, a face: open or no), and agrees where it decides.
    const int f = placed_tetrahedron_filter(mp0, mq, pbp, qbp);
    EXPECT_TRUE(f == kTetrahedronOpen || f == int(want));
    if (trial % 5 < 2) {
      EXPECT_NE(f, 1);
    }
  }
}

// The climb sign's exact stage on integers (A, n and the points doubles):
// near-zero and zero signs that the doubles and the intervals leave open,
// against the rational evaluation; also with entries and coordinates of
// extreme exponents (subnormal to 2^900).
TEST(PlacedPredicates, ClimbSignOnIntegersAgreesWithRationals) {
  const std::uint64_t seed = 3904;
  Rng r(seed);
  const auto before = placed_predicate_counts();
  int zeros = 0;
  for (int trial = 0; trial < 600; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    std::array<double, 9> a = random_matrix(r);
    if (trial % 6 == 5) a = {std::ldexp(1.0, -400), 0, std::ldexp(3.0, -600), 0, 1.5, 0, 0, 0, std::ldexp(1.0, 500)};
    if (trial % 6 == 4) a = {1, 1, 0, 0, 1, 0, 0, 0, 1};  // a shear: exact zeros below
    const PlacedMap m(a, Vec3d{r.uniform(-1, 1), 0, 0});
    Point3 pa(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
    const double s = trial % 3 == 0 ? std::ldexp(1.0, -1000) : trial % 3 == 1 ? 1.0 : std::ldexp(1.0, 900);
    Vec3d n{r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    // b − a nearly orthogonal to u = Aᵀ n (doubles): d = u × w, rounded, scaled.
    const Vec3d u{a[0] * n.x + a[3] * n.y + a[6] * n.z, a[1] * n.x + a[4] * n.y + a[7] * n.z,
                  a[2] * n.x + a[5] * n.y + a[8] * n.z};
    const Vec3d w{r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    Vec3d d{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
    int top = 0;  // scaled by a power of two to at most 1 (a direction only: no rounding)
    std::frexp(std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)}), &top);
    d = {std::ldexp(d.x, -top), std::ldexp(d.y, -top), std::ldexp(d.z, -top)};
    if (trial % 6 == 4) n = {1, -1, 0}, d = {1, 1, std::ldexp(r.uniform(-1, 1), -70)};  // u = (1, 0, 0): u·d = 1 ≠ 0
    if (trial % 12 == 4) n = {0, 1, -1}, d = {0, 1, 1}, pa = P(1, 2, 3);  // u = (0, 1, -1): u·(0, 1, 1) = 0, exactly
    const Point3 pb(d.x * s + to_double(pa.x) * s, d.y * s + to_double(pa.y) * s, d.z * s + to_double(pa.z) * s);
    const Point3 pa_s(to_double(pa.x) * s, to_double(pa.y) * s, to_double(pa.z) * s);
    const int want = sgn(dot(pull_exact(m, n), pb - pa_s));
    zeros += want == 0;
    const PulledDirection pd(m, n);
    EXPECT_EQ(pd.difference_sign(pa_s, point_bounds(pa_s), pb, point_bounds(pb)), want);
    EXPECT_EQ(pd.difference_sign(pb, point_bounds(pb), pa_s, point_bounds(pa_s)), -want);
  }
  EXPECT_GT(zeros, 10);
  EXPECT_GT(placed_predicate_counts().exact, before.exact);
}

// PulledNormalFilter: the interval stage of sign N · A (b − a) for exact
// rational N of any size (up to 2^±3000), against the rational sign: every
// decided sign right, exact zeros never decided wrongly, and the common
// case decided.
TEST(PlacedPredicates, PulledNormalFilterAgreesWithRationals) {
  const std::uint64_t seed = 3905;
  Rng r(seed);
  int decided = 0, zeros = 0;
  for (int trial = 0; trial < 800; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    const PlacedMap m = random_pose(r, 3, trial % 3 == 0).map();
    const Point3 a(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
    Point3 b(r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-2, 2));
    if (trial % 5 == 0) b = Point3(Rational(r.integer(-30, 30), 3), Rational(1, 7), a.z);
    // N = Aᵀ-pulled (b − a) × w: orthogonal to A (b − a) on some trials
    // (exact zeros), scaled by 2^s with s up to ±3000.
    const Point3 ab = m.apply_linear(b - a);
    const Point3 w(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    Point3 n = trial % 4 == 0 ? cross(ab, w) : Point3(r.uniform(-1, 1), r.uniform(-1, 1), Rational(r.integer(-5, 5), 3));
    const long s = r.integer(-3000, 3000);
    const Rational scale = s >= 0 ? Rational(Integer(1) << static_cast<unsigned long>(s))
                                  : Rational(Integer(1), Integer(1) << static_cast<unsigned long>(-s));
    n = scale * n;
    const int want = sgn(dot(n, ab));
    zeros += want == 0;
    const PulledNormalFilter f(m, n);
    const int got = f.difference_sign(point_bounds(a), point_bounds(b));
    if (got != PulledNormalFilter::kOpen) {
      ++decided;
      EXPECT_EQ(got, want);
    }
    const int back = f.difference_sign(point_bounds(b), point_bounds(a));
    if (back != PulledNormalFilter::kOpen) {
      EXPECT_EQ(back, -want);
    }
  }
  EXPECT_GT(zeros, 100);
  EXPECT_GT(decided, 400);
  // N = 0 decides nothing.
  EXPECT_EQ(PulledNormalFilter(PlacedMap(), P(0, 0, 0)).difference_sign(point_bounds(P(0, 0, 0)), point_bounds(P(1, 0, 0))),
            PulledNormalFilter::kOpen);
}

TEST(PlacedMap, RejectsSingularReflectedAndNonFiniteMatrices) {
  EXPECT_THROW(PlacedMap({1, 0, 0, 0, 1, 0, 0, 0, 0}, Vec3d{0, 0, 0}), UsageError);    // singular
  EXPECT_THROW(PlacedMap({1, 0, 0, 0, 1, 0, 0, 0, -1}, Vec3d{0, 0, 0}), UsageError);   // a reflection
  EXPECT_THROW(PlacedMap({NAN, 0, 0, 0, 1, 0, 0, 0, 1}, Vec3d{0, 0, 0}), UsageError);
  EXPECT_THROW(PlacedMap({1, 0, 0, 0, 1, 0, 0, 0, 1}, Vec3d{INFINITY, 0, 0}), UsageError);
  EXPECT_THROW(PlacedMap::rotation({Integer(0), Integer(0), Integer(0), Integer(0)}, P(0, 0, 0)), UsageError);
  // Determinant 2^-200 > 0: accepted (exact, not "near singular").
  const double tiny = std::ldexp(1.0, -100);
  EXPECT_NO_THROW(PlacedMap({tiny, 0, 0, 0, tiny, 0, 0, 0, 1}, Vec3d{0, 0, 0}));
  const PlacedMap q = PlacedMap::rotation({Integer(1), Integer(2), Integer(3), Integer(4)}, P(1, 2, 3));
  EXPECT_EQ(q.a(0, 0), Rational(-2, 3));  // (1 + 4 − 9 − 16) / 30
  EXPECT_EQ(q.apply(P(0, 0, 0)), P(1, 2, 3));
  EXPECT_FALSE(q.doubles());
  EXPECT_TRUE(PlacedMap().doubles());
}

// A matrix of doubles is accepted exactly when its exact determinant is
// positive, whichever stage decides (doubles with the permanent's bound,
// intervals, rationals): rotations (det ≈ 1), random matrices, matrices made
// singular exactly and then moved by one ulp in one entry (det a few ulps
// either side of 0), in every rounding mode.
TEST(PlacedMap, DeterminantSignOfDoubleMatricesIsExact) {
  const std::uint64_t seed = 4417;
  Rng r(seed);
  int accepted = 0, refused = 0;
  for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO})
    for (int trial = 0; trial < 300; ++trial) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", mode " + std::to_string(mode) + ", trial " +
                   std::to_string(trial));
      std::array<double, 9> a;
      for (double& x : a) x = r.uniform(-2, 2);
      if (trial % 3 == 1) {  // row 2 = row 0 + row 1 with small integers: singular, then one ulp off
        for (int c = 0; c < 3; ++c) {
          a[c] = double(r.integer(-8, 8)), a[3 + c] = double(r.integer(-8, 8));
          a[6 + c] = a[c] + a[3 + c];
        }
        const int k = int(r.integer(0, 8));
        a[k] = std::nextafter(a[k], r.integer(0, 1) ? INFINITY : -INFINITY);
      } else if (trial % 3 == 2) {  // a rotation's doubles
        const double t = r.uniform(0, 6.28), c = std::cos(t), s = std::sin(t);
        a = {c, -s, 0, s, c, 0, 0, 0, 1};
      }
      Rational det = 0;
      {
        const auto e = [&](int i) { return Rational(a[i]); };
        det = e(0) * (e(4) * e(8) - e(5) * e(7)) - e(1) * (e(3) * e(8) - e(5) * e(6)) +
              e(2) * (e(3) * e(7) - e(4) * e(6));
      }
      const int old = std::fegetround();
      std::fesetround(mode);
      bool threw = false;
      try {
        PlacedMap m(a, Vec3d{0, 0, 0});
      } catch (const UsageError&) {
        threw = true;
      }
      std::fesetround(old);
      ASSERT_EQ(threw, sgn(det) <= 0) << "det " << det;
      (threw ? refused : accepted) += 1;
    }
  EXPECT_GT(accepted, 300);
  EXPECT_GT(refused, 200);
}

// The rotation of machine-integer components (rotation64, quaternion64:
// Python's int64 arrays) is the
// rotation of the same components as GMP integers: the same nearest doubles,
// enclosures and exact entries, up to 2^25 on the machine-integer path and
// beyond it on GMP's.
TEST(PlacedMap, MachineIntegerQuaternionIsTheGmpOne) {
  const std::uint64_t seed = 5120;
  Rng r(seed);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    const long edge = trial % 4 == 3 ? (1L << 40) : (1L << 25);
    std::array<std::int64_t, 4> q;
    for (auto& x : q) x = r.integer(-edge, edge);
    if (q == std::array<std::int64_t, 4>{0, 0, 0, 0}) q[0] = 1;
    Quaternion big;
    for (int k = 0; k < 4; ++k) big[k] = Integer(static_cast<long>(q[k]));
    const Vec3d t{r.uniform(-3, 3), 0.5, -2};
    const PlacedMap a = PlacedMap::rotation64(q, t), b = PlacedMap::rotation(big, t);
    EXPECT_EQ(a.approx_a(), b.approx_a());
    for (int k = 0; k < 9; ++k) {
      EXPECT_EQ(a.bounds_a()[k].lo, b.bounds_a()[k].lo);
      EXPECT_EQ(a.bounds_a()[k].hi, b.bounds_a()[k].hi);
      EXPECT_EQ(a.a(k / 3, k % 3), b.a(k / 3, k % 3));
    }
    EXPECT_EQ(a.t(), b.t());
    EXPECT_EQ(a.doubles(), b.doubles());
    EXPECT_EQ(RigidPose::quaternion64(q, t).map().approx_a(), a.approx_a());
  }
  EXPECT_THROW(PlacedMap::rotation64({0, 0, 0, 0}, Vec3d{0, 0, 0}), UsageError);
  EXPECT_THROW(PlacedMap::rotation64({1, 0, 0, 0}, Vec3d{NAN, 0, 0}), UsageError);
  // A braced quaternion still names one overload (docs/proximity.md's example).
  EXPECT_EQ(RigidPose::quaternion({1, 2, 3, 4}, Vec3d{0, 0, 0}).map().approx_a(),
            RigidPose::quaternion64({1, 2, 3, 4}, Vec3d{0, 0, 0}).map().approx_a());
}

// The rotation of an integer quaternion (machine integers for components up
// to 2^25 when rounding to nearest, GMP otherwise) is the map of the
// rational matrix built here, entry by entry: the same exact entries, the
// same nearest doubles and enclosures, whatever the rounding mode, the
// translation as a Point3 or as doubles.
TEST(PlacedMap, QuaternionRotationIsTheRationalMatrix) {
  const std::uint64_t seed = 3902;
  Rng r(seed);
  const long edge = 1L << 25;
  int small = 0, large = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial));
    Quaternion q;
    // Even trials: machine-size components; odd ones: one at least beyond.
    const long forced = trial % 2 ? r.integer(0, 3) : -1;
    for (int k = 0; k < 4; ++k) {
      switch (k == forced ? r.integer(4, 5) : r.integer(0, trial % 2 ? 5 : 3)) {
        case 0: q[k] = 0; break;
        case 1: q[k] = Integer(r.integer(-9, 9)); break;
        case 2: q[k] = Integer(r.integer(-edge, edge)); break;
        case 3: q[k] = r.integer(0, 1) ? Integer(edge) : Integer(-edge); break;  // the largest machine case
        case 4: q[k] = Integer(r.integer(0, 1) ? edge + 1 : -edge - 1); break;   // the smallest GMP case
        default: q[k] = Integer(r.integer(-(1L << 40), 1L << 40)) * Integer(r.integer(1, 1L << 30)); break;
      }
    }
    if (!sgn(q[0]) && !sgn(q[1]) && !sgn(q[2]) && !sgn(q[3])) q[0] = 1;
    bool fits = true;
    for (const Integer& x : q) fits = fits && abs(x) <= edge;
    (fits ? small : large)++;
    const Integer &a = q[0], &b = q[1], &c = q[2], &d = q[3];
    const Integer n = a * a + b * b + c * c + d * d;
    const Integer e[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                             {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                             {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
    std::array<std::array<Rational, 3>, 3> m;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = Rational(e[i][j]) / Rational(n);
    const Vec3d td{r.uniform(-3, 3), r.uniform(-3, 3), 0.0};
    const Point3 t(td.x, td.y, td.z);
    const PlacedMap want(m, t);  // rounding to nearest
    for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      SCOPED_TRACE("rounding mode " + std::to_string(mode));
      std::array<PlacedMap, 2> got;
      {
        const RoundingMode rm(mode);
        got = {PlacedMap::rotation(q, t), PlacedMap::rotation(q, td)};
      }
      for (const PlacedMap& g : got) {
        EXPECT_EQ(g.doubles(), want.doubles());
        EXPECT_EQ(g.filter_ready(), want.filter_ready());
        for (int k = 0; k < 9; ++k) {
          EXPECT_EQ(g.a(k / 3, k % 3), m[k / 3][k % 3]) << k;
          EXPECT_EQ(g.approx_a()[k], want.approx_a()[k]) << k;
          EXPECT_EQ(g.bounds_a()[k].lo, want.bounds_a()[k].lo) << k;
          EXPECT_EQ(g.bounds_a()[k].hi, want.bounds_a()[k].hi) << k;
        }
        EXPECT_EQ(g.t(), t);
        EXPECT_EQ(g.approx_t().x, td.x);
        EXPECT_EQ(g.approx_t().y, td.y);
        EXPECT_EQ(g.approx_t().z, td.z);
        EXPECT_EQ(g.bounds_t().x.lo, td.x);
        EXPECT_EQ(g.bounds_t().y.hi, td.y);
      }
    }
  }
  EXPECT_EQ(small, 200);
  EXPECT_EQ(large, 200);
  EXPECT_THROW(PlacedMap::rotation({Integer(1), Integer(0), Integer(0), Integer(0)}, Vec3d{NAN, 0, 0}), UsageError);
  EXPECT_THROW(PlacedMap::rotation({Integer(0), Integer(0), Integer(0), Integer(0)}, Vec3d{0, 0, 0}), UsageError);
  // The identity, made without a determinant check, is the identity matrix's map.
  const PlacedMap id, mat({1, 0, 0, 0, 1, 0, 0, 0, 1}, Vec3d{0, 0, 0});
  EXPECT_TRUE(id.doubles() && id.filter_ready() && mat.filter_ready());
  for (int k = 0; k < 9; ++k)
    EXPECT_TRUE(id.approx_a()[k] == mat.approx_a()[k] && id.bounds_a()[k].lo == mat.bounds_a()[k].lo &&
                id.bounds_a()[k].hi == mat.bounds_a()[k].hi)
        << k;
  EXPECT_EQ(id.t(), mat.t());
  EXPECT_EQ(id.apply(P(1, 2, 3)), P(1, 2, 3));
}

// ---------------------------------------------------------------------------
// Collision.

namespace {

void expect_agrees_with_sat(const std::string& a, const std::string& b, int poses, double spread, std::uint64_t seed) {
  const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
  Rng r(seed);
  RigidWarmStart warm;
  int counts[3] = {0, 0, 0};
  const RigidStats before = rigid_stats();
  for (int i = 0; i < poses; ++i) {
    const bool quat = i % 2 == 0;
    const RigidPose pp = random_pose(r, spread, quat), pq = random_pose(r, spread, !quat);
    const ContactStatus want = sat_status(pa.polytope(), pp.map(), pb.polytope(), pq.map());
    const RigidCollision got = collide(pa, pp, pb, pq, i % 3 ? &warm : nullptr);
    ASSERT_EQ(got.status, want) << a << " / " << b << ", seed " << seed << ", pose " << i;
    ++counts[int(want)];
    if (got.certificate == RigidCertificate::separating_plane) {
      // The certificate's plane separates: every vertex of P below q, every
      // vertex of Q above p, checked exactly.
      const Point3 n(got.normal.x, got.normal.y, got.normal.z);
      const Rational hp = dot(n, pp.map().apply(pa.polytope().point(got.p)));
      const Rational hq = dot(n, pq.map().apply(pb.polytope().point(got.q)));
      EXPECT_LT(hp, hq);
      for (Index v = 0; v < pa.polytope().num_vertices(); ++v)
        EXPECT_LT(dot(n, pp.map().apply(pa.polytope().point(v))), hq);
      for (Index v = 0; v < pb.polytope().num_vertices(); ++v)
        EXPECT_GT(dot(n, pq.map().apply(pb.polytope().point(v))), hp);
    }
  }
  // The spread gives both outcomes; no pose is exactly touching, and the
  // search certifies nearly all of them (the exact path only within
  // rounding of contact).
  EXPECT_GT(counts[int(ContactStatus::separate)], poses / 10) << a << " / " << b;
  EXPECT_GT(counts[int(ContactStatus::penetrating)], poses / 10) << a << " / " << b;
  EXPECT_EQ(counts[int(ContactStatus::touching)], 0) << a << " / " << b;
  const RigidStats after = rigid_stats();
  EXPECT_LE(after.exact - before.exact, std::uint64_t(poses / 100)) << a << " / " << b;
  std::printf("%s / %s: %d poses, %llu separating planes, %llu simplices, %llu exact\n", a.c_str(), b.c_str(), poses,
              (unsigned long long)(after.separating_plane - before.separating_plane),
              (unsigned long long)(after.simplex - before.simplex), (unsigned long long)(after.exact - before.exact));
}

}  // namespace

TEST(RigidCollide, AgreesWithSeparatingAxesOnRandomPoses) {
  expect_agrees_with_sat("cube", "cube", 300, 1.5, 11);
  expect_agrees_with_sat("tetra", "octahedron", 300, 1.5, 12);
  expect_agrees_with_sat("dodecahedron", "cube", 120, 2.5, 13);
  expect_agrees_with_sat("random:12:1", "random:10:2", 200, 1.5, 14);
}

namespace {

// Random poses of a and b with translations in [-spread, spread]^3 (exact),
// every answer against the exact obstacle; both outcomes occur.
void expect_agrees_with_exact(const std::string& a, const std::string& b, double spread, std::uint64_t seed) {
  const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
  Rng r(seed);
  int separate = 0;
  for (int i = 0; i < 60; ++i) {
    const RigidPose pp = random_pose(r, 0, i % 2 == 0);
    const RigidPose pq0 = random_pose(r, 0, i % 2 == 1);
    const Point3 t(r.uniform(-spread, spread), r.uniform(-spread, spread), r.uniform(-spread, spread));
    std::array<std::array<Rational, 3>, 3> m;
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) m[x][y] = pq0.map().a(x, y);
    const RigidPose pq(PlacedMap(m, t));
    const ContactStatus want = collide_exact(pa, pp, pb, pq);
    separate += want == ContactStatus::separate;
    EXPECT_EQ(collide(pa, pp, pb, pq).status, want) << a << " / " << b << ", seed " << seed << ", pose " << i;
  }
  EXPECT_GT(separate, 5) << a;
  EXPECT_LT(separate, 55) << a;
}

}  // namespace

TEST(RigidCollide, RationalCoordinatesTakeTheIntervalStage) {
  // Vertices p/q (cube@scale:1/3): no doubles stage.
  expect_agrees_with_exact("cube@scale:1/3", "tetra@rot:2", 2.0, 41);
}

TEST(RigidCollide, TinyAndHugeBodiesWhoseSearchUnderflowsOrOverflows) {
  // Bodies of size 1e-80: the search's products of four coordinates
  // underflow and its closest point of a triangle divided by zero, which
  // made an infinite normal reach the interval stage (an assertion of
  // CGAL's Interval_nt).  A normal that is not finite certifies nothing now.
  expect_agrees_with_exact("dodecahedron@scale:1e-80", "cube@scale:1e-80", 5e-80, 42);
  // Size 1e80: the same products overflow.
  expect_agrees_with_exact("dodecahedron@scale:1e80", "cube@scale:1e80", 5e80, 43);
  const PlacedMap id;
  const Point3 o(0, 0, 0);
  EXPECT_THROW(PulledDirection(id, Vec3d{INFINITY, 0, 0}), UsageError);
  EXPECT_THROW(placed_gap_sign(Vec3d{NAN, 0, 0}, id, o, point_bounds(o), id, o, point_bounds(o)), UsageError);
}

TEST(RigidCollide, AgreesWithTheExactObstacleOnLargerPairs) {
  for (const auto& [a, b, seed] : std::vector<std::tuple<std::string, std::string, std::uint64_t>>{
           {"sphere:2", "sphere:2", 21}, {"random:50:1", "random:50:2", 22}, {"sphere:3", "cube", 23}}) {
    const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
    Rng r(seed);
    RigidWarmStart warm;
    for (int i = 0; i < 60; ++i) {
      const RigidPose pp = random_pose(r, 1.5, i % 2 == 0), pq = random_pose(r, 1.5, i % 2 == 1);
      const ContactStatus want = collide_exact(pa, pp, pb, pq);
      EXPECT_EQ(collide(pa, pp, pb, pq, &warm).status, want) << a << " / " << b << ", seed " << seed << ", pose " << i;
    }
  }
}

namespace {

// Whether x lies in the polytope c placed by m: on the inner side of every
// facet's placed plane (through three placed vertices of the facet).
bool in_placed(const ConvexPolytope& c, const PlacedMap& m, const Point3& x) {
  for (Index f = 0; f < c.num_facets(); ++f) {
    const std::vector<Index> v = c.facet_vertices(f);
    const Point3 a = m.apply(c.point(v[0])), b = m.apply(c.point(v[1])), e = m.apply(c.point(v[2]));
    if (sgn(dot(cross(b - a, e - a), x - a)) > 0) return false;
  }
  return true;
}

// Q placed on top of P = cube ([-1, 1]^3, identity) by the rotation `rot`,
// translated so that its lowest point along z, the vertex `low` of Q, goes
// to (x, y, 1 + dz).
RigidPose on_top(const ConvexPolytope& q, const PlacedMap& rot, Index low, const Rational& x, const Rational& y,
                 const Rational& dz, bool matrix, const std::array<double, 9>& m) {
  const Point3 image = rot.apply_linear(q.point(low));
  const Point3 t = Point3(x, y, Rational(1) + dz) - image;
  return matrix ? RigidPose::matrix(m, t) : RigidPose(PlacedMap(
                                               [&] {
                                                 std::array<std::array<Rational, 3>, 3> a;
                                                 for (int i = 0; i < 3; ++i)
                                                   for (int j = 0; j < 3; ++j) a[i][j] = rot.a(i, j);
                                                 return a;
                                               }(),
                                               t));
}

Index lowest(const ConvexPolytope& q, const PlacedMap& rot) {
  Index best = 0;
  for (Index v = 1; v < q.num_vertices(); ++v)
    if (rot.apply_linear(q.point(v)).z < rot.apply_linear(q.point(best)).z) best = v;
  return best;
}

void expect_contact(const RigidBody& p, const RigidBody& q, const PlacedMap& rot, const Rational& x, const Rational& y,
                    bool matrix, const std::array<double, 9>& m, const std::string& what) {
  const Index low = lowest(q.polytope(), rot);
  const Rational hair(1, Integer(1) << 40);
  for (const auto& [dz, want] : std::vector<std::pair<Rational, ContactStatus>>{
           {Rational(0), ContactStatus::touching},
           {hair, ContactStatus::separate},
           {-hair, ContactStatus::penetrating}}) {
    const RigidPose pq = on_top(q.polytope(), rot, low, x, y, dz, matrix, m);
    const RigidCollision c = collide(p, RigidPose(), q, pq);
    EXPECT_EQ(c.status, want) << what << ", dz " << dz.get_str();
    // 2^-40 from contact is far above the rounding of the search: the
    // answer is certified by the separating plane of the nearest triangle
    // of D, or a tetrahedron; at contact, by the plane of the touching
    // features (without M).
    const RigidCertificate proof = want == ContactStatus::separate      ? RigidCertificate::separating_plane
                                   : want == ContactStatus::penetrating ? RigidCertificate::simplex
                                                                        : RigidCertificate::feature_plane;
    EXPECT_EQ(c.certificate, proof) << what << ", dz " << dz.get_str();
    EXPECT_EQ(sat_status(p.polytope(), PlacedMap(), q.polytope(), pq.map()), want) << what;
  }
}

}  // namespace

TEST(RigidCollide, ExactlyTouchingPoses) {
  const RigidBody cube(catalog_polytope("cube"));
  const std::array<double, 9> none{};
  // Face on face: Q a cube turned about z by the rational rotation of
  // (2, 0, 0, 1) (cos = 3/5), its bottom face on P's top face.
  const PlacedMap about_z = PlacedMap::rotation({Integer(2), Integer(0), Integer(0), Integer(1)}, P(0, 0, 0));
  expect_contact(cube, cube, about_z, Rational(1, 2), Rational(0), false, none, "face-face");
  // Edge on face: turned about x (2, 1, 0, 0); its lowest edge on P's top.
  const PlacedMap about_x = PlacedMap::rotation({Integer(2), Integer(1), Integer(0), Integer(0)}, P(0, 0, 0));
  expect_contact(cube, cube, about_x, Rational(0), Rational(0), false, none, "edge-face");
  // Vertex on face: a generic rational rotation, the lowest vertex at the
  // centre of P's top face.
  const PlacedMap generic = PlacedMap::rotation({Integer(1), Integer(2), Integer(3), Integer(4)}, P(0, 0, 0));
  expect_contact(cube, cube, generic, Rational(0), Rational(0), false, none, "vertex-face");
  // Vertex on face with a double matrix taken exactly as given (the doubles
  // of a random rotation, near orthogonal, not exactly).
  Rng r(5);
  const std::array<double, 9> m = random_matrix(r);
  const PlacedMap dm(m, P(0, 0, 0));
  expect_contact(cube, cube, dm, Rational(1, 3), Rational(-1, 5), true, m, "vertex-face, double matrix");
  // A dodecahedron on the cube: vertex or edge down.
  const RigidBody dodeca(catalog_polytope("dodecahedron"));
  expect_contact(cube, dodeca, generic, Rational(1, 7), Rational(0), false, none, "dodecahedron vertex-face");
}

// Exactly touching poses of randomly turned pairs, as the rotation
// benchmark makes them: Q translated to the exit point s of a random ray
// from M's interior point (M = R_P P ⊕ (−R_Q Q) of the turned bodies,
// exact rationals).  Every one is touching, and the feature plane proves
// it without M: collide (status), distance (0 and a common point of both
// placed bodies), penetration_depth (0).
TEST(RigidCollide, TouchingClimbsOnlyThePlanesThroughTheContact) {
  // Exactly touching poses of two 642-vertex spheres: the feature plane's
  // ranking climbs a candidate's supports only when its bound over the
  // simplex's points reaches the best gap climbed so far, so the planes
  // tilted from the contact are not climbed before the first is tried.
  // Every answer is touching, proved by the feature plane.
  const std::uint64_t seed = 53;
  Rng r(seed);
  std::normal_distribution<double> nd(0, 1);
  const RigidBody pa(catalog_polytope("sphere:4")), pb(catalog_polytope("sphere:4"));
  std::uint64_t steps = 0;
  int poses = 0;
  for (int k = 0; k < 3; ++k) {
    const std::array<double, 9> rp = random_matrix(r), rq = random_matrix(r);
    TranslationalObstacle ob(placed_linear(pa.polytope(), PlacedMap(rp, Vec3d{0, 0, 0})),
                             placed_linear(pb.polytope(), PlacedMap(rq, Vec3d{0, 0, 0})));
    const Point3 c = ob.interior_point();
    for (int i = 0; i < 8; ++i, ++poses) {
      const Point3 u(nd(r.g), nd(r.g), nd(r.g));
      const Point3 s = c + ob.directional_depth_point(c, -u).t * u;
      const std::string what = "orientation " + std::to_string(k) + ", ray " + std::to_string(i) + ", seed " +
                               std::to_string(seed);
      RigidWarmStart warm;  // a search from the contact's neighbourhood, as on a trajectory
      collide(pa, RigidPose::matrix(rp, Vec3d{0, 0, 0}), pb, RigidPose::matrix(rq, to_double(s)), &warm);
      const RigidStats before = rigid_stats();
      const RigidCollision col = collide(pa, RigidPose::matrix(rp, Vec3d{0, 0, 0}), pb, RigidPose::matrix(rq, s), &warm);
      steps += rigid_stats().climb_steps - before.climb_steps;
      EXPECT_EQ(col.status, ContactStatus::touching) << what;
      EXPECT_EQ(col.certificate, RigidCertificate::feature_plane) << what;
    }
  }
  std::printf("climb steps per touching query: %.1f\n", double(steps) / poses);
  EXPECT_LT(steps, std::uint64_t(poses) * 30);
}

TEST(RigidCollide, TouchingPosesOfRandomRotationsProvedByTheFeaturePlane) {
  const std::uint64_t seed = 20261206;
  Rng r(seed);
  std::normal_distribution<double> nd(0, 1);
  for (const auto& [a, b] : std::vector<std::pair<const char*, const char*>>{
           {"cube", "dodecahedron"}, {"sphere:2", "random:50:1"}, {"octahedron", "cube"}}) {
    const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
    for (int k = 0; k < 4; ++k) {
      const std::array<double, 9> rp = random_matrix(r), rq = random_matrix(r);
      const PlacedMap mp(rp, Vec3d{0, 0, 0}), mq(rq, Vec3d{0, 0, 0});
      TranslationalObstacle ob(placed_linear(pa.polytope(), mp), placed_linear(pb.polytope(), mq));
      const Point3 c = ob.interior_point();
      for (int i = 0; i < 6; ++i) {
        const Point3 u(nd(r.g), nd(r.g), nd(r.g));
        const Point3 s = c + ob.directional_depth_point(c, -u).t * u;
        const std::string what = std::string(a) + " / " + b + ", orientation " + std::to_string(k) + ", ray " +
                                 std::to_string(i) + ", seed " + std::to_string(seed);
        ASSERT_EQ(ob.collide_point(s).status, ContactStatus::touching) << what;
        const RigidPose pp = RigidPose::matrix(rp, Vec3d{0, 0, 0}), pq = RigidPose::matrix(rq, s);
        const RigidStats before = rigid_stats();
        const RigidCollision col = collide(pa, pp, pb, pq);
        EXPECT_EQ(col.status, ContactStatus::touching) << what;
        EXPECT_EQ(col.certificate, RigidCertificate::feature_plane) << what;
        const RigidDistance d = distance(pa, pp, pb, pq);
        EXPECT_EQ(d.status, ContactStatus::touching) << what;
        EXPECT_EQ(d.certificate, RigidCertificate::feature_plane) << what;
        EXPECT_EQ(d.distance, 0) << what;
        const RigidDistanceExact e = exact_values(pa, pp, pb, pq, d);
        EXPECT_EQ(e.squared_distance, 0) << what;
        EXPECT_EQ(e.point_p, e.point_q) << what;
        EXPECT_TRUE(in_placed(pa.polytope(), pp.map(), e.point_p)) << what;
        EXPECT_TRUE(in_placed(pb.polytope(), pq.map(), e.point_q)) << what;
        const RigidDepth dep = penetration_depth(pa, pp, pb, pq);
        EXPECT_EQ(dep.status, ContactStatus::touching) << what;
        EXPECT_EQ(dep.depth, 0) << what;
        EXPECT_EQ(rigid_stats().exact, before.exact) << what << ": M was built";
      }
    }
  }
}

TEST(RigidCollide, EdgeCrossingEdge) {
  // P turned about y so that its top is an edge along y; Q turned about x so
  // that its bottom is an edge along x: the two edges cross at one point.
  const RigidBody cube(catalog_polytope("cube"));
  // (2, 0, 1, 0) turns about y by an angle of cosine 3/5: the top of P is
  // the edge through its two highest vertices.
  const PlacedMap py = PlacedMap::rotation({Integer(2), Integer(0), Integer(1), Integer(0)}, P(0, 0, 0));
  const PlacedMap qx = PlacedMap::rotation({Integer(2), Integer(1), Integer(0), Integer(0)}, P(0, 0, 0));
  const ConvexPolytope& c = cube.polytope();
  Index top = 0, low = 0;
  for (Index v = 1; v < c.num_vertices(); ++v) {
    if (py.apply_linear(c.point(v)).z > py.apply_linear(c.point(top)).z) top = v;
    if (qx.apply_linear(c.point(v)).z < qx.apply_linear(c.point(low)).z) low = v;
  }
  const Point3 pt = py.apply_linear(c.point(top)), ql = qx.apply_linear(c.point(low));
  // The top edge of P runs along y (y from -1 to 1) at x = pt.x; the bottom
  // edge of Q runs along x from ql to ql ∓ (2, 0, 0) (ql.x = ±1).  Placed by
  // t = (pt.x, −ql.y, pt.z − ql.z), it runs from x = pt.x − 1 to pt.x + 1 at
  // y = 0: the edges cross at (pt.x, 0, pt.z).
  const Rational hair(1, Integer(1) << 40);
  std::array<std::array<Rational, 3>, 3> qa;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) qa[i][j] = qx.a(i, j);
  const RigidPose pp = RigidPose(py);
  for (const auto& [dz, want] : std::vector<std::pair<Rational, ContactStatus>>{
           {Rational(0), ContactStatus::touching},
           {hair, ContactStatus::separate},
           {-hair, ContactStatus::penetrating}}) {
    const RigidPose pq(PlacedMap(qa, Point3(pt.x, -ql.y, pt.z - ql.z + dz)));
    EXPECT_EQ(sat_status(c, pp.map(), c, pq.map()), want);
    EXPECT_EQ(collide(cube, pp, cube, pq).status, want) << "dz " << dz.get_str();
  }
}

TEST(RigidCollide, BatchEqualsSingleQueries) {
  const RigidBody a(catalog_polytope("random:50:1")), b(catalog_polytope("sphere:2"));
  std::vector<RigidPose> pp, pq;
  random_pose_pairs(31, 700, 1.5, pp, pq);
  std::vector<RigidCollision> out(pp.size()), one(pp.size());
  collide(a, pp, b, pq, out, 2);
  for (std::size_t i = 0; i < pp.size(); ++i) {
    EXPECT_EQ(out[i].status, collide(a, pp[i], b, pq[i]).status) << "pose " << i;
    if (i % 50 == 0) {
      EXPECT_EQ(out[i].status, collide_exact(a, pp[i], b, pq[i])) << "pose " << i;
    }
  }
  // One pose of P for all the poses of Q.
  collide(a, std::span<const RigidPose>(pp.data(), 1), b, pq, one, 0);
  for (std::size_t i = 0; i < pp.size(); i += 7) EXPECT_EQ(one[i].status, collide(a, pp[0], b, pq[i]).status);
  std::vector<RigidCollision> wrong(3);
  EXPECT_THROW(collide(a, pp, b, pq, wrong, 1), UsageError);
}

// The batches over a RigidPoseSource (poses made on demand, as the Python
// module does) answer exactly as the span batches on the same poses: the
// same statuses, certificates and doubles, whatever the threads; one pose
// the source keeps stands for all; an exception of the source comes out of
// the batch, the first in pose order.
TEST(RigidCollide, PoseSourceBatchEqualsSpanBatch) {
  const RigidBody a(catalog_polytope("random:50:1")), b(catalog_polytope("sphere:2"));
  std::vector<RigidPose> pp, pq;
  random_pose_pairs(39, 900, 1.5, pp, pq);
  const std::size_t n = pp.size();
  const RigidPoseSource made = [&](std::size_t i, int body, RigidPose& scratch) -> const RigidPose& {
    scratch = body == 0 ? pp[i] : pq[i];  // built in scratch, as a caller from other data does
    return scratch;
  };
  std::vector<RigidCollision> want(n), got(n);
  std::vector<RigidDistance> dwant(n), dgot(n);
  std::vector<RigidDepth> pwant(n), pgot(n);
  collide(a, pp, b, pq, want, 2);
  distance(a, pp, b, pq, dwant, 2);
  penetration_depth(a, pp, b, pq, pwant, 2);
  for (unsigned threads : {1u, 2u, 0u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    collide(a, b, made, got, threads);
    distance(a, b, made, dgot, threads);
    penetration_depth(a, b, made, pgot, threads);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(got[i].status, want[i].status) << "pose " << i;
      EXPECT_EQ(got[i].certificate, want[i].certificate) << "pose " << i;
      EXPECT_EQ(dgot[i].status, dwant[i].status) << "pose " << i;
      EXPECT_EQ(dgot[i].distance, dwant[i].distance) << "pose " << i;
      EXPECT_EQ(dgot[i].lower, dwant[i].lower) << "pose " << i;
      EXPECT_EQ(dgot[i].upper, dwant[i].upper) << "pose " << i;
      EXPECT_EQ(pgot[i].status, pwant[i].status) << "pose " << i;
      EXPECT_EQ(pgot[i].depth, pwant[i].depth) << "pose " << i;
    }
  }
  // One pose of P, kept by the source, for all the poses of Q.
  std::vector<RigidCollision> one(n), one_span(n);
  const RigidPoseSource first = [&](std::size_t i, int body, RigidPose&) -> const RigidPose& {
    return body == 0 ? pp[0] : pq[i];
  };
  collide(a, b, first, one, 2);
  collide(a, std::span<const RigidPose>(pp.data(), 1), b, pq, one_span, 2);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(one[i].status, one_span[i].status) << "pose " << i;
  // A source failing at poses 700 and 300: the batch throws pose 300's error.
  const RigidPoseSource bad = [&](std::size_t i, int body, RigidPose& scratch) -> const RigidPose& {
    if (body == 1 && (i == 300 || i == 700)) throw UsageError("pose " + std::to_string(i));
    return made(i, body, scratch);
  };
  try {
    collide(a, b, bad, got, 2);
    ADD_FAILURE() << "no exception";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "pose 300");
  }
}

TEST(RigidCollide, CoherentTrajectoryStaysCheap) {
  // A small rotation and translation per step, warm-started: most steps
  // take a few climb steps, and every answer agrees with the exact one.
  const RigidBody a(catalog_polytope("sphere:3")), b(catalog_polytope("sphere:3"));
  RigidWarmStart warm;
  const auto before = rigid_stats();
  int exact_checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double ang = 0.01 * i, c = std::cos(ang), s = std::sin(ang);
    const std::array<double, 9> rz{c, -s, 0, s, c, 0, 0, 0, 1};
    const RigidPose pq = RigidPose::matrix(rz, Vec3d{3.0 - 0.01 * i, 0.1, 0.05});
    const RigidCollision got = collide(a, RigidPose(), b, pq, &warm);
    if (i % 40 == 0) {
      EXPECT_EQ(got.status, collide_exact(a, RigidPose(), b, pq)) << "step " << i;
      ++exact_checked;
    }
  }
  const auto after = rigid_stats();
  EXPECT_EQ(after.queries - before.queries, 400u);
  EXPECT_EQ(exact_checked, 10);
  // Far fewer climb steps than a scan of the 642 vertices per query would be.
  EXPECT_LT(after.climb_steps - before.climb_steps, 400u * 60u);
}

TEST(RigidCollide, WarmTetrahedronIsOnlyAGuess) {
  // A coherent trajectory through penetration: most penetrating steps are
  // proved by the previous step's tetrahedron (the warm start's), and
  // every answer checked agrees with the exact one.
  const RigidBody a(catalog_polytope("sphere:3")), b(catalog_polytope("sphere:3"));
  RigidWarmStart warm;
  const auto before = rigid_stats();
  int penetrating = 0, checked = 0;
  for (int i = 0; i < 600; ++i) {
    const double ang = 0.002 * i, c = std::cos(ang), s = std::sin(ang);
    const std::array<double, 9> rz{c, -s, 0, s, c, 0, 0, 0, 1};
    const RigidPose pq = RigidPose::matrix(rz, Vec3d{2.5 - 0.005 * i, 0.2, -0.1});
    const RigidCollision got = collide(a, RigidPose(), b, pq, &warm);
    penetrating += got.status == ContactStatus::penetrating;
    if (i % 30 == 0) {
      EXPECT_EQ(got.status, collide_exact(a, RigidPose(), b, pq)) << "step " << i;
      ++checked;
    }
  }
  const auto after = rigid_stats();
  EXPECT_EQ(checked, 20);
  EXPECT_GT(penetrating, 300);
  EXPECT_GT(after.warm_tetrahedra - before.warm_tetrahedra, std::uint64_t(penetrating) / 2);
  EXPECT_LE(after.warm_tetrahedra - before.warm_tetrahedra, after.simplex - before.simplex);
  // A stale tetrahedron: of a penetrating pose, then given with separate
  // and touching poses, with another pair of bodies (indices beyond their
  // vertices), and made of arbitrary pairs: each answer is the exact one.
  const RigidBody cube(catalog_polytope("cube"));
  const RigidWarmStart deep = warm;
  for (const Vec3d& t : {Vec3d{5, 0, 0}, Vec3d{0.5, 0.2, 0}}) {
    const RigidPose pq = RigidPose::translation(Point3(t.x, t.y, t.z));
    RigidWarmStart w = deep;
    EXPECT_EQ(collide(a, RigidPose(), b, pq, &w).status, collide_exact(a, RigidPose(), b, pq));
    w = deep;
    EXPECT_EQ(collide(cube, RigidPose(), cube, pq, &w).status, collide_exact(cube, RigidPose(), cube, pq));
    w = RigidWarmStart{};
    w.tetrahedron = true, w.tp = {0, 1, 2, 3}, w.tq = {4, 5, 6, 7};
    EXPECT_EQ(collide(cube, RigidPose(), cube, pq, &w).status, collide_exact(cube, RigidPose(), cube, pq));
  }
  const RigidPose face = RigidPose::translation(Point3(2, 0, 0));  // cube on cube, face to face
  RigidWarmStart w = deep;
  EXPECT_EQ(collide(cube, RigidPose(), cube, face, &w).status, ContactStatus::touching);
}

TEST(RigidCollide, IncoherentPosesClimbFromTheSeeds) {
  // Every pose unrelated to the previous one (a new rotation of each body
  // and a new translation), so the warm start is no help: each search's
  // first support starts from the seed of its direction's cell, a few steps
  // from the maximum, where a climb across the 642 vertices of sphere:4
  // took about 25 steps a body.  The answers agree with the exact ones.
  const std::uint64_t seed = 47;
  const RigidBody a(catalog_polytope("sphere:4")), b(catalog_polytope("sphere:4"));
  Rng r(seed);
  RigidWarmStart warm;
  const auto before = rigid_stats();
  int separate = 0, checked = 0;
  for (int i = 0; i < 400; ++i) {
    const RigidPose pp = random_pose(r, 0, false), pq = random_pose(r, 1.8, i % 2 == 0);
    const RigidCollision got = collide(a, pp, b, pq, &warm);
    separate += got.status == ContactStatus::separate;
    if (i % 20 == 0) {
      EXPECT_EQ(got.status, collide_exact(a, pp, b, pq)) << "seed " << seed << ", pose " << i;
      ++checked;
    }
  }
  const auto after = rigid_stats();
  EXPECT_EQ(checked, 20);
  EXPECT_GT(separate, 40) << "seed " << seed;
  EXPECT_LT(separate, 360) << "seed " << seed;
  EXPECT_LT(after.climb_steps - before.climb_steps, 400u * 10u) << "seed " << seed;
}

// ---------------------------------------------------------------------------
// Distance under rigid motion, against M built exactly.

namespace {

// The answer's exact values against the obstacle's: the same status and
// squared distance, closest points |v| apart, the certified bounds around
// the exact distance.
void expect_distance_agrees(const RigidBody& a, const RigidPose& pa, const RigidBody& b, const RigidPose& pb,
                            const RigidDistance& d, const std::string& what) {
  const RigidDistanceExact want = distance_exact(a, pa, b, pb);
  const RigidDistanceExact got = exact_values(a, pa, b, pb, d);
  EXPECT_EQ(got.squared_distance, want.squared_distance) << what;
  const Point3 gap = got.point_q - got.point_p;
  EXPECT_EQ(dot(gap, gap), want.squared_distance) << what;
  EXPECT_EQ(d.status == ContactStatus::separate, sgn(want.squared_distance) > 0) << what;
  const Rational lo(d.lower), hi(d.upper);
  EXPECT_LE(lo * lo, want.squared_distance) << what;
  EXPECT_GE(hi * hi, want.squared_distance) << what;
  EXPECT_LE(d.lower, d.distance) << what;
  EXPECT_LE(d.distance, d.upper) << what;
  if (d.status != ContactStatus::separate) {
    // A common point: in both placed bodies (P' and Q' as half-spaces).
    EXPECT_EQ(got.point_p, got.point_q) << what;
    EXPECT_TRUE(in_placed(a.polytope(), pa.map(), got.point_p)) << what;
    EXPECT_TRUE(in_placed(b.polytope(), pb.map(), got.point_q)) << what;
  }
}

void expect_distances_agree(const std::string& a, const std::string& b, int poses, double spread, std::uint64_t seed,
                            int max_exact) {
  const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
  Rng r(seed);
  RigidWarmStart warm;
  int separate = 0;
  const RigidStats before = rigid_stats();
  for (int i = 0; i < poses; ++i) {
    // Quaternion and matrix, matrix and quaternion, two matrices (then
    // every input is a double: the exact stage's integers).
    const RigidPose pp = random_pose(r, spread, i % 3 == 0), pq = random_pose(r, spread, i % 3 == 1);
    const RigidDistance d = distance(pa, pp, pb, pq, &warm);
    separate += d.status == ContactStatus::separate;
    expect_distance_agrees(pa, pp, pb, pq, d,
                           a + " / " + b + ", seed " + std::to_string(seed) + ", pose " + std::to_string(i));
  }
  EXPECT_GT(separate, poses / 10) << a;
  EXPECT_LT(separate, poses - poses / 10) << a;
  // Random poses are certified by the search (closest points or a
  // tetrahedron): M is built for (nearly) none of them.
  EXPECT_LE(int(rigid_stats().exact - before.exact), max_exact) << a << " / " << b;
}

}  // namespace

TEST(RigidDistance, AgreesWithTheExactObstacleOnRandomPoses) {
  expect_distances_agree("cube", "cube", 80, 2.5, 61, 0);
  expect_distances_agree("tetra", "octahedron", 80, 2.0, 62, 0);
  expect_distances_agree("dodecahedron", "cube@rot:3", 80, 2.5, 63, 0);
  expect_distances_agree("sphere:2", "random:50:2", 60, 2.0, 64, 0);
  expect_distances_agree("cube@scale:1/3", "tetra@rot:2", 60, 0.8, 65, 0);  // rationals: no doubles stage
}

TEST(RigidDistance, FaceOnFaceEdgeOnFaceAndVertexOnFaceAtAHair) {
  // The contacts of RigidCollide.ExactlyTouchingPoses, moved 2^-40 up: the
  // closest features are a face pair (four level vertices on each side), an
  // edge over a face and a vertex over a face; the distance is 2^-40
  // exactly.  At contact the distance is 0 (touching, on M).
  const RigidBody cube(catalog_polytope("cube")), dodeca(catalog_polytope("dodecahedron"));
  const std::array<double, 9> none{};
  const Rational hair(1, Integer(1) << 40);
  Rng r(5);
  const std::array<double, 9> m = random_matrix(r);
  const PlacedMap dm(m, P(0, 0, 0));
  struct Case {
    const RigidBody* q;
    PlacedMap rot;
    Rational x, y;
    bool matrix;
    const char* what;
  };
  const std::vector<Case> cases{
      {&cube, PlacedMap::rotation({Integer(2), Integer(0), Integer(0), Integer(1)}, P(0, 0, 0)), Rational(1, 2), 0,
       false, "face-face"},
      {&cube, PlacedMap::rotation({Integer(2), Integer(1), Integer(0), Integer(0)}, P(0, 0, 0)), 0, 0, false,
       "edge-face"},
      {&cube, PlacedMap::rotation({Integer(1), Integer(2), Integer(3), Integer(4)}, P(0, 0, 0)), 0, 0, false,
       "vertex-face"},
      {&cube, dm, Rational(1, 3), Rational(-1, 5), true, "vertex-face, double matrix"},
      {&dodeca, PlacedMap::rotation({Integer(1), Integer(2), Integer(3), Integer(4)}, P(0, 0, 0)), Rational(1, 7),
       0, false, "dodecahedron"}};
  for (const Case& c : cases) {
    const Index low = lowest(c.q->polytope(), c.rot);
    for (const Rational& dz : std::vector<Rational>{hair, Rational(0), Rational(-hair)}) {
      const RigidPose pq = on_top(c.q->polytope(), c.rot, low, c.x, c.y, dz, c.matrix, c.matrix ? m : none);
      const RigidDistance d = distance(cube, RigidPose(), *c.q, pq);
      const std::string what = std::string(c.what) + ", dz " + dz.get_str();
      expect_distance_agrees(cube, RigidPose(), *c.q, pq, d, what);
      const RigidDistanceExact e = exact_values(cube, RigidPose(), *c.q, pq, d);
      if (sgn(dz) > 0) {
        EXPECT_EQ(d.certificate, RigidCertificate::closest_points) << what;
        EXPECT_EQ(e.squared_distance, hair * hair) << what;
        EXPECT_EQ(e.point_q - e.point_p, Point3(0, 0, hair)) << what;
      } else {
        EXPECT_EQ(e.squared_distance, 0) << what;
        EXPECT_EQ(d.status, sgn(dz) == 0 ? ContactStatus::touching : ContactStatus::penetrating) << what;
      }
      if (sgn(dz) == 0) {
        // Touching, proved by the feature plane: its common point lies in
        // both placed bodies (on P's top face, inside Q's placed hull).
        EXPECT_EQ(d.certificate, RigidCertificate::feature_plane) << what;
        EXPECT_EQ(e.point_p, e.point_q) << what;
        EXPECT_EQ(e.point_p.z, 1) << what;
        EXPECT_TRUE(abs(e.point_p.x) <= 1 && abs(e.point_p.y) <= 1) << what;
      }
    }
  }
}

TEST(RigidDistance, ParallelEdgesAndTheClosestPointInsideAFace) {
  // Two unit cubes side by side along x, 1/3 apart, Q shifted by (…, 1/2,
  // 1/4): the closest points form a whole rectangle of the facing faces
  // (no unique pair); any certified pair is 1/3 apart.
  const RigidBody cube(catalog_polytope("cube"));
  const RigidPose pq = RigidPose::translation(Point3(Rational(7, 3), Rational(1, 2), Rational(1, 4)));
  const RigidDistance d = distance(cube, RigidPose(), cube, pq);
  expect_distance_agrees(cube, RigidPose(), cube, pq, d, "face-face, offset");
  EXPECT_EQ(exact_values(cube, RigidPose(), cube, pq, d).squared_distance, Rational(1, 9));
  // Turned by 45° in doubles about z (a matrix taken exactly): an edge of Q
  // parallel to a face of P.
  const double c = std::sqrt(0.5);
  const RigidPose turned = RigidPose::matrix({c, -c, 0, c, c, 0, 0, 0, 1}, Point3(3, Rational(1, 5), 0));
  const RigidDistance e = distance(cube, RigidPose(), cube, turned);
  expect_distance_agrees(cube, RigidPose(), cube, turned, e, "edge-face, turned");
}

namespace {

// A mesh-like hull: grids on the faces of [-1, 1]^3 bulging out by up to
// 2e-7 (a cap of a paraboloid, jittered), so that neighbouring facets
// differ by about 1e-8 rad.
ConvexPolytope flattened_hull(Rng& r) {
  PointList pts;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0})
      for (int i = 0; i <= 12; ++i)
        for (int j = 0; j <= 12; ++j) {
          double c[3];
          const double x = -1 + i / 6.0, y = -1 + j / 6.0;
          c[axis] = side * (1 + 1e-7 * (2 - x * x - y * y + r.uniform(0, 0.01)));
          c[(axis + 1) % 3] = x, c[(axis + 2) % 3] = y;
          pts.push_back(Vec3d{c[0], c[1], c[2]});
        }
  return ConvexPolytope::hull(pts);
}

// Poses of `small` at 1e-9 of its contact with `hull`: for 4 random
// orientation pairs, 50 translations each, the exact contact translation
// along a random direction times f (1 ± 1e-9), rounded to doubles.  `check`
// gets each pose with its orientation pair's exact obstacle and the
// translation.
template <class Check>
void near_contact_poses(Rng& r, const ConvexPolytope& hull, const ConvexPolytope& small, double f, const Check& check) {
  for (int k = 0; k < 4; ++k) {
    const std::array<double, 9> ra = random_matrix(r), rb = random_matrix(r);
    TranslationalObstacle ob(placed_linear(hull, PlacedMap(ra, Vec3d{0, 0, 0})),
                             placed_linear(small, PlacedMap(rb, Vec3d{0, 0, 0})));
    const Point3 c = ob.interior_point();
    for (int i = 0; i < 50; ++i) {
      const Point3 u(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
      const Rational alpha = ob.directional_depth_point(c, -u).t;
      const Vec3d sd = to_double(c + (alpha * Rational(f)) * u);
      check(RigidPose::matrix(ra, Vec3d{0, 0, 0}), RigidPose::matrix(rb, sd), ob, Point3(sd.x, sd.y, sd.z),
            "orientation " + std::to_string(k) + ", pose " + std::to_string(i));
    }
  }
}

}  // namespace

TEST(RigidDistance, NearTouchingOnNearlyCoplanarFacetsWithoutM) {
  // A small cube at 1e-9 outside its contact with the flattened hull: the
  // search's doubles then stop near the closest features, not always on
  // them; the certificate fails there and exact GJK steps go on from the
  // search's simplex (refine_closest).  Every answer is the exact
  // obstacle's, and M is built for none of them.
  const std::uint64_t seed = 48;
  Rng r(seed);
  const ConvexPolytope hull = flattened_hull(r);
  ASSERT_GT(hull.num_facets(), 1000u);
  const ConvexPolytope small = catalog_polytope("cube@scale:1/4");
  const RigidBody a(hull), b(small);
  const RigidStats before = rigid_stats();
  int separate = 0, poses = 0;
  RigidWarmStart warm;
  near_contact_poses(r, hull, small, 1 + 1e-9,
                     [&](const RigidPose& pa, const RigidPose& pb, TranslationalObstacle& ob, const Point3& s,
                         const std::string& where) {
                       const RigidDistance d = distance(a, pa, b, pb, &warm);
                       const std::string what = "seed " + std::to_string(seed) + ", " + where;
                       const DistanceResult want = ob.distance_point(s);
                       EXPECT_EQ(d.status, want.status) << what;
                       EXPECT_EQ(exact_values(a, pa, b, pb, d).squared_distance, want.squared_distance()) << what;
                       separate += d.status == ContactStatus::separate;
                       ++poses;
                     });
  EXPECT_EQ(poses, 200);
  EXPECT_GT(separate, 150) << "seed " << seed;
  EXPECT_EQ(rigid_stats().exact - before.exact, 0u) << "seed " << seed;
}

TEST(RigidCollide, NearTouchingOutsideByTheFiltersAlone) {
  // Bodies at 1e-9 outside contact: along the separating direction the
  // vertices of the facet in contact are level within rounding, and an
  // exact climb needs exact signs to name the highest.  The top clusters
  // (Placed::top_cluster) prove the gap with the filters alone: no exact
  // sign at all, and every answer the exact obstacle's, its plane checked
  // on every vertex.
  const std::uint64_t seed = 51;
  Rng r(seed);
  for (const auto& [a, b] : {std::pair{"cube", "cube@scale:1/2"}, {"random:50:1", "random:50:2"}}) {
    const ConvexPolytope pa = catalog_polytope(a), pb = catalog_polytope(b);
    const RigidBody ba(pa), bb(pb);
    int separate = 0;
    std::uint64_t exact = 0;
    RigidWarmStart warm;
    near_contact_poses(r, pa, pb, 1 + 1e-9,
                       [&](const RigidPose& ppa, const RigidPose& ppb, TranslationalObstacle& ob, const Point3& s,
                           const std::string& where) {
                         const std::string what = std::string(a) + ", seed " + std::to_string(seed) + ", " + where;
                         const PlacedPredicateCounts before = placed_predicate_counts();
                         const RigidCollision c = collide(ba, ppa, bb, ppb, &warm);
                         exact += placed_predicate_counts().exact - before.exact;
                         ASSERT_EQ(c.status, ob.collide_point(s).status) << what;
                         if (c.status != ContactStatus::separate) return;
                         ++separate;
                         ASSERT_EQ(c.certificate, RigidCertificate::separating_plane) << what;
                         const Point3 n(c.normal.x, c.normal.y, c.normal.z);
                         const Rational hp = dot(n, ppa.map().apply(pa.point(c.p)));
                         const Rational hq = dot(n, ppb.map().apply(pb.point(c.q)));
                         for (Index v = 0; v < pa.num_vertices(); ++v)
                           EXPECT_LT(dot(n, ppa.map().apply(pa.point(v))), hq) << what;
                         for (Index v = 0; v < pb.num_vertices(); ++v)
                           EXPECT_GT(dot(n, ppb.map().apply(pb.point(v))), hp) << what;
                       });
    EXPECT_GT(separate, 150) << a;
    EXPECT_EQ(exact, 0u) << a << ": exact signs";
  }
}

TEST(RigidCollide, NearTouchingInsideOnNearlyCoplanarFacets) {
  // The cube at 1e-9 inside its contact with the flattened hull: the search
  // in doubles often finds no tetrahedron (the origin within rounding of
  // ∂D) and no candidate plane separates or touches; a tetrahedron over the
  // face of D nearest the origin, certified exactly, proves the
  // penetration (FeaturePlane::inward_tetrahedron) where M was built.
  // Every answer is the exact obstacle's.
  const std::uint64_t seed = 49;
  Rng r(seed);
  const ConvexPolytope hull = flattened_hull(r);
  const ConvexPolytope small = catalog_polytope("cube@scale:1/4");
  const RigidBody a(hull), b(small);
  const RigidStats before = rigid_stats();
  int penetrating = 0, poses = 0;
  RigidWarmStart warm;
  near_contact_poses(r, hull, small, 1 - 1e-9,
                     [&](const RigidPose& pa, const RigidPose& pb, TranslationalObstacle& ob, const Point3& s,
                         const std::string& where) {
                       const RigidCollision c = collide(a, pa, b, pb, &warm);
                       EXPECT_EQ(c.status, ob.collide_point(s).status)
                           << "seed " << seed << ", " << where;
                       penetrating += c.status == ContactStatus::penetrating;
                       ++poses;
                     });
  const RigidStats after = rigid_stats();
  EXPECT_EQ(poses, 200);
  EXPECT_GT(penetrating, 150) << "seed " << seed;
  EXPECT_GE(after.inward_tetrahedra - before.inward_tetrahedra, 10u) << "seed " << seed;
  EXPECT_LE(after.exact - before.exact, 4u) << "seed " << seed;  // 16 without the tetrahedra over the face
  std::printf("flattened hull / cube 1e-9 inside: %llu inward tetrahedra, M built for %llu of 200 poses\n",
              static_cast<unsigned long long>(after.inward_tetrahedra - before.inward_tetrahedra),
              static_cast<unsigned long long>(after.exact - before.exact));
}

TEST(RigidDistance, BatchEqualsSingleQueries) {
  const RigidBody a(catalog_polytope("random:50:1")), b(catalog_polytope("sphere:2"));
  std::vector<RigidPose> pp, pq;
  random_pose_pairs(71, 600, 2.0, pp, pq);
  std::vector<RigidDistance> out(pp.size());
  distance(a, pp, b, pq, out, 2);
  for (std::size_t i = 0; i < pp.size(); ++i) {
    const RigidDistance one = distance(a, pp[i], b, pq[i]);
    EXPECT_EQ(out[i].status, one.status) << "pose " << i;
    EXPECT_EQ(exact_values(a, pp[i], b, pq[i], out[i]).squared_distance,
              exact_values(a, pp[i], b, pq[i], one).squared_distance)
        << "pose " << i;
    if (i % 60 == 0) expect_distance_agrees(a, pp[i], b, pq[i], out[i], "pose " + std::to_string(i));
  }
  std::vector<RigidDistance> wrong(3);
  EXPECT_THROW(distance(a, pp, b, pq, wrong, 1), UsageError);
  RigidDistance bad = out[0];
  bad.k = 0;
  bad.certificate = RigidCertificate::closest_points;
  EXPECT_THROW(exact_values(a, pp[0], b, pq[0], bad), UsageError);
}

TEST(PlacedSimplexPoint, AgreesWithRationals) {
  // Random pairs on random placements, in all four rounding modes: λ signs,
  // independence, |v|² inside its enclosure, and the climb signs against
  // the exact direction −v pulled through A_p.
  Rng r(81);
  for (int i = 0; i < 200; ++i) {
    // Every third case: both maps doubles and every point a double (the
    // exact stage on integers over a power of two).
    const bool doubles = i % 3 == 2;
    const RigidPose pp = random_pose(r, 1.0, !doubles && i % 2 == 0), pq = random_pose(r, 1.0, !doubles && i % 2 == 1);
    const int k = 1 + (i / 3) % 3;
    std::array<Point3, 3> p, q;
    std::array<PointBounds, 3> pb, qb;
    for (int j = 0; j < k; ++j) {
      // Sometimes the same vertex twice (a dependent simplex).
      p[j] = (j > 0 && i % 7 == 0) ? p[0] : Point3(Rational(Rational(r.integer(-9, 9)) / 4), Rational(r.integer(-9, 9)), Rational(r.uniform(-1, 1)));
      q[j] = (j > 0 && i % 7 == 0) ? q[0]
             : Point3(Rational(r.uniform(-1, 1)), Rational(Rational(r.integer(-9, 9)) / (doubles ? 8 : 3)),
                      Rational(r.integer(-9, 9)));
      pb[j] = point_bounds(p[j]), qb[j] = point_bounds(q[j]);
    }
    std::array<const Point3*, 3> pp3{&p[0], &p[1], &p[2]}, qp3{&q[0], &q[1], &q[2]};
    std::array<const PointBounds*, 3> pbb{&pb[0], &pb[1], &pb[2]}, qbb{&qb[0], &qb[1], &qb[2]};
    // The reference: v by least squares in rationals.
    std::array<Point3, 3> d;
    for (int j = 0; j < k; ++j) d[j] = pp.map().apply(p[j]) - pq.map().apply(q[j]);
    for (int mode : {FE_TONEAREST, FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
      const RoundingMode guard(mode);
      const PlacedSimplexPoint sp(pp.map(), pq.map(), k, pp3, pbb, qp3, qbb);
      bool independent = true;
      if (k == 2) independent = !is_zero(d[1] - d[0]);
      if (k == 3) independent = !is_zero(cross(d[1] - d[0], d[2] - d[0]));
      ASSERT_EQ(sp.independent(), independent) << "seed 81, case " << i;
      if (!independent) continue;
      Point3 v(0, 0, 0);
      Rational sum = 0;
      for (int j = 0; j < k; ++j) {
        v = v + sp.lambda(j) * d[j];
        sum += sp.lambda(j);
        EXPECT_EQ(sp.lambda_sign(j), sgn(sp.lambda(j))) << "case " << i;
      }
      EXPECT_EQ(sum, 1) << "case " << i;
      for (int j = 1; j < k; ++j) EXPECT_EQ(dot(v, d[j] - d[0]), 0) << "case " << i;  // v ⊥ the hull
      EXPECT_EQ(sp.squared_norm(), dot(v, v)) << "case " << i;
      const Bounds b = sp.squared_norm_bounds();
      EXPECT_LE(Rational(b.lo), dot(v, v)) << "case " << i;
      EXPECT_GE(Rational(b.hi), dot(v, v)) << "case " << i;
      EXPECT_EQ(sp.nonzero(), !is_zero(v)) << "case " << i;
      const Point3 a(Rational(r.integer(-3, 3)), Rational(1, 3), Rational(0));
      const Point3 c(Rational(0), Rational(r.uniform(-1, 1)), Rational(Rational(r.integer(-5, 5)) / 7));
      Point3 up, uq;
      for (int col = 0; col < 3; ++col) {
        up[col] = -(pp.map().a(0, col) * v.x + pp.map().a(1, col) * v.y + pp.map().a(2, col) * v.z);
        uq[col] = pq.map().a(0, col) * v.x + pq.map().a(1, col) * v.y + pq.map().a(2, col) * v.z;
      }
      EXPECT_EQ(sp.climb_sign_p(a, point_bounds(a), c, point_bounds(c)), sgn(dot(up, c - a))) << "case " << i;
      EXPECT_EQ(sp.climb_sign_q(a, point_bounds(a), c, point_bounds(c)), sgn(dot(uq, c - a))) << "case " << i;
      // Level by construction: the climb sign between two points of a pair
      // set with the same partner is exactly 0.
      if (k >= 2) {
        EXPECT_EQ(sp.climb_sign_p(a, point_bounds(a), a, point_bounds(a)), 0);
      }
    }
  }
}

TEST(RigidDistance, SymmetricPenetrationOnACoplanarTriangle) {
  // A cube turned about z by the rational rotation of (2, 0, 0, 1) and a
  // cube shifted by 1/2 along x: every support of the search has z = ±1 in
  // pairs, its triangle holds the origin and no tetrahedron of the search
  // does.  The supports along the triangle's normals give one: penetrating,
  // certified without M (it used to be decided on M).
  const RigidBody cube(catalog_polytope("cube"));
  const RigidPose pa = RigidPose::translation(Point3(Rational(1, 2), 0, 0));
  const RigidPose pb = RigidPose::quaternion({Integer(2), Integer(0), Integer(0), Integer(1)}, P(0, 0, 0));
  const RigidDistance d = distance(cube, pa, cube, pb);
  EXPECT_EQ(d.status, ContactStatus::penetrating);
  EXPECT_EQ(d.certificate, RigidCertificate::simplex);
  expect_distance_agrees(cube, pa, cube, pb, d, "turned cube");
  const RigidCollision c = collide(cube, pa, cube, pb);
  EXPECT_EQ(c.status, ContactStatus::penetrating);
  EXPECT_EQ(c.certificate, RigidCertificate::simplex);
}

// ---------------------------------------------------------------------------
// Penetration depth under rigid motion, against M built exactly.

namespace {

void expect_depth_agrees(const RigidBody& a, const RigidPose& pa, const RigidBody& b, const RigidPose& pb,
                         const RigidDepth& d, const std::string& what) {
  const RigidDepthExact want = depth_exact(a, pa, b, pb);
  const RigidDepthExact got = exact_values(a, pa, b, pb, d);
  EXPECT_EQ(got.squared_depth, want.squared_depth) << what;
  EXPECT_EQ(dot(got.direction, got.direction), want.squared_depth) << what;
  EXPECT_EQ(d.status, collide_exact(a, pa, b, pb)) << what;
  const Rational lo(d.lower), hi(d.upper);
  EXPECT_LE(lo * lo, want.squared_depth) << what;
  EXPECT_GE(hi * hi, want.squared_depth) << what;
  if (d.status == ContactStatus::penetrating) {
    // Translated by the direction, the bodies touch.
    Point3 t = pa.map().t() + got.direction;
    std::array<std::array<Rational, 3>, 3> m;
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) m[x][y] = pa.map().a(x, y);
    EXPECT_EQ(collide_exact(a, RigidPose(PlacedMap(m, t)), b, pb), ContactStatus::touching) << what;
  }
}

void expect_depths_agree(const std::string& a, const std::string& b, int poses, double spread, std::uint64_t seed,
                         int max_exact) {
  const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
  Rng r(seed);
  RigidWarmStart warm;
  int penetrating = 0;
  const RigidStats before = rigid_stats();
  for (int i = 0; i < poses; ++i) {
    const RigidPose pp = random_pose(r, spread, i % 3 == 0), pq = random_pose(r, spread, i % 3 == 1);
    const RigidDepth d = penetration_depth(pa, pp, pb, pq, &warm);
    penetrating += d.status == ContactStatus::penetrating;
    expect_depth_agrees(pa, pp, pb, pq, d,
                        a + " / " + b + ", seed " + std::to_string(seed) + ", pose " + std::to_string(i));
  }
  EXPECT_GT(penetrating, poses / 2) << a;
  EXPECT_LE(int(rigid_stats().exact - before.exact), max_exact) << a << " / " << b;
}

}  // namespace

TEST(RigidDepth, AgreesWithTheExactObstacleOnRandomPoses) {
  expect_depths_agree("cube", "cube", 60, 1.0, 91, 0);
  expect_depths_agree("tetra", "octahedron", 60, 0.6, 92, 0);
  expect_depths_agree("dodecahedron", "cube@rot:3", 60, 1.0, 93, 0);
  expect_depths_agree("sphere:2", "random:50:2", 40, 0.8, 94, 0);
  expect_depths_agree("cube@scale:1/3", "tetra@rot:2", 40, 0.3, 95, 0);
}

TEST(RigidDepth, NearTouchingOnNearlyCoplanarFacetsGrowsPastRefutedFaces) {
  // A cylinder at 1e-9 inside its contact with the flattened hull: EPA's
  // doubles stop on a face whose plane a vertex of D passes by less than
  // they resolve.  The exact climbs that refute the face find that vertex,
  // and EPA grows on from it (penetration_depth's continuation) where M
  // was built.  Every depth is the exact obstacle's.
  const std::uint64_t seed = 52;
  Rng r(seed);
  // The box [-1, 1]^3 with faces bulging by 1e-7 (a 30 x 30 grid each) and
  // a cylinder of 600 sides, radius 0.8, height 2, their points rounded to
  // floats as a mesh file stores them: on the box, runs of facets within
  // rounding of one plane.
  const auto to_float = [](double x) { return double(float(x)); };
  PointList box_points, cylinder_points;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0})
      for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 30; ++j) {
          double c[3];
          const double x = -1 + i * 2 / 29.0, y = -1 + j * 2 / 29.0;
          c[axis] = to_float(side * (1 + 0.5e-7 * (2 - x * x - y * y)));
          c[(axis + 1) % 3] = to_float(x), c[(axis + 2) % 3] = to_float(y);
          box_points.push_back(Vec3d{c[0], c[1], c[2]});
        }
  for (int k = 0; k < 600; ++k)
    for (double z : {-1.0, 1.0}) {
      const double t = 2 * M_PI * k / 600;
      cylinder_points.push_back(Vec3d{to_float(0.8 * std::cos(t)), to_float(0.8 * std::sin(t)), z});
    }
  const ConvexPolytope hull = ConvexPolytope::hull(box_points), small = ConvexPolytope::hull(cylinder_points);
  const RigidBody a(hull), b(small);
  const RigidStats before = rigid_stats();
  int penetrating = 0;
  RigidWarmStart warm;
  near_contact_poses(r, hull, small, 1 - 1e-9,
                     [&](const RigidPose& pa, const RigidPose& pb, TranslationalObstacle& ob, const Point3& s,
                         const std::string& where) {
                       const RigidDepth d = penetration_depth(a, pa, b, pb, &warm);
                       const std::string what = "seed " + std::to_string(seed) + ", " + where;
                       const DepthResult want = ob.penetration_depth(Point3(0, 0, 0), s);
                       ASSERT_EQ(d.status, want.status) << what;
                       if (d.status != ContactStatus::penetrating) return;
                       ++penetrating;
                       EXPECT_EQ(exact_values(a, pa, b, pb, d).squared_depth, want.squared_depth()) << what;
                     });
  const RigidStats after = rigid_stats();
  std::printf("vertices added past refuted faces: %llu; M built: %llu\n",
              static_cast<unsigned long long>(after.epa_continuations - before.epa_continuations),
              static_cast<unsigned long long>(after.exact - before.exact));
  EXPECT_GT(penetrating, 150) << "seed " << seed;
  EXPECT_GT(after.epa_continuations, before.epa_continuations) << "seed " << seed;
  EXPECT_EQ(after.exact - before.exact, 0u) << "seed " << seed;  // 16 without the continuation
}

TEST(RigidDepth, AxisAlignedOverlapAndContactsAtAHair) {
  // Aligned cubes overlapping by 1/2 along x: D's nearest facet is a square
  // (the surface's triangles on it are coplanar: ties decided exactly).
  const RigidBody cube(catalog_polytope("cube"));
  const RigidPose pq = RigidPose::translation(Point3(Rational(3, 2), Rational(1, 5), Rational(-1, 7)));
  const RigidDepth d = penetration_depth(cube, RigidPose(), cube, pq);
  expect_depth_agrees(cube, RigidPose(), cube, pq, d, "aligned cubes");
  const RigidDepthExact e = exact_values(cube, RigidPose(), cube, pq, d);
  EXPECT_EQ(e.squared_depth, Rational(1, 4));
  EXPECT_EQ(e.direction, Point3(Rational(-1, 2), 0, 0));
  // The contacts of RigidCollide.ExactlyTouchingPoses pushed 2^-40 in: the
  // depth is 2^-40 exactly, upwards; at contact 0 (touching), above 0.
  const Rational hair(1, Integer(1) << 40);
  const std::array<double, 9> none{};
  for (const auto& [quat, what] : std::vector<std::pair<Quaternion, std::string>>{
           {{Integer(2), Integer(0), Integer(0), Integer(1)}, "face-face"},
           {{Integer(2), Integer(1), Integer(0), Integer(0)}, "edge-face"},
           {{Integer(1), Integer(2), Integer(3), Integer(4)}, "vertex-face"}}) {
    const PlacedMap rot = PlacedMap::rotation(quat, P(0, 0, 0));
    const Index low = lowest(cube.polytope(), rot);
    for (const Rational& dz : std::vector<Rational>{Rational(-hair), Rational(0), hair}) {
      const RigidPose pose = on_top(cube.polytope(), rot, low, Rational(1, 3), 0, dz, false, none);
      const RigidDepth r = penetration_depth(cube, RigidPose(), cube, pose);
      expect_depth_agrees(cube, RigidPose(), cube, pose, r, what + ", dz " + dz.get_str());
      const RigidDepthExact x = exact_values(cube, RigidPose(), cube, pose, r);
      if (sgn(dz) < 0) {
        EXPECT_EQ(x.squared_depth, hair * hair) << what;
        EXPECT_EQ(x.direction, Point3(0, 0, -hair)) << what;
      } else {
        EXPECT_EQ(x.squared_depth, 0) << what;
      }
    }
  }
  std::vector<RigidDepth> out(2);
  const std::vector<RigidPose> poses{RigidPose(), pq};
  penetration_depth(cube, std::span<const RigidPose>(poses.data(), 1), cube, poses, out, 1);
  EXPECT_EQ(exact_values(cube, RigidPose(), cube, pq, out[1]).squared_depth, Rational(1, 4));
  EXPECT_EQ(out[0].status, ContactStatus::penetrating);  // the same cube twice
}

TEST(RigidDirectionalDepth, AgreesWithTheExactObstacleOnRandomPoses) {
  // Random poses and random directions (exact: doubles and p/q); every α
  // equal to M's; moved by α·d, P touches Q exactly.
  for (const auto& [a, b, spread, seed] : std::vector<std::tuple<std::string, std::string, double, std::uint64_t>>{
           {"cube", "cube", 1.0, 101}, {"dodecahedron", "cube@rot:3", 1.0, 102}, {"sphere:2", "random:50:2", 0.8, 103},
           {"cube@scale:1/3", "tetra@rot:2", 0.3, 104}}) {
    const RigidBody pa(catalog_polytope(a)), pb(catalog_polytope(b));
    Rng r(seed);
    RigidWarmStart warm;
    int penetrating = 0;
    const RigidStats before = rigid_stats();
    for (int i = 0; i < 40; ++i) {
      const RigidPose pp = random_pose(r, spread, i % 3 == 0), pq = random_pose(r, spread, i % 3 == 1);
      const Point3 d = i % 2 ? Point3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1))
                             : Point3(Rational(r.integer(-5, 5)), Rational(1, 3), Rational(r.integer(1, 4)));
      const std::string what = a + " / " + b + ", seed " + std::to_string(seed) + ", pose " + std::to_string(i);
      const RigidDirectionalDepth dd = directional_depth(pa, pp, pb, pq, d, &warm);
      const Rational want = directional_depth_exact(pa, pp, pb, pq, d);
      const Rational got = exact_values(pa, pp, pb, pq, d, dd);
      EXPECT_EQ(got, want) << what;
      EXPECT_LE(Rational(dd.lower), want) << what;
      EXPECT_GE(Rational(dd.upper), want) << what;
      if (dd.status != ContactStatus::penetrating) continue;
      ++penetrating;
      std::array<std::array<Rational, 3>, 3> m;
      for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y) m[x][y] = pp.map().a(x, y);
      EXPECT_EQ(collide_exact(pa, RigidPose(PlacedMap(m, pp.map().t() + got * d)), pb, pq), ContactStatus::touching)
          << what;
    }
    EXPECT_GT(penetrating, 20) << a;
    EXPECT_EQ(rigid_stats().exact - before.exact, 0u) << a << " / " << b;
  }
  const RigidBody cube(catalog_polytope("cube"));
  EXPECT_THROW(directional_depth(cube, RigidPose(), cube, RigidPose(), Point3(0, 0, 0)), UsageError);
}
