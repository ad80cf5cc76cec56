// minksum's exact union of convex polytopes, the third step of the
// non-convex sum (docs/nonconvex.md, "Method").
//
// The boundary of the union U of convex polytopes C_1..C_n, facing n on an
// oriented plane H (outward normal n), is the closure of
//     R(H) = (union of the facets of the C_i on H facing n)
//            minus (union of C_j ∩ H over the pieces C_j without a facet on H facing n).
// A point p of a facet of C_i on H has U just below it (C_i); it is on the
// boundary unless U is also just above it, which happens exactly when a
// piece meets H in a region around p and reaches above H there: a piece
// C_j ∩ H of positive area whose C_j has no facet on H facing n (such a
// C_j lies below H).  A piece touching H face to face from above (its facet
// on H facing −n) removes the contact from both sides; a contact along an
// edge or at a vertex has zero area and removes nothing.  Facets of several
// pieces on H facing n may overlap: each facet is cut by the earlier pieces
// with a facet there too, so the cut facets do not overlap.
//
// Each facet is cut by the facet planes of the pieces that overlap it,
// successively (convex fragments, exactly in the facet's plane); the
// fragments of one plane are merged back into maximal faces by cancelling
// opposite edges along each line of the plane (in its two coordinates); an
// edge of the union lying across another plane's face splits that face
// (a slit); the faces of all planes are welded at exactly equal points,
// points where two edges cross become vertices, every vertex lying inside
// an edge is inserted into it, and each plane's
// edges are traced into loops (faces with holes or slits triangulated).
// Every decision is the sign of an exact polynomial, decided by a double
// filter with a proved bound when it can, else in exact rationals.
#include <minksum/error.hpp>
#include <minksum/half_space_side.hpp>
#include <minksum/parallel.hpp>
#include <minksum/predicates.hpp>

#include "kernel/plane.hpp"
#include "nonconvex/morton.hpp"
#include "nonconvex/union.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace minksum::nonconvex_detail {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// ---------------------------------------------------------------------------
// side(h, p) is the sign of a*x + b*y + c*z - d for the rational
// coefficients of a half-space (integers for the pieces' facets) and a point
// p of rationals: the kernel's filter on the nearest doubles of all seven
// (<minksum/half_space_side.hpp>, bound and derivation there), else the
// exact value.

// A cut point: where three integer planes meet, (X, Y, Z) / W with W > 0 as
// Cramer's rule gives them, not reduced.  Its signs against planes are
// taken on the integers; the canonical rational point (three gcds of
// numbers of several hundred bits) is made only when something asks for it
// (a fragment that reaches the merge, a segment), as many cut points are
// dropped with the part of a facet a piece covers.
struct CutPoint {
  Integer X, Y, Z, W;
  mutable std::optional<Point3> canonical;
  const Point3& point() const {
    if (!canonical) {
      Rational x(X, W), y(Y, W), z(Z, W);
      x.canonicalize();
      y.canonicalize();
      z.canonicalize();
      canonical.emplace(std::move(x), std::move(y), std::move(z));
    }
    return *canonical;
  }
};

// A point of a facet's plane: the exact point (kept elsewhere: a piece's
// loop, a segment, or an Arena: a given point or a cut point), with its
// nearest doubles (or a faithful rounding: within relative 2^-52).  Copying
// one copies no number.  In a polygon, `edge` is a plane other than the
// polygon's own that holds the edge from this vertex to the next: a cut
// point is then the meeting point of three integer planes, whose size does
// not grow with the number of cuts.
// `label`, when not kNoLabel, is the point's label in the piece its facet
// came from (Piece::labels), for PlaneBuilder::contains.
constexpr std::uint64_t kNoLabel = ~std::uint64_t(0);
struct V3 {
  const Point3* p = nullptr;
  const CutPoint* c = nullptr;
  Vec3d d;
  bool filtered = false;
  const Plane* edge = nullptr;
  std::uint64_t label = kNoLabel;
  const Point3& exact() const { return p ? *p : c->point(); }
};

// p with its nearest doubles d.
V3 make_v3(const Point3& p, const Vec3d& d) {
  V3 v;
  v.d = d;
  v.filtered = half_space_filter_usable(v.d.x, p.x) && half_space_filter_usable(v.d.y, p.y) &&
               half_space_filter_usable(v.d.z, p.z);
  v.p = &p;
  return v;
}

V3 make_v3(const Point3& p) { return make_v3(p, to_double(p)); }

// Usable in the filter: zero with the exact value, or of magnitude in
// [2^-480, 2^480).
bool cut_filter_usable(double x, const Integer& X) {
  return std::isfinite(x) && std::fabs(x) < kHalfSpaceFilterMax &&
         (x == 0 ? sgn(X) == 0 : std::fabs(x) >= kHalfSpaceFilterMin);
}

V3 make_v3(const CutPoint& c) {
  V3 v;
  v.d = Vec3d{truncated_ratio(c.X, c.W), truncated_ratio(c.Y, c.W), truncated_ratio(c.Z, c.W)};
  v.filtered = cut_filter_usable(v.d.x, c.X) && cut_filter_usable(v.d.y, c.Y) && cut_filter_usable(v.d.z, c.Z);
  v.c = &c;
  return v;
}

// The cut points of one plane, and the planes of the edges (deques: they do
// not move).
struct Arena {
  std::deque<CutPoint> points;
  std::deque<Plane> planes;
};

// The points where two fixed planes p and r meet a third plane q (a x +
// b y + c z = d; the three normals independent), by Cramer's rule in
// integers, each determinant expanded along q's row: the six 2×2 minors of
// p's and r's rows are made once, then each point costs 12 products.
// (The determinants are those of the rows p, q, r.)
class Meet {
 public:
  Meet(const Plane& p, const Plane& r) {
    minor(bc_, p.b, p.c, r.b, r.c);
    minor(ac_, p.a, p.c, r.a, r.c);
    minor(ab_, p.a, p.b, r.a, r.b);
    minor(dc_, p.d, p.c, r.d, r.c);
    minor(db_, p.d, p.b, r.d, r.b);
    minor(ad_, p.a, p.d, r.a, r.d);
  }
  CutPoint with(const Plane& q) const {
    CutPoint out;
    // det = −q.a m_bc + q.b m_ac − q.c m_ab;  X = −q.d m_bc + q.b m_dc − q.c m_db;
    // Y = −q.a m_dc + q.d m_ac − q.c m_ad;    Z = q.a m_db + q.b m_ad − q.d m_ab.
    expand(out.W, q.b, ac_, q.a, bc_, q.c, ab_);
    expand(out.X, q.b, dc_, q.d, bc_, q.c, db_);
    expand(out.Y, q.d, ac_, q.a, dc_, q.c, ad_);
    mpz_mul(out.Z.get_mpz_t(), q.a.get_mpz_t(), db_.get_mpz_t());
    mpz_addmul(out.Z.get_mpz_t(), q.b.get_mpz_t(), ad_.get_mpz_t());
    mpz_submul(out.Z.get_mpz_t(), q.d.get_mpz_t(), ab_.get_mpz_t());
    if (sgn(out.W) == 0) throw std::logic_error("union: a cut point of parallel planes");
    if (sgn(out.W) < 0)
      for (Integer* v : {&out.W, &out.X, &out.Y, &out.Z}) mpz_neg(v->get_mpz_t(), v->get_mpz_t());
    return out;
  }

 private:
  static void minor(Integer& out, const Integer& u1, const Integer& v1, const Integer& u2, const Integer& v2) {
    mpz_mul(out.get_mpz_t(), u1.get_mpz_t(), v2.get_mpz_t());
    mpz_submul(out.get_mpz_t(), u2.get_mpz_t(), v1.get_mpz_t());
  }
  // out = x1 m1 − x2 m2 − x3 m3.
  static void expand(Integer& out, const Integer& x1, const Integer& m1, const Integer& x2, const Integer& m2,
                     const Integer& x3, const Integer& m3) {
    mpz_mul(out.get_mpz_t(), x1.get_mpz_t(), m1.get_mpz_t());
    mpz_submul(out.get_mpz_t(), x2.get_mpz_t(), m2.get_mpz_t());
    mpz_submul(out.get_mpz_t(), x3.get_mpz_t(), m3.get_mpz_t());
  }
  Integer bc_, ac_, ab_, dc_, db_, ad_;
};

// The sign of a X + b Y + c Z - d W for a cut point (W > 0): the plane's
// side of the point, in integers.
int side_of_cut(const Plane& h, const CutPoint& c) {
  Integer acc;
  mpz_mul(acc.get_mpz_t(), h.a.get_mpz_t(), c.X.get_mpz_t());
  mpz_addmul(acc.get_mpz_t(), h.b.get_mpz_t(), c.Y.get_mpz_t());
  mpz_addmul(acc.get_mpz_t(), h.c.get_mpz_t(), c.Z.get_mpz_t());
  mpz_submul(acc.get_mpz_t(), h.d.get_mpz_t(), c.W.get_mpz_t());
  return sgn(acc);
}

// The half-space a*x + b*y + c*z <= d (inside) of an integer plane (kept
// by reference: the pieces' planes, or planes the caller keeps alive), with
// the nearest doubles of its four integers.
struct Half {
  const Plane* plane = nullptr;  // null for a lazy plane not built yet: piece->plane(index)
  double da = 0, db = 0, dc = 0, dd = 0;
  bool filtered = false;
  const Piece* piece = nullptr;
  Index index = 0;
  std::uint64_t generation = 0;  // of the union (a later one may reuse the piece's address)
};

// A lazy plane, built for an exact test: the last few built on this thread
// are kept (a facet's vertices are tested against the same planes in turn).
const Plane& built_plane(const Half& h) {
  struct Entry {
    const Piece* piece = nullptr;
    Index index = 0;
    std::uint64_t generation = 0;
    Plane plane;
  };
  constexpr std::size_t kEntries = 64;
  thread_local std::array<Entry, kEntries> cache;
  const std::size_t slot = (std::hash<const void*>()(h.piece) * 31 + h.index) % kEntries;
  Entry& e = cache[slot];
  if (e.piece != h.piece || e.index != h.index || e.generation != h.generation) {
    e.plane = h.piece->plane(h.index);
    e.piece = h.piece;
    e.index = h.index;
    e.generation = h.generation;
  }
  return e.plane;
}

// The doubles of a positive multiple of q, scaled by a power of two when
// its integers are too long for the filter (kernel/plane.hpp).
Half half_of(const Plane& q) {
  Half h;
  h.plane = &q;
  double out[4];
  h.filtered = plane_filter_doubles(q.a, q.b, q.c, q.d, out);
  h.da = out[0];
  h.db = out[1];
  h.dc = out[2];
  h.dd = out[3];
  return h;
}

