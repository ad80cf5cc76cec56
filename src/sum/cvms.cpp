// CVMS, the Contributing Vertices-based Minkowski Sum (Barki et al. 2009, §3-4,
// Algorithm 1), with exact predicates.
//
// (1) Translated facets: for every facet f of A, its contributing vertices in
//     B (eq. 3) are found by scanning all vertices of B.  One contributing
//     vertex v: f translated by v.  Two: f ⊕ the edge of B joining them.
//     Three or more: f ⊕ the parallel facet g of B, which then does not
//     contribute again (Property 2).
// (2) Corner facets: the same for the facets of B not used in (1), scanning
//     all vertices of A.
// (3) Edge facets: for every edge e_A of A whose two facets have no common
//     contributing vertex (Property 1), the visibility of every facet of B
//     with respect to e_A (eq. 4: invisible iff <e_A, n_B> > 0) gives the
//     horizon edges of B; each horizon edge e_B whose facets have no common
//     contributing vertex and which passes the normal-orientation criterion
//     (eq. 5) gives the edge facet e_A ⊕ e_B.
// Cost O(f_A v_B + f_B v_A + e_A (f_B + e_B)), the paper's profile.
//
// Eq. 5 with n = e_A × e_B reads <n1 × n, e_A> < 0 and <n × n2, e_A> < 0.
// Because n1 and n2 are orthogonal to e_A, the Binet-Cauchy identity turns
// both into degree-3 signs of <n1, e_B> and <n2, e_B>, which must be strictly
// opposite.  The orientation of e_B matters (the antipodal parallel edge of a
// centrally symmetric B passes every test with the other orientation): with
// h the halfedge of e_A (p0 -> p1), n1 the normal of facet(h) and n2 that of
// facet(twin(h)), n = e_A × e_B is on A's arc from n1 to n2 iff
// <n1, e_B> > 0 > <n2, e_B>; with k the halfedge of e_B (q0 -> q1), m1, m2
// the normals of facet(k), facet(twin(k)), the same n is on B's arc iff e_B
// runs q1 -> q0 when facet(k) is the invisible one (<e_A, m1> > 0) and
// q0 -> q1 otherwise.  So the horizon edge is oriented by its invisible side
// and eq. 5 is then tested as <n1, e_B> > 0 > <n2, e_B>.
//
// Coincidences (parallel facets, facet normals on arcs, A = B) can make two
// steps produce pieces of the same facet of S; the assembly groups candidates
// by exact normal direction and takes each facet as the planar hull of its
// pieces (face_A(n) ⊕ face_B(n)).
#include <minksum/minkowski.hpp>
#include <minksum/predicates.hpp>

#include <algorithm>
#include <array>
#include <chrono>

#include "mesh/support.hpp"
#include "sum/faces.hpp"

namespace minksum {

namespace {

using Frame = std::array<Index, 3>;  // three consecutive vertices of a facet

std::vector<Frame> frames(const ConvexPolytope& p) {
  std::vector<Frame> fr(p.num_facets());
  for (Index f = 0; f < p.num_facets(); ++f) {
    Index h = p.facet_halfedge(f);
    fr[f] = {p.origin(h), p.target(h), p.target(p.next(h))};
  }
  return fr;
}

// Exact predicates on the operands' coordinates: the filtered double forms
// when every coordinate is a double, the rational forms otherwise.
struct Geometry {
  const ConvexPolytope& A;
  const ConvexPolytope& B;
  bool doubles;

