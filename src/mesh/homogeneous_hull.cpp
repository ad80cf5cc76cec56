// The exact convex hull of homogeneous integer points by Quickhull
// (mesh/homogeneous_hull.hpp has the algorithm and why it is exact).
#include "mesh/homogeneous_hull.hpp"

#include <minksum/polytope.hpp>  // Index, kNoIndex

#include <CGAL/FPU.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace minksum {

namespace {

using detail::HomogeneousPlane;
using detail::HomogeneousPoint;

struct Facet {
  std::array<Index, 3> v{}, nb{kNoIndex, kNoIndex, kNoIndex};
  HomogeneousPlane plane;
  std::vector<Index> outside;
  Index farthest = kNoIndex;
  double far = -std::numeric_limits<double>::infinity();
  unsigned seen = 0;  // the round in which `visible` was decided
  bool visible = false;
  bool alive = true;
};

class Quickhull {
 public:
  explicit Quickhull(const std::vector<HomogeneousPoint>& points) : p_(points) {}

  HomogeneousHull run() {
    start();
    for (Index t = 0; t < f_.size(); ++t)
      if (!f_[t].outside.empty()) todo_.push_back(t);
    while (!todo_.empty()) {
      const Index t = todo_.back();
      todo_.pop_back();
      if (f_[t].alive && !f_[t].outside.empty()) add(f_[t].farthest, t);
    }
    return result();
  }

 private:
  const std::vector<HomogeneousPoint>& p_;
  std::vector<Facet> f_;
  std::vector<Index> todo_;
  unsigned round_ = 0;
  std::vector<Index> start_of_;     // horizon vertex -> the new facet whose horizon edge starts there
  std::vector<unsigned> start_round_;

  int side(const Facet& t, Index x) const { return detail::side(t.plane, p_[t.v[0]], p_[t.v[1]], p_[t.v[2]], p_[x]); }
  int side(Index a, Index b, Index c, Index x) const {
    return detail::side(detail::homogeneous_plane(p_[a], p_[b], p_[c]), p_[a], p_[b], p_[c], p_[x]);
  }

  // The height of x above t's plane, up to t's scale (doubles: which point
  // of an outside set goes first is a choice, not a decision).
  double height(const Facet& t, Index x) const {
    const auto& s = t.plane.s;
    const auto& q = p_[x].s;
    const FastInterval v = s[0] * q[0] + s[1] * q[1] + s[2] * q[2] + s[3] * q[3];
    return 0.5 * (v.inf() + v.sup()) / q[3].sup();
  }

  Index make(Index a, Index b, Index c) {
    Facet t;
    t.v = {a, b, c};
    t.plane = detail::homogeneous_plane(p_[a], p_[b], p_[c]);
    f_.push_back(std::move(t));
    return Index(f_.size() - 1);
  }

  // x goes to the outside set of the first facet of `candidates` it lies
  // strictly beyond; false if none.
  template <class Range>
  bool assign(Index x, const Range& candidates) {
    for (Index t : candidates) {
      Facet& g = f_[t];
      if (side(g, x) > 0) {
        g.outside.push_back(x);
        const double h = height(g, x);
        if (g.farthest == kNoIndex || h > g.far) g.farthest = x, g.far = h;
        return true;
      }
    }
    return false;
  }

  // Whether points i and j are the same point: x_i w_j = x_j w_i for each
  // coordinate.
  bool same(Index i, Index j) const {
    if (i == j) return true;
    for (int k = 0; k < 3; ++k)
      if (p_[i].c[k] * p_[j].c[3] != p_[j].c[k] * p_[i].c[3]) return false;
    return true;
  }

