// Convex sets of dimension 0 to 3 (see convex_set.hpp): validation of flat
// polygons and the exact hull of points of any dimension.  Every decision is
// the sign of an exact rational expression.
#include <minksum/convex_set.hpp>
#include <minksum/error.hpp>

#include <algorithm>

namespace minksum {

namespace {

// The coordinate axis along which the plane with normal n is projected
// without collapsing: the one of the largest |n_k| (any nonzero one would
// do; the largest keeps the numbers small).
int drop_axis(const Point3& n) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (cmp(abs(n[i]), abs(n[k])) > 0) k = i;
  return k;
}

// Sign of the 2D cross product of (b - a) and (c - b) in the plane that
// drops axis k: positive for a left turn seen from +e_k.
int turn(const Point3& a, const Point3& b, const Point3& c, int k) {
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  const Rational x1 = b[u] - a[u], y1 = b[v] - a[v], x2 = c[u] - b[u], y2 = c[v] - b[v];
  return sgn(x1 * y2 - y1 * x2);
}

std::string count_text(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

const char* dimension_name(int dimension) {
  switch (dimension) {
    case 0: return "point";
    case 1: return "segment";
    case 2: return "polygon";
    default: return "polytope";
  }
}

ConvexSet::ConvexSet(ConvexPolytope p) : dim_(3), polytope_(std::move(p)) {}

ConvexSet ConvexSet::convex_polygon(std::vector<Point3> loop) {
  ConvexSet out;
  out.dim_ = 2;
  out.vertices_ = std::move(loop);
  out.normal_ = cross(out.vertices_[1] - out.vertices_[0], out.vertices_[2] - out.vertices_[1]);
  return out;
}

ConvexSet ConvexSet::point(const Point3& p) {
  ConvexSet s;
  s.dim_ = 0;
  s.vertices_ = {p};
  return s;
}

ConvexSet ConvexSet::segment(const Point3& a, const Point3& b, const std::string& source) {
  if (a == b) throw InputError(source, "", "zero-length segment (both endpoints are equal; a point is point:X,Y,Z)");
  ConvexSet s;
  s.dim_ = 1;
  s.vertices_ = {a, b};
  return s;
}

ConvexSet ConvexSet::polygon(const std::vector<Point3>& given, const std::string& source) {
  // Weld equal consecutive points (cyclically).
  std::vector<Point3> loop;
  for (const Point3& p : given)
    if (loop.empty() || !(loop.back() == p)) loop.push_back(p);
  while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
  if (loop.size() < 3)
    throw InputError(source, "", "degenerate polygon: " + count_text(loop.size(), "distinct point"));
  // A normal from the first corner that is not collinear; every point must
  // lie in its plane.
  const std::size_t n = loop.size();
  Point3 nrm;
  for (std::size_t i = 2; i < n && is_zero(nrm); ++i) nrm = cross(loop[1] - loop[0], loop[i] - loop[0]);
  if (is_zero(nrm)) throw InputError(source, "", "degenerate polygon: all " + std::to_string(n) + " points are collinear");
  for (std::size_t i = 0; i < n; ++i)
    if (sgn(dot(nrm, loop[i] - loop[0])) != 0)
      throw InputError(source, "vertex " + std::to_string(i), "polygon not planar: the point is off the plane of the others");
  // Drop points in the middle of an edge (a straight corner going on);
  // a corner going back is not convex.
  const int k = drop_axis(nrm);
  for (bool changed = true; changed && loop.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < loop.size() && loop.size() >= 3; ++i) {
      const std::size_t m = loop.size();
      const Point3 &a = loop[(i + m - 1) % m], &b = loop[i], &c = loop[(i + 1) % m];
      if (turn(a, b, c, k) == 0) {
        if (sgn(dot(b - a, c - b)) <= 0)
          throw InputError(source, "vertex " + std::to_string(i), "polygon not convex: its boundary turns back on itself");
        loop.erase(loop.begin() + long(i));
        changed = true;
        break;
      }
    }
  }
  // Every corner turns the same way, and the loop winds around once: the
  // edge directions, in order, pass the direction of the first edge once.
  const std::size_t m = loop.size();
  const int s = turn(loop[m - 1], loop[0], loop[1], k);
  for (std::size_t i = 0; i < m; ++i)
    if (turn(loop[(i + m - 1) % m], loop[i], loop[(i + 1) % m], k) != s)
      throw InputError(source, "vertex " + std::to_string(i), "polygon not convex: a reflex corner");
  {
    // With every turn to the left (after reversing a clockwise loop), the
    // loop is simple when its edge directions go round once: in the angular
    // order from the positive u axis, exactly one step goes back down.
    std::vector<Point3> ccw = loop;
    if (s < 0) std::reverse(ccw.begin(), ccw.end());
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    auto dir = [&](std::size_t i) {
      const Point3& a = ccw[i];
      const Point3& b = ccw[(i + 1) % m];
      return std::pair<Rational, Rational>(b[u] - a[u], b[v] - a[v]);
    };
    auto half = [](const std::pair<Rational, Rational>& d) {
      return sgn(d.second) > 0 || (sgn(d.second) == 0 && sgn(d.first) > 0) ? 0 : 1;
    };
    auto before = [&](const std::pair<Rational, Rational>& a, const std::pair<Rational, Rational>& b) {
      const int ha = half(a), hb = half(b);
      if (ha != hb) return ha < hb;
      return sgn(a.first * b.second - a.second * b.first) > 0;
    };
    std::size_t descents = 0;
    for (std::size_t i = 0; i < m; ++i)
      if (before(dir((i + 1) % m), dir(i))) ++descents;
    if (descents != 1)
      throw InputError(source, "", "polygon not convex: its boundary winds around " + std::to_string(descents) + " times");
  }
  return convex_polygon(std::move(loop));
}

ConvexSet ConvexSet::hull(const PointList& points, const std::string& source) {
  return hull(points.to_points(), source);
}

ConvexSet ConvexSet::hull(const std::vector<Point3>& given, const std::string& source) {
  if (given.empty()) throw InputError(source, "", "no points");
  std::vector<Point3> pts = given;
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() == 1) return point(pts[0]);
  const Point3 d = pts[1] - pts[0];
  Point3 nrm;
  for (std::size_t i = 2; i < pts.size() && is_zero(nrm); ++i) nrm = cross(d, pts[i] - pts[0]);
  if (is_zero(nrm)) {
    // Collinear: the two extremes along d (lexicographic order is monotone
    // along a line, so they are the first and the last).
    return segment(pts.front(), pts.back(), source);
  }
  bool flat = true;
  for (const Point3& p : pts)
    if (sgn(dot(nrm, p - pts[0])) != 0) {
      flat = false;
      break;
    }
  if (!flat) return ConvexSet(ConvexPolytope::hull(pts, source));
  // Coplanar: Andrew's monotone chain in the plane that drops axis k, on the
  // points sorted by the two remaining coordinates; strict turns only, so
  // points in the middle of an edge are left out.
  const int k = drop_axis(nrm);
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  std::sort(pts.begin(), pts.end(), [&](const Point3& a, const Point3& b) {
    const int c = cmp(a[u], b[u]);
    return c != 0 ? c < 0 : cmp(a[v], b[v]) < 0;
  });
  std::vector<Point3> h(2 * pts.size());
  std::size_t t = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (t >= 2 && turn(h[t - 2], h[t - 1], pts[i], k) <= 0) --t;
    h[t++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lower = t + 1; i-- > 0;) {
    while (t >= lower && turn(h[t - 2], h[t - 1], pts[i], k) <= 0) --t;
    h[t++] = pts[i];
  }
  h.resize(t - 1);
  return convex_polygon(std::move(h));
}

