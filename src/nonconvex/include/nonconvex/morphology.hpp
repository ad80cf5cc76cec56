// Internal to src/nonconvex/: what erosion, opening and closing
// (morphology.cpp) take from other files: a closed triangle surface that
// touches itself cut apart combinatorially (round.cpp), for the sweep of
// such a surface, and, for the tests, the erosion of a convex polytope as an
// intersection of half-spaces (convex_erosion.cpp).
#pragma once

#include <minksum/nonconvex.hpp>

#include <optional>

namespace minksum::nonconvex_detail {

// `triangles` (a closed surface, every directed edge matched by an opposite
// one, exactly equal points already one point) with every edge of more than
// two triangles and every vertex of several fans cut apart: around such an
// edge each triangle is paired with its neighbour across the solid (the
// side its orientation calls inside; exact radial order), and each fan of a
// point gets a copy of the point of its own, at the same exact coordinates.
// The result is a 2-manifold triangle mesh bounding the same set, so the
// local normal cones read off it (SurfaceCones) are those of the set's
// parts on either side of the contact.  The same mesh when nothing touches.
Mesh separate_contacts(const Mesh& triangles);

// A ⊖ B for convex polytopes A and B, the tests' independent construction
// with CGAL's halfspace_intersection_3 (erode uses halfspace_erosion): the
// intersection of the half-spaces n · x <= d - h_B(n) over A's facet
// planes n · x <= d (h_B: B's support),
// exact, from a point strictly inside all of them.  Empty (nullopt) when no
// such point is found (the linear program that looks for one works on
// doubles): the erosion is then empty, or thinner than doubles tell, and
// the caller decides by the sweep.
std::optional<ConvexPolytope> convex_erosion(const ConvexPolytope& a, const ConvexPolytope& b);

// A ⊖ B for convex polytopes A and B, what erode, opening and closing use
// for a convex A (halfspace_erosion.cpp): the same intersection of moved
// half-spaces, built exactly as the polar of the exact hull of the dual
// points about a point strictly inside, checked with exact signs.  nullopt
// when no point strictly inside is found — the difference of A's and B's
// vertex centroids, rounded to doubles or exact, is the only candidate —,
// which includes every empty or lower-dimensional erosion: the caller then
// takes the sweep, which decides exactly.
std::optional<ConvexPolytope> halfspace_erosion(const ConvexPolytope& a, const ConvexPolytope& b);

}  // namespace minksum::nonconvex_detail
