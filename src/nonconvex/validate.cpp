// Validation of a closed solid (validate_solid) and its exact volume.
#include <minksum/error.hpp>
#include <minksum/parallel.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/predicates.hpp>

#include "kernel/interval.hpp"
#include "kernel/plane.hpp"
#include "mesh/builder.hpp"
#include "nonconvex/morton.hpp"
#include "nonconvex/nef.hpp"
#include "nonconvex/sweep.hpp"
#include "nonconvex/validate.hpp"

#include <CGAL/FPU.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <unordered_map>

namespace minksum {

namespace {

std::string face_name(Index f) { return "facet " + std::to_string(f); }
std::string vertex_name(Index v) { return "vertex " + std::to_string(v); }

// Exact normal of a planar polygon (Newell's formula: twice its vector area).
Point3 polygon_normal(const std::vector<Point3>& p) {
  Point3 n(Rational(0), Rational(0), Rational(0));
  for (std::size_t i = 0; i < p.size(); ++i) n = n + cross(p[i], p[(i + 1) % p.size()]);
  return n;
}

const Point3& origin_point() {
  static const Point3 o(Rational(0), Rational(0), Rational(0));
  return o;
}
const Vec3d kOriginApprox{0, 0, 0};
const Point3& axis_point(int k) {
  static const Point3 e[3] = {Point3(Rational(1), Rational(0), Rational(0)), Point3(Rational(0), Rational(1), Rational(0)),
                              Point3(Rational(0), Rational(0), Rational(1))};
  return e[k];
}
const Vec3d kAxisApprox[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

// The sign of ((b - a) x (c - a))_k, the doubled signed area of the triangle
// a b c projected along axis k: support_compare(a, b, c, e_k, 0), the
// kernel's filtered predicate on the points' cached roundings.
int orient2d(const RoundedPoint3& a, const RoundedPoint3& b, const RoundedPoint3& c, int drop) {
  return support_compare(a, b, c, RoundedPoint3{axis_point(drop), kAxisApprox[drop]},
                         RoundedPoint3{origin_point(), kOriginApprox});
}

// Whether the triangle a b c has zero area: every component of its normal
// (b - a) x (c - a) is zero.
bool collinear(const Point3& a, const Point3& b, const Point3& c) {
  const Vec3d da = to_double(a), db = to_double(b), dc = to_double(c);
  const RoundedPoint3 ra{a, da}, rb{b, db}, rc{c, dc};
  for (int k = 0; k < 3; ++k)
    if (orient2d(ra, rb, rc, k) != 0) return false;
  return true;
}

bool same_point(const Vec3d& a, const Vec3d& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// The same for points of doubles, exactly: the kernel's support_compare on
// doubles.
bool collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  for (int k = 0; k < 3; ++k)
    if (support_compare(a, b, c, kAxisApprox[k], kOriginApprox) != 0) return false;
  return true;
}

// The coordinate a polygon with normal n is projected along (where |n| is
// largest; the same for every positive or negative multiple of n).
int drop_axis(const Point3& n) {
  int drop = 0;
  for (int i = 1; i < 3; ++i)
    if (cmp(abs(n[i]), abs(n[drop])) > 0) drop = i;
  return drop;
}

// Ear clipping of a simple planar polygon (indices into `pts`), exact,
// projected along axis `drop`, where a counter-clockwise triangle of the
// polygon has orientation `ccw` (the sign of its normal's component).
// Returns false when no ear is found (the polygon is not simple).
bool ear_clip(const std::vector<Index>& loop, const std::vector<Point3>& pts, int drop, int ccw,
              const std::vector<Vec3d>& approx, std::vector<std::array<Index, 3>>& out) {
  auto at = [&](std::size_t i) { return RoundedPoint3{pts[loop[i]], approx[i]}; };
  std::vector<std::size_t> poly(loop.size());
  std::iota(poly.begin(), poly.end(), std::size_t(0));
  while (poly.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < poly.size() && !clipped; ++i) {
      const std::size_t n = poly.size();
      const std::size_t a = poly[(i + n - 1) % n], b = poly[i], c = poly[(i + 1) % n];
      if (orient2d(at(a), at(b), at(c), drop) != ccw) continue;  // reflex or flat corner
      bool empty = true;
      for (std::size_t j = 0; j < n && empty; ++j) {
        const std::size_t q = poly[j];
        if (q == a || q == b || q == c) continue;
        // q inside or on the closed triangle a b c blocks the ear.
        if (orient2d(at(a), at(b), at(q), drop) != -ccw && orient2d(at(b), at(c), at(q), drop) != -ccw &&
            orient2d(at(c), at(a), at(q), drop) != -ccw)
          empty = false;
      }
      if (!empty) continue;
      out.push_back({loop[a], loop[b], loop[c]});
      poly.erase(poly.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (orient2d(at(poly[0]), at(poly[1]), at(poly[2]), drop) != ccw) return false;
  out.push_back({loop[poly[0]], loop[poly[1]], loop[poly[2]]});
  return true;
}

// The same, counter-clockwise about `normal`.
bool ear_clip(const std::vector<Index>& loop, const std::vector<Point3>& pts, const Point3& normal,
              std::vector<std::array<Index, 3>>& out) {
  const int drop = drop_axis(normal);
  std::vector<Vec3d> approx(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i) approx[i] = to_double(pts[loop[i]]);
  return ear_clip(loop, pts, drop, sgn(normal[drop]), approx, out);
}

// Ear clipping of a face of a valid solid (a simple planar polygon) without
// its rational normal: the plane's normal direction from the first
// non-collinear corner (any multiple gives the same drop axis), and the
// orientation from the turn at the vertex whose projection is
// lexicographically smallest, a vertex of the projection's hull and so a
// convex corner of the simple polygon, which turns as the polygon does.
// Every sign a filtered predicate.  False when the polygon has no such
// corner or no ear (it is not simple).
bool ear_clip_face(const std::vector<Index>& loop, const std::vector<Point3>& pts,
                   std::vector<std::array<Index, 3>>& out) {
  const std::size_t n = loop.size();
  std::vector<Vec3d> approx(n);
  for (std::size_t i = 0; i < n; ++i) approx[i] = to_double(pts[loop[i]]);
  auto at = [&](std::size_t i) { return RoundedPoint3{pts[loop[i]], approx[i]}; };
  // Any axis along which the plane's normal has a non-zero component gives
  // the same ears (each orientation in the projection is the 3D one times
  // the sign of that component, which ccw below takes out); the largest
  // component is the best conditioned.  It is taken from the doubles'
  // cross product when the exact sign there is non-zero, else exactly.
  int drop = -1;
  for (std::size_t i = 0; i < n && drop < 0; ++i) {
    const std::size_t a = (i + n - 1) % n, c = (i + 1) % n;
    for (int k = 0; k < 3 && drop < 0; ++k)
      if (orient2d(at(a), at(i), at(c), k) != 0) {
        const Vec3d u{approx[i].x - approx[a].x, approx[i].y - approx[a].y, approx[i].z - approx[a].z};
        const Vec3d w{approx[c].x - approx[a].x, approx[c].y - approx[a].y, approx[c].z - approx[a].z};
        const double m[3] = {std::fabs(u.y * w.z - u.z * w.y), std::fabs(u.z * w.x - u.x * w.z),
                             std::fabs(u.x * w.y - u.y * w.x)};
        const int guess = m[0] >= m[1] ? (m[0] >= m[2] ? 0 : 2) : (m[1] >= m[2] ? 1 : 2);
        drop = guess == k || orient2d(at(a), at(i), at(c), guess) != 0
                   ? guess
                   : drop_axis(cross(pts[loop[i]] - pts[loop[a]], pts[loop[c]] - pts[loop[a]]));
      }
  }
  if (drop < 0) return false;
  const int iu = (drop + 1) % 3, iv = (drop + 2) % 3;
  std::size_t low = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const Point3& p = pts[loop[i]];
    const Point3& q = pts[loop[low]];
    const int c = cmp(p[iu], q[iu]);
    if (c < 0 || (c == 0 && cmp(p[iv], q[iv]) < 0)) low = i;
  }
  const int ccw = orient2d(at((low + n - 1) % n), at(low), at((low + 1) % n), drop);
  if (ccw == 0) return false;
  return ear_clip(loop, pts, drop, ccw, approx, out);
}

// Shells (the connected components of the surface; vertex-disjoint, as each
// vertex is a single fan, and disjoint, as no two faces intersect) nest: the
// depth of a shell is the number of shells enclosing it, decided by whether
// one of its vertices lies strictly inside them (exact ray parity).  The
// orientation must agree with the depth: an outer boundary (even depth)
// faces outwards (positive signed volume), a cavity's boundary (odd depth)
// inwards.  Anything else describes no solid, or another one than the
// volumes say: an error naming the shell by its first face.
void check_shell_orientation(const Solid& s, int volume_sign, const std::string& source) {
  const auto& tris = s.triangles.faces;
  const std::size_t nv = s.triangles.points.size();
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), Index(0));
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : tris)
    for (int i = 1; i < 3; ++i) parent[find(t[i])] = find(t[0]);
  std::vector<Index> shell_of_root(nv, kNoIndex);
  std::vector<std::vector<std::array<Index, 3>>> shell;
  std::vector<Index> first_face;
  for (Index t = 0; t < tris.size(); ++t) {
    Index& k = shell_of_root[find(tris[t][0])];
    if (k == kNoIndex) {
      k = Index(shell.size());
      shell.emplace_back();
      first_face.push_back(s.source_face[t]);
    }
    shell[k].push_back({tris[t][0], tris[t][1], tris[t][2]});
  }
  auto name = [&](std::size_t k) { return "the shell of " + face_name(first_face[k]); };
  if (shell.size() == 1) {
    if (volume_sign < 0)
      throw InputError(source, "", "the faces are oriented inwards (the enclosed volume is negative)");
    if (volume_sign == 0) throw InputError(source, "", "the enclosed volume is zero");
    return;
  }
  const std::vector<Point3> pts = s.triangles.points.to_points();
  // Per shell: signed volume and exact bounding box.
  std::vector<int> sign(shell.size());
  std::vector<Point3> lo, hi;
  for (std::size_t k = 0; k < shell.size(); ++k) {
    Rational six_v = 0;
    Point3 l = pts[shell[k][0][0]], h = l;
    for (const auto& t : shell[k]) {
      six_v += dot(pts[t[0]], cross(pts[t[1]], pts[t[2]]));
      for (Index v : t)
        for (int c = 0; c < 3; ++c) {
          if (cmp(pts[v][c], l[c]) < 0) l[c] = pts[v][c];
          if (cmp(pts[v][c], h[c]) > 0) h[c] = pts[v][c];
        }
    }
    sign[k] = sgn(six_v);
    if (sign[k] == 0) throw InputError(source, name(k), "encloses zero volume");
    lo.push_back(l);
    hi.push_back(h);
  }
  for (std::size_t k = 0; k < shell.size(); ++k) {
    const Point3& q = pts[shell[k][0][0]];
    std::size_t depth = 0;
    for (std::size_t j = 0; j < shell.size(); ++j) {
      if (j == k) continue;
      bool boxed = true;  // shell k's box inside shell j's: else j cannot enclose k
      for (int c = 0; c < 3 && boxed; ++c) boxed = cmp(lo[j][c], lo[k][c]) <= 0 && cmp(hi[k][c], hi[j][c]) <= 0;
      if (boxed && nonconvex_detail::strictly_inside(q, pts, shell[j])) ++depth;
    }
    const bool outward = sign[k] > 0;
    if (depth % 2 == 0 && !outward)
      throw InputError(source, name(k),
                       depth == 0 ? "faces inwards but lies inside no other shell (an outer boundary must face "
                                    "outwards)"
                                  : "faces inwards but lies in a cavity (the boundary of an island in a cavity "
                                    "must face outwards)");
    if (depth % 2 == 1 && outward)
      throw InputError(source, name(k),
                       "faces outwards but lies inside another shell, in the solid (the boundary of a cavity must "
                       "face inwards)");
  }
}

}  // namespace

