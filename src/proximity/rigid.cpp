// Collision of two placed convex polytopes: GJK on doubles with supports by
// hill climbing, certified by exact signs (rigid_proximity.hpp,
// docs/proximity.md "Rigid motion").
#include <minksum/error.hpp>
#include <minksum/parallel.hpp>
#include <minksum/rigid_proximity.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace minksum {

struct RigidBody::Data {
  ConvexPolytope poly;
  std::vector<Vec3d> approx;          // vertices, nearest doubles
  std::vector<PointBounds> bounds;    // their enclosures
  std::vector<Index> first;           // neighbours of v: nbr[first[v] .. first[v + 1])
  std::vector<Index> nbr;
  Vec3d centroid;                     // of the vertices (doubles): the first search direction
  const Point3* exact = nullptr;      // poly.points(), exact (built once)
  // Every vertex coordinate is a double, and the least dyadic_exponent of
  // the non-zero ones (the feature plane's PlacedFrame).
  bool doubles = true;
  int exponent = std::numeric_limits<int>::max();
  // Where the searches' climbs start (a guess: every support is climbed to
  // a local maximum from wherever it starts).  The unit cube's six faces are
  // cut into side × side cells; seeds[(face · side + i) · side + j] is a
  // vertex maximising, in doubles, the direction to the centre of cell
  // (i, j).  seed(u) is that of the cell u points through, a few steps from
  // u's support where a climb from a far vertex takes about √V steps.
  // Empty only for a body without vertices.
  int side = 0;
  std::vector<Index> seeds;
  Index seed(double x, double y, double z) const {
    const double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    int face;
    double m, a, b;
    if (ax >= ay && ax >= az) face = x < 0, m = ax, a = y, b = z;
    else if (ay >= az) face = 2 + (y < 0), m = ay, a = z, b = x;
    else face = 4 + (z < 0), m = az, a = x, b = y;
    if (!(m > 0) || !std::isfinite(m)) return seeds[0];  // (NaN fails every comparison)
    // |a| ≤ m, so a / m is in [−1, 1] (division rounds monotonically).
    const double h = 0.5 * side;
    const int i = std::min(side - 1, int((a / m + 1) * h)), j = std::min(side - 1, int((b / m + 1) * h));
    return seeds[(std::size_t(face) * side + i) * side + j];
  }
};

namespace {

thread_local RigidStats g_stats;

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(double s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
inline double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline V3 v3(const Vec3d& v) { return {v.x, v.y, v.z}; }

// Bodies of at most this many vertices are scanned whole for a support in
// doubles: cheaper than a seed and a climb's branches at that size.
constexpr std::size_t kScanVertices = 16;

// One placed body for the search: the pose's doubles.
struct Placed {
  const RigidBody::Data& d;
  const PlacedMap& map;
  const std::array<double, 9>& a;
  V3 t;
  Placed(const RigidBody::Data& data, const PlacedMap& m) : d(data), map(m), a(m.approx_a()), t(v3(m.approx_t())) {}
  // Aᵀ n (doubles).
  V3 pull(const V3& n) const {
    return {a[0] * n.x + a[3] * n.y + a[6] * n.z, a[1] * n.x + a[4] * n.y + a[7] * n.z,
            a[2] * n.x + a[5] * n.y + a[8] * n.z};
  }
  V3 point(Index v) const {
    const Vec3d& p = d.approx[v];
    return {a[0] * p.x + a[1] * p.y + a[2] * p.z + t.x, a[3] * p.x + a[4] * p.y + a[5] * p.z + t.y,
            a[6] * p.x + a[7] * p.y + a[8] * p.z + t.z};
  }
  // A vertex maximising n · x over the placed body, by steepest ascent on
  // the vertex graph from `v` (doubles: a guess, certified separately).
  Index support(const V3& n, Index v) const {
    const V3 u = pull(n);
    double best = dot(u, v3(d.approx[v]));
    if (d.approx.size() <= kScanVertices) {  // a few vertices: all of them (v kept on a tie)
      for (Index w = 0; w < Index(d.approx.size()); ++w) {
        const double s = dot(u, v3(d.approx[w]));
        if (s > best) best = s, v = w;
      }
      return v;
    }
    if (!d.seeds.empty()) {  // from the better of v and u's seed
      const Index s = d.seed(u.x, u.y, u.z);
      const double at_s = dot(u, v3(d.approx[s]));
      if (at_s > best) best = at_s, v = s;
    }
    for (;;) {
      Index next = v;
      for (Index k = d.first[v]; k < d.first[v + 1]; ++k) {
        const Index w = d.nbr[k];
        const double s = dot(u, v3(d.approx[w]));
        if (s > best) best = s, next = w;
      }
      if (next == v) return v;
      v = next;
      ++g_stats.climb_steps;
    }
  }
  // The same with exact signs: from v, move to a neighbour that is further
  // along u's direction n (exactly) until none is.  A vertex no neighbour of
  // which is further is a maximum over the polytope (its cone of edges
  // holds the polytope).
  Index certified_support(const PulledDirection& u, Index v) const {
    for (;;) {
      Index next = v;
      const Point3& pv = d.exact[v];
      for (Index k = d.first[v]; k < d.first[v + 1]; ++k) {
        const Index w = d.nbr[k];
        if (u.difference_sign(pv, d.bounds[v], d.exact[w], d.bounds[w]) > 0) {
          next = w;
          break;
        }
      }
      if (next == v) return v;
      v = next;
      ++g_stats.climb_steps;
    }
  }
  // The vertices near the maximum along u's direction n, by the filters
  // alone (no exact sign): from v, move to a neighbour proved further while
  // v is alone; then gather into `top` every vertex reached from it by an
  // edge not proved to go down.  Every edge leaving `top` then goes strictly
  // down, so the vertex of `top` highest along n has no higher neighbour:
  // it is the maximum over the polytope.  False when more than
  // TopCluster::kMax vertices would be gathered.
  struct TopCluster {
    static constexpr int kMax = 16;
    std::array<Index, kMax> v;
    int n = 0;
    bool has(Index x) const { return std::find(v.begin(), v.begin() + n, x) != v.begin() + n; }
  };
  bool top_cluster(const PulledDirection& u, Index v, TopCluster& top) const {
    top.v[0] = v, top.n = 1;
    for (int i = 0; i < top.n; ++i) {
      const Index x = top.v[i];
      for (Index k = d.first[x]; k < d.first[x + 1]; ++k) {
        const Index w = d.nbr[k];
        if (top.has(w)) continue;
        const int s = u.difference_sign_filter(d.bounds[x], d.bounds[w]);
        if (s == -1) continue;
        if (s == 1 && top.n == 1) {  // a climb step: start again from w
          top.v[0] = w, i = -1;
          ++g_stats.climb_steps;
          break;
        }
        if (top.n == TopCluster::kMax) return false;
        top.v[top.n++] = w;
      }
    }
    return true;
  }
};

// A vertex of the GJK simplex: w = p' − q'.
struct SimplexVertex {
  V3 w;
  Index p, q;
};

// The closest point to the origin of the simplex s (1–4 vertices), s
// reduced to the vertices of the smallest face holding it.  Returns false
// when the origin lies inside the tetrahedron (s keeps its 4 vertices).
// Doubles only (C. Ericson, "Real-Time Collision Detection", Morgan
// Kaufmann 2005, §5.1.5–5.1.6): a guide for the search, never a decision.
V3 closest_on_triangle(const SimplexVertex& A, const SimplexVertex& B, const SimplexVertex& C,
                       std::array<SimplexVertex, 4>& out, int& n) {
  const V3 a = A.w, b = B.w, c = C.w;
  const V3 ab = b - a, ac = c - a, ap = -a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    out[0] = A, n = 1;
    return a;
  }
  const V3 bp = -b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    out[0] = B, n = 1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    out[0] = A, out[1] = B, n = 2;
    return a + v * ab;
  }
  const V3 cp = -c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    out[0] = C, n = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    out[0] = A, out[1] = C, n = 2;
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    out[0] = B, out[1] = C, n = 2;
    return b + w * (c - b);
  }
  const double denom = 1 / (va + vb + vc);
  out[0] = A, out[1] = B, out[2] = C, n = 3;
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

bool closest_on_simplex(std::array<SimplexVertex, 4>& s, int& n, V3& v) {
  if (n == 1) {
    v = s[0].w;
    return true;
  }
  if (n == 2) {
    const V3 a = s[0].w, ab = s[1].w - a;
    const double l = dot(ab, ab);
    const double t = l > 0 ? -dot(a, ab) / l : 0;
    if (t <= 0) {
      n = 1;
      v = a;
    } else if (t >= 1) {
      s[0] = s[1], n = 1;
      v = s[0].w;
    } else {
      v = a + t * ab;
    }
    return true;
  }
  if (n == 3) {
    std::array<SimplexVertex, 4> out;
    int m = 0;
    v = closest_on_triangle(s[0], s[1], s[2], out, m);
    s = out, n = m;
    return true;
  }
  // A tetrahedron: the origin is inside unless it lies beyond the plane of a
  // face (on the side away from the fourth vertex); then the closest point
  // is on such a face.  A flat tetrahedron has no inside: every face is a
  // candidate.
  const V3 a = s[0].w, b = s[1].w, c = s[2].w, d = s[3].w;
  const double vol = dot(b - a, cross(c - a, d - a));
  const double scale = std::max({dot(b - a, b - a), dot(c - a, c - a), dot(d - a, d - a)});
  // Only the search's choice of faces, not a decision: the answer is
  // certified afterwards by exact signs whatever simplex the search keeps.
  const bool flat = !(std::fabs(vol) > 1e-12 * scale * std::sqrt(scale));
  static constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  double best = std::numeric_limits<double>::infinity();
  std::array<SimplexVertex, 4> best_s;
  int best_n = 0;
  bool outside = false;
  for (const auto& f : faces) {
    const V3 p0 = s[f[0]].w, p1 = s[f[1]].w, p2 = s[f[2]].w, p3 = s[f[3]].w;
    const V3 nf = cross(p1 - p0, p2 - p0);
    const double so = dot(-p0, nf), sd = dot(p3 - p0, nf);
    if (!flat && !(so * sd < 0)) continue;
    outside = true;
    std::array<SimplexVertex, 4> out;
    int m = 0;
    const V3 x = closest_on_triangle(s[f[0]], s[f[1]], s[f[2]], out, m);
    const double dd = dot(x, x);
    if (dd < best) best = dd, best_s = out, best_n = m, v = x;
  }
  if (!outside) return false;
  s = best_s, n = best_n;
  return true;
}

struct Query {
  Placed P, Q;
  const RigidBody::Data& dp;
  const RigidBody::Data& dq;

  // Certify "separate" along n from the supports' guesses ip, iq.  With
  // `open`, a gap the filters leave open is not evaluated exactly: *open is
  // set and the caller may evaluate it later (exact_gap).
  bool certify_separation(const Vec3d& n, Index& ip, Index& iq, bool* open = nullptr) const {
    if (open) *open = false;
    const PulledDirection up(P.map, n), uq(Q.map, Vec3d{-n.x, -n.y, -n.z});
    // The filters alone first: the maximum of P along n lies in P's top
    // cluster and the minimum of Q in Q's, so the plane separates strictly
    // when every pair of the two is proved apart along n, and does not when
    // one pair is proved not apart.  Near a contact a facet's vertices are
    // level within rounding along its normal, where only exact signs would
    // say which is the maximum; the gap between the bodies decides without
    // it.
    Placed::TopCluster tp, tq;
    if (P.top_cluster(up, ip, tp) && Q.top_cluster(uq, iq, tq)) {
      int worst = 1;
      for (int i = 0; i < tp.n && worst == 1; ++i)
        for (int j = 0; j < tq.n && worst == 1; ++j)
          worst = placed_gap_filter(n, P.map, dp.bounds[tp.v[i]], Q.map, dq.bounds[tq.v[j]]);
      if (worst != kGapOpen) {
        ip = tp.v[0], iq = tq.v[0];
        return worst == 1;
      }
    }
    ip = P.certified_support(up, ip);
    iq = Q.certified_support(uq, iq);
    if (open) {
      const int f = placed_gap_filter(n, P.map, dp.bounds[ip], Q.map, dq.bounds[iq]);
      *open = f == kGapOpen;
      return f == 1;
    }
    return exact_gap(n, ip, iq);
  }
  bool exact_gap(const Vec3d& n, Index ip, Index iq) const {
    return placed_gap_sign(n, P.map, dp.exact[ip], dp.bounds[ip], Q.map, dq.exact[iq], dq.bounds[iq]) > 0;
  }
  bool certify_tetrahedron(const std::array<SimplexVertex, 4>& s) const {
    std::array<const Point3*, 4> p, q;
    std::array<const PointBounds*, 4> pb, qb;
    for (int k = 0; k < 4; ++k) {
      p[k] = &dp.exact[s[k].p], pb[k] = &dp.bounds[s[k].p];
      q[k] = &dq.exact[s[k].q], qb[k] = &dq.bounds[s[k].q];
    }
    return placed_tetrahedron_holds_origin(P.map, Q.map, p, pb, q, qb);
  }
  // The interval stage only: 1, 0 or kTetrahedronOpen.
  int filter_tetrahedron(const std::array<SimplexVertex, 4>& s) const {
    std::array<const PointBounds*, 4> pb, qb;
    for (int k = 0; k < 4; ++k) pb[k] = &dp.bounds[s[k].p], qb[k] = &dq.bounds[s[k].q];
    return placed_tetrahedron_filter(P.map, Q.map, pb, qb);
  }
  SimplexVertex support(const V3& dir, Index ip, Index iq) const {
    // The support of D = P' − Q' along dir: P's along dir minus Q's along −dir.
    const Index a = P.support(dir, ip), b = Q.support(-dir, iq);
    return {P.point(a) - Q.point(b), a, b};
  }
};

