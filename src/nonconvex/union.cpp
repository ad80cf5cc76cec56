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
// Each facet is cut in its plane's two coordinates by successive half-plane
// splits (convex fragments); the fragments of one plane are merged back
// into maximal faces by cancelling opposite edges along each line; the
// faces of all planes are welded at exactly equal points, every vertex lying
// inside an edge is inserted into it, and each plane's edges are traced
// into loops (holes triangulated).  Every decision is the sign of an exact
// polynomial, decided by a double filter with a proved bound when it can,
// else in exact rationals.
#include <minksum/error.hpp>
#include <minksum/parallel.hpp>

#include "nonconvex/union.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace minksum::nonconvex_detail {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// ---------------------------------------------------------------------------
// The filter.  side(l, p) is the sign of a*u + b*v - c for integers a, b, c
// and rationals u, v.  With â, û... the nearest doubles (relative error at
// most 2^-53 each, u and v normal or zero) and the value evaluated in
// doubles as s = (â*û + b̂*v̂) - ĉ, the error of s is at most about
// 5 * 2^-53 * (|â*û| + |b̂*v̂| + |ĉ|) in round to nearest and twice that in a
// directed rounding mode; the filter trusts the sign of s only when |s|
// exceeds 2^-48 times that sum (more than 3x the bound in any mode), and
// only for u, v that are zero or at least 2^-960 in magnitude (no underflow
// in the products: |a|, |b| >= 1 when nonzero).  Otherwise the exact value.
constexpr double kFilterBound = 0x1p-48;
constexpr double kTiny = 0x1p-960;

bool filterable(double x, const Rational& q) {
  return std::isfinite(x) && (x == 0 ? sgn(q) == 0 : std::fabs(x) >= kTiny);
}

// A point of a plane in its frame's two coordinates, with their doubles.
struct V2 {
  Rational u, v;
  double du = 0, dv = 0;
  bool filtered = false;
};

V2 make_v2(Rational u, Rational v) {
  V2 p;
  p.du = to_double(u);
  p.dv = to_double(v);
  p.filtered = filterable(p.du, u) && filterable(p.dv, v);
  p.u = std::move(u);
  p.v = std::move(v);
  return p;
}

// The half-plane a*u + b*v <= c (inside), (a, b) != 0.
struct Line2 {
  Rational a, b, c;
  double da = 0, db = 0, dc = 0;
  bool filtered = false;
};

Rational value(const Line2& l, const V2& p) { return l.a * p.u + l.b * p.v - l.c; }

// > 0 outside, 0 on the line, < 0 inside.
int side(const Line2& l, const V2& p) {
  if (l.filtered && p.filtered) {
    const double t1 = l.da * p.du, t2 = l.db * p.dv;
    const double s = (t1 + t2) - l.dc;
    const double e = kFilterBound * (std::fabs(t1) + std::fabs(t2) + std::fabs(l.dc));
    if (s > e) return 1;
    if (s < -e) return -1;
  }
  return sgn(value(l, p));
}

// The frame of an oriented plane h: the coordinate k with the largest
// |normal_k| is dropped, the other two (u, v) are ordered so that
// counter-clockwise in (u, v) is counter-clockwise seen from outside
// (from the side the normal points to).
struct Frame {
  Plane h;
  Integer n[3];
  int k = 2, iu = 0, iv = 1, s = 1;  // s: sign of n[k]

