// The boundary sweep of the non-convex sum (docs/nonconvex.md, "Method"):
// the local normal cones of a solid's surface, which decide which facets of
// a piece t ⊕ B_j can be on the boundary of A ⊕ B, and the exact
// point-in-solid test that tells the pockets of the sweep inside A + b from
// the boundary of A ⊕ B.
#include <minksum/dot_difference.hpp>
#include <minksum/parallel.hpp>
#include <minksum/predicates.hpp>

#include "kernel/line_box.hpp"
#include "kernel/plane.hpp"
#include "nonconvex/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <unordered_map>

namespace minksum::nonconvex_detail {

SurfaceCones::SurfaceCones(const Mesh& triangles) {
  const std::size_t nv = triangles.points.size();
  points_.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    points_.push_back(triangles.points[v]);
    approx_.push_back(to_double(points_.back()));
  }
  tri_.reserve(triangles.faces.size());
  for (const auto& f : triangles.faces) {
    if (f.size() != 3) throw std::logic_error("SurfaceCones: a face that is not a triangle");
    tri_.push_back({f[0], f[1], f[2]});
  }
  // (a, b) -> (triangle, edge); then each triangle's normal, and for each
  // edge the face across it, in parallel.
  struct PairHash {
    std::size_t operator()(const std::pair<Index, Index>& e) const {
      return std::hash<std::uint64_t>()((std::uint64_t(e.first) << 32) ^ e.second);
    }
  };
  std::unordered_map<std::pair<Index, Index>, std::pair<Index, int>, PairHash> directed;
  directed.reserve(3 * tri_.size());
  for (Index t = 0; t < tri_.size(); ++t)
    for (int k = 0; k < 3; ++k) directed[{tri_[t][k], tri_[t][(k + 1) % 3]}] = {t, k};
  normal_.resize(tri_.size());
  normal_approx_.resize(tri_.size());
  box_.resize(tri_.size());
  opposite_.resize(tri_.size());
  kind_.resize(tri_.size());
  neighbours_.resize(nv);
  incident_.resize(nv);
  across_.resize(tri_.size());
  for (Index t = 0; t < tri_.size(); ++t) {
    const auto& c = tri_[t];
    for (int k = 0; k < 3; ++k) {
      incident_[c[k]].push_back(t);
      neighbours_[c[k]].push_back(c[(k + 1) % 3]);
      if (directed.find({c[(k + 1) % 3], c[k]}) == directed.end())
        throw std::logic_error("SurfaceCones: an edge with one triangle");
    }
  }
  // The points as integers over a common denominator each: the normals and
  // the edges' kinds in integers, with no rational normalisation (the
  // vertices of an erosion, swept in an opening, have several hundred bits).
  scaled_.resize(nv);
  parallel_for(nv, parallel_threads(0, nv / 256 + 1), [&](std::size_t v) { scaled_[v] = scaled_point(points_[v]); });
  const std::vector<ScaledPoint>& scaled = scaled_;
  parallel_for(tri_.size(), parallel_threads(0, tri_.size() / 256 + 1), [&](std::size_t t) {
    const auto& c = tri_[t];
    // The primitive integer multiple of (p1 - p0) x (p2 - p0): a positive
    // multiple of positive multiples' cross product, divided by its gcd.
    Integer e1[3], e2[3], n[3], g;
    scaled_difference(scaled[c[0]], scaled[c[1]], e1);
    scaled_difference(scaled[c[0]], scaled[c[2]], e2);
    for (int j = 0; j < 3; ++j) {
      const int k = (j + 1) % 3, l = (j + 2) % 3;
      mpz_mul(n[j].get_mpz_t(), e1[k].get_mpz_t(), e2[l].get_mpz_t());
      mpz_submul(n[j].get_mpz_t(), e1[l].get_mpz_t(), e2[k].get_mpz_t());
      mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), n[j].get_mpz_t());
    }
    if (sgn(g) != 0 && g != 1)
      for (Integer& x : n) mpz_divexact(x.get_mpz_t(), x.get_mpz_t(), g.get_mpz_t());
    // n . p0 = off / p0.den, the same for the triangle's three points.
    Integer off, val, t1;
    const ScaledPoint& s0 = scaled[c[0]];
    mpz_mul(off.get_mpz_t(), n[0].get_mpz_t(), s0.num[0].get_mpz_t());
    mpz_addmul(off.get_mpz_t(), n[1].get_mpz_t(), s0.num[1].get_mpz_t());
    mpz_addmul(off.get_mpz_t(), n[2].get_mpz_t(), s0.num[2].get_mpz_t());
    normal_[t] = Point3(Rational(n[0]), Rational(n[1]), Rational(n[2]));
    normal_approx_[t] = to_double(normal_[t]);
    double* lo = &box_[t][0];
    double* hi = &box_[t][3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min({approx_[c[0]][k], approx_[c[1]][k], approx_[c[2]][k]});
      hi[k] = std::max({approx_[c[0]][k], approx_[c[1]][k], approx_[c[2]][k]});
    }
    widen_box(lo, hi);
    for (int k = 0; k < 3; ++k) {
      const Index a = c[k], b = c[(k + 1) % 3];
      const auto it = directed.find({b, a});
      const auto& o = tri_[it->second.first];
      const Index w = o[(it->second.second + 2) % 3];
      opposite_[t][k] = w;
      // Paired both ways: t is the triangle across the reversed edge too.
      const auto back = directed.find({a, b});
      across_[t][k] = back->second.first == Index(t) ? it->second.first : kNoTriangle;
      // The neighbour's far vertex below this triangle's plane: a convex
      // edge; on it: flat; above: reflex.
      // sign n . (w - p0) = sign(n . w.num p0.den - off w.den), the
      // denominators positive.
      const ScaledPoint& sw = scaled[w];
      mpz_mul(t1.get_mpz_t(), n[0].get_mpz_t(), sw.num[0].get_mpz_t());
      mpz_addmul(t1.get_mpz_t(), n[1].get_mpz_t(), sw.num[1].get_mpz_t());
      mpz_addmul(t1.get_mpz_t(), n[2].get_mpz_t(), sw.num[2].get_mpz_t());
      mpz_mul(val.get_mpz_t(), t1.get_mpz_t(), s0.den.get_mpz_t());
      mpz_submul(val.get_mpz_t(), off.get_mpz_t(), sw.den.get_mpz_t());
      kind_[t][k] = static_cast<signed char>(sgn(val));
    }
  });
  // Each edge numbered by the first triangle holding it; the triangle
  // across, later, runs it the other way.
  edge_.resize(tri_.size());
  for (Index t = 0; t < tri_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = tri_[t][k], b = tri_[t][(k + 1) % 3], o = across_[t][k];
      if (o != kNoTriangle && o < t) {
        const auto& d = tri_[o];
        int j = 0;
        while (!(d[j] == b && d[(j + 1) % 3] == a)) ++j;
        edge_[t][k] = edge_[o][j] | 1;
      } else {
        edge_[t][k] = Index(edge_ends_.size()) << 1;
        edge_ends_.push_back({a, b});
      }
    }
  // Each triangle its own polygon (merge_coplanar groups them).
  polygons_.resize(tri_.size());
  polygon_of_.resize(tri_.size());
  for (Index t = 0; t < tri_.size(); ++t) {
    polygons_[t].corners.assign(tri_[t].begin(), tri_[t].end());
    polygons_[t].edge_triangle.assign(3, t);
    polygons_[t].edge_index = {0, 1, 2};
    polygon_of_[t] = t;
  }
}

