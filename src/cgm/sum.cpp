// The Minkowski sum by overlaying the six pairs of planar maps of two Cubical
// Gaussian Maps (Fogel and Halperin 2006, §3).  See docs/cgm.md.
//
// A facet of S = A ⊕ B with outer normal n exists exactly where the overlay
// of the two Gaussian maps has a vertex at which the two operand features
// together span a plane: face_A(n) ⊕ face_B(n) is 2-dimensional.  Per cube
// face k the overlay vertices are
//   * the vertices of A's map and of B's map (real ones: facet normals;
//     artificial ones: square corners and the points where an arc crosses a
//     cube edge), each located in the other map: coinciding vertices (exact
//     2D point lookup), vertex on an edge (point strictly inside a real
//     segment), or vertex in a face (the face's primal vertex: a monotone
//     walk on the operand's vertex graph towards n, started from the previous
//     answer);
//   * the proper crossings of a real segment of A with a real segment of B
//     (exact rational intersection point).
// Overlapping collinear segments and segments inside faces create no overlay
// vertex (the overlap's ends are vertices of one map lying on an edge of the
// other, or coinciding vertices); face overlaps are the vertices of S.
//
// Candidate pairs are found by a sweep over x-extents: every feature (real
// segment or vertex) of one map is tested against the features of the other
// map whose closed x-extent meets its own.  Cost per pair of maps:
// O((n_A + n_B) log(n_A + n_B) + I) exact tests, I the number of pairs of
// features whose x-extents overlap (k <= I; I is O(n_A n_B) in the worst case,
// near-linear for the well-spread maps of typical polytopes), plus the walks
// for vertex-in-face, then the assembly of the facets (sorting the candidate
// normals, planar hull per facet).
//
// Every decision is the sign of an exact rational expression (2D
// orientations through an interval filter with exact fallback).
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

#include "kernel/interval.hpp"
#include "mesh/support.hpp"
#include "sum/faces.hpp"

