// ConvexPolytope: validation of polygon meshes, coplanar merging, half-edge
// connectivity.  Every decision is the sign of an exact rational expression.
//
// Why the checks below prove convexity: after merging coplanar facets, the
// builder checks (1) the surface is a closed, connected, consistently oriented
// 2-manifold with V - E + F = 2; (2) every facet is a convex polygon turning
// counter-clockwise exactly once around its outward normal; (3) every edge is
// strictly convex; (4) around every vertex the edge directions, projected
// along an axis inside the would-be tangent cone, turn strictly
// counter-clockwise and wind exactly once, so the surface near the vertex is
// the graph of a piecewise-linear function over a plane, convex across each
// edge by (3).  A compact connected surface that is locally convex everywhere
// bounds a convex body (Hadamard; van Heijenoort), so (1)-(4) are equivalent
// to the mesh being the boundary of a convex polytope.
#include "mesh/builder.hpp"
#include "mesh/weld.hpp"
#include "kernel/big_array.hpp"
#include "kernel/interval.hpp"
#include "kernel/plane.hpp"

#include <minksum/error.hpp>
#include <minksum/parallel.hpp>
#include <minksum/predicates.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>
#include <unordered_map>

namespace minksum {

namespace {

std::string vtx(Index v) { return "vertex " + std::to_string(v); }
// Where a defect of the user's file is: its vertex numbers and coordinates
// (an STL has no vertex numbers of its own; the reader numbers its corners).
std::string vertex_place(Index v, const PointList& named) { return vtx(v) + " at " + format_point(named[v]); }
std::string edge_place(Index u, Index w, const PointList& named) {
  return "edge " + std::to_string(u) + "-" + std::to_string(w) + " from " + format_point(named[u]) + " to " +
         format_point(named[w]);
}
std::string fct(Index f) { return "facet " + std::to_string(f); }

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(Index n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// body(begin, end) over [0, n) in blocks of kValidationBlock items, on
// several threads when `threads` and there are two blocks or more (at least
// two threads, one per hardware thread beyond).  Each block runs with the
// FPU rounding upward, as the caller's loop.  A block stops at its first
// failure; of the failures, parallel_for rethrows the one of the first
// block, so the error is the first in input order, as on one thread.
// Validation (and the rounding certificate, moved) use threads from
// parallel_items() facets on (<minksum/parallel.hpp>: below, a loop is too
// short to gain from a second thread).  On a loaded machine a started
// thread may wait to be scheduled; the jobs are handed out one block at a
// time, so the calling thread then does the blocks itself and only the last
// block may wait.
constexpr std::size_t kValidationBlock = 2048;
template <class Body>
void in_blocks(std::size_t n, bool threads, Body&& body) {
  const std::size_t blocks = (n + kValidationBlock - 1) / kValidationBlock;
  if (!threads || blocks < 2) {
    body(std::size_t(0), n);
    return;
  }
  parallel_for(blocks, std::max(2u, hardware_threads()), [&](std::size_t b) {
    CGAL::Protect_FPU_rounding<true> upward;
    body(b * kValidationBlock, std::min(n, (b + 1) * kValidationBlock));
  });
}

struct Graph {
  std::vector<Index> origin, facet, next, prev, facet_he, vertex_he;
  Index num_halfedges() const { return Index(origin.size()); }
};

// Link polygons (vertex ids 0..nv-1, every id used) into half-edges.
// `vname` / `fname` translate internal ids into the user's numbering.
//
// Edges are matched by sorting, not hashing: the corners (one per polygon
// side, polygons in order) are distributed by a counting sort into one
// bucket per smaller endpoint, each bucket is sorted by the other endpoint,
// and a run of equal endpoints is one edge.  Every pass is sequential but
// the distribution, and the arrays are a few words per corner, so a million
// vertices stay in cache-sized strides.  Edges are numbered in the order of
// their first corner (as they first appear in the polygons), and the first
// error of each kind is the one on the edge that appears first: the
// numbering and the messages do not depend on how edges are matched.
// With `not_sphere`, a surface that is not one topological sphere (an open,
// non-manifold or inconsistently oriented one, several components, or a
// genus) sets it and returns instead of throwing: it bounds no convex
// polytope (a probe's answer).
Graph link(Index nv, const std::vector<std::vector<Index>>& faces, const std::string& source,
           const std::vector<Index>& vname, const std::vector<Index>& fname, const PointList& named,
           bool* not_sphere = nullptr) {
  const Index nf = Index(faces.size());
  // Corners in polygon order: corner c runs from co[c] to co[succ(c)].
  std::vector<Index> face_start = big_array<Index>(std::size_t(nf) + 1);
  std::size_t total = 0;
  for (Index f = 0; f < nf; ++f) {
    face_start[f] = Index(total);
    total += faces[f].size();
  }
  if (total > std::size_t(kNoIndex) / 2)
    throw InputError(source, "", "too many polygon corners (" + std::to_string(total) + ")");
  face_start[nf] = Index(total);
  std::vector<Index> co = big_array<Index>(total);
  for (Index f = 0, c = 0; f < nf; ++f)
    for (Index v : faces[f]) co[c++] = v;
  auto face_of = [&](Index c) {
    return Index(std::upper_bound(face_start.begin(), face_start.end(), c) - face_start.begin() - 1);
  };
  // bucket u (the corners whose smaller endpoint is u) = [bucket[u], bucket[u + 1]).
  std::vector<Index> bucket = big_array<Index>(std::size_t(nv) + 1, 0);
  for (Index f = 0; f < nf; ++f)
    for (Index c = face_start[f], e = face_start[f + 1]; c < e; ++c) {
      const Index u = co[c], v = co[c + 1 == e ? face_start[f] : c + 1];
      ++bucket[std::min(u, v) + 1];
    }
  for (Index u = 0; u < nv; ++u) bucket[u + 1] += bucket[u];
  struct Failure {
    Index first = kNoIndex, u = 0, w = 0, count = 0, c0 = 0, c1 = 0;
    void note(Index f, Index uu, Index ww, Index n, Index a, Index b) {
      if (f < first) *this = {f, uu, ww, n, a, b};
    }
  } non_manifold, same_direction, open;
  const bool threads = nf >= parallel_items();
  struct Failures {
    Failure non_manifold, same_direction, open;
  };
  std::vector<Failures> block_failures((std::size_t(nv) + kValidationBlock - 1) / kValidationBlock);
  // corner_edge[c] = the first corner of c's edge, then the edge's number.
  // Made before `uses`, the largest array here and the first freed, which
  // is then the last block of the heap: its memory goes back to the top,
  // where the graph's arrays are taken from next (the peak is lower by an
  // array than with `uses` freed below other blocks).
  std::vector<Index> corner_edge = big_array<Index>(total);
  struct Use {
    Index other, corner;  // the larger endpoint, the corner
  };
  std::vector<Use> uses = big_array<Use>(total);
  {
    std::vector<Index> fill;
    reserve_big(fill, nv);
    fill.assign(bucket.begin(), bucket.end() - 1);
    for (Index f = 0; f < nf; ++f)
      for (Index c = face_start[f], e = face_start[f + 1]; c < e; ++c) {
        const Index u = co[c], v = co[c + 1 == e ? face_start[f] : c + 1];
        uses[fill[std::min(u, v)]++] = {std::max(u, v), c};
      }
  }
  // Each bucket sorted by (other, corner): a bucket holds about twice a
  // vertex's degree, so insertion sort (stable: corners stay increasing).
  // Buckets in blocks of vertices (on threads for large meshes); each block
  // keeps its own first failures (block_failures, made with the other
  // arrays above), merged after: the one on the edge that appears first, as
  // on one thread.
  in_blocks(nv, threads, [&](std::size_t ubegin, std::size_t uend) {
    Failures& fail = block_failures[ubegin / kValidationBlock];
    for (Index u = Index(ubegin); u < uend; ++u) {
      Use* b = uses.data() + bucket[u];
      Use* e = uses.data() + bucket[u + 1];
      for (Use* i = b + 1; i < e; ++i) {
        const Use x = *i;
        Use* j = i;
        for (; j > b && j[-1].other > x.other; --j) *j = j[-1];
        *j = x;
      }
      for (Use* i = b; i < e;) {
        Use* j = i + 1;
        while (j < e && j->other == i->other) ++j;
        const Index count = Index(j - i), first = i->corner;
        for (Use* k = i; k < j; ++k) corner_edge[k->corner] = first;
        if (count > 2) fail.non_manifold.note(first, u, i->other, count, first, i[1].corner);
        else if (count == 2 && co[first] == co[i[1].corner])
          fail.same_direction.note(first, u, i->other, count, first, i[1].corner);
        else if (count == 1) fail.open.note(first, u, i->other, count, first, first);
        i = j;
      }
    }
  });
  for (const Failures& b : block_failures) {
    const Failure& x = b.non_manifold;
    non_manifold.note(x.first, x.u, x.w, x.count, x.c0, x.c1);
    const Failure& y = b.same_direction;
    same_direction.note(y.first, y.u, y.w, y.count, y.c0, y.c1);
    const Failure& z = b.open;
    open.note(z.first, z.u, z.w, z.count, z.c0, z.c1);
  }
  auto edge_name = [&](const Failure& x) { return edge_place(vname[x.u], vname[x.w], named); };
  if (not_sphere && (non_manifold.first != kNoIndex || same_direction.first != kNoIndex || open.first != kNoIndex)) {
    *not_sphere = true;  // a probe: no closed 2-manifold, no convex polytope
    return Graph{};
  }
  if (non_manifold.first != kNoIndex)
    throw InputError(source, edge_name(non_manifold),
                     "non-manifold edge shared by " + std::to_string(non_manifold.count) + " facets");
  if (same_direction.first != kNoIndex)
    throw InputError(source, edge_name(same_direction),
                     "inconsistent orientation: " + fct(fname[face_of(same_direction.c0)]) + " and " +
                         fct(fname[face_of(same_direction.c1)]) + " traverse this edge in the same direction");
  if (open.first != kNoIndex)
    throw InputError(source, edge_name(open), "open mesh: the edge belongs to " + fct(fname[face_of(open.c0)]) + " only");
  // Number the edges in the order of their first corners.
  Index num_edges = 0;
  for (Index c = 0; c < total; ++c) {
    const Index first = corner_edge[c];
    corner_edge[c] = first == c ? num_edges++ : corner_edge[first];
  }
  release(uses);

  Graph g;
  Index nh = Index(num_edges * 2);
  g.origin = big_array(nh, kNoIndex);
  g.facet = big_array(nh, kNoIndex);
  g.next = big_array(nh, kNoIndex);
  g.prev = big_array(nh, kNoIndex);
  g.facet_he = big_array(nf, kNoIndex);
  g.vertex_he = big_array(nv, kNoIndex);
  // The half-edges of each facet (in blocks of facets: each half-edge
  // belongs to one corner), then each vertex's first outgoing half-edge in
  // facet order.
  in_blocks(nf, threads, [&](std::size_t fbegin, std::size_t fend) {
    for (Index f = Index(fbegin); f < fend; ++f) {
      const Index c0 = face_start[f], ce = face_start[f + 1];
      auto half = [&](Index c) {
        const Index u = co[c], v = co[c + 1 == ce ? c0 : c + 1];
        return 2 * corner_edge[c] + (u < v ? 0u : 1u);
      };
      const Index h0 = half(c0);
      Index h = h0;
      for (Index c = c0; c < ce; ++c) {
        const Index hn = c + 1 == ce ? h0 : half(c + 1);
        g.origin[h] = co[c];
        g.facet[h] = f;
        g.next[h] = hn;
        g.prev[hn] = h;
        h = hn;
      }
      g.facet_he[f] = h0;
    }
  });
  for (Index f = 0; f < nf; ++f)
    for (Index h = g.facet_he[f], h0 = h;;) {
      if (g.vertex_he[g.origin[h]] == kNoIndex) g.vertex_he[g.origin[h]] = h;
      if ((h = g.next[h]) == h0) break;
    }
  // Vertex manifoldness: the facets around each vertex form a single fan.
  std::vector<Index> outdeg = big_array<Index>(nv, 0);
  for (Index h = 0; h < nh; ++h) ++outdeg[g.origin[h]];
  std::atomic<bool> fans{true};
  in_blocks(nv, threads, [&](std::size_t vbegin, std::size_t vend) {
    for (Index v = Index(vbegin); v < vend; ++v) {
      Index h = g.vertex_he[v], steps = 0;
      do {
        h = g.prev[h] ^ 1u;
        ++steps;
      } while (h != g.vertex_he[v] && steps <= outdeg[v]);
      if (steps != outdeg[v]) {
        if (not_sphere) {
          fans = false;
          return;
        }
        throw InputError(source, vertex_place(vname[v], named), "non-manifold vertex: its facets form more than one fan");
      }
    }
  });
  if (!fans) {
    *not_sphere = true;
    return g;
  }
  // Connected, sphere topology.  Every vertex now has one fan, so two
  //    facets are connected across edges exactly when their vertices are
  //    connected along edges (a path of edges passes from fan to fan), and
  //    the facets connected to facet 0 are found by a union-find of the
  //    vertices over the edges, in edge order, not by a search over facets.
  {
    UnionFind uf(nv);
    for (Index h = 0; h < nh; h += 2) uf.unite(g.origin[h], g.origin[h + 1]);
    const Index root = uf.find(co[0]);
    for (Index f = 1; f < nf; ++f)
      if (uf.find(co[face_start[f]]) != root) {
        if (not_sphere) {
          *not_sphere = true;
          return g;
        }
        throw InputError(source, fct(fname[f]),
                         "the mesh has more than one connected component (this facet is not connected to " +
                             fct(fname[0]) + ")");
      }
  }
  long chi = long(nv) - long(num_edges) + long(faces.size());
  if (chi != 2 && not_sphere) {
    *not_sphere = true;
    return g;
  }
  if (chi != 2)
    throw InputError(source, "",
                     "the surface is not a topological sphere (V - E + F = " + std::to_string(chi) +
                         ", genus " + std::to_string((2 - chi) / 2) + ")");
  return g;
}

// Newell normal (twice the vector area) of a polygon: sum (p_i - p_0) x (p_{i+1} - p_0).
Point3 polygon_normal(const PointList& pts, const std::vector<Index>& poly) {
  Point3 n(Rational(0), Rational(0), Rational(0));
  const Point3 o = pts.exact(poly[0]);
  Point3 prev = pts.exact(poly[1]) - o;
  for (std::size_t i = 2; i < poly.size(); ++i) {
    Point3 cur = pts.exact(poly[i]) - o;
    Point3 c = cross(prev, cur);
    n.x += c.x;
    n.y += c.y;
    n.z += c.z;
    prev = std::move(cur);
  }
  return n;
}


}  // namespace

namespace {

// The vertex of triangle `tri` that is neither a nor b.
Index third_vertex(const std::vector<Index>& tri, Index a, Index b) {
  for (Index v : tri)
    if (v != a && v != b) return v;
  return tri[0];
}

// For two triangles sharing the edge p-q, f = (p, q, c) and o = (q, p, d) in
// either order around their outward normals: orient3d(p, q, c, d), decided by
// the kernel's filtered predicate on the double coordinates (exact when the
// filter cannot decide), without the facets' exact normals.  It is 0 exactly
// when the triangles are coplanar, and sign <n_f x n_o, q - p> =
// -orient3d(p, q, c, d) (n_o = -(q - p) x (d - p) up to a positive factor, and
// <n_f, q - p> = 0), so the edge is convex exactly when it is negative.
// Only for lists of doubles: nullopt otherwise.
std::optional<int> triangle_pair_orient(const PointList& pts, const std::vector<Index>& f,
                                        const std::vector<Index>& o, Index p, Index q) {
  if (pts.form() != PointList::Form::doubles || f.size() != 3 || o.size() != 3) return std::nullopt;
  return orient3d(pts.approx(p), pts.approx(q), pts.approx(third_vertex(f, p, q)), pts.approx(third_vertex(o, p, q)));
}

}  // namespace

int sign_det(const Point3& a, const Point3& b, const Point3& c) { return sgn(dot(a, cross(b, c))); }

namespace {
inline int sign_any(const Rational& q) { return sgn(q); }
inline int sign_any(const Interval& i) { return sign_of(i); }
inline int sign_any(const FastInterval& i) { return sign_of(i); }

// check_fan on exact points (never uncertain) or on intervals (returns
// kFanUncertain when an interval sign cannot be decided).
constexpr long kFanUncertain = -2;
//
// `turn_normals`, when given, holds for each step i a vector that is a
// positive multiple of d[i] x d[i+1] (around a vertex whose facets are
// strictly convex: the outward normal of the facet between the two edges),
// which saves computing the cross products.
template <class V>
long check_fan_t(const V& a, const std::vector<V>& d, const std::vector<V>* turn_normals = nullptr) {
  const std::size_t k = d.size();
  for (std::size_t i = 0; i < k; ++i) {
    int s = sign_any(turn_normals ? dot(a, (*turn_normals)[i]) : dot(a, cross(d[i], d[(i + 1) % k])));
    if (s == kUncertain) return kFanUncertain;
    if (s <= 0) return long(i);
  }
  // The winding number, counted by a reference ray R, seen along a.
  // Regions relative to R: Z same direction as R, P counter-clockwise
  // within (0, pi), O opposite, N within (pi, 2pi).  Each step turns by an
  // angle in (0, pi); it passes (or lands on) R exactly when it goes from N
  // into Z or P (from O or P it cannot reach R in less than pi, and it
  // enters Z only from N), so the winding number is the number of such
  // steps, cyclically.  Two rays serve: R = d[0] (d[0] in Z), and
  // R = d[0] + d[1], strictly between d[0] and d[1] (the turn from one to
  // the other is in (0, pi), just checked; d[0] in N, d[1] in P).  On
  // intervals the first cannot decide a side exactly opposite to d[0] (a
  // parallelogram's, and a Minkowski sum has many): a zero; the second
  // cannot decide a direction along d[0] + d[1], which a vertex's fan of a
  // symmetric sum can have.  Each is tried while the other cannot decide.
  enum Region { Z, P, O, N, U };
  auto winding = [&](const V& R, bool between) -> long {
    const V ra = cross(a, R);  // det(a, R, x) = <a x R, x>
    const auto aa = dot(a, a);
    const auto Ra = dot(R, a);
    auto region = [&](const V& x) {
      int c = sign_any(dot(ra, x));
      if (c == kUncertain) return U;
      if (c > 0) return P;
      if (c < 0) return N;
      // Collinear with R in projection: same or opposite direction.
      int s = sign_any(dot(x, R) * aa - dot(x, a) * Ra);
      if (s == kUncertain) return U;
      return s > 0 ? Z : O;
    };
    const Region first = between ? N : Z;
    long w = between ? 1 : 0;  // the step from d[0] to d[1] when R is between them
    Region prev = between ? P : first;
    for (std::size_t j = between ? 2 : 1; j <= k; ++j) {
      const Region r = j == k ? first : region(d[j]);  // back to d[0]
      if (r == U) return kFanUncertain;
      if (prev == N && (r == Z || r == P)) ++w;
      prev = r;
    }
    return w;
  };
  long w = winding(d[0], false);
  if (w == kFanUncertain) w = winding(d[0] + d[1], true);
  if (w == kFanUncertain) return kFanUncertain;
  return w == 1 ? -1 : long(k);
}
}  // namespace

long check_fan(const Point3& a, const std::vector<Point3>& d) { return check_fan_t(a, d); }

namespace {
std::atomic<std::uint64_t> g_exact_fan_tests{0};
}  // namespace

std::uint64_t exact_fan_tests() { return g_exact_fan_tests.load(std::memory_order_relaxed); }

namespace {

struct FanScratch {
  std::vector<Point3> dirs;
  std::vector<FastIPoint> idirs, inormals;
};

// Step 8's facet test: the polygon `poly` (intervals `ip` of the points
// `pts`) turns strictly counter-clockwise about its normal, whose interval
// is `n`, and winds once.  `exact_normal()` gives the exact normal when the
// intervals cannot decide.
template <class IPoints, class ExactNormal>
bool convex_polygon(const std::vector<Index>& poly, const IPoints& ip, const PointList& pts,
                    const FastIPoint& n, ExactNormal&& exact_normal, FanScratch& s) {
  const std::size_t k = poly.size();
  s.idirs.clear();
  for (std::size_t i = 0; i < k; ++i) s.idirs.push_back(ip[poly[(i + 1) % k]] - ip[poly[i]]);
  long r = check_fan_t(n, s.idirs);
  if (r == kFanUncertain) {
    g_exact_fan_tests.fetch_add(1, std::memory_order_relaxed);
    s.dirs.clear();
    for (std::size_t i = 0; i < k; ++i) s.dirs.push_back(pts.exact(poly[(i + 1) % k]) - pts.exact(poly[i]));
    r = check_fan_t(exact_normal(), s.dirs);
  }
  return r < 0;
}

// Step 8's vertex test: around v (outgoing half-edge `start`; half-edge
// arrays origin, prev, facet with twin(h) = h ^ 1), the edge directions,
// seen along the axis minus their sum, turn strictly counter-clockwise and
// wind once.  The facet between consecutive edges d_i, d_(i+1) (the facet
// of the outgoing half-edge h_i) has its outward normal along
// d_i x d_(i+1) once every facet is a strictly convex polygon, so the
// intervals of the facets' normals `facet_normal` serve for the turns.
//    `ip[i]` and `facet_normal[f]` give intervals (vectors, or the views
// below that make them on demand).
template <class IPoints, class INormals>
bool convex_vertex(Index v, Index start, const Index* origin, const Index* prev, const Index* facet,
                   const IPoints& ip, const INormals& facet_normal, const PointList& pts, FanScratch& s) {
  s.idirs.clear();
  s.inormals.clear();
  FastIPoint isum{FastInterval(0), FastInterval(0), FastInterval(0)};
  Index h = start;
  do {
    s.idirs.push_back(ip[origin[h ^ 1u]] - ip[v]);
    s.inormals.push_back(facet_normal[facet[h]]);
    isum = isum + s.idirs.back();
    h = prev[h] ^ 1u;
  } while (h != start);
  long r = check_fan_t(-isum, s.idirs, &s.inormals);
  if (r == kFanUncertain) {
    g_exact_fan_tests.fetch_add(1, std::memory_order_relaxed);
    s.dirs.clear();
    Point3 sum(Rational(0), Rational(0), Rational(0));
    const Point3 pv = pts.exact(v);
    do {
      s.dirs.push_back(pts.exact(origin[h ^ 1u]) - pv);
      sum = sum + s.dirs.back();
      h = prev[h] ^ 1u;
    } while (h != start);
    r = is_zero(sum) ? 0 : check_fan_t(-sum, s.dirs);
  }
  return r < 0;
}

// Point intervals of a list of doubles, made on demand (exact: no rounding).
struct DoubleIntervals {
  const std::vector<Vec3d>* v;
  FastIPoint operator[](Index i) const {
    const Vec3d& a = (*v)[i];
    return {FastInterval(a.x), FastInterval(a.y), FastInterval(a.z)};
  }
};

// Interval normals of triangles, made on demand: (b - a) x (c - a) for the
// corners a, b, c of facet f from its half-edge facet_he[f] on, as step 4
// makes them.  Needs the rounding upward.
template <class IPoints>
struct TriangleNormals {
  const IPoints* ip;
  const Index *origin, *next, *facet_he;
  FastIPoint operator[](Index f) const {
    const Index h0 = facet_he[f], h1 = next[h0], h2 = next[h1];
    const FastIPoint a = (*ip)[origin[h0]];
    return cross((*ip)[origin[h1]] - a, (*ip)[origin[h2]] - a);
  }
};

// A first vertex test on doubles, enough to accept most vertices of a
// double mesh without intervals.  It holds for any axis a (once every facet
// is a strictly convex polygon and every edge strictly convex: projected
// along a, the facets around v are wedges of angle below pi; turning
// strictly counter-clockwise and winding once, they cover a neighbourhood
// of v's projection once, so the surface near v is a graph over the plane
// orthogonal to a).  Here a = v - c for a double point c (reference_point,
// whose rounding is irrelevant: any c gives some axis): then
// det(a, d_i, d_j) = -orient3d(v, u_i, u_j, c), the kernel's filtered
// orient3d, with u_i the neighbours of v counter-clockwise (outgoing
// half-edges from `start`, next one twin(prev(h))).  True when the test
// accepts v; false leaves v to step 8's test (axis minus the sum of the
// edge directions, on intervals, exact when they cannot decide), which
// decides: a sign zero or a failed test here proves nothing.
// Signs already known of some wedges: for a triangle f, below[f] is 1 when
// c lies strictly below it, 0 when not (the wedge test fails), -1 for a
// polygon (its wedge is computed); facet[h] is the facet of half-edge h.
struct WedgeSigns {
  const signed char* below;
  const Index* facet;
};

bool convex_vertex_on_doubles(Index i, Index start, const Index* origin, const Index* prev,
                              const std::vector<Vec3d>& v, const Vec3d& c, std::vector<Index>& around,
                              const WedgeSigns* known = nullptr) {
  around.clear();
  Index h = start;
  do {
    around.push_back(origin[h ^ 1u]);
    if (known) {
      const signed char b = known->below[known->facet[h]];
      if (b == 0) return false;
      around.push_back(b < 0);  // the wedge's sign still to compute
    } else {
      around.push_back(1);
    }
    h = prev[h] ^ 1u;
  } while (h != start);
  const std::size_t k = around.size() / 2;
  auto u = [&](std::size_t j) { return v[around[2 * j]]; };
  for (std::size_t j = 0; j < k; ++j)
    if (around[2 * j + 1] && orient3d(v[i], u(j), u(j + 1 == k ? 0 : j + 1), c) >= 0) return false;
  // Winding: the side of d_j of the reference ray d_0 (within (0, pi)
  // counter-clockwise, or within (pi, 2 pi)); each step turns by less than
  // pi, so it passes the ray exactly when it goes from the second side
  // back to the first, or to d_0 itself at the end.  The sides of d_1
  // (first side) and d_k-1 (second side) are those of the first and the
  // last wedge, known once every wedge has passed.  With k <= 4 wedges of
  // less than pi each, the total turn, a positive multiple of 2 pi, is below
  // 4 pi: the fan winds once.
  if (k <= 4) return true;
  long winding = 0;
  bool prev_second = false;
  for (std::size_t j = 1; j < k; ++j) {
    const int side = j == 1 ? 1 : j + 1 == k ? -1 : -orient3d(v[i], u(0), u(j), c);
    if (side == 0) return false;  // along the ray or against it
    if (prev_second && side > 0) ++winding;
    prev_second = side < 0;
  }
  winding += prev_second;
  return winding == 1;
}


// The reference point c of convex_vertex_on_doubles, in doubles (any
// rounding), or nullopt when it is not finite: the mean m of the points
// moved a little towards three of them,
//     c = m + w1 (p_i1 − m) + w2 (p_i2 − m) + w3 (p_i3 − m),
// w = 0.0371, 0.0527, 0.0613 (not dyadic, nor simple fractions), a convex
// combination of m and the three points with weight 0.85 on m, so inside the
// solid as m is.  Its only role is speed: any c gives a valid test (see
// above), but the mean itself of a symmetric solid (a sphere, a Minkowski
// sum of symmetric operands) lies on its mirror planes, and so does every
// triple (v, u_0, u_j) of a fan on such a plane: those orient3d calls are
// then nearly or exactly zero, beyond the filter, and go to exact
// arithmetic (1 669 of them when validating the 10 242-vertex geodesic
// sphere of `minksum gen sphere:6`).  A c off those planes gives signs the
// filter decides.
std::optional<Vec3d> reference_point(const std::vector<Vec3d>& v) {
  const std::size_t n = v.size();
  if (n == 0) return std::nullopt;
  const double dn = double(n);
  Vec3d m{0, 0, 0};
  for (const Vec3d& p : v) m = Vec3d{m.x + p.x / dn, m.y + p.y / dn, m.z + p.z / dn};
  Vec3d c = m;
  const double w[3] = {0.0371, 0.0527, 0.0613};
  for (int k = 0; k < 3; ++k) {
    const Vec3d& p = v[(std::size_t(2 * k + 1) * n) / 7];
    c = Vec3d{c.x + w[k] * (p.x - m.x), c.y + w[k] * (p.y - m.y), c.z + w[k] * (p.z - m.z)};
  }
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) return std::nullopt;
  return c;
}

// The state of one validation, PolytopeBuilder::build, stage by stage (the
// numbers are the steps named in the comments): check_indices (1), weld (2),
// link (3), check_facets (4), orientation (5), merge_coplanar (6),
// drop_vertices (7), check_convexity (8); build makes the polytope (9).
// Each stage reads what the earlier ones left in the state.  From
// check_facets on, the caller keeps the FPU rounding upward (the interval
// operations are unprotected).
struct Validation {
  const Mesh& mesh;
  const std::string& source;

