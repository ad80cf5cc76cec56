// The improved 3D-MSSD of Wu et al., as Barki et al. (2009) re-implement it for their
// comparison (§2, §5.1, §6.1, Table 1), with exact predicates and no position
// threshold.
//
// The same merge of slope diagrams as ESSDMS, without embedding on the sphere
// and without stereographic projection (sum/slope_diagram.hpp), but without
// the contributing-vertex concept:
//
//   1. Two facet points (eq. 6-7): facet ⊕ facet.
//   2. A facet point on an edge arc (eq. 8-11): facet ⊕ edge.
//   3. Two edge arcs (eq. 12): EVERY pair of an edge arc of A and an edge arc
//      of B is tested (no Property 1 pruning): edge ⊕ edge.
//   4. A facet point in a vertex region: every facet point left after cases 1
//      and 2 is located by explicit point-in-spherical-polygon queries
//      against the vertex regions of the other diagram, one vertex after the
//      other, until the region holding it is found; the facet is translated
//      by that vertex.
//
// Cost O(f_A f_B + f_A e_B + f_B e_A + e_A e_B): locating one facet point
// costs at most the sum of the region sizes of the other diagram (2 e side
// tests), the order of case 2.
#include <minksum/minkowski.hpp>

#include <chrono>
#include <stdexcept>

#include "sum/slope_diagram.hpp"

namespace minksum {

SumResult minkowski_sum_mssd(const ConvexPolytope& A, const ConvexPolytope& B, const SumOptions& options) {
  using namespace slope_diagram;
  auto t0 = std::chrono::steady_clock::now();
  options.report("mssd", -1);
  const Diagram da(A), db(B);
  const Geometry g(da, db);
  Merge m(g);

  m.two_facet_points();           // case 1
  m.facet_points_on_edge_arcs();  // case 2
  options.report("mssd", -1);

  // Case 3: all pairs of edge arcs.
  for (Index ea = 0; ea < A.num_edges(); ++ea)
    for (Index eb = 0; eb < B.num_edges(); ++eb) m.edge_arc_pair(ea, eb);
  options.report("mssd", -1);

  // Case 4: point-in-polygon queries for the remaining facet points.
  m.facet_points_in_vertex_regions([&](const Diagram& P, Index f, const Diagram& Q) {
    for (Index v = 0; v < Q.p.num_vertices(); ++v) {
      ++m.point_in_polygon_queries;
      if (g.facet_point_in_vertex_region(P, f, Q, v, m.polygon_side_tests)) return v;
    }
    throw std::logic_error("mssd: a facet point left after the facet-point and edge-arc cases lies in no vertex region");
  });
  options.report("mssd", -1);

  SumResult r = finish(m, Method::mssd);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
