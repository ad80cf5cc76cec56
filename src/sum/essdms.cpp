// ESSDMS, the Enhanced and Simplified Slope Diagram-based Minkowski Sum
// (Barki et al. 2009, §5.2), with exact predicates and no position threshold.
//
// The slope diagrams of A and B are never embedded on the sphere nor
// projected; facet points, edge arcs and vertex regions are read off the
// polytopes (sum/slope_diagram.hpp).  The four intersection cases:
//
//   1. Two facet points (eq. 6-7): every facet point of A against the facet
//      points of B: facet ⊕ facet.  The contributing vertices of each facet
//      are the vertices of the other.
//   2. A facet point on an edge arc (eq. 8-11): every remaining facet point
//      against every edge arc of the other diagram: facet ⊕ edge.  The
//      contributing vertices of the facet are the edge's two ends.
//   4. A facet point in a vertex region: a facet contributes exactly once
//      (Property 2), so every facet point left after cases 1 and 2 lies in
//      the interior of a vertex region, with no point-in-polygon query: the
//      region is that of the facet's single contributing vertex, found by
//      eq. 3 (a scan of the other operand's vertices).  The facet is
//      translated by that vertex.
//   3. Two edge arcs (eq. 12): an edge arc whose two facets have a common
//      contributing vertex lies inside that vertex's region and crosses no
//      arc of the other diagram (Property 1); it is discarded from every
//      pair.  The remaining pairs are tested with eq. 8-9 applied to
//      x = n × n' and x' = n' × n: edge ⊕ edge.
//
// Case 4 runs before case 3 because case 3's pruning needs the contributing
// vertices of every facet; case 3 does not consume facet points, so the
// order does not change which facets each case produces.
//
// Cost O(f_A f_B + f_A e_B + f_B e_A + f_A v_B + f_B v_A + e_A e_B), the
// paper's §6.2 profile, with e_A e_B reduced to the pairs of unpruned arcs.
#include <minksum/minkowski.hpp>

#include <chrono>
#include <stdexcept>

#include "mesh/support.hpp"
#include "sum/slope_diagram.hpp"

namespace minksum {

namespace {

// Eq. 3 by a scan: the vertices of Q maximising <x, n_f> for facet f of P.
std::vector<Index> contributing(slope_diagram::Merge& m, const slope_diagram::Diagram& P, Index f,
                                const slope_diagram::Diagram& Q) {
  return support_scan(Q.p, [&](Index x, Index y) {
    ++m.contributing_vertex_tests;
    return m.g.support(P, f, Q, x, y);
  });
}

}  // namespace

SumResult minkowski_sum_essdms(const ConvexPolytope& A, const ConvexPolytope& B, const SumOptions& options) {
  using namespace slope_diagram;
  auto t0 = std::chrono::steady_clock::now();
  options.report("essdms", -1);
  const Diagram da(A), db(B);
  const Geometry g(da, db);
  Merge m(g);

  m.two_facet_points();           // case 1
  m.facet_points_on_edge_arcs();  // case 2
  options.report("essdms", -1);

  // Case 4: the remaining facet points, each in the region of its single
  // contributing vertex.
  m.facet_points_in_vertex_regions([&](const Diagram& P, Index f, const Diagram& Q) {
    const std::vector<Index> cv = contributing(m, P, f, Q);
    if (cv.size() != 1)
      throw std::logic_error("essdms: a facet left after the facet-point and edge-arc cases has " +
                             std::to_string(cv.size()) + " contributing vertices");
    return cv[0];
  });
  options.report("essdms", -1);

  // Case 3, with Property 1 pruning the edge arcs.
  auto active = [&](const ConvexPolytope& P, const std::vector<std::vector<Index>>& cv) {
    std::vector<Index> keep;
    for (Index e = 0; e < P.num_edges(); ++e) {
      if (share_a_vertex(cv[P.facet(2 * e)], cv[P.facet(2 * e + 1)])) ++m.edge_arcs_pruned;
      else keep.push_back(e);
    }
    return keep;
  };
  const std::vector<Index> arcs_a = active(A, m.cv_a), arcs_b = active(B, m.cv_b);
  for (Index ea : arcs_a)
    for (Index eb : arcs_b) m.edge_arc_pair(ea, eb);
  options.report("essdms", -1);

  SumResult r = finish(m, Method::essdms);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