// The doubles a lazy plane equal to q has: those of the primitive normal
// (a, b, c) / g, g = gcd(a, b, c), with the offset d / g along it.
std::array<double, 4> lazy_doubles(const Plane& q) {
  Integer g, m[3];
  mpz_gcd(g.get_mpz_t(), q.a.get_mpz_t(), q.b.get_mpz_t());
  mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), q.c.get_mpz_t());
  const Integer* abc[3] = {&q.a, &q.b, &q.c};
  for (int j = 0; j < 3; ++j) mpz_divexact(m[j].get_mpz_t(), abc[j]->get_mpz_t(), g.get_mpz_t());
  LazyPlane l;
  lazy_plane_doubles(m, q.d, g, l);
  return {l.a, l.b, l.c, l.d};
}

// The facet half-spaces of one piece, in the order of its planes: the lazy
// ones made from the piece's LazyPlane when asked (their doubles are the
// piece's own, not copied for every piece of the union), the others kept.
struct HalfSet {
  const Piece* piece = nullptr;
  std::vector<Half> held;  // planes lazy.size() .. num_planes() − 1
  std::uint64_t generation = 0;
  std::size_t size() const { return piece->lazy.size() + held.size(); }
  Half operator[](std::size_t k) const {
    const std::size_t lazy = piece->lazy.size();
    if (k >= lazy) return held[k - lazy];
    const LazyPlane& l = piece->lazy[k];
    Half h;
    h.plane = piece->held(Index(k));
    h.da = l.a;
    h.db = l.b;
    h.dc = l.c;
    h.dd = l.d;
    h.filtered = l.filtered;
    h.piece = piece;
    h.index = Index(k);
    h.generation = generation;
    return h;
  }
};

// > 0 outside, 0 on the plane, < 0 inside.  A point the filter leaves open
// is most often on the plane by construction (a point of a facet of a
// neighbouring piece, made from the same point of the surface and vertex
// of B): the builder tells that from the labels, else the exact value.
int side(const Half& h, const V3& v) {
  if (h.filtered && v.filtered)
    if (const auto s = half_space_side_filter(h.da, h.db, h.dc, h.dd, v.d.x, v.d.y, v.d.z)) return *s;
  if (v.label != kNoLabel && h.piece && h.piece->builder->contains(*h.piece, h.index, v.label)) return 0;
  const Plane& plane = h.plane ? *h.plane : built_plane(h);
  if (v.c) return side_of_cut(plane, *v.c);
  return plane.side(*v.p);  // integer arithmetic, no rational normalisation
}

// The filter alone: the sign when the doubles decide it.
std::optional<int> side_filter(const Half& h, const V3& v) {
  if (h.filtered && v.filtered) return half_space_side_filter(h.da, h.db, h.dc, h.dd, v.d.x, v.d.y, v.d.z);
  return std::nullopt;
}


// The two coordinates of an oriented plane h's points: the coordinate k
// with the largest |normal_k| is dropped, the other two (u, v) are ordered
// so that counter-clockwise in (u, v) is counter-clockwise seen from
// outside (from the side the normal points to).
struct Frame {
  int iu = 0, iv = 1;
  explicit Frame(const Plane& h) {
    const Integer n[3] = {h.a, h.b, h.c};
    int k = 2;
    for (int i = 0; i < 3; ++i)
      if (cmp(abs(n[i]), abs(n[k])) > 0) k = i;
    iu = (k + 1) % 3;
    iv = (k + 2) % 3;
    if (sgn(n[k]) < 0) std::swap(iu, iv);
  }
};

// A convex polygon of a facet's plane, counter-clockwise seen from outside.
using Poly = std::vector<V3>;

// The convex polygon g cut by the plane of h, sg the signs of its vertices
// (some > 0, some < 0): the part outside and the part inside.  The new
// points are on g's edges, so in its plane, exactly.
// `face` is g's own plane.  Each part's edges keep the planes of g's edges
// they lie on; the new edge lies on h.
void cut(const Poly& g, const Half& h, const std::vector<int>& sg, Poly& outside, Poly& inside, Arena& arena,
         const Plane& face) {
  const std::size_t n = g.size();
  // A lazy cutting plane is built into the arena: the new edge keeps it.
  const Plane* cutting = h.plane;
  if (!cutting) {
    arena.planes.push_back(built_plane(h));
    cutting = &arena.planes.back();
  }
  std::optional<Meet> meet;  // face and cutting plane: made at the first cut point
  // The edges of g each vertex of a part lies on: g[i] on edges i - 1 and i,
  // a cut point of edge i on edge i only.
  std::vector<std::array<std::size_t, 2>> on_out, on_in;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n, before = (i + n - 1) % n;
    if (sg[i] >= 0) {
      outside.push_back(g[i]);
      on_out.push_back({before, i});
    }
    if (sg[i] <= 0) {
      inside.push_back(g[i]);
      on_in.push_back({before, i});
    }
    if (sg[i] * sg[j] < 0) {
      if (!meet) meet.emplace(face, *cutting);
      arena.points.push_back(meet->with(*g[i].edge));
      V3 x = make_v3(arena.points.back());
      outside.push_back(x);
      on_out.push_back({i, i});
      inside.push_back(x);
      on_in.push_back({i, i});
    }
  }
  auto edges = [&](Poly& part, const std::vector<std::array<std::size_t, 2>>& on) {
    for (std::size_t k = 0; k < part.size(); ++k) {
      const auto& u = on[k];
      const auto& w = on[(k + 1) % part.size()];
      std::size_t common = n;
      for (std::size_t e : u)
        if (e == w[0] || e == w[1]) common = e;
      part[k].edge = common < n ? g[common].edge : cutting;
    }
  };
  edges(outside, on_out);
  edges(inside, on_in);
}

// The signs of g's vertices for h; whether some are > 0 and some < 0.
void signs(const Poly& g, const Half& h, std::vector<int>& sg, bool& pos, bool& neg) {
  sg.resize(g.size());
  pos = neg = false;
  for (std::size_t i = 0; i < g.size(); ++i) {
    sg[i] = side(h, g[i]);
    pos |= sg[i] > 0;
    neg |= sg[i] < 0;
  }
}

// g minus the convex piece bounded by `halves`: when their interiors meet
// (in g's plane), the convex parts of g outside are appended to `out` and
// the result is true; when they do not (the overlap has zero area), `out`
// is left as it was and the result is false.  A facet plane of the piece
// that contains g's plane has every sign 0 and cuts nothing.
// `order`, when given, names planes to try first for the rejection (guesses
// of one that rejects the piece, best first), and planes from `extra_from` on
// are tried next; the rest after them.  An order of exact tests only.
struct RejectOrder {
  const std::uint16_t* first = nullptr;
  std::size_t count = 0;
  std::size_t extra_from = SIZE_MAX;
};

// The box of a polygon's cached doubles, when every vertex may enter the
// filter (for half_space_box_side).
struct PolyBox {
  double lo[3], hi[3];
  bool usable = false;
  explicit PolyBox(const Poly& g) {
    usable = !g.empty();
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = usable ? g.front().d[k] : 0;
    for (const V3& v : g) {
      usable = usable && v.filtered;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], v.d[k]);
        hi[k] = std::max(hi[k], v.d[k]);
      }
    }
  }
  // −1: every vertex strictly inside h; +1: every vertex strictly outside.
  std::optional<int> side(const Half& h) const {
    if (!usable || !h.filtered) return std::nullopt;
    return half_space_box_side(h.da, h.db, h.dc, h.dd, lo, hi);
  }
};

// Whether one of `halves` has all of g on or outside it and some of g
// outside: then the piece and g's interior do not meet, and neither do the
// piece and any polygon of positive area inside g (its points are on or
// outside that plane too, and not all on its line in g's plane).  The
// planes in `order`'s order.
bool rejected(const Poly& g, const PolyBox& box, const HalfSet& halves, const RejectOrder& order) {
  // First the signs only: a plane with all of g on or outside it rejects the
  // piece before any cut is made.  Per plane the filter's signs first (the
  // box's, then the vertices'), then the exact ones it left open (vertices
  // on or very near the plane: those shared with the piece), only when no
  // vertex is known to be inside.
  auto rejects = [&](const Half& h) {
    if (const auto s = box.side(h)) return *s > 0;
    bool above = false, open = false;
    std::uint64_t decided = 0;  // bit i: vertex i's sign known (i < 64)
    for (std::size_t i = 0; i < g.size(); ++i) {
      const auto c = side_filter(h, g[i]);
      if (!c) {
        open = true;
        continue;
      }
      if (*c < 0) return false;
      above |= *c > 0;
      if (i < 64) decided |= std::uint64_t(1) << i;
    }
    if (open)
      for (std::size_t i = 0; i < g.size(); ++i) {
        if (i < 64 ? (decided >> i & 1) != 0 : side_filter(h, g[i]).has_value()) continue;  // (decided above)
        const int c = side(h, g[i]);
        if (c < 0) return false;
        above |= c > 0;
      }
    return above;
  };
  const std::size_t n = halves.size();
  auto preferred = [&](std::size_t k) {
    for (std::size_t i = 0; i < order.count; ++i)
      if (order.first[i] == k) return true;
    return false;
  };
  for (std::size_t i = 0; i < order.count; ++i)
    if (order.first[i] < n && rejects(halves[order.first[i]])) return true;
  for (std::size_t k = std::min(order.extra_from, n); k < n; ++k)
    if (rejects(halves[k])) return true;
  for (std::size_t k = 0; k < std::min(order.extra_from, n); ++k)
    if (!preferred(k) && rejects(halves[k])) return true;
  return false;
}

bool subtract(const Poly& g, const HalfSet& halves, std::vector<Poly>& out, Arena& arena,
              const Plane& face, const RejectOrder& order = {}) {
  std::vector<int> sg;
  bool pos = false, neg = false;
  const PolyBox box(g);
  if (rejected(g, box, halves, order)) return false;
  const std::size_t mark = out.size();
  Poly rem = g;
  PolyBox rem_box = box;
  for (std::size_t k = 0; k < halves.size(); ++k) {
    const Half h = halves[k];
    // rem wholly inside h, proved from its box: nothing to cut.
    if (rem_box.side(h) == std::optional<int>(-1)) continue;
    signs(rem, h, sg, pos, neg);
    if (!pos) continue;  // rem inside this half-space
    if (!neg) {          // rem outside: the overlap has no interior
      out.resize(mark);
      return false;
    }
    Poly outside, inside;
    cut(rem, h, sg, outside, inside, arena, face);
    out.push_back(std::move(outside));
    rem = std::move(inside);
    rem_box = PolyBox(rem);
  }
  return true;
}

// Bounding boxes from the nearest doubles: rounding to nearest is monotone,
// so boxes of rounded coordinates that do not meet prove that the exact ones
// do not.
struct Box {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  void add(const Vec3d& p) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  bool meets(const Box& o) const {
    for (int i = 0; i < 3; ++i)
      if (lo[i] > o.hi[i] || o.lo[i] > hi[i]) return false;
    return true;
  }
};