Mesh triangulate(const Mesh& mesh, const std::string& source) {
  Mesh out;
  out.points = mesh.points;
  const std::vector<Point3> pts = mesh.points.to_points();
  // The faces' triangles in parallel (each face on its own), then in the
  // order of the faces; the first face that is not simple is named.
  const std::size_t n = mesh.faces.size();
  std::vector<std::vector<std::array<Index, 3>>> tris(n);
  std::vector<char> simple(n, 1);
  parallel_for(n, parallel_threads(0, n / 256 + 1), [&](std::size_t f) {
    const auto& loop = mesh.faces[f];
    if (loop.size() == 3) return;
    if (!ear_clip_face(loop, pts, tris[f])) simple[f] = 0;
  });
  for (Index f = 0; f < n; ++f) {
    if (!simple[f])
      throw InputError(source, face_name(f), "is not a simple polygon (its boundary crosses or touches itself)");
    if (mesh.faces[f].size() == 3) {
      out.faces.push_back(mesh.faces[f]);
      continue;
    }
    for (const auto& t : tris[f]) out.faces.push_back({t[0], t[1], t[2]});
  }
  return out;
}

// Six times the signed volume of each face's fan from the origin, summed
// in a tree.  Each fan triangle's term in integers: with the points as
// P / D over one denominator each (ScaledPoint), det(p0, p1, p2) =
// det(P0, P1, P2) / (D0 D1 D2), one gcd per triangle instead of one per
// rational operation.  The terms' denominators differ (a vertex of the
// union is a cut point with its own denominator, and the exact volume's
// denominator is about the product of all of them), so a running sum would
// cost the final size per term; the pairwise sums of equal halves cost
// about the final size per level.  The faces are summed in the order of a
// Morton code of their first vertex's doubles, so that each node of the
// tree holds a patch of the surface: two sibling patches share the vertices
// of their common border only.  The lower levels (many small sums, in
// parallel) are reduced at every addition; the top levels (a few huge sums,
// one at a time) are added as n1/d1 + n2/d2 = (n1 d2 + n2 d1) / (d1 d2)
// without the gcds that reduce them, which cost several multiplications
// each: the denominators grow by the factors of the shared border vertices
// only, and the final sum is reduced once.  Exact in any order.
Rational mesh_volume(const Mesh& mesh) {
  const std::size_t nf = mesh.faces.size();
  const unsigned workers = parallel_threads(0, nf / 256 + 1);
  std::vector<ScaledPoint> scaled(mesh.points.size());
  parallel_for(scaled.size(), parallel_threads(0, scaled.size() / 256 + 1),
               [&](std::size_t v) { scaled[v] = scaled_point(mesh.points[v]); });
  // The faces in Morton order of their first vertex (the order decides the
  // cost only).
  std::vector<Vec3d> first_vertex(nf);
  for (std::size_t k = 0; k < nf; ++k)
    first_vertex[k] = mesh.faces[k].empty() ? Vec3d{0, 0, 0} : to_double(mesh.points[mesh.faces[k][0]]);
  const std::vector<std::size_t> order = nonconvex_detail::morton_order(first_vertex);
  std::vector<Rational> term(nf);
  parallel_for(nf, workers, [&](std::size_t k) {
    const auto& f = mesh.faces[order[k]];
    const ScaledPoint& p0 = scaled[f[0]];
    Integer c[3], det, den;
    Rational t;
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const ScaledPoint& p1 = scaled[f[i]];
      const ScaledPoint& p2 = scaled[f[i + 1]];
      for (int j = 0; j < 3; ++j) {
        const int a = (j + 1) % 3, b = (j + 2) % 3;
        mpz_mul(c[j].get_mpz_t(), p1.num[a].get_mpz_t(), p2.num[b].get_mpz_t());
        mpz_submul(c[j].get_mpz_t(), p1.num[b].get_mpz_t(), p2.num[a].get_mpz_t());
      }
      mpz_mul(det.get_mpz_t(), p0.num[0].get_mpz_t(), c[0].get_mpz_t());
      mpz_addmul(det.get_mpz_t(), p0.num[1].get_mpz_t(), c[1].get_mpz_t());
      mpz_addmul(det.get_mpz_t(), p0.num[2].get_mpz_t(), c[2].get_mpz_t());
      mpz_mul(den.get_mpz_t(), p0.den.get_mpz_t(), p1.den.get_mpz_t());
      mpz_mul(den.get_mpz_t(), den.get_mpz_t(), p2.den.get_mpz_t());
      mpz_swap(t.get_num_mpz_t(), det.get_mpz_t());
      mpz_swap(t.get_den_mpz_t(), den.get_mpz_t());
      t.canonicalize();
      term[k] += t;
    }
  });
  if (term.empty()) return Rational(0);
  // Reduced levels down to 16 sums (their gcds keep the numbers of the
  // levels above small: callgrind counts on rounded erosions and openings,
  // whose cut points have long denominators, are least with the last three
  // or four levels unreduced).
  std::vector<Rational> next;
  while (term.size() > 1 && term.size() / 2 >= 8) {
    const std::size_t half = term.size() / 2;
    next.resize(half + term.size() % 2);
    parallel_for(half, workers, [&](std::size_t k) { next[k] = term[2 * k] + term[2 * k + 1]; });
    if (term.size() % 2) next[half] = std::move(term.back());
    term.swap(next);
  }
  // The top levels unreduced (denominators stay positive), then one reduction.
  std::vector<std::pair<Integer, Integer>> frac(term.size());
  for (std::size_t k = 0; k < term.size(); ++k) {
    mpz_swap(frac[k].first.get_mpz_t(), term[k].get_num_mpz_t());
    mpz_swap(frac[k].second.get_mpz_t(), term[k].get_den_mpz_t());
  }
  Integer cross;
  while (frac.size() > 1) {
    const std::size_t half = frac.size() / 2;
    for (std::size_t k = 0; k < half; ++k) {
      auto& [n1, d1] = frac[2 * k];
      auto& [n2, d2] = frac[2 * k + 1];
      mpz_mul(cross.get_mpz_t(), n2.get_mpz_t(), d1.get_mpz_t());
      mpz_mul(n1.get_mpz_t(), n1.get_mpz_t(), d2.get_mpz_t());
      mpz_add(n1.get_mpz_t(), n1.get_mpz_t(), cross.get_mpz_t());
      mpz_mul(d1.get_mpz_t(), d1.get_mpz_t(), d2.get_mpz_t());
      if (k != 0) {
        mpz_swap(frac[k].first.get_mpz_t(), n1.get_mpz_t());
        mpz_swap(frac[k].second.get_mpz_t(), d1.get_mpz_t());
      }
    }
    if (frac.size() % 2) {
      mpz_swap(frac[half].first.get_mpz_t(), frac.back().first.get_mpz_t());
      mpz_swap(frac[half].second.get_mpz_t(), frac.back().second.get_mpz_t());
    }
    frac.resize(half + frac.size() % 2);
  }
  Rational sum;
  mpz_swap(sum.get_num_mpz_t(), frac[0].first.get_mpz_t());
  mpz_swap(sum.get_den_mpz_t(), frac[0].second.get_mpz_t());
  sum.canonicalize();
  return sum / 6;
}

