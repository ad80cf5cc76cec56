// The slope diagrams of two convex polytopes and the parts of their merge
// that ESSDMS and the improved 3D-MSSD share (Barki et al. 2009, §5).  The equations and
// their exact degree-3/4 forms are derived in slope_diagram.hpp.
#include "sum/slope_diagram.hpp"

#include <minksum/predicates.hpp>

#include <algorithm>
#include <stdexcept>

namespace minksum::slope_diagram {

std::vector<std::string> case_names() {
  return {"two_facet_points", "facet_point_on_edge_arc", "two_edge_arcs", "facet_point_in_vertex_region"};
}

Diagram::Diagram(const ConvexPolytope& poly) : p(poly), frame(poly.num_facets()) {
  for (Index f = 0; f < p.num_facets(); ++f) {
    Index h = p.facet_halfedge(f);
    frame[f] = {p.origin(h), p.target(h), p.target(p.next(h))};
  }
}

Geometry::Geometry(const Diagram& a, const Diagram& b)
    : a_(a), b_(b), doubles_(a.p.coordinates_are_doubles() && b.p.coordinates_are_doubles()) {
  if (doubles_) return;
  for (int k = 0; k < 2; ++k) {
    const Diagram& D = k == 0 ? a_ : b_;
    point_[k].reserve(D.p.num_vertices());
    for (Index v = 0; v < D.p.num_vertices(); ++v) {
      point_[k].push_back(to_fast(to_interval(D.p.point(v))));  // smallest double enclosures
    }
    normal_[k].reserve(D.p.num_facets());
    CGAL::Protect_FPU_rounding<true> upward;
    for (const Frame& x : D.frame) {
      const FastIPoint& p0 = point_[k][x[0]];
      normal_[k].push_back(cross(point_[k][x[1]] - p0, point_[k][x[2]] - p0));
    }
  }
}

bool Geometry::same_facet_point(const Diagram& P, Index f, const Diagram& Q, Index g) const {
  const Frame& x = P.frame[f];
  const Frame& y = Q.frame[g];
  if (doubles_)
    return normals_same_direction(P.p.approx(x[0]), P.p.approx(x[1]), P.p.approx(x[2]), Q.p.approx(y[0]),
                                  Q.p.approx(y[1]), Q.p.approx(y[2]));
  // n1 × n2 = 0 and <n1, n2> > 0 on the enclosures first.
  int cx, cy, cz, d;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const FastIPoint& n1 = normal_[side(P)][f];
    const FastIPoint& n2 = normal_[side(Q)][g];
    const FastIPoint c = cross(n1, n2);
    cx = sign_of(c.x), cy = sign_of(c.y), cz = sign_of(c.z), d = sign_of(dot(n1, n2));
  }
  if (cx == 1 || cx == -1 || cy == 1 || cy == -1 || cz == 1 || cz == -1 || d == -1 || d == 0) return false;
  if (cx == 0 && cy == 0 && cz == 0 && d == 1) return true;
  ++fallbacks_;
  return normals_same_direction(P.p.point(x[0]), P.p.point(x[1]), P.p.point(x[2]), Q.p.point(y[0]), Q.p.point(y[1]),
                                Q.p.point(y[2]));
}

int Geometry::edge_sign(const Diagram& Q, Index q0, Index q1, const Diagram& P, Index f) const {
  const Frame& x = P.frame[f];
  if (doubles_)
    return edge_facet_sign(Q.p.approx(q0), Q.p.approx(q1), P.p.approx(x[0]), P.p.approx(x[1]), P.p.approx(x[2]));
  int s;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const std::vector<FastIPoint>& q = point_[side(Q)];
    s = sign_of(dot(q[q1] - q[q0], normal_[side(P)][f]));
  }
  if (s != kUncertain) return s;
  ++fallbacks_;
  return edge_facet_sign(Q.p.point(q0), Q.p.point(q1), P.p.point(x[0]), P.p.point(x[1]), P.p.point(x[2]));
}

int Geometry::support(const Diagram& P, Index f, const Diagram& Q, Index i, Index j) const {
  const Frame& x = P.frame[f];
  if (doubles_)
    return support_compare(P.p.approx(x[0]), P.p.approx(x[1]), P.p.approx(x[2]), Q.p.approx(i), Q.p.approx(j));
  int s;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const std::vector<FastIPoint>& q = point_[side(Q)];
    s = sign_of(dot(q[i] - q[j], normal_[side(P)][f]));
  }
  if (s != kUncertain) return s;
  ++fallbacks_;
  return support_compare(P.p.point(x[0]), P.p.point(x[1]), P.p.point(x[2]), Q.p.point(i), Q.p.point(j));
}