// The pieces' boxes in a uniform grid, so that a facet is compared with the
// pieces near it only.  The cell of a coordinate is floor((x - lo) / size),
// a non-decreasing function of x in floating point (subtraction and division
// by a positive number round monotonically), so two boxes that meet share a
// cell; the boxes are then compared themselves.
class PieceGrid {
 public:
  explicit PieceGrid(const std::vector<Box>& boxes) : boxes_(boxes) {
    Box all;
    std::vector<double> extent;
    for (const Box& b : boxes) {
      if (b.lo[0] > b.hi[0]) continue;  // empty piece
      for (int i = 0; i < 3; ++i) {
        all.lo[i] = std::min(all.lo[i], b.lo[i]);
        all.hi[i] = std::max(all.hi[i], b.hi[i]);
      }
      extent.push_back(std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]}));
    }
    double cell = 0;
    if (!extent.empty()) {
      std::nth_element(extent.begin(), extent.begin() + std::ptrdiff_t(extent.size() / 2), extent.end());
      cell = extent[extent.size() / 2];
    }
    bool usable = std::isfinite(cell) && cell > 0;
    for (int i = 0; i < 3 && usable; ++i) usable = std::isfinite(all.lo[i]) && std::isfinite(all.hi[i]);
    const double limit = 8.0 * double(boxes.size()) + 64.0;
    for (int i = 0; i < 3; ++i) {
      lo_[i] = usable ? all.lo[i] : 0;
      n_[i] = 1;
    }
    if (usable) {
      for (;;) {
        double total = 1;
        for (int i = 0; i < 3; ++i) {
          n_[i] = std::max<std::size_t>(1, std::size_t(std::min(1e6, std::floor((all.hi[i] - all.lo[i]) / cell)) + 1));
          total *= double(n_[i]);
        }
        if (total <= limit) break;
        cell *= 1.25;
      }
      size_ = cell;
    }
    // Each cell's items grouped by their class: bit i set when the cell is
    // the first of the item's cells along axis i (see query).
    const std::size_t cells = n_[0] * n_[1] * n_[2];
    start_.assign(cells + 1, 0);
    class_end_.assign(8 * cells, 0);
    for_each_piece_cell([&](std::size_t c, unsigned m, Index) {
      ++start_[c + 1];
      ++class_end_[8 * c + m];
    });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    // Each class's start within its cell; filling moves it to the class's end.
    for (std::size_t c = 0; c < cells; ++c) {
      std::uint32_t at = 0;
      for (unsigned m = 0; m < 8; ++m) at += std::exchange(class_end_[8 * c + m], at);
    }
    items_.resize(start_.back());
    item_box_.resize(start_.back());
    for_each_piece_cell([&](std::size_t c, unsigned m, Index j) {
      const std::size_t k = start_[c] + class_end_[8 * c + m]++;
      item_box_[k] = boxes_[j];
      items_[k] = j;
    });
  }

  // The pieces whose boxes meet `box`, ascending, each once.  A box b that
  // meets `box` is looked at in one cell only: the cell c* of the lower
  // corner of the two boxes' intersection, c*_i = cell(max(lo_i, b.lo_i)) =
  // max(cell(lo_i), cell(b.lo_i)) (cell is non-decreasing), which lies in
  // both boxes' ranges of cells (max(lo_i, b.lo_i) <= min(hi_i, b.hi_i) when
  // they meet).  In a cell c of the query's range, along each axis i with
  // c_i > cell(lo_i), only the boxes whose first cell along i is c_i can
  // have c*_i = c_i: those are the classes scanned.  In c* every class
  // that holds b is scanned; in any other cell c of both ranges some axis
  // has c_i > c*_i, so c_i > cell(lo_i) while c_i > cell(b.lo_i), and b's
  // class there is not scanned.
  void query(const Box& box, std::vector<Index>& out) const {
    out.clear();
    std::size_t lo[3], hi[3];
    range(box, lo, hi);
    for (std::size_t x = lo[0]; x <= hi[0]; ++x)
      for (std::size_t y = lo[1]; y <= hi[1]; ++y)
        for (std::size_t z = lo[2]; z <= hi[2]; ++z) {
          const std::size_t c = (x * n_[1] + y) * n_[2] + z;
          const unsigned need = unsigned(x > lo[0]) | unsigned(y > lo[1]) << 1 | unsigned(z > lo[2]) << 2;
          for (unsigned m = need; m < 8; m = (m + 1) | need) {
            const std::size_t b = start_[c] + (m ? class_end_[8 * c + m - 1] : 0), e = start_[c] + class_end_[8 * c + m];
            for (std::size_t k = b; k < e; ++k)
              if (box.meets(item_box_[k])) out.push_back(items_[k]);
          }
        }
    std::sort(out.begin(), out.end());
  }

 private:
  std::size_t cell_of(double x, int i) const {
    if (size_ <= 0) return 0;
    const double c = std::floor((x - lo_[i]) / size_);
    if (!(c > 0)) return 0;
    return std::min(n_[i] - 1, std::size_t(std::min(c, 1e15)));
  }
  void range(const Box& b, std::size_t lo[3], std::size_t hi[3]) const {
    for (int i = 0; i < 3; ++i) {
      lo[i] = cell_of(b.lo[i], i);
      hi[i] = cell_of(b.hi[i], i);
    }
  }
  // f(cell, class, piece) for each cell of each piece's box; the class has
  // bit i set when the cell is the first of the box's cells along axis i.
  template <class F>
  void for_each_piece_cell(F&& f) const {
    for (Index j = 0; j < boxes_.size(); ++j) {
      const Box& b = boxes_[j];
      if (b.lo[0] > b.hi[0]) continue;
      std::size_t lo[3], hi[3];
      range(b, lo, hi);
      for (std::size_t x = lo[0]; x <= hi[0]; ++x)
        for (std::size_t y = lo[1]; y <= hi[1]; ++y)
          for (std::size_t z = lo[2]; z <= hi[2]; ++z)
            f((x * n_[1] + y) * n_[2] + z, unsigned(x == lo[0]) | unsigned(y == lo[1]) << 1 | unsigned(z == lo[2]) << 2,
              j);
    }
  }

  const std::vector<Box>& boxes_;
  double lo_[3] = {0, 0, 0}, size_ = 0;
  std::size_t n_[3] = {1, 1, 1};
  std::vector<std::size_t> start_;
  // Per cell and class m: the end of the class's items, counted from the
  // cell's start (a cell holds each box at most once: fewer than 2^32).
  std::vector<std::uint32_t> class_end_;
  std::vector<Index> items_;
  std::vector<Box> item_box_;  // the box of items_[k], beside it in the cell's list (no indirection)
};

// ---------------------------------------------------------------------------
// Merging the fragments of one plane: along each line of the plane, a
// fragment edge in the line's direction covers an interval (the fragment
// lies to its left), one in the opposite direction covers one backwards;
// the fragments do not overlap, so where one direction is covered more than
// the other only one side is in the region and that stretch is on the
// boundary, directed by the side.  Along a slit (an edge of the union lying
// in this plane, where the solid touches the face from outside: see
// plane_boundary) both directions are kept, so the face is split there.

struct LineKey {
  Integer a, b;  // primitive direction, first nonzero positive
  Rational c;    // a*v - b*u of its points
  friend bool operator<(const LineKey& x, const LineKey& y) {
    if (int r = cmp(x.a, y.a)) return r < 0;
    if (int r = cmp(x.b, y.b)) return r < 0;
    return cmp(x.c, y.c) < 0;
  }
};

// The primitive integer vector with the direction of the rational (x, y) != 0.
std::pair<Integer, Integer> primitive(const Rational& x, const Rational& y) {
  Integer l;
  mpz_lcm(l.get_mpz_t(), x.get_den_mpz_t(), y.get_den_mpz_t());
  Integer a = x.get_num() * (l / x.get_den()), b = y.get_num() * (l / y.get_den());
  Integer g = gcd(a, b);
  return {a / g, b / g};
}

// The segment p q on its line: the line, whether p -> q runs along the
// line's direction, and the parameters of p and q along it.
struct OnLine {
  LineKey key;
  bool forward;
  Rational tp, tq;
};

OnLine on_line(const Frame& f, const Point3& p, const Point3& q) {
  auto [a, b] = primitive(q[f.iu] - p[f.iu], q[f.iv] - p[f.iv]);
  bool forward = true;
  if (sgn(a) < 0 || (sgn(a) == 0 && sgn(b) < 0)) {
    a = -a;
    b = -b;
    forward = false;
  }
  const Rational ra(a), rb(b);
  return OnLine{LineKey{a, b, ra * p[f.iv] - rb * p[f.iu]}, forward, ra * p[f.iu] + rb * p[f.iv],
                ra * q[f.iu] + rb * q[f.iv]};
}

// A line of a plane in its frame's two coordinates, as the primitive
// integer equation A u + B v = C (gcd(A, B, C) = 1, A > 0 or A = 0 < B):
// one key per line, however it was found.
struct Line2 {
  Integer A, B, C;
  friend bool operator<(const Line2& x, const Line2& y) {
    if (int r = cmp(x.A, y.A)) return r < 0;
    if (int r = cmp(x.B, y.B)) return r < 0;
    return cmp(x.C, y.C) < 0;
  }
};

void make_canonical(Line2& l) {
  Integer g;
  mpz_gcd(g.get_mpz_t(), l.A.get_mpz_t(), l.B.get_mpz_t());
  mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), l.C.get_mpz_t());
  if (g != 1)
    for (Integer* x : {&l.A, &l.B, &l.C}) mpz_divexact(x->get_mpz_t(), x->get_mpz_t(), g.get_mpz_t());
  if (sgn(l.A) < 0 || (sgn(l.A) == 0 && sgn(l.B) < 0))
    for (Integer* x : {&l.A, &l.B, &l.C}) mpz_neg(x->get_mpz_t(), x->get_mpz_t());
}

// The line where the plane e meets the oriented plane h (not parallel to
// it), in h's frame: with k the coordinate the frame drops (h_k != 0),
// h gives x_k = (h_d - h_u u - h_v v) / h_k, and e times h_k becomes
// (e_u h_k - e_k h_u) u + (e_v h_k - e_k h_v) v = e_d h_k - e_k h_d.
// False when e is parallel to h.
bool line_of(const Plane& h, const Plane& e, const Frame& f, Line2& out) {
  const int k = 3 - f.iu - f.iv;
  const Integer* hc[3] = {&h.a, &h.b, &h.c};
  const Integer* ec[3] = {&e.a, &e.b, &e.c};
  auto term = [](Integer& r, const Integer& x1, const Integer& y1, const Integer& x2, const Integer& y2) {
    mpz_mul(r.get_mpz_t(), x1.get_mpz_t(), y1.get_mpz_t());
    mpz_submul(r.get_mpz_t(), x2.get_mpz_t(), y2.get_mpz_t());
  };
  term(out.A, *ec[f.iu], *hc[k], *ec[k], *hc[f.iu]);
  term(out.B, *ec[f.iv], *hc[k], *ec[k], *hc[f.iv]);
  if (sgn(out.A) == 0 && sgn(out.B) == 0) return false;
  term(out.C, e.d, *hc[k], *ec[k], h.d);
  make_canonical(out);
  return true;
}

