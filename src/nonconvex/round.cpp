// round_solid: an exact solid boundary written in doubles (or floats) as a
// valid solid (docs/nonconvex.md, "Output").
//
// The exact faces are cut into triangles exactly.  Where the sum touches
// itself (an edge of more than two faces, a vertex of several fans), the
// surface is cut apart: around such an edge each face is paired with its
// neighbour across the solid (exact radial order), and each fan of a vertex
// gets a point of its own, pushed two spacings into its own part of the
// solid so that the parts no longer touch.  Every point is rounded to the
// nearest; points that round to the same point are merged, and the
// triangles that became degenerate are removed with the surface kept
// closed (a triangle with a repeated vertex goes; two triangles on the same
// three points facing opposite ways cancel; a triangle whose points became
// collinear goes and the triangle across its longest side is split at the
// middle point).  That is usually a valid solid, which validate_solid
// confirms.
//
// Else the surface is repaired locally, in rounds.  Each round tests it
// exactly: every directed edge matched by one opposite edge, every vertex a
// single fan, no two triangles meeting other than in their shared edge or
// vertex (the test of CGAL's self_intersections, by CGAL's exact predicates
// on the rounded points; only the triangles that changed are tested again,
// against all).  What fails is moved, and the next round tests again:
//   * two triangles that meet though in the exact surface each lies in
//     front of the other (a gap that rounding closed): their points are
//     pushed into the solid, 2^k spacings, k growing while they meet;
//   * a merged point of several points where the surface is not a
//     2-manifold (parts that rounding brought together): its points are
//     pushed apart along their exact offsets from their centre;
//   * anything else (a sliver that rounding folded over): the points of
//     the offending triangles, a group per connected set of problems, are
//     snapped to a coarser grid of 2^e, all of a group to the same one, e
//     one above the coarsest of them: points that are close merge, and the
//     slivers between them disappear.
// When nothing fails, validate_solid confirms.  When the problems multiply
// instead (features smaller than the spacing everywhere), the same is done
// on every point first snapped to a grid of 2^e, e from the format's
// spacing at the largest coordinate up to 2^-20 of it.  The largest
// distance from an exact point to where it went is reported.
#include <minksum/error.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/parallel.hpp>

#include "nonconvex/morphology.hpp"
#include "nonconvex/triangles_meet.hpp"
#include "nonconvex/validate.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace minksum {

namespace {

// The rounded points are doubles: CGAL's filtered predicates decide on them
// exactly (no construction is used).
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EP = K::Point_3;
using Tri = std::array<Index, 3>;

struct Key {
  double x, y, z;
  friend bool operator==(const Key& a, const Key& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};
std::size_t mix(std::size_t h, double d) {
  if (d == 0) d = 0;  // -0 and +0 are one point
  std::uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return (h ^ (u + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2))) * 0xff51afd7ed558ccdULL;
}
struct KeyHash {
  std::size_t operator()(const Key& k) const { return mix(mix(mix(0, k.x), k.y), k.z); }
};

std::uint64_t pack(Index a, Index b) { return std::uint64_t(a) << 32 | b; }

struct TriSetHash {
  std::size_t operator()(const Tri& s) const { return std::size_t(pack(s[0], s[1]) * 0x9e3779b97f4a7c15ULL) ^ s[2]; }
};

// Union-find over 0..n-1.
struct Sets {
  std::vector<Index> parent;
  explicit Sets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index(0)); }
  Index find(Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
  void join(Index a, Index b) { parent[find(a)] = find(b); }
};

// ---------------------------------------------------------------------------
// Cutting the surface apart where the exact sum touches itself.

// Where the surface touches itself, one point per fan: the triangles over
// the new points and, for each, its exact point and (for the points of a
// vertex with several fans) the direction into its own part of the solid.
struct Fans {
  std::vector<Tri> tris;
  std::vector<Index> vertex;  // point -> exact point
  std::vector<Vec3d> inward;  // unit vector into the solid (zero where none is found)
  std::vector<char> split;    // whether the point is one of several fans of an exact point
  std::size_t split_vertices = 0;
};

// Whether directions v and w (both across the axis u, neither along it)
// point the same way once projected on the plane normal to u.
bool same_side_of_axis(const Point3& u, const Point3& v, const Point3& w) {
  return sgn(dot(v, w) * dot(u, u) - dot(v, u) * dot(w, u)) > 0;
}