namespace minksum {

namespace {

using Key2 = std::pair<Rational, Rational>;
using Map = CubicalGaussianMap::PlanarMap;

int orient2(const Key2& a, const Key2& b, const Key2& c) {
  return sgn((b.first - a.first) * (c.second - a.second) - (b.second - a.second) * (c.first - a.first));
}

// x strictly inside segment pq (p != q).
bool strictly_inside(const Key2& p, const Key2& q, const Key2& x) {
  if (orient2(p, q, x) != 0) return false;
  Rational dx = q.first - p.first, dy = q.second - p.second;
  return sgn((x.first - p.first) * dx + (x.second - p.second) * dy) > 0 &&
         sgn((x.first - q.first) * dx + (x.second - q.second) * dy) < 0;
}

// The features of A and B at an overlay vertex, as far as known.
struct Located {
  std::optional<Feature> a, b;
};

// The feature behind a vertex of a planar map: a facet (real vertex), an
// edge (an arc crossing a cube edge), nothing (a square corner).
std::optional<Feature> vertex_feature(const CubicalGaussianMap::Vertex& v) {
  if (v.real) return Feature::facet(v.facet);
  if (v.arc_edge != kNoIndex) return Feature::edge(v.arc_edge);
  return std::nullopt;
}

struct Counters {
  long long vertex_vertex = 0, a_on_edge_b = 0, b_on_edge_a = 0, a_in_face_b = 0, b_in_face_a = 0, crossing = 0,
            overlap = 0, edge_a_in_face_b = 0, edge_b_in_face_a = 0;
};

struct Item {
  Rational xmin, xmax;
  int color;      // 0: A, 1: B
  bool point;     // a vertex, else a real segment
  Index id;       // vertex, or halfedge (even) of the segment
};

void overlay_map(int k, const Map& ma, const Map& mb, const ConvexPolytope& A, const ConvexPolytope& B,
                 Index& walk_a, Index& walk_b, Counters& cnt, std::vector<FacetCandidate>& out) {
  std::map<Key2, Located> pts;
  const Map* maps[2] = {&ma, &mb};
  auto key = [&](int c, Index v) { return Key2(maps[c]->vertices[v].x, maps[c]->vertices[v].y); };
  for (Index v = 0; v < ma.vertices.size(); ++v) pts[key(0, v)].a = vertex_feature(ma.vertices[v]);
  for (Index v = 0; v < mb.vertices.size(); ++v) {
    auto [it, fresh] = pts.try_emplace(key(1, v));
    if (!fresh) ++cnt.vertex_vertex;
    it->second.b = vertex_feature(mb.vertices[v]);
  }
  // The sweep over x-extents.
  std::vector<Item> items;
  std::vector<char> hit[2];
  for (int c = 0; c < 2; ++c) {
    const Map& m = *maps[c];
    hit[c].assign(m.halfedges.size() / 2, 0);
    for (Index v = 0; v < m.vertices.size(); ++v) items.push_back({m.vertices[v].x, m.vertices[v].x, c, true, v});
    for (Index h = 0; h < m.halfedges.size(); h += 2) {
      if (!m.halfedges[h].real) continue;
      const Rational& x0 = m.vertices[m.halfedges[h].origin].x;
      const Rational& x1 = m.vertices[m.halfedges[h + 1].origin].x;
      items.push_back({std::min(x0, x1), std::max(x0, x1), c, false, h});
    }
  }
  std::sort(items.begin(), items.end(), [](const Item& p, const Item& q) { return cmp(p.xmin, q.xmin) < 0; });
  std::vector<std::size_t> active[2];
  auto seg = [&](int c, Index h) {
    const Map& m = *maps[c];
    return std::make_pair(key(c, m.halfedges[h].origin), key(c, m.halfedges[h + 1].origin));
  };
  // Orientation of three map vertices (color, vertex): an interval filter on
  // the nearest-double enclosures, the exact rational determinant when the
  // filter cannot decide.
  std::vector<Interval> ix[2], iy[2];
  for (int c = 0; c < 2; ++c)
    for (const auto& v : maps[c]->vertices) {
      ix[c].push_back(to_interval(v.x));
      iy[c].push_back(to_interval(v.y));
    }
  using VId = std::pair<int, Index>;
  auto orient = [&](VId a, VId b, VId d) {
    Interval det = (ix[b.first][b.second] - ix[a.first][a.second]) * (iy[d.first][d.second] - iy[a.first][a.second]) -
                   (iy[b.first][b.second] - iy[a.first][a.second]) * (ix[d.first][d.second] - ix[a.first][a.second]);
    int sg = sign_of(det);
    if (sg != kUncertain) return sg;
    return orient2(key(a.first, a.second), key(b.first, b.second), key(d.first, d.second));
  };
  auto ends = [&](int c, Index h) {
    const Map& m = *maps[c];
    return std::make_pair(VId(c, m.halfedges[h].origin), VId(c, m.halfedges[h + 1].origin));
  };
  auto edge_of = [&](int c, Index h) { return Feature::edge(maps[c]->halfedges[h].primal >> 1); };
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& it = items[i];
    auto& other = active[1 - it.color];
    for (std::size_t t = 0; t < other.size();) {
      if (cmp(items[other[t]].xmax, it.xmin) < 0) {
        other[t] = other.back();
        other.pop_back();
      } else {
        ++t;
      }
    }
    for (std::size_t j : other) {
      const Item& jt = items[j];
      if (it.point && jt.point) continue;
      if (it.point || jt.point) {
        const Item& pt = it.point ? it : jt;
        const Item& sg = it.point ? jt : it;
        auto [ep, eq] = ends(sg.color, sg.id);
        if (orient(ep, eq, VId(pt.color, pt.id)) != 0) continue;
        auto [p, q] = seg(sg.color, sg.id);
        Key2 x = key(pt.color, pt.id);
        if (!strictly_inside(p, q, x)) continue;
        Located& l = pts[x];
        if (pt.color == 0) {
          l.b = edge_of(1, sg.id);
          ++cnt.a_on_edge_b;
        } else {
          l.a = edge_of(0, sg.id);
          ++cnt.b_on_edge_a;
        }
        hit[sg.color][sg.id / 2] = 1;
        continue;
      }
      const Item& sa = it.color == 0 ? it : jt;
      const Item& sb = it.color == 0 ? jt : it;
      auto [vp1, vp2] = ends(0, sa.id);
      auto [vq1, vq2] = ends(1, sb.id);
      int o1 = orient(vp1, vp2, vq1), o2 = orient(vp1, vp2, vq2);
      if (o1 * o2 > 0) continue;
      auto [p1, p2] = seg(0, sa.id);
      auto [q1, q2] = seg(1, sb.id);
      if (o1 == 0 && o2 == 0) {
        // Collinear: an overlap when the interiors meet.
        Rational dx = p2.first - p1.first, dy = p2.second - p1.second;
        // p1 copied: a lambda may not capture a structured binding before C++20 (clang 14).
        auto along = [&, o = p1](const Key2& x) -> Rational { return (x.first - o.first) * dx + (x.second - o.second) * dy; };
        Rational a0 = 0, a1 = along(p2), b0 = along(q1), b1 = along(q2);
        if (cmp(b0, b1) > 0) std::swap(b0, b1);
        if (cmp(std::max(a0, b0), std::min(a1, b1)) < 0) {
          ++cnt.overlap;
          hit[0][sa.id / 2] = hit[1][sb.id / 2] = 1;
        }
        continue;
      }
      if (o1 * o2 >= 0) continue;
      int o3 = orient(vq1, vq2, vp1), o4 = orient(vq1, vq2, vp2);
      if (o3 * o4 >= 0) continue;
      // Proper crossing: p1 + t (p2 - p1), t = cross(q1 - p1, q2 - q1) / cross(p2 - p1, q2 - q1).
      Rational rx = p2.first - p1.first, ry = p2.second - p1.second;
      Rational sx = q2.first - q1.first, sy = q2.second - q1.second;
      Rational t = ((q1.first - p1.first) * sy - (q1.second - p1.second) * sx) / (rx * sy - ry * sx);
      Located& l = pts[Key2(p1.first + t * rx, p1.second + t * ry)];
      l.a = edge_of(0, sa.id);
      l.b = edge_of(1, sb.id);
      ++cnt.crossing;
      hit[0][sa.id / 2] = hit[1][sb.id / 2] = 1;
    }
    active[it.color].push_back(i);
  }
  for (int c = 0; c < 2; ++c) {
    const Map& m = *maps[c];
    for (Index h = 0; h < m.halfedges.size(); h += 2)
      if (m.halfedges[h].real && !hit[c][h / 2]) ++(c == 0 ? cnt.edge_a_in_face_b : cnt.edge_b_in_face_a);
  }