// The line through two distinct points of the plane, in its frame.
Line2 line_through(const Frame& f, const Point3& p, const Point3& q) {
  // Direction (a, b) primitive; the line is b u - a v = b p_u - a p_v.
  auto [a, b] = primitive(q[f.iu] - p[f.iu], q[f.iv] - p[f.iv]);
  Rational c = Rational(b) * p[f.iu] - Rational(a) * p[f.iv];
  Line2 l;
  l.A = b * c.get_den();
  l.B = -a * c.get_den();
  l.C = c.get_num();
  make_canonical(l);
  return l;
}

// The sign of x_k − y_k for two points of a plane, exactly.  A cut point
// (X, Y, Z) / W, W > 0, is compared by cross-multiplication, so that only
// the points that become vertices of the boundary are made canonical (three
// gcds of numbers of several hundred bits each).
int compare_coordinate(const V3& x, const V3& y, int k) {
  if (x.c && x.c == y.c) return 0;
  if (x.filtered && y.filtered)
    if (const auto s = compare_filter(x.d[k], y.d[k])) return *s;
  const CutPoint* cx = x.c && !x.c->canonical ? x.c : nullptr;
  const CutPoint* cy = y.c && !y.c->canonical ? y.c : nullptr;
  if (!cx && !cy) return cmp(x.exact()[k], y.exact()[k]);
  auto num = [k](const CutPoint& c) -> const Integer& { return k == 0 ? c.X : k == 1 ? c.Y : c.Z; };
  Integer l, r;
  if (cx && cy) {
    mpz_mul(l.get_mpz_t(), num(*cx).get_mpz_t(), cy->W.get_mpz_t());
    mpz_mul(r.get_mpz_t(), num(*cy).get_mpz_t(), cx->W.get_mpz_t());
  } else if (cx) {
    const Rational& q = y.exact()[k];
    mpz_mul(l.get_mpz_t(), num(*cx).get_mpz_t(), q.get_den_mpz_t());
    mpz_mul(r.get_mpz_t(), q.get_num_mpz_t(), cx->W.get_mpz_t());
  } else {
    const Rational& q = x.exact()[k];
    mpz_mul(l.get_mpz_t(), q.get_num_mpz_t(), cy->W.get_mpz_t());
    mpz_mul(r.get_mpz_t(), num(*cy).get_mpz_t(), q.get_den_mpz_t());
  }
  return cmp(l, r);
}

struct Event {
  const V3* point;  // its parameter along the line is its u or its v
  int kind;   // 0: fragment edge along the line, 1: against it, 2: slit
  int delta;  // +1 where the interval starts, -1 where it ends
};

// A boundary segment of a plane's region, lifted: from a to b, the region
// on its left seen from outside.
struct Segment {
  Point3 a, b;
  Vec3d da, db;  // their nearest doubles (round_ends)
};

// Fills the nearest doubles of the segments' ends, converting each point
// once where a segment starts at the previous one's end.
void round_ends(std::vector<Segment>& segments) {
  for (std::size_t i = 0; i < segments.size(); ++i) {
    Segment& sg = segments[i];
    sg.da = i > 0 && segments[i - 1].b == sg.a ? segments[i - 1].db : to_double(sg.a);
    sg.db = i + 1 == segments.size() && i > 0 && segments[0].a == sg.b ? segments[0].da : to_double(sg.b);
  }
}