void SurfaceCones::merge_coplanar() {
  constexpr Index kNone = ~Index(0);
  std::vector<Polygon> merged;
  std::vector<Index> of(tri_.size(), kNone);
  // sign n . ((y - x) x (z - y)) for the primitive normal n of the plane of
  // x, y, z: > 0 when x, y, z turn counter-clockwise seen from outside.  In
  // integers (each difference a positive multiple of the exact one).
  auto turn = [&](const Point3& n, Index x, Index y, Index z) {
    Integer d1[3], d2[3], c;
    scaled_difference(scaled_[x], scaled_[y], d1);
    scaled_difference(scaled_[y], scaled_[z], d2);
    Integer sum;
    for (int j = 0; j < 3; ++j) {
      const int k = (j + 1) % 3, l = (j + 2) % 3;
      mpz_mul(c.get_mpz_t(), d1[k].get_mpz_t(), d2[l].get_mpz_t());
      mpz_submul(c.get_mpz_t(), d1[l].get_mpz_t(), d2[k].get_mpz_t());
      mpz_addmul(sum.get_mpz_t(), c.get_mpz_t(), n[j].get_num().get_mpz_t());
    }
    return sgn(sum);
  };
  for (Index t0 = 0; t0 < tri_.size(); ++t0) {
    if (of[t0] != kNone) continue;
    const Index id = Index(merged.size());
    Polygon p;
    p.corners.assign(tri_[t0].begin(), tri_[t0].end());
    p.edge_triangle.assign(3, t0);
    p.edge_index = {0, 1, 2};
    of[t0] = id;
    const Point3& n = normal_[t0];
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t k = 0; k < p.corners.size() && p.corners.size() < kMaxCorners; ++k) {
        const Index t = p.edge_triangle[k];
        const int j = p.edge_index[k];
        const Index s = across_[t][j];
        // A flat edge between two triangles of the same oriented plane
        // (their primitive normals equal), s not grouped yet.
        if (s == kNoTriangle || of[s] != kNone || kind_[t][j] != 0 || normal_[s] != n) continue;
        const std::size_t m = p.corners.size();
        const Index a = p.corners[k], b = p.corners[(k + 1) % m];
        const Index w = opposite_[t][j];
        const Index before = p.corners[(k + m - 1) % m], after = p.corners[(k + 2) % m];
        // Strictly convex at a and b (at w it is: s is counter-clockwise).
        if (turn(n, before, a, w) <= 0 || turn(n, w, b, after) <= 0) continue;
        // s runs b, a, w: its edges (a, w) and (w, b) replace (a, b).
        const auto& d = tri_[s];
        int ia = 0;
        while (d[ia] != a) ++ia;
        const int iw = (ia + 1) % 3;
        if (d[iw] != w || d[(iw + 1) % 3] != b) throw std::logic_error("SurfaceCones: a flat neighbour not across its edge");
        p.corners.insert(p.corners.begin() + std::ptrdiff_t(k + 1), w);
        p.edge_triangle[k] = s;
        p.edge_index[k] = std::uint8_t(ia);
        p.edge_triangle.insert(p.edge_triangle.begin() + std::ptrdiff_t(k + 1), s);
        p.edge_index.insert(p.edge_index.begin() + std::ptrdiff_t(k + 1), std::uint8_t(iw));
        of[s] = id;
        grew = true;
      }
    }
    merged.push_back(std::move(p));
  }
  polygons_ = std::move(merged);
  polygon_of_ = std::move(of);
  polygons_at_.assign(points_.size(), {});
  for (Index g = 0; g < polygons_.size(); ++g)
    for (Index v : polygons_[g].corners) polygons_at_[v].push_back(g);  // ascending in g
  merged_ = true;
}