  // sign <q_i - q_j, n(facet of P)>
  int support(const ConvexPolytope& P, const Frame& f, const ConvexPolytope& Q, Index i, Index j) const {
    if (doubles)
      return support_compare(P.approx(f[0]), P.approx(f[1]), P.approx(f[2]), Q.approx(i), Q.approx(j));
    return support_compare(P.point(f[0]), P.point(f[1]), P.point(f[2]), Q.point(i), Q.point(j));
  }
  // sign <q1 - q0, n(facet of P)> with q0, q1 vertices of Q
  int edge_vs_facet(const ConvexPolytope& Q, Index q0, Index q1, const ConvexPolytope& P, const Frame& f) const {
    if (doubles)
      return edge_facet_sign(Q.approx(q0), Q.approx(q1), P.approx(f[0]), P.approx(f[1]), P.approx(f[2]));
    return edge_facet_sign(Q.point(q0), Q.point(q1), P.point(f[0]), P.point(f[1]), P.point(f[2]));
  }
};

// Contributing vertices of facet f of P with respect to Q (eq. 3): the
// support set of Q along the facet's normal, by a scan of all vertices of Q;
// sorted.
std::vector<Index> contributing(const Geometry& g, const ConvexPolytope& P, const Frame& f, const ConvexPolytope& Q) {
  return support_scan(Q, [&](Index x, Index y) { return g.support(P, f, Q, x, y); });
}

// Candidate facet (face of P) ⊕ (face of Q spanned by vs), with P's role given
// by `p_is_a`.
FacetCandidate facet_candidate(const ConvexPolytope& P, Index f, const ConvexPolytope& Q, const std::vector<Index>& vs,
                               bool p_is_a, Feature q_face) {
  FacetCandidate c;
  c.normal = P.plane(f).normal();
  std::vector<Index> qv = vs;
  if (q_face.dim == FeatureDim::facet) qv = Q.facet_vertices(q_face.index);
  for (Index pv : P.facet_vertices(f))
    for (Index v : qv) c.points.push_back(p_is_a ? std::make_pair(pv, v) : std::make_pair(v, pv));
  const Feature pf = Feature::facet(f);
  c.provenance = p_is_a ? FacetProvenance{pf, q_face} : FacetProvenance{q_face, pf};
  return c;
}

}  // namespace

SumResult minkowski_sum_cvms(const ConvexPolytope& A, const ConvexPolytope& B, const SumOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  options.report("cvms", -1);
  const Geometry g{A, B, A.coordinates_are_doubles() && B.coordinates_are_doubles()};
  const std::vector<Frame> frA = frames(A), frB = frames(B);
  std::vector<std::vector<Index>> cvA(A.num_facets()), cvB(B.num_facets());
  std::vector<char> usedB(B.num_facets(), 0);
  std::vector<FacetCandidate> candidates;

  // (1) Translated facets.
  for (Index f = 0; f < A.num_facets(); ++f) {
    cvA[f] = contributing(g, A, frA[f], B);
    const Feature face = feature_of_vertices(B, cvA[f]);
    if (face.dim == FeatureDim::facet) {
      usedB[face.index] = 1;  // Property 2: it contributes once
      cvB[face.index] = A.facet_vertices(f);
      std::sort(cvB[face.index].begin(), cvB[face.index].end());
    }
    candidates.push_back(facet_candidate(A, f, B, cvA[f], true, face));
  }
  options.report("cvms", -1);
  // (2) Corner facets.
  for (Index f = 0; f < B.num_facets(); ++f) {
    if (usedB[f]) continue;
    cvB[f] = contributing(g, B, frB[f], A);
    candidates.push_back(facet_candidate(B, f, A, cvB[f], false, feature_of_vertices(A, cvB[f])));
  }
  options.report("cvms", -1);
  // (3) Edge facets.  Property 1 for the edges of B first.
  std::vector<char> activeB(B.num_edges());
  for (Index e = 0; e < B.num_edges(); ++e)
    activeB[e] = !share_a_vertex(cvB[B.facet(2 * e)], cvB[B.facet(2 * e + 1)]);
  std::vector<char> invisible(B.num_facets());
  for (Index e = 0; e < A.num_edges(); ++e) {
    const Index h = 2 * e;
    const Index f1 = A.facet(h), f2 = A.facet(h + 1);
    if (share_a_vertex(cvA[f1], cvA[f2])) continue;  // Property 1
    const Index p0 = A.origin(h), p1 = A.target(h);
    // Eq. 4: facet j of B is invisible from direction e_A iff <e_A, n_j> > 0.
    for (Index j = 0; j < B.num_facets(); ++j) invisible[j] = g.edge_vs_facet(A, p0, p1, B, frB[j]) > 0;
    for (Index k = 0; k < B.num_edges(); ++k) {
      if (!activeB[k]) continue;
      if (invisible[B.facet(2 * k)] == invisible[B.facet(2 * k + 1)]) continue;  // not a horizon edge
      Index q0 = B.origin(2 * k), q1 = B.target(2 * k);
      if (invisible[B.facet(2 * k)]) std::swap(q0, q1);  // orient the horizon edge
      // Eq. 5 (see the comment at the top).
      if (g.edge_vs_facet(B, q0, q1, A, frA[f1]) <= 0 || g.edge_vs_facet(B, q0, q1, A, frA[f2]) >= 0) continue;
      FacetCandidate c;
      c.normal = cross(A.point(p1) - A.point(p0), B.point(q1) - B.point(q0));
      c.points = {{p0, q0}, {p1, q0}, {p1, q1}, {p0, q1}};
      c.provenance = {Feature::edge(e), Feature::edge(k)};
      candidates.push_back(std::move(c));
    }
  }

  options.report("cvms", -1);
  SumResult r = assemble_sum(A, B, std::move(candidates), Method::cvms);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
