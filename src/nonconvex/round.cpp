// round_solid: an exact solid boundary written in doubles (or floats) as a
// valid solid (docs/nonconvex.md, "Output").
//
// The exact faces are cut into triangles exactly, every coordinate is
// rounded, points that round to the same point are merged, and the
// triangles that rounding made degenerate are removed while keeping the
// surface closed: a triangle with a repeated vertex goes; two triangles on
// the same three points facing opposite ways cancel; a triangle whose three
// points became collinear goes and the triangle across its longest side is
// split at the middle point.  The result must pass validate_solid, the same
// exact checks as any input solid.  When it does not (rounding made two faces
// cross), the points are snapped to a coarser grid of 2^e and the same steps
// are repeated, e growing one at a time from the precision of the format:
// points that are close merge, and the slivers between them disappear.  The
// largest distance a point moved is reported.
#include <minksum/error.hpp>
#include <minksum/nonconvex.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace minksum {

namespace {

struct Key {
  double x, y, z;
  friend bool operator<(const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
  }
};

using Tri = std::array<Index, 3>;

// Whether q lies strictly between p and r on the segment p r (all exact
// doubles; the points are collinear).
bool strictly_between(const Point3& p, const Point3& q, const Point3& r) {
  const Point3 d = r - p;
  const Rational t = dot(q - p, d);
  return sgn(t) > 0 && cmp(t, dot(d, d)) < 0;
}

// Removes the triangles that rounding made degenerate, keeping every
// directed edge matched (see the file comment).  False when a collinear
// triangle has no triangle across its longest side (the surface is not
// closed there): this grid is not usable.
bool clean(std::vector<Tri>& tris, const std::vector<Point3>& pts) {
  for (bool changed = true; changed;) {
    changed = false;
    // Repeated vertices.
    std::vector<Tri> kept;
    kept.reserve(tris.size());
    for (const Tri& t : tris)
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) kept.push_back(t);
    changed |= kept.size() != tris.size();
    tris = std::move(kept);
    // Opposite triangles on the same three points cancel.
    {
      std::map<std::array<Index, 3>, std::vector<std::size_t>> by_set;
      for (std::size_t i = 0; i < tris.size(); ++i) {
        std::array<Index, 3> s = tris[i];
        std::sort(s.begin(), s.end());
        by_set[s].push_back(i);
      }
      std::vector<char> gone(tris.size(), 0);
      auto rotation_of = [](const Tri& t) {  // the rotation starting at the smallest index
        int k = 0;
        for (int i = 1; i < 3; ++i)
          if (t[i] < t[k]) k = i;
        return Tri{t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
      };
      for (auto& [s, list] : by_set) {
        if (list.size() < 2) continue;
        std::vector<std::size_t> one, other;
        const Tri first = rotation_of(tris[list[0]]);
        for (std::size_t i : list) (rotation_of(tris[i]) == first ? one : other).push_back(i);
        const std::size_t pairs = std::min(one.size(), other.size());
        for (std::size_t k = 0; k < pairs; ++k) gone[one[k]] = gone[other[k]] = 1;
      }
      if (std::find(gone.begin(), gone.end(), 1) != gone.end()) {
        std::vector<Tri> rest;
        for (std::size_t i = 0; i < tris.size(); ++i)
          if (!gone[i]) rest.push_back(tris[i]);
        tris = std::move(rest);
        changed = true;
      }
    }
    // Collinear triangles: the one across the longest side is split.
    std::map<std::pair<Index, Index>, std::size_t> directed;
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (int k = 0; k < 3; ++k) directed[{tris[i][k], tris[i][(k + 1) % 3]}] = i;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const Tri t = tris[i];
      if (!is_zero(cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]))) continue;
      // The vertex strictly inside the opposite side.
      int m = -1;
      for (int k = 0; k < 3; ++k)
        if (strictly_between(pts[t[(k + 1) % 3]], pts[t[k]], pts[t[(k + 2) % 3]])) m = k;
      if (m < 0) return false;  // cannot happen with three distinct collinear points
      const Index c = t[m], a = t[(m + 1) % 3], b = t[(m + 2) % 3];  // t = (c, a, b): side a -> b
      auto across = directed.find({b, a});
      if (across == directed.end() || across->second == i) return false;
      const std::size_t j = across->second;
      const Tri u = tris[j];
      int k = 0;
      while (!(u[k] == b && u[(k + 1) % 3] == a)) ++k;
      const Index x = u[(k + 2) % 3];  // u = (b, a, x)
      tris[j] = Tri{b, c, x};
      tris.push_back(Tri{c, a, x});
      tris[i] = Tri{c, c, c};  // removed by the next pass
      changed = true;
      break;  // the edge map is stale: start again
    }
  }
  return true;
}