// Faces (directed) around the undirected edge a-b of a closed triangle
// surface, each face paired with the one across the solid from it.
// `around`: (triangle, its corner where the edge starts, forward: the
// triangle runs a -> b).  Pairs are written as unions of the corners
// at a and at b.
void pair_around_edge(Index a, Index b, std::vector<std::array<Index, 3>>& around, const std::vector<Tri>& tris,
                      const std::vector<Point3>& pts, Sets& corners) {
  auto third = [&](const std::array<Index, 3>& e) { return tris[e[0]][(e[1] + 2) % 3]; };
  auto link = [&](const std::array<Index, 3>& f, const std::array<Index, 3>& g) {
    // f runs a -> b from corner f[1], g runs b -> a from corner g[1].
    corners.join(3 * f[0] + f[1], 3 * g[0] + (g[1] + 1) % 3);
    corners.join(3 * f[0] + (f[1] + 1) % 3, 3 * g[0] + g[1]);
  };
  if (around.size() == 2) {
    if (around[0][2] != around[1][2]) link(around[0][2] ? around[0] : around[1], around[0][2] ? around[1] : around[0]);
    return;
  }
  // Counter-clockwise order about u = b - a of the half-planes of the faces
  // (exact: signs of det(u, v, w)), starting from the first face's.
  const Point3 u = pts[b] - pts[a];
  std::vector<Point3> dir;
  for (const auto& e : around) dir.push_back(pts[third(e)] - pts[a]);
  const Point3 ref = dir[0];
  auto half = [&](const Point3& v) {
    const int s = sgn(dot(u, cross(ref, v)));
    return s > 0 || (s == 0 && same_side_of_axis(u, ref, v)) ? 0 : 1;
  };
  std::vector<std::size_t> order(around.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::vector<int> halves;
  for (const Point3& v : dir) halves.push_back(half(v));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    if (halves[i] != halves[j]) return halves[i] < halves[j];
    return sgn(dot(u, cross(dir[i], dir[j]))) > 0;
  });
  // A face running a -> b has the solid clockwise of it (its normal
  // u x v points counter-clockwise): its partner is the first face
  // clockwise of it running b -> a.
  const std::size_t m = order.size();
  std::vector<char> taken(m, 0);
  for (std::size_t p = 0; p < m; ++p) {
    const auto& f = around[order[p]];
    if (!f[2]) continue;
    for (std::size_t k = 1; k < m; ++k) {
      const std::size_t q = (p + m - k) % m;
      if (around[order[q]][2] || taken[q]) continue;
      taken[q] = 1;
      link(f, around[order[q]]);
      break;
    }
  }
}

Fans separate_fans(const std::vector<Tri>& tris, const std::vector<Point3>& pts, const std::vector<Vec3d>& approx) {
  // Edges: (undirected key, triangle, corner).
  std::vector<std::pair<std::uint64_t, Index>> edges;
  edges.reserve(3 * tris.size());
  for (Index t = 0; t < tris.size(); ++t)
    for (Index k = 0; k < 3; ++k) {
      const Index a = tris[t][k], b = tris[t][(k + 1) % 3];
      edges.push_back({pack(std::min(a, b), std::max(a, b)), 3 * t + k});
    }
  std::sort(edges.begin(), edges.end());
  Sets corners(3 * tris.size());
  std::vector<std::array<Index, 3>> around;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const Index a = Index(edges[i].first >> 32), b = Index(edges[i].first & 0xffffffffu);
    around.clear();
    for (std::size_t k = i; k < j; ++k) {
      const Index t = edges[k].second / 3, c = edges[k].second % 3;
      around.push_back({t, c, Index(tris[t][c] == a)});
    }
    pair_around_edge(a, b, around, tris, pts, corners);
    i = j;
  }
  Fans out;
  out.tris = tris;
  std::unordered_map<Index, Index> point_of_root;
  std::vector<Index> fans_of(pts.size(), 0);
  for (Index t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      auto [it, fresh] = point_of_root.emplace(corners.find(3 * t + k), Index(out.vertex.size()));
      if (fresh) {
        out.vertex.push_back(tris[t][k]);
        ++fans_of[tris[t][k]];
      }
      out.tris[t][k] = it->second;
    }
  // Into the solid: minus the sum of the unit normals of the fan's
  // triangles (minus one of them where they cancel).
  out.inward.assign(out.vertex.size(), Vec3d{});
  out.split.assign(out.vertex.size(), 0);
  std::vector<std::array<double, 3>> normal_sum(out.vertex.size(), {0, 0, 0}), one(out.vertex.size(), {0, 0, 0});
  for (Index t = 0; t < tris.size(); ++t) {
    const Tri& o = tris[t];
    const Vec3d &p = approx[o[0]], &q = approx[o[1]], &r = approx[o[2]];
    double ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z, vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
    // Scaled so that the products neither overflow nor underflow.
    const double scale = std::max({std::fabs(ux), std::fabs(uy), std::fabs(uz), std::fabs(vx), std::fabs(vy),
                                   std::fabs(vz)});
    if (!(scale > 0) || !std::isfinite(scale)) continue;
    ux /= scale, uy /= scale, uz /= scale, vx /= scale, vy /= scale, vz /= scale;
    double n[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double len = std::hypot(n[0], n[1], n[2]);
    if (!(len > 0) || !std::isfinite(len)) continue;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        normal_sum[out.tris[t][k]][c] -= n[c] / len;
        one[out.tris[t][k]][c] = -n[c] / len;
      }
  }
  for (Index v = 0; v < out.vertex.size(); ++v) {
    out.split[v] = fans_of[out.vertex[v]] > 1;
    for (const auto* s : {&normal_sum[v], &one[v]}) {
      const double len = std::hypot((*s)[0], (*s)[1], (*s)[2]);
      // Only the direction a split point is pushed in, not a decision: a
      // sum of unit normals that nearly cancels gives a poor direction, so
      // one face's normal is taken instead; wherever the point goes, the
      // surface is checked again exactly.
      if (len > 1e-3 && std::isfinite(len)) {
        out.inward[v] = Vec3d{(*s)[0] / len, (*s)[1] / len, (*s)[2] / len};
        break;
      }
    }
  }
  for (Index v = 0; v < pts.size(); ++v) out.split_vertices += fans_of[v] > 1;
  return out;
}

