// FCL's convex shape of a polytope: the same vertices (their doubles) and
// facets.  For the FCL columns of bench_proximity.
#pragma once

#ifdef MINKSUM_HAVE_FCL
#include <fcl/geometry/shape/convex.h>
#include <minksum/polytope.hpp>

#include <memory>
#include <vector>

inline std::shared_ptr<fcl::Convexd> fcl_convex(const minksum::ConvexPolytope& p) {
  auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
  for (minksum::Index v = 0; v < p.num_vertices(); ++v) {
    const minksum::Vec3d a = p.approx(v);
    verts->emplace_back(a.x, a.y, a.z);
  }
  auto faces = std::make_shared<std::vector<int>>();
  for (minksum::Index f = 0; f < p.num_facets(); ++f) {
    const std::vector<minksum::Index> loop = p.facet_vertices(f);
    faces->push_back(int(loop.size()));
    for (minksum::Index v : loop) faces->push_back(int(v));
  }
  return std::make_shared<fcl::Convexd>(verts, int(p.num_facets()), faces);
}
#endif