Solid validate_solid(const Mesh& mesh, const std::string& source) {
  // A convex polytope is a valid solid: the convex path, no further test.
  try {
    if (std::optional<ConvexPolytope> p = PolytopeBuilder::build_if_convex(mesh, source))
      return solid_of(std::move(*p));
  } catch (const InputError&) {
    // Not convex (or not valid at all): the general checks say why.
  }
  return nonconvex_detail::validate_surface(mesh, source);
}

namespace {

// The sign of the volume a closed triangle surface encloses: the sum of
// det(p0 − o, p1 − o, p2 − o) over its triangles (six times the volume, o
// its first point), on intervals (kernel/interval.hpp: each operation
// rounded outward, so the sum encloses the exact one) when the points are
// doubles; exactly (mesh_volume) when the interval does not decide.
int volume_sign(const Mesh& tris) {
  if (tris.points.all_doubles() && !tris.points.empty()) {
    int sign = kUncertain;
    {
      CGAL::Protect_FPU_rounding<true> upward;
      const std::vector<Vec3d>& v = tris.points.approx();
      auto at = [&](Index i) {
        return FastIPoint{FastInterval(v[i].x), FastInterval(v[i].y), FastInterval(v[i].z)};
      };
      const FastIPoint o = at(0);
      FastInterval six(0);
      for (const auto& f : tris.faces) six += dot(at(f[0]) - o, cross(at(f[1]) - o, at(f[2]) - o));
      sign = sign_of(six);
    }
    if (sign != kUncertain) return sign;
  }
  return sgn(mesh_volume(tris));
}

Solid checked_surface(const Mesh& mesh, const std::string& source, bool with_volume);

}  // namespace

