// Construction of the Cubical Gaussian Map from a ConvexPolytope, the
// cyclic chains, the invariant checks and the extraction back to a polytope.
//
// Per polytope edge h (p0 -> p1, facets f1 = facet(h), f2 = facet(twin h)),
// the arc from n1 = n(f1) to n2 = n(f2) is the central projection of the 3D
// segment n(t) = n1 + t (n2 - n1), t in [0, 1] (it misses the origin since
// n1, n2 are not antiparallel).  The cube face of n(t) changes only where two
// coordinates tie in absolute value, |n_i(t)| = |n_j(t)|: six linear
// equations in t.  Between consecutive roots the set of closed cube faces
// containing n(t) is constant (one face, or two faces while the arc runs
// along a cube edge); runs with the same set become one segment per face.
// All of this is exact rational arithmetic.
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace minksum {

const char* cgm_location_name(CgmLocation l) {
  switch (l) {
    case CgmLocation::corner: return "corner";
    case CgmLocation::edge: return "edge";
    case CgmLocation::interior: return "interior";
  }
  return "?";
}

int CubicalGaussianMap::axis_x(int k) {
  static constexpr int ax[6] = {2, 0, 1, 1, 2, 0};
  return ax[k];
}
int CubicalGaussianMap::axis_y(int k) {
  static constexpr int ay[6] = {1, 2, 0, 2, 0, 1};
  return ay[k];
}

Point3 CubicalGaussianMap::lift(int k, const Rational& x, const Rational& y) {
  Point3 p;
  p[axis(k)] = Rational(sign(k));
  p[axis_x(k)] = x;
  p[axis_y(k)] = y;
  return p;
}

Index CubicalGaussianMap::PlanarMap::num_real_vertices() const {
  Index n = 0;
  for (const auto& v : vertices) n += v.real;
  return n;
}
Index CubicalGaussianMap::PlanarMap::num_real_edges() const {
  Index n = 0;
  for (std::size_t h = 0; h < halfedges.size(); h += 2) n += halfedges[h].real;
  return n;
}

CubicalGaussianMap::Counts CubicalGaussianMap::counts(int k) const {
  const PlanarMap& m = maps_[k];
  return {Index(m.vertices.size()), Index(m.halfedges.size()), Index(m.faces.size())};
}

namespace {

using Key2 = std::pair<Rational, Rational>;

// Bit k set when direction n lies in the closed cube face of map k.
unsigned face_mask(const Point3& n) {
  Rational m = 0;
  for (int i = 0; i < 3; ++i) m = std::max(m, Rational(abs(n[i])));
  unsigned mask = 0;
  for (int i = 0; i < 3; ++i)
    if (abs(n[i]) == m) mask |= 1u << (sgn(n[i]) < 0 ? i : i + 3);
  return mask;
}

// Central projection of n on map k (precondition: bit k of face_mask(n)).
Key2 project(int k, const Point3& n) {
  Rational d = abs(n[CubicalGaussianMap::axis(k)]);
  return {n[CubicalGaussianMap::axis_x(k)] / d, n[CubicalGaussianMap::axis_y(k)] / d};
}

CgmLocation location_of(const Rational& x, const Rational& y) {
  int on = (abs(x) == 1) + (abs(y) == 1);
  return on == 2 ? CgmLocation::corner : (on == 1 ? CgmLocation::edge : CgmLocation::interior);
}

// Position of a 2D direction for a counter-clockwise angular order from +X.
bool angle_less(const Rational& ax, const Rational& ay, const Rational& bx, const Rational& by) {
  int ha = (sgn(ay) > 0 || (sgn(ay) == 0 && sgn(ax) > 0)) ? 0 : 1;
  int hb = (sgn(by) > 0 || (sgn(by) == 0 && sgn(bx) > 0)) ? 0 : 1;
  if (ha != hb) return ha < hb;
  return sgn(ax * by - ay * bx) > 0;
}

// Which side of the square a boundary point is on (bit s for side s).
unsigned side_mask(const Rational& x, const Rational& y) {
  unsigned m = 0;
  if (y == -1) m |= 1;
  if (x == 1) m |= 2;
  if (y == 1) m |= 4;
  if (x == -1) m |= 8;
  return m;
}

}  // namespace

struct CgmBuilder {
  struct Seg {
    Index u, w;
    Index edge;  // polytope edge or kNoIndex (artificial)
  };

  static Index vertex_at(CubicalGaussianMap::PlanarMap& m, std::map<Key2, Index>& index, const Key2& p) {
    auto [it, fresh] = index.try_emplace(p, Index(m.vertices.size()));
    if (fresh) {
      CubicalGaussianMap::Vertex v;
      v.x = p.first;
      v.y = p.second;
      v.location = location_of(v.x, v.y);
      m.vertices.push_back(std::move(v));
    }
    return it->second;
  }

  static void build(CubicalGaussianMap& g, const ConvexPolytope& p) {
    g.points_ = p.points();
    g.num_facets_ = p.num_facets();
    g.primal_target_.resize(p.num_halfedges());
    for (Index h = 0; h < p.num_halfedges(); ++h) g.primal_target_[h] = p.target(h);
    std::array<std::map<Key2, Index>, 6> index;
    std::array<std::vector<Seg>, 6> segs;
    for (int k = 0; k < 6; ++k) {
      auto& m = g.maps_[k];
      m = {};
      m.id = k;
      for (int c = 0; c < 4; ++c)
        m.corner[c] = vertex_at(m, index[k], {Rational(c & 2 ? 1 : -1), Rational(c & 1 ? 1 : -1)});
    }
    // Facet normals.
    std::vector<Point3> normal(p.num_facets());
    for (Index f = 0; f < p.num_facets(); ++f) {
      normal[f] = p.plane(f).normal();
      unsigned mask = face_mask(normal[f]);
      for (int k = 0; k < 6; ++k) {
        if (!(mask >> k & 1)) continue;
        Index v = vertex_at(g.maps_[k], index[k], project(k, normal[f]));
        auto& vx = g.maps_[k].vertices[v];
        vx.real = true;
        vx.facet = f;
        vx.plane = p.plane(f);
      }
    }
    // Arcs.
    for (Index e = 0; e < p.num_edges(); ++e) {
      const Point3& n1 = normal[p.facet(2 * e)];
      const Point3& n2 = normal[p.facet(2 * e + 1)];
      const Point3 d = n2 - n1;
      std::vector<Rational> ts = {Rational(0), Rational(1)};
      for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
          for (int s = -1; s <= 1; s += 2) {
            // n1_i + t d_i = s (n1_j + t d_j)
            Rational den = d[i] - s * d[j];
            if (sgn(den) == 0) continue;
            Rational t = (s * n1[j] - n1[i]) / den;
            if (sgn(t) > 0 && cmp(t, 1) < 0) ts.push_back(t);
          }
      std::sort(ts.begin(), ts.end());
      ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
      auto at = [&](const Rational& t) { return n1 + t * d; };
      std::size_t i = 0;
      while (i + 1 < ts.size()) {
        unsigned mask = face_mask(at((ts[i] + ts[i + 1]) / 2));
        std::size_t j = i + 1;
        while (j + 1 < ts.size() && face_mask(at((ts[j] + ts[j + 1]) / 2)) == mask) ++j;
        Point3 a = at(ts[i]), b = at(ts[j]);
        for (int k = 0; k < 6; ++k) {
          if (!(mask >> k & 1)) continue;
          auto& m = g.maps_[k];
          Index u = vertex_at(m, index[k], project(k, a)), w = vertex_at(m, index[k], project(k, b));
          if (i > 0 && !m.vertices[u].real) m.vertices[u].arc_edge = e;
          if (j + 1 < ts.size() && !m.vertices[w].real) m.vertices[w].arc_edge = e;
          segs[k].push_back({u, w, e});
        }
        i = j;
      }
    }
    for (int k = 0; k < 6; ++k) finish_map(g, k, segs[k], p);
    link_chains(g);
  }

  static void finish_map(CubicalGaussianMap& g, int k, std::vector<Seg>& segs, const ConvexPolytope& p) {
    auto& m = g.maps_[k];
    std::map<std::pair<Index, Index>, Index> boundary_real;  // (min, max) vertex -> edge
    std::vector<Seg> edges;
    for (const Seg& s : segs) {
      const auto& a = m.vertices[s.u];
      const auto& b = m.vertices[s.w];
      unsigned common = side_mask(a.x, a.y) & side_mask(b.x, b.y);
      if (common) boundary_real[{std::min(s.u, s.w), std::max(s.u, s.w)}] = s.edge;
      else edges.push_back(s);
    }
    // Sides of the square, counter-clockwise.
    static const int start_corner[4] = {0, 2, 3, 1};
    for (int side = 0; side < 4; ++side) {
      std::vector<Index> on;
      for (Index v = 0; v < m.vertices.size(); ++v)
        if (side_mask(m.vertices[v].x, m.vertices[v].y) >> side & 1) on.push_back(v);
      // Sort along the side's direction.
      auto key = [&](Index v) -> Rational {
        const auto& x = m.vertices[v];
        switch (side) {
          case 0: return x.x;
          case 1: return x.y;
          case 2: return -x.x;
          default: return -x.y;
        }
      };
      std::sort(on.begin(), on.end(), [&](Index a, Index b) { return cmp(key(a), key(b)) < 0; });
      if (on.front() != m.corner[start_corner[side]]) throw std::logic_error("cgm: square side does not start at its corner");
      for (std::size_t t = 0; t + 1 < on.size(); ++t) {
        Index u = on[t], w = on[t + 1];
        auto it = boundary_real.find({std::min(u, w), std::max(u, w)});
        Index e = kNoIndex;
        if (it != boundary_real.end()) {
          e = it->second;
          boundary_real.erase(it);
        }
        edges.push_back({u, w, e});
      }
    }
    if (!boundary_real.empty()) throw std::logic_error("cgm: an arc on a cube edge spans several boundary pieces");

    // DCEL.  Halfedge 2i runs u -> w of edges[i], 2i + 1 runs back.
    const Index nh = Index(2 * edges.size());
    m.halfedges.assign(nh, {});
    std::vector<std::vector<Index>> out(m.vertices.size());
    for (Index i = 0; i < edges.size(); ++i) {
      const Seg& s = edges[i];
      for (int dir = 0; dir < 2; ++dir) {
        auto& h = m.halfedges[2 * i + dir];
        h.origin = dir ? s.w : s.u;
        h.twin = 2 * i + 1 - dir;
        h.real = s.edge != kNoIndex;
        out[h.origin].push_back(2 * i + dir);
      }
      if (s.edge != kNoIndex) {
        // The primal halfedge whose target is the vertex on the left.
        for (int dir = 0; dir < 2; ++dir) {
          Index hu = dir ? s.w : s.u, hw = dir ? s.u : s.w;
          Point3 U = g.lift(k, hu), W = g.lift(k, hw);
          Point3 o;
          o[CubicalGaussianMap::axis(k)] = Rational(CubicalGaussianMap::sign(k));
          Point3 left = cross(o, W - U);
          Index h0 = 2 * s.edge;
          int sd = sgn(dot(left, p.point(p.target(h0)) - p.point(p.origin(h0))));
          if (sd == 0) throw std::logic_error("cgm: degenerate arc segment");
          m.halfedges[2 * i + dir].primal = sd > 0 ? h0 : h0 + 1;
        }
      }
    }
    for (Index v = 0; v < m.vertices.size(); ++v) {
      auto& o = out[v];
      const auto& pv = m.vertices[v];
      auto dir_of = [&](Index h) {
        const auto& q = m.vertices[m.halfedges[m.halfedges[h].twin].origin];
        return std::make_pair(Rational(q.x - pv.x), Rational(q.y - pv.y));
      };
      std::sort(o.begin(), o.end(), [&](Index a, Index b) {
        auto da = dir_of(a), db = dir_of(b);
        return angle_less(da.first, da.second, db.first, db.second);
      });
      if (o.empty()) throw std::logic_error("cgm: isolated map vertex");
      m.vertices[v].halfedge = o[0];
      for (std::size_t t = 0; t < o.size(); ++t) {
        // next(twin(o[t])) = the clockwise successor of o[t] around v.
        Index in = m.halfedges[o[t]].twin;
        Index nx = o[(t + o.size() - 1) % o.size()];
        m.halfedges[in].next = nx;
        m.halfedges[nx].prev = in;
      }
    }
    // Faces.
    for (Index h = 0; h < nh; ++h) {
      if (m.halfedges[h].face != kNoIndex) continue;
      Index f = Index(m.faces.size());
      m.faces.push_back({h, false, kNoIndex});
      Index x = h;
      do {
        m.halfedges[x].face = f;
        if (m.faces[f].vertex == kNoIndex && m.halfedges[x].real) m.faces[f].vertex = p.target(m.halfedges[x].primal);
        x = m.halfedges[x].next;
      } while (x != h);
    }
    // Side lists; the unbounded face lies right of them.
    for (int side = 0; side < 4; ++side) {
      m.side[side].clear();
      Index v = m.corner[start_corner[side]];
      Index end = m.corner[start_corner[(side + 1) % 4]];
      while (v != end) {
        Index step = kNoIndex;
        for (Index h : out[v]) {
          const auto& a = m.vertices[v];
          const auto& b = m.vertices[m.halfedges[m.halfedges[h].twin].origin];
          if (!((side_mask(a.x, a.y) & side_mask(b.x, b.y)) >> side & 1)) continue;
          bool forward = side == 0 ? cmp(b.x, a.x) > 0
                         : side == 1 ? cmp(b.y, a.y) > 0
                         : side == 2 ? cmp(b.x, a.x) < 0
                                     : cmp(b.y, a.y) < 0;
          if (forward) step = h;
        }
        if (step == kNoIndex) throw std::logic_error("cgm: broken square side");
        m.side[side].push_back(step);
        v = m.halfedges[m.halfedges[step].twin].origin;
      }
    }
    Index outer = m.halfedges[m.side[0][0]].twin;
    m.faces[m.halfedges[outer].face].unbounded = true;
    m.faces[m.halfedges[outer].face].vertex = kNoIndex;
    // Faces bounded by artificial edges only: the whole square, dual of the
    // support vertex of the cube face's direction.
    for (auto& f : m.faces) {
      if (f.unbounded || f.vertex != kNoIndex) continue;
      Point3 o;
      o[CubicalGaussianMap::axis(k)] = Rational(CubicalGaussianMap::sign(k));
      Index best = 0;
      for (Index v = 1; v < p.num_vertices(); ++v)
        if (cmp(dot(o, p.point(v)), dot(o, p.point(best))) > 0) best = v;
      f.vertex = best;
    }
  }

  static void link_chains(CubicalGaussianMap& g) {
    std::map<Point3, std::vector<CubicalGaussianMap::VertexRef>> copies;
    for (int k = 0; k < 6; ++k)
      for (Index v = 0; v < g.maps_[k].vertices.size(); ++v)
        if (g.maps_[k].vertices[v].location != CgmLocation::interior) copies[g.lift(k, v)].push_back({k, v});
    for (auto& [pt, refs] : copies) {
      if (refs.size() == 2) {
        g.maps_[refs[0].map].vertices[refs[0].vertex].link = refs[1];
        g.maps_[refs[1].map].vertices[refs[1].vertex].link = refs[0];
      } else if (refs.size() == 3) {
        // Clockwise seen from outside: next(a) = b when <o_a x o_b, corner> < 0.
        for (const auto& a : refs)
          for (const auto& b : refs) {
            if (a == b) continue;
            Point3 oa, ob;
            oa[CubicalGaussianMap::axis(a.map)] = Rational(CubicalGaussianMap::sign(a.map));
            ob[CubicalGaussianMap::axis(b.map)] = Rational(CubicalGaussianMap::sign(b.map));
            if (sgn(dot(cross(oa, ob), pt)) < 0) g.maps_[a.map].vertices[a.vertex].link = b;
          }
      } else {
        throw std::logic_error("cgm: a cube edge or corner point has " + std::to_string(refs.size()) + " copies");
      }
    }
  }
};

CubicalGaussianMap CubicalGaussianMap::from_polytope(const ConvexPolytope& p) {
  CubicalGaussianMap g;
  CgmBuilder::build(g, p);
  return g;
}

std::vector<CubicalGaussianMap::VertexRef> CubicalGaussianMap::chain(int k, Index v) const {
  std::vector<VertexRef> r{{k, v}};
  VertexRef x = maps_[k].vertices[v].link;
  while (x.map >= 0 && !(x == r[0]) && r.size() < 4) {
    r.push_back(x);
    x = maps_[x.map].vertices[x.vertex].link;
  }
  return r;
}

std::string CubicalGaussianMap::check_invariants() const {
  for (int k = 0; k < 6; ++k) {
    const PlanarMap& m = maps_[k];
    const std::string where = "map " + std::to_string(k) + ": ";
    long V = long(m.vertices.size()), E = long(m.halfedges.size() / 2), F = long(m.faces.size());
    if (V - E + F != 2) return where + "V - E + F != 2";
    int unbounded = 0;
    for (const auto& f : m.faces) {
      unbounded += f.unbounded;
      if (!f.unbounded && f.vertex == kNoIndex) return where + "a bounded face without primal vertex";
    }
    if (unbounded != 1) return where + "not exactly one unbounded face";
    for (Index h = 0; h < m.halfedges.size(); ++h) {
      const auto& x = m.halfedges[h];
      if (m.halfedges[x.twin].twin != h || m.halfedges[x.next].prev != h) return where + "broken halfedge links";
      if (m.halfedges[x.next].origin != m.halfedges[x.twin].origin) return where + "next does not start at target";
      if (m.halfedges[x.twin].real != x.real) return where + "twin real flags differ";
      if (x.real && !m.faces[x.face].unbounded && primal_target_[x.primal] != m.faces[x.face].vertex)
        return where + "a face's halfedges disagree on its primal vertex";
      if (x.real && x.primal >> 1 != m.halfedges[x.twin].primal >> 1) return where + "twins on different arcs";
    }
    // The unbounded face is the square.
    Index outer = m.halfedges[m.side[0][0]].twin;
    std::size_t sides = 0;
    for (int s = 0; s < 4; ++s) {
      sides += m.side[s].size();
      for (Index h : m.side[s])
        if (!m.faces[m.halfedges[m.halfedges[h].twin].face].unbounded) return where + "side halfedge not on the unbounded face";
    }
    std::size_t len = 0;
    Index x = outer;
    do {
      ++len;
      x = m.halfedges[x].next;
    } while (x != outer && len <= m.halfedges.size());
    if (len != sides) return where + "the unbounded face is not the square";
    for (int c = 0; c < 4; ++c) {
      const auto& v = m.vertices[m.corner[c]];
      if (v.x != (c & 2 ? 1 : -1) || v.y != (c & 1 ? 1 : -1) || v.location != CgmLocation::corner)
        return where + "corner vertex misplaced";
    }
    for (Index v = 0; v < m.vertices.size(); ++v) {
      const auto& vx = m.vertices[v];
      if (vx.location != location_of(vx.x, vx.y)) return where + "wrong vertex location";
      if (cmp(abs(vx.x), 1) > 0 || cmp(abs(vx.y), 1) > 0) return where + "vertex outside the square";
      auto ch = chain(k, v);
      std::size_t want = vx.location == CgmLocation::corner ? 3 : (vx.location == CgmLocation::edge ? 2 : 1);
      if (ch.size() != want) return where + "chain of wrong length";
      if (want > 1 && !(maps_[ch.back().map].vertices[ch.back().vertex].link == ch[0])) return where + "chain not cyclic";
      for (const auto& r : ch) {
        if (!(lift(r.map, r.vertex) == lift(k, v))) return where + "chain links different points";
        const auto& o = maps_[r.map].vertices[r.vertex];
        if (o.real != vx.real || o.facet != vx.facet) return where + "chain copies disagree";
      }
    }
  }
  return {};
}

ConvexPolytope CubicalGaussianMap::to_polytope() const {
  std::vector<std::vector<Index>> around(num_facets_);
  std::vector<Plane> plane(num_facets_);
  std::vector<char> seen(num_facets_, 0);
  for (int k = 0; k < 6; ++k) {
    const PlanarMap& m = maps_[k];
    for (Index v = 0; v < m.vertices.size(); ++v) {
      const Vertex& vx = m.vertices[v];
      if (!vx.real) continue;
      seen[vx.facet] = 1;
      plane[vx.facet] = vx.plane;
      Index h = vx.halfedge;
      do {
        const Face& f = m.faces[m.halfedges[h].face];
        if (!f.unbounded) around[vx.facet].push_back(f.vertex);
        h = m.halfedges[m.halfedges[h].prev].twin;  // next outgoing, counter-clockwise
      } while (h != vx.halfedge);
    }
  }
  Mesh mesh;
  std::vector<Index> renum(points_.size(), kNoIndex);
  for (Index f = 0; f < num_facets_; ++f) {
    if (!seen[f]) throw std::logic_error("cgm: a facet has no map vertex");
    auto& vs = around[f];
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    if (vs.size() < 3) throw std::logic_error("cgm: a facet has fewer than 3 vertices");
    // Counter-clockwise about the facet normal (the points are in convex position).
    const Point3 N = plane[f].normal();
    Point3 c = points_[vs[0]];
    for (std::size_t t = 1; t < vs.size(); ++t) c = c + points_[vs[t]];
    c = Rational(1, vs.size()) * c;
    const Point3 r = points_[vs[0]] - c;
    auto half = [&](Index q) {
      Point3 d = points_[q] - c;
      int s = sgn(dot(N, cross(r, d)));
      if (s != 0) return s > 0 ? 0 : 1;
      return sgn(dot(r, d)) > 0 ? 0 : 1;
    };
    std::sort(vs.begin(), vs.end(), [&](Index a, Index b) {
      int ha = half(a), hb = half(b);
      if (ha != hb) return ha < hb;
      return sgn(dot(N, cross(points_[a] - c, points_[b] - c))) > 0;
    });
    std::vector<Index> poly;
    for (Index q : vs) {
      if (renum[q] == kNoIndex) {
        renum[q] = Index(mesh.points.size());
        mesh.points.push_back(points_[q]);
      }
      poly.push_back(renum[q]);
    }
    mesh.faces.push_back(std::move(poly));
  }
  return ConvexPolytope::from_mesh(mesh, "cubical Gaussian map");
}

void CubicalGaussianMap::set_operands(const std::vector<std::pair<Index, Index>>& origin, const ConvexPolytope& s) {
  for (auto& m : maps_)
    for (auto& h : m.halfedges) {
      h.operands = 0;
      if (!h.real) continue;
      auto [i, j] = origin[s.origin(h.primal)];
      auto [k, l] = origin[s.target(h.primal)];
      if (i != k) h.operands |= 1;
      if (j != l) h.operands |= 2;
    }
}

}  // namespace minksum