std::vector<Segment> merge_fragments(const Plane& plane, const Frame& frame, const std::vector<Poly>& fragments,
                                     const std::vector<Segment>& slits) {
  // Along a line A u + B v = C, u grows with the line's direction (B, -A)
  // made first-nonzero-positive when B != 0, else v does: the parameter of a
  // point is its u or its v, exactly, with no arithmetic.
  std::map<Line2, std::vector<Event>> lines;
  auto add = [&](const Line2& line, const V3& p, const V3& q, int kind) {
    const int along = sgn(line.B) != 0 ? frame.iu : frame.iv;
    const bool up = compare_coordinate(p, q, along) < 0;  // p has the smaller parameter
    if (kind == 0 && !up) kind = 1;
    auto& ev = lines[line];
    ev.push_back(Event{up ? &p : &q, kind, 1});
    ev.push_back(Event{up ? &q : &p, kind, -1});
  };
  // The line of an edge's plane, made once per plane (the fragments of one
  // facet share its edges' planes, the two sides of a cut its plane).
  std::unordered_map<const Plane*, std::optional<Line2>> line_of_plane;
  for (const Poly& g : fragments)
    for (std::size_t i = 0; i < g.size(); ++i) {
      const V3& p = g[i];
      const V3& q = g[(i + 1) % g.size()];
      std::optional<Line2>* known = nullptr;
      if (p.edge) {
        auto [it, fresh] = line_of_plane.try_emplace(p.edge);
        known = &it->second;
        if (fresh) {
          Line2 l;
          if (line_of(plane, *p.edge, frame, l)) *known = std::move(l);
        }
      }
      if (known && *known) add(**known, p, q, 0);
      else add(line_through(frame, p.exact(), q.exact()), p, q, 0);
    }
  std::vector<V3> slit_ends;
  slit_ends.reserve(2 * slits.size());
  for (const Segment& sl : slits) {
    slit_ends.push_back(make_v3(sl.a));
    slit_ends.push_back(make_v3(sl.b));
  }
  for (std::size_t i = 0; i < slits.size(); ++i)
    add(line_through(frame, slits[i].a, slits[i].b), slit_ends[2 * i], slit_ends[2 * i + 1], 2);
  std::vector<Segment> out;
  for (auto& [key, ev] : lines) {
    const int k = sgn(key.B) != 0 ? frame.iu : frame.iv;
    std::sort(ev.begin(), ev.end(),
              [k](const Event& x, const Event& y) { return compare_coordinate(*x.point, *y.point, k) < 0; });
    int count[3] = {0, 0, 0};
    bool along = false, against = false;  // the stretches under way
    const V3 *start_along = nullptr, *start_against = nullptr;
    for (std::size_t i = 0; i < ev.size();) {
      const V3* here = ev[i].point;
      for (const std::size_t first = i; i < ev.size() && compare_coordinate(*ev[i].point, *ev[first].point, k) == 0; ++i)
        count[ev[i].kind] += ev[i].delta;
      const bool slit = count[2] > 0;
      const bool now_along = slit ? count[0] > 0 : count[0] > count[1];
      const bool now_against = slit ? count[1] > 0 : count[1] > count[0];
      if (now_along != along) {
        if (along) out.push_back({start_along->exact(), here->exact(), {}, {}});
        start_along = here;
        along = now_along;
      }
      if (now_against != against) {
        if (against) out.push_back({here->exact(), start_against->exact(), {}, {}});
        start_against = here;
        against = now_against;
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// One plane's boundary: its facets cut by the other pieces, merged.

// A plane through the segment p → q of a facet's plane, perpendicular to
// it: normal (q − p) × n, in integers, not made primitive (an edge plane
// only enters cut points, whose W is normalised, and line equations, which
// are made canonical).
Plane edge_plane(const ScaledPoint& p, const ScaledPoint& q, const Integer n[3]) {
  Integer e[3], m[3];
  scaled_difference(p, q, e);
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3, l = (j + 2) % 3;
    mpz_mul(m[j].get_mpz_t(), e[k].get_mpz_t(), n[l].get_mpz_t());
    mpz_submul(m[j].get_mpz_t(), e[l].get_mpz_t(), n[k].get_mpz_t());
  }
  Plane out;
  mpz_mul(out.d.get_mpz_t(), m[0].get_mpz_t(), p.num[0].get_mpz_t());
  mpz_addmul(out.d.get_mpz_t(), m[1].get_mpz_t(), p.num[1].get_mpz_t());
  mpz_addmul(out.d.get_mpz_t(), m[2].get_mpz_t(), p.num[2].get_mpz_t());
  mpz_mul(out.a.get_mpz_t(), m[0].get_mpz_t(), p.den.get_mpz_t());
  mpz_mul(out.b.get_mpz_t(), m[1].get_mpz_t(), p.den.get_mpz_t());
  mpz_mul(out.c.get_mpz_t(), m[2].get_mpz_t(), p.den.get_mpz_t());
  return out;
}

struct FacetRef {
  Index piece, facet;
};

struct PlaneResult {
  std::vector<Segment> segments;
  std::size_t clips = 0;
};

// The boundary of the union on one plane, from the facets there.  `slits`
// are edges of the union found on the other planes that lie in this one
// (where the solid touches this face from outside along a segment): the
// fragments are cut along their lines and the face is split along them, so
// that such an edge is an edge of this face too (a non-manifold edge).
// `facets` are the candidate facets on the plane, `below` the other pieces
// with a facet on it facing the same way (not candidates), ascending.
// `labelled`: the pieces share one builder, whose labels of their points
// (Piece::labels) may be asked about any piece's planes.
PlaneResult plane_boundary(const Plane& plane, const std::vector<FacetRef>& facets, const std::vector<Index>& below,
                           const std::vector<Piece>& parts, const std::vector<HalfSet>& halves,
                           const PieceGrid& grid, bool labelled, const std::vector<Segment>& slits = {}) {
  PlaneResult r;
  Arena arena;
  const Integer normal_integers[3] = {plane.a, plane.b, plane.c};
  std::vector<ScaledPoint> scaled;
  std::vector<Poly> fragments;
  std::vector<Index> near;
  auto member = [&](Index j) {
    // facets are in ascending piece order, as is below
    if (std::binary_search(below.begin(), below.end(), j)) return true;
    auto it = std::lower_bound(facets.begin(), facets.end(), j,
                               [](const FacetRef& f, Index x) { return f.piece < x; });
    return it != facets.end() && it->piece == j;
  };
  for (const FacetRef& f : facets) {
    std::vector<Poly> frags(1);
    Box box;
    const Piece& own = parts[f.piece];
    const std::vector<Point3>& loop = own.loops[f.facet];
    scaled.clear();
    for (const Point3& p : loop) scaled.push_back(scaled_point(p));
    const std::vector<std::uint64_t>* names =
        labelled && f.facet < own.labels.size() && own.labels[f.facet].size() == loop.size() ? &own.labels[f.facet]
                                                                                             : nullptr;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      frags[0].push_back(make_v3(loop[k]));
      if (names) frags[0].back().label = (*names)[k];
      box.add(frags[0].back().d);
      // The plane through the edge perpendicular to this one.
      arena.planes.push_back(edge_plane(scaled[k], scaled[(k + 1) % loop.size()], normal_integers));
      frags[0].back().edge = &arena.planes.back();
    }
    const Poly whole = frags[0];
    const PolyBox whole_box(whole);
    grid.query(box, near);
    for (std::size_t k = 0; k < near.size() && !frags.empty(); ++k) {
      const Index j = near[k];
      // The pieces with a facet on this plane facing the same way lie below
      // it: they never remove anything, except that the earlier ones with a
      // candidate facet there remove their facet's overlap with this one (so
      // the plane's fragments do not overlap).
      if (j == f.piece) continue;
      if (member(j) && (j > f.piece || std::binary_search(below.begin(), below.end(), j))) continue;
      std::vector<Poly> next;
      const Piece& other = parts[j];
      // The planes tried first: those whose normals point most towards the
      // facet from the neighbour's box, then the piece's planes beyond its
      // operand's facets (an order of the exact tests only).
      RejectOrder order;
      if (other.directions) {
        double d[3];
        for (int c = 0; c < 3; ++c) d[c] = (box.lo[c] + box.hi[c]) - (other.lo[c] + other.hi[c]);
        order.count = other.directions->best(d, order.first);
        order.extra_from = other.directions->size();
      }
      // A piece that misses the whole facet misses each of its fragments:
      // one test instead of one per fragment.
      if (frags.size() > 1 && rejected(whole, whole_box, halves[j], order)) continue;
      for (Poly& g : frags)
        if (subtract(g, halves[j], next, arena, plane, order))
          ++r.clips;
        else
          next.push_back(std::move(g));
      frags = std::move(next);
    }
    for (Poly& g : frags) fragments.push_back(std::move(g));
  }
  const Point3 n = plane.normal();
  for (const Segment& sl : slits) {
    // The plane through the slit, across this one.
    arena.planes.push_back(canonical_plane(cross(sl.b - sl.a, n), sl.a));
    const Half h = half_of(arena.planes.back());
    std::vector<Poly> next;
    std::vector<int> sg;
    bool pos = false, neg = false;
    for (Poly& g : fragments) {
      signs(g, h, sg, pos, neg);
      if (!(pos && neg)) {
        next.push_back(std::move(g));
        continue;
      }
      Poly outside, inside;
      cut(g, h, sg, outside, inside, arena, plane);
      next.push_back(std::move(outside));
      next.push_back(std::move(inside));
    }
    fragments = std::move(next);
  }
  if (fragments.size() == 1 && slits.empty()) {
    // One convex fragment (most planes): nothing to cancel, its edges are
    // the boundary (its vertices are distinct and no three consecutive are
    // collinear, as merging would make them).
    const Poly& g = fragments.front();
    for (std::size_t i = 0; i < g.size(); ++i) r.segments.push_back({g[i].exact(), g[(i + 1) % g.size()].exact(), {}, {}});
    round_ends(r.segments);
    return r;
  }
  r.segments = merge_fragments(plane, Frame(plane), fragments, slits);
  round_ends(r.segments);
  return r;
}

// ---------------------------------------------------------------------------
// Assembly.

// Every vertex lying strictly inside the segment a b, ordered from a to b.
// `order` sorts the vertices by their rounded x.  On the cached roundings:
// m is on the line ab when |u × (m − a)|² = 0 (u = b − a; arc_side), inside
// the segment when ⟨m − a, u⟩ > 0 > ⟨m − b, u⟩ (dot_sign), and x comes
// before y along it when ⟨y − x, u⟩ > 0.
std::vector<Index> inner_vertices(Index a, Index b, const std::vector<Point3>& pts, const std::vector<Vec3d>& approx,
                                  const std::vector<Index>& order) {
  Box box;
  box.add(approx[a]);
  box.add(approx[b]);
  auto first = std::lower_bound(order.begin(), order.end(), box.lo[0],
                                [&](Index v, double x) { return approx[v].x < x; });
  auto rounded = [&](Index v) { return RoundedPoint3{pts[v], approx[v]}; };
  const RoundedPoint3 ra = rounded(a), rb = rounded(b);
  std::vector<Index> out;
  for (auto it = first; it != order.end() && approx[*it].x <= box.hi[0]; ++it) {
    const Index m = *it;
    if (m == a || m == b) continue;
    const Vec3d& q = approx[m];
    if (q.y < box.lo[1] || q.y > box.hi[1] || q.z < box.lo[2] || q.z > box.hi[2]) continue;
    const RoundedPoint3 rm = rounded(m);
    if (arc_side(ra, rb, ra, rm, ra, rb, rm) != 0) continue;
    if (dot_sign(ra, rm, ra, rb) > 0 && dot_sign(rb, rm, ra, rb) < 0) out.push_back(m);
  }
  if (out.size() > 1)
    std::sort(out.begin(), out.end(),
              [&](Index x, Index y) { return dot_sign(rounded(x), rounded(y), ra, rb) > 0; });
  return out;
}

// A vertex of a plane in the plane's two coordinates.
struct V2 {
  Rational u, v;
};

// The points where two of the edges cross, inside both (not at an end of
// either), found among the pairs whose rounded boxes meet (approx: the
// points' nearest doubles).  Segments ab and cd cross inside both exactly
// when they are coplanar, c and d lie strictly on either side of the line
// ab in their plane, and a and b strictly on either side of the line cd:
// with u = b − a, the sides of c and d are opposite when
// ⟨u × (c − a), u × (d − a)⟩ < 0 (both vectors are normals of the common
// plane, of the same direction when c and d are on the same side, zero
// when one is on the line), which is arc_side(a, b, a, c, a, b, d).  Two
// parallel segments fail the first test (c and d on one side or on the
// line).  Only a crossing is computed, in rationals.  The pairs of one
// segment in parallel; the points in the order of the segments.
std::vector<Point3> crossings(const std::vector<std::vector<std::pair<Index, Index>>>& edges,
                              const std::vector<Point3>& pts, const std::vector<Vec3d>& approx,
                              unsigned threads) {
  std::vector<std::pair<Index, Index>> all;
  for (const auto& plane : edges)
    for (auto [a, b] : plane) all.emplace_back(std::min(a, b), std::max(a, b));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::vector<Box> box(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    box[i].add(approx[all[i].first]);
    box[i].add(approx[all[i].second]);
  }
  std::vector<std::size_t> order(all.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return box[x].lo[0] < box[y].lo[0]; });
  auto rounded = [&](Index v) { return RoundedPoint3{pts[v], approx[v]}; };
  // The boxes in that order, in a grid: each segment is compared with the
  // later ones whose boxes meet its own, in their order (a sweep along x
  // alone would look at every segment of the slab its x-range spans).
  std::vector<Box> sorted(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = box[order[i]];
  const PieceGrid grid(sorted);
  std::vector<std::vector<Point3>> found(order.size());
  parallel_for(order.size(), parallel_threads(threads, order.size() / 1024 + 1), [&](std::size_t i) {
    const auto [a, b] = all[order[i]];
    const RoundedPoint3 ra = rounded(a), rb = rounded(b);
    thread_local std::vector<Index> near;
    grid.query(sorted[i], near);  // ascending, boxes meeting sorted[i]
    for (Index j : near) {
      if (j <= i) continue;
      const auto [c, d] = all[order[j]];
      if (a == c || a == d || b == c || b == d) continue;
      const RoundedPoint3 rc = rounded(c), rd = rounded(d);
      if (orient3d(ra, rb, rc, rd) != 0) continue;
      if (arc_side(ra, rb, ra, rc, ra, rb, rd) >= 0 || arc_side(rc, rd, rc, ra, rc, rd, rb) >= 0) continue;
      // a + s u = c + t v: s = ((w x v) . (u x v)) / |u x v|^2.
      const Point3 u = pts[b] - pts[a], v = pts[d] - pts[c], w = pts[c] - pts[a];
      const Point3 uv = cross(u, v);
      found[i].push_back(pts[a] + Rational(dot(cross(w, v), uv) / dot(uv, uv)) * u);
    }
  });
  std::vector<Point3> out;
  for (auto& f : found)
    for (Point3& p : f) out.push_back(std::move(p));
  return out;
}

// The loops of one plane's directed edges (the region on their left, in
// the frame's coordinates), each a simple cycle: at a vertex with several
// ways out, the loop takes the first one clockwise from the way it came
// back, and a loop through a vertex twice is cut there.
std::vector<std::vector<Index>> trace_loops(const std::vector<std::pair<Index, Index>>& edges,
                                            const std::vector<V2>& at) {
  std::unordered_map<Index, std::vector<std::size_t>> out_of;
  for (std::size_t e = 0; e < edges.size(); ++e) out_of[edges[e].first].push_back(e);
  std::vector<char> used(edges.size(), 0);
  std::vector<std::vector<Index>> loops;
  auto dir = [&](std::size_t e) {
    const V2& p = at[edges[e].first];
    const V2& q = at[edges[e].second];
    return std::make_pair(Rational(q.u - p.u), Rational(q.v - p.v));
  };
  auto crs = [](const std::pair<Rational, Rational>& x, const std::pair<Rational, Rational>& y) {
    return sgn(x.first * y.second - x.second * y.first);
  };
  auto dt = [](const std::pair<Rational, Rational>& x, const std::pair<Rational, Rational>& y) {
    return sgn(x.first * y.first + x.second * y.second);
  };
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (used[start]) continue;
    std::vector<Index> walk;
    std::size_t e = start;
    while (true) {
      used[e] = 1;
      walk.push_back(edges[e].first);
      const auto& outs = out_of[edges[e].second];
      std::size_t best = SIZE_MAX;
      if (outs.size() == 1) {
        best = outs[0];
      } else {
        // Counter-clockwise order from r (the way back); the last one is the
        // first clockwise.
        auto [du, dv] = dir(e);
        const std::pair<Rational, Rational> r(-du, -dv);
        auto half = [&](const std::pair<Rational, Rational>& w) {
          const int c = crs(r, w);
          return (c > 0 || (c == 0 && dt(r, w) > 0)) ? 0 : 1;
        };
        std::pair<Rational, Rational> wb;
        int hb = 0;
        for (std::size_t o : outs) {
          if (used[o] && o != start) continue;
          auto w = dir(o);
          const int h = half(w);
          if (best == SIZE_MAX || h > hb || (h == hb && crs(wb, w) > 0)) {
            best = o;
            wb = std::move(w);
            hb = h;
          }
        }
      }
      if (best == SIZE_MAX || (used[best] && best != start))
        throw std::logic_error("union boundary: a loop of a plane does not close");
      if (best == start) break;
      e = best;
    }
    // Cut at repeated vertices.
    std::vector<Index> stack;
    std::unordered_map<Index, std::size_t> pos;
    for (Index v : walk) {
      auto it = pos.find(v);
      if (it != pos.end()) {
        const std::size_t p = it->second;
        loops.emplace_back(stack.begin() + std::ptrdiff_t(p), stack.end());
        for (std::size_t i = p + 1; i < stack.size(); ++i) pos.erase(stack[i]);
        stack.resize(p + 1);
      } else {
        pos.emplace(v, stack.size());
        stack.push_back(v);
      }
    }
    loops.push_back(std::move(stack));
  }
  return loops;
}

Rational twice_area(const std::vector<Index>& loop, const std::vector<V2>& at) {
  Rational s = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const V2& p = at[loop[i]];
    const V2& q = at[loop[(i + 1) % loop.size()]];
    s += p.u * q.v - p.v * q.u;
  }
  return s;
}

