// Internal to src/nonconvex/: the steps done with CGAL's exact Nef polyhedra
// (nef.cpp) and its self-intersection test (validate.cpp), kept in their own
// translation units for compile time.
#pragma once

#include <minksum/nonconvex.hpp>

#include <optional>
#include <utility>

namespace minksum::nonconvex_detail {

// The first pair of triangles of `triangles` (a closed 2-manifold triangle
// mesh) that intersect other than in a shared edge or vertex, if any
// (CGAL Polygon_mesh_processing::self_intersections, exact kernel).
std::optional<std::pair<Index, Index>> first_self_intersection(const Mesh& triangles);

// The convex pieces of a validated solid (CGAL convex_decomposition_3).
std::vector<ConvexPolytope> nef_convex_pieces(const Mesh& triangles);

// The boundary of the union of convex polytopes (each a Nef polyhedron,
// joined in a balanced tree).  Reports "union" with the fraction of joins
// done, then "boundary"; fills the counts and seconds of `out` (mesh,
// unions, shells, non_manifold_edges, seconds_union, seconds_boundary).
void nef_union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out);

}  // namespace minksum::nonconvex_detail