namespace {

const Point3& origin() {
  static const Point3 o(Rational(0), Rational(0), Rational(0));
  return o;
}
const Vec3d kOriginApprox{0, 0, 0};

}  // namespace

// sign(u . (w - v)) = dot_difference_sign(u, v, w); `level` is a
// neighbour known to be at v's height along u (u . (level - v) = 0 exactly,
// as the caller decided it), which needs no test: the filter cannot prove a
// zero, so it would go to exact arithmetic every time.
bool SurfaceCones::below_all_neighbours(Index v, const RoundedPoint3& u, Index level) const {
  for (Index w : neighbours_[v])
    if (w != level && dot_difference_sign(u, at(v), at(w)) > 0) return false;
  return true;
}

bool SurfaceCones::candidate(Index t, const RoundedPoint3& u) const {
  const auto& c = tri_[t];
  // The vertices of t highest along u: compare u . p_k with u . p_top.
  int top = 0;
  for (int k = 1; k < 3; ++k)
    if (dot_difference_sign(u, at(c[top]), at(c[k])) > 0) top = k;
  bool at_top[3];
  for (int k = 0; k < 3; ++k) at_top[k] = k == top || dot_difference_sign(u, at(c[top]), at(c[k])) == 0;
  return candidate(t, u, at_top);
}