  for (auto& [p, l] : pts) {
    const Point3 n = CubicalGaussianMap::lift(k, p.first, p.second);
    // Vertex in a face: the face's primal vertex by hill climbing from the
    // previous answer (mesh/support.hpp).
    auto locate = [&](const ConvexPolytope& P, Index& start) {
      const Support s = support(P, n, start);
      start = s.vertex;
      return s.face;
    };
    if (!l.a) {
      l.a = locate(A, walk_a);
      if (l.b) ++cnt.b_in_face_a;
    }
    if (!l.b) {
      l.b = locate(B, walk_b);
      ++cnt.a_in_face_b;
    }
    const Feature fa = *l.a, fb = *l.b;
    // face_A(n) ⊕ face_B(n) is a facet when its dimensions add up to 2 or more.
    if (int(fa.dim) + int(fb.dim) < 2) continue;
    if (fa.dim == FeatureDim::edge && fb.dim == FeatureDim::edge) {
      Point3 ea = A.point(A.target(2 * fa.index)) - A.point(A.origin(2 * fa.index));
      Point3 eb = B.point(B.target(2 * fb.index)) - B.point(B.origin(2 * fb.index));
      if (is_zero(cross(ea, eb))) continue;  // inside an overlap of parallel edges
    }
    FacetCandidate c;
    c.normal = n;
    for (Index i : feature_vertices(A, fa))
      for (Index j : feature_vertices(B, fb)) c.points.emplace_back(i, j);
    c.provenance = {fa, fb};
    out.push_back(std::move(c));
  }
}

}  // namespace

SumResult minkowski_sum_cgm(const CubicalGaussianMap& a, const CubicalGaussianMap& b, const ConvexPolytope& pa,
                            const ConvexPolytope& pb, const SumOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<FacetCandidate> candidates;
  Counters cnt;
  Index walk_a = 0, walk_b = 0;
  for (int k = 0; k < 6; ++k) {
    options.report("cgm", -1);
    overlay_map(k, a.map(k), b.map(k), pa, pb, walk_a, walk_b, cnt, candidates);
  }
  options.report("cgm", -1);
  const long long overlay_vertices = static_cast<long long>(candidates.size());
  SumResult r = assemble_sum(pa, pb, std::move(candidates), Method::cgm);
  r.counters = {{"overlay_facet_vertices", overlay_vertices},
                {"vertex_vertex", cnt.vertex_vertex},
                {"vertex_a_on_edge_b", cnt.a_on_edge_b},
                {"vertex_b_on_edge_a", cnt.b_on_edge_a},
                {"vertex_a_in_face_b", cnt.a_in_face_b},
                {"vertex_b_in_face_a", cnt.b_in_face_a},
                {"edge_crossing", cnt.crossing},
                {"edge_overlap", cnt.overlap},
                {"edge_a_in_face_b", cnt.edge_a_in_face_b},
                {"edge_b_in_face_a", cnt.edge_b_in_face_a},
                {"face_overlap", static_cast<long long>(r.polytope.num_vertices())}};
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

SumResult minkowski_sum_cgm(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  options.report("cgm", -1);
  CubicalGaussianMap ga = CubicalGaussianMap::from_polytope(a), gb = CubicalGaussianMap::from_polytope(b);
  SumResult r = minkowski_sum_cgm(ga, gb, a, b, options);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
