// Non-convex catalog solids: tube, lshape, ring:N, star:N, gear:N — prisms
// over a plane profile — and torus:M:N, a triangulated torus, for the sums
// of docs/nonconvex.md.
#include "catalog/catalog_internal.hpp"

namespace minksum::catalog_detail {

namespace {

using Profile = std::vector<std::array<Rational, 2>>;

// The prism over `outer` (a simple polygon, counter-clockwise seen from +z)
// between z = lo and z = hi.  With `inner` (the same number of points, each
// on the segment from the origin to the outer point of the same index, the
// origin strictly inside), the prism over the ring between them: caps made of
// the quadrilaterals outer[i] outer[i+1] inner[i+1] inner[i]; without, each
// cap is one polygon.  Faces counter-clockwise seen from outside.
Mesh prism(const Profile& outer, const Profile& inner, const Rational& lo, const Rational& hi) {
  Mesh m;
  const Index n = Index(outer.size());
  auto add = [&](const Profile& loop, const Rational& z) {
    for (const auto& p : loop) m.points.push_back(Point3(p[0], p[1], z));
  };
  add(outer, lo);  // 0 .. n-1
  add(outer, hi);  // n .. 2n-1
  const Index ob = 0, ot = n, ib = 2 * n, it = 3 * n;
  for (Index i = 0; i < n; ++i) {
    const Index j = (i + 1) % n;
    m.faces.push_back({ob + i, ob + j, ot + j, ot + i});
  }
  if (inner.empty()) {
    std::vector<Index> bottom, top;
    for (Index i = 0; i < n; ++i) {
      bottom.push_back(ob + n - 1 - i);
      top.push_back(ot + i);
    }
    m.faces.push_back(bottom);
    m.faces.push_back(top);
    return m;
  }
  add(inner, lo);
  add(inner, hi);
  for (Index i = 0; i < n; ++i) {
    const Index j = (i + 1) % n;
    m.faces.push_back({ib + j, ib + i, it + i, it + j});  // the hole's wall, facing the axis
    m.faces.push_back({ot + i, ot + j, it + j, it + i});  // top, seen from above
    m.faces.push_back({ob + j, ob + i, ib + i, ib + j});  // bottom, seen from below
  }
  return m;
}

// Point k of n on the circle of radius r (deterministic doubles, scaled exactly).
std::array<Rational, 2> circle(std::uint64_t k, std::uint64_t n, const Rational& r) {
  const auto p = unit_circle_point(k, n);
  return {Rational(p[0]) * r, Rational(p[1]) * r};
}

Profile scaled(const Profile& p, const Rational& s) {
  Profile q;
  for (const auto& v : p) q.push_back({v[0] * s, v[1] * s});
  return q;
}

}  // namespace

Mesh make_tube(const Rational& hole) {
  const Profile outer = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  return prism(outer, scaled(outer, hole / 2), -1, 1);
}

Mesh make_lshape() {
  const Profile outer = {{-1, -1}, {1, -1}, {1, 0}, {0, 0}, {0, 1}, {-1, 1}};
  return prism(outer, {}, Rational(-1, 2), Rational(1, 2));
}

Mesh make_ring(std::uint64_t n) {
  Profile outer;
  for (std::uint64_t k = 0; k < n; ++k) outer.push_back(circle(k, n, 1));
  return prism(outer, scaled(outer, Rational(1, 2)), Rational(-1, 4), Rational(1, 4));
}

Mesh make_star(std::uint64_t n) {
  Profile outer;
  for (std::uint64_t k = 0; k < 2 * n; ++k) outer.push_back(circle(k, 2 * n, k % 2 ? Rational(1, 2) : Rational(1)));
  return prism(outer, {}, Rational(-1, 4), Rational(1, 4));
}

Mesh make_gear(std::uint64_t n) {
  Profile outer, inner;
  for (std::uint64_t k = 0; k < 4 * n; ++k) {
    const bool tip = k % 4 == 1 || k % 4 == 2;
    outer.push_back(circle(k, 4 * n, tip ? Rational(1) : Rational(3, 4)));
    inner.push_back(circle(k, 4 * n, Rational(1, 4)));
  }
  return prism(outer, inner, Rational(-1, 4), Rational(1, 4));
}

Mesh make_torus(std::uint64_t m, std::uint64_t n) {
  // Point (i, j): angle i of m about the z axis, angle j of n about the
  // tube's core circle (radius 1), tube radius 1/3; each coordinate the
  // double that IEEE arithmetic gives from the circle's doubles (the same on
  // every machine), as a mesh read from a file has.
  Mesh t;
  for (std::uint64_t i = 0; i < m; ++i) {
    const auto a = unit_circle_point(i, m);
    for (std::uint64_t j = 0; j < n; ++j) {
      const auto b = unit_circle_point(j, n);
      const double radius = 1.0 + b[0] / 3.0;
      t.points.push_back(Vec3d{a[0] * radius, a[1] * radius, b[1] / 3.0});
    }
  }
  auto at = [&](std::uint64_t i, std::uint64_t j) { return Index((i % m) * n + j % n); };
  for (std::uint64_t i = 0; i < m; ++i)
    for (std::uint64_t j = 0; j < n; ++j) {
      // The quadrilateral (i, j) (i+1, j) (i+1, j+1) (i, j+1), outward, as two triangles.
      t.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return t;
}

}  // namespace minksum::catalog_detail