namespace {

// The corners of a convex polygon (a triangle: m = 3) at its top along u
// (at_top): how many, the first of them, and when two, the edge k (corners
// k, k + 1) they span.  The top of a convex polygon along a direction is a
// corner, an edge or the whole polygon.
struct Top {
  int count = 0, first = -1, edge = -1;
};
Top top_of(const bool* at_top, std::size_t m = 3) {
  Top t;
  for (std::size_t k = 0; k < m; ++k)
    if (at_top[k]) {
      ++t.count;
      if (t.first < 0) t.first = int(k);
    }
  if (t.count == 2) {
    t.edge = 0;
    while (!(at_top[t.edge] && at_top[(std::size_t(t.edge) + 1) % m])) ++t.edge;
  } else if (t.count != 1 && std::size_t(t.count) != m) {
    throw std::logic_error("SurfaceCones: the top of a convex polygon is not a corner, an edge or the polygon");
  }
  return t;
}

}  // namespace

// The same answer as without the memo (a neighbour at `level` is at v's
// height either way); -1 in the memo: not known yet.  Two threads may both
// compute an entry, and store the same value.
bool SurfaceCones::below_all_neighbours(Index v, const RoundedPoint3& u, Index level, signed char* memo,
                                        std::size_t stride) const {
  if (!memo) return below_all_neighbours(v, u, level);
  std::atomic_ref<signed char> known(memo[std::size_t(v) * stride]);
  const signed char k = known.load(std::memory_order_relaxed);
  if (k >= 0) return k != 0;
  const bool below = below_all_neighbours(v, u, level);
  known.store(below ? 1 : 0, std::memory_order_relaxed);
  return below;
}

bool SurfaceCones::candidate(Index t, const RoundedPoint3& u, const bool at_top[3], signed char* memo,
                             std::size_t stride) const {
  const RoundedPoint3 o{origin(), kOriginApprox};
  const auto& c = tri_[t];
  const Top tp = top_of(at_top);
  const int top = tp.first, count = tp.count;
  if (count == 3)  // the triangle itself: its outward normal only
    return dot_sign(o, u, o, RoundedPoint3{normal_[t], normal_approx_[t]}) > 0;
  if (count == 2) {
    // The edge k = (c[k], c[k+1]) at the top.
    const int k = tp.edge;
    const Index a = c[k], b = c[(k + 1) % 3];
    // Inside the edge: a convex edge's normals are the arc between its two
    // faces' normals, u . (far vertex of either face - a) <= 0 (this face's
    // holds, as its far vertex is below the top); a flat or reflex edge has
    // no outward normal at its inner points.
    if (kind_[t][k] < 0 && dot_difference_sign(u, at(a), at(opposite_[t][k])) <= 0) return true;
    return below_all_neighbours(a, u, b, memo, stride) || below_all_neighbours(b, u, a, memo, stride);
  }
  return below_all_neighbours(c[top], u, ~Index(0), memo, stride);
}

bool SurfaceCones::keeps(Index t, const RoundedPoint3& u, const bool at_top[3]) const {
  const auto& c = tri_[t];
  const Top tp = top_of(at_top);
  const int top = tp.first, count = tp.count;
  if (count == 3) return true;
  if (count == 2) {
    const int k = tp.edge;
    const Index other = across_[t][k];
    if (other == kNoTriangle || other > t) return true;
    return dot_difference_sign(u, at(c[k]), at(opposite_[t][k])) >= 0;
  }
  const Index v = c[top];
  for (Index s : incident_[v]) {
    if (s >= t) break;  // ascending
    const auto& d = tri_[s];
    bool below = true;
    for (Index w : d)
      if (w != v && dot_difference_sign(u, at(v), at(w)) >= 0) below = false;
    if (below) return false;
  }
  return true;
}