  // weld: the points used, welded, numbered in input order; the user's
  // numbers of the vertices (vname) and facets (fname).  same_faces: the
  // facets are the caller's mesh.faces as they are (faces_own stays empty).
  PointList pts;
  std::vector<Index> vname, fname;
  bool same_faces = false;
  std::vector<std::vector<Index>> faces_own;
  const std::vector<std::vector<Index>>& faces() const { return same_faces ? mesh.faces : faces_own; }

  // link
  Graph g;

  // check_facets: point and normal intervals, exact normals where a filter
  // could not decide, six times the volume as an interval.
  Index nf = 0;
  bool threads = false, triangles_on_doubles = false;
  std::vector<FastIPoint> ip;    // (triangles on doubles: made by fill_ip when needed)
  std::vector<FastIPoint> inrm;  // (triangles on doubles: made by fill_inrm when needed)
  DoubleIntervals dip{nullptr};
  std::vector<std::unique_ptr<Point3>> xnrm;
  FastInterval six{0};

  // merge_coplanar: the merged facets (empty when none merged: they are
  // faces()), the user's number and the representative input facet of each.
  bool any_merge = false;
  std::vector<FastIPoint> edge_cross;
  std::vector<signed char> edge_orient;
  std::vector<std::vector<Index>> merged;
  std::vector<Index> merged_name, merged_rep;