constexpr int kMaxIterations = 128;
// Vertices of D a depth's surface takes beyond a nearest face that the
// exact climbs refute (penetration_depth), before M.
constexpr int kDepthContinuations = 8;

// The calling thread's count of answers proved by c.
void count(RigidCertificate c) {
  switch (c) {
    case RigidCertificate::separating_plane:
      ++g_stats.separating_plane;
      break;
    case RigidCertificate::simplex:
      ++g_stats.simplex;
      break;
    case RigidCertificate::exact:
      ++g_stats.exact;
      break;
    case RigidCertificate::closest_points:
      ++g_stats.closest_points;
      break;
    case RigidCertificate::nearest_facet:
      ++g_stats.nearest_facet;
      break;
    case RigidCertificate::exit_facet:
      ++g_stats.exit_facet;
      break;
    case RigidCertificate::feature_plane:
      ++g_stats.feature_plane;
      break;
  }
}

// When the search's triangle holds the origin in doubles (symmetric poses
// of bodies with parallel faces make the supports coplanar), no
// tetrahedron of the search holds it: take the supports a+ and a− of D
// along the triangle's two normals; the three tetrahedra (a+, a−, two
// vertices of the triangle) cover the double pyramid, and one of them
// holds an origin that lies inside it strictly.  True when one is
// certified (s then holds it).  With `deferred`, a tetrahedron whose
// intervals leave the answer open (the origin within rounding of its
// boundary) is not evaluated exactly but appended there, for the caller to
// evaluate after cheaper certificates.
using Tetrahedra = std::vector<std::array<SimplexVertex, 4>>;
bool blow_up_triangle(const Query& qu, std::array<SimplexVertex, 4>& s, Tetrahedra* deferred = nullptr) {
  const V3 nrm = cross(s[1].w - s[0].w, s[2].w - s[0].w);
  if (!(dot(nrm, nrm) > 0) || !std::isfinite(dot(nrm, nrm))) return false;
  const SimplexVertex up = qu.support(nrm, s[0].p, s[0].q), down = qu.support(-nrm, s[0].p, s[0].q);
  static constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& e : pairs) {
    const std::array<SimplexVertex, 4> t{up, down, s[e[0]], s[e[1]]};
    const int f = deferred ? qu.filter_tetrahedron(t) : int(qu.certify_tetrahedron(t));
    if (f == kTetrahedronOpen) deferred->push_back(t);
    if (f == 1) {
      s = t;
      return true;
    }
  }
  return false;
}

// The centroid of a placed body's vertices (doubles: a guess for the search).
V3 centre(const Placed& b) {
  const Vec3d& c = b.d.centroid;
  const auto& a = b.a;
  return V3{a[0] * c.x + a[1] * c.y + a[2] * c.z + b.t.x, a[3] * c.x + a[4] * c.y + a[5] * c.z + b.t.y,
            a[6] * c.x + a[7] * c.y + a[8] * c.z + b.t.z};
}

// ---------------------------------------------------------------------------
// The feature plane (docs/proximity.md, "Rigid motion"): near contact the
// double search ends on a simplex spanning (nearly) a facet of D = P' − Q',
// and a facet of D is a facet of P' with a vertex of Q', a vertex of P'
// with a facet of Q', or an edge of each.  Those features' plane, built
// exactly from the placed points (rationals), decides the pose without M:
// with N oriented from P' towards Q', h_P = max of N·x over P' and l_Q =
// min of N·y over Q' (exact climbs on the vertex graphs):
//   * h_P < l_Q: the plane N·x = h_P separates strictly: separate;
//   * h_P = l_Q: P' lies in N·x ≤ h, Q' in N·x ≥ h, so P' ∩ Q' = F_P ∩ F_Q
//     for their faces F_P = P' ∩ plane and F_Q = Q' ∩ plane (each a vertex,
//     an edge or a facet, the connected level set of the climb's vertex):
//     touching when F_P and F_Q meet, separate otherwise;
//   * h_P > l_Q: the plane proves nothing (M decides, as before).
// Two convex polygons in a plane (points and segments included) meet iff a
// vertex of one lies in the other or an edge of one crosses an edge of the
// other properly; the edges of a face are the edges of the vertex graph
// between its vertices (a segment between two vertices of a face of a
// convex polytope that is an edge of the polytope is an edge of the face).
struct FeatureContact {
  ContactStatus status = ContactStatus::separate;
  Point3 normal;  // N
  Index p = kNoIndex, q = kNoIndex;  // the climbs' vertices
  Point3 common;  // touching: a point of P' ∩ Q' (placed only when decide() is asked for it)
};

// Doubles along the direction of a rational vector, whatever its size (the
// frame's normals exceed the range of doubles): each coordinate as f 2^e
// from its numerator and denominator, all scaled by one power of two.  For
// choices only (an orientation), never a decision.
Vec3d scaled_direction(const Point3& n) {
  double f[3];
  long e[3], top = std::numeric_limits<long>::min();
  for (int r = 0; r < 3; ++r) {
    long en = 0, ed = 0;
    const double fn = mpz_get_d_2exp(&en, n[r].get_num_mpz_t()), fd = mpz_get_d_2exp(&ed, n[r].get_den_mpz_t());
    f[r] = fn / fd, e[r] = en - ed;
    if (fn != 0) top = std::max(top, e[r]);
  }
  if (top == std::numeric_limits<long>::min()) return {0, 0, 0};
  const auto at = [&](int r) { return f[r] == 0 ? 0.0 : std::ldexp(f[r], int(std::max(e[r] - top, -2000L))); };
  return {at(0), at(1), at(2)};
}

// The frame's points are integer vectors when the maps and the vertices are
// doubles (PlacedFrame): their signs below are then evaluated on the
// numerators alone, in GMP integers (no gcd, no temporaries), and in
// rationals otherwise.  The same polynomials, so the same signs.
bool integral(const Point3& p) {
  return mpz_cmp_ui(p.x.get_den_mpz_t(), 1) == 0 && mpz_cmp_ui(p.y.get_den_mpz_t(), 1) == 0 &&
         mpz_cmp_ui(p.z.get_den_mpz_t(), 1) == 0;
}
struct IntegerScratch {
  mpz_class t, u, acc;
};
IntegerScratch& scratch() {
  thread_local IntegerScratch s;
  return s;
}
// sign n · (b − a).
int dot_difference_sign(const Point3& n, const Point3& a, const Point3& b) {
  if (!integral(n) || !integral(a) || !integral(b)) return sgn(dot(n, b - a));
  IntegerScratch& z = scratch();
  mpz_set_ui(z.acc.get_mpz_t(), 0);
  for (int r = 0; r < 3; ++r) {
    mpz_sub(z.t.get_mpz_t(), b[r].get_num_mpz_t(), a[r].get_num_mpz_t());
    mpz_addmul(z.acc.get_mpz_t(), n[r].get_num_mpz_t(), z.t.get_mpz_t());
  }
  return mpz_sgn(z.acc.get_mpz_t());
}

// (b − a) × (d − c), on the numerators when all four are integer vectors.
Point3 cross_of_differences(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  if (!integral(a) || !integral(b) || !integral(c) || !integral(d)) return cross(b - a, d - c);
  mpz_class u[3], w[3];
  for (int r = 0; r < 3; ++r) {
    mpz_sub(u[r].get_mpz_t(), b[r].get_num_mpz_t(), a[r].get_num_mpz_t());
    mpz_sub(w[r].get_mpz_t(), d[r].get_num_mpz_t(), c[r].get_num_mpz_t());
  }
  Point3 n;  // denominators 1
  for (int r = 0; r < 3; ++r) {
    const int i = (r + 1) % 3, j = (r + 2) % 3;
    mpz_ptr x = mpq_numref(n[r].get_mpq_t());
    mpz_mul(x, u[i].get_mpz_t(), w[j].get_mpz_t());
    mpz_submul(x, u[j].get_mpz_t(), w[i].get_mpz_t());
  }
  return n;
}

class FeaturePlane {
 public:
  explicit FeaturePlane(const Query& qu)
      : qu_(qu), frame_(qu.P.map, qu.dp.doubles, qu.dp.exponent, qu.Q.map, qu.dq.doubles, qu.dq.exponent) {}

  // `common`: the touching answer's common point is wanted (distance);
  // collide asks for the status and the normal only.
  std::optional<FeatureContact> decide(const std::array<SimplexVertex, 4>& s, int n, Index ip, Index iq,
                                       bool common = true) {
    want_common_ = common;
    std::vector<Index> sp, sq;
    simplex_vertices(s, n, ip, iq, sp, sq);
    std::vector<Candidate> cands = candidates(sp, sq);
    // Each is tried in that order; the first plane that decides answers.
    const auto attempt = [&](std::vector<Candidate>& list) -> std::optional<FeatureContact> {
      Ranking ranking(*this, list, sp, sq);
      while (const Candidate* next = ranking.next()) {
        const Candidate& c = *next;
        Point3 nrm = normal_exact(c);
        if (is_zero(nrm)) continue;
        if (c.flip) nrm = -nrm;
        if (auto r = try_plane(nrm, c.from_p, c.from_q)) return placed(*r);
      }
      return std::nullopt;
    };
    if (auto r = attempt(cands)) return r;
    // None decided: on a nearly flat stretch of a body (a mesh's hull: many
    // facets within rounding of one plane) the search's simplex may lie on a
    // facet next to the contact's.  The facets around the neighbours of the
    // simplex's vertices, once, before M.
    std::vector<Candidate> ring;
    const auto ring_facets = [&](const RigidBody::Data& d, const std::vector<Index>& seeds, Candidate::Kind kind) {
      std::vector<Index> around;
      for (Index v : seeds)
        for (Index k = d.first[v]; k < d.first[v + 1]; ++k)
          if (std::find(seeds.begin(), seeds.end(), d.nbr[k]) == seeds.end()) add_unique(around, d.nbr[k]);
      for (Index v : around)
        for (Index k = d.first[v], e = d.first[v + 1]; k < e; ++k) {
          const Index w = d.nbr[k], x = d.nbr[k + 1 < e ? k + 1 : d.first[v]];
          if (kind == Candidate::p_facet) ring.push_back({kind, v, w, x, 0, false, 0});
          else ring.push_back({kind, v, x, w, 0, false, 0});  // Q's inward normal
        }
    };
    ring_facets(qu_.dp, sp, Candidate::p_facet);
    ring_facets(qu_.dq, sq, Candidate::q_facet);
    return attempt(ring);
  }

  // Penetrating within rounding (decide() answered nothing: every
  // candidate plane has h_P > l_Q), a tetrahedron of D that holds the
  // origin strictly, into t.  Near such a pose the origin lies just inside
  // the facet of D nearest to it, whose plane is a candidate's: along the
  // candidate's exact normal N, D's face is F_P − F_Q (the level sets of
  // the exact climbs, whose differences include its corners), and the
  // origin, below that face by h_P − l_Q, projects into it.  Three corners
  // of that face and the vertex of D lowest along N (the exact climbs the
  // other way) make tetrahedra that cover the pyramid over the face; each
  // is certified exactly (placed_tetrahedron_holds_origin), so whatever is
  // returned is a proof.  The four best-ranked candidates whose bodies
  // overlap along them are tried, and faces of at most 8 corners.
  bool inward_tetrahedron(const std::array<SimplexVertex, 4>& s, int n, Index ip, Index iq,
                          std::array<SimplexVertex, 4>& t) {
    std::vector<Index> sp, sq;
    simplex_vertices(s, n, ip, iq, sp, sq);
    std::vector<Candidate> cands = candidates(sp, sq);
    Ranking ranking(*this, cands, sp, sq);
    int tried = 0;
    while (const Candidate* next = ranking.next()) {
      const Candidate& c = *next;
      if (tried == 4) break;
      Point3 nrm = normal_exact(c);
      if (is_zero(nrm)) continue;
      if (c.flip) nrm = -nrm;
      const PulledNormalFilter filter_p(qu_.P.map, nrm), filter_q(qu_.Q.map, nrm);
      const auto ptp = [&](Index v) -> const Point3& { return pp(v); };
      const auto ptq = [&](Index v) -> const Point3& { return pq(v); };
      const Index top_p = climb(qu_.dp, ptp, filter_p, nrm, 1, c.from_p);
      const Index top_q = climb(qu_.dq, ptq, filter_q, nrm, -1, c.from_q);
      if (dot_difference_sign(nrm, pp(top_p), pq(top_q)) >= 0) continue;  // not overlapping along N
      ++tried;
      std::vector<Index> vp, vq;
      std::vector<std::pair<Index, Index>> ep, eq;
      face(qu_.dp, ptp, filter_p, nrm, top_p, vp, ep);
      face(qu_.dq, ptq, filter_q, nrm, top_q, vq, eq);
      if (vp.size() * vq.size() > 8) continue;
      const Index low_p = climb(qu_.dp, ptp, filter_p, nrm, -1, top_p);
      const Index low_q = climb(qu_.dq, ptq, filter_q, nrm, 1, top_q);
      const auto pair = [&](Index a, Index b) { return SimplexVertex{qu_.P.point(a) - qu_.Q.point(b), a, b}; };
      std::vector<SimplexVertex> corners;
      for (Index a : vp)
        for (Index b : vq) corners.push_back(pair(a, b));
      const SimplexVertex apex = pair(low_p, low_q);
      for (std::size_t i = 0; i < corners.size(); ++i)
        for (std::size_t j = i + 1; j < corners.size(); ++j)
          for (std::size_t k = j + 1; k < corners.size(); ++k) {
            t = {corners[i], corners[j], corners[k], apex};
            if (qu_.filter_tetrahedron(t) != 0 && qu_.certify_tetrahedron(t)) return true;
          }
    }
    return false;
  }