Solid nonconvex_detail::validate_surface(const Mesh& mesh, const std::string& source) {
  return checked_surface(mesh, source, true);
}

void nonconvex_detail::check_surface(const Mesh& mesh, const std::string& source) {
  (void)checked_surface(mesh, source, false);
}

namespace {

Solid checked_surface(const Mesh& mesh, const std::string& source, bool with_volume) {
  // Weld exactly equal points: canonical index = first of its value.
  const std::size_t n = mesh.points.size();
  // The exact points as rationals only when some coordinate is not a
  // double (or a face has more than three corners): a surface of doubles,
  // such as a rounded output, is checked on its doubles by the kernel's
  // predicates, which are exact on them.
  const bool doubles = mesh.points.all_doubles();
  std::vector<Point3> exact;
  if (!doubles) exact = mesh.points.to_points();
  auto point = [&](Index v) { return doubles ? mesh.points.exact(v) : exact[v]; };
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index(0));
  if (doubles) {
    // The doubles are the exact coordinates: the same order, without GMP.
    const std::vector<Vec3d>& d = mesh.points.approx();
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
      if (d[a].x != d[b].x) return d[a].x < d[b].x;
      if (d[a].y != d[b].y) return d[a].y < d[b].y;
      if (d[a].z != d[b].z) return d[a].z < d[b].z;
      return a < b;
    });
  } else {
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
      if (exact[a] < exact[b]) return true;
      if (exact[b] < exact[a]) return false;
      return a < b;
    });
  }
  std::vector<Index> weld(n);
  for (std::size_t i = 0; i < n; ++i)
    weld[order[i]] = (i > 0 && (doubles ? same_point(mesh.points.approx(order[i]), mesh.points.approx(order[i - 1]))
                                        : exact[order[i]] == exact[order[i - 1]]))
                         ? weld[order[i - 1]]
                         : order[i];

  if (mesh.faces.empty()) throw InputError(source, "", "the mesh has no faces (a point cloud is not a solid)");
  // Faces: distinct vertices, planar, simple; triangulated.
  std::vector<std::array<Index, 3>> tris;
  std::vector<Index> tri_face;
  for (Index f = 0; f < mesh.faces.size(); ++f) {
    std::vector<Index> loop;
    for (Index v : mesh.faces[f]) loop.push_back(weld[v]);
    if (loop.size() < 3) throw InputError(source, face_name(f), "has fewer than three vertices");
    {
      std::vector<Index> s = loop;
      std::sort(s.begin(), s.end());
      if (std::adjacent_find(s.begin(), s.end()) != s.end())
        throw InputError(source, face_name(f), "uses a vertex twice (after welding equal points)");
    }
    if (loop.size() == 3 && (doubles ? !collinear(mesh.points.approx(loop[0]), mesh.points.approx(loop[1]),
                                                  mesh.points.approx(loop[2]))
                                     : !collinear(exact[loop[0]], exact[loop[1]], exact[loop[2]]))) {
      tris.push_back({loop[0], loop[1], loop[2]});
      tri_face.push_back(f);
      continue;
    }
    if (exact.empty()) exact = mesh.points.to_points();
    std::vector<Point3> p;
    for (Index v : loop) p.push_back(exact[v]);
    const Point3 normal = polygon_normal(p);
    if (is_zero(normal)) {
      // Zero vector area: collinear vertices, or a boundary whose lobes
      // cancel (a bow tie), which is not a simple polygon.
      bool collinear = true;
      for (std::size_t i = 2; i < p.size() && collinear; ++i) collinear = is_zero(cross(p[1] - p[0], p[i] - p[0]));
      throw InputError(source, face_name(f),
                       collinear ? std::string("has zero area (its vertices are collinear)")
                                 : std::string("is not a simple polygon (its boundary crosses or touches itself)"));
    }
    if (loop.size() == 3) {
      tris.push_back({loop[0], loop[1], loop[2]});
      tri_face.push_back(f);
      continue;
    }
    for (std::size_t i = 0; i < p.size(); ++i)
      if (sgn(dot(normal, p[i] - p[0])) != 0) throw InputError(source, face_name(f), "is not planar");
    const std::size_t before = tris.size();
    if (!ear_clip(loop, exact, normal, tris))
      throw InputError(source, face_name(f), "is not a simple polygon (its boundary crosses or touches itself)");
    tri_face.resize(tris.size(), f);
    (void)before;
  }

  // Edges: each shared by exactly two triangles traversing it in opposite
  // directions.  Worded as the polytope builder words them (every command
  // says the same of the same defect): the first edge of each kind in the
  // order the triangles first use it, non-manifold edges before
  // inconsistent ones before open ones, located by vertex numbers and
  // coordinates.  The corners leaving each vertex, sorted by the vertex
  // they lead to and then by triangle, give each edge's uses by binary
  // search; walking the triangles' edges in order, the first one of a kind
  // met is the first of that kind in the order of first uses (an edge met
  // earlier would have been used earlier).
  std::vector<Index> leaving_start(n + 1, 0);
  for (const auto& t : tris)
    for (Index v : t) ++leaving_start[v + 1];
  for (std::size_t v = 0; v < n; ++v) leaving_start[v + 1] += leaving_start[v];
  std::vector<std::pair<Index, Index>> leaving(leaving_start[n]);  // (to, triangle), by origin
  {
    std::vector<Index> fill(leaving_start.begin(), leaving_start.end() - 1);
    for (Index t = 0; t < tris.size(); ++t)
      for (int i = 0; i < 3; ++i) leaving[fill[tris[t][i]]++] = {tris[t][(i + 1) % 3], t};
    for (std::size_t v = 0; v < n; ++v)
      std::sort(leaving.begin() + leaving_start[v], leaving.begin() + leaving_start[v + 1]);
  }
  // The corners leaving `from` towards `to`, ascending by triangle.
  auto corners_towards = [&](Index from, Index to) {
    return std::equal_range(leaving.begin() + leaving_start[from], leaving.begin() + leaving_start[from + 1],
                            std::make_pair(to, Index(0)),
                            [](const std::pair<Index, Index>& x, const std::pair<Index, Index>& y) {
                              return x.first < y.first;
                            });
  };
  struct EdgeUse {
    Index count = 0, forward = 0, t0 = kNoIndex, t1 = kNoIndex;  // t0 < t1: its first two triangles
  };
  auto uses_of = [&](Index u, Index v) {
    EdgeUse e;
    auto add = [&](Index from, Index to, bool forward) {
      const auto [first, last] = corners_towards(from, to);
      for (auto k = first; k != last; ++k) {
        ++e.count;
        e.forward += forward;
        const Index t = k->second;
        if (e.t0 == kNoIndex || t < e.t0) {
          e.t1 = e.t0;
          e.t0 = t;
        } else if (e.t1 == kNoIndex || t < e.t1) {
          e.t1 = t;
        }
      }
    };
    add(u, v, true);
    add(v, u, false);
    return e;
  };
  auto edge_place = [&](Index u, Index v) {
    const Index a = std::min(u, v), b = std::max(u, v);
    return "edge " + std::to_string(a) + "-" + std::to_string(b) + " from " + format_point(point(a)) + " to " +
           format_point(point(b));
  };
  for (int kind = 0; kind < 3; ++kind)
    for (Index t = 0; t < tris.size(); ++t)
      for (int i = 0; i < 3; ++i) {
        const Index u = tris[t][i], v = tris[t][(i + 1) % 3];
        const EdgeUse e = uses_of(u, v);
        if (kind == 0 && e.count > 2)
          throw InputError(source, edge_place(u, v),
                           "non-manifold edge shared by " + std::to_string(e.count) + " facets");
        if (kind == 1 && e.count == 2 && e.forward != 1)
          throw InputError(source, edge_place(u, v),
                           "inconsistent orientation: " + face_name(tri_face[e.t0]) + " and " +
                               face_name(tri_face[e.t1]) + " traverse this edge in the same direction");
        if (kind == 2 && e.count == 1)
          throw InputError(source, edge_place(u, v),
                           "open mesh: the edge belongs to " + face_name(tri_face[e.t0]) + " only");
      }

  // Vertices: the triangles around each form one cycle (a single fan).  The
  // corners at v, as its leaving edges v -> next: each (next, prev) links
  // next to prev (the edges being sound, every next is one corner's); the
  // walk from the first corner's next must go through all of them.
  std::size_t used = 0;
  for (Index v = 0; v < n; ++v) {
    const Index b = leaving_start[v], e = leaving_start[v + 1];
    if (b == e) continue;
    ++used;
    auto link = [&](Index w) {  // the prev of the corner whose next is w
      const auto [first, last] = corners_towards(v, w);
      if (first == last) throw std::logic_error("checked_surface: a vertex's edges are not matched");
      for (Index u : tris[first->second])
        if (u != v && u != w) return u;
      throw std::logic_error("checked_surface: a triangle with a repeated vertex");
    };
    const Index start = leaving[b].first;
    Index w = start;
    std::size_t steps = 0;
    do {
      w = link(w);
      ++steps;
    } while (w != start && steps <= e - b);
    if (steps != e - b)
      throw InputError(source, vertex_name(v) + " at " + format_point(point(v)),
                       "non-manifold vertex: its facets form more than one fan");
  }

  Solid s;
  // Compact the vertices.
  std::vector<Index> renum(n, kNoIndex);
  for (const auto& t : tris)
    for (Index v : t)
      if (renum[v] == kNoIndex) {
        renum[v] = Index(s.triangles.points.size());
        s.triangles.points.push_from(mesh.points, v);
      }
  for (const auto& t : tris) s.triangles.faces.push_back({renum[t[0]], renum[t[1]], renum[t[2]]});
  s.source_face = std::move(tri_face);
  s.faces = mesh.faces.size();
  s.vertices = used;

  if (const auto hit = nonconvex_detail::first_self_intersection(s.triangles))
    throw InputError(source, face_name(s.source_face[hit->first]) + " and " + face_name(s.source_face[hit->second]),
                     "intersect (the surface intersects itself)");
  int sign = 0;
  if (with_volume) {
    s.volume = mesh_volume(s.triangles);
    sign = sgn(s.volume);
  } else {
    sign = volume_sign(s.triangles);
  }
  check_shell_orientation(s, sign, source);
  return s;
}

}  // namespace

