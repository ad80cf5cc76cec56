// ConvexPolytope from parts a method has already proven valid (builder.hpp).
#include "mesh/builder.hpp"
#include "kernel/plane.hpp"

#include <stdexcept>

namespace minksum {

ConvexPolytope PolytopeBuilder::from_trusted_parts(std::vector<Point3> points, std::vector<Index> he_origin,
                                                   std::vector<Index> he_next, std::vector<Index> he_facet,
                                                   std::vector<Index> facet_he, const std::vector<Point3>& normals) {
  const Index nv = Index(points.size()), nh = Index(he_origin.size()), nf = Index(facet_he.size());
  if (he_next.size() != nh || he_facet.size() != nh || normals.size() != nf || nh % 2)
    throw std::logic_error("from_trusted_parts: inconsistent array sizes");
  ConvexPolytope p;
  p.he_prev_.assign(nh, kNoIndex);
  p.vertex_he_.assign(nv, kNoIndex);
  for (Index h = 0; h < nh; ++h) {
    if (he_next[h] >= nh || he_origin[h] >= nv) throw std::logic_error("from_trusted_parts: bad half-edge link");
    p.he_prev_[he_next[h]] = h;
    if (p.vertex_he_[he_origin[h]] == kNoIndex) p.vertex_he_[he_origin[h]] = h;
  }
  p.approx_.resize(nv);
  p.source_vertex_.resize(nv);
  p.all_double_ = true;
  for (Index v = 0; v < nv; ++v) {
    p.approx_[v] = to_double(points[v]);
    p.source_vertex_[v] = v;
    if (p.all_double_ && !is_double(points[v])) p.all_double_ = false;
  }
  p.planes_.reserve(nf);
  for (Index f = 0; f < nf; ++f) p.planes_.push_back(minksum::canonical_plane(normals[f], points[he_origin[facet_he[f]]]));
  p.points_ = std::move(points);
  p.he_origin_ = std::move(he_origin);
  p.he_next_ = std::move(he_next);
  p.he_facet_ = std::move(he_facet);
  p.facet_he_ = std::move(facet_he);
  return p;
}

}  // namespace minksum