 private:
  static void add_unique(std::vector<Index>& v, Index i) {
    if (std::find(v.begin(), v.end(), i) == v.end()) v.push_back(i);
  }
  // The search's vertices of P and of Q (its simplex, then its last pair).
  static void simplex_vertices(const std::array<SimplexVertex, 4>& s, int n, Index ip, Index iq,
                               std::vector<Index>& sp, std::vector<Index>& sq) {
    for (int k = 0; k < n; ++k) add_unique(sp, s[k].p), add_unique(sq, s[k].q);
    add_unique(sp, ip), add_unique(sq, iq);
  }

  // A candidate plane: the facet of P' through the points a, b, c
  // (normal (b − a) × (c − a)), of Q' likewise, or the edges ab of P' and
  // cd of Q' (normal (b − a) × (d − c)); `orient`: the normal is turned by
  // the centres (else it is outward from P', inward into Q', as the
  // vertex graph's order gives it), `flip` the turn chosen.
  struct Candidate {
    enum Kind { p_facet, q_facet, edges } kind;
    Index a, b, c, d;
    bool orient;
    double gap;
    bool flip = false;
    Index from_p = 0, from_q = 0;  // the double supports along it
    V3 unit;                       // its unit normal in doubles, oriented (ranking)
  };
  V3 normal_double(const Candidate& c) const {
    switch (c.kind) {
      case Candidate::p_facet:
        return cross(qu_.P.point(c.b) - qu_.P.point(c.a), qu_.P.point(c.c) - qu_.P.point(c.a));
      case Candidate::q_facet:
        return cross(qu_.Q.point(c.b) - qu_.Q.point(c.a), qu_.Q.point(c.c) - qu_.Q.point(c.a));
      default:
        return cross(qu_.P.point(c.b) - qu_.P.point(c.a), qu_.Q.point(c.d) - qu_.Q.point(c.c));
    }
  }
  // The candidate planes: a facet of P' through three of its points in
  // the simplex (P' below), a facet of Q' (Q' above), the edges of each;
  // then, for a smaller simplex (the search stopped on an edge or a vertex
  // of D), the facets around its vertices and the edges at its first
  // pair.  Neighbours run counter-clockwise seen from outside, so two
  // consecutive ones and the vertex span a facet, the cross product of
  // their edges outward (a placement keeps orientation).
  std::vector<Candidate> candidates(const std::vector<Index>& sp, const std::vector<Index>& sq) const {
    std::vector<Candidate> cands;
    if (sp.size() >= 3) cands.push_back({Candidate::p_facet, sp[0], sp[1], sp[2], 0, true, 0});
    if (sq.size() >= 3) cands.push_back({Candidate::q_facet, sq[0], sq[1], sq[2], 0, true, 0});
    for (std::size_t i = 0; i < sp.size(); ++i)
      for (std::size_t j = i + 1; j < sp.size(); ++j)
        for (std::size_t k = 0; k < sq.size(); ++k)
          for (std::size_t l = k + 1; l < sq.size(); ++l)
            cands.push_back({Candidate::edges, sp[i], sp[j], sq[k], sq[l], true, 0});
    for (Index v : sp)
      for (Index k = qu_.dp.first[v], e = qu_.dp.first[v + 1]; k < e; ++k)
        cands.push_back({Candidate::p_facet, v, qu_.dp.nbr[k], qu_.dp.nbr[k + 1 < e ? k + 1 : qu_.dp.first[v]], 0,
                         false, 0});
    for (Index v : sq)
      for (Index k = qu_.dq.first[v], e = qu_.dq.first[v + 1]; k < e; ++k)  // Q's inward normal
        cands.push_back({Candidate::q_facet, v, qu_.dq.nbr[k + 1 < e ? k + 1 : qu_.dq.first[v]], qu_.dq.nbr[k], 0,
                         false, 0});
    for (Index k = qu_.dp.first[sp[0]]; k < qu_.dp.first[sp[0] + 1]; ++k)
      for (Index l = qu_.dq.first[sq[0]]; l < qu_.dq.first[sq[0] + 1]; ++l)
        cands.push_back({Candidate::edges, sp[0], qu_.dp.nbr[k], sq[0], qu_.dq.nbr[l], true, 0});
    return cands;
  }
  // Their order, a choice in doubles (the exact climbs decide whatever
  // the order): the plane of the contact has h_P = l_Q, a plane that
  // proves nothing h_P > l_Q.  So each candidate's normal, oriented as
  // the exact one will be, and the gap l_Q − h_P along it over the double
  // supports (climbed from the simplex's first pair) rank them, largest
  // first (ties in the list's order); the exact climbs start from those
  // supports.  A facet of P found around a vertex (not oriented) supports
  // P: its corner a is P's support along it, and likewise for Q's.
  //
  // The gaps are climbed lazily, in that order: a candidate's gap is at
  // most its bound over the simplex's points (l_Q ≤ n·y for the simplex's
  // vertices y of Q, h_P ≥ n·x for its vertices x of P), so a candidate
  // whose bound is below a climbed gap comes after it and is not climbed
  // until that one is taken.  Near a contact the simplex spans the contact
  // facet of D: a plane tilted from it leaves a simplex point on the wrong
  // side and a negative bound, and only the planes through the contact
  // are climbed before the first is tried.
  class Ranking {
   public:
    Ranking(const FeaturePlane& fp, std::vector<Candidate>& list, const std::vector<Index>& sp,
            const std::vector<Index>& sq)
        : fp_(fp), list_(list), sp_(sp), sq_(sq) {
      const Placed &P = fp.qu_.P, &Q = fp.qu_.Q;
      std::vector<V3> xp, xq;
      for (Index v : sp) xp.push_back(P.point(v));
      for (Index v : sq) xq.push_back(Q.point(v));
      const V3 cp = centre(P), cq = centre(Q);
      constexpr double kNone = -std::numeric_limits<double>::infinity();
      heap_.reserve(list.size());
      for (int k = 0; k < int(list.size()); ++k) {
        Candidate& c = list[k];
        V3 nd = fp.normal_double(c);
        if (c.orient) {
          // Orient N so that P's centre (a facet of P), Q's centre (a facet
          // of Q), or Q's centre minus P's (edges) lies on its side.
          const V3 a = c.kind == Candidate::q_facet ? Q.point(c.a) : P.point(c.a);
          const double side = c.kind == Candidate::p_facet   ? -dot(nd, cp - a)
                              : c.kind == Candidate::q_facet ? dot(nd, cq - a)
                                                             : dot(nd, cq - cp);
          c.flip = side < 0;
          if (c.flip) nd = -nd;
        }
        const double l = std::sqrt(dot(nd, nd));
        c.from_p = sp[0], c.from_q = sq[0];
        if (!(l > 0) || !std::isfinite(l)) {
          c.gap = kNone;
          push({kNone, k, true});
          continue;
        }
        c.unit = (1 / l) * nd;
        double hp = kNone, lq = -kNone;
        if (c.kind == Candidate::p_facet && !c.orient) hp = dot(c.unit, P.point(c.a));
        else
          for (const V3& x : xp) hp = std::max(hp, dot(c.unit, x));
        if (c.kind == Candidate::q_facet && !c.orient) lq = dot(c.unit, Q.point(c.a));
        else
          for (const V3& y : xq) lq = std::min(lq, dot(c.unit, y));
        const double bound = lq - hp;
        push({std::isfinite(bound) ? bound : -kNone, k, false});
      }
    }
    // The next candidate in rank order, or null.
    const Candidate* next() {
      while (!heap_.empty()) {
        std::pop_heap(heap_.begin(), heap_.end(), Entry::below);
        const Entry e = heap_.back();
        heap_.pop_back();
        if (e.climbed) return &list_[e.order];
        Candidate& c = list_[e.order];
        const Placed &P = fp_.qu_.P, &Q = fp_.qu_.Q;
        c.from_p = c.kind == Candidate::p_facet && !c.orient ? c.a : P.support(c.unit, sp_[0]);
        c.from_q = c.kind == Candidate::q_facet && !c.orient ? c.a : Q.support(-c.unit, sq_[0]);
        c.gap = dot(c.unit, Q.point(c.from_q) - P.point(c.from_p));
        if (!std::isfinite(c.gap)) c.gap = -std::numeric_limits<double>::infinity();
        push({c.gap, e.order, true});
      }
      return nullptr;
    }

   private:
    struct Entry {
      double key;  // the gap when climbed, else its bound
      int order;   // the candidate's place in the list
      bool climbed;
      // Max-heap order: larger key first, then the earlier candidate.
      static bool below(const Entry& a, const Entry& b) {
        return a.key < b.key || (a.key == b.key && a.order > b.order);
      }
    };
    void push(const Entry& e) {
      heap_.push_back(e);
      std::push_heap(heap_.begin(), heap_.end(), Entry::below);
    }
    const FeaturePlane& fp_;
    std::vector<Candidate>& list_;
    const std::vector<Index>& sp_;
    const std::vector<Index>& sq_;
    std::vector<Entry> heap_;
  };
  Point3 normal_exact(const Candidate& c) {
    switch (c.kind) {
      case Candidate::p_facet:
        return cross_of_differences(pp(c.a), pp(c.b), pp(c.a), pp(c.c));
      case Candidate::q_facet:
        return cross_of_differences(pq(c.a), pq(c.b), pq(c.a), pq(c.c));
      default:
        return cross_of_differences(pp(c.a), pp(c.b), pq(c.c), pq(c.d));
    }
  }

  const Query& qu_;
  // The placed points in one frame: K (x' − t_P) for a positive K, integers
  // when the maps and the vertices are doubles (PlacedFrame).  Every test
  // below is invariant under that translation and homogeneous, so it has
  // the same sign on these points as on the placed ones; a common point
  // found is mapped back.
  PlacedFrame frame_;
  std::unordered_map<Index, Point3> placed_p_, placed_q_;

  const Point3& pp(Index v) {
    auto it = placed_p_.find(v);
    if (it == placed_p_.end()) it = placed_p_.emplace(v, frame_.p(qu_.dp.exact[v], qu_.dp.bounds[v])).first;
    return it->second;
  }
  const Point3& pq(Index v) {
    auto it = placed_q_.find(v);
    if (it == placed_q_.end()) it = placed_q_.emplace(v, frame_.q(qu_.dq.exact[v], qu_.dq.bounds[v])).first;
    return it->second;
  }

  // sign N · (x_w − x_u) on a placed body: the interval filter on the
  // vertices' enclosures, else exactly on the frame's points.
  template <class Pt>
  static int step_sign(const RigidBody::Data& d, Pt pt, const PulledNormalFilter& f, const Point3& nrm, Index u,
                       Index w) {
    const int s = f.difference_sign(d.bounds[u], d.bounds[w]);
    if (s != PulledNormalFilter::kOpen) return s;
    return dot_difference_sign(nrm, pt(u), pt(w));
  }
  // A vertex maximising sign·N·x over a placed body (exact: a vertex no
  // neighbour of which is further is a maximum), from v.
  template <class Pt>
  Index climb(const RigidBody::Data& d, Pt pt, const PulledNormalFilter& f, const Point3& nrm, int sign, Index v) {
    for (;;) {
      Index next = v;
      for (Index k = d.first[v]; k < d.first[v + 1]; ++k)
        if (sign * step_sign(d, pt, f, nrm, v, d.nbr[k]) > 0) {
          next = d.nbr[k];
          break;
        }
      if (next == v) break;
      v = next;
      ++g_stats.climb_steps;
    }
    return v;
  }
  // The face of a placed body in the plane N·x = h through v: its vertices
  // (the level set of v, connected in the vertex graph) and its edges.
  // (N · x_w = h for a neighbour w of a face vertex u exactly when
  // N · (x_w − x_u) = 0.)
  template <class Pt>
  void face(const RigidBody::Data& d, Pt pt, const PulledNormalFilter& f, const Point3& nrm, Index v,
            std::vector<Index>& verts, std::vector<std::pair<Index, Index>>& edges) {
    verts.assign(1, v);
    for (std::size_t i = 0; i < verts.size(); ++i) {
      const Index u = verts[i];
      for (Index k = d.first[u]; k < d.first[u + 1]; ++k) {
        const Index w = d.nbr[k];
        if (step_sign(d, pt, f, nrm, u, w) != 0) continue;
        if (u < w) edges.emplace_back(u, w);
        if (std::find(verts.begin(), verts.end(), w) == verts.end()) verts.push_back(w);
      }
    }
  }
  // Orientations of points of the plane N·x = h: N · ((b − a) × (c − a)).
  // For u, v orthogonal to N, u × v = λ N, so N · (u × v) = λ |N|² and
  // (u × v)_r = λ N_r: with N_r ≠ 0, s = sign N_r, the value
  // s (u × v)_r is N · (u × v) times |N_r| / |N|² > 0 — the same sign, and
  // the same ratios — from two products instead of nine.
  struct InPlane {
    int r = 0, s = 1;
    explicit InPlane(const Point3& nrm) {
      const Vec3d d = scaled_direction(nrm);
      for (int k = 1; k < 3; ++k)
        if (std::fabs(d[k]) > std::fabs(d[r])) r = k;
      if (sgn(nrm[r]) == 0)  // a rounding of the choice only; N ≠ 0
        for (int k = 0; k < 3; ++k)
          if (sgn(nrm[k]) != 0) r = k;
      s = sgn(nrm[r]);
    }
    Rational value(const Point3& a, const Point3& b, const Point3& c) const {
      const int i = (r + 1) % 3, j = (r + 2) % 3;
      Rational v = (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
      if (s < 0) v = -v;
      return v;
    }
    int orient(const Point3& a, const Point3& b, const Point3& c) const {
      if (!integral(a) || !integral(b) || !integral(c)) return sgn(value(a, b, c));
      const int i = (r + 1) % 3, j = (r + 2) % 3;
      IntegerScratch& z = scratch();
      mpz_sub(z.t.get_mpz_t(), b[i].get_num_mpz_t(), a[i].get_num_mpz_t());
      mpz_sub(z.u.get_mpz_t(), c[j].get_num_mpz_t(), a[j].get_num_mpz_t());
      mpz_mul(z.acc.get_mpz_t(), z.t.get_mpz_t(), z.u.get_mpz_t());
      mpz_sub(z.t.get_mpz_t(), b[j].get_num_mpz_t(), a[j].get_num_mpz_t());
      mpz_sub(z.u.get_mpz_t(), c[i].get_num_mpz_t(), a[i].get_num_mpz_t());
      mpz_submul(z.acc.get_mpz_t(), z.t.get_mpz_t(), z.u.get_mpz_t());
      return s * mpz_sgn(z.acc.get_mpz_t());
    }
  };
  // Whether y (in the plane) lies in the convex face of points `f` with
  // edges `e`: equal to its point, on its segment, or on the inner side of
  // every edge that has the face's points on one side (a boundary edge).
  static bool in_face(const InPlane& pl, const Point3& y, const std::vector<Point3>& f,
                      const std::vector<std::pair<std::size_t, std::size_t>>& e) {
    if (f.size() == 1) return y == f[0];
    if (f.size() == 2) {
      // Collinear: (b − a) × (y − a) = λ N with λ = 0 (every point in the plane).
      if (pl.orient(f[0], f[1], y) != 0) return false;
      const Point3 ab = f[1] - f[0], ay = y - f[0];
      const Rational t = dot(ay, ab);
      return t >= 0 && t <= dot(ab, ab);
    }
    for (const auto& [i, j] : e) {
      int side = 0;
      bool boundary = true;
      for (std::size_t k = 0; k < f.size() && boundary; ++k) {
        const int o = pl.orient(f[i], f[j], f[k]);
        if (o == 0) continue;
        if (side == 0) side = o;
        else if (o != side) boundary = false;
      }
      if (!boundary || side == 0) continue;
      if (pl.orient(f[i], f[j], y) == -side) return false;
    }
    return true;
  }