  // drop_vertices: unchanged (the usual case for a valid mesh) keeps the
  // structure linked above; otherwise the final one is the *_own below.
  bool unchanged = false;
  PointList fpts_own;
  std::vector<FastIPoint> fip_own, finrm_own;
  std::vector<Index> fname_v_own;
  Graph fg_own;
  const PointList& fpts() const { return unchanged ? pts : fpts_own; }
  const std::vector<FastIPoint>& fip() const { return unchanged ? ip : fip_own; }
  std::vector<Index>& fname_v() { return unchanged ? vname : fname_v_own; }
  Graph& fg() { return unchanged ? g : fg_own; }
  const std::vector<std::vector<Index>>& final_faces() const { return unchanged ? faces() : merged; }
  const std::vector<FastIPoint>& finrm() const { return unchanged ? inrm : finrm_own; }  // (unchanged: merged_rep[f] == f)
  const Point3& fnormal(Index f) { return exact_normal(merged_rep[f]); }

  Validation(const Mesh& m, const std::string& s) : mesh(m), source(s) {}

  // A probe (PolytopeBuilder::build_if_convex): link_faces records a
  // surface that is not one topological sphere, merge_coplanar coplanar
  // facets that are not one convex polygon, check_convexity a non-convex
  // edge, vertex or polygon, in not_convex instead of throwing.
  bool probe = false;
  bool not_convex = false;


