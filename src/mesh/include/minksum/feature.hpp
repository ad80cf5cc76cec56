// The vertices of a feature (vertex, edge or facet) of a convex polytope.
#pragma once

#include <minksum/polytope.hpp>

#include <vector>

namespace minksum {

// The vertices of feature f of p: the vertex; the edge's origin and target
// (of its half-edge 2e); the facet's loop, counter-clockwise seen from outside.
std::vector<Index> feature_vertices(const ConvexPolytope& p, const Feature& f);

}  // namespace minksum