ConvexSet ConvexSet::from_mesh(const Mesh& mesh, const std::string& source) {
  if (mesh.faces.size() != 1) return ConvexSet(ConvexPolytope::from_mesh(mesh, source));
  std::vector<Point3> loop;
  for (Index i : mesh.faces[0]) {
    if (i >= mesh.points.size())
      throw InputError(source, "face 0", "vertex index " + std::to_string(i) + " out of range");
    loop.push_back(mesh.points.exact(i));
  }
  return polygon(loop, source);
}

Index ConvexSet::num_vertices() const {
  return dim_ == 3 ? polytope_.num_vertices() : Index(vertices_.size());
}
Index ConvexSet::num_edges() const {
  switch (dim_) {
    case 0: return 0;
    case 1: return 1;
    case 2: return Index(vertices_.size());
    default: return polytope_.num_edges();
  }
}
Index ConvexSet::num_facets() const { return dim_ == 3 ? polytope_.num_facets() : dim_ == 2 ? 1 : 0; }

Mesh ConvexSet::to_mesh() const {
  if (dim_ == 3) return polytope_.to_mesh();
  Mesh m;
  m.points = PointList(vertices_);
  if (dim_ == 2) {
    std::vector<Index> face(vertices_.size());
    for (Index i = 0; i < face.size(); ++i) face[i] = i;
    m.faces.push_back(std::move(face));
  }
  return m;
}

Rational ConvexSet::volume() const { return dim_ == 3 ? polytope_.volume() : Rational(0); }

Rational ConvexSet::area_squared() const {
  if (dim_ != 2) return Rational(0);
  Point3 s(Rational(0), Rational(0), Rational(0));
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    s = s + cross(vertices_[i], vertices_[(i + 1) % vertices_.size()]);
  return dot(s, s) / 4;
}

ConvexSet ConvexSet::translated(const Point3& t) const {
  if (dim_ == 3) return ConvexSet(polytope_.translated(t));
  ConvexSet s = *this;
  for (Point3& p : s.vertices_) p = p + t;
  return s;
}

ConvexSet ConvexSet::negated() const {
  if (dim_ == 3) return ConvexSet(polytope_.negated());
  ConvexSet s = *this;
  for (Point3& p : s.vertices_) p = -p;
  // -P keeps the loop's orientation as seen from -normal.
  if (dim_ == 2) s.normal_ = -s.normal_;
  return s;
}

bool same_set(const ConvexSet& a, const ConvexSet& b) {
  if (a.dimension() != b.dimension()) return false;
  std::vector<Point3> x = a.vertices(), y = b.vertices();
  std::sort(x.begin(), x.end());
  std::sort(y.begin(), y.end());
  return x == y;
}

}  // namespace minksum
