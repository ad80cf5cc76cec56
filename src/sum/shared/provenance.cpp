// Facet provenance by brute force: for each facet normal n of S, the faces of
// A and B maximising <x, n>, found by scanning every vertex.
#include <minksum/sum_result.hpp>

#include "mesh/support.hpp"

namespace minksum {

FacetOrigin FacetProvenance::origin() const {
  using enum FeatureDim;
  if (a.dim == facet && b.dim == facet) return FacetOrigin::facet_facet;
  if (a.dim == facet && b.dim == vertex) return FacetOrigin::translated;
  if (a.dim == vertex && b.dim == facet) return FacetOrigin::corner;
  if (a.dim == edge && b.dim == edge) return FacetOrigin::edge;
  return FacetOrigin::facet_edge;
}

std::vector<FacetProvenance> facet_provenance(const ConvexPolytope& a, const ConvexPolytope& b,
                                              const ConvexPolytope& s) {
  std::vector<FacetProvenance> out;
  out.reserve(s.num_facets());
  for (Index f = 0; f < s.num_facets(); ++f) {
    Point3 n = s.plane(f).normal();
    out.push_back({feature_of_vertices(a, support_vertices(a, n)), feature_of_vertices(b, support_vertices(b, n))});
  }
  return out;
}

}  // namespace minksum