  void check_indices();
  void weld();
  void link_faces() {
    g = link(Index(pts.size()), faces(), source, vname, fname, mesh.points, probe ? &not_convex : nullptr);
  }
  void prepare_intervals();
  void check_facets();
  int volume_sign();
  void reverse_own_facets();
  void merge_coplanar();
  void drop_vertices();
  void check_convexity();

  void fill_ip();
  void fill_inrm();
  // Exact normals, made only where a filter cannot decide (a default Point3
  // would cost three GMP rationals per facet).
  const Point3& exact_normal(Index f) {
    if (!xnrm[f]) xnrm[f] = std::make_unique<Point3>(polygon_normal(pts, faces()[f]));
    return *xnrm[f];
  }
  // The interval Newell normal of facet f: sum (p_i - p_0) x (p_(i+1) - p_0).
  template <class IPoints>
  FastIPoint newell(const IPoints& ipa, Index f) const {
    const auto& poly = faces()[f];
    FastIPoint n{FastInterval(0), FastInterval(0), FastInterval(0)};
    const FastIPoint o = ipa[poly[0]];
    FastIPoint prev = ipa[poly[1]] - o;
    for (std::size_t i = 2; i < poly.size(); ++i) {
      FastIPoint cur = ipa[poly[i]] - o;
      n = n + cross(prev, cur);
      prev = cur;
    }
    return n;
  }
  bool planar_on_doubles(const std::vector<Index>& poly) const;
  template <class IPoints>
  void facets_pass(const IPoints& ipa);
};

// 1. Index range, facet sizes.
void Validation::check_indices() {
  const Index n_in = Index(mesh.points.size());
  if (n_in == 0) throw InputError(source, "", "no vertices");
  if (mesh.faces.empty())
    throw InputError(source, "",
                     "no facets, only " + std::to_string(n_in) +
                         " points (use --hull to take the convex hull of a point cloud)");
  for (Index f = 0; f < mesh.faces.size(); ++f) {
    const auto& poly = mesh.faces[f];
    if (poly.size() < 3)
      throw InputError(source, fct(f), "has " + std::to_string(poly.size()) + " vertices (needs at least 3)");
    for (Index v : poly)
      if (v >= n_in)
        throw InputError(source, fct(f),
                         "refers to vertex " + std::to_string(v) + " but there are only " +
                             std::to_string(n_in) + " vertices");
  }
}

// 2. Weld exactly equal points (weld_exact); number the used vertices in
//    input order.
void Validation::weld() {
  const Index n_in = Index(mesh.points.size());
  std::vector<Index> canon;
  {
    std::vector<char> used = big_array<char>(n_in, 0);
    for (const auto& poly : mesh.faces)
      for (Index v : poly) used[v] = 1;
    canon = weld_exact(mesh.points, &used);
  }
  std::vector<Index> new_id = big_array(n_in, kNoIndex);
  if (mesh.points.form() == PointList::Form::doubles &&
      std::all_of(canon.begin(), canon.end(), [v = Index(0)](Index c) mutable { return c == v++; })) {
    // Every point used, none welded: the list as it is.
    pts = mesh.points;
    std::iota(new_id.begin(), new_id.end(), 0);
    reserve_big(vname, n_in);
    vname.resize(n_in);
    std::iota(vname.begin(), vname.end(), 0);
  } else {
    for (Index v = 0; v < n_in; ++v)
      if (canon[v] == v) {
        new_id[v] = Index(pts.size());
        pts.push_from(mesh.points, v);
        vname.push_back(v);
      }
  }
  // After welding, a facet may repeat a vertex consecutively (a zero-length
  // edge): the repeat is dropped; a facet left with fewer than 3 distinct
  // corners (a collapsed sliver, common in exported STL) is dropped whole.
  //    The usual valid input (every point used, none welded, no facet
  //    visiting a vertex twice) keeps its facets as they are: no copy.
  same_faces = pts.size() == n_in;  // then new_id[canon[v]] == v for every v
  for (std::size_t f = 0; same_faces && f < mesh.faces.size(); ++f) {
    const auto& poly = mesh.faces[f];
    if (poly.size() > 16) same_faces = false;
    for (std::size_t i = 0; same_faces && i < poly.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (poly[j] == poly[i]) same_faces = false;
  }
  fname.reserve(mesh.faces.size());
  if (same_faces)
    for (Index f = 0; f < mesh.faces.size(); ++f) fname.push_back(f);
  else
    faces_own.reserve(mesh.faces.size());
  for (Index f = 0; !same_faces && f < mesh.faces.size(); ++f) {
    std::vector<Index> poly;
    poly.reserve(mesh.faces[f].size());
    for (Index v : mesh.faces[f]) {
      Index w = new_id[canon[v]];
      if (poly.empty() || poly.back() != w) poly.push_back(w);
    }
    while (poly.size() > 1 && poly.back() == poly.front()) poly.pop_back();
    std::size_t distinct;
    if (poly.size() <= 16) {
      distinct = 0;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        bool repeat = false;
        for (std::size_t j = 0; j < i && !repeat; ++j) repeat = poly[j] == poly[i];
        distinct += !repeat;
      }
    } else {
      std::vector<Index> sorted = poly;
      std::sort(sorted.begin(), sorted.end());
      distinct = std::size_t(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
    }
    if (distinct < 3) continue;
    if (distinct != poly.size()) {
      std::vector<Index> seen;
      for (Index v : poly) {
        if (std::find(seen.begin(), seen.end(), v) != seen.end())
          throw InputError(source, fct(f), "visits " + vtx(vname[v]) + " twice");
        seen.push_back(v);
      }
    }
    faces_own.push_back(std::move(poly));
    fname.push_back(f);
  }
  if (faces().empty()) throw InputError(source, "", "every facet collapses to a segment or a point");
  if (faces().size() != mesh.faces.size()) {
    // Dropped facets may leave vertices unused: number the used ones again.
    std::vector<Index> renum(pts.size(), kNoIndex);
    for (const auto& poly : faces())
      for (Index v : poly) renum[v] = 0;
    PointList kept_pts;
    std::vector<Index> kept_names;
    for (Index v = 0; v < pts.size(); ++v)
      if (renum[v] == 0) {
        renum[v] = Index(kept_pts.size());
        kept_pts.push_from(pts, v);
        kept_names.push_back(vname[v]);
      }
    for (auto& poly : faces_own)  // (same_faces keeps every facet)
      for (Index& v : poly) v = renum[v];
    pts = std::move(kept_pts);
    vname = std::move(kept_names);
  }
}

// 3. Topology: closed, manifold, consistently oriented, connected sphere
//    (link_faces).

// 4. Nonzero area, planar facets (exactly).  Signs are filtered with
//    interval arithmetic; exact Newell normals are computed only when a
//    filter cannot decide (and for the final planes).
//    Intervals of the exact coordinates: point intervals for doubles,
//    hi + lo (rounded outward under the guard) for double pairs, the
//    enclosing doubles of each rational.
//    Triangles on doubles (what most large files are) need no stored
//    intervals: a triangle is planar, the convexity of its edges and its
//    coplanarity with a neighbour are one orient3d each (the kernel's
//    filtered predicate), and the intervals of points and normals that a
//    fallback needs are made on demand (DoubleIntervals,
//    TriangleNormals).  Every decision is the same as on stored intervals.
// prepare_intervals runs before the rounding is set upward (to_interval
// uses protected intervals), the other stages after.
void Validation::prepare_intervals() {
  nf = Index(faces().size());
  threads = nf >= parallel_items();
  triangles_on_doubles =
      pts.form() == PointList::Form::doubles &&
      std::all_of(faces().begin(), faces().end(), [](const std::vector<Index>& poly) { return poly.size() == 3; });
  if (pts.form() == PointList::Form::rationals) {
    ip.resize(pts.size());
    for (Index v = 0; v < pts.size(); ++v) ip[v] = to_fast(to_interval(pts.exact_ref(v)));
  }
  dip = DoubleIntervals{&pts.approx()};
  xnrm.resize(nf);
}

void Validation::fill_ip() {
  if (!ip.empty()) return;
  ip.resize(pts.size());
  for (Index v = 0; v < pts.size(); ++v) {
    const Vec3d& a = pts.approx(v);
    if (pts.form() == PointList::Form::doubles) {
      ip[v] = {FastInterval(a.x), FastInterval(a.y), FastInterval(a.z)};
    } else {
      const Vec3d& l = pts.low(v);
      ip[v] = {FastInterval(a.x) + FastInterval(l.x), FastInterval(a.y) + FastInterval(l.y),
               FastInterval(a.z) + FastInterval(l.z)};
    }
  }
}

void Validation::fill_inrm() {
  if (!inrm.empty()) return;
  fill_ip();
  inrm.resize(nf);
  for (Index f = 0; f < nf; ++f) inrm[f] = newell(ip, f);
}

// An exactly planar polygon (a parallelogram of a Minkowski sum, written
// rounded) leaves every vertex's sign in check_facets at an exact zero that
// intervals cannot decide.  On doubles one decision covers the polygon:
// when its first three corners are not collinear and every other corner
// lies on their plane (the kernel's orient3d, exact), all its points are
// coplanar, the Newell normal is normal to that plane, and every sign is
// 0.  When that is not shown, each vertex is decided exactly as before
// (and the error names the same vertex).
bool Validation::planar_on_doubles(const std::vector<Index>& poly) const {
  if (pts.form() != PointList::Form::doubles) return false;
  const FastIPoint e = cross(dip[poly[1]] - dip[poly[0]], dip[poly[2]] - dip[poly[0]]);
  auto nonzero = [](const FastInterval& c) { const int s = sign_of(c); return s == 1 || s == -1; };
  if (!nonzero(e.x) && !nonzero(e.y) && !nonzero(e.z)) return false;
  const std::vector<Vec3d>& v = pts.approx();
  for (std::size_t i = 3; i < poly.size(); ++i)
    if (orient3d(v[poly[0]], v[poly[1]], v[poly[2]], v[poly[i]]) != 0) return false;
  return true;
}

// Six times the volume, for step 5: sum over the facets of <p_0(f) - p_0, n(f)>,
// summed per block of facets, then the blocks in order (the same interval
// on any number of threads).
template <class IPoints>
void Validation::facets_pass(const IPoints& ipa) {
  std::vector<FastInterval> six_part((nf + kValidationBlock - 1) / kValidationBlock, FastInterval(0));
  if (!triangles_on_doubles) inrm.resize(nf);
  const FastIPoint origin = ipa[0];
  const auto& faces = this->faces();
  in_blocks(nf, threads, [&](std::size_t begin, std::size_t end) {
    FastInterval six(0);
    for (Index f = Index(begin); f < end; ++f) {
      const auto& poly = faces[f];
      const FastIPoint n = newell(ipa, f);
      if (!triangles_on_doubles) inrm[f] = n;
      auto certainly_nonzero = [](const FastInterval& c) { int s = sign_of(c); return s == 1 || s == -1; };
      if (!certainly_nonzero(n.x) && !certainly_nonzero(n.y) && !certainly_nonzero(n.z) &&
          is_zero(exact_normal(f)))
        throw InputError(source, fct(fname[f]), "has zero area");
      const FastIPoint o = ipa[poly[0]];
      if (poly.size() > 3) {
        int planar = 0;  // 1: exactly planar (planar_on_doubles), -1: not shown, 0: not asked yet
        for (Index v : poly) {
          int s = sign_of(dot(n, ipa[v] - o));
          if (s == kUncertain && planar == 0) planar = planar_on_doubles(poly) ? 1 : -1;
          if (s == kUncertain) s = planar == 1 ? 0 : sgn(dot(exact_normal(f), pts.exact(v) - pts.exact(poly[0])));
          if (s != 0)
            throw NotConvexError(source, fct(fname[f]),
                                 "is not planar (" + vtx(vname[v]) + " is off the plane of the others)");
        }
      }
      six += dot(o - origin, n);
    }
    six_part[begin / kValidationBlock] = six;
  });
  for (const FastInterval& part : six_part) this->six += part;
}

void Validation::check_facets() {
  if (!triangles_on_doubles) fill_ip();
  if (triangles_on_doubles) facets_pass(dip);
  else facets_pass(ip);
}

// 5. Orientation from the sign of the volume (the caller flips a
//    consistently inward mesh).
int Validation::volume_sign() {
  int vol_sign = sign_of(six);
  if (vol_sign == kUncertain) {
    Rational exact_six = 0;
    const Point3 o = pts.exact(0);
    for (Index f = 0; f < nf; ++f) exact_six += dot(pts.exact(faces()[f][0]) - o, exact_normal(f));
    vol_sign = sgn(exact_six);
  }
  if (vol_sign == 0)
    throw InputError(source, "", "zero volume: the solid is flat (all its points are coplanar)");
  return vol_sign;
}

// The facets (own, not the caller's) reversed, with their normals, and
// linked again.
void Validation::reverse_own_facets() {
  for (auto& poly : faces_own) std::reverse(poly.begin(), poly.end());
  for (auto& n : inrm) n = -n;
  for (Index f = 0; f < nf; ++f)
    if (xnrm[f]) *xnrm[f] = -*xnrm[f];
  link_faces();
}

// 6. Merge adjacent coplanar facets: adjacent facets are coplanar exactly
//    when their normals are parallel (they share an edge); same
//    orientation merges, opposite orientation is a zero-thickness fold.
void Validation::merge_coplanar() {
  const auto& faces = this->faces();
  UnionFind uf(nf);
  // n(f) x n(o) per edge, kept for the edge convexity test below when the
  // structure stays unchanged.
  // Triangles on doubles: orient3d(p, q, c, d) per edge instead (see
  // triangle_pair_orient; the corner after q in f is c, after p in o is d).
  edge_cross.resize(triangles_on_doubles ? 0 : g.num_halfedges() / 2);
  edge_orient = big_array<signed char>(triangles_on_doubles ? g.num_halfedges() / 2 : 0);
  if (triangles_on_doubles)
    in_blocks(edge_orient.size(), threads, [&](std::size_t begin, std::size_t end) {
      const std::vector<Vec3d>& v = pts.approx();
      for (std::size_t e = begin; e < end; ++e) {
        const Index h = Index(2 * e);
        edge_orient[e] = static_cast<signed char>(orient3d(v[g.origin[h]], v[g.origin[h + 1]],
                                                           v[g.origin[g.next[g.next[h]]]],
                                                           v[g.origin[g.next[g.next[h + 1]]]]));
      }
    });
  for (Index h = 0; h < g.num_halfedges(); h += 2) {
    if (triangles_on_doubles && edge_orient[h / 2] != 0) continue;
    Index f = g.facet[h], o = g.facet[h + 1];
    if (!triangles_on_doubles) {
      FastIPoint c = cross(inrm[f], inrm[o]);
      edge_cross[h / 2] = c;
      auto certainly_nonzero = [](const FastInterval& x) { int s = sign_of(x); return s == 1 || s == -1; };
      if (certainly_nonzero(c.x) || certainly_nonzero(c.y) || certainly_nonzero(c.z)) continue;
      if (auto t = triangle_pair_orient(pts, faces[f], faces[o], g.origin[h], g.origin[h + 1]); t && *t != 0)
        continue;
    }
    if (!is_zero(cross(exact_normal(f), exact_normal(o)))) continue;
    if (sgn(dot(exact_normal(f), exact_normal(o))) > 0) {
      uf.unite(f, o);
      any_merge = true;
    } else {
      throw InputError(source, fct(fname[f]),
                       "lies back to back with " + fct(fname[o]) + " (zero thickness)");
    }
  }
  if (!any_merge) {
    merged_name = fname;  // merged stays empty: the facets are faces()
    merged_rep.resize(nf);
    std::iota(merged_rep.begin(), merged_rep.end(), 0);
    return;
  }
  std::vector<Index> group_of(nf);
  std::vector<Index> group_id(nf, kNoIndex);
  for (Index f = 0; f < nf; ++f) {
    Index r = uf.find(f);
    if (group_id[r] == kNoIndex) {
      group_id[r] = Index(merged.size());
      merged.emplace_back();
      merged_name.push_back(fname[r]);
      merged_rep.push_back(r);
    }
    group_of[f] = group_id[r];
  }
  // Boundary halfedges of each group, keyed by (group, origin).
  std::unordered_map<std::uint64_t, Index> out;
  std::vector<Index> boundary_count(merged.size(), 0), start(merged.size(), kNoIndex);
  for (Index h = 0; h < g.num_halfedges(); ++h) {
    Index gr = group_of[g.facet[h]];
    if (gr == group_of[g.facet[h ^ 1u]]) continue;
    auto [it, ok] = out.try_emplace((std::uint64_t(gr) << 32) | g.origin[h], h);
    if (!ok && probe) {
      not_convex = true;
      return;
    }
    if (!ok)
      throw NotConvexError(source, fct(merged_name[gr]),
                           "coplanar facets around " + vtx(vname[g.origin[h]]) +
                               " do not form one convex polygon (the solid is not convex)");
    ++boundary_count[gr];
    if (start[gr] == kNoIndex) start[gr] = h;
  }
  for (Index gr = 0; gr < merged.size(); ++gr) {
    Index h = start[gr];
    if (h == kNoIndex)
      throw InputError(source, fct(merged_name[gr]), "all facets are coplanar (zero volume)");
    do {
      merged[gr].push_back(g.origin[h]);
      h = out.find((std::uint64_t(gr) << 32) | g.origin[h ^ 1u])->second;
    } while (h != start[gr] && merged[gr].size() <= boundary_count[gr]);
    if (merged[gr].size() != boundary_count[gr]) {
      if (probe) {
        not_convex = true;
        return;
      }
      throw NotConvexError(source, fct(merged_name[gr]),
                           "coplanar facets form a polygon with a hole (the solid is not convex)");
    }
  }
}

// 7. Drop vertices of degree 2 (in the middle of an edge) and vertices that
//    vanished inside merged facets; renumber.
void Validation::drop_vertices() {
  std::vector<Index> degree(pts.size(), 0);
  for (const auto& poly : any_merge ? merged : faces())
    for (Index v : poly) ++degree[v];
  unchanged = !any_merge && std::all_of(degree.begin(), degree.end(), [](Index d) { return d >= 3; });
  // Unchanged: the final structure is the one linked above.  Otherwise
  // renumber and link again.
  if (unchanged) return;
  fill_ip();
  fill_inrm();
  if (!any_merge) merged = faces();
  std::vector<Index> final_id(pts.size(), kNoIndex);
  fpts_own.reserve(pts.size());
  fip_own.reserve(pts.size());
  for (Index v = 0; v < pts.size(); ++v)
    if (degree[v] >= 3) {
      final_id[v] = Index(fpts_own.size());
      fpts_own.push_from(pts, v);
      fip_own.push_back(ip[v]);
      fname_v_own.push_back(vname[v]);
    }
  for (Index f = 0; f < merged.size(); ++f) {
    auto& poly = merged[f];
    std::vector<Index> kept;
    kept.reserve(poly.size());
    for (Index v : poly)
      if (final_id[v] != kNoIndex) kept.push_back(final_id[v]);
    if (kept.size() < 3)
      throw InputError(source, fct(merged_name[f]), "degenerates to fewer than 3 corners");
    poly = std::move(kept);
  }
  fg_own = link(Index(fpts_own.size()), merged, source, fname_v_own, merged_name, mesh.points);
  // The outward normal of each facet, from its representative input facet:
  //    intervals for the filters, the exact Newell normal only when a filter
  //    cannot decide.  (The canonical planes are computed on demand later.)
  finrm_own.resize(merged.size());
  for (Index f = 0; f < merged.size(); ++f) finrm_own[f] = inrm[merged_rep[f]];
}

// 8. Convexity: facets, edges, vertices (see the comment at the top).
//    Each test runs on intervals first and exactly when undecided.
void Validation::check_convexity() {
  const PointList& fpts = this->fpts();
  const std::vector<FastIPoint>& fip = this->fip();
  const std::vector<FastIPoint>& finrm = this->finrm();
  const std::vector<std::vector<Index>>& final_faces = this->final_faces();
  const std::vector<Index>& fname_v = this->fname_v();
  const Graph& fg = this->fg();
  auto fpoint = [&](Index v) { return fpts.exact(v); };
  FanScratch scratch;
  for (Index f = 0; f < final_faces.size(); ++f) {
    const auto& poly = final_faces[f];
    if (poly.size() == 3) continue;  // a triangle turns counter-clockwise about its own normal
    if (!convex_polygon(poly, fip, fpts, finrm[f], [&]() -> const Point3& { return fnormal(f); }, scratch)) {
      if (probe) {
        not_convex = true;
        return;
      }
      throw NotConvexError(source, fct(merged_name[f]), "is not a convex polygon (the solid is not convex)");
    }
  }
  for (Index h = 0; h < fg.num_halfedges(); h += 2) {
    Index f = fg.facet[h], o = fg.facet[h + 1];
    int s = unchanged && triangles_on_doubles
                ? -edge_orient[h / 2]
                : sign_of(dot(unchanged ? edge_cross[h / 2] : cross(finrm[f], finrm[o]),
                              fip[fg.origin[h + 1]] - fip[fg.origin[h]]));
    if (s == kUncertain) {
      if (auto t = triangle_pair_orient(fpts, final_faces[f], final_faces[o], fg.origin[h], fg.origin[h + 1]))
        s = -*t;
      else
        s = sgn(dot(cross(fnormal(f), fnormal(o)), fpoint(fg.origin[h + 1]) - fpoint(fg.origin[h])));
    }
    if (s <= 0 && probe) {
      not_convex = true;
      return;
    }
    if (s <= 0)
      throw NotConvexError(source, edge_place(fname_v[fg.origin[h]], fname_v[fg.origin[h + 1]], mesh.points),
                           "reflex edge between " + fct(merged_name[f]) + " and " + fct(merged_name[o]) +
                               " (the solid is not convex)");
  }
  if (unchanged && triangles_on_doubles) {
    // The test on doubles first; the vertex test below where it does not
    // accept.  Every facet is a triangle, the wedge of each of its corners:
    // its sign is computed once per triangle, not once per corner (as in
    // moved).
    const std::optional<Vec3d> c = reference_point(pts.approx());
    std::vector<signed char> below = big_array<signed char>(c ? final_faces.size() : 0);
    if (c)
      in_blocks(below.size(), threads, [&](std::size_t begin, std::size_t end) {
        const std::vector<Vec3d>& v = pts.approx();
        for (std::size_t f = begin; f < end; ++f) {
          const Index h0 = fg.facet_he[f], h1 = fg.next[h0], h2 = fg.next[h1];
          below[f] = orient3d(v[fg.origin[h0]], v[fg.origin[h1]], v[fg.origin[h2]], *c) < 0;
        }
      });
    const WedgeSigns wedges{below.data(), fg.facet.data()};
    const TriangleNormals<DoubleIntervals> tn{&dip, fg.origin.data(), fg.next.data(), fg.facet_he.data()};
    std::atomic<bool> found{false};  // a probe's non-convex vertex
    in_blocks(fpts.size(), threads, [&](std::size_t begin, std::size_t end) {
      std::vector<Index> around;
      FanScratch block_scratch;
      for (Index v = Index(begin); v < end && !(probe && found.load(std::memory_order_relaxed)); ++v)
        if (!(c && convex_vertex_on_doubles(v, fg.vertex_he[v], fg.origin.data(), fg.prev.data(), pts.approx(),
                                            *c, around, &wedges)) &&
            !convex_vertex(v, fg.vertex_he[v], fg.origin.data(), fg.prev.data(), fg.facet.data(), dip, tn, fpts,
                           block_scratch)) {
          if (probe) {
            found.store(true, std::memory_order_relaxed);
            return;
          }
          throw NotConvexError(source, vertex_place(fname_v[v], mesh.points), "the solid is not convex around this vertex");
        }
    });
    not_convex = found.load();
  } else {
    for (Index v = 0; v < fpts.size(); ++v)
      if (!convex_vertex(v, fg.vertex_he[v], fg.origin.data(), fg.prev.data(), fg.facet.data(), fip, finrm, fpts,
                         scratch)) {
        if (probe) {
          not_convex = true;
          return;
        }
        throw NotConvexError(source, vertex_place(fname_v[v], mesh.points), "the solid is not convex around this vertex");
      }
  }
}

}  // namespace

ConvexPolytope PolytopeBuilder::build(const Mesh& mesh, const std::string& source) {
  return *build(mesh, source, false);
}

std::optional<ConvexPolytope> PolytopeBuilder::build_if_convex(const Mesh& mesh, const std::string& source) {
  return build(mesh, source, true);
}

std::optional<ConvexPolytope> PolytopeBuilder::build(const Mesh& mesh, const std::string& source, bool probe) {
  Validation s(mesh, source);
  s.probe = probe;
  s.check_indices();
  s.weld();
  s.link_faces();
  if (s.not_convex) return std::nullopt;
  s.prepare_intervals();
  {
    // From here on every interval operation runs with the FPU rounding
    // upward, set once (unprotected intervals); the guard restores the mode,
    // also when an InputError leaves.  Exact fallbacks use GMP integers and
    // rationals, which do not depend on the rounding mode.
    CGAL::Protect_FPU_rounding<true> upward;
    s.check_facets();
    if (s.volume_sign() < 0) {
      if (s.same_faces) {
        // The facets are the caller's: validate the reversed mesh instead
        // (the same numbering, so the same result and the same messages).
        Mesh flipped;
        flipped.points = mesh.points;
        flipped.faces = mesh.faces;
        for (auto& poly : flipped.faces) std::reverse(poly.begin(), poly.end());
        return build(flipped, source, probe);
      }
      s.reverse_own_facets();
    }
    s.merge_coplanar();
    if (s.not_convex) return std::nullopt;
    s.drop_vertices();
    s.check_convexity();
    if (s.not_convex) return std::nullopt;
  }

  // 9. The polytope.
  ConvexPolytope p;
  p.coords_ = s.unchanged ? std::move(s.pts) : std::move(s.fpts_own);
  p.source_vertex_ = std::move(s.fname_v());
  Graph& fg = s.fg();
  p.he_origin_ = std::move(fg.origin);
  p.he_facet_ = std::move(fg.facet);
  p.he_next_ = std::move(fg.next);
  p.he_prev_ = std::move(fg.prev);
  p.facet_he_ = std::move(fg.facet_he);
  p.vertex_he_ = std::move(fg.vertex_he);
  p.reset_cache();
  return p;
}

// Why the tests below suffice (see also the comment at the top): the
// moved surface keeps p's vertices (pairwise distinct, checked first), its
// edges and its facets, except that a quadrilateral cut along a diagonal
// becomes two triangles, one more edge and one more facet.  So it is a
// closed, connected, consistently oriented 2-manifold with V - E + F = 2,
// point (1), without linking anything.  Each facet is then checked planar
// (orient3d of its corners against its first three, zero) and strictly
// convex turning counter-clockwise once about its normal, point (2); for a
// triangle that is its edge tests below being nonzero.  Each edge p->q of
// facet f (the next corner of f after q is c) with the facet o on its other
// side (whose corner after p is d) is strictly convex exactly when
// orient3d(p, q, c, d) < 0: f is a strictly convex planar polygon, so p, q,
// c span its plane with (q - p) x (c - p) a positive multiple of its outward
// normal, and d is a corner of o off the line p-q; zero would make f and o
// coplanar (from_mesh would merge them: not certified here), point (3).
// Point (4) is step 8's vertex test.  Then from_mesh would weld nothing,
// merge nothing, drop no vertex (p has none of degree 2 and cutting adds
// edges) and flip nothing: it would build this same structure.
std::optional<ConvexPolytope> PolytopeBuilder::moved(const ConvexPolytope& p, const PointList& points,
                                                     std::size_t* split) {
  const Index nv = p.num_vertices(), nf0 = p.num_facets(), nh0 = p.num_halfedges();
  if (points.form() != PointList::Form::doubles || points.size() != nv) return std::nullopt;
  const std::vector<Vec3d>& v = points.approx();
  // Pairwise distinct.
  {
    const std::vector<Index> canon = weld_exact(points);
    for (Index i = 0; i < nv; ++i)
      if (canon[i] != i) return std::nullopt;
  }
  // Facets still planar; a quadrilateral that is not is cut along the
  // diagonal that folds outwards (1: a-c, when d lies below the plane of
  // a, b, c; 2: b-d), as writable_polytope's full path cuts it.
  // The loops over facets, edges and vertices below run in blocks, on
  // threads for large polytopes (as the validation's); a block that finds
  // the surface not certified clears `certified` and the others stop early.
  const bool threads = nf0 >= parallel_items();
  std::atomic<bool> certified{true};
  std::vector<unsigned char> cut(nf0, 0);
  in_blocks(nf0, threads, [&](std::size_t begin, std::size_t end) {
    for (Index f = Index(begin); f < end && certified.load(std::memory_order_relaxed); ++f) {
      const Index h0 = p.facet_he_[f], h1 = p.he_next_[h0], h2 = p.he_next_[h1];
      Index h = p.he_next_[h2];
      if (h == h0) continue;  // a triangle
      const Vec3d &a = v[p.he_origin_[h0]], &b = v[p.he_origin_[h1]], &c = v[p.he_origin_[h2]];
      int side = 0;  // of the first corner off the plane of a, b, c
      for (; h != h0 && side == 0; h = p.he_next_[h]) side = orient3d(a, b, c, v[p.he_origin_[h]]);
      if (side == 0) continue;
      if (p.he_next_[p.he_next_[h2]] != h0) {  // a larger polygon: the full path cuts it by a hull
        certified = false;
        return;
      }
      cut[f] = side < 0 ? 1 : 2;  // (a quadrilateral: that corner is d)
    }
  });
  if (!certified) return std::nullopt;
  const std::size_t cuts = std::size_t(std::count_if(cut.begin(), cut.end(), [](unsigned char x) { return x != 0; }));
  // The structure: p's half-edges, then one edge per cut quadrilateral.
  // Facets are numbered as the full path's mesh lists them: a cut facet's
  // two pieces take consecutive numbers, each starting where that mesh's
  // polygon starts.
  const Index nh = nh0 + Index(2 * cuts), nf = nf0 + Index(cuts);
  std::vector<Index> origin(p.he_origin_), next(p.he_next_), facet(nh), facet_he(nf);
  origin.resize(nh);
  next.resize(nh);
  {
    Index g = 0, e = nh0;
    for (Index f = 0; f < nf0; ++f) {
      const Index h0 = p.facet_he_[f];
      if (!cut[f]) {
        Index h = h0;
        do {
          facet[h] = g;
          h = p.he_next_[h];
        } while (h != h0);
        facet_he[g++] = h0;
        continue;
      }
      const Index h1 = p.he_next_[h0], h2 = p.he_next_[h1], h3 = p.he_next_[h2];
      const Index a = p.he_origin_[h0], b = p.he_origin_[h1], c = p.he_origin_[h2], d = p.he_origin_[h3];
      if (cut[f] == 1) {  // (a, b, c), (a, c, d): e = a->c, e + 1 = c->a
        origin[e] = a, origin[e + 1] = c;
        next[h1] = e + 1, next[e + 1] = h0, next[h3] = e, next[e] = h2;
        facet[h0] = facet[h1] = facet[e + 1] = g, facet_he[g] = h0;
        facet[e] = facet[h2] = facet[h3] = g + 1, facet_he[g + 1] = e;
      } else {  // (b, c, d), (b, d, a): e = d->b, e + 1 = b->d
        origin[e] = d, origin[e + 1] = b;
        next[h2] = e, next[e] = h1, next[h0] = e + 1, next[e + 1] = h3;
        facet[h1] = facet[h2] = facet[e] = g, facet_he[g] = h1;
        facet[e + 1] = facet[h3] = facet[h0] = g + 1, facet_he[g + 1] = e + 1;
      }
      g += 2;
      e += 2;
    }
  }
  // Point (3): every edge strictly convex, by the kernel's filtered orient3d.
  in_blocks(nh / 2, threads, [&](std::size_t begin, std::size_t end) {
    for (Index h = Index(2 * begin); h < 2 * end && certified.load(std::memory_order_relaxed); h += 2)
      if (orient3d(v[origin[h]], v[origin[h + 1]], v[origin[next[next[h]]]], v[origin[next[next[h + 1]]]]) >= 0)
        certified = false;
  });
  if (!certified) return std::nullopt;
  ConvexPolytope r = from_trusted_parts(points, std::move(origin), std::move(next), std::move(facet),
                                        std::move(facet_he));
  // Point (4) on the doubles first (convex_vertex_on_doubles); a vertex it
  // does not accept is left to step 8's test, which decides (on intervals,
  // exactly where they cannot).  The wedge of a vertex in a triangle (v, u_j, u_j+1) is the
  // triangle itself (orient3d is invariant under cyclic rotation of its
  // first three points), so its sign is computed once per triangle, not
  // once per corner.
  const std::optional<Vec3d> c = reference_point(v);
  std::vector<signed char> below(nf, -1);  // 1: c strictly below the triangle, 0: not, -1: not a triangle
  if (c)
    in_blocks(nf, threads, [&](std::size_t begin, std::size_t end) {
      for (Index f = Index(begin); f < end; ++f) {
        const Index h0 = r.facet_he_[f], h1 = r.he_next_[h0], h2 = r.he_next_[h1];
        if (r.he_next_[h2] == h0)
          below[f] = orient3d(v[r.he_origin_[h0]], v[r.he_origin_[h1]], v[r.he_origin_[h2]], *c) < 0;
      }
    });
  const WedgeSigns wedges{below.data(), r.he_facet_.data()};
  // 1: accepted on the doubles; the others go to the interval test below.
  std::vector<unsigned char> accepted(nv, 0);
  if (c)
    in_blocks(nv, threads, [&](std::size_t begin, std::size_t end) {
      std::vector<Index> around;
      for (Index i = Index(begin); i < end; ++i)
        accepted[i] = convex_vertex_on_doubles(i, r.vertex_he_[i], r.he_origin_.data(), r.he_prev_.data(), v, *c,
                                               around, &wedges);
    });
  std::vector<Index> undecided;
  for (Index i = 0; i < nv; ++i)
    if (!accepted[i]) undecided.push_back(i);
  // Points (2) for polygons and (4) where the doubles did not decide, on
  // intervals of the points made on demand (exact when undecided), as step 8
  // of build.  The interval normals the tests read: those of the polygons
  // and of the facets around the undecided vertices (a triangle elsewhere
  // needs none).
  std::vector<unsigned char> needed(nf, 0);
  bool any = false;
  for (Index f = 0; f < nf; ++f)
    if (r.he_next_[r.he_next_[r.he_next_[r.facet_he_[f]]]] != r.facet_he_[f]) needed[f] = 1, any = true;
  for (Index i : undecided) {
    Index h = r.vertex_he_[i];
    do {
      needed[r.he_facet_[h]] = 1, any = true;
      h = r.he_prev_[h] ^ 1u;
    } while (h != r.vertex_he_[i]);
  }
  if (any) {
    CGAL::Protect_FPU_rounding<true> upward;
    const DoubleIntervals dip{&v};
    std::vector<FastIPoint> nrm(undecided.empty() ? 0 : nf);  // read by the vertex test only
    FanScratch scratch;
    std::vector<Index> loop;
    for (Index f = 0; f < nf; ++f) {
      if (!needed[f]) continue;
      loop.clear();
      const Index h0 = r.facet_he_[f];
      Index h = h0;
      do {
        loop.push_back(r.he_origin_[h]);
        h = r.he_next_[h];
      } while (h != h0);
      const FastIPoint o = dip[loop[0]];
      FastIPoint prev = dip[loop[1]] - o, n{FastInterval(0), FastInterval(0), FastInterval(0)};
      for (std::size_t i = 2; i < loop.size(); ++i) {
        const FastIPoint cur = dip[loop[i]] - o;
        n = n + cross(prev, cur);
        prev = cur;
      }
      if (!nrm.empty()) nrm[f] = n;
      if (loop.size() == 3) continue;
      Point3 exact;
      if (!convex_polygon(loop, dip, points, n,
                          [&]() -> const Point3& { return exact = polygon_normal(points, loop); }, scratch))
        return std::nullopt;
    }
    for (Index i : undecided)
      if (!convex_vertex(i, r.vertex_he_[i], r.he_origin_.data(), r.he_prev_.data(), r.he_facet_.data(), dip, nrm,
                         points, scratch))
        return std::nullopt;
  }
  if (split) *split = cuts;
  return r;
}

void PolytopeBuilder::canonicalize_facets(ConvexPolytope& p) {
  const Index nf = p.num_facets();
  std::vector<std::vector<Index>> loops(nf);
  for (Index f = 0; f < nf; ++f) {
    Index h = p.facet_he_[f], best = h;
    do {
      if (p.he_origin_[h] < p.he_origin_[best]) best = h;
      h = p.he_next_[h];
    } while (h != p.facet_he_[f]);
    p.facet_he_[f] = best;
    loops[f] = p.facet_vertices(f);
  }
  std::vector<Index> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Index x, Index y) { return loops[x] < loops[y]; });
  std::vector<Index> new_id(nf);
  for (Index i = 0; i < nf; ++i) new_id[order[i]] = i;
  std::vector<Index> facet_he(nf);
  for (Index f = 0; f < nf; ++f) facet_he[new_id[f]] = p.facet_he_[f];
  p.facet_he_ = std::move(facet_he);
  for (auto& f : p.he_facet_) f = new_id[f];
  p.reset_cache();
}

