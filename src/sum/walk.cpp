// The walk method (docs/walk.md): the output-sensitive exact Minkowski sum.
// The algorithm and its output are described in src/sum/include/minksum/walk.hpp;
// docs/walk.md has the case analysis.  Conventions used below:
//
//  * Gaussian map.  For a half-edge h of a convex polytope with facet(h) on
//    its left, n(facet(h)) × n(facet(twin h)) is a positive multiple of the
//    edge direction target(h) − origin(h).  So the great arc of the edge of
//    h, walked from n(facet(h)) to n(facet(twin h)), has the side
//    <n, d_h> > 0 on its left.
//  * Around a vertex b, the outgoing half-edges h_0, h_1, ... follow each
//    other counter-clockwise (next_around_vertex), facet(h_i) lies between
//    h_i and h_{i+1}, and the vertex region of b on the Gaussian sphere is
//    the convex spherical polygon n(facet(h_0)), n(facet(h_1)), ...
//    (counter-clockwise seen from outside); its side between
//    n(facet(h_{i-1})) and n(facet(h_i)) is the arc of the edge of h_i.
//  * A directed great circle crossing a convex region counter-clockwise
//    numbered leaves it where the side signs go from − to + (possibly
//    through one 0: the exit is then a vertex of the region).
//
// Every decision is the sign of  <x − y, n(f)>  with x, y two vertices of one
// operand and n(f) = (f1 − f0) × (f2 − f0) the normal of a facet f of either
// operand (f0, f1, f2: the facet's first three vertices; every corner of a
// facet is strictly convex, so n(f) is a positive multiple of its outer
// normal).  It is evaluated with the kernel's det3 filter, the per-facet
// cross product cached (kernel/det3_filter.hpp, with its error bound), and,
// when the filter cannot decide, by the error-free certificates of det3_slow
// (exact double evaluations, axis-parallel differences, a difference equal
// to ± an edge of the facet: the kernel's same_difference) or exactly by
// support_compare().
#include <minksum/predicates.hpp>
#include <minksum/walk.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cfenv>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "kernel/big_array.hpp"
#include "kernel/det3_filter.hpp"
#include "kernel/difference.hpp"
#include "kernel/predicates_internal.hpp"
#include "mesh/builder.hpp"
#include "mesh/support.hpp"

namespace minksum {

std::uint64_t WalkSum::features(const ConvexPolytope& a, const ConvexPolytope& b) const {
  auto n = [](const auto& p) { return std::uint64_t(p.num_vertices()) + p.num_edges() + p.num_facets(); };
  return n(a) + n(b) + n(*this);
}

namespace {


// Error-free checks, valid in round-to-nearest without overflow or
// underflow (operands are 0 or at least 2^-300 in magnitude, at most 2^333):
// s = fl(x + y) is exact iff Knuth's TwoSum error is 0; p = fl(x · y) is exact
// iff fma(x, y, −p) (the exact x·y − p, representable) is 0.
bool round_to_nearest() { return std::fegetround() == FE_TONEAREST; }
inline bool usable(double x) { return x == 0 || (std::fabs(x) >= 0x1p-300 && std::fabs(x) <= 0x1p333); }
inline bool sum_exact(double x, double y, double s) {
  const double bb = s - x;
  return (x - (s - bb)) + (y - bb) == 0;
}
inline bool product_exact(double x, double y, double p) { return std::fma(x, y, -p) == 0; }

struct Stats {
  std::uint64_t calls = 0, exact = 0, steps = 0;
  bool round_to_nearest = false;
};

// One operand with what the filter needs: rounded coordinates, and per facet
// the rounded edge vectors' maxima and their cross product.
struct Operand {
  const ConvexPolytope* P = nullptr;
  bool doubles = false;      // every coordinate is exactly a double
  bool filterable = true;    // every rounded coordinate within the filters' assumptions
  const Vec3d* x = nullptr;  // nearest doubles (exact when `doubles`): P's own approximations
  std::vector<double> cmax;  // max |coordinate| of x[v]
  // Per facet, what the filter reads (hot: kernel/det3_filter.hpp) and what
  // the exact stages need.
  using Facet = detail::Det3Facet;
  struct FacetCorners {
    Index v0, v1, v2;
    // (nx, ny, nz) is exactly n(f): 1 yes, 0 no, 2 not checked yet (on
    // demand, by exact_normal()).
    mutable std::int8_t exact;
  };
  std::vector<Facet> f;
  std::vector<FacetCorners> fc;

