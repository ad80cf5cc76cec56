// Internal: the slope diagrams of two convex polytopes and their merge
// (Barki et al. 2009, §5), shared by the ESSDMS (essdms.cpp) and improved 3D-MSSD
// (mssd.cpp) methods.
//
// A slope diagram is never embedded on the sphere and never projected: every
// facet point, edge arc and vertex region is read off the half-edge structure
// of the polytope, and every intersection test is the sign of an exact
// polynomial in the input coordinates (src/kernel/include/minksum/predicates.hpp).
//
// Reading the diagram off the polytope P:
//   * facet point of facet f: the outer normal n_f = n(frame(f)) (three
//     consecutive vertices of f, counter-clockwise from outside);
//   * edge arc of edge e: with h = 2e running p0 -> p1, the shorter arc from
//     s = n_facet(h) to t = n_facet(twin h).  Its great circle has normal
//     s × t, which for a strictly convex edge is a POSITIVE multiple of the
//     edge vector e = p1 − p0 (s × t = β|s|² e with β > 0, because t has a
//     positive component along −(s × e), the direction leaving facet s
//     across the edge);
//   * vertex region of vertex v: the spherical polygon whose corners are the
//     facet points of the facets around v and whose sides are the edge arcs
//     of the edges at v.
//
// The paper's equations, evaluated exactly:
//   eq. 6  two facet points coincide: a × b = 0 and <a, b> > 0
//          -> normals_same_direction (degree 4).
//   eq. 8  facet point f on the great circle of arc st: <f, s × t> = 0
//          <=> <f, e> = 0 -> edge_facet_sign == 0 (degree 3).
//   eq. 9  f strictly inside the shorter arc: <s × f, n> > 0 and
//          <f × t, n> > 0 with n = s × t = β|s|² e.  With L1 = s × e, the
//          direction from the edge into facet s, <s × f, e> = <f, e × s> =
//          −<f, L1>; given <f, e> = 0 this has the sign of −<f, w1 − p0> for
//          any vertex w1 of facet s off the edge (w1 − p0 = a·e + b·L1 with
//          b > 0).  Likewise <f × t, e> = <f, t × e> = −<f, L2> with L2 the
//          direction into facet t, whose sign is that of −<f, w2 − p0>.  So
//          eq. 9 <=> <w1 − p0, f> < 0 and <w2 − p0, f> < 0: two
//          support_compare signs (degree 3).
//   eq. 12 two edge arcs (edges eA of A with arc s -> t, eB of B with arc
//          s' -> t') cross at x = n × n' (a positive multiple of eA × eB) or
//          at x' = −x.  Eq. 8 holds for x by construction; eq. 9 for x on
//          arc st expands with s × (eA × eB) = eA <s, eB> − eB <s, eA> and
//          <s, eA> = 0 to |eA|² <s, eB> > 0 and −|eA|² <t, eB> > 0; on arc
//          s't' to −|eB|² <s', eA> > 0 and |eB|² <t', eA> > 0.  So
//            x  on both arcs <=> <s, eB> > 0 > <t, eB> and <s', eA> < 0 < <t', eA>,
//            x' on both arcs <=> all four signs reversed,
//          four edge_facet_sign values (degree 3).  Parallel edge arcs
//          (eA ∥ eB, the same great circle) give <s, eB> = 0 and fail.
//   vertex region (point-in-spherical-polygon, mssd): f lies strictly inside
//          the region of v iff det(n_i, n_{i+1}, f) < 0 for every side: the
//          side between facet(h) and facet(twin h) for an outgoing halfedge
//          h = v -> u has great-circle normal n_facet(h) × n_facet(twin h) =
//          β (u − v), so det(...) has the sign of <u − v, f>
//          (edge_facet_sign, degree 3; the same value as the degree-6
//          determinant of three exact facet normals, which the tests check).
//   eq. 3  contributing vertices (essdms): the vertices of Q maximising
//          <x, n_f>, by support_compare (degree 3).
//
// Every predicate runs on the filtered double form of predicates.hpp when
// both operands' coordinates are doubles.  Otherwise (exact rational
// coordinates, e.g. rotated solids) each vertex is enclosed once in its
// smallest double interval (kernel/interval.hpp) and each facet normal
// n(frame) in an interval computed from those; every sign is then evaluated
// in interval arithmetic rounded outward (CGAL::Interval_nt under a
// Protect_FPU_rounding guard), whose result contains the exact value.  A
// sign whose interval excludes zero, or is exactly [0, 0], is the exact
// sign; any other call falls back to the rational form of the same
// predicate (counted in Geometry::exact_fallbacks).
#pragma once

#include <minksum/sum_result.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "kernel/interval.hpp"
#include "sum/faces.hpp"

namespace minksum::slope_diagram {

// The four intersection cases of Barki et al. 2009, §5.1, in the order of
// SumResult::facet_case_names.
enum class Case : std::uint8_t {
  two_facet_points = 0,              // eq. 6-7:  facet ⊕ facet
  facet_point_on_edge_arc = 1,       // eq. 8-11: facet ⊕ edge
  two_edge_arcs = 2,                 // eq. 12:   edge ⊕ edge
  facet_point_in_vertex_region = 3,  // facet translated by a vertex
};
std::vector<std::string> case_names();

using Frame = std::array<Index, 3>;  // three consecutive vertices of a facet

// One operand's slope diagram, read off the polytope.
struct Diagram {
  const ConvexPolytope& p;
  std::vector<Frame> frame;  // frame[f] spans the outer normal of facet f
  explicit Diagram(const ConvexPolytope& poly);
};

// The exact intersection tests between the components of two diagrams.
class Geometry {
 public:
  Geometry(const Diagram& a, const Diagram& b);