// ---------------------------------------------------------------------------

ConvexPolytope ConvexPolytope::from_mesh(const Mesh& mesh, const std::string& source) {
  return PolytopeBuilder::build(mesh, source);
}

Index ConvexPolytope::facet_degree(Index f) const {
  Index n = 0, h = facet_he_[f];
  do {
    ++n;
    h = he_next_[h];
  } while (h != facet_he_[f]);
  return n;
}

Index ConvexPolytope::vertex_degree(Index v) const {
  Index n = 0, h = vertex_he_[v];
  do {
    ++n;
    h = next_around_vertex(h);
  } while (h != vertex_he_[v]);
  return n;
}

std::vector<Index> ConvexPolytope::facet_vertices(Index f) const {
  std::vector<Index> out;
  Index h = facet_he_[f];
  do {
    out.push_back(he_origin_[h]);
    h = he_next_[h];
  } while (h != facet_he_[f]);
  return out;
}

std::vector<Index> ConvexPolytope::vertex_neighbours(Index v) const {
  std::vector<Index> out;
  Index h = vertex_he_[v];
  do {
    out.push_back(target(h));
    h = next_around_vertex(h);
  } while (h != vertex_he_[v]);
  return out;
}

// ---------------------------------------------------------------------------
// Lazy exact data: the exact points (built all at once, on first use) and the
// canonical plane of each facet (built per facet, on first use).  Both are
// published with release/acquire atomics, so concurrent readers of one
// polytope are safe; two threads racing on one plane both compute it and one
// result is kept (they are equal).