  explicit Frame(const Plane& plane) : h(plane), n{plane.a, plane.b, plane.c} {
    for (int i = 0; i < 3; ++i)
      if (cmp(abs(n[i]), abs(n[k])) > 0) k = i;
    s = sgn(n[k]);
    iu = (k + 1) % 3;
    iv = (k + 2) % 3;
    if (s < 0) std::swap(iu, iv);
  }
  V2 project(const Point3& p) const { return make_v2(p[iu], p[iv]); }
  Point3 lift(const Rational& u, const Rational& v) const {
    Point3 p;
    p[iu] = u;
    p[iv] = v;
    p[k] = (Rational(h.d) - Rational(n[iu]) * u - Rational(n[iv]) * v) / Rational(n[k]);
    return p;
  }
  // The trace on this plane of the half-space inside the plane q:
  // q.a x + q.b y + q.c z <= q.d with x_k eliminated and multiplied by
  // |n_k|.  Returns 0 for a proper line in `out`, +1 when the whole plane
  // is inside (q parallel to it, on or beyond it), -1 when it is wholly
  // outside.
  int trace(const Plane& q, Line2& out) const {
    const Integer p[3] = {q.a, q.b, q.c};
    Integer a = s * (p[iu] * n[k] - p[k] * n[iu]);
    Integer b = s * (p[iv] * n[k] - p[k] * n[iv]);
    Integer c = s * (q.d * n[k] - p[k] * h.d);
    if (sgn(a) == 0 && sgn(b) == 0) return sgn(c) >= 0 ? 1 : -1;
    out.da = a.get_d();
    out.db = b.get_d();
    out.dc = c.get_d();
    out.filtered = std::isfinite(out.da) && std::isfinite(out.db) && std::isfinite(out.dc);
    out.a = Rational(a);
    out.b = Rational(b);
    out.c = Rational(c);
    return 0;
  }
};

using Poly = std::vector<V2>;

// A convex piece seen from one plane: the traces of its facets' half-spaces
// (empty: it does not meet the plane).
struct Trace {
  bool meets = true;
  std::vector<Line2> lines;
};

Trace trace_of(const Frame& frame, const ConvexPolytope& piece) {
  Trace t;
  for (Index f = 0; f < piece.num_facets(); ++f) {
    Line2 l;
    const int r = frame.trace(piece.plane(f), l);
    if (r < 0) return Trace{false, {}};
    if (r == 0) t.lines.push_back(std::move(l));
  }
  return t;
}