  // A contact from the frame's points back to the placed ones: the common
  // point z / K + t_P, the normal (a cross product of two differences of
  // frame points, K² times that of the placed points) over K².
  FeatureContact placed(FeatureContact c) const {
    if (frame_.factor() != 1) c.normal = Rational(1) / (frame_.factor() * frame_.factor()) * c.normal;
    if (c.status == ContactStatus::touching && want_common_) c.common = frame_.placed(c.common);
    return c;
  }
  bool want_common_ = true;

  std::optional<FeatureContact> try_plane(const Point3& nrm, Index from_p, Index from_q) {
    FeatureContact c;
    const PulledNormalFilter filter_p(qu_.P.map, nrm), filter_q(qu_.Q.map, nrm);
    c.p = climb(qu_.dp, [&](Index v) -> const Point3& { return pp(v); }, filter_p, nrm, 1, from_p);
    c.q = climb(qu_.dq, [&](Index v) -> const Point3& { return pq(v); }, filter_q, nrm, -1, from_q);
    c.normal = nrm;
    // sign (l_Q − h_P) = sign N · (x_q − x_p).
    const int gap = dot_difference_sign(nrm, pp(c.p), pq(c.q));
    if (gap > 0) {
      c.status = ContactStatus::separate;
      return c;
    }
    if (gap < 0) return std::nullopt;
    // h_P = l_Q: the faces in the plane.
    std::vector<Index> vp, vq;
    std::vector<std::pair<Index, Index>> ep, eq;
    face(qu_.dp, [&](Index v) -> const Point3& { return pp(v); }, filter_p, nrm, c.p, vp, ep);
    face(qu_.dq, [&](Index v) -> const Point3& { return pq(v); }, filter_q, nrm, c.q, vq, eq);
    std::vector<Point3> fp, fq;
    for (Index v : vp) fp.push_back(pp(v));
    for (Index v : vq) fq.push_back(pq(v));
    const auto local = [](const std::vector<Index>& verts, const std::vector<std::pair<Index, Index>>& edges) {
      std::vector<std::pair<std::size_t, std::size_t>> out;
      for (const auto& [u, w] : edges)
        out.emplace_back(std::find(verts.begin(), verts.end(), u) - verts.begin(),
                         std::find(verts.begin(), verts.end(), w) - verts.begin());
      return out;
    };
    const auto lp = local(vp, ep), lq2 = local(vq, eq);
    c.status = ContactStatus::touching;
    const InPlane pl(nrm);
    for (const Point3& y : fq)
      if (in_face(pl, y, fp, lp)) {
        c.common = y;
        return c;
      }
    for (const Point3& x : fp)
      if (in_face(pl, x, fq, lq2)) {
        c.common = x;
        return c;
      }
    for (const auto& [i, j] : lp)
      for (const auto& [k, l] : lq2) {
        const Point3 &a = fp[i], &b = fp[j], &e = fq[k], &f = fq[l];
        if (pl.orient(a, b, e) * pl.orient(a, b, f) < 0 && pl.orient(e, f, a) * pl.orient(e, f, b) < 0) {
          if (want_common_) {  // the crossing point (a rational of the frame), only when asked
            const Rational sa = pl.value(e, f, a), sb = pl.value(e, f, b);
            c.common = a + Rational(sa / (sa - sb)) * (b - a);
          }
          return c;
        }
      }
    c.status = ContactStatus::separate;
    return c;
  }
};

// The warm start's direction, or from the centre of placed Q towards the
// centre of placed P: the support of D along −dir is near the closest point
// of D to the origin.
V3 initial_direction(const Query& qu, const RigidWarmStart& start) {
  V3 dir = v3(start.direction);
  if (dot(dir, dir) > 0 && std::isfinite(dot(dir, dir))) return dir;
  dir = centre(qu.P) - centre(qu.Q);
  if (!(dot(dir, dir) > 0) || !std::isfinite(dot(dir, dir))) dir = {1, 0, 0};
  return dir;
}

RigidWarmStart checked_start(const RigidBody& p, const RigidBody& q, const RigidWarmStart* warm) {
  RigidWarmStart start;
  if (warm) start = *warm;
  if (start.p >= p.data().approx.size()) start.p = 0;
  if (start.q >= q.data().approx.size()) start.q = 0;
  for (int k = 0; k < 4 && start.tetrahedron; ++k)
    start.tetrahedron = start.tp[k] < p.data().approx.size() && start.tq[k] < q.data().approx.size();
  return start;
}

// Whether the origin lies strictly inside the tetrahedron of the four
// points, in doubles (a guess: the tetrahedron filter decides).
bool holds_origin_doubles(const std::array<SimplexVertex, 4>& t) {
  const auto det = [](const V3& a, const V3& b, const V3& c) { return dot(a, cross(b, c)); };
  const V3 &a = t[0].w, &b = t[1].w, &c = t[2].w, &d = t[3].w;
  const double total = det(b - a, c - a, d - a);
  if (!(total != 0) || !std::isfinite(total)) return false;
  // The origin's side of each face, against the fourth vertex's.
  const double s0 = det(b, c, d), s1 = -det(a, c, d), s2 = det(a, b, d), s3 = -det(a, b, c);
  return total > 0 ? (s0 > 0 && s1 > 0 && s2 > 0 && s3 > 0) : (s0 < 0 && s1 < 0 && s2 < 0 && s3 < 0);
}

// The batches: N answers from N poses (or one) of each body, in runs of
// consecutive poses over threads, each run warm-started along itself.
constexpr std::size_t kRun = 256;  // consecutive poses per job, warm-started along the run
template <class Answer, class One>
void batch(const char* what, std::span<const RigidPose> poses_p, std::span<const RigidPose> poses_q,
           std::span<Answer> out, unsigned threads, const One& one) {
  const std::size_t n = out.size();
  const auto fits = [n](std::size_t k) { return k == n || k == 1; };
  if (!fits(poses_p.size()) || !fits(poses_q.size()))
    throw UsageError(std::string(what) + ": " + std::to_string(n) + " answers need " + std::to_string(n) +
                     " poses (or one) of each body, got " + std::to_string(poses_p.size()) + " and " +
                     std::to_string(poses_q.size()));
  if (n == 0) return;
  const std::size_t runs = (n + kRun - 1) / kRun;
  parallel_for(runs, threads, [&](std::size_t run) {
    RigidWarmStart warm;
    const std::size_t end = std::min(n, (run + 1) * kRun);
    for (std::size_t i = run * kRun; i < end; ++i)
      out[i] = one(poses_p[poses_p.size() == 1 ? 0 : i], poses_q[poses_q.size() == 1 ? 0 : i], &warm);
  });
}

// The same runs with the poses made on demand by `poses`, each just before
// its query on the thread answering it: the same answers as the spans of
// the same poses.
template <class Answer, class One>
void batch(const RigidPoseSource& poses, std::span<Answer> out, unsigned threads, const One& one) {
  const std::size_t n = out.size();
  if (n == 0) return;
  const std::size_t runs = (n + kRun - 1) / kRun;
  parallel_for(runs, threads, [&](std::size_t run) {
    RigidWarmStart warm;
    RigidPose scratch_p, scratch_q;
    const std::size_t end = std::min(n, (run + 1) * kRun);
    for (std::size_t i = run * kRun; i < end; ++i) {
      const RigidPose& a = poses(i, 0, scratch_p);
      const RigidPose& b = poses(i, 1, scratch_q);
      out[i] = one(a, b, &warm);
    }
  });
}

}  // namespace

const char* rigid_certificate_name(RigidCertificate c) {
  switch (c) {
    case RigidCertificate::separating_plane:
      return "separating_plane";
    case RigidCertificate::simplex:
      return "simplex";
    case RigidCertificate::exact:
      return "exact";
    case RigidCertificate::closest_points:
      return "closest_points";
    case RigidCertificate::nearest_facet:
      return "nearest_facet";
    case RigidCertificate::exit_facet:
      return "exit_facet";
    case RigidCertificate::feature_plane:
      return "feature_plane";
  }
  return "exact";
}

RigidPose RigidPose::translation(const Point3& t) {
  return RigidPose(PlacedMap(std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}, t));
}
RigidPose RigidPose::quaternion(const Quaternion& q, const Point3& t) { return RigidPose(PlacedMap::rotation(q, t)); }
RigidPose RigidPose::quaternion(const Quaternion& q, const Vec3d& t) { return RigidPose(PlacedMap::rotation(q, t)); }
RigidPose RigidPose::quaternion64(const std::array<std::int64_t, 4>& q, const Vec3d& t) {
  return RigidPose(PlacedMap::rotation64(q, t));
}
RigidPose RigidPose::matrix(const std::array<double, 9>& r, const Point3& t) { return RigidPose(PlacedMap(r, t)); }
RigidPose RigidPose::matrix(const std::array<double, 9>& r, const Vec3d& t) { return RigidPose(PlacedMap(r, t)); }

RigidBody::RigidBody(ConvexPolytope p) {
  auto d = std::make_shared<Data>();
  d->poly = std::move(p);
  const ConvexPolytope& poly = d->poly;
  const Index nv = poly.num_vertices();
  d->approx.resize(nv);
  d->bounds.resize(nv);
  d->first.assign(nv + 1, 0);
  double cx = 0, cy = 0, cz = 0;
  for (Index v = 0; v < nv; ++v) {
    d->approx[v] = poly.approx(v);
    d->bounds[v] = point_bounds(poly.point(v));
    for (const Bounds& b : {d->bounds[v].x, d->bounds[v].y, d->bounds[v].z}) {
      d->doubles = d->doubles && b.lo == b.hi;
      d->exponent = std::min(d->exponent, dyadic_exponent(b.lo));
    }
    cx += d->approx[v].x, cy += d->approx[v].y, cz += d->approx[v].z;
    d->first[v + 1] = d->first[v] + poly.vertex_degree(v);
  }
  d->centroid = {cx / nv, cy / nv, cz / nv};
  d->exact = poly.points().data();
  d->nbr.resize(d->first[nv]);
  for (Index v = 0; v < nv; ++v) {
    Index k = d->first[v];
    for (Index w : poly.vertex_neighbours(v)) d->nbr[k++] = w;
  }
  // The seeds: about one cell per vertex, 2 × 2 to 16 × 16 a face.  Each
  // cell's vertex is climbed (steepest ascent in doubles) from the previous
  // cell's, its neighbour on the face.
  if (nv > 0) {
    d->side = std::min(16, int(std::ceil(std::sqrt(nv / 6.0))));
    const int side = d->side;
    d->seeds.resize(std::size_t(6) * side * side);
    Index v = 0;
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
          const double a = -1 + (2 * i + 1) / double(side), b = -1 + (2 * j + 1) / double(side);
          const double m = face % 2 ? -1 : 1;
          const Vec3d u = face < 2 ? Vec3d{m, a, b} : face < 4 ? Vec3d{b, m, a} : Vec3d{a, b, m};
          const auto at = [&](Index w) { return u.x * d->approx[w].x + u.y * d->approx[w].y + u.z * d->approx[w].z; };
          double best = at(v);
          for (Index next = v;; v = next) {
            for (Index k = d->first[v]; k < d->first[v + 1]; ++k)
              if (const double s = at(d->nbr[k]); s > best) best = s, next = d->nbr[k];
            if (next == v) break;
          }
          d->seeds[(std::size_t(face) * side + i) * side + j] = v;
        }
  }
  d_ = std::move(d);
}

const ConvexPolytope& RigidBody::polytope() const { return d_->poly; }