// ---------------------------------------------------------------------------
// Degenerate triangles.

// Removes the triangles that rounding made degenerate, keeping every
// directed edge matched (see the file comment).  A collinear triangle with
// no triangle across its longest side (the surface is not closed there
// after merging) is removed too, its points added to `stuck`, and so is
// every collinear triangle past a bound on the number of splits (which
// makes sure this ends whatever the configuration).
void clean(std::vector<Tri>& tris, const std::vector<EP>& pts, std::vector<Index>& stuck) {
  std::size_t splits = 0;
  const std::size_t most_splits = 4 * tris.size() + 64;
  for (bool changed = true; changed;) {
    changed = false;
    // Repeated vertices.
    std::size_t kept = 0;
    for (const Tri& t : tris)
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) tris[kept++] = t;
    changed |= kept != tris.size();
    tris.resize(kept);
    // Opposite triangles on the same three points cancel.
    {
      auto rotation_of = [](const Tri& t) {  // the rotation starting at the smallest index
        int k = 0;
        for (int i = 1; i < 3; ++i)
          if (t[i] < t[k]) k = i;
        return Tri{t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
      };
      // (sorted set, orientation, triangle), sorted: per set, the triangles
      // of one orientation, then those of the other, each ascending; the
      // first of each cancel in pairs.
      struct Entry {
        Tri set;
        bool up;
        std::size_t i;
      };
      std::vector<Entry> entries(tris.size());
      for (std::size_t i = 0; i < tris.size(); ++i) {
        const Tri r = rotation_of(tris[i]);
        entries[i] = {Tri{r[0], std::min(r[1], r[2]), std::max(r[1], r[2])}, r[1] < r[2], i};
      }
      std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
        return std::tie(x.set, x.up, x.i) < std::tie(y.set, y.up, y.i);
      });
      std::vector<char> gone(tris.size(), 0);
      bool any = false;
      for (std::size_t b = 0, e = 0; b < entries.size(); b = e) {
        std::size_t mid = b;
        while (mid < entries.size() && entries[mid].set == entries[b].set && !entries[mid].up) ++mid;
        e = mid;
        while (e < entries.size() && entries[e].set == entries[b].set) ++e;
        const std::size_t pairs = std::min(mid - b, e - mid);
        for (std::size_t k = 0; k < pairs; ++k) gone[entries[b + k].i] = gone[entries[mid + k].i] = 1, any = true;
      }
      if (any) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < tris.size(); ++i)
          if (!gone[i]) tris[n++] = tris[i];
        tris.resize(n);
        changed = true;
      }
    }
    // Collinear triangles: the one across the longest side is split (the
    // directed edges are indexed only when there is one).
    auto collinear = [&](const Tri& t) {
      return t[0] != t[1] && t[1] != t[2] && t[2] != t[0] && CGAL::collinear(pts[t[0]], pts[t[1]], pts[t[2]]);
    };
    std::size_t first_collinear = 0;
    while (first_collinear < tris.size() && !collinear(tris[first_collinear])) ++first_collinear;
    if (first_collinear == tris.size()) continue;
    std::unordered_map<std::uint64_t, std::size_t> directed;
    directed.reserve(3 * tris.size());
    auto enter = [&](std::size_t i) {
      for (int k = 0; k < 3; ++k) directed[pack(tris[i][k], tris[i][(k + 1) % 3])] = i;
    };
    auto leave = [&](std::size_t i) {
      for (int k = 0; k < 3; ++k) {
        auto it = directed.find(pack(tris[i][k], tris[i][(k + 1) % 3]));
        if (it != directed.end() && it->second == i) directed.erase(it);
      }
    };
    for (std::size_t i = 0; i < tris.size(); ++i) enter(i);
    for (std::size_t i = first_collinear; i < tris.size(); ++i) {
      const Tri t = tris[i];
      if (!collinear(t)) continue;  // (a repeated vertex: removed by the next pass)
      // The vertex strictly inside the opposite side.
      int m = 0;
      while (m < 2 && !CGAL::collinear_are_strictly_ordered_along_line(pts[t[(m + 1) % 3]], pts[t[m]],
                                                                        pts[t[(m + 2) % 3]]))
        ++m;
      const Index c = t[m], a = t[(m + 1) % 3], b = t[(m + 2) % 3];  // t = (c, a, b): side a -> b
      auto across = directed.find(pack(b, a));
      leave(i);
      tris[i] = Tri{c, c, c};  // removed by the next pass
      changed = true;
      if (across == directed.end() || ++splits > most_splits) {
        stuck.insert(stuck.end(), t.begin(), t.end());
        continue;
      }
      const std::size_t j = across->second;
      const Tri u = tris[j];
      int k = 0;
      while (!(u[k] == b && u[(k + 1) % 3] == a)) ++k;
      const Index x = u[(k + 2) % 3];  // u = (b, a, x)
      leave(j);
      if (x == c) {  // u = (b, a, c): t's opposite, which it cancels
        tris[j] = Tri{c, c, c};
        continue;
      }
      tris[j] = Tri{b, c, x};
      enter(j);
      tris.push_back(Tri{c, a, x});
      enter(tris.size() - 1);
    }
  }
}