// Whether m lies inside the loop (m on none of its edges).
bool encloses(const std::vector<Index>& loop, const std::vector<V2>& at, const Rational& mu, const Rational& mv) {
  bool in = false;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const V2& p = at[loop[i]];
    const V2& q = at[loop[(i + 1) % loop.size()]];
    if ((cmp(p.v, mv) > 0) == (cmp(q.v, mv) > 0)) continue;
    // The crossing is right of m when (q - p) x (m - p) has the sign of q.v - p.v's opposite.
    const int c = sgn((q.u - p.u) * (mv - p.v) - (mu - p.u) * (q.v - p.v));
    if (c * sgn(q.v - p.v) > 0) in = !in;
  }
  return in;
}

// The faces of one plane from its traced loops: an outer loop alone is one
// face; an outer loop with holes or slits is triangulated.
std::vector<std::vector<Index>> plane_faces(const std::vector<std::vector<Index>>& loops, const std::vector<V2>& at) {
  // Counter-clockwise loops are outer boundaries, clockwise ones holes, and
  // loops of two vertices (there and back) slits inside a face.
  std::vector<std::size_t> outer, hole;
  std::vector<Rational> area(loops.size());
  for (std::size_t i = 0; i < loops.size(); ++i) {
    area[i] = twice_area(loops[i], at);
    (sgn(area[i]) > 0 ? outer : hole).push_back(i);
  }
  std::vector<std::vector<std::size_t>> holes_of(loops.size());
  for (std::size_t h : hole) {
    const V2& p = at[loops[h][0]];
    const V2& q = at[loops[h][1]];
    const Rational mu = (p.u + q.u) / 2, mv = (p.v + q.v) / 2;
    std::size_t best = SIZE_MAX;
    for (std::size_t o : outer)
      if ((best == SIZE_MAX || cmp(area[o], area[best]) < 0) && encloses(loops[o], at, mu, mv)) best = o;
    if (best == SIZE_MAX) throw std::logic_error("union boundary: a hole outside every face");
    holes_of[best].push_back(h);
  }
  std::vector<std::vector<Index>> faces;
  for (std::size_t o : outer) {
    if (holes_of[o].empty()) {
      faces.push_back(loops[o]);
      continue;
    }
    std::vector<std::vector<PlanePoint>> region;
    for (std::size_t l : [&] {
           std::vector<std::size_t> all{o};
           all.insert(all.end(), holes_of[o].begin(), holes_of[o].end());
           return all;
         }()) {
      std::vector<PlanePoint> loop;
      for (Index v : loops[l]) loop.push_back(PlanePoint{at[v].u, at[v].v, v});
      region.push_back(std::move(loop));
    }
    for (const auto& t : triangulate_region(region)) faces.push_back({t[0], t[1], t[2]});
  }
  return faces;
}

}  // namespace

long lazy_plane_scale(const Integer m[3]) {
  std::size_t bits = 0;
  for (int j = 0; j < 3; ++j)
    if (sgn(m[j]) != 0) bits = std::max(bits, mpz_sizeinbase(m[j].get_mpz_t(), 2));
  return bits >= 480 ? long(bits) - 470 : 0;
}

void lazy_plane_doubles(const Integer m[3], const Integer& num, const Integer& den, LazyPlane& out) {
  const long k = lazy_plane_scale(m);
  bool usable = scaled_filter_double(m[0], k, out.a);
  usable = scaled_filter_double(m[1], k, out.b) && usable;
  usable = scaled_filter_double(m[2], k, out.c) && usable;
  if (k == 0) {
    out.d = truncated_ratio(num, den);
  } else {
    Integer scaled_den;
    mpz_mul_2exp(scaled_den.get_mpz_t(), den.get_mpz_t(), mp_bitcnt_t(k));
    out.d = truncated_ratio(num, scaled_den);
  }
  out.filtered = usable && std::isfinite(out.d) && std::fabs(out.d) < kHalfSpaceFilterMax &&
                 (out.d == 0 ? sgn(num) == 0 : std::fabs(out.d) >= kHalfSpaceFilterMin);
}

DirectionIndex::DirectionIndex(std::vector<Vec3d> unit_normals) : normals_(std::move(unit_normals)) {
  if (normals_.empty() || normals_.size() > 65535) {
    normals_.clear();
    return;
  }
  width_ = std::min<std::size_t>(kBest, normals_.size());
  cell_.resize(std::size_t(6) * kCells * kCells * width_);
  filled_ = std::make_unique<std::once_flag[]>(std::size_t(6) * kCells * kCells);
}

std::array<double, 3> DirectionIndex::cell_centre(int face, int i, int j) {
  const int axis = face / 2;
  std::array<double, 3> d;
  d[axis] = face % 2 ? -1.0 : 1.0;
  d[(axis + 1) % 3] = (2.0 * i + 1.0) / kCells - 1.0;
  d[(axis + 2) % 3] = (2.0 * j + 1.0) / kCells - 1.0;
  return d;
}

void DirectionIndex::fill(int face, int i, int j, std::uint16_t* out) const {
  // The width_ normals of largest dot product with the cell's centre,
  // largest first, equal ones in index order: each normal is inserted into
  // the short sorted list when it beats its last (a later normal never goes
  // before an equal one).
  const std::array<double, 3> d = cell_centre(face, i, j);
  double top[kBest];
  std::size_t filled = 0;
  for (std::size_t q = 0; q < normals_.size(); ++q) {
    const double x = normals_[q].x * d[0] + normals_[q].y * d[1] + normals_[q].z * d[2];
    if (filled == width_ && !(x > top[width_ - 1])) continue;
    std::size_t at = filled < width_ ? filled++ : width_ - 1;
    for (; at > 0 && x > top[at - 1]; --at) {
      top[at] = top[at - 1];
      out[at] = out[at - 1];
    }
    top[at] = x;
    out[at] = std::uint16_t(q);
  }
}

std::size_t DirectionIndex::best(const double d[3], const std::uint16_t*& out) const {
  out = nullptr;
  if (normals_.empty()) return 0;
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (std::fabs(d[c]) > std::fabs(d[axis])) axis = c;
  const double m = std::fabs(d[axis]);
  if (!(m > 0) || !std::isfinite(m)) return 0;
  auto index = [&](double x) {
    const double t = (x / m + 1.0) * 0.5 * kCells;  // in [0, kCells] (|x| <= m), NaN taken as 0
    return t >= 0 ? int(std::min(t, double(kCells - 1))) : 0;
  };
  const int face = 2 * axis + (d[axis] < 0 ? 1 : 0);
  const int i = index(d[(axis + 1) % 3]), j = index(d[(axis + 2) % 3]);
  const std::size_t cell = (std::size_t(face) * kCells + std::size_t(i)) * kCells + std::size_t(j);
  std::uint16_t* list = &cell_[cell * width_];
  // Each cell's list is made when first asked for (a small union asks for
  // a few hundred of the 6144), once, whichever thread asks first; the
  // others wait for it.
  std::call_once(filled_[cell], [&] { fill(face, i, j, list); });
  out = list;
  return width_;
}

Piece piece_of(const ConvexPolytope& p, const std::vector<char>* candidate) {
  Piece out;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] = INFINITY;
    out.hi[k] = -INFINITY;
  }
  // approx(v): the nearest doubles of the exact point.
  for (Index v = 0; v < p.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      out.lo[k] = std::min(out.lo[k], p.approx(v)[k]);
      out.hi[k] = std::max(out.hi[k], p.approx(v)[k]);
    }
  for (Index f = 0; f < p.num_facets(); ++f) {
    out.planes.push_back(p.plane(f));
    if (candidate && !(*candidate)[f]) continue;
    out.candidates.push_back(f);
    std::vector<Point3> loop;
    for (Index v : p.facet_vertices(f)) loop.push_back(p.point(v));
    out.loops.push_back(std::move(loop));
  }
  return out;
}

void union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out,
                    unsigned threads) {
  std::vector<Piece> pieces(parts.size());
  parallel_for(parts.size(), parallel_threads(threads, parts.size()),
               [&](std::size_t i) { pieces[i] = piece_of(parts[i]); });
  union_boundary(pieces, options, out, threads);
}