RigidStats rigid_stats() { return g_stats; }

ConvexPolytope placed_linear(const ConvexPolytope& p, const PlacedMap& map) {
  Mesh m = p.to_mesh();
  m.points.transform([&](const Point3& x) { return map.apply_linear(x); });
  return ConvexPolytope::from_mesh(m, "placed polytope");
}

ContactStatus collide_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q) {
  TranslationalObstacle ob(placed_linear(p.polytope(), pose_p.map()), placed_linear(q.polytope(), pose_q.map()));
  return ob.collide(pose_p.map().t(), pose_q.map().t()).status;
}

namespace {

// FeaturePlane::inward_tetrahedron on its own frame; the tetrahedron found
// replaces the contents of `out`.  (Out of line: collide's rare last step
// before M.)
bool inward_tetrahedron(const Query& qu, const std::array<SimplexVertex, 4>& s, int n, Index ip, Index iq,
                        Tetrahedra& out) {
  std::array<SimplexVertex, 4> t;
  if (!FeaturePlane(qu).inward_tetrahedron(s, n, ip, iq, t)) return false;
  out.assign(1, t);
  return true;
}

// collide, with `warm_tetrahedron`: whether the warm start's tetrahedron is
// tried first (the depths run the search, whose last direction and
// witnesses their own search starts from).
RigidCollision collide_search(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                              const RigidPose& pose_q, RigidWarmStart* warm, bool warm_tetrahedron) {
  ++g_stats.queries;
  const Query qu{Placed(p.data(), pose_p.map()), Placed(q.data(), pose_q.map()), p.data(), q.data()};
  const RigidWarmStart start = checked_start(p, q, warm);
  RigidCollision r;
  // The previous answer's tetrahedron, when it still holds the origin (the
  // filter decides; an open or failed filter leaves the search to decide).
  if (warm_tetrahedron && start.tetrahedron) {
    std::array<SimplexVertex, 4> t;
    for (int k = 0; k < 4; ++k) t[k] = {qu.P.point(start.tp[k]) - qu.Q.point(start.tq[k]), start.tp[k], start.tq[k]};
    if (holds_origin_doubles(t) && qu.filter_tetrahedron(t) == 1) {
      r.status = ContactStatus::penetrating;
      r.certificate = RigidCertificate::simplex;
      r.p = t[0].p, r.q = t[0].q;
      count(r.certificate);
      ++g_stats.warm_tetrahedra;
      if (warm) warm->p = r.p, warm->q = r.q;  // the direction and the tetrahedron stay
      return r;
    }
  }
  const V3 dir = initial_direction(qu, start);

  std::array<SimplexVertex, 4> s;
  int n = 1;
  s[0] = qu.support(-dir, start.p, start.q);
  V3 v = s[0].w;
  Index ip = s[0].p, iq = s[0].q;
  bool decided = false;
  double last = std::numeric_limits<double>::infinity();
  // A separating plane of normal nrm (doubles, taken exactly), from the
  // support guesses cp, cq: certified or not.
  // Planes whose gap the filters left open (within rounding of touching):
  // evaluated exactly after the feature plane, which decides touching poses.
  struct OpenGap {
    Vec3d n;
    Index p, q;
  };
  std::vector<OpenGap> open_gaps;
  const auto separate = [&](const Vec3d& nrm, Index cp, Index cq) {
    r.status = ContactStatus::separate;
    r.certificate = RigidCertificate::separating_plane;
    r.normal = nrm;
    r.p = cp, r.q = cq;
    return true;
  };
  const auto try_plane = [&](const Vec3d& nrm, Index cp, Index cq) {
    // A normal that is zero, or not finite (the search's doubles overflow or
    // underflow on bodies of extreme size), proves nothing.
    const double l1 = std::fabs(nrm.x) + std::fabs(nrm.y) + std::fabs(nrm.z);
    if (!(l1 > 0) || !std::isfinite(l1)) return false;
    bool open = false;
    if (!qu.certify_separation(nrm, cp, cq, &open)) {
      if (open) open_gaps.push_back({nrm, cp, cq});
      return false;
    }
    return separate(nrm, cp, cq);
  };
  // The normal of the simplex's triangle, turned towards the origin.  Near
  // contact the closest point v is tiny and its direction is only as good
  // as its absolute rounding (about 1e-16 over |v|), while the triangle,
  // which lies on the facet of D nearest to the origin, gives that facet's
  // normal to about 1e-16 relative whatever the distance.
  const auto triangle_normal = [&]() {
    V3 nt = cross(s[1].w - s[0].w, s[2].w - s[0].w);
    if (dot(nt, s[0].w) > 0) nt = -nt;
    return Vec3d{nt.x, nt.y, nt.z};
  };
  bool tried_triangle = false;
  Tetrahedra deferred;  // tetrahedra the intervals left open
  const std::array<SimplexVertex, 4>* tetra = nullptr;  // the certificate's, when penetrating
  for (int it = 0; it < kMaxIterations && !decided; ++it) {
    ++g_stats.iterations;
    const double vv = dot(v, v);
    if (!(vv > 0)) break;  // the origin on the simplex (in doubles): touching or near it
    const SimplexVertex w = qu.support(-v, ip, iq);
    ip = w.p, iq = w.q;
    const double vw = dot(v, w.w);
    if (vw > 0) {
      // −v separates in doubles; certify it, or the triangle's normal.
      decided = try_plane(Vec3d{-v.x, -v.y, -v.z}, w.p, w.q);
      if (!decided && n == 3) {
        tried_triangle = true;
        decided = try_plane(triangle_normal(), s[0].p, s[0].q);
      }
      if (decided) break;
    }
    bool repeated = false;
    for (int k = 0; k < n; ++k) repeated = repeated || (s[k].p == w.p && s[k].q == w.q);
    // When the search in doubles stops (no decision: an answer it did not
    // certify goes to the exact path).
    if (repeated || !(vv < last) || vv - vw <= 1e-15 * vv) break;  // converged without a certificate
    last = vv;
    s[n++] = w;
    tried_triangle = false;
    if (!closest_on_simplex(s, n, v)) {
      const int f = qu.filter_tetrahedron(s);
      if (f == 1) {
        r.status = ContactStatus::penetrating;
        r.certificate = RigidCertificate::simplex;
        r.p = w.p, r.q = w.q;
        decided = true;
        tetra = &s;
      } else if (f == kTetrahedronOpen) {
        deferred.push_back(s);
      }
      break;
    }
  }
  if (!decided && n == 3 && !tried_triangle) decided = try_plane(triangle_normal(), s[0].p, s[0].q);
  if (!decided && n == 3 && blow_up_triangle(qu, s, &deferred)) {
    r.status = ContactStatus::penetrating;
    r.certificate = RigidCertificate::simplex;
    r.p = s[0].p, r.q = s[0].q;
    decided = true;
    tetra = &s;
  }
  if (!decided) {
    FeaturePlane plane(qu);
    if (const auto c = plane.decide(s, n, ip, iq, false)) {
      r.status = c->status;
      r.certificate = RigidCertificate::feature_plane;
      r.normal = to_double(c->normal);
      r.p = c->p, r.q = c->q;
      decided = true;
    }
  }
  // The planes and the tetrahedra whose filters left them open, exactly:
  // after the feature plane, which decides the touching poses where no
  // plane separates strictly and no tetrahedron holds the origin strictly.
  for (const OpenGap& g : open_gaps) {
    if (decided) break;
    if (qu.exact_gap(g.n, g.p, g.q)) decided = separate(g.n, g.p, g.q);
  }
  for (const auto& t : deferred) {
    if (decided) break;
    if (qu.certify_tetrahedron(t)) {
      r.status = ContactStatus::penetrating;
      r.certificate = RigidCertificate::simplex;
      r.p = t[0].p, r.q = t[0].q;
      decided = true;
      tetra = &t;
    }
  }
  // Still undecided: the origin within rounding of ∂D, just inside it.  A
  // tetrahedron over the face of D nearest it, certified exactly
  // (FeaturePlane::inward_tetrahedron), before M; kept in `deferred` for
  // the warm start.
  if (!decided) [[unlikely]] {
    if (inward_tetrahedron(qu, s, n, ip, iq, deferred)) {
      r.status = ContactStatus::penetrating;
      r.certificate = RigidCertificate::simplex;
      r.p = deferred.front()[0].p, r.q = deferred.front()[0].q;
      decided = true;
      tetra = &deferred.front();
      ++g_stats.inward_tetrahedra;
    }
  }
  if (!decided) {
    r.status = collide_exact(p, pose_p, q, pose_q);
    r.certificate = RigidCertificate::exact;
    r.p = ip, r.q = iq;
  }
  count(r.certificate);
  if (warm) {
    warm->p = r.p, warm->q = r.q;
    warm->direction = {v.x, v.y, v.z};
    warm->tetrahedron = tetra != nullptr;
    if (tetra)
      for (int k = 0; k < 4; ++k) warm->tp[k] = (*tetra)[k].p, warm->tq[k] = (*tetra)[k].q;
  }
  return r;
}

}  // namespace

RigidCollision collide(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                       RigidWarmStart* warm) {
  return collide_search(p, pose_p, q, pose_q, warm, true);
}

void collide(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
             std::span<const RigidPose> poses_q, std::span<RigidCollision> out, unsigned threads) {
  batch("collide", poses_p, poses_q, out, threads, [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) {
    return collide(p, a, q, b, w);
  });
}

void collide(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses, std::span<RigidCollision> out,
             unsigned threads) {
  batch(poses, out, threads, [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) {
    return collide(p, a, q, b, w);
  });
}

