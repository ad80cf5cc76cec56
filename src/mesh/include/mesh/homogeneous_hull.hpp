// Internal: the exact convex hull of points in homogeneous integer
// coordinates (kernel/homogeneous.hpp), as a triangulated surface.
//
// Quickhull (C. B. Barber, D. P. Dobkin, H. Huhdanpaa, "The Quickhull
// algorithm for convex hulls", ACM TOMS 22(4), 1996) with every decision an
// exact sign: a start tetrahedron, each remaining point in the outside set of
// one facet it lies strictly beyond (points beyond none are inside or on the
// hull, and are dropped), then, facet by facet, the point of its outside set
// farthest from it (by doubles: a choice, not a decision) is added — the
// facets it sees strictly form a disc whose boundary, the horizon, is a
// simple cycle; they are replaced by the triangles from the point to the
// horizon edges (never degenerate: a point collinear with a horizon edge
// would lie on the plane of the visible facet at that edge), and the points
// of their outside sets go to the new facets they lie strictly beyond, or
// are dropped (inside the new hull: Barber et al.'s argument).  A point on
// the plane of a facet is never beyond it, so coplanar points make coplanar
// triangles, not errors: the caller groups them (`flat`).
#pragma once

#include "kernel/homogeneous.hpp"

#include <minksum/polytope.hpp>  // Index

#include <array>
#include <vector>

namespace minksum {

struct HomogeneousHull {
  // Triangles of input point indices, counter-clockwise seen from outside;
  // neighbour[t][k] is the triangle across edge (v_k, v_(k+1)), and
  // flat[t][k] says whether it lies in the same plane (exactly).
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::array<Index, 3>> neighbour;
  std::vector<std::array<bool, 3>> flat;
};

// The hull of `points`, which must span three dimensions
// (std::invalid_argument otherwise); a point may repeat (the same point
// with another w, too).  The caller holds a CGAL::Protect_FPU_rounding<true>
// guard (std::logic_error otherwise).
HomogeneousHull homogeneous_hull(const std::vector<detail::HomogeneousPoint>& points);

}  // namespace minksum