// The array of plane slots is itself made on the first plane asked for: a
// polytope only read, summed and written (the command line's usual path)
// never holds it, 8 bytes a facet.
struct ConvexPolytope::Cache {
  explicit Cache(Index nf) : num_facets(nf) {}
  ~Cache() {
    if (planes)
      for (Index f = 0; f < num_facets; ++f) delete planes[f].load(std::memory_order_relaxed);
  }
  Cache(const Cache&) = delete;
  Cache& operator=(const Cache&) = delete;

  std::atomic<const Plane*>& plane_slot(Index f) {
    std::call_once(planes_once, [this] {
      planes.reset(new std::atomic<const Plane*>[num_facets]);
      for (Index g = 0; g < num_facets; ++g) planes[g].store(nullptr, std::memory_order_relaxed);
    });
    return planes[f];
  }

  std::once_flag points_once, planes_once;
  std::vector<Point3> points;
  std::unique_ptr<std::atomic<const Plane*>[]> planes;  // once planes_once has run
  Index num_facets;
};

void ConvexPolytope::reset_cache() { cache_ = std::make_shared<Cache>(num_facets()); }

const std::vector<Point3>& ConvexPolytope::points() const {
  // Rationals: the stored points; otherwise built once.
  std::call_once(cache_->points_once, [this] { cache_->points = coords_.to_points(); });
  return cache_->points;
}