namespace {

// The answer on M built exactly, with its status.
struct ExactDistance {
  ContactStatus status;
  RigidDistanceExact values;
};
ExactDistance distance_on_m(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q) {
  TranslationalObstacle ob(placed_linear(p.polytope(), pose_p.map()), placed_linear(q.polytope(), pose_q.map()));
  const DistanceResult d = ob.distance(pose_p.map().t(), pose_q.map().t());
  return {d.status, {d.squared_distance(), d.point_p(), d.point_q()}};
}

// lower and upper from an enclosure of the square (sqrt rounded outward)
// and the value within them.
template <class Answer>
void set_bounds(Answer& r, const Bounds& sq, double value) {
  r.lower = sq.lo > 0 ? std::nextafter(std::sqrt(sq.lo), 0.0) : 0.0;
  // [0, 0] holds only 0: the bounds stay 0 (touching or overlapping bodies).
  r.upper = sq.hi > 0 ? std::nextafter(std::sqrt(sq.hi), std::numeric_limits<double>::infinity()) : 0.0;
  const double x = std::clamp(value, r.lower, r.upper);
  if constexpr (requires { r.distance; }) r.distance = x;
  else r.depth = x;
}

// The certificate of a distance (rigid_proximity.hpp) on the pairs of
// `pairs` (1 to 3 of the final simplex).  On success fills r.
bool certify_closest(const Query& qu, const std::array<SimplexVertex, 4>& pairs, int k, RigidDistance& r) {
  const RigidBody::Data &dp = qu.dp, &dq = qu.dq;
  std::array<const Point3*, 3> p{}, q{};
  std::array<const PointBounds*, 3> pb{}, qb{};
  for (int j = 0; j < k; ++j) {
    p[j] = &dp.exact[pairs[j].p], pb[j] = &dp.bounds[pairs[j].p];
    q[j] = &dq.exact[pairs[j].q], qb[j] = &dq.bounds[pairs[j].q];
  }
  const PlacedSimplexPoint sp(qu.P.map, qu.Q.map, k, p, pb, q, qb);
  if (!sp.independent()) return false;
  for (int j = 0; j < k; ++j)
    if (sp.lambda_sign(j) < 0) return false;
  if (!sp.nonzero()) return false;  // the origin in D: not separate
  // A neighbour whose climb sign is 0 by construction: V is orthogonal to
  // d_i − d_j for the pairs i, j of the simplex, so V · (p_i' − p_j') = 0
  // when q_i = q_j (and likewise on Q).
  const auto zero_on_p = [&](Index a, Index w) {
    for (int i = 0; i < k; ++i)
      if (pairs[i].p == w)
        for (int j = 0; j < k; ++j)
          if (pairs[j].p == a && pairs[j].q == pairs[i].q) return true;
    return false;
  };
  const auto zero_on_q = [&](Index a, Index w) {
    for (int i = 0; i < k; ++i)
      if (pairs[i].q == w)
        for (int j = 0; j < k; ++j)
          if (pairs[j].q == a && pairs[j].p == pairs[i].p) return true;
    return false;
  };
  // One pair (p_a, q_a) suffices: with p_a a maximum of −v · x over P' and
  // q_a a minimum over Q', the gap between the two planes is
  // (−v) · (q_a' − p_a') = v · d_a = |v|² / |v| · |v| (v · d_j = |v|² for
  // every j).  Take the pair with the most neighbours known to be level.
  int anchor = 0, best = -1;
  for (int a = 0; a < k; ++a) {
    int known = 0;
    const Index ia = pairs[a].p, ja = pairs[a].q;
    for (Index e = dp.first[ia]; e < dp.first[ia + 1]; ++e) known += zero_on_p(ia, dp.nbr[e]);
    for (Index e = dq.first[ja]; e < dq.first[ja + 1]; ++e) known += zero_on_q(ja, dq.nbr[e]);
    if (known > best) best = known, anchor = a;
  }
  const Index ia = pairs[anchor].p, ja = pairs[anchor].q;
  for (Index e = dp.first[ia]; e < dp.first[ia + 1]; ++e) {
    const Index w = dp.nbr[e];
    if (zero_on_p(ia, w)) continue;
    if (sp.climb_sign_p(dp.exact[ia], dp.bounds[ia], dp.exact[w], dp.bounds[w]) > 0) return false;
  }
  for (Index e = dq.first[ja]; e < dq.first[ja + 1]; ++e) {
    const Index w = dq.nbr[e];
    if (zero_on_q(ja, w)) continue;
    if (sp.climb_sign_q(dq.exact[ja], dq.bounds[ja], dq.exact[w], dq.bounds[w]) > 0) return false;
  }
  r.status = ContactStatus::separate;
  r.certificate = RigidCertificate::closest_points;
  r.k = k;
  V3 x, y;
  for (int j = 0; j < k; ++j) {
    r.p[j] = pairs[j].p, r.q[j] = pairs[j].q;
    const double l = sp.lambda_approx(j);
    x = x + l * qu.P.point(pairs[j].p);
    y = y + l * qu.Q.point(pairs[j].q);
  }
  r.point_p = {x.x, x.y, x.z}, r.point_q = {y.x, y.y, y.z};
  const V3 v = x - y;
  set_bounds(r, sp.squared_norm_bounds(), std::sqrt(dot(v, v)));
  return true;
}

// The subsets of the simplex's pairs to try, largest first (at most 3
// pairs: of a tetrahedron, its faces): the double search's reduction may
// keep a pair whose exact λ is negative (the closest point then lies on a
// smaller face) or drop to a degenerate one.
bool certify_closest_subsets(const Query& qu, const std::array<SimplexVertex, 4>& s, int n, RigidDistance& r) {
  if (n <= 3 && certify_closest(qu, s, n, r)) return true;
  for (int size = std::min(n - 1, 3); size >= 1; --size)
    for (unsigned mask = 1; mask < (1u << n); ++mask) {
      if (std::popcount(mask) != size) continue;
      std::array<SimplexVertex, 4> sub;
      int m = 0;
      for (int j = 0; j < n; ++j)
        if (mask & (1u << j)) sub[m++] = s[j];
      if (certify_closest(qu, sub, m, r)) return true;
    }
  return false;
}

// When no subset of the search's simplex certifies (the doubles stopped
// near the closest features, not on them: on the hull of a mesh, facets
// within rounding of one plane, and a distance of 1e-9 its size), GJK goes
// on in exact signs from there.  Of the subsets whose exact closest point
// v_S lies in their relative interior (λ_j ≥ 0), the one with the least
// |v_S|² holds the closest point v of the simplex's hull; the exact
// supports of D along −v (climbs from its first pair, exact signs) give a
// new pair, strictly beyond v's plane unless v's certificate holds, so |v|
// decreases strictly from step to step and no simplex comes back (GJK's
// argument, here without rounding).  At most kRefineSteps steps, each
// followed by the certificate on the subsets; false when the origin is in
// the hull (not separate) or no certificate came.
constexpr int kRefineSteps = 16;

// From v, to a neighbour w with sign(u, w) > 0 (w further along the climb's
// direction than u, an exact sign) until none is: a vertex of the convex
// polytope maximising the direction.
template <class Sign>
Index exact_climb(const RigidBody::Data& d, Index v, const Sign& sign) {
  for (bool moved = true; moved;) {
    moved = false;
    for (Index e = d.first[v]; e < d.first[v + 1] && !moved; ++e)
      if (sign(v, d.nbr[e]) > 0) v = d.nbr[e], moved = true, ++g_stats.climb_steps;
  }
  return v;
}
bool refine_closest(const Query& qu, std::array<SimplexVertex, 4> s, int n, RigidDistance& r) {
  const RigidBody::Data &dp = qu.dp, &dq = qu.dq;
  for (int step = 0; step < kRefineSteps; ++step) {
    std::array<SimplexVertex, 4> best_sub;
    int best_m = 0;
    std::unique_ptr<PlacedSimplexPoint> best;
    for (unsigned mask = 1; mask < (1u << n); ++mask) {
      const int m = std::popcount(mask);
      if (m > 3) continue;
      std::array<SimplexVertex, 4> sub;
      std::array<const Point3*, 3> p{}, q{};
      std::array<const PointBounds*, 3> pb{}, qb{};
      int j = 0;
      for (int i = 0; i < n; ++i)
        if (mask & (1u << i)) {
          sub[j] = s[i];
          p[j] = &dp.exact[s[i].p], pb[j] = &dp.bounds[s[i].p], q[j] = &dq.exact[s[i].q], qb[j] = &dq.bounds[s[i].q];
          ++j;
        }
      auto sp = std::make_unique<PlacedSimplexPoint>(qu.P.map, qu.Q.map, m, p, pb, q, qb);
      if (!sp->independent()) continue;
      bool inside = true;
      for (int i = 0; i < m && inside; ++i) inside = sp->lambda_sign(i) >= 0;
      if (!inside) continue;
      if (!sp->nonzero()) return false;  // the origin in the hull, which lies in D: not separate
      if (best) {
        const Bounds a = sp->squared_norm_bounds(), b = best->squared_norm_bounds();
        const bool less = a.hi < b.lo ? true : a.lo > b.hi ? false : sp->squared_norm() < best->squared_norm();
        if (!less) continue;
      }
      best = std::move(sp), best_sub = sub, best_m = m;
    }
    if (!best) return false;
    // The exact supports along −v: P's maximum, Q's minimum.
    const Index a = exact_climb(dp, best_sub[0].p, [&](Index u, Index w) {
      return best->climb_sign_p(dp.exact[u], dp.bounds[u], dp.exact[w], dp.bounds[w]);
    });
    const Index b = exact_climb(dq, best_sub[0].q, [&](Index u, Index w) {
      return best->climb_sign_q(dq.exact[u], dq.bounds[u], dq.exact[w], dq.bounds[w]);
    });
    // The first pair supports D along −v: every pair of the subset is level
    // with it, so v's certificate holds.
    if (a == best_sub[0].p && b == best_sub[0].q) return certify_closest(qu, best_sub, best_m, r);
    s = best_sub;
    s[best_m] = {qu.P.point(a) - qu.Q.point(b), a, b};
    n = best_m + 1;
    if (certify_closest_subsets(qu, s, n, r)) return true;
  }
  return false;
}

}  // namespace

RigidDistanceExact distance_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                  const RigidPose& pose_q) {
  return distance_on_m(p, pose_p, q, pose_q).values;
}

RigidDistance distance(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                       RigidWarmStart* warm) {
  ++g_stats.queries;
  const Query qu{Placed(p.data(), pose_p.map()), Placed(q.data(), pose_q.map()), p.data(), q.data()};
  const RigidWarmStart start = checked_start(p, q, warm);
  const V3 dir = initial_direction(qu, start);
  std::array<SimplexVertex, 4> s;
  int n = 1;
  s[0] = qu.support(-dir, start.p, start.q);
  V3 v = s[0].w;
  Index ip = s[0].p, iq = s[0].q;
  double last = std::numeric_limits<double>::infinity();
  bool tetrahedron = false;
  // GJK to convergence (doubles: the search proposes, the certificate
  // decides).
  for (int it = 0; it < kMaxIterations; ++it) {
    ++g_stats.iterations;
    const double vv = dot(v, v);
    if (!(vv > 0) || !std::isfinite(vv)) break;
    const SimplexVertex w = qu.support(-v, ip, iq);
    ip = w.p, iq = w.q;
    const double vw = dot(v, w.w);
    bool repeated = false;
    for (int k = 0; k < n; ++k) repeated = repeated || (s[k].p == w.p && s[k].q == w.q);
    if (repeated || !(vv < last) || vv - vw <= 1e-15 * vv) break;
    last = vv;
    s[n++] = w;
    if (!closest_on_simplex(s, n, v)) {
      tetrahedron = true;
      break;
    }
  }
  RigidDistance r;
  // Penetrating, certified by the tetrahedron s.
  const auto simplex_answer = [&] {
    r = RigidDistance{};
    r.status = ContactStatus::penetrating;
    r.certificate = RigidCertificate::simplex;
    r.k = 4;
    for (int j = 0; j < 4; ++j) r.p[j] = s[j].p, r.q[j] = s[j].q;
    // Doubles near the common point of exact_values: Σ μ_j p_j′ with μ_j the
    // origin's barycentric coordinates in the tetrahedron.
    const auto volume = [](const V3& a, const V3& b, const V3& c, const V3& e) {
      return dot(b - a, cross(c - a, e - a));
    };
    const double total = volume(s[0].w, s[1].w, s[2].w, s[3].w);
    V3 x;
    for (int j = 0; j < 4; ++j) {
      std::array<V3, 4> f{s[0].w, s[1].w, s[2].w, s[3].w};
      f[j] = V3{};
      x = x + (volume(f[0], f[1], f[2], f[3]) / total) * qu.P.point(s[j].p);
    }
    r.point_p = r.point_q = {x.x, x.y, x.z};
    return true;
  };
  bool decided = false;
  if (tetrahedron) {
    if (qu.certify_tetrahedron(s)) decided = simplex_answer();
  } else {
    decided = certify_closest_subsets(qu, s, n, r);
    if (!decided && n == 3 && blow_up_triangle(qu, s)) decided = simplex_answer();
    if (!decided) decided = refine_closest(qu, s, n, r);
  }
  if (!decided) {
    // Touching (the closest-points certificate needs v ≠ 0): the feature
    // plane proves it and gives a common point.
    FeaturePlane plane(qu);
    const auto c = plane.decide(s, n, ip, iq);
    if (c && c->status == ContactStatus::touching) {
      r = RigidDistance{};
      r.status = ContactStatus::touching;
      r.certificate = RigidCertificate::feature_plane;
      r.point_p = r.point_q = to_double(c->common);
      r.exact = std::make_shared<const RigidDistanceExact>(RigidDistanceExact{Rational(0), c->common, c->common});
      decided = true;
    }
  }
  if (!decided) {
    ExactDistance e = distance_on_m(p, pose_p, q, pose_q);
    r = RigidDistance{};
    r.status = e.status;
    r.certificate = RigidCertificate::exact;
    r.point_p = to_double(e.values.point_p), r.point_q = to_double(e.values.point_q);
    set_bounds(r, rational_bounds(e.values.squared_distance), std::sqrt(to_double(e.values.squared_distance)));
    r.exact = std::make_shared<const RigidDistanceExact>(std::move(e.values));
  }
  count(r.certificate);
  if (warm) {
    warm->p = ip, warm->q = iq;
    warm->direction = {v.x, v.y, v.z};
  }
  return r;
}

void distance(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
              std::span<const RigidPose> poses_q, std::span<RigidDistance> out, unsigned threads) {
  batch("distance", poses_p, poses_q, out, threads, [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) {
    return distance(p, a, q, b, w);
  });
}

void distance(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses, std::span<RigidDistance> out,
              unsigned threads) {
  batch(poses, out, threads, [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) {
    return distance(p, a, q, b, w);
  });
}

RigidDistanceExact exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                const RigidPose& pose_q, const RigidDistance& d) {
  if (d.certificate == RigidCertificate::exact || d.certificate == RigidCertificate::feature_plane) {
    if (d.exact) return *d.exact;
    return distance_exact(p, pose_p, q, pose_q);
  }
  const RigidBody::Data &dp = p.data(), &dq = q.data();
  const int k = d.k;
  const bool fits = (d.certificate == RigidCertificate::closest_points && k >= 1 && k <= 3) ||
                    (d.certificate == RigidCertificate::simplex && k == 4);
  if (!fits) throw UsageError("exact_values: the answer is not one of distance()");
  for (int j = 0; j < k; ++j)
    if (d.p[j] >= dp.approx.size() || d.q[j] >= dq.approx.size())
      throw UsageError("exact_values: the answer's vertices do not fit the bodies");
  const PlacedMap &mp = pose_p.map(), &mq = pose_q.map();
  RigidDistanceExact e;
  if (k == 4) {
    // The origin = Σ μ_j d_j with μ_j the barycentric coordinates (ratios of
    // signed volumes): Σ μ_j p_j' = Σ μ_j q_j' is a common point.
    std::array<Point3, 4> pp, dd;
    for (int j = 0; j < 4; ++j) pp[j] = mp.apply(dp.exact[d.p[j]]), dd[j] = pp[j] - mq.apply(dq.exact[d.q[j]]);
    const auto volume = [](const Point3& a, const Point3& b, const Point3& c, const Point3& f) {
      return dot(b - a, cross(c - a, f - a));
    };
    const Rational total = volume(dd[0], dd[1], dd[2], dd[3]);
    Point3 x(0, 0, 0);
    for (int j = 0; j < 4; ++j) {
      std::array<Point3, 4> f = dd;
      f[j] = Point3(0, 0, 0);
      x = x + (volume(f[0], f[1], f[2], f[3]) / total) * pp[j];
    }
    e.squared_distance = 0;
    e.point_p = e.point_q = x;
    return e;
  }
  std::array<const Point3*, 3> ps{}, qs{};
  std::array<const PointBounds*, 3> pb{}, qb{};
  for (int j = 0; j < k; ++j) {
    ps[j] = &dp.exact[d.p[j]], pb[j] = &dp.bounds[d.p[j]];
    qs[j] = &dq.exact[d.q[j]], qb[j] = &dq.bounds[d.q[j]];
  }
  const PlacedSimplexPoint sp(mp, mq, k, ps, pb, qs, qb);
  std::tie(e.point_p, e.point_q) = sp.points();
  e.squared_distance = sp.squared_norm();
  return e;
}