  // A start tetrahedron: two points far apart along an axis (by doubles),
  // a third far from their line, then the first point off their plane
  // (exact); if the three are collinear exactly, other thirds in turn.
  void start() {
    const Index n = Index(p_.size());
    if (n < 4) throw std::invalid_argument("homogeneous_hull: fewer than four points");
    auto coord = [&](Index i, int k) { return 0.5 * (p_[i].s[k].inf() + p_[i].s[k].sup()) / p_[i].s[3].sup(); };
    Index a = 0, b = 0;
    double spread = -1;
    for (int k = 0; k < 3; ++k) {
      Index lo = 0, hi = 0;
      for (Index i = 1; i < n; ++i) {
        if (coord(i, k) < coord(lo, k)) lo = i;
        if (coord(i, k) > coord(hi, k)) hi = i;
      }
      if (coord(hi, k) - coord(lo, k) > spread) spread = coord(hi, k) - coord(lo, k), a = lo, b = hi;
    }
    // b a point other than a exactly (a repeated point may share a's doubles
    // or even be a's copy with another w).
    if (same(a, b)) {
      b = kNoIndex;
      for (Index i = 0; i < n && b == kNoIndex; ++i)
        if (!same(a, i)) b = i;
      if (b == kNoIndex) throw std::invalid_argument("homogeneous_hull: the points do not span three dimensions");
    }
    // Thirds by decreasing distance from the line ab (doubles).
    std::vector<std::pair<double, Index>> thirds;
    thirds.reserve(n);
    const double ax = coord(a, 0), ay = coord(a, 1), az = coord(a, 2);
    const double ux = coord(b, 0) - ax, uy = coord(b, 1) - ay, uz = coord(b, 2) - az;
    for (Index i = 0; i < n; ++i) {
      if (i == a || i == b) continue;
      const double vx = coord(i, 0) - ax, vy = coord(i, 1) - ay, vz = coord(i, 2) - az;
      const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      thirds.emplace_back(-(cx * cx + cy * cy + cz * cz), i);
    }
    std::sort(thirds.begin(), thirds.end());
    for (const auto& [unused, c] : thirds) {
      const HomogeneousPlane h = detail::homogeneous_plane(p_[a], p_[b], p_[c]);
      // The fourth: the farthest off the plane by doubles, else the first
      // off it exactly.
      Index d = kNoIndex;
      double best = -1;
      for (Index i = 0; i < n; ++i) {
        if (i == a || i == b || i == c) continue;
        const auto& q = p_[i].s;
        const FastInterval v = h.s[0] * q[0] + h.s[1] * q[1] + h.s[2] * q[2] + h.s[3] * q[3];
        const double hgt = std::fabs(0.5 * (v.inf() + v.sup()) / q[3].sup());
        if (hgt > best) best = hgt, d = i;
      }
      if (d == kNoIndex || detail::side(h, p_[a], p_[b], p_[c], p_[d]) == 0) {
        d = kNoIndex;
        for (Index i = 0; i < n && d == kNoIndex; ++i)
          if (i != a && i != b && i != c && detail::side(h, p_[a], p_[b], p_[c], p_[i]) != 0) d = i;
      }
      if (d == kNoIndex) continue;  // a, b, c collinear, or every point on their plane
      tetrahedron(a, b, c, d);
      const std::array<Index, 4> faces{0, 1, 2, 3};
      for (Index i = 0; i < n; ++i)
        if (i != a && i != b && i != c && i != d) assign(i, faces);
      return;
    }
    throw std::invalid_argument("homogeneous_hull: the points do not span three dimensions");
  }

  // The four facets of the tetrahedron abcd (not coplanar), each oriented so
  // that the fourth corner is beneath it, and linked.
  void tetrahedron(Index a, Index b, Index c, Index d) {
    const std::array<std::array<Index, 4>, 4> faces{{{a, b, c, d}, {a, b, d, c}, {a, c, d, b}, {b, c, d, a}}};
    for (const auto& q : faces) {
      if (side(q[0], q[1], q[2], q[3]) > 0) make(q[0], q[2], q[1]);
      else make(q[0], q[1], q[2]);
    }
    for (Index t = 0; t < 4; ++t)
      for (int k = 0; k < 3; ++k) {
        const Index u = f_[t].v[k], w = f_[t].v[(k + 1) % 3];
        for (Index g = 0; g < 4; ++g)
          for (int j = 0; j < 3; ++j)
            if (f_[g].v[j] == w && f_[g].v[(j + 1) % 3] == u) f_[t].nb[k] = g;
      }
  }