// ---------------------------------------------------------------------------
// Exact tests of the rounded surface.

// Whether two distinct triangles (indices into `p`, distinct points) meet
// other than in their shared edge or vertex: as CGAL's
// Polygon_mesh_processing::self_intersections decides it, which
// validate_solid's test follows (nonconvex/triangles_meet.hpp).
bool triangles_meet(const Tri& h, const Tri& g, const std::vector<EP>& p) {
  return nonconvex_detail::triangles_meet<K>(h, g, p);
}

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

Box box_of(const Tri& t, const std::vector<Vec3d>& at, std::size_t i) {
  double lo[3], hi[3];
  for (int c = 0; c < 3; ++c) {
    lo[c] = std::min({at[t[0]][c], at[t[1]][c], at[t[2]][c]});
    hi[c] = std::max({at[t[0]][c], at[t[1]][c], at[t[2]][c]});
  }
  return Box(lo, hi, i);
}

// The pairs of triangles that meet wrongly, among the pairs with at least
// one triangle marked in `dirty` (all pairs when every one is), in the
// order the boxes report them.  False when there are more than `most` of
// them (or too many pairs of boxes to test): the surface is too far from
// valid for local repair.  The pairs of boxes are gathered in batches and
// each batch is tested on every hardware thread (the predicates are CGAL's
// filtered ones on doubles, which keep no shared state).
struct TooMany {};
bool meeting_pairs(const std::vector<Tri>& tris, const std::vector<Vec3d>& at, const std::vector<EP>& ep,
                   const std::vector<char>& dirty, std::size_t most,
                   std::vector<std::pair<std::size_t, std::size_t>>& hits) {
  hits.clear();
  std::vector<Box> all, some;
  all.reserve(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    all.push_back(box_of(tris[i], at, i));
    if (dirty[i]) some.push_back(all.back());
  }
  if (some.empty()) return true;
  const bool every = some.size() == all.size();
  constexpr std::size_t kBatch = std::size_t(1) << 18, kChunk = 512;
  std::vector<std::pair<std::size_t, std::size_t>> batch;
  batch.reserve(std::min(kBatch, 16 * tris.size() + 16));
  std::vector<char> meets;
  std::size_t tested = 0;
  auto test_batch = [&] {
    meets.assign(batch.size(), 0);
    const std::size_t chunks = (batch.size() + kChunk - 1) / kChunk;
    const unsigned workers = batch.size() >= parallel_items() ? parallel_threads(0, chunks) : 1;
    parallel_for(chunks, workers, [&](std::size_t c) {
      const std::size_t end = std::min(batch.size(), (c + 1) * kChunk);
      for (std::size_t k = c * kChunk; k < end; ++k)
        meets[k] = triangles_meet(tris[batch[k].first], tris[batch[k].second], ep);
    });
    for (std::size_t k = 0; k < batch.size(); ++k)
      if (meets[k]) {
        hits.push_back(batch[k]);
        if (hits.size() > most) throw TooMany{};
      }
    batch.clear();
  };
  auto gather = [&](const Box& x, const Box& y) {
    std::size_t i = x.info(), j = y.info();
    if (i == j) return;
    // Two marked triangles are reported from each one's box: kept once.
    if (!every && dirty[j] && j < i) return;
    if (i > j) std::swap(i, j);
    if (++tested > 16 * tris.size() + 64 * most) throw TooMany{};
    batch.emplace_back(i, j);
    if (batch.size() == kBatch) test_batch();
  };
  try {
    if (every)
      CGAL::box_self_intersection_d(all.begin(), all.end(), gather);
    else
      CGAL::box_intersection_d(some.begin(), some.end(), all.begin(), all.end(), gather);
    test_batch();
  } catch (const TooMany&) {
    return false;
  }
  return true;
}

// The places where the rounded surface is not a closed 2-manifold, each
// reported as report(center, points): a directed edge used other than once
// with its opposite used once (center: its two points; points: those of a
// triangle on it), and a vertex whose triangles form more than one fan
// (center: it; points: it and its neighbours).
template <class Report>
void topology_problems(const std::vector<Tri>& tris, std::size_t points, Report report) {
  std::unordered_map<std::uint64_t, Index> uses;
  uses.reserve(3 * tris.size());
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++uses[pack(t[k], t[(k + 1) % 3])];
  std::vector<char> bad(points, 0);
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      const Index a = t[k], b = t[(k + 1) % 3];
      auto back = uses.find(pack(b, a));
      if (uses[pack(a, b)] == 1 && back != uses.end() && back->second == 1) continue;
      bad[t[0]] = bad[t[1]] = bad[t[2]] = 1;
      report(std::vector<Index>{a, b}, std::vector<Index>(t.begin(), t.end()));
    }
  // Fans: corners (next, prev) around each vertex whose edges are all sound.
  std::vector<Index> start(points + 1, 0);
  for (const Tri& t : tris)
    for (Index v : t) ++start[v + 1];
  for (std::size_t v = 0; v < points; ++v) start[v + 1] += start[v];
  std::vector<std::pair<Index, Index>> corner(start[points]);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) corner[fill[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  for (std::size_t v = 0; v < points; ++v) {
    const Index b = start[v], e = start[v + 1];
    if (b == e || bad[v]) continue;
    // Walk next -> prev from the first corner: one cycle through all.
    Index w = corner[b].first;
    std::size_t steps = 0;
    do {
      Index next = kNoIndex;
      for (Index i = b; i < e; ++i)
        if (corner[i].first == w) next = corner[i].second;
      if (next == kNoIndex) break;
      w = next;
      ++steps;
    } while (w != corner[b].first && steps <= e - b);
    if (steps == e - b && w == corner[b].first) continue;
    std::vector<Index> around{Index(v)};
    for (Index i = b; i < e; ++i) around.push_back(corner[i].first);
    report(std::vector<Index>{Index(v)}, around);
  }
}

// ---------------------------------------------------------------------------

double to_format(const Rational& q, bool floats) { return floats ? double(to_float(q)) : to_double(q); }
double to_format(double d, bool floats) { return floats ? double(float(d)) : d; }

// The exponent of the format's spacing at magnitude m.
int spacing_exponent(double m, bool floats) {
  const int lowest = floats ? -149 : -1074;
  if (m == 0) return lowest;
  int e = 0;
  std::frexp(m, &e);
  return std::max(e - (floats ? 24 : 53), lowest);
}

}  // namespace

