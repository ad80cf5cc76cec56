// CHMS (Barki et al. 2009, §6.1-6.2): the Minkowski sum as the convex hull of all
// pairwise vertex sums a_i + b_j.  The sums are exact (a sum of two doubles
// is not always a double), the hull is CGAL's on exact points, and coplanar
// hull triangles are merged exactly by the polytope builder.  O(vA vB log).
// This is the project's reference oracle.
#include <minksum/minkowski.hpp>

#include <chrono>

namespace minksum {

SumResult minkowski_sum_chms(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  options.report("chms", -1);
  const Index na = a.num_vertices(), nb = b.num_vertices();
  std::vector<Point3> sums;
  sums.reserve(std::size_t(na) * nb);
  for (Index i = 0; i < na; ++i)
    for (Index j = 0; j < nb; ++j) sums.push_back(a.point(i) + b.point(j));
  options.report("chms", -1);
  SumResult r;
  r.method = Method::chms;
  r.polytope = ConvexPolytope::hull(sums, "chms");
  r.vertex_origin.reserve(r.polytope.num_vertices());
  for (Index v = 0; v < r.polytope.num_vertices(); ++v) {
    Index k = r.polytope.source_vertex(v);
    r.vertex_origin.emplace_back(k / nb, k % nb);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