const Point3& ConvexPolytope::point(Index v) const {
  if (coords_.form() == PointList::Form::rationals) return coords_.exact_ref(v);
  return points()[v];
}

const Plane& ConvexPolytope::plane(Index f) const {
  std::atomic<const Plane*>& slot = cache_->plane_slot(f);
  if (const Plane* p = slot.load(std::memory_order_acquire)) return *p;
  // Three consecutive corners of a strictly convex facet are never collinear;
  // counter-clockwise seen from outside, so (v1 - v0) x (v2 - v0) points out.
  const Index h0 = facet_he_[f], h1 = he_next_[h0], h2 = he_next_[h1];
  const Index v[3] = {he_origin_[h0], he_origin_[h1], he_origin_[h2]};
  auto made = std::make_unique<Plane>();
  switch (coords_.form()) {
    case PointList::Form::doubles: {
      const Vec3d hi[3] = {coords_.approx(v[0]), coords_.approx(v[1]), coords_.approx(v[2])};
      *made = canonical_plane_of_dyadic_triangle(hi, nullptr);
      break;
    }
    case PointList::Form::double_pairs: {
      const Vec3d hi[3] = {coords_.approx(v[0]), coords_.approx(v[1]), coords_.approx(v[2])};
      const Vec3d lo[3] = {coords_.low(v[0]), coords_.low(v[1]), coords_.low(v[2])};
      *made = canonical_plane_of_dyadic_triangle(hi, lo);
      break;
    }
    case PointList::Form::rationals: {
      const Point3& p0 = coords_.exact_ref(v[0]);
      *made = canonical_plane(cross(coords_.exact_ref(v[1]) - p0, coords_.exact_ref(v[2]) - p0), p0);
      break;
    }
  }
  const Plane* expected = nullptr;
  if (slot.compare_exchange_strong(expected, made.get(), std::memory_order_acq_rel, std::memory_order_acquire))
    return *made.release();
  return *expected;  // another thread was first; ours is dropped
}