double to_format(const Rational& q, bool floats) { return floats ? double(float(to_double(q))) : to_double(q); }

}  // namespace

RoundedSolid round_solid(const Mesh& exact, bool floats, const std::string& name) {
  const Mesh tri = triangulate(exact, name);
  RoundedSolid r;
  std::vector<Point3> pts = tri.points.to_points();
  std::vector<Vec3d> nearest(pts.size());
  double largest = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = to_format(pts[i][k], floats);
      if (!std::isfinite(c[k]))
        throw RoundingError(std::string("a coordinate is beyond the range of ") +
                            (floats ? "32-bit floats" : "doubles"));
      r.rounded_coordinates += Rational(c[k]) != pts[i][k];
      largest = std::max(largest, std::fabs(c[k]));
    }
    nearest[i] = Vec3d{c[0], c[1], c[2]};
  }
  if (r.rounded_coordinates == 0) {
    r.mesh = exact;
    return r;
  }
  // An edge of more than two faces (the exact sum touching itself along it)
  // is not a 2-manifold: validate_solid would refuse any rounding of it.
  {
    std::map<std::pair<Index, Index>, int> edges;
    for (const auto& f : tri.faces)
      for (int k = 0; k < 3; ++k) ++edges[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
    std::size_t touching = 0;
    for (const auto& [e, n] : edges) touching += n != 2;
    if (touching)
      throw RoundingError("the sum touches itself along " + std::to_string(touching) +
                          " edges, which only exact coordinates keep apart");
  }
  if (largest == 0)
    throw RoundingError(std::string("every coordinate rounds to zero: the solid is below the range of ") +
                        (floats ? "32-bit floats" : "doubles"));
  // Grids: none (the nearest values), then 2^e from the format's spacing at
  // the largest coordinate upwards, up to 2^-20 of it.
  int e0 = 0;
  std::frexp(largest, &e0);
  const int steps = floats ? 4 : 33;
  e0 -= floats ? 24 : 53;
  std::string last_problem;
  for (int step = -1; step <= steps; ++step) {
    const double grid = step < 0 ? 0 : std::ldexp(1.0, e0 + step);
    std::map<Key, Index> id;
    std::vector<Point3> at;
    std::vector<Index> map(pts.size());
    double moved = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      Vec3d p = nearest[i];
      if (grid > 0) p = Vec3d{std::nearbyint(p.x / grid) * grid, std::nearbyint(p.y / grid) * grid,
                              std::nearbyint(p.z / grid) * grid};
      auto [it, fresh] = id.emplace(Key{p.x, p.y, p.z}, Index(at.size()));
      if (fresh) at.push_back(Point3(Rational(p.x), Rational(p.y), Rational(p.z)));
      map[i] = it->second;
      const Point3 d = at[it->second] - pts[i];
      // hypot of the components: |d|^2 overflows doubles for coordinates
      // above 2^512 (the displacement was reported as inf).
      moved = std::max(moved, std::hypot(to_double(d.x), to_double(d.y), to_double(d.z)));
    }
    std::vector<Tri> tris;
    for (const auto& f : tri.faces) tris.push_back(Tri{map[f[0]], map[f[1]], map[f[2]]});
    if (!clean(tris, at) || tris.empty()) continue;
    Mesh m;
    std::vector<Index> renumber(at.size(), Index(-1));
    for (Tri& t : tris)
      for (Index& v : t) {
        if (renumber[v] == Index(-1)) {
          renumber[v] = Index(m.points.size());
          m.points.push_back(at[v]);
        }
        v = renumber[v];
      }
    for (const Tri& t : tris) m.faces.push_back({t[0], t[1], t[2]});
    try {
      validate_solid(m, name);
    } catch (const InputError& err) {
      last_problem = err.problem();
      continue;
    }
    r.mesh = std::move(m);
    r.max_displacement = moved;
    r.grid = grid;
    return r;
  }
  if (last_problem.empty())
    throw RoundingError("the rounded surface collapses (every face degenerates, even with points snapped to 2^-20 of "
                        "the largest coordinate)");
  throw RoundingError("the rounded surface is not a valid solid even with points snapped to 2^-20 of the largest "
                      "coordinate (" + last_problem + ")");
}

}  // namespace minksum
