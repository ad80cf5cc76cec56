// ConvexPolytope from parts a method has already proven valid (builder.hpp).
#include "mesh/builder.hpp"

#include <stdexcept>

namespace minksum {

ConvexPolytope PolytopeBuilder::from_trusted_parts(PointList points, std::vector<Index> he_origin,
                                                   std::vector<Index> he_next, std::vector<Index> he_facet,
                                                   std::vector<Index> facet_he) {
  const Index nv = Index(points.size()), nh = Index(he_origin.size());
  if (he_next.size() != nh || he_facet.size() != nh || nh % 2)
    throw std::logic_error("from_trusted_parts: inconsistent array sizes");
  ConvexPolytope p;
  p.he_prev_.assign(nh, kNoIndex);
  p.vertex_he_.assign(nv, kNoIndex);
  for (Index h = 0; h < nh; ++h) {
    if (he_next[h] >= nh || he_origin[h] >= nv) throw std::logic_error("from_trusted_parts: bad half-edge link");
    p.he_prev_[he_next[h]] = h;
    if (p.vertex_he_[he_origin[h]] == kNoIndex) p.vertex_he_[he_origin[h]] = h;
  }
  p.source_vertex_.resize(nv);
  for (Index v = 0; v < nv; ++v) p.source_vertex_[v] = v;
  p.coords_ = std::move(points);
  p.he_origin_ = std::move(he_origin);
  p.he_next_ = std::move(he_next);
  p.he_facet_ = std::move(he_facet);
  p.facet_he_ = std::move(facet_he);
  p.reset_cache();
  return p;
}

}  // namespace minksum