void union_boundary(const std::vector<Piece>& parts, const SumOptions& options, NonconvexSum& out, unsigned threads,
                    const std::function<bool(const Point3&)>& interior) {
  auto t0 = Clock::now();
  options.report("union", 0.0);
  static std::atomic<std::uint64_t> unions{0};
  const std::uint64_t generation = ++unions;
  const unsigned all_workers = parallel_threads(threads, parts.size());
  // Boxes and half-spaces of the pieces (in parallel).
  std::vector<Box> boxes(parts.size());
  std::vector<HalfSet> halves(parts.size());
  parallel_for(parts.size(), all_workers, [&](std::size_t i) {
    for (int k = 0; k < 3; ++k) {
      boxes[i].lo[k] = parts[i].lo[k];
      boxes[i].hi[k] = parts[i].hi[k];
    }
    const Piece& p = parts[i];
    halves[i].piece = &p;
    halves[i].generation = generation;
    halves[i].held.reserve(p.planes.size());
    for (const Plane& h : p.planes) halves[i].held.push_back(half_of(h));
  });
  const PieceGrid grid(boxes);
  // Candidate facets by oriented plane; then the other facets on those
  // planes (their pieces lie below the plane and remove nothing there).
  struct Group {
    const Plane* plane;
    std::vector<FacetRef> facets;
    std::vector<Index> below;
  };
  struct PlaneHash {
    std::size_t operator()(const Plane* p) const {
      std::size_t h = 0;
      for (const Integer* x : {&p->a, &p->b, &p->c, &p->d})
        h = h * 1000003u ^ (std::size_t(mpz_get_ui(x->get_mpz_t())) + std::size_t(mpz_sgn(x->get_mpz_t()) + 1));
      return h;
    }
  };
  struct PlaneEq {
    bool operator()(const Plane* p, const Plane* q) const { return *p == *q; }
  };
  std::unordered_map<const Plane*, std::size_t, PlaneHash, PlaneEq> group_of;
  std::vector<Group> groups;
  // The candidates' planes also by their lazy doubles (the primitive normal
  // and the offset along it, each rounded towards zero): a lazy plane equal
  // to one of them has the same doubles.  A held candidate's are made only
  // when some piece has lazy planes (the sweep's pieces are all lazy, the
  // others all held: usually none is needed).
  struct DoublesHash {
    std::size_t operator()(const std::array<double, 4>& k) const {
      std::size_t h = 0;
      for (double x : k) h = h * 1000003u ^ std::hash<double>()(x);
      return h;
    }
  };
  std::unordered_multimap<std::array<double, 4>, std::size_t, DoublesHash> lazy_group_of;
  bool any_lazy = false;
  for (const Piece& p : parts) any_lazy = any_lazy || !p.lazy.empty();
  bool labelled = !parts.empty() && parts.front().builder;
  for (const Piece& p : parts) labelled = labelled && p.builder == parts.front().builder;
  for (Index i = 0; i < parts.size(); ++i)
    for (Index f = 0; f < parts[i].candidates.size(); ++f) {
      const Index k = parts[i].candidates[f];
      const Plane* pl = parts[i].held(k);
      auto [it, fresh] = group_of.emplace(pl, groups.size());
      if (fresh) {
        groups.push_back(Group{pl, {}, {}});
        if (k < parts[i].lazy.size()) {
          const LazyPlane& l = parts[i].lazy[k];
          lazy_group_of.emplace(std::array<double, 4>{l.a, l.b, l.c, l.d}, it->second);
        } else if (any_lazy) {
          lazy_group_of.emplace(lazy_doubles(*pl), it->second);
        }
      }
      groups[it->second].facets.push_back(FacetRef{i, f});
    }
  // Each piece's other facets on those planes, in parallel (a lazy one is
  // built only when its doubles match a candidate's), then gathered in the
  // order of the pieces.
  std::vector<std::vector<std::size_t>> below_of(parts.size());
  parallel_for(parts.size(), all_workers, [&](std::size_t i) {
    const Piece& p = parts[i];
    const std::vector<Index>& c = p.candidates;  // ascending
    for (Index f = 0, next = 0; f < p.num_planes(); ++f) {
      if (next < c.size() && c[next] == f) {
        ++next;
        continue;
      }
      if (f < p.lazy.size()) {
        const LazyPlane& l = p.lazy[f];
        auto range = lazy_group_of.equal_range(std::array<double, 4>{l.a, l.b, l.c, l.d});
        if (range.first == range.second) continue;
        const Plane exact = p.plane(f);
        for (auto it = range.first; it != range.second; ++it)
          if (*groups[it->second].plane == exact) below_of[i].push_back(it->second);
        continue;
      }
      auto it = group_of.find(&p.planes[f - p.lazy.size()]);
      if (it != group_of.end()) below_of[i].push_back(it->second);
    }
  });
  for (Index i = 0; i < parts.size(); ++i)
    for (std::size_t g : below_of[i]) groups[g].below.push_back(i);
  below_of.clear();
  lazy_group_of.clear();
  group_of.clear();
  // In the order of the planes, so that the output does not depend on the
  // order of the pieces' facets.
  std::sort(groups.begin(), groups.end(), [](const Group& x, const Group& y) { return *x.plane < *y.plane; });
  std::vector<const Group*> planes;
  for (const auto& entry : groups) planes.push_back(&entry);
  const std::size_t n = planes.size();
  std::vector<PlaneResult> results(n);
  const unsigned workers = parallel_threads(threads, n);
  const std::size_t batch = std::max<std::size_t>(64, std::size_t(workers) * 16);
  // The planes are done in the Morton order of the centres of their first
  // facets' pieces, so that consecutive planes read the same neighbouring
  // pieces, still in the cache (in the order of the planes, neighbours on
  // the surface are far apart in the list); each result keeps its place.
  std::vector<Vec3d> centre(n);
  for (std::size_t g = 0; g < n; ++g) {
    const Piece& p = parts[planes[g]->facets.front().piece];
    centre[g] = Vec3d{p.lo[0] / 2 + p.hi[0] / 2, p.lo[1] / 2 + p.hi[1] / 2, p.lo[2] / 2 + p.hi[2] / 2};
  }
  const std::vector<std::size_t> visit = morton_order(centre);
  for (std::size_t start = 0; start < n; start += batch) {
    const std::size_t count = std::min(batch, n - start);
    parallel_for(count, workers, [&](std::size_t k) {
      const std::size_t at = visit[start + k];
      const Group& g = *planes[at];
      results[at] = plane_boundary(*g.plane, g.facets, g.below, parts, halves, grid, labelled);
    });
    options.report("union", double(start + count) / double(n));
  }
  // Slits: a boundary segment of one plane lying in another plane, inside
  // that plane's face rather than along its boundary (the solid touching the
  // face from outside along that segment); those planes are done again with
  // their slits.
  {
    struct Item {
      std::size_t plane;
      const Segment* segment;
      Box box;
      V3 a, b;  // the ends with their nearest doubles, for the plane tests
    };
    std::vector<Item> items;
    for (std::size_t g = 0; g < n; ++g)
      for (const Segment& sg : results[g].segments) {
        Item it{g, &sg, {}, make_v3(sg.a, sg.da), make_v3(sg.b, sg.db)};
        it.box.add(it.a.d);
        it.box.add(it.b.d);
        items.push_back(std::move(it));
      }
    std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.box.lo[0] < y.box.lo[0]; });
    // The segments' boxes in a grid, so that a plane looks only at the
    // segments whose boxes meet its face's, in their order.
    std::vector<Box> item_boxes;
    item_boxes.reserve(items.size());
    for (const Item& it : items) item_boxes.push_back(it.box);
    const PieceGrid item_grid(item_boxes);
    std::vector<std::vector<Segment>> slits(n);
    parallel_for(n, workers, [&](std::size_t k) {
      const std::size_t g = visit[k];  // (in the order the planes were done)
      const std::vector<Segment>& own = results[g].segments;
      if (own.empty()) return;
      Box region;
      for (const Segment& sg : own) {
        region.add(sg.da);
        region.add(sg.db);
      }
      const Half h = half_of(*planes[g]->plane);
      const Frame frame(*planes[g]->plane);
      std::map<LineKey, std::vector<std::pair<Rational, Rational>>> along;  // own stretches by line
      bool indexed = false;
      // This plane's own segments by the nearest doubles of their two ends
      // (unordered): most segments of other planes found here are shared
      // edges, the same segment, which is covered (checked exactly).
      auto end_hash = [](const Vec3d& p, const Vec3d& q) {
        auto one = [](const Vec3d& v) {
          return std::hash<double>()(v.x) ^ (std::hash<double>()(v.y) * 31u) ^ (std::hash<double>()(v.z) * 1000003u);
        };
        return one(p) + one(q);
      };
      std::unordered_multimap<std::size_t, const Segment*> own_ends;
      own_ends.reserve(own.size());
      for (const Segment& sg : own) own_ends.emplace(end_hash(sg.da, sg.db), &sg);
      auto is_own = [&](const Item& it) {
        auto [lo, hi] = own_ends.equal_range(end_hash(it.a.d, it.b.d));
        for (auto e = lo; e != hi; ++e) {
          const Segment& sg = *e->second;
          if ((sg.a == *it.a.p && sg.b == *it.b.p) || (sg.a == *it.b.p && sg.b == *it.a.p)) return true;
        }
        return false;
      };
      std::vector<Index> near;
      item_grid.query(region, near);
      for (Index at : near) {
        const Item& it = items[at];
        if (it.plane == g) continue;
        if (is_own(it)) continue;
        // Both ends on the plane; the filter first for both (an end shared
        // with this face's boundary is exactly on it, which only the exact
        // evaluation shows).
        {
          const auto fa = side_filter(h, it.a), fb = side_filter(h, it.b);
          if ((fa && *fa != 0) || (fb && *fb != 0)) continue;
        }
        if (side(h, it.a) != 0 || side(h, it.b) != 0) continue;
        if (!indexed) {
          for (const Segment& sg : own) {
            OnLine o = on_line(frame, sg.a, sg.b);
            along[o.key].push_back(cmp(o.tp, o.tq) < 0 ? std::make_pair(o.tp, o.tq) : std::make_pair(o.tq, o.tp));
          }
          for (auto& [key, v] : along)
            std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) { return cmp(x.first, y.first) < 0; });
          indexed = true;
        }
        // Covered by this plane's own boundary stretches: not a slit.
        OnLine o = on_line(frame, it.segment->a, it.segment->b);
        Rational from = cmp(o.tp, o.tq) < 0 ? o.tp : o.tq;
        const Rational to = cmp(o.tp, o.tq) < 0 ? o.tq : o.tp;
        auto found = along.find(o.key);
        if (found != along.end())
          for (const auto& [lo, hi] : found->second)
            if (cmp(lo, from) <= 0 && cmp(hi, from) > 0) from = hi;
        if (cmp(from, to) < 0) slits[g].push_back(*it.segment);
      }
    });
    std::vector<PlaneResult> redone(n);
    parallel_for(n, workers, [&](std::size_t g) {
      if (!slits[g].empty())
        redone[g] =
            plane_boundary(*planes[g]->plane, planes[g]->facets, planes[g]->below, parts, halves, grid, labelled, slits[g]);
    });
    for (std::size_t g = 0; g < n; ++g)
      if (!slits[g].empty()) results[g] = std::move(redone[g]);
  }
  out.clips = 0;
  for (const auto& r : results) out.clips += r.clips;
  out.seconds_union = since(t0);

  t0 = Clock::now();
  options.report("boundary", -1.0);
  // Weld exactly equal points: looked up by their nearest doubles (equal
  // points have equal ones), then compared exactly among the points with
  // the same doubles.  The segments' ends are spread over partitions by the
  // hash of their doubles, each partition sorted and grouped on its own (in
  // parallel); a point's number is the order of its first appearance, plane
  // after plane, segment after segment, a before b.
  std::vector<std::size_t> base(n + 1, 0);
  for (std::size_t g = 0; g < n; ++g) base[g + 1] = base[g] + results[g].segments.size();
  struct End {
    std::array<double, 3> key;
    std::size_t at;  // 2 (segment number) + 0 for a, 1 for b
    Point3* p;  // (moved into pts when it is the first of its value)
  };
  auto key_hash = [](const std::array<double, 3>& k) {
    std::size_t h = 0;
    for (double x : k) h = h * 1000003u ^ std::hash<double>()(x);
    return h;
  };
  auto key_less = [](const End& x, const End& y) { return x.key != y.key ? x.key < y.key : x.at < y.at; };
  const std::size_t ends = 2 * base[n];
  std::vector<End> end(ends);
  parallel_for(n, workers, [&](std::size_t g) {
    for (std::size_t i = 0; i < results[g].segments.size(); ++i) {
      Segment& sg = results[g].segments[i];
      const std::size_t at = 2 * (base[g] + i);
      const Vec3d& a = sg.da;
      const Vec3d& b = sg.db;
      end[at] = End{{a.x, a.y, a.z}, at, &sg.a};
      end[at + 1] = End{{b.x, b.y, b.z}, at + 1, &sg.b};
    }
  });
  const std::size_t parts_count = std::max<std::size_t>(1, std::min<std::size_t>(256, ends / 4096 + 1));
  std::vector<std::vector<End>> part(parts_count);
  for (const End& e : end) part[key_hash(e.key) % parts_count].push_back(e);
  // first[at]: the position of the first end exactly equal to this one.
  std::vector<std::size_t> first(ends);
  parallel_for(parts_count, parallel_threads(threads, parts_count), [&](std::size_t q) {
    std::vector<End>& v = part[q];
    std::sort(v.begin(), v.end(), key_less);
    std::vector<const End*> reps;  // of one run of equal doubles, in order of position
    for (std::size_t i = 0; i < v.size();) {
      std::size_t j = i;
      reps.clear();
      for (; j < v.size() && v[j].key == v[i].key; ++j) {
        const End* rep = nullptr;
        for (const End* r : reps)
          if (*r->p == *v[j].p) {
            rep = r;
            break;
          }
        if (!rep) reps.push_back(rep = &v[j]);
        first[v[j].at] = rep->at;
      }
      i = j;
    }
  });
  std::vector<Point3> pts;
  std::vector<Vec3d> approx;
  std::vector<Index> id(ends);
  for (std::size_t at = 0; at < ends; ++at) {
    if (first[at] != at) {
      id[at] = id[first[at]];
      continue;
    }
    id[at] = Index(pts.size());
    pts.push_back(std::move(*end[at].p));
    approx.push_back(Vec3d{end[at].key[0], end[at].key[1], end[at].key[2]});
  }
  std::vector<std::vector<std::pair<Index, Index>>> edges(n);
  for (std::size_t g = 0; g < n; ++g)
    for (std::size_t i = 0; i < results[g].segments.size(); ++i)
      edges[g].emplace_back(id[2 * (base[g] + i)], id[2 * (base[g] + i) + 1]);
  // A point not among the ends (a crossing below): looked up in its
  // partition, then among the points added so far.
  std::unordered_multimap<std::array<double, 3>, Index, decltype(key_hash)> added(16, key_hash);
  auto weld = [&](Point3& p, const Vec3d& d) {
    const std::array<double, 3> key{d.x, d.y, d.z};
    const std::vector<End>& v = part[key_hash(key) % parts_count];
    for (auto it = std::lower_bound(v.begin(), v.end(), End{key, 0, nullptr}, key_less);
         it != v.end() && it->key == key; ++it)
      if (pts[id[it->at]] == p) return;
    auto range = added.equal_range(key);
    for (auto it = range.first; it != range.second; ++it)
      if (pts[it->second] == p) return;
    added.emplace(key, Index(pts.size()));
    pts.push_back(std::move(p));
    approx.push_back(d);
  };
  // Two edges crossing at a point inside both (the solid touching itself at
  // a point there): the point becomes a vertex of both.
  for (Point3& x : crossings(edges, pts, approx, threads)) {
    const Vec3d d = to_double(x);
    weld(x, d);
  }
  // The segments' other copies of the points (a million rationals on a
  // large sum): handed to the caller's release, else freed on every thread.
  if (options.release)
    options.release(std::make_shared<std::vector<PlaneResult>>(std::move(results)));
  else
    parallel_for(n, workers, [&](std::size_t g) { results[g] = PlaneResult(); });
  results.clear();
  part.clear();
  end.clear();
  added.clear();
  std::vector<Index> order(pts.size());
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index x, Index y) { return approx[x].x < approx[y].x; });

  // Per plane: every vertex inside an edge inserted into it, loops, faces.
  std::vector<std::vector<std::vector<Index>>> faces(n);
  parallel_for(n, workers, [&](std::size_t g) {
    const Frame frame(*planes[g]->plane);
    std::vector<std::pair<Index, Index>> split;
    for (auto [a, b] : edges[g]) {
      Index prev = a;
      for (Index m : inner_vertices(a, b, pts, approx, order)) {
        split.emplace_back(prev, m);
        prev = m;
      }
      split.emplace_back(prev, b);
    }
    // The loops' coordinates in the plane's frame, by vertex.
    std::vector<V2> at;
    std::vector<Index> local_id;
    std::unordered_map<Index, Index> id;
    for (auto& [a, b] : split)
      for (Index* v : {&a, &b}) {
        auto [it, fresh] = id.emplace(*v, Index(at.size()));
        if (fresh) {
          at.push_back(V2{pts[*v][frame.iu], pts[*v][frame.iv]});
          local_id.push_back(*v);
        }
        *v = it->second;
      }
    for (auto& f : plane_faces(trace_loops(split, at), at)) {
      for (Index& v : f) v = local_id[v];
      faces[g].push_back(std::move(f));
    }
  });

  if (interior) {
    // The connected components of the boundary (faces sharing a vertex);
    // those whose vertex the caller calls interior are dropped, then the
    // points no face uses.
    std::vector<Index> parent(pts.size());
    std::iota(parent.begin(), parent.end(), Index(0));
    auto find = [&](Index v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    for (const auto& plane_faces : faces)
      for (const auto& f : plane_faces)
        for (Index v : f) parent[find(v)] = find(f[0]);
    // One vertex per component (the first face's first), asked in parallel.
    std::vector<signed char> drop(pts.size(), -1);  // by root: -1 not asked yet
    std::vector<Index> asked;
    for (const auto& plane_faces : faces)
      for (const auto& f : plane_faces) {
        const Index r = find(f[0]);
        if (drop[r] < 0) {
          drop[r] = 0;
          asked.push_back(f[0]);
        }
      }
    std::vector<char> inside(asked.size());
    parallel_for(asked.size(), parallel_threads(threads, asked.size()),
                 [&](std::size_t k) { inside[k] = interior(pts[asked[k]]) ? 1 : 0; });
    for (std::size_t k = 0; k < asked.size(); ++k) {
      drop[find(asked[k])] = static_cast<signed char>(inside[k]);
      out.dropped_components += std::size_t(inside[k]);
    }
    std::vector<Index> renumber(pts.size(), Index(-1));
    std::vector<Point3> kept;
    for (auto& plane_faces : faces) {
      std::vector<std::vector<Index>> keep;
      for (auto& f : plane_faces) {
        if (drop[find(f[0])] == 1) continue;
        for (Index& v : f) {
          if (renumber[v] == Index(-1)) {
            renumber[v] = Index(kept.size());
            kept.push_back(std::move(pts[v]));  // (pts is replaced below; each v is moved once)
          }
          v = renumber[v];
        }
        keep.push_back(std::move(f));
      }
      plane_faces = std::move(keep);
    }
    pts = std::move(kept);
  }
  out.mesh = Mesh{};
  out.mesh.points.reserve(pts.size());
  for (Point3& p : pts) out.mesh.points.push_back(std::move(p));
  std::vector<Index> face_plane;
  for (std::size_t g = 0; g < n; ++g)
    for (auto& f : faces[g]) {
      out.mesh.faces.push_back(std::move(f));
      face_plane.push_back(Index(g));
    }

  // Shells: the number of bounded volumes the boundary encloses (solid
  // parts and cavities; by Alexander duality the dimension of its space of
  // 2-cycles mod 2).  Faces are linked across each edge twice: across the
  // solid between them and across the empty space between them (for an edge
  // of two faces both links join the same pair; around an edge of more than
  // two faces, each face to its neighbour on its solid side and on its empty
  // side).  The classes of either linking are closed surfaces (2-cycles)
  // that together span all of them, and the only relations are one per
  // class of both linkings together: volumes = solid classes + empty
  // classes - joint classes (for a 2-manifold boundary, its shells).
  const std::vector<std::vector<Index>>& mf = out.mesh.faces;
  struct Classes {
    std::vector<std::size_t> parent;
    explicit Classes(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
    std::size_t find(std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    }
    void join(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
    std::size_t count() {
      std::size_t c = 0;
      for (std::size_t i = 0; i < parent.size(); ++i) c += find(i) == i;
      return c;
    }
  };
  Classes solid(mf.size()), empty(mf.size()), both(mf.size());
  std::map<std::pair<Index, Index>, std::vector<std::size_t>> around;  // undirected edge -> faces
  for (std::size_t f = 0; f < mf.size(); ++f)
    for (std::size_t i = 0; i < mf[f].size(); ++i) {
      const Index a = mf[f][i], b = mf[f][(i + 1) % mf[f].size()];
      around[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  out.non_manifold_edges = 0;
  for (const auto& [e, fs] : around) {
    if (fs.size() == 2) {
      solid.join(fs[0], fs[1]);
      empty.join(fs[0], fs[1]);
      both.join(fs[0], fs[1]);
      continue;
    }
    ++out.non_manifold_edges;
    // The edge's direction D = b - a; each face's way into itself from the
    // edge, w = n x (its direction of the edge); angles about D.
    const Point3 d = out.mesh.points.exact(e.second) - out.mesh.points.exact(e.first);
    struct Around {
      std::size_t face;
      Point3 w;
      bool solid_ccw;  // the solid lies on its counter-clockwise side about D
    };
    std::vector<Around> list;
    for (std::size_t f : fs) {
      const Plane& h = *planes[face_plane[f]]->plane;
      const Point3 nrm = h.normal();
      // The face runs a -> b or b -> a.
      bool forward = false;
      for (std::size_t i = 0; i < mf[f].size(); ++i)
        if (mf[f][i] == e.first && mf[f][(i + 1) % mf[f].size()] == e.second) forward = true;
      const Point3 w = cross(nrm, forward ? d : -d);
      list.push_back({f, w, sgn(dot(cross(d, w), nrm)) < 0});
    }
    const Point3 e1 = list[0].w, e2 = cross(d, e1);
    auto coords = [&](const Point3& w) { return std::make_pair(dot(w, e1), dot(w, e2)); };
    auto half = [&](const Point3& w) {
      auto [x, y] = coords(w);
      return (sgn(y) > 0 || (sgn(y) == 0 && sgn(x) > 0)) ? 0 : 1;
    };
    std::sort(list.begin(), list.end(), [&](const Around& p, const Around& q) {
      const int hp = half(p.w), hq = half(q.w);
      if (hp != hq) return hp < hq;
      auto [px, py] = coords(p.w);
      auto [qx, qy] = coords(q.w);
      return sgn(px * qy - py * qx) > 0;
    });
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::size_t f = list[i].face, next = list[(i + 1) % list.size()].face;
      (list[i].solid_ccw ? solid : empty).join(f, next);
      both.join(f, next);
    }
  }
  out.shells = solid.count() + empty.count() - both.count();
  out.seconds_boundary = since(t0);
}

}  // namespace minksum::nonconvex_detail