  // Adds the point `eye`, strictly beyond facet t.
  void add(Index eye, Index t0) {
    ++round_;
    std::vector<Index> visible{t0};
    f_[t0].seen = round_;
    f_[t0].visible = true;
    for (std::size_t i = 0; i < visible.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        Facet& g = f_[f_[visible[i]].nb[k]];
        if (g.seen == round_) continue;
        g.seen = round_;
        g.visible = side(g, eye) > 0;
        if (g.visible) visible.push_back(f_[visible[i]].nb[k]);
      }
    // The horizon: edges of visible facets whose neighbour is not visible,
    // each the base of a new facet towards the eye.
    if (start_of_.size() < p_.size()) start_of_.assign(p_.size(), kNoIndex), start_round_.assign(p_.size(), 0);
    std::vector<Index> made;
    for (Index t : visible)
      for (int k = 0; k < 3; ++k) {
        const Index g = f_[t].nb[k];
        if (f_[g].visible && f_[g].seen == round_) continue;
        const Index u = f_[t].v[k], w = f_[t].v[(k + 1) % 3];
        const Index n = make(u, w, eye);
        made.push_back(n);
        f_[n].nb[0] = g;
        Facet& other = f_[g];
        for (int j = 0; j < 3; ++j)
          if (other.v[j] == w && other.v[(j + 1) % 3] == u) other.nb[j] = n;
        if (start_round_[u] == round_) throw std::logic_error("homogeneous_hull: the horizon is not a simple cycle");
        start_round_[u] = round_;
        start_of_[u] = n;
      }
    for (Index n : made) {
      const Index w = f_[n].v[1];
      if (start_round_[w] != round_) throw std::logic_error("homogeneous_hull: the horizon is not a cycle");
      const Index m = start_of_[w];
      f_[n].nb[1] = m;
      f_[m].nb[2] = n;
    }
    // The visible facets' points go to the new facets (or are inside).
    for (Index t : visible) {
      Facet& g = f_[t];
      g.alive = false;
      for (Index x : g.outside)
        if (x != eye) assign(x, made);
      std::vector<Index>().swap(g.outside);
    }
    for (Index n : made)
      if (!f_[n].outside.empty()) todo_.push_back(n);
  }

  HomogeneousHull result() const {
    std::vector<Index> number(f_.size(), kNoIndex);
    HomogeneousHull h;
    for (Index t = 0; t < f_.size(); ++t)
      if (f_[t].alive) {
        number[t] = Index(h.triangles.size());
        h.triangles.push_back(f_[t].v);
      }
    h.neighbour.resize(h.triangles.size());
    h.flat.resize(h.triangles.size());
    for (Index t = 0; t < f_.size(); ++t) {
      if (!f_[t].alive) continue;
      const Index i = number[t];
      for (int k = 0; k < 3; ++k) {
        const Index g = f_[t].nb[k];
        h.neighbour[i][k] = number[g];
        // The neighbour's corner off the shared edge, on t's plane or not.
        Index off = kNoIndex;
        for (Index v : f_[g].v)
          if (v != f_[t].v[k] && v != f_[t].v[(k + 1) % 3]) off = v;
        h.flat[i][k] = side(f_[t], off) == 0;
      }
    }
    return h;
  }
};

}  // namespace

HomogeneousHull homogeneous_hull(const std::vector<detail::HomogeneousPoint>& points) {
  if (CGAL::FPU_get_cw() != CGAL_FE_UPWARD)
    throw std::logic_error("homogeneous_hull: called without the upward rounding guard its interval filter needs");
  return Quickhull(points).run();
}

}  // namespace minksum