bool Geometry::facet_point_on_arc(const Diagram& P, Index f, const Diagram& Q, Index e) const {
  const ConvexPolytope& q = Q.p;
  const Index h = 2 * e;
  const Index p0 = q.origin(h), p1 = q.target(h);
  // Eq. 8: <f, s × t> = 0, i.e. f is orthogonal to the edge.
  if (edge_sign(Q, p0, p1, P, f) != 0) return false;
  // Eq. 9: <w1 − p0, f> < 0 and <w2 − p0, f> < 0, with w1 the vertex after
  // p1 in facet s = facet(h) and w2 the vertex after p0 in facet t =
  // facet(twin h) (neither lies on the edge's line: facets are strictly
  // convex polygons).
  const Index w1 = q.target(q.next(h));
  if (support(P, f, Q, w1, p0) >= 0) return false;
  const Index w2 = q.target(q.next(h + 1));
  return support(P, f, Q, w2, p0) < 0;
}

int Geometry::arcs_cross(Index ea, Index eb, long long& tests) const {
  const ConvexPolytope& A = a_.p;
  const ConvexPolytope& B = b_.p;
  const Index ha = 2 * ea, hb = 2 * eb;
  const Index p0 = A.origin(ha), p1 = A.target(ha);
  const Index q0 = B.origin(hb), q1 = B.target(hb);
  // <s, eB> and <t, eB>: x or x' on A's arc.
  ++tests;
  const int s_a = edge_sign(b_, q0, q1, a_, A.facet(ha));
  if (s_a == 0) return 0;
  ++tests;
  if (edge_sign(b_, q0, q1, a_, A.facet(ha + 1)) != -s_a) return 0;
  // On A's arc lies x when s_a > 0, x' when s_a < 0.  B's arc must hold the
  // same point: <s', eA> = −s_a and <t', eA> = s_a.
  ++tests;
  if (edge_sign(a_, p0, p1, b_, B.facet(hb)) != -s_a) return 0;
  ++tests;
  if (edge_sign(a_, p0, p1, b_, B.facet(hb + 1)) != s_a) return 0;
  return s_a;
}

bool Geometry::facet_point_in_vertex_region(const Diagram& P, Index f, const Diagram& Q, Index v,
                                            long long& side_tests) const {
  const ConvexPolytope& q = Q.p;
  const Index first = q.vertex_halfedge(v);
  Index h = first;
  do {
    // Side between facet(h) and facet(twin h): det(n_facet(h), n_facet(twin h), f)
    // has the sign of <target(h) − v, f>; strictly inside means negative.
    ++side_tests;
    if (edge_sign(Q, v, q.target(h), P, f) >= 0) return false;
    h = q.next_around_vertex(h);
  } while (h != first);
  return true;
}

int normals_det_exact(const ConvexPolytope& p, Index f1, Index f2, const ConvexPolytope& q, Index g) {
  const Point3 n1 = p.plane(f1).normal(), n2 = p.plane(f2).normal(), n3 = q.plane(g).normal();
  return sgn(dot(n1, cross(n2, n3)));
}