  // Whether facet k's rounded normal is exact: every difference and product
  // of the cross product computed without rounding (checked once).
  bool exact_normal(Index k) const {
    const FacetCorners& gc = fc[k];
    if (gc.exact != 2) return gc.exact == 1;
    const Vec3d &a = x[gc.v0], &b = x[gc.v1], &c = x[gc.v2];
    const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    const double pa[3] = {a.x, a.y, a.z}, pb[3] = {b.x, b.y, b.z}, pc[3] = {c.x, c.y, c.z};
    const double n[3] = {f[k].nx, f[k].ny, f[k].nz};
    bool exact = true;
    for (int i = 0; i < 3; ++i)
      exact = exact && usable(u[i]) && usable(v[i]) && sum_exact(pb[i], -pa[i], u[i]) && sum_exact(pc[i], -pa[i], v[i]);
    for (int i = 0; i < 3 && exact; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      const double p1 = u[j] * v[l], p2 = u[l] * v[j];
      exact = product_exact(u[j], v[l], p1) && product_exact(u[l], v[j], p2) && sum_exact(p1, -p2, p1 - p2) &&
              n[i] == p1 - p2;
    }
    gc.exact = exact ? 1 : 0;
    return exact;
  }

  // Exact signs of the coordinates of n(f), computed on demand (0, ±1; 2 = not yet).
  mutable std::vector<std::array<std::int8_t, 3>> axis_sign;