bool SurfaceCones::polygon_candidate(Index g, const RoundedPoint3& u, const bool* at_top, signed char* memo,
                                     std::size_t stride) const {
  const Polygon& p = polygons_[g];
  const std::size_t m = p.corners.size();
  const Top tp = top_of(at_top, m);
  bool top3[3] = {true, true, true};
  Index t = p.edge_triangle[0];
  if (std::size_t(tp.count) != m) {  // a corner (the start of edge `first`) or edge `edge`: the triangle holding it
    const std::size_t k = std::size_t(tp.count == 2 ? tp.edge : tp.first);
    t = p.edge_triangle[k];
    const int j = p.edge_index[k];
    top3[0] = top3[1] = top3[2] = false;
    top3[j] = true;
    if (tp.count == 2) top3[(j + 1) % 3] = true;
  }
  return candidate(t, u, top3, memo, stride);
}

bool SurfaceCones::polygon_candidate(Index g, const RoundedPoint3& u) const {
  const Polygon& p = polygons_[g];
  const std::size_t m = p.corners.size();
  std::size_t top = 0;
  for (std::size_t k = 1; k < m; ++k)
    if (dot_difference_sign(u, at(p.corners[top]), at(p.corners[k])) > 0) top = k;
  std::unique_ptr<bool[]> at_top(new bool[m]);
  for (std::size_t k = 0; k < m; ++k)
    at_top[k] = k == top || dot_difference_sign(u, at(p.corners[top]), at(p.corners[k])) == 0;
  return polygon_candidate(g, u, at_top.get());
}

bool SurfaceCones::polygon_keeps(Index g, const RoundedPoint3& u, const bool* at_top) const {
  if (!merged_) return keeps(g, u, at_top);
  const Polygon& p = polygons_[g];
  const std::size_t m = p.corners.size();
  const Top tp = top_of(at_top, m);
  if (std::size_t(tp.count) == m) return true;
  if (tp.count == 2) {
    const std::size_t k = std::size_t(tp.edge);
    const Index t = p.edge_triangle[k];
    const int j = p.edge_index[k];
    const Index other = across_[t][j];
    if (other == kNoTriangle || polygon_of_[other] > g) return true;
    // (The polygon across holds the triangle across, whose far vertex is one of its corners off the edge.)
    return dot_difference_sign(u, at(p.corners[k]), at(opposite_[t][j])) >= 0;
  }
  const Index v = p.corners[std::size_t(tp.first)];
  for (Index q : polygons_at_[v]) {
    if (q >= g) break;  // ascending
    const std::vector<Index>& c = polygons_[q].corners;
    const std::size_t n = c.size();
    std::size_t i = 0;
    while (c[i] != v) ++i;
    if (dot_difference_sign(u, at(v), at(c[(i + 1) % n])) < 0 && dot_difference_sign(u, at(v), at(c[(i + n - 1) % n])) < 0)
      return false;
  }
  return true;
}

namespace {

// Exact line/triangle test for the ray from q through q + d: 1 when the
// line crosses the triangle's interior, 0 when it misses the closed
// triangle, -1 when it meets its boundary or lies in its plane (the
// direction is then not generic for this triangle).
template <class P>
int line_meets(const P& q, const P& r, const P& a, const P& b, const P& c) {
  const int o1 = orient3d(q, r, a, b), o2 = orient3d(q, r, b, c), o3 = orient3d(q, r, c, a);
  const bool pos = o1 > 0 || o2 > 0 || o3 > 0, neg = o1 < 0 || o2 < 0 || o3 < 0;
  if (pos && neg) return 0;
  if (o1 == 0 || o2 == 0 || o3 == 0) return -1;
  return 1;
}

}  // namespace