  // Eq. 6: facet point f of P and facet point g of Q coincide.
  bool same_facet_point(const Diagram& P, Index f, const Diagram& Q, Index g) const;
  // Eq. 8-9: facet point f of P lies in the open edge arc of edge e of Q.
  bool facet_point_on_arc(const Diagram& P, Index f, const Diagram& Q, Index e) const;
  // Eq. 12 with eq. 8-9 applied to x and x': +1 when x = eA × eB lies in the
  // open arcs of edge ea of A and edge eb of B, −1 when −x does, 0 when the
  // arcs do not cross (including parallel arcs).  `tests` counts the sign
  // evaluations made.
  int arcs_cross(Index ea, Index eb, long long& tests) const;
  // Point-in-spherical-polygon: facet point f of P lies strictly inside the
  // vertex region of vertex v of Q.  `side_tests` counts the sides tested.
  bool facet_point_in_vertex_region(const Diagram& P, Index f, const Diagram& Q, Index v,
                                    long long& side_tests) const;
  // Eq. 3: sign <q_i − q_j, n_f> for facet f of P and vertices i, j of Q.
  int support(const Diagram& P, Index f, const Diagram& Q, Index i, Index j) const;

  const Diagram& a() const { return a_; }
  const Diagram& b() const { return b_; }
  // Interval signs that could not be decided (rational coordinates only).
  long long exact_fallbacks() const { return fallbacks_; }

 private:
  // sign <q1 − q0, n_f>: edge (q0, q1) of Q against facet f of P.
  int edge_sign(const Diagram& Q, Index q0, Index q1, const Diagram& P, Index f) const;
  // The interval enclosures of diagram D (0 for a, 1 for b).
  int side(const Diagram& D) const { return &D == &a_ ? 0 : 1; }
  const Diagram& a_;
  const Diagram& b_;
  bool doubles_;
  // Unprotected intervals (kernel/interval.hpp), used only under a
  // CGAL::Protect_FPU_rounding guard (rounding upward), the pattern of
  // CGAL's filtered predicates.
  std::vector<FastIPoint> point_[2], normal_[2];  // filled when !doubles_
  mutable long long fallbacks_ = 0;
};

// The state of a merge: the candidates found so far, which facets have
// contributed (a facet contributes exactly once), the contributing vertices
// deduced from each intersection (sorted; empty while unknown), and the
// operation counters.
struct Merge {
  const Geometry& g;
  std::vector<FacetCandidate> candidates;
  std::vector<char> done_a, done_b;
  std::vector<std::vector<Index>> cv_a, cv_b;
  long long facet_point_tests = 0;      // eq. 6 tests
  long long facet_point_arc_tests = 0;  // eq. 8-9 tests
  long long arc_pair_tests = 0;         // eq. 12 tests (pairs of edge arcs)
  long long arc_sign_tests = 0;         // the sign evaluations inside them
  long long point_in_polygon_queries = 0;
  long long polygon_side_tests = 0;
  long long contributing_vertex_tests = 0;  // eq. 3 comparisons
  long long edge_arcs_pruned = 0;           // edge arcs skipped by Property 1

  explicit Merge(const Geometry& geometry);

  // Case 1 (eq. 6-7): every facet point of A against the facet points of B
  // that have not contributed yet.
  void two_facet_points();
  // Case 2 (eq. 8-11): every facet point not yet contributed against every
  // edge arc of the other diagram.
  void facet_points_on_edge_arcs();
  // Case 3 (eq. 12) for one pair of edge arcs; adds the candidate when they
  // cross.
  void edge_arc_pair(Index ea, Index eb);
  // Case 4: facet f of A (`f_of_a`) or of B translated by vertex v of the
  // other operand.
  void facet_in_vertex_region(bool f_of_a, Index f, Index v);
  // Case 4 for every facet point left after cases 1 and 2, those of A then
  // those of B: locate(P, f, Q) is the vertex of Q whose region holds the
  // facet point of facet f of P.
  template <class Locate>
  void facet_points_in_vertex_regions(Locate&& locate) {
    auto regions = [&](const Diagram& P, bool p_is_a, const Diagram& Q) {
      const std::vector<char>& done = p_is_a ? done_a : done_b;
      for (Index f = 0; f < P.p.num_facets(); ++f)
        if (!done[f]) facet_in_vertex_region(p_is_a, f, locate(P, f, Q));
    };
    regions(g.a(), true, g.b());
    regions(g.b(), false, g.a());
  }

  // The operation counters, for SumResult::counters.
  std::vector<std::pair<std::string, long long>> counters() const;
};

// The finished sum: assembly, case names, counters.
SumResult finish(Merge& m, Method method);

// The degree-6 determinant det(n1, n2, n3) of three exact facet normals,
// evaluated with the polytopes' exact integer plane normals: for tests of the
// degree-3 reductions above.
int normals_det_exact(const ConvexPolytope& p, Index f1, Index f2, const ConvexPolytope& q, Index g);

}  // namespace minksum::slope_diagram