Rational ConvexPolytope::volume() const {
  // Six times the volume: the sum over facets (fanned from their first
  // vertex) of det(p0 - o, pi - o, pi+1 - o), on integer coordinates D
  // (vertex-major, three per vertex) that are the points times one common
  // factor s; the determinant scales by s^3.
  auto six_times = [&](std::vector<Integer>& D) {
    // D = the points minus vertex 0, in place (vertex 0 last): one
    // subtraction per coordinate instead of nine per triangle.
    const std::size_t n3 = std::size_t(num_vertices()) * 3;
    for (std::size_t i = n3; i-- > 0;) mpz_sub(D[i].get_mpz_t(), D[i].get_mpz_t(), D[i % 3].get_mpz_t());
    // GMP's functions on preallocated integers (mul, submul, addmul): no
    // temporary per operation.  Fanned along the half-edges: no list of
    // corners per facet.
    Integer six = 0, t;
    for (Index f = 0; f < num_facets(); ++f) {
      const Index h0 = facet_he_[f];
      const std::size_t pa = 3 * std::size_t(he_origin_[h0]);
      for (Index h = he_next_[h0], g = he_next_[h]; g != h0; h = g, g = he_next_[g]) {
        const std::size_t pb = 3 * std::size_t(he_origin_[h]), pc = 3 * std::size_t(he_origin_[g]);
        for (std::size_t k = 0; k < 3; ++k) {
          const std::size_t k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          mpz_mul(t.get_mpz_t(), D[pb + k1].get_mpz_t(), D[pc + k2].get_mpz_t());
          mpz_submul(t.get_mpz_t(), D[pb + k2].get_mpz_t(), D[pc + k1].get_mpz_t());
          mpz_addmul(six.get_mpz_t(), D[pa + k].get_mpz_t(), t.get_mpz_t());
        }
      }
    }
    return six;
  };
  const Index nv = num_vertices();
  if (coords_.form() == PointList::Form::rationals) {
    // The common factor is the least common multiple L of the coordinates'
    // denominators.  The sum of two operands' vertices typically has few
    // distinct denominators (powers of two, or the one of a scaled
    // catalog shape), so L stays small and the integers are about as long
    // as the numerators: a tenth of the work of reduced rationals, whose
    // every product and sum takes a gcd.  When L grows past a few times the
    // longest denominator (many unrelated denominators), the sum is taken
    // on the rationals themselves: same value, no blow-up of L.
    Integer L = 1;
    std::size_t longest = 1;
    bool common = true;
    for (Index v = 0; v < nv && common; ++v)
      for (int k = 0; k < 3; ++k) {
        const mpz_srcptr d = mpq_denref(coords_.exact_ref(v)[k].get_mpq_t());
        if (mpz_divisible_p(L.get_mpz_t(), d)) continue;
        longest = std::max(longest, mpz_sizeinbase(d, 2));
        mpz_lcm(L.get_mpz_t(), L.get_mpz_t(), d);
        if (mpz_sizeinbase(L.get_mpz_t(), 2) > 4 * longest + 64) {
          common = false;
          break;
        }
      }
    if (!common) {
      Rational six = 0;
      const Point3& o = coords_.exact_ref(0);
      for (Index f = 0; f < num_facets(); ++f) {
        const Index h0 = facet_he_[f];
        const Point3 a = coords_.exact_ref(he_origin_[h0]) - o;
        for (Index h = he_next_[h0], g = he_next_[h]; g != h0; h = g, g = he_next_[g])
          six += dot(a, cross(coords_.exact_ref(he_origin_[h]) - o, coords_.exact_ref(he_origin_[g]) - o));
      }
      return six / 6;
    }
    std::vector<Integer> D(std::size_t(nv) * 3);
    for (Index v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        const mpq_srcptr q = coords_.exact_ref(v)[k].get_mpq_t();
        Integer& x = D[3 * std::size_t(v) + k];
        mpz_divexact(x.get_mpz_t(), L.get_mpz_t(), mpq_denref(q));
        mpz_mul(x.get_mpz_t(), x.get_mpz_t(), mpq_numref(q));
      }
    Rational r(six_times(D));
    Integer L3 = L * L * L * 6;
    mpz_set(mpq_denref(r.get_mpq_t()), L3.get_mpz_t());
    r.canonicalize();
    return r;
  }
  // Dyadic coordinates: integers after one common scaling by 2^-e.
  const bool pairs = coords_.form() == PointList::Form::double_pairs;
  std::vector<double> raw(std::size_t(nv) * (pairs ? 6 : 3));
  for (Index v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      raw[3 * std::size_t(v) + k] = coords_.approx(v)[k];
      if (pairs) raw[3 * (std::size_t(nv) + v) + k] = coords_.low(v)[k];
    }
  ScaledIntegers si(raw.data(), raw.size());
  std::vector<Integer>& D = si.value;
  const std::size_t n3 = std::size_t(nv) * 3;
  if (pairs)
    for (std::size_t i = 0; i < n3; ++i) mpz_add(D[i].get_mpz_t(), D[i].get_mpz_t(), D[n3 + i].get_mpz_t());
  return si.unscale(six_times(D), 3) / 6;
}

Mesh ConvexPolytope::to_mesh() const {
  Mesh m;
  m.points = coords_;
  m.faces.reserve(num_facets());
  for (Index f = 0; f < num_facets(); ++f) m.faces.push_back(facet_vertices(f));
  return m;
}

ConvexPolytope ConvexPolytope::translated(const Point3& t) const {
  Mesh m = to_mesh();
  m.points.transform([&](const Point3& p) { return p + t; });
  ConvexPolytope r = from_mesh(m);
  r.source_vertex_ = source_vertex_;
  return r;
}

ConvexPolytope ConvexPolytope::negated() const {
  Mesh m = to_mesh();
  m.points.negate();
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  ConvexPolytope r = from_mesh(m);
  r.source_vertex_ = source_vertex_;
  return r;
}

std::string ConvexPolytope::check_invariants() const {
  const Index nh = num_halfedges();
  if (nh % 2 != 0) return "odd number of halfedges";
  for (Index h = 0; h < nh; ++h) {
    if (he_next_[h] >= nh || he_prev_[h] >= nh) return "halfedge " + std::to_string(h) + ": bad link";
    if (he_prev_[he_next_[h]] != h) return "halfedge " + std::to_string(h) + ": prev(next(h)) != h";
    if (he_facet_[he_next_[h]] != he_facet_[h]) return "halfedge " + std::to_string(h) + ": next leaves the facet";
    if (target(h) != he_origin_[he_next_[h]]) return "halfedge " + std::to_string(h) + ": next does not start at target";
    if (target(h) == origin(h)) return "halfedge " + std::to_string(h) + ": loop";
  }
  for (Index f = 0; f < num_facets(); ++f)
    if (he_facet_[facet_he_[f]] != f) return "facet " + std::to_string(f) + ": bad halfedge";
  for (Index v = 0; v < num_vertices(); ++v)
    if (he_origin_[vertex_he_[v]] != v) return "vertex " + std::to_string(v) + ": bad halfedge";
  if (euler_characteristic() != 2) return "V - E + F != 2";
  for (Index f = 0; f < num_facets(); ++f)
    for (Index v : facet_vertices(f))
      if (plane(f).side(point(v)) != 0) return "facet " + std::to_string(f) + ": vertex off its plane";
  ConvexPolytope again;
  try {
    again = from_mesh(to_mesh());
  } catch (const InputError& e) {
    return std::string("revalidation failed: ") + e.what();
  }
  if (again.num_vertices() != num_vertices() || again.num_edges() != num_edges() ||
      again.num_facets() != num_facets())
    return "revalidation changed the counts (coplanar facets or degree-2 vertices left)";
  for (Index f = 0; f < num_facets(); ++f)
    if (!(again.plane(f) == plane(f))) return "facet " + std::to_string(f) + ": plane not canonical";
  return "";
}

}  // namespace minksum