namespace {

// EPA's surface: triangles of vertices of D, each outward (the origin on
// the inner side), with the unit normal and distance of its plane, and
// the face across each edge (v[e], v[e + 1]) as 3 · face + its edge.
struct EpaFace {
  std::array<int, 3> v;
  std::array<int, 3> adj;
  V3 n;
  double dist;
  bool alive;
};

bool epa_face(const std::vector<SimplexVertex>& verts, int a, int b, int c, EpaFace& f) {
  const V3 n = cross(verts[b].w - verts[a].w, verts[c].w - verts[a].w);
  const double l = std::sqrt(dot(n, n));
  if (!(l > 0) || !std::isfinite(l)) return false;
  f.v = {a, b, c};
  f.adj = {-1, -1, -1};
  f.n = (1 / l) * n;
  f.dist = dot(f.n, verts[a].w);
  f.alive = true;
  return true;
}

// The faces of EPA's surface by distance (a min-heap of (dist, face);
// faces no longer alive are skipped when they come up).
using FaceQueue = std::vector<std::pair<double, int>>;

void queue_face(FaceQueue& queue, const std::vector<EpaFace>& faces, int k) {
  queue.push_back({faces[k].dist, k});
  std::push_heap(queue.begin(), queue.end(), std::greater<>());
}

int nearest_face(const std::vector<SimplexVertex>&, const std::vector<EpaFace>& faces, FaceQueue& queue) {
  while (!queue.empty() && !faces[queue.front().second].alive) {
    std::pop_heap(queue.begin(), queue.end(), std::greater<>());
    queue.pop_back();
  }
  return queue.empty() ? -1 : queue.front().second;
}

// An edge of the horizon: (a, b) as in the removed faces, and the face
// left alive across it (3 · face + its edge).
struct HorizonEdge {
  int a, b, outer;
};

// EPA's working storage, kept by each thread from one query to the next
// (cleared, not freed): a depth query then allocates nothing once warm.
struct EpaScratch {
  std::vector<SimplexVertex> verts;
  std::vector<EpaFace> faces;
  FaceQueue queue;
  std::vector<HorizonEdge> horizon;
  std::vector<std::array<int, 3>> tris;
  std::vector<const EpaFace*> alive;
  std::vector<int> first, to;
  std::vector<PointBounds> db;
  std::vector<std::array<int, 2>> signs;
};
EpaScratch& epa_scratch() {
  thread_local EpaScratch s;
  return s;
}

// The faces that see w, from the face g entered across its edge e (g's
// side of an edge of a removed face): removed, depth first, each face's
// other two edges in turn, so that the horizon comes out as one loop in
// order when the removed faces form a disc.
void remove_visible(const std::vector<SimplexVertex>& verts, std::vector<EpaFace>& faces, const V3& w, int g, int e,
                    std::vector<HorizonEdge>& horizon) {
  EpaFace& f = faces[g];
  if (!f.alive) return;
  if (!(dot(f.n, w - verts[f.v[0]].w) > 0)) {
    horizon.push_back({f.v[(e + 1) % 3], f.v[e], 3 * g + e});
    return;
  }
  f.alive = false;
  for (int k = 1; k < 3; ++k) {
    const int across = faces[g].adj[(e + k) % 3];
    remove_visible(verts, faces, w, across / 3, across % 3, horizon);
  }
}

// The tetrahedron s (holding the origin) as EPA's first surface: four
// outward faces, their neighbours, the queue.
bool start_surface(const std::array<SimplexVertex, 4>& s, std::vector<SimplexVertex>& verts,
                   std::vector<EpaFace>& faces) {
  verts.assign(s.begin(), s.end());
  faces.clear();
  FaceQueue& queue = epa_scratch().queue;
  queue.clear();
  static constexpr int tri[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
  for (const auto& t : tri) {
    EpaFace f;
    if (!epa_face(verts, t[0], t[1], t[2], f)) return false;
    if (dot(f.n, verts[t[3]].w - verts[t[0]].w) > 0 && !epa_face(verts, t[0], t[2], t[1], f)) return false;
    faces.push_back(f);
  }
  for (int g = 0; g < 4; ++g)
    for (int e = 0; e < 3; ++e)
      for (int h = 0; h < 4; ++h)
        for (int x = 0; x < 3; ++x)
          if (faces[h].v[x] == faces[g].v[(e + 1) % 3] && faces[h].v[(x + 1) % 3] == faces[g].v[e])
            faces[g].adj[e] = 3 * h + x;
  for (int g = 0; g < 4; ++g) {
    for (int e = 0; e < 3; ++e)
      if (faces[g].adj[e] < 0) return false;
    queue_face(queue, faces, g);
  }
  return true;
}

// The vertex w, beyond the face `best`, replaces that face and the faces
// that see it (found across edges from it) by the cone over their horizon.
// False when the horizon is not one loop or a new face degenerates.
bool insert_vertex(std::vector<SimplexVertex>& verts, std::vector<EpaFace>& faces, int best,
                   const SimplexVertex& w) {
  std::vector<HorizonEdge>& horizon = epa_scratch().horizon;
  const int iw = int(verts.size());
  verts.push_back(w);
  horizon.clear();
  faces[best].alive = false;
  const std::array<int, 3> adj = faces[best].adj;
  for (int e = 0; e < 3; ++e) remove_visible(verts, faces, w.w, adj[e] / 3, adj[e] % 3, horizon);
  const int m = int(horizon.size());
  if (m < 3) return false;
  for (int k = 0; k < m; ++k)
    if (horizon[k].b != horizon[(k + 1) % m].a) return false;
  const int first = int(faces.size());
  for (int k = 0; k < m; ++k) {
    EpaFace g;
    if (!epa_face(verts, horizon[k].a, horizon[k].b, iw, g)) return false;
    g.adj = {horizon[k].outer, 3 * (first + (k + 1) % m) + 2, 3 * (first + (k + m - 1) % m) + 1};
    faces[horizon[k].outer / 3].adj[horizon[k].outer % 3] = 3 * (first + k);
    faces.push_back(g);
    queue_face(epa_scratch().queue, faces, first + k);
  }
  return true;
}

// Grows EPA's surface towards ∂D in doubles, each time at the face `select`
// picks (EPA: the nearest; a ray: the one it crosses), until the support
// along that face's normal brings no new vertex.  False when the search
// degenerates (no certificate is tried).
template <class Select>
bool grow(const Query& qu, std::vector<SimplexVertex>& verts, std::vector<EpaFace>& faces, const Select& select) {
  for (int it = 0; it < 4 * kMaxIterations; ++it) {
    ++g_stats.iterations;
    const int best = select(verts, faces, epa_scratch().queue);
    if (best < 0) return false;
    const EpaFace& f = faces[best];
    const SimplexVertex& a0 = verts[f.v[0]];
    const SimplexVertex w = qu.support(f.n, a0.p, a0.q);
    const double gain = dot(f.n, w.w) - f.dist;
    bool known = false;
    for (const SimplexVertex& x : verts) known = known || (x.p == w.p && x.q == w.q);
    if (known || gain <= 1e-14 * std::max(1.0, std::fabs(f.dist))) return true;
    if (!insert_vertex(verts, faces, best, w)) return false;
  }
  return false;
}

// The face whose cone from the origin holds the direction u best (the
// largest of the smallest of its three edge determinants, normalised).
struct CrossedFace {
  V3 u;
  int operator()(const std::vector<SimplexVertex>& verts, const std::vector<EpaFace>& faces,
                 const FaceQueue& = {}) const {
    int best = -1;
    double best_score = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < int(faces.size()); ++k) {
      if (!faces[k].alive) continue;
      double score = std::numeric_limits<double>::infinity();
      for (int e = 0; e < 3; ++e) {
        const V3 a = verts[faces[k].v[e]].w, b = verts[faces[k].v[(e + 1) % 3]].w;
        const V3 c = cross(a, b);
        const double l = std::sqrt(dot(c, c));
        score = std::min(score, l > 0 ? dot(c, u) / l : 0.0);
      }
      if (dot(faces[k].n, u) > 0 && score > best_score) best = k, best_score = score;
    }
    return best;
  }
};

// The vertices of P (of Q) level with the vertex 0 of the triangle f of
// D along its normal n by construction: n is orthogonal to d_j − d_i for
// f's pairs i, j, so n · (p_j′ − p_i′) = 0 when q_i = q_j (and n · (q_j′ −
// q_i′) = 0 when p_i = p_j).  Three distinct vertices of P so joined span
// f's plane (once h ≠ 0 is proved, n ≠ 0 and they are not collinear): when a
// facet of P holds them, all its vertices are level.
struct LevelSets {
  std::vector<Index> p, q;
};
bool in(const std::vector<Index>& v, Index x) { return std::find(v.begin(), v.end(), x) != v.end(); }

LevelSets level_sets(const Query& qu, const std::vector<SimplexVertex>& verts, const EpaFace& f) {
  std::array<Index, 3> fp, fq;
  for (int j = 0; j < 3; ++j) fp[j] = verts[f.v[j]].p, fq[j] = verts[f.v[j]].q;
  LevelSets l{{fp[0]}, {fq[0]}};
  for (bool grew = true; grew;) {
    grew = false;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (fq[i] == fq[j] && in(l.p, fp[i]) && !in(l.p, fp[j])) l.p.push_back(fp[j]), grew = true;
        if (fp[i] == fp[j] && in(l.q, fq[i]) && !in(l.q, fq[j])) l.q.push_back(fq[j]), grew = true;
      }
  }
  const auto facet_of = [](const ConvexPolytope& poly, std::vector<Index>& level) {
    if (level.size() < 3) return;
    const Index h0 = poly.vertex_halfedge(level[0]);
    Index h = h0;
    do {
      const std::vector<Index> fv = poly.facet_vertices(poly.facet(h));
      bool all = true;
      for (Index x : level) all = all && std::find(fv.begin(), fv.end(), x) != fv.end();
      if (all) {
        for (Index x : fv)
          if (!in(level, x)) level.push_back(x);
        return;
      }
      h = poly.next_around_vertex(h);
    } while (h != h0);
  };
  facet_of(qu.dp.poly, l.p);
  facet_of(qu.dq.poly, l.q);
  return l;
}

// Whether the plane of F supports D, checked at the pair (ia, ja) of F:
// no neighbour of ia further along n on placed P, none of ja further back
// on placed Q (level neighbours skipped).
// When it does not, *beyond (if given) is the pair of D found strictly
// beyond the plane (that neighbour with the other vertex of (ia, ja)).
bool plane_supports(const Query& qu, const PlacedTriangle& F, const LevelSets& level, Index ia, Index ja,
                    SimplexVertex* beyond = nullptr) {
  const RigidBody::Data &dp = qu.dp, &dq = qu.dq;
  const auto found = [&](Index a, Index b) {
    if (beyond) *beyond = {qu.P.point(a) - qu.Q.point(b), a, b};
    return false;
  };
  for (Index e = dp.first[ia]; e < dp.first[ia + 1]; ++e)
    if (!in(level.p, dp.nbr[e]) &&
        F.climb_sign_p(dp.exact[ia], dp.bounds[ia], dp.exact[dp.nbr[e]], dp.bounds[dp.nbr[e]]) > 0)
      return found(dp.nbr[e], ja);
  for (Index e = dq.first[ja]; e < dq.first[ja + 1]; ++e)
    if (!in(level.q, dq.nbr[e]) &&
        F.climb_sign_q(dq.exact[ja], dq.bounds[ja], dq.exact[dq.nbr[e]], dq.bounds[dq.nbr[e]]) > 0)
      return found(ia, dq.nbr[e]);
  return true;
}

// The placed triangle of EPA's face f; `db`: the enclosures of the
// vertices (placed_difference_bounds), when made already.
PlacedTriangle placed_triangle(const Query& qu, const std::vector<SimplexVertex>& verts, const EpaFace& f,
                               const std::vector<PointBounds>* db = nullptr) {
  std::array<const Point3*, 3> p, q;
  std::array<const PointBounds*, 3> pb, qb, d;
  for (int j = 0; j < 3; ++j) {
    const SimplexVertex& x = verts[f.v[j]];
    p[j] = &qu.dp.exact[x.p], pb[j] = &qu.dp.bounds[x.p], q[j] = &qu.dq.exact[x.q], qb[j] = &qu.dq.bounds[x.q];
    if (db) d[j] = &(*db)[f.v[j]];
  }
  if (db) return PlacedTriangle(qu.P.map, qu.Q.map, p, pb, q, qb, d);
  return PlacedTriangle(qu.P.map, qu.Q.map, p, pb, q, qb);
}

