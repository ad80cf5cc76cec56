// Internal to src/nonconvex/: a closed triangle surface that touches itself
// cut apart combinatorially (round.cpp), for the sweep of such a surface
// (morphology.cpp).
#pragma once

#include <minksum/nonconvex.hpp>

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

}  // namespace minksum::nonconvex_detail