namespace {

std::vector<Index> sorted(std::vector<Index> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Candidate facet f of P ⊕ the vertices qv of Q (all on the face of Q with
// the same outer normal), with P's role given by `p_is_a`.
FacetCandidate facet_plus(const ConvexPolytope& P, Index f, const std::vector<Index>& qv, bool p_is_a, Feature q_face,
                          Case c) {
  FacetCandidate cand;
  cand.normal = P.plane(f).normal();
  for (Index pv : P.facet_vertices(f))
    for (Index v : qv) cand.points.push_back(p_is_a ? std::make_pair(pv, v) : std::make_pair(v, pv));
  const Feature pf = Feature::facet(f);
  cand.provenance = p_is_a ? FacetProvenance{pf, q_face} : FacetProvenance{q_face, pf};
  cand.facet_case = int(c);
  return cand;
}

}  // namespace

Merge::Merge(const Geometry& geometry)
    : g(geometry),
      done_a(geometry.a().p.num_facets(), 0),
      done_b(geometry.b().p.num_facets(), 0),
      cv_a(geometry.a().p.num_facets()),
      cv_b(geometry.b().p.num_facets()) {}

void Merge::two_facet_points() {
  const ConvexPolytope& A = g.a().p;
  const ConvexPolytope& B = g.b().p;
  for (Index f = 0; f < A.num_facets(); ++f) {
    for (Index j = 0; j < B.num_facets(); ++j) {
      // The facet points of one diagram are pairwise distinct: a facet point
      // of B that already coincided with one of A cannot coincide again.
      if (done_b[j]) continue;
      ++facet_point_tests;
      if (!g.same_facet_point(g.a(), f, g.b(), j)) continue;
      // Eq. 7: f ⊕ j.  Each facet's contributing vertices are the other's.
      std::vector<Index> vj = B.facet_vertices(j);
      candidates.push_back(facet_plus(A, f, vj, true, Feature::facet(j), Case::two_facet_points));
      cv_a[f] = sorted(vj);
      cv_b[j] = sorted(A.facet_vertices(f));
      done_a[f] = done_b[j] = 1;
      break;
    }
  }
}

void Merge::facet_points_on_edge_arcs() {
  // A facet point lies in the interior of at most one edge arc of the other
  // diagram (two arcs meet only at facet points), so the scan of a facet
  // stops at the first arc that holds it.
  auto scan = [&](const Diagram& P, std::vector<char>& done, std::vector<std::vector<Index>>& cv, const Diagram& Q,
                  bool p_is_a) {
    for (Index f = 0; f < P.p.num_facets(); ++f) {
      if (done[f]) continue;
      for (Index e = 0; e < Q.p.num_edges(); ++e) {
        ++facet_point_arc_tests;
        if (!g.facet_point_on_arc(P, f, Q, e)) continue;
        // Eq. 10 / 11: f ⊕ e; the contributing vertices of f are e's ends.
        std::vector<Index> ends = sorted({Q.p.origin(2 * e), Q.p.target(2 * e)});
        candidates.push_back(facet_plus(P.p, f, ends, p_is_a, Feature::edge(e), Case::facet_point_on_edge_arc));
        cv[f] = std::move(ends);
        done[f] = 1;
        break;
      }
    }
  };
  scan(g.a(), done_a, cv_a, g.b(), true);
  scan(g.b(), done_b, cv_b, g.a(), false);
}

void Merge::edge_arc_pair(Index ea, Index eb) {
  ++arc_pair_tests;
  const int side = g.arcs_cross(ea, eb, arc_sign_tests);
  if (side == 0) return;
  const ConvexPolytope& A = g.a().p;
  const ConvexPolytope& B = g.b().p;
  const Index p0 = A.origin(2 * ea), p1 = A.target(2 * ea);
  const Index q0 = B.origin(2 * eb), q1 = B.target(2 * eb);
  // Eq. 12: eA ⊕ eB, outer normal the crossing point ±(eA × eB).
  FacetCandidate c;
  c.normal = cross(A.point(p1) - A.point(p0), B.point(q1) - B.point(q0));
  if (side < 0) c.normal = -c.normal;
  c.points = {{p0, q0}, {p1, q0}, {p1, q1}, {p0, q1}};
  c.provenance = {Feature::edge(ea), Feature::edge(eb)};
  c.facet_case = int(Case::two_edge_arcs);
  candidates.push_back(std::move(c));
}

void Merge::facet_in_vertex_region(bool f_of_a, Index f, Index v) {
  const ConvexPolytope& P = f_of_a ? g.a().p : g.b().p;
  candidates.push_back(facet_plus(P, f, {v}, f_of_a, Feature::vertex(v), Case::facet_point_in_vertex_region));
  (f_of_a ? cv_a : cv_b)[f] = {v};
  (f_of_a ? done_a : done_b)[f] = 1;
}

std::vector<std::pair<std::string, long long>> Merge::counters() const {
  return {
      {"facet_point_tests", facet_point_tests},
      {"facet_point_arc_tests", facet_point_arc_tests},
      {"arc_pair_tests", arc_pair_tests},
      {"arc_sign_tests", arc_sign_tests},
      {"edge_arcs_pruned", edge_arcs_pruned},
      {"point_in_polygon_queries", point_in_polygon_queries},
      {"polygon_side_tests", polygon_side_tests},
      {"contributing_vertex_tests", contributing_vertex_tests},
      {"interval_exact_fallbacks", g.exact_fallbacks()},
  };
}

SumResult finish(Merge& m, Method method) {
  SumResult r = assemble_sum(m.g.a().p, m.g.b().p, std::move(m.candidates), method);
  r.facet_case_names = case_names();
  r.counters = m.counters();
  return r;
}

}  // namespace minksum::slope_diagram