// The certificate of a depth (rigid_proximity.hpp) on EPA's surface.  When
// every check holds but the last (the nearest face's plane supports D),
// *unsupported is that face and *beyond the pair of D beyond its plane.
bool certify_depth(const Query& qu, const std::vector<SimplexVertex>& verts, const std::vector<EpaFace>& faces,
                   RigidDepth& r, int* unsupported = nullptr, SimplexVertex* beyond = nullptr) {
  if (unsupported) *unsupported = -1;
  EpaScratch& scratch = epa_scratch();
  std::vector<std::array<int, 3>>& tris = scratch.tris;
  std::vector<const EpaFace*>& alive = scratch.alive;
  tris.clear(), alive.clear();
  int nearest = 0;
  for (const EpaFace& f : faces) {
    if (!f.alive) continue;
    if (alive.empty() || f.dist < alive[nearest]->dist) nearest = int(alive.size());
    alive.push_back(&f);
    tris.push_back(f.v);
  }
  const int nf = int(alive.size());
  if (nf == 0) return false;
  // A closed, consistently oriented surface of genus 0: each directed edge
  // (a, b) once, and (b, a) one too (each vertex's out-edges listed), and
  // V − E + F = 2.
  const int n = int(verts.size());
  std::vector<int>& first = scratch.first;
  std::vector<int>& to = scratch.to;
  first.assign(n + 2, 0), to.resize(3 * nf);
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) ++first[t[e] + 2];
  for (int a = 0; a < n; ++a) first[a + 2] += first[a + 1];
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) to[first[t[e] + 1]++] = t[(e + 1) % 3];
  const auto out = [&](int a) { return std::span<const int>(to.data() + first[a], to.data() + first[a + 1]); };
  int nv = 0;
  for (int a = 0; a < n; ++a) {
    const auto oa = out(a);
    nv += !oa.empty();
    for (std::size_t i = 0; i < oa.size(); ++i) {
      if (std::find(oa.begin() + i + 1, oa.end(), oa[i]) != oa.end()) return false;
      const auto ob = out(oa[i]);
      if (std::find(ob.begin(), ob.end(), a) == ob.end()) return false;
    }
  }
  if (nv - 3 * nf / 2 + nf != 2) return false;
  // The enclosures of the surface's vertices, once (each is a corner of
  // several faces), and the filters of every face on them.
  std::vector<PointBounds>& db = scratch.db;
  db.resize(n);
  for (int a = 0; a < n; ++a)
    if (first[a + 1] > first[a])
      db[a] = placed_difference_bounds(qu.P.map, qu.dp.bounds[verts[a].p], qu.Q.map, qu.dq.bounds[verts[a].q]);
  std::vector<std::array<int, 2>>& signs = scratch.signs;
  placed_surface_signs(db, tris, nearest, signs);
  const PlacedTriangle F = placed_triangle(qu, verts, *alive[nearest], &db);
  const EpaFace& f = *alive[nearest];
  const LevelSets level = level_sets(qu, verts, f);
  // Each face's exact signs only where its intervals leave them undecided.
  for (int k = 0; k < nf; ++k) {
    const int offset = signs[k][0];
    if (offset == 0 || offset == -1) return false;
    if (offset == kUndecidedSign &&
        (k == nearest ? F.offset_sign() : placed_triangle(qu, verts, *alive[k], &db).offset_sign()) <= 0)
      return false;
    if (k == nearest || signs[k][1] == 0 || signs[k][1] == 1) continue;
    bool coplanar = true;
    for (int j = 0; j < 3 && coplanar; ++j)
      coplanar = in(level.p, verts[alive[k]->v[j]].p) && in(level.q, verts[alive[k]->v[j]].q);
    if (!coplanar &&
        (signs[k][1] == -1 || compare_distance(placed_triangle(qu, verts, *alive[k], &db), F) < 0))
      return false;
  }
  if (!plane_supports(qu, F, level, verts[f.v[0]].p, verts[f.v[0]].q, beyond)) {
    if (unsupported && beyond) *unsupported = int(&f - faces.data());
    return false;
  }
  for (int j = 0; j < 3; ++j) r.p[j] = verts[f.v[j]].p, r.q[j] = verts[f.v[j]].q;
  r.status = ContactStatus::penetrating;
  r.certificate = RigidCertificate::nearest_facet;
  set_bounds(r, F.squared_distance_bounds(), std::max(f.dist, 0.0));
  r.direction = {-r.depth * f.n.x, -r.depth * f.n.y, -r.depth * f.n.z};
  return true;
}

// The tetrahedron of D that proved collide's penetrating answer (left in
// the warm start), on this pose's doubles: EPA starts from it.
bool collision_tetrahedron(const Query& qu, const RigidWarmStart& w, std::array<SimplexVertex, 4>& s) {
  if (!w.tetrahedron) return false;
  for (int k = 0; k < 4; ++k) s[k] = {qu.P.point(w.tp[k]) - qu.Q.point(w.tq[k]), w.tp[k], w.tq[k]};
  return true;
}

// A tetrahedron of D holding the origin (in doubles), by the search again
// from the witnesses collide left (a few steps), when collide's answer came
// from M; a triangle holding it is blown up as collide does.
bool search_tetrahedron(const Query& qu, const RigidWarmStart& start, std::array<SimplexVertex, 4>& s) {
  const V3 dir = initial_direction(qu, start);
  int n = 1;
  s[0] = qu.support(-dir, start.p, start.q);
  V3 v = s[0].w;
  Index ip = s[0].p, iq = s[0].q;
  bool tetrahedron = false;
  double last = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxIterations; ++it) {
    const double vv = dot(v, v);
    if (!(vv > 0) || !std::isfinite(vv)) break;
    const SimplexVertex w = qu.support(-v, ip, iq);
    ip = w.p, iq = w.q;
    bool repeated = false;
    for (int k = 0; k < n; ++k) repeated = repeated || (s[k].p == w.p && s[k].q == w.q);
    if (repeated || !(vv < last)) break;
    last = vv;
    s[n++] = w;
    if (!closest_on_simplex(s, n, v)) {
      tetrahedron = true;
      break;
    }
  }
  if (!tetrahedron && n == 3) tetrahedron = blow_up_triangle(qu, s);
  return tetrahedron;
}

RigidDepthExact depth_on_m(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                           ContactStatus* status) {
  TranslationalObstacle ob(placed_linear(p.polytope(), pose_p.map()), placed_linear(q.polytope(), pose_q.map()));
  const DepthResult d = ob.penetration_depth(pose_p.map().t(), pose_q.map().t());
  if (status) *status = d.status;
  return {d.squared_depth(), d.direction()};
}

}  // namespace

RigidDepthExact depth_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q) {
  return depth_on_m(p, pose_p, q, pose_q, nullptr);
}

RigidDepth penetration_depth(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                             RigidWarmStart* warm) {
  RigidDepth r;
  RigidWarmStart local;
  if (!warm) warm = &local;
  const RigidCollision c = collide_search(p, pose_p, q, pose_q, warm, false);
  r.status = c.status;
  r.certificate = c.certificate;
  if (c.status != ContactStatus::penetrating) return r;
  const Query qu{Placed(p.data(), pose_p.map()), Placed(q.data(), pose_q.map()), p.data(), q.data()};
  // EPA from collide's tetrahedron; when its surface is not certified (the
  // doubles' choices), once more from the search's.
  std::array<SimplexVertex, 4> s;
  std::vector<SimplexVertex>& verts = epa_scratch().verts;
  std::vector<EpaFace>& faces = epa_scratch().faces;
  // A surface whose nearest face's plane turns out not to support D
  // exactly (a vertex of D beyond it by less than the doubles resolve) takes
  // that vertex and grows on, a few times.
  const auto epa = [&](const std::array<SimplexVertex, 4>& t) {
    if (!start_surface(t, verts, faces) || !grow(qu, verts, faces, nearest_face)) return false;
    for (int round = 0;; ++round) {
      int unsupported = -1;
      SimplexVertex beyond;
      if (certify_depth(qu, verts, faces, r, &unsupported, &beyond)) return true;
      if (unsupported < 0 || round == kDepthContinuations) return false;
      for (const SimplexVertex& x : verts)
        if (x.p == beyond.p && x.q == beyond.q) return false;
      ++g_stats.epa_continuations;
      if (!insert_vertex(verts, faces, unsupported, beyond) || !grow(qu, verts, faces, nearest_face)) return false;
    }
  };
  if ((collision_tetrahedron(qu, *warm, s) && epa(s)) ||
      (search_tetrahedron(qu, checked_start(p, q, warm), s) && epa(s))) {
    count(r.certificate);
    return r;
  }
  count(RigidCertificate::exact);
  ContactStatus st;
  RigidDepthExact e = depth_on_m(p, pose_p, q, pose_q, &st);
  r = RigidDepth{};
  r.status = st;
  r.certificate = RigidCertificate::exact;
  r.direction = to_double(e.direction);
  set_bounds(r, rational_bounds(e.squared_depth), std::sqrt(to_double(e.squared_depth)));
  r.exact = std::make_shared<const RigidDepthExact>(std::move(e));
  return r;
}

void penetration_depth(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
                       std::span<const RigidPose> poses_q, std::span<RigidDepth> out, unsigned threads) {
  batch("penetration_depth", poses_p, poses_q, out, threads,
        [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) { return penetration_depth(p, a, q, b, w); });
}

void penetration_depth(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses,
                       std::span<RigidDepth> out, unsigned threads) {
  batch(poses, out, threads,
        [&](const RigidPose& a, const RigidPose& b, RigidWarmStart* w) { return penetration_depth(p, a, q, b, w); });
}

RigidDepthExact exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                             const RigidDepth& d) {
  if (d.status != ContactStatus::penetrating) return {Rational(0), Point3(0, 0, 0)};
  if (d.certificate == RigidCertificate::exact) {
    if (d.exact) return *d.exact;
    return depth_exact(p, pose_p, q, pose_q);
  }
  if (d.certificate != RigidCertificate::nearest_facet)
    throw UsageError("exact_values: the answer is not one of penetration_depth()");
  const RigidBody::Data &dp = p.data(), &dq = q.data();
  std::array<const Point3*, 3> ps, qs;
  std::array<const PointBounds*, 3> pb, qb;
  for (int j = 0; j < 3; ++j) {
    if (d.p[j] >= dp.approx.size() || d.q[j] >= dq.approx.size())
      throw UsageError("exact_values: the answer's vertices do not fit the bodies");
    ps[j] = &dp.exact[d.p[j]], pb[j] = &dp.bounds[d.p[j]], qs[j] = &dq.exact[d.q[j]], qb[j] = &dq.bounds[d.q[j]];
  }
  const PlacedTriangle t(pose_p.map(), pose_q.map(), ps, pb, qs, qb);
  return {t.squared_distance(), -t.nearest_point()};
}

Rational directional_depth_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                 const RigidPose& pose_q, const Point3& d) {
  TranslationalObstacle ob(placed_linear(p.polytope(), pose_p.map()), placed_linear(q.polytope(), pose_q.map()));
  return ob.directional_depth(pose_p.map().t(), pose_q.map().t(), d).t;
}

RigidDirectionalDepth directional_depth(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                        const RigidPose& pose_q, const Point3& d, RigidWarmStart* warm) {
  if (is_zero(d)) throw UsageError("directional_depth: the direction must not be the zero vector");
  RigidDirectionalDepth r;
  RigidWarmStart local;
  if (!warm) warm = &local;
  const RigidCollision c = collide_search(p, pose_p, q, pose_q, warm, false);
  r.status = c.status;
  r.certificate = c.certificate;
  if (c.status != ContactStatus::penetrating) return r;
  const Query qu{Placed(p.data(), pose_p.map()), Placed(q.data(), pose_q.map()), p.data(), q.data()};
  std::array<SimplexVertex, 4> s;
  const Point3 u = -d;  // the ray leaves D at −α d
  const PointBounds ub = point_bounds(u);
  const Vec3d ud = to_double(u);
  std::vector<SimplexVertex>& verts = epa_scratch().verts;
  std::vector<EpaFace>& faces = epa_scratch().faces;
  const CrossedFace crossed{V3{ud.x, ud.y, ud.z}};
  // From collide's tetrahedron, then (its surface not certified) from the
  // search's, as for the depth.
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!(attempt == 0 ? collision_tetrahedron(qu, *warm, s) : search_tetrahedron(qu, checked_start(p, q, warm), s)) ||
        !start_surface(s, verts, faces) || !grow(qu, verts, faces, crossed))
      continue;
    const int k = crossed(verts, faces);
    if (k < 0) continue;
    const EpaFace& f = faces[k];
    const PlacedTriangle T = placed_triangle(qu, verts, f);
    bool ok = T.offset_sign() > 0 && T.direction_sign(u, ub) > 0;
    for (int e = 0; e < 3 && ok; ++e) ok = T.edge_sign(e, u, ub) >= 0;
    if (ok && plane_supports(qu, T, level_sets(qu, verts, f), verts[f.v[0]].p, verts[f.v[0]].q)) {
      r.certificate = RigidCertificate::exit_facet;
      count(r.certificate);
      for (int j = 0; j < 3; ++j) r.p[j] = verts[f.v[j]].p, r.q[j] = verts[f.v[j]].q;
      const Bounds b = T.ray_parameter_bounds(ub);
      r.lower = std::max(0.0, b.lo), r.upper = b.hi;
      const V3 a = verts[f.v[0]].w;
      const double nu = dot(f.n, V3{ud.x, ud.y, ud.z});
      r.t = std::clamp(nu > 0 ? dot(f.n, a) / nu : r.lower, r.lower, r.upper);
      return r;
    }
  }
  count(RigidCertificate::exact);
  r = RigidDirectionalDepth{};
  r.status = ContactStatus::penetrating;
  r.certificate = RigidCertificate::exact;
  Rational t = directional_depth_exact(p, pose_p, q, pose_q, d);
  const Bounds b = rational_bounds(t);
  r.lower = b.lo, r.upper = b.hi, r.t = to_double(t);
  r.exact = std::make_shared<const Rational>(std::move(t));
  return r;
}

Rational exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                      const Point3& d, const RigidDirectionalDepth& r) {
  if (r.status != ContactStatus::penetrating) return Rational(0);
  if (r.certificate == RigidCertificate::exact) return r.exact ? *r.exact : directional_depth_exact(p, pose_p, q, pose_q, d);
  if (r.certificate != RigidCertificate::exit_facet)
    throw UsageError("exact_values: the answer is not one of directional_depth()");
  const RigidBody::Data &dp = p.data(), &dq = q.data();
  std::array<const Point3*, 3> ps, qs;
  std::array<const PointBounds*, 3> pb, qb;
  for (int j = 0; j < 3; ++j) {
    if (r.p[j] >= dp.approx.size() || r.q[j] >= dq.approx.size())
      throw UsageError("exact_values: the answer's vertices do not fit the bodies");
    ps[j] = &dp.exact[r.p[j]], pb[j] = &dp.bounds[r.p[j]], qs[j] = &dq.exact[r.q[j]], qb[j] = &dq.bounds[r.q[j]];
  }
  return PlacedTriangle(pose_p.map(), pose_q.map(), ps, pb, qs, qb).ray_parameter(-d);
}

}  // namespace minksum