Solid solid_of(const ConvexPolytope& p, bool with_volume) {
  Solid s;
  const Mesh m = p.to_mesh();
  s.faces = m.faces.size();
  s.vertices = p.num_vertices();
  s.triangles.points = m.points;
  for (Index f = 0; f < m.faces.size(); ++f)
    for (std::size_t i = 1; i + 1 < m.faces[f].size(); ++i) {
      s.triangles.faces.push_back({m.faces[f][0], m.faces[f][i], m.faces[f][i + 1]});
      s.source_face.push_back(f);
    }
  if (with_volume) s.volume = p.volume();
  s.convex = p;
  return s;
}

Mesh solid_faces(const Solid& s) {
  const Mesh& t = s.triangles;
  // The triangles of each input face, in the order of the faces.
  std::map<Index, std::vector<std::size_t>> by_face;
  for (std::size_t i = 0; i < t.faces.size(); ++i) by_face[s.source_face[i]].push_back(i);
  Mesh m;
  m.points = t.points;
  m.faces.reserve(by_face.size());
  for (const auto& [face, tris] : by_face) {
    // A face is a simple polygon cut by ear clipping (no point added): its
    // triangles' halfedges without their twin in the face are its boundary,
    // one loop through each of its vertices once.
    std::map<std::pair<Index, Index>, int> half;
    for (std::size_t i : tris)
      for (std::size_t k = 0; k < 3; ++k) ++half[{t.faces[i][k], t.faces[i][(k + 1) % 3]}];
    std::unordered_map<Index, Index> next;
    for (const auto& [uv, n] : half)
      if (!half.count({uv.second, uv.first})) next[uv.first] = uv.second;
    std::vector<Index> loop;
    const Index start = t.faces[tris[0]][0];
    Index v = start;
    do {
      loop.push_back(v);
      v = next.at(v);
    } while (v != start && loop.size() <= next.size());
    m.faces.push_back(std::move(loop));
  }
  return m;
}