  explicit Operand(const ConvexPolytope& p) : P(&p), doubles(p.coordinates_are_doubles()) {
    const bool nearest = round_to_nearest();
    x = p.num_vertices() ? &p.approx(0) : nullptr;
    cmax.resize(p.num_vertices());
    for (Index v = 0; v < p.num_vertices(); ++v) {
      cmax[v] = std::max({std::fabs(x[v].x), std::fabs(x[v].y), std::fabs(x[v].z)});
      // The rational filter needs |x̂ − x| ≤ κ|x̂| for every rounded
      // coordinate: true for the nearest double in the normal range, and for
      // 0 only when the coordinate is 0.  Tiny coordinates (underflow) make
      // every sign of this operand exact-only.
      if (!doubles)
        for (int i = 0; i < 3; ++i) {
          const double c = x[v][i];
          if (c == 0 ? sgn(p.point(v)[i]) != 0 : std::fabs(c) < 0x1p-1022) filterable = false;
        }
    }
    f.resize(p.num_facets());
    fc.resize(p.num_facets());
    if (doubles) axis_sign.assign(p.num_facets(), {2, 2, 2});
    for (Index k = 0; k < p.num_facets(); ++k) {
      Facet& g = f[k];
      FacetCorners& gc = fc[k];
      const Index h = p.facet_halfedge(k);
      gc.v0 = p.origin(h), gc.v1 = p.target(h), gc.v2 = p.target(p.next(h));
      const bool ok = detail::make_det3_facet(x[gc.v0], x[gc.v1], x[gc.v2], cmax[gc.v0], cmax[gc.v1],
                                              cmax[gc.v2], filterable, g);
      gc.exact = doubles && ok && nearest ? 2 : 0;
    }
  }
};

// sign <X(xi) − X(yi), n(F facet fi)>: the kernel's det3 filter with the
// facet's normal cached (kernel/det3_filter.hpp, with its proof), then
// det3_slow.
using Diff = detail::Det3Diff;
inline Diff make_diff(const Operand& X, Index xi, Index yi) {
  return detail::make_det3_diff(X.x[xi], X.x[yi], X.cmax[xi], X.cmax[yi]);
}
using detail::det3_filter;

int det3_slow(const Operand& F, Index fi, const Operand& X, Index xi, Index yi, Stats& st);

inline int det3(const Operand& F, Index fi, const Operand& X, Index xi, Index yi, Stats& st) {
  ++st.calls;
  const int s = det3_filter(F.f[fi], F.doubles && X.doubles, X.filterable, make_diff(X, xi, yi));
  return s != 2 ? s : det3_slow(F, fi, X, xi, yi, st);
}
// The same with the difference X(xi) − X(yi) already made.
inline int det3(const Operand& F, Index fi, const Operand& X, const Diff& d, Index xi, Index yi, Stats& st) {
  ++st.calls;
  const int s = det3_filter(F.f[fi], F.doubles && X.doubles, X.filterable, d);
  return s != 2 ? s : det3_slow(F, fi, X, xi, yi, st);
}

// Whether X(xi) − X(yi) is exactly ± the vector of an edge of facet fi of F
// (the kernel's same_difference: error-free for doubles, equal points for
// rationals).
bool zero_by_facet_edge(const Operand& F, Index fi, const Operand& X, Index xi, Index yi, bool nearest) {
  const ConvexPolytope& PF = *F.P;
  const ConvexPolytope& PX = *X.P;
  const Index h0 = PF.facet_halfedge(fi);
  Index h = h0;
  if (F.doubles && X.doubles) {
    const Vec3d &p = X.x[xi], &q = X.x[yi];
    do {
      if (detail::same_difference(F.x[PF.origin(h)], F.x[PF.target(h)], q, p, nearest) != 0) return true;
      h = PF.next(h);
    } while (h != h0);
    return false;
  }
  const Point3 &p = PX.point(xi), &q = PX.point(yi);
  do {
    if (detail::same_difference(PF.point(PF.origin(h)), PF.point(PF.target(h)), q, p) != 0) return true;
    h = PF.next(h);
  } while (h != h0);
  return false;
}

// When the filter cannot decide.
int det3_slow(const Operand& F, Index fi, const Operand& X, Index xi, Index yi, Stats& st) {
  const Operand::Facet& g = F.f[fi];
  const Operand::FacetCorners& gc = F.fc[fi];
  if (F.doubles && X.doubles && F.exact_normal(fi)) {
    // Often the value was computed without any rounding (axis-parallel
    // facets, edges in coordinate planes: the degenerate signs 0 of
    // symmetric inputs).  Then it is exact, zero included.
    const Vec3d &p = X.x[xi], &q = X.x[yi];
    const double pe[3] = {p.x, p.y, p.z}, qe[3] = {q.x, q.y, q.z}, n[3] = {g.nx, g.ny, g.nz};
    double t[3];
    bool exact = st.round_to_nearest;
    for (int i = 0; i < 3 && exact; ++i) {
      if (n[i] == 0) {
        t[i] = 0;  // exactly 0 whatever the difference
        continue;
      }
      const double e = pe[i] - qe[i];
      t[i] = e * n[i];
      exact = usable(e) && sum_exact(pe[i], -qe[i], e) && product_exact(e, n[i], t[i]);
    }
    if (exact) {
      const double s01 = t[0] + t[1], v = s01 + t[2];
      if (sum_exact(t[0], t[1], s01) && sum_exact(s01, t[2], v)) {
        return (v > 0) - (v < 0);
      }
    }
  }
  if (F.doubles && X.doubles) {
    // An axis-parallel difference (the other two coordinates equal, e.g. an
    // edge of a box): the sign is sign(e_i) times the exact sign of the
    // coordinate i of n(f), computed once per facet and axis.
    const Vec3d &p = X.x[xi], &q = X.x[yi];
    const int axis = p.x != q.x ? (p.y == q.y && p.z == q.z ? 0 : -1)
                                : p.y != q.y ? (p.z == q.z ? 1 : -1) : (p.z != q.z ? 2 : -1);
    if (axis >= 0) {
      std::int8_t& c = F.axis_sign[fi][axis];
      if (c == 2) {
        const Vec3d o{0, 0, 0}, unit{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
        ++st.exact;
        c = std::int8_t(edge_facet_sign(o, unit, F.x[gc.v0], F.x[gc.v1], F.x[gc.v2]));
      }
      const double e = axis == 0 ? p.x - q.x : axis == 1 ? p.y - q.y : p.z - q.z;
      return e > 0 ? c : -c;
    }
  }
  // A zero certificate without arithmetic on products: X(xi) − X(yi) equal
  // to ± an edge vector of the facet lies in the facet's plane, so the sign
  // is exactly 0.  Identical operands, translates and point reflections
  // make most of their degenerate signs this way (an edge of one operand
  // against the facet of the other that carries the same edge).
  if (zero_by_facet_edge(F, fi, X, xi, yi, st.round_to_nearest)) return 0;
  ++st.exact;
  // Exact doubles: the kernel's Vec3d form (its dynamic filter, then GMP
  // integers in a reused workspace).  Rationals: the Point3 form.
  if (F.doubles && X.doubles) return support_compare(F.x[gc.v0], F.x[gc.v1], F.x[gc.v2], X.x[xi], X.x[yi]);
  const ConvexPolytope& PF = *F.P;
  const ConvexPolytope& PX = *X.P;
  return support_compare(PF.point(gc.v0), PF.point(gc.v1), PF.point(gc.v2), PX.point(xi), PX.point(yi));
}

// Walks the arcs of P's edges over Q's Gaussian map.
class Walker {
 public:
  Walker(const Operand& p, const Operand& q, Stats& st)
      : P_(p), Q_(q), p_(*p.P), q_(*q.P), st_(st),
        short_arcs_(std::uint64_t(q_.num_vertices()) * 4 <= p_.num_vertices()) {}

  // face_Q(n(f)) for every facet f of P; with `crossings`, every proper
  // crossing of an arc of P with an arc of Q as (half-edge of P walked,
  // half-edge of Q crossed from the region of its origin into its target's).
  std::vector<Feature> run(std::vector<std::pair<Index, Index>>* crossings, const SumOptions& options, double progress0,
                           double progress_span) {
    crossings_ = crossings;
    const Index nf = p_.num_facets();
    std::vector<Feature> S(nf);
    std::vector<std::uint8_t> known(nf, 0);  // S[f] found
    std::vector<std::uint8_t> walked(p_.num_edges(), 0);
    std::vector<Index> queue;
    queue.reserve(nf);
    S[0] = climb(0);
    known[0] = 1;
    queue.push_back(0);
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      if ((qi & 4095) == 0) options.report("walk", progress0 + progress_span * double(qi) / nf);
      const Index f1 = queue[qi];
      const Index h0 = p_.facet_halfedge(f1);
      Index h = h0;
      do {
        const Index e = ConvexPolytope::edge(h);
        if (!walked[e]) {
          walked[e] = 1;
          const Index f2 = p_.facet(ConvexPolytope::twin(h));
          const bool need = !known[f2];
          // Without crossings to record, only the arcs of a spanning tree of
          // the facets are needed.
          if (!need && !crossings) {
            h = p_.next(h);
            continue;
          }
          const std::optional<Feature> s2 = walk(h, S[f1], need);
          if (need) {
            S[f2] = *s2;
            known[f2] = 1;
            queue.push_back(f2);
          }
        }
        h = p_.next(h);
      } while (h != h0);
    }
    if (queue.size() != nf) throw std::logic_error("walk: the facets of an operand are not connected");
    return S;
  }

 private:
  struct State {
    bool overlap;  // running along the arc of Q's edge `index` (a half-edge) instead of inside a region
    Index index;   // vertex of Q, or half-edge of Q directed like the walked edge
  };

  // sign <x − y, n(f)>, f a facet of P, x and y vertices of Q.
  int higher(Index f, Index x, Index y) { return det3(P_, f, Q_, x, y, st_); }
  // sign <d_h, n(g)>, h a half-edge of P, g a facet of Q.
  // (The walk of h sets hd_ = d_h once.)
  int side(Index g, Index h) { return det3(Q_, g, P_, hd_, p_.target(h), p_.origin(h), st_); }

  // The face of Q maximising <x, n(f)> when its vertex b is a maximiser,
  // nothing when a neighbour of b is higher (mesh/support.hpp: each sign
  // once, stopping at the first higher neighbour).
  std::optional<Feature> face_at(Index b, Index f) {
    return support_face_at(q_, b, [&](Index x, Index y) { return higher(f, x, y); });
  }

  // The face of Q maximising <x, n(f)>, given its vertex b (a maximiser).
  Feature support_face(Index b, Index f) {
    if (const std::optional<Feature> face = face_at(b, f)) return *face;
    throw std::logic_error("walk: the support vertex is not a maximum");
  }

  // Hill climbing on Q's vertex graph to the support of n(f) (a walk step
  // per sign).
  Feature climb(Index f) {
    const Index b = minksum::climb(q_, 0, [&](Index x, Index y) {
      ++st_.steps;
      return higher(f, x, y);
    });
    return support_face(b, f);
  }

  // Outgoing half-edges of b, counter-clockwise, into hbuf_, starting with
  // h0 (an outgoing half-edge of b) or any.
  void ring(Index b, Index h0 = kNoIndex) {
    hbuf_.clear();
    if (h0 == kNoIndex) h0 = q_.vertex_halfedge(b);
    Index h = h0;
    do {
      hbuf_.push_back(h);
      h = q_.next_around_vertex(h);
    } while (h != h0);
  }

  // Where the arc of hp continues from a point whose support in Q is the
  // face S: the vertex of S highest along n(f2) (the arc's end), or, when two
  // vertices of S tie, the edge joining them (parallel to hp: the arc runs
  // along that edge's arc).
  State enter(Feature S, Index hp, Index f2) {
    if (S.dim == FeatureDim::vertex) return {false, S.index};
    feature_vertices(q_, S, verts_);
    support_among(verts_, [&](Index x, Index y) { return higher(f2, x, y); }, top_);
    if (top_.size() == 1) return {false, top_[0]};
    if (top_.size() != 2) throw std::logic_error("walk: more than two vertices of a face tie along an arc's end");
    // The edge joining the two, directed like hp.
    const Index h = halfedge_between(q_, top_[0], top_[1]);
    if (h == kNoIndex) throw std::logic_error("walk: tied support vertices are not adjacent");
    ++st_.calls;
    const int d = q_.coordinates_are_doubles() && p_.coordinates_are_doubles()
                      ? dot_sign(q_.approx(q_.origin(h)), q_.approx(q_.target(h)), p_.approx(p_.origin(hp)),
                                 p_.approx(p_.target(hp)))
                      : dot_sign(q_.point(q_.origin(h)), q_.point(q_.target(h)), p_.point(p_.origin(hp)),
                                 p_.point(p_.target(hp)));
    if (d == 0) throw std::logic_error("walk: overlapping arcs of non-parallel edges");
    return {true, d > 0 ? h : ConvexPolytope::twin(h)};
  }

  // Walk the arc of P's half-edge hp from n(facet(hp)) (support S1 in Q) to
  // n(facet(twin hp)); returns the support there when `need_end`, else
  // possibly nothing.
  std::optional<Feature> walk(Index hp, Feature S1, bool need_end) {
    const Index f2 = p_.facet(ConvexPolytope::twin(hp));
    hd_ = make_diff(P_, p_.target(hp), p_.origin(hp));
    State s = enter(S1, hp, f2);
    Index entry = kNoIndex;  // the half-edge of Q through which the region was entered by a crossing
    // The arc is shorter than π and the regions and edge arcs are convex:
    // each is met at most once.  More steps than that is a bug, not a loop.
    const std::uint64_t limit = std::uint64_t(q_.num_vertices()) + q_.num_edges() + q_.num_facets() + 2;
    for (std::uint64_t n = 0;; ++n) {
      if (n > limit) throw std::logic_error("walk: an arc walk does not end");
      ++st_.steps;
      if (s.overlap) {
        // Along the arc of Q's edge hq: it ends at n(facet(twin hq)).  The
        // arc's end n(f2) lies on it iff origin(hq) supports n(f2).
        const Index hq = s.index, x = q_.origin(hq);
        if (const std::optional<Feature> face = face_at(x, f2)) return need_end ? face : std::nullopt;
        s = enter(Feature::facet(q_.facet(ConvexPolytope::twin(hq))), hp, f2);
        entry = kNoIndex;
        continue;
      }
      // Arcs much shorter than Q's regions mostly end where they start: then
      // test the end first (one sign per neighbour of b, stopping at the
      // first neighbour higher along n(f2)).
      if (short_arcs_ && need_end && n == 0) {
        const Index b = s.index;
        if (const std::optional<Feature> face = face_at(b, f2)) return face;
      }
      // Inside the region of vertex b: find where the arc's great circle
      // leaves it (side signs − then +, or −, 0, +), evaluating the signs
      // lazily.  Entered by crossing the edge `entry`, the two facets beside
      // it are known: − after it, + before it.
      const Index b = s.index;
      ring(b, entry);
      const std::size_t k = hbuf_.size();
      sbuf_.assign(k, 2);
      if (entry != kNoIndex) sbuf_[0] = -1, sbuf_[k - 1] = 1;
      auto S = [&](std::size_t i) {
        if (i >= k) i -= k;
        if (sbuf_[i] == 2) sbuf_[i] = std::int8_t(side(q_.facet(hbuf_[i]), hp));
        return int(sbuf_[i]);
      };
      std::size_t exit = k;
      bool through_vertex = false;
      for (std::size_t i = 0; i < k; ++i) {
        const int sp = S(i + k - 1);
        if (sp >= 0) continue;
        const int si = S(i);
        if (si > 0) {
          exit = i;
          break;
        }
        if (si == 0 && S(i + 1) > 0) {
          exit = i;
          through_vertex = true;
          break;
        }
      }
      if (exit == k) throw std::logic_error("walk: the arc does not leave a vertex region");
      const Index he = hbuf_[exit];
      // The arc ends before the exit iff n(f2) is on b's side of the exit
      // side's great circle; strictly inside that side, n(f2) lies on the
      // open chord of the region cut by the arc's circle: b alone supports it.
      const int c = higher(f2, q_.target(he), b);
      if (c < 0) return Feature::vertex(b);
      if (c == 0) return need_end ? std::optional(support_face(b, f2)) : std::nullopt;
      if (through_vertex) {
        s = enter(Feature::facet(q_.facet(he)), hp, f2);
        entry = kNoIndex;
      } else {
        if (crossings_) crossings_->emplace_back(hp, he);
        s = {false, q_.target(he)};
        entry = ConvexPolytope::twin(he);
      }
    }
  }

  const Operand &P_, &Q_;
  const ConvexPolytope &p_, &q_;
  Stats& st_;
  std::vector<std::pair<Index, Index>>* crossings_ = nullptr;
  Diff hd_{};
  // Q has far fewer vertices than P (its regions are much larger than P's
  // arcs): the walks test whether they end in their first region first.
  bool short_arcs_ = false;
  std::vector<Index> hbuf_, verts_, top_;
  std::vector<std::int8_t> sbuf_;
};

// The loops of the output facets, before linking.
struct Loops {
  std::vector<std::pair<Index, Index>> corners;  // (vertex of A, vertex of B)
  std::vector<Index> start{0};                   // facet i: corners[start[i], start[i+1])
  std::vector<FacetProvenance> prov;
  void close(FacetProvenance p) {
    start.push_back(Index(corners.size()));
    prov.push_back(p);
  }
};


// Facet fa of A ⊕ facet fb of B with the same outer normal n: the merge of
// the two counter-clockwise edge sequences by angle (the planar Minkowski sum
// of convex polygons).  Both start at the edge direction of A's first edge
// e_0: A at its vertex 0, B at its vertex supporting the in-plane outer
// normal m_0 = e_0 × n of e_0 (the origin of B's edge parallel to e_0, if
// any).  Then, from (i, j), the next vertex is (i+1, j) when e_i turns before
// f_j (det(e_i, f_j, n) > 0), (i, j+1) when after, (i+1, j+1) when they are
// parallel — then the same direction, since two consecutive edges of a convex
// polygon turn by less than π.  Signs: arc_side (exact, filtered).
void facet_plus_facet(const ConvexPolytope& a, Index fa, const ConvexPolytope& b, Index fb, Loops& out) {
  const std::vector<Index> p = a.facet_vertices(fa), q = b.facet_vertices(fb);
  const std::size_t k = p.size(), m = q.size();
  const bool dbl = a.coordinates_are_doubles() && b.coordinates_are_doubles();
  // det(x1 − x0, y1 − y0, n(fa)), x from X, y from Y.
  // Equal or opposite edge vectors (the kernel's same_difference: exact) are
  // parallel, det = 0 — the sign of every pair of matching edges of
  // identical or point-reflected facets, which the filter cannot certify.
  const bool nearest = round_to_nearest();
  auto det = [&](const ConvexPolytope& X, Index x0, Index x1, const ConvexPolytope& Y, Index y0, Index y1) {
    if (dbl ? detail::same_difference(X.approx(x0), X.approx(x1), Y.approx(y0), Y.approx(y1), nearest) != 0
            : detail::same_difference(X.point(x0), X.point(x1), Y.point(y0), Y.point(y1)) != 0)
      return 0;
    return dbl ? arc_side(X.approx(x0), X.approx(x1), Y.approx(y0), Y.approx(y1), a.approx(p[0]), a.approx(p[1]),
                          a.approx(p[2]))
               : arc_side(X.point(x0), X.point(x1), Y.point(y0), Y.point(y1), a.point(p[0]), a.point(p[1]),
                          a.point(p[2]));
  };
  // <y − x, m_0> = det(y − x, e_0, n): B's vertex highest along m_0, the
  // first of two tied ones in B's order (the tie is an edge parallel to e_0,
  // and its origin comes first).
  std::size_t j0 = 0;
  for (std::size_t j = 1; j < m; ++j)
    if (det(b, q[j0], q[j], a, p[0], p[1]) > 0) j0 = j;
  for (std::size_t j = 0; j < m; ++j)
    if (j != j0 && det(b, q[j0], q[j], a, p[0], p[1]) == 0) {
      // Tied: q[j] is the neighbour of q[j0] along an edge parallel to e_0;
      // start at the edge's origin.
      if (q[(j + 1) % m] == q[j0]) j0 = j;
      break;
    }
  std::size_t i = 0, j = 0;
  while (i < k || j < m) {
    out.corners.emplace_back(p[i % k], q[(j0 + j) % m]);
    if (i == k) {
      ++j;
      continue;
    }
    if (j == m) {
      ++i;
      continue;
    }
    const Index pi = p[i % k], pn = p[(i + 1) % k], qj = q[(j0 + j) % m], qn = q[(j0 + j + 1) % m];
    const int c = det(a, pi, pn, b, qj, qn);
    if (c >= 0) ++i;
    if (c <= 0) ++j;
  }
  out.close({Feature::facet(fa), Feature::facet(fb)});
}

// Facet fi of F ⊕ edge ei of E, the edge parallel to the facet's plane
// (normal n): the facet's loop with its chain facing −d translated by x, the
// chain facing +d by y (d = y − x); an edge of the facet parallel to d merges
// with the segment.  Edge e_i = p_{i+1} − p_i faces ±d by the sign of
// det(e_i, n, d) = −arc_side(p_i, p_{i+1}, x, y, f0, f1, f2) (exact, filtered).
void facet_plus_edge(const ConvexPolytope& F, Index fi, const ConvexPolytope& E, Index ei, bool f_is_a,
                     Loops& out) {
  const Index x = E.origin(2 * ei), y = E.target(2 * ei);
  const std::vector<Index> p = F.facet_vertices(fi);
  const std::size_t k = p.size();
  const bool dbl = F.coordinates_are_doubles() && E.coordinates_are_doubles();
  std::vector<int> side(k);
  const bool nearest = round_to_nearest();
  for (std::size_t i = 0; i < k; ++i) {
    const Index p0 = p[i], p1 = p[(i + 1) % k];
    // An edge of the facet equal or opposite to d (exactly) is parallel to it.
    if (dbl ? detail::same_difference(F.approx(p0), F.approx(p1), E.approx(x), E.approx(y), nearest) != 0
            : detail::same_difference(F.point(p0), F.point(p1), E.point(x), E.point(y)) != 0) {
      side[i] = 0;
      continue;
    }
    side[i] = -(dbl ? arc_side(F.approx(p0), F.approx(p1), E.approx(x), E.approx(y), F.approx(p[0]), F.approx(p[1]),
                               F.approx(p[2]))
                    : arc_side(F.point(p0), F.point(p1), E.point(x), E.point(y), F.point(p[0]), F.point(p[1]),
                               F.point(p[2])));
  }
  auto emit = [&](Index pv, Index ev) { out.corners.push_back(f_is_a ? std::pair(pv, ev) : std::pair(ev, pv)); };
  for (std::size_t i = 0; i < k; ++i) {
    const int prev = side[(i + k - 1) % k], cur = side[i];
    const bool hx = prev < 0 || cur < 0, hy = prev > 0 || cur > 0;
    if (hx && hy) {
      if (prev < 0) emit(p[i], x), emit(p[i], y);
      else emit(p[i], y), emit(p[i], x);
    } else if (hx) {
      emit(p[i], x);
    } else if (hy) {
      emit(p[i], y);
    } else {
      throw std::logic_error("walk: two consecutive edges of a facet are parallel");
    }
  }
  const Feature ff = Feature::facet(fi), fe = Feature::edge(ei);
  out.close(f_is_a ? FacetProvenance{ff, fe} : FacetProvenance{fe, ff});
}

}  // namespace

WalkSum minkowski_walk(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options) {
  options.report("walk", 0);
  Stats st;
  st.round_to_nearest = round_to_nearest();
  std::vector<std::pair<Index, Index>> crossings;
  const double fa = a.num_facets(), fb = b.num_facets();
  // The operand with fewer edges walks all its arcs and records the
  // crossings; the other walks a spanning tree of its facets only.
  const bool a_records = a.num_edges() <= b.num_edges();
  std::vector<Feature> SA, SB;
  {
    // The walkers' per-facet filter data (about 80 bytes a facet) is freed
    // before the output's arrays are made: the peak memory of a sum is then
    // that of the operands and the output, not the three together.
    const Operand A(a), B(b);
    if (a_records) {
      SB = Walker(A, B, st).run(&crossings, options, 0, 0.8 * fa / (fa + fb));
      SA = Walker(B, A, st).run(nullptr, options, 0.8 * fa / (fa + fb), 0.8 * fb / (fa + fb));
    } else {
      SA = Walker(B, A, st).run(&crossings, options, 0, 0.8 * fb / (fa + fb));
      SB = Walker(A, B, st).run(nullptr, options, 0.8 * fb / (fa + fb), 0.8 * fa / (fa + fb));
    }
  }
  options.report("walk", 0.8);

  // Output facets: A's facets, B's facets not parallel to one of A's, and
  // the edge facets of the crossings.
  // Corners: a facet's own loop, two more for a facet ⊕ edge, the other
  // facet's loop for a facet ⊕ facet (that facet of B is then skipped), four
  // for an edge facet.  The bound is tight enough that the reservation does
  // not raise the sum's peak memory (it is at the linking below).
  std::size_t facet_plus_edges = 0;
  for (const Feature s : SA) facet_plus_edges += s.dim == FeatureDim::edge;
  for (const Feature s : SB) facet_plus_edges += s.dim == FeatureDim::edge;
  const std::size_t corner_bound =
      std::size_t(a.num_halfedges()) + b.num_halfedges() + 2 * facet_plus_edges + 4 * crossings.size();
  Loops L;
  L.corners.reserve(corner_bound);
  L.start.reserve(a.num_facets() + b.num_facets() + crossings.size() + 1);
  L.prov.reserve(a.num_facets() + b.num_facets() + crossings.size());
  for (Index f = 0; f < a.num_facets(); ++f) {
    const Feature s = SB[f];
    if (s.dim == FeatureDim::vertex) {
      const Index h0 = a.facet_halfedge(f);
      Index h = h0;
      do {
        L.corners.emplace_back(a.origin(h), s.index);
        h = a.next(h);
      } while (h != h0);
      L.close({Feature::facet(f), s});
    } else if (s.dim == FeatureDim::edge) {
      facet_plus_edge(a, f, b, s.index, true, L);
    } else {
      facet_plus_facet(a, f, b, s.index, L);
    }
  }
  for (Index g = 0; g < b.num_facets(); ++g) {
    const Feature s = SA[g];
    if (s.dim == FeatureDim::facet) continue;  // parallel to a facet of A: done above
    if (s.dim == FeatureDim::vertex) {
      const Index h0 = b.facet_halfedge(g);
      Index h = h0;
      do {
        L.corners.emplace_back(s.index, b.origin(h));
        h = b.next(h);
      } while (h != h0);
      L.close({s, Feature::facet(g)});
    } else {
      facet_plus_edge(b, g, a, s.index, false, L);
    }
  }
  release(SA);
  release(SB);
  // An edge facet e_a ⊕ e_b, crossed from the region of x into that of y
  // while walking u → v: its loop is (v,x) (u,x) (u,y) (v,y) — the side
  // e_a ⊕ x borders the output facet met before on the arc, so it runs
  // against the walk (first bullet at the top of the file).
  // (The loop is that of the sum of the walked edge and the crossed one,
  // whichever operand walked: as pairs (vertex of A, vertex of B).)
  const ConvexPolytope &P = a_records ? a : b, &Q = a_records ? b : a;
  for (auto [hp, hq] : crossings) {
    const Index u = P.origin(hp), v = P.target(hp), x = Q.origin(hq), y = Q.target(hq);
    const Feature ep = Feature::edge(ConvexPolytope::edge(hp)), eq = Feature::edge(ConvexPolytope::edge(hq));
    if (a_records) {
      L.corners.insert(L.corners.end(), {{v, x}, {u, x}, {u, y}, {v, y}});
      L.close({ep, eq});
    } else {
      L.corners.insert(L.corners.end(), {{x, v}, {x, u}, {y, u}, {y, v}});
      L.close({eq, ep});
    }
  }

  assert(L.corners.size() <= corner_bound);  // checked on every sum of the test suites

  // Link: vertices are pairs, edges are pairs of vertices.
  WalkSum w;
  const Index nf = Index(L.prov.size());
  const std::size_t nc = L.corners.size();
  if (nc % 2) throw std::logic_error("walk: the facet loops do not close up into edges");
  const std::size_t ne = nc / 2;
  const std::size_t nv = 2 + ne - nf;
  w.vertex_origin.reserve(nv);
  w.he_origin.assign(nc, kNoIndex);
  w.he_next.assign(nc, kNoIndex);
  w.he_facet.assign(nc, kNoIndex);
  w.facet_he.resize(nf);
  // Vertex (pa, pb) is found through the vertex of the operand with more
  // vertices (short lists), edge {p, q} through its smaller endpoint: linked
  // lists threaded through the vertex and edge arrays, no hashing.
  const bool key_b = b.num_vertices() >= a.num_vertices();
  std::vector<Index> vhead(key_b ? b.num_vertices() : a.num_vertices(), kNoIndex), vnext;
  std::vector<Index> ehead(nv, kNoIndex), enext, eother;
  vnext.reserve(nv);
  enext.reserve(ne);
  eother.reserve(ne);
  std::vector<Index> vid;
  Index edges = 0;
  for (Index f = 0; f < nf; ++f) {
    const Index s = L.start[f], t = L.start[f + 1];
    vid.clear();
    for (Index i = s; i < t; ++i) {
      const auto c = L.corners[i];
      const Index key = key_b ? c.second : c.first;
      Index v = vhead[key];
      while (v != kNoIndex && w.vertex_origin[v] != c) v = vnext[v];
      if (v == kNoIndex) {
        if (w.vertex_origin.size() == nv) throw std::logic_error("walk: the output is not a sphere (V − E + F ≠ 2)");
        v = Index(w.vertex_origin.size());
        w.vertex_origin.push_back(c);
        vnext.push_back(vhead[key]);
        vhead[key] = v;
      }
      vid.push_back(v);
    }
    const Index k = t - s;
    Index first = kNoIndex, last = kNoIndex;
    for (Index i = 0; i < k; ++i) {
      const Index p = vid[i], q = vid[i + 1 == k ? 0 : i + 1];
      const Index lo = std::min(p, q), hi = std::max(p, q);
      Index e = ehead[lo];
      while (e != kNoIndex && eother[e] != hi) e = enext[e];
      if (e == kNoIndex) {
        if (edges == ne) throw std::logic_error("walk: more edges than the facet loops allow");
        e = edges++;
        eother.push_back(hi);
        enext.push_back(ehead[lo]);
        ehead[lo] = e;
      }
      const Index h = 2 * e + (p < q ? 0 : 1);
      if (w.he_origin[h] != kNoIndex) throw std::logic_error("walk: an output half-edge is used twice");
      w.he_origin[h] = p;
      w.he_facet[h] = f;
      if (last != kNoIndex) w.he_next[last] = h;
      else first = h;
      last = h;
    }
    w.he_next[last] = first;
    w.facet_he[f] = first;
  }
  if (edges != ne || w.vertex_origin.size() != nv)
    throw std::logic_error("walk: the output is not a sphere (V − E + F ≠ 2)");
  w.provenance = std::move(L.prov);
  w.crossings = crossings.size();
  w.steps = st.steps;
  w.predicates = st.calls;
  w.exact_predicates = st.exact;
  return w;
}

PointList sum_coordinates(const std::vector<std::pair<Index, Index>>& pairs, const PointList& a, const PointList& b) {
  return PointList::sums(pairs, a, b);
}

ConvexPolytope to_polytope(const WalkSum& w, const ConvexPolytope& a, const ConvexPolytope& b) {
  return PolytopeBuilder::from_trusted_parts(sum_coordinates(w.vertex_origin, a.coordinates(), b.coordinates()),
                                             w.he_origin, w.he_next, w.he_facet, w.facet_he);
}

ConvexPolytope to_polytope(WalkSum&& w, const ConvexPolytope& a, const ConvexPolytope& b) {
  return PolytopeBuilder::from_trusted_parts(sum_coordinates(w.vertex_origin, a.coordinates(), b.coordinates()),
                                             std::move(w.he_origin), std::move(w.he_next), std::move(w.he_facet),
                                             std::move(w.facet_he));
}

SumResult minkowski_sum_walk(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  WalkSum w = minkowski_walk(a, b, options);
  const auto t1 = clock::now();
  options.report("convert", -1);
  SumResult r;
  r.method = Method::walk;
  r.polytope = to_polytope(std::move(w), a, b);
  const auto t2 = clock::now();
  r.vertex_origin = std::move(w.vertex_origin);
  r.facet_provenance = std::move(w.provenance);
  auto us = [](auto d) { return (long long)std::chrono::duration_cast<std::chrono::microseconds>(d).count(); };
  r.counters = {{"crossings", (long long)w.crossings},
                {"walk_steps", (long long)w.steps},
                {"predicates", (long long)w.predicates},
                {"exact_predicates", (long long)w.exact_predicates},
                {"walk_microseconds", us(t1 - t0)},
                {"convert_microseconds", us(t2 - t1)}};
  r.seconds = std::chrono::duration<double>(t2 - t0).count();
  r.explicit_seconds = std::chrono::duration<double>(t2 - t1).count();
  return r;
}

}  // namespace minksum