// g minus the convex region of `lines`: when their interiors meet, the convex
// parts of g outside are appended to `out` and the result is true; when
// they do not (the overlap has zero area), `out` is left as it was and the
// result is false.
bool subtract(const Poly& g, const std::vector<Line2>& lines, std::vector<Poly>& out) {
  const std::size_t mark = out.size();
  Poly rem = g;
  std::vector<int> sg;
  for (const Line2& l : lines) {
    const std::size_t n = rem.size();
    sg.resize(n);
    bool pos = false, neg = false;
    for (std::size_t i = 0; i < n; ++i) {
      sg[i] = side(l, rem[i]);
      pos |= sg[i] > 0;
      neg |= sg[i] < 0;
    }
    if (!pos) continue;  // rem inside this half-plane
    if (!neg) {          // rem outside: the overlap has no interior
      out.resize(mark);
      return false;
    }
    Poly outside, inside;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (sg[i] >= 0) outside.push_back(rem[i]);
      if (sg[i] <= 0) inside.push_back(rem[i]);
      if (sg[i] * sg[j] < 0) {
        const Rational sp = value(l, rem[i]), sq = value(l, rem[j]);
        const Rational t = sp / (sp - sq);
        V2 x = make_v2(rem[i].u + t * (rem[j].u - rem[i].u), rem[i].v + t * (rem[j].v - rem[i].v));
        outside.push_back(x);
        inside.push_back(std::move(x));
      }
    }
    out.push_back(std::move(outside));
    rem = std::move(inside);
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

// ---------------------------------------------------------------------------
// Merging the fragments of one plane: along each line of the plane, a
// fragment edge in the line's direction covers an interval with +1 (the
// fragment lies to its left), one in the opposite direction with -1; the
// fragments do not overlap, so where the sum is not zero one side only is
// covered and that stretch is on the boundary, directed by the sign.

struct LineKey {
  Integer a, b;  // primitive direction, first nonzero positive
  Rational c;    // a*v - b*u of its points
  friend bool operator<(const LineKey& x, const LineKey& y) {
    if (int r = cmp(x.a, y.a)) return r < 0;
    if (int r = cmp(x.b, y.b)) return r < 0;
    return cmp(x.c, y.c) < 0;
  }
};

struct Event {
  Rational t;
  int delta;
  const V2* point;
};

// The primitive integer vector with the direction of the rational (x, y) != 0.
std::pair<Integer, Integer> primitive(const Rational& x, const Rational& y) {
  Integer l;
  mpz_lcm(l.get_mpz_t(), x.get_den_mpz_t(), y.get_den_mpz_t());
  Integer a = x.get_num() * (l / x.get_den()), b = y.get_num() * (l / y.get_den());
  Integer g = gcd(a, b);
  return {a / g, b / g};
}

// A boundary segment of a plane's region, lifted: from a to b, the region
// on its left seen from outside.
struct Segment {
  Point3 a, b;
};

std::vector<Segment> merge_fragments(const Frame& frame, const std::vector<Poly>& fragments) {
  std::map<LineKey, std::vector<Event>> lines;
  for (const Poly& g : fragments)
    for (std::size_t i = 0; i < g.size(); ++i) {
      const V2& p = g[i];
      const V2& q = g[(i + 1) % g.size()];
      auto [a, b] = primitive(q.u - p.u, q.v - p.v);
      int dir = 1;
      if (sgn(a) < 0 || (sgn(a) == 0 && sgn(b) < 0)) {
        a = -a;
        b = -b;
        dir = -1;
      }
      Rational c = Rational(a) * p.v - Rational(b) * p.u;
      const Rational tp = Rational(a) * p.u + Rational(b) * p.v, tq = Rational(a) * q.u + Rational(b) * q.v;
      auto& ev = lines[LineKey{a, b, std::move(c)}];
      // Along the direction: from the smaller parameter to the larger one.
      const bool forward = dir > 0;
      ev.push_back(Event{forward ? tp : tq, dir, forward ? &p : &q});
      ev.push_back(Event{forward ? tq : tp, -dir, forward ? &q : &p});
    }
  std::vector<Segment> out;
  for (auto& [key, ev] : lines) {
    std::sort(ev.begin(), ev.end(), [](const Event& x, const Event& y) { return cmp(x.t, y.t) < 0; });
    int sum = 0;
    const V2* start = nullptr;  // start of the current boundary stretch
    int stretch = 0;            // its direction
    for (std::size_t i = 0; i < ev.size();) {
      std::size_t j = i;
      int next = sum;
      while (j < ev.size() && cmp(ev[j].t, ev[i].t) == 0) next += ev[j++].delta;
      const int now = (next > 0) - (next < 0);
      if (now != stretch) {
        if (stretch > 0) out.push_back({frame.lift(start->u, start->v), frame.lift(ev[i].point->u, ev[i].point->v)});
        if (stretch < 0) out.push_back({frame.lift(ev[i].point->u, ev[i].point->v), frame.lift(start->u, start->v)});
        start = ev[i].point;
        stretch = now;
      }
      sum = next;
      i = j;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// One plane's boundary: its facets cut by the other pieces, merged.

struct FacetRef {
  Index piece, facet;
};

struct PlaneResult {
  std::vector<Segment> segments;
  std::size_t clips = 0;
};

PlaneResult plane_boundary(const Plane& plane, const std::vector<FacetRef>& facets,
                           const std::vector<ConvexPolytope>& parts, const std::vector<Box>& boxes) {
  const Frame frame(plane);
  PlaneResult r;
  std::vector<Poly> fragments;
  std::unordered_map<Index, Trace> traces;
  std::vector<char> member(parts.size(), 0);
  for (const FacetRef& f : facets) member[f.piece] = 1;
  for (const FacetRef& f : facets) {
    const ConvexPolytope& p = parts[f.piece];
    std::vector<Poly> frags(1);
    Box box;
    for (Index v : p.facet_vertices(f.facet)) {
      frags[0].push_back(frame.project(p.point(v)));
      box.add(to_double(p.point(v)));
    }
    for (Index j = 0; j < parts.size() && !frags.empty(); ++j) {
      // The pieces with a facet on this plane facing the same way lie below
      // it: they never remove anything, except that the earlier ones remove
      // their facet's overlap with this one (so the plane's fragments do
      // not overlap).
      if (j == f.piece || (member[j] && j > f.piece) || !box.meets(boxes[j])) continue;
      auto it = traces.find(j);
      if (it == traces.end()) it = traces.emplace(j, trace_of(frame, parts[j])).first;
      if (!it->second.meets) continue;
      std::vector<Poly> next;
      for (Poly& g : frags)
        if (subtract(g, it->second.lines, next))
          ++r.clips;
        else
          next.push_back(std::move(g));
      frags = std::move(next);
    }
    for (Poly& g : frags) fragments.push_back(std::move(g));
  }
  r.segments = merge_fragments(frame, fragments);
  return r;
}

// ---------------------------------------------------------------------------
// Assembly.

// Every vertex lying strictly inside the segment a b, ordered from a to b.
// `order` sorts the vertices by their rounded x.
std::vector<Index> inner_vertices(Index a, Index b, const std::vector<Point3>& pts, const std::vector<Vec3d>& approx,
                                  const std::vector<Index>& order) {
  Box box;
  box.add(approx[a]);
  box.add(approx[b]);
  auto first = std::lower_bound(order.begin(), order.end(), box.lo[0],
                                [&](Index v, double x) { return approx[v].x < x; });
  const Point3 d = pts[b] - pts[a];
  const Rational len = dot(d, d);
  std::vector<std::pair<Rational, Index>> inside;
  for (auto it = first; it != order.end() && approx[*it].x <= box.hi[0]; ++it) {
    const Index m = *it;
    if (m == a || m == b) continue;
    const Vec3d& q = approx[m];
    if (q.y < box.lo[1] || q.y > box.hi[1] || q.z < box.lo[2] || q.z > box.hi[2]) continue;
    const Point3 am = pts[m] - pts[a];
    if (!is_zero(cross(d, am))) continue;
    Rational t = dot(am, d);
    if (sgn(t) > 0 && cmp(t, len) < 0) inside.emplace_back(std::move(t), m);
  }
  std::sort(inside.begin(), inside.end(), [](const auto& x, const auto& y) { return cmp(x.first, y.first) < 0; });
  std::vector<Index> out;
  for (auto& [t, m] : inside) out.push_back(m);
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
// face; an outer loop with holes is triangulated.
std::vector<std::vector<Index>> plane_faces(const std::vector<std::vector<Index>>& loops, const std::vector<V2>& at) {
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

void union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out,
                    unsigned threads) {
  auto t0 = Clock::now();
  options.report("union", 0.0);
  // Facets by oriented plane.
  std::map<Plane, std::vector<FacetRef>> by_plane;
  std::vector<Box> boxes(parts.size());
  for (Index i = 0; i < parts.size(); ++i) {
    for (Index v = 0; v < parts[i].num_vertices(); ++v) boxes[i].add(to_double(parts[i].point(v)));
    for (Index f = 0; f < parts[i].num_facets(); ++f) by_plane[parts[i].plane(f)].push_back(FacetRef{i, f});
  }
  std::vector<const std::pair<const Plane, std::vector<FacetRef>>*> planes;
  for (const auto& entry : by_plane) planes.push_back(&entry);
  const std::size_t n = planes.size();
  std::vector<PlaneResult> results(n);
  const unsigned workers = parallel_threads(threads, n);
  const std::size_t batch = std::max<std::size_t>(64, std::size_t(workers) * 16);
  for (std::size_t start = 0; start < n; start += batch) {
    const std::size_t count = std::min(batch, n - start);
    parallel_for(count, workers, [&](std::size_t k) {
      const auto& [plane, facets] = *planes[start + k];
      results[start + k] = plane_boundary(plane, facets, parts, boxes);
    });
    options.report("union", double(start + count) / double(n));
  }
  out.clips = 0;
  for (const auto& r : results) out.clips += r.clips;
  out.seconds_union = since(t0);

  t0 = Clock::now();
  options.report("boundary", -1.0);
  // Weld exactly equal points.
  std::map<Point3, Index> index;
  std::vector<Point3> pts;
  std::vector<std::vector<std::pair<Index, Index>>> edges(n);
  for (std::size_t g = 0; g < n; ++g)
    for (Segment& s : results[g].segments) {
      Index ends[2];
      for (int e = 0; e < 2; ++e) {
        Point3& p = e ? s.b : s.a;
        auto [it, fresh] = index.emplace(p, Index(pts.size()));
        if (fresh) pts.push_back(std::move(p));
        ends[e] = it->second;
      }
      edges[g].emplace_back(ends[0], ends[1]);
    }
  results.clear();
  index.clear();
  std::vector<Vec3d> approx(pts.size());
  for (std::size_t v = 0; v < pts.size(); ++v) approx[v] = to_double(pts[v]);
  std::vector<Index> order(pts.size());
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index x, Index y) { return approx[x].x < approx[y].x; });

  // Per plane: every vertex inside an edge inserted into it, loops, faces.
  std::vector<std::vector<std::vector<Index>>> faces(n);
  parallel_for(n, workers, [&](std::size_t g) {
    const Frame frame(planes[g]->first);
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
          at.push_back(frame.project(pts[*v]));
          local_id.push_back(*v);
        }
        *v = it->second;
      }
    for (auto& f : plane_faces(trace_loops(split, at), at)) {
      for (Index& v : f) v = local_id[v];
      faces[g].push_back(std::move(f));
    }
  });

  out.mesh = Mesh{};
  for (const Point3& p : pts) out.mesh.points.push_back(p);
  std::vector<Index> face_plane;
  for (std::size_t g = 0; g < n; ++g)
    for (auto& f : faces[g]) {
      out.mesh.faces.push_back(std::move(f));
      face_plane.push_back(Index(g));
    }

  // Shells: faces linked across their edges.  Around an edge of more than
  // two faces (the solid touching itself), each face is linked to the next
  // one around the edge across the solid between them, so the shells are
  // the boundaries of the union's separate volumes.
  const std::vector<std::vector<Index>>& mf = out.mesh.faces;
  std::vector<std::size_t> parent(mf.size());
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<Index, Index>, std::vector<std::size_t>> around;  // undirected edge -> faces
  for (std::size_t f = 0; f < mf.size(); ++f)
    for (std::size_t i = 0; i < mf[f].size(); ++i) {
      const Index a = mf[f][i], b = mf[f][(i + 1) % mf[f].size()];
      around[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  out.non_manifold_edges = 0;
  for (const auto& [e, fs] : around) {
    if (fs.size() == 2) {
      parent[find(fs[0])] = find(fs[1]);
      continue;
    }
    ++out.non_manifold_edges;
    // The edge's direction D = b - a; each face's way into itself from the
    // edge, w = n x (its direction of the edge); angles about D.
    const Point3 d = pts[e.second] - pts[e.first];
    struct Around {
      std::size_t face;
      Point3 w;
      bool solid_ccw;  // the solid lies on its counter-clockwise side about D
    };
    std::vector<Around> list;
    for (std::size_t f : fs) {
      const Plane& h = planes[face_plane[f]]->first;
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
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i].solid_ccw) parent[find(list[i].face)] = find(list[(i + 1) % list.size()].face);
  }
  out.shells = 0;
  for (std::size_t f = 0; f < mf.size(); ++f)
    if (find(f) == f) ++out.shells;
  out.seconds_boundary = since(t0);
}

}  // namespace minksum::nonconvex_detail