SolidStats solid_stats(const Mesh& faces) {
  SolidStats st;
  st.vertices = faces.points.size();
  st.facets = faces.faces.size();
  std::size_t corners = 0;
  for (const auto& f : faces.faces) corners += f.size();
  st.edges = corners / 2;  // every edge has as many faces on each side
  // Shells: the components of the vertices joined by the faces (every vertex
  // is one fan of faces, so these are the surface's components).
  std::vector<Index> parent(faces.points.size());
  std::iota(parent.begin(), parent.end(), Index(0));
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : faces.faces)
    for (std::size_t k = 1; k < f.size(); ++k) parent[find(f[k])] = find(f[0]);
  for (Index v = 0; v < parent.size(); ++v) st.shells += find(v) == v;
  // Euler: V - E + F = 2 (shells - genus) for closed orientable surfaces of
  // disks.
  const long long chi = (long long)st.vertices - (long long)st.edges + (long long)st.facets;
  st.genus = std::size_t((2 * (long long)st.shells - chi) / 2);
  for (std::size_t i = 0; i < faces.points.size(); ++i) {
    const Point3 p = faces.points.exact(i);
    if (i == 0) {
      st.min = st.max = p;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      if (p[k] < st.min[k]) st.min[k] = p[k];
      if (p[k] > st.max[k]) st.max[k] = p[k];
    }
  }
  return st;
}

}  // namespace minksum
