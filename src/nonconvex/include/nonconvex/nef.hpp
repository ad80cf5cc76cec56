// Internal to src/nonconvex/: the steps done with CGAL's exact Nef polyhedra
// (nef.cpp) and its self-intersection test (validate.cpp), kept in their own
// translation units for compile time.
#pragma once

#include <minksum/nonconvex.hpp>

#include <optional>
#include <utility>

namespace minksum::nonconvex_detail {

// The first pair of triangles of `triangles` (a closed 2-manifold triangle
// mesh) that intersect other than in a shared edge or vertex, if any: the
// pair CGAL's Polygon_mesh_processing::self_intersections reports first,
// found by the same box intersection and the same exact predicates
// (triangles_meet.hpp), the pairs tested on every hardware thread when all
// coordinates are doubles.
std::optional<std::pair<Index, Index>> first_self_intersection(const Mesh& triangles);

// The convex pieces of a validated solid (CGAL convex_decomposition_3).
std::vector<ConvexPolytope> nef_convex_pieces(const Mesh& triangles);

// The boundary of the union of convex polytopes by CGAL's Nef polyhedra
// (each a Nef polyhedron, joined in a balanced tree); the tests compare
// minksum's union (union_boundary, nonconvex/union.hpp) with it.  Reports
// "union" with the fraction of joins done, then "boundary"; fills mesh,
// shells, non_manifold_edges, seconds_union and seconds_boundary of `out`.
void nef_union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out);

// The exact volume of the union of convex polytopes by CGAL's Nef
// polyhedra, without their boundary: the joined Nef polyhedron cut into
// convex pieces (convex_decomposition_3), their volumes added.  For the
// tests, where CGAL's conversion of a Nef boundary to polygons fails.
Rational nef_union_volume(const std::vector<ConvexPolytope>& parts);

}  // namespace minksum::nonconvex_detail