RoundedSolid round_solid(const Mesh& exact, bool floats, const std::string& name) {
  const Mesh tri = triangulate(exact, name);
  RoundedSolid r;
  const std::vector<Point3> exact_pts = tri.points.to_points();
  // Equal exact points are one point (the cut below decides fans by index).
  std::vector<Index> weld(exact_pts.size());
  std::vector<Point3> pts;
  std::vector<Vec3d> nearest;
  double largest = 0;
  {
    // The welded points of each position, as a chain from the last one.
    std::unordered_map<Key, Index, KeyHash> last_at;
    last_at.reserve(exact_pts.size());
    std::vector<Index> before;  // welded point -> the one before it at its position
    // Each point rounded (on every hardware thread), with the
    // number of its coordinates that are not of the format.  A coordinate
    // equal to its rounding is that double: its nearest double is the
    // rounding too, so only those are compared exactly.
    const std::size_t np = exact_pts.size();
    std::vector<Vec3d> rounding(np);
    std::vector<unsigned char> inexact(np);
    parallel_for(np, parallel_threads(0, np / 1024 + 1), [&](std::size_t i) {
      double c[3];
      unsigned char count = 0;
      const Vec3d& near = tri.points.approx(i);
      for (int k = 0; k < 3; ++k) {
        c[k] = to_format(exact_pts[i][k], floats);
        // (Beyond the format's range: refused below.)
        if (std::isfinite(c[k])) count += near[k] != c[k] || Rational(c[k]) != exact_pts[i][k];
      }
      rounding[i] = Vec3d{c[0], c[1], c[2]};
      inexact[i] = count;
    });
    for (std::size_t i = 0; i < np; ++i) {
      const double c[3] = {rounding[i].x, rounding[i].y, rounding[i].z};
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(c[k]))
          throw RoundingError(std::string("a coordinate is beyond the range of ") +
                              (floats ? "32-bit floats" : "doubles"));
        largest = std::max(largest, std::fabs(c[k]));
      }
      const auto slot = last_at.emplace(Key{c[0], c[1], c[2]}, kNoIndex).first;
      Index w = kNoIndex;
      for (Index j = slot->second; j != kNoIndex && w == kNoIndex; j = before[j])
        if (pts[j] == exact_pts[i]) w = j;
      if (w == kNoIndex) {
        w = Index(pts.size());
        pts.push_back(exact_pts[i]);
        nearest.push_back(Vec3d{c[0], c[1], c[2]});
        before.push_back(slot->second);
        slot->second = w;
        r.rounded_coordinates += inexact[i];
      }
      weld[i] = w;
    }
  }
  std::vector<Tri> faces;
  faces.reserve(tri.faces.size());
  for (const auto& f : tri.faces) faces.push_back(Tri{weld[f[0]], weld[f[1]], weld[f[2]]});
  const Fans fans = separate_fans(faces, pts, nearest);
  if (r.rounded_coordinates == 0 && fans.split_vertices == 0) {
    r.mesh = exact;
    return r;
  }
  if (largest == 0)
    throw RoundingError(std::string("every coordinate rounds to zero: the solid is below the range of ") +
                        (floats ? "32-bit floats" : "doubles"));

  // Per point of the cut surface: the grid exponent it is snapped to
  // (kNearest: none, each coordinate to the nearest), the exponent of the
  // format's spacing at it, and how far it is pushed into the solid (0:
  // not; k: 2^k units of its grid or spacing).
  constexpr int kNearest = INT_MIN;
  const std::size_t n = fans.vertex.size();
  std::vector<int> grid(n, kNearest), spacing(n), push(n, 0);
  std::vector<Vec3d> direction = fans.inward;  // of the push
  for (std::size_t c = 0; c < n; ++c) {
    const Vec3d& p = nearest[fans.vertex[c]];
    spacing[c] = spacing_exponent(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}), floats);
  }
  int largest_exponent = 0;
  std::frexp(largest, &largest_exponent);
  auto position = [&](std::size_t c) {
    const Vec3d& p = nearest[fans.vertex[c]];
    const Vec3d& d = direction[c];
    if (grid[c] == kNearest && push[c] == 0) return p;
    const int e = grid[c] == kNearest ? spacing[c] : grid[c];
    const double offset = push[c] ? std::ldexp(1.0, e + push[c]) : 0.0;
    double q[3];
    for (int k = 0; k < 3; ++k) {
      double x = p[k] + offset * d[k];
      if (grid[c] != kNearest) x = std::ldexp(std::nearbyint(std::ldexp(x, -e)), e);
      x = to_format(x, floats);
      if (!std::isfinite(x)) return p;
      q[k] = x;
    }
    return Vec3d{q[0], q[1], q[2]};
  };

  // The rounded surface: points of equal position merged, degenerate
  // triangles removed.
  std::vector<Vec3d> at;
  std::vector<EP> ep;
  std::vector<Index> id(n), first(n);  // point -> merged point; merged point -> one of its points
  std::vector<Tri> tris;
  std::vector<Index> stuck;
  auto build = [&] {
    std::unordered_map<Key, Index, KeyHash> index;
    index.reserve(n);
    at.clear();
    ep.clear();
    for (std::size_t c = 0; c < n; ++c) {
      const Vec3d p = position(c);
      auto [it, fresh] = index.emplace(Key{p.x, p.y, p.z}, Index(at.size()));
      if (fresh) {
        first[at.size()] = Index(c);
        at.push_back(p);
        ep.push_back(EP(p.x, p.y, p.z));
      }
      id[c] = it->second;
    }
    tris.clear();
    for (const Tri& t : fans.tris) tris.push_back(Tri{id[t[0]], id[t[1]], id[t[2]]});
    stuck.clear();
    clean(tris, ep, stuck);
  };
  auto mesh_of = [&] {
    Mesh m;
    std::vector<Index> renumber(at.size(), kNoIndex);
    for (const Tri& t : tris) {
      std::vector<Index> f;
      for (Index v : t) {
        if (renumber[v] == kNoIndex) {
          renumber[v] = Index(m.points.size());
          m.points.push_back(Point3(Rational(at[v].x), Rational(at[v].y), Rational(at[v].z)));
        }
        f.push_back(renumber[v]);
      }
      m.faces.push_back(std::move(f));
    }
    return m;
  };
  auto finish = [&](Mesh&& m) {
    // The points in blocks, on every hardware thread.
    const std::size_t blocks = std::min<std::size_t>(n, 256);
    std::vector<double> block_moved(blocks, 0.0);
    parallel_for(blocks, parallel_threads(0, n / 1024 + 1), [&](std::size_t k) {
      double most = 0;
      Rational d[3];
      for (std::size_t c = n * k / blocks; c < n * (k + 1) / blocks; ++c) {
        const Vec3d& q = at[id[c]];
        const Point3& p = pts[fans.vertex[c]];
        for (int i = 0; i < 3; ++i) d[i] = Rational(q[i]) - p[i];
        // hypot of the components: |d|^2 overflows doubles for coordinates
        // above 2^512.
        most = std::max(most, std::hypot(to_double(d[0]), to_double(d[1]), to_double(d[2])));
      }
      block_moved[k] = most;
    });
    double moved = 0;
    for (double m : block_moved) moved = std::max(moved, m);
    int coarsest_used = kNearest;
    for (std::size_t c = 0; c < n; ++c) coarsest_used = std::max(coarsest_used, grid[c]);
    // Each component is within half an ulp, hypot within one: rounded up.
    if (moved > 0) moved = std::nextafter(moved * (1 + 0x1p-50), HUGE_VAL);
    r.mesh = std::move(m);
    r.max_displacement = moved;
    r.grid = coarsest_used == kNearest ? 0 : std::ldexp(1.0, coarsest_used);
    return r;
  };

  // The usual case: rounded to the nearest, nothing touching, valid.  (When
  // it is not valid, the repair on the format's own numbers starts from
  // this same surface: no point pushed, none snapped.)
  bool built_nearest = false;
  if (fans.split_vertices == 0) {
    build();
    built_nearest = true;
    if (stuck.empty() && !tris.empty()) {
      Mesh m = mesh_of();
      try {
        nonconvex_detail::check_surface(m, name);
        return finish(std::move(m));
      } catch (const InputError&) {
        // Repaired below.
      }
    }
  }

  auto tri_key = [&](const Tri& t) {
    std::array<Key, 3> k = {Key{at[t[0]].x, at[t[0]].y, at[t[0]].z}, Key{at[t[1]].x, at[t[1]].y, at[t[1]].z},
                            Key{at[t[2]].x, at[t[2]].y, at[t[2]].z}};
    std::sort(k.begin(), k.end(), [](const Key& a, const Key& b) {
      if (a.x != b.x) return a.x < b.x;
      if (a.y != b.y) return a.y < b.y;
      return a.z < b.z;
    });
    return std::array<double, 9>{k[0].x, k[0].y, k[0].z, k[1].x, k[1].y, k[1].z, k[2].x, k[2].y, k[2].z};
  };
  struct TriKeyHash {
    std::size_t operator()(const std::array<double, 9>& k) const {
      std::size_t h = 0;
      for (double d : k) h = mix(h, d);
      return h;
    }
  };
  // Whether each of two triangles lies in front of the other (on the
  // outer side of its plane or on it, not all on it), by the exact points
  // they come from: with the two apart on the surface, a gap between two
  // parts of it that rounding closed, which pushing both into the solid
  // opens again.
  auto facing = [&](const Tri& a, const Tri& b) {
    auto exact_point = [&](Index v) -> const Point3& { return pts[fans.vertex[first[v]]]; };
    auto in_front = [&](const Tri& s, const Tri& o) {
      const Point3& p0 = exact_point(s[0]);
      const Point3 normal = cross(exact_point(s[1]) - p0, exact_point(s[2]) - p0);
      if (is_zero(normal)) return false;
      bool strictly = false;
      for (Index w : o) {
        const int side = sgn(dot(normal, exact_point(w) - p0));
        if (side < 0) return false;
        strictly |= side > 0;
      }
      return strictly;
    };
    return in_front(a, b) && in_front(b, a);
  };
  constexpr int kMostPushes = 4, kMostRounds = 32;
  // No grid and no push coarser than 2^-10 of the largest coordinate.
  const int coarsest = largest_exponent - 10;
  std::string last_problem;

  // Local repair on a floor grid (kNearest: none): test, move the points
  // of what fails, test again what changed.  False when it does not
  // converge (problems multiply, or too many rounds).
  auto repair = [&](int floor) {
    std::fill(grid.begin(), grid.end(), floor);
    for (std::size_t c = 0; c < n; ++c) push[c] = fans.split[c] ? 1 : 0;
    direction = fans.inward;
    // Triangles (by position) tested against every other of the previous
    // surface and found meeting none.
    std::unordered_set<std::array<double, 9>, TriKeyHash> sound;
    std::size_t first_count = 0;
    std::vector<std::pair<std::size_t, std::size_t>> hits;
    for (int round = 0; round < kMostRounds; ++round) {
      if (!std::exchange(built_nearest, false) || floor != kNearest || round != 0) build();
      if (tris.empty()) {
        last_problem = "every face degenerates";
        return false;
      }
      // Problems to snap: their points joined, one grid per group.
      Sets problems(at.size());
      std::size_t count = 0;
      for (std::size_t i = 0; i + 2 < stuck.size(); i += 3) {
        problems.join(stuck[i], stuck[i + 1]);
        problems.join(stuck[i], stuck[i + 2]);
      }
      count += stuck.size() / 3;
      // A merged point of several points where the surface is not a
      // 2-manifold: parts that rounding brought together, pushed apart
      // (each point into its own part of the solid); else snapped.
      std::vector<Index> copies(at.size(), 0);
      for (std::size_t c = 0; c < n; ++c) ++copies[id[c]];
      std::vector<char> pushed(at.size(), 0);
      topology_problems(tris, at.size(), [&](const std::vector<Index>& center, const std::vector<Index>& around) {
        ++count;
        bool push_them = false;
        for (Index v : center) push_them |= copies[v] > 1;
        if (push_them)
          for (Index v : center) push_them &= copies[v] == 1 || push[first[v]] < kMostPushes;
        if (push_them) {
          for (Index v : center)
            if (copies[v] > 1) pushed[v] = 2;
        } else {
          for (Index v : around) problems.join(v, around[0]);
        }
      });
      // Problems multiply: local repair does not converge.
      const std::size_t most = round == 0 ? std::max<std::size_t>(1024, tris.size() / 8)
                                          : std::max<std::size_t>(64, 2 * first_count + tris.size() / 64);
      std::vector<char> dirty(tris.size());
      std::vector<std::array<double, 9>> keys;
      keys.reserve(tris.size());
      for (std::size_t i = 0; i < tris.size(); ++i) {
        keys.push_back(tri_key(tris[i]));
        dirty[i] = !sound.count(keys[i]);
      }
      if (!meeting_pairs(tris, at, ep, dirty, most, hits)) {
        last_problem = "the surface intersects itself";
        return false;
      }
      count += hits.size();
      if (!hits.empty())
        last_problem = "the surface intersects itself";
      else if (count)
        last_problem = "the surface is not a closed 2-manifold";
      if (round == 0) first_count = count;
      if (count > most) return false;
      if (count == 0) {
        Mesh m = mesh_of();
        try {
          nonconvex_detail::check_surface(m, name);
          finish(std::move(m));
          return true;
        } catch (const InputError& err) {
          last_problem = err.problem();  // what the tests above do not see (the nesting of shells)
          return false;
        }
      }
      std::vector<char> hit(tris.size(), 0);
      // Neighbours of each point (for the points of meeting triangles).
      std::unordered_map<Index, std::vector<Index>> neighbours;
      for (const auto& [i, j] : hits)
        for (Index v : tris[i]) neighbours[v], neighbours[tris[j][0]], neighbours[tris[j][1]], neighbours[tris[j][2]];
      if (!hits.empty())
        for (const Tri& t : tris)
          for (int k = 0; k < 3; ++k)
            if (auto it = neighbours.find(t[k]); it != neighbours.end()) it->second.push_back(t[(k + 1) % 3]);
      // Two parts of the surface: no point of one is a point of the other
      // or next to one.
      auto apart = [&](const Tri& a, const Tri& b) {
        for (Index v : a)
          for (Index w : b) {
            if (v == w) return false;
            const auto& around = neighbours[v];
            if (std::find(around.begin(), around.end(), w) != around.end()) return false;
          }
        return true;
      };
      for (const auto& [i, j] : hits) {
        hit[i] = hit[j] = 1;
        bool push_them = apart(tris[i], tris[j]) && facing(tris[i], tris[j]);
        for (const Tri* t : {&tris[i], &tris[j]})
          for (Index v : *t) push_them &= push[first[v]] < kMostPushes;
        if (push_them) {
          for (Index v : tris[i]) pushed[v] = std::max<char>(pushed[v], 1);
          for (Index v : tris[j]) pushed[v] = std::max<char>(pushed[v], 1);
        } else {
          for (Index v : tris[i]) problems.join(v, tris[j][0]);
          for (Index v : tris[j]) problems.join(v, tris[j][0]);
        }
      }
      sound.clear();
      for (std::size_t i = 0; i < tris.size(); ++i)
        if (!hit[i]) sound.insert(keys[i]);
      bool changed = false;
      // Points of different exact points merged where the surface is not a
      // 2-manifold are pushed away from each other as well: along their
      // exact offsets from their centre (a gap or a neck narrower than
      // the spacing, widened).
      {
        std::unordered_map<Index, std::vector<Index>> members;
        for (std::size_t c = 0; c < n; ++c)
          if (pushed[id[c]] == 2) members[id[c]].push_back(Index(c));
        for (const auto& [v, list] : members) {
          Point3 centre(Rational(0), Rational(0), Rational(0));
          for (Index c : list) centre = centre + pts[fans.vertex[c]];
          centre = Rational(1, long(list.size())) * centre;
          for (Index c : list) {
            const Vec3d d = to_double(pts[fans.vertex[c]] - centre);
            const double len = std::hypot(d.x, d.y, d.z);
            if (!(len > 0) || !std::isfinite(len)) continue;
            const Vec3d& in = fans.inward[c];
            const Vec3d w{2 * d.x / len + in.x, 2 * d.y / len + in.y, 2 * d.z / len + in.z};
            const double wl = std::hypot(w.x, w.y, w.z);
            if (wl > 0) direction[c] = Vec3d{w.x / wl, w.y / wl, w.z / wl};
          }
        }
      }
      // Pushed: each point one step further.
      for (std::size_t c = 0; c < n; ++c) {
        if (!pushed[id[c]]) continue;
        const int e = (grid[c] == kNearest ? spacing[c] : grid[c]) + push[c] + 1;
        if (e > coarsest) continue;
        ++push[c];
        changed = true;
      }
      // Snapped: the points of each group to one grid, one above the
      // coarsest of them.
      std::vector<char> marked(at.size(), 0);
      for (Index v = 0; v < at.size(); ++v)
        if (problems.find(v) != v) marked[v] = marked[problems.find(v)] = 1;
      std::unordered_map<Index, int> level;  // group -> its points' coarsest exponent
      for (std::size_t c = 0; c < n; ++c) {
        const Index v = id[c];
        if (!marked[v]) continue;
        const int e = grid[c] == kNearest ? spacing[c] - 1 : grid[c];
        auto [it, fresh] = level.emplace(problems.find(v), e);
        if (!fresh) it->second = std::max(it->second, e);
      }
      for (std::size_t c = 0; c < n; ++c) {
        const Index v = id[c];
        if (!marked[v]) continue;
        const int e = level.at(problems.find(v)) + 1;
        if (e > std::max(coarsest, spacing[c])) continue;
        grid[c] = e;
        changed = true;
      }
      if (!changed) return false;
    }
    return false;
  };

  // Local repair on the format's own numbers; failing that, on every
  // point snapped to a grid of 2^e first, e from the format's spacing at
  // the largest coordinate up to 2^-20 of it.
  const int lowest_floor = spacing_exponent(largest, floats), highest_floor = largest_exponent - 20;
  if (repair(kNearest)) return r;
  for (int floor = lowest_floor; floor <= highest_floor; ++floor)
    if (repair(floor)) return r;
  if (last_problem == "every face degenerates")
    throw RoundingError(std::string("the rounded surface collapses (every face degenerates: the solid is thinner "
                                    "than the spacing of ") +
                        (floats ? "32-bit floats" : "doubles") + ")");
  throw RoundingError("the rounded surface is not a valid solid even with points snapped to 2^-20 of the largest "
                      "coordinate (" + last_problem + ")");
}

namespace nonconvex_detail {

// The cut of round_solid's step 2 without the push: each fan of faces
// around a point gets its own copy of the exact point (contacts.hpp).
Mesh separate_contacts(const Mesh& triangles) {
  const std::vector<Point3> pts = triangles.points.to_points();
  std::vector<Vec3d> approx;
  approx.reserve(pts.size());
  for (const Point3& p : pts) approx.push_back(to_double(p));
  std::vector<Tri> tris;
  tris.reserve(triangles.faces.size());
  for (const auto& f : triangles.faces) {
    if (f.size() != 3) throw std::logic_error("separate_contacts: a face that is not a triangle");
    tris.push_back(Tri{f[0], f[1], f[2]});
  }
  const Fans fans = separate_fans(tris, pts, approx);
  if (fans.split_vertices == 0) return triangles;
  Mesh out;
  for (Index v : fans.vertex) out.points.push_back(pts[v]);
  for (const Tri& t : fans.tris) out.faces.push_back({t[0], t[1], t[2]});
  return out;
}

}  // namespace nonconvex_detail

}  // namespace minksum