bool strictly_inside(const Point3& q, const std::vector<Point3>& points, const std::vector<std::array<Index, 3>>& tris,
                     const std::vector<Point3>* normals, const std::vector<Vec3d>* approx,
                     const std::vector<std::array<double, 6>>* boxes) {
  const Vec3d q_approx = to_double(q);
  const IPoint q_interval = to_interval(q);
  std::vector<Index> near;
  // Rays in directions with large co-prime integer components, tried in turn
  // until one meets no edge or vertex of the surface and lies in no
  // triangle's plane: each triangle excludes the directions of a few planes
  // through q, so almost every direction is generic.  The first eight are
  // fixed; then directions of a fixed pseudo-random sequence (splitmix64),
  // up to 256 in all.
  static const long kDirections[][3] = {{1000003, 7919, 104729},    {-7927, 1000033, 130363},
                                        {15485863, -2750159, 7},   {-104723, -5381, 1299709},
                                        {611953, 1000037, -49979687}, {3, -32452843, 86028121},
                                        {-982451653, 67867967, 1},  {2038074743, 3, -179424673}};
  std::uint64_t state = 0x6d696e6b73756dULL;
  auto next = [&state] {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return long((z ^ (z >> 31)) >> 33) - (long(1) << 30);  // in [-2^30, 2^30)
  };
  for (int attempt = 0; attempt < 256; ++attempt) {
    long dir[3];
    for (int k = 0; k < 3; ++k) dir[k] = attempt < 8 ? kDirections[attempt][k] : next();
    if (dir[0] == 0 && dir[1] == 0 && dir[2] == 0) continue;
    const Point3 d{Rational(dir[0]), Rational(dir[1]), Rational(dir[2])};
    const Point3 r = q + d;
    const Vec3d r_approx = to_double(r);
    const RoundedPoint3 rq{q, q_approx}, rr{r, r_approx};
    bool inside = false, generic = true;
    // The triangles whose boxes the line may meet: the others it misses
    // (line_meets would answer 0), proved on intervals (kernel/line_box.hpp).
    near.clear();
    if (boxes) {
      const double dd[3] = {double(dir[0]), double(dir[1]), double(dir[2])};  // exact (|dir| < 2^31)
      CGAL::Protect_FPU_rounding<true> upward;
      const FastIPoint qi = to_fast(q_interval);
      for (Index t = 0; t < tris.size(); ++t)
        if (!line_misses_box(qi, dd, &(*boxes)[t][0], &(*boxes)[t][3])) near.push_back(t);
    }
    const std::size_t count = boxes ? near.size() : tris.size();
    for (std::size_t i = 0; i < count && generic; ++i) {
      const std::size_t t = boxes ? near[i] : i;
      const auto& c = tris[t];
      // The orientation tests on the cached roundings when given.
      const int m = approx ? line_meets(rq, rr, RoundedPoint3{points[c[0]], (*approx)[c[0]]},
                                        RoundedPoint3{points[c[1]], (*approx)[c[1]]},
                                        RoundedPoint3{points[c[2]], (*approx)[c[2]]})
                           : line_meets(q, r, points[c[0]], points[c[1]], points[c[2]]);
      if (m < 0) {
        generic = false;
      } else if (m > 0) {
        // The crossing is ahead of q (along d) iff n . (q - a) and n . d
        // have opposite signs.
        const Point3 n = normals ? (*normals)[t] : cross(points[c[1]] - points[c[0]], points[c[2]] - points[c[0]]);
        const int sq = sgn(dot(n, q - points[c[0]]));
        if (sq == 0) throw std::logic_error("strictly_inside: the point is on the surface");
        if (sq * sgn(dot(n, d)) < 0) inside = !inside;
      }
    }
    if (generic) return inside;
  }
  throw std::logic_error("strictly_inside: no generic ray direction");
}

bool SurfaceCones::strictly_inside(const Point3& q) const {
  return nonconvex_detail::strictly_inside(q, points_, tri_, &normal_, &approx_, &box_);
}

}  // namespace minksum::nonconvex_detail
