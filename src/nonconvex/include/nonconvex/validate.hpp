// Internal to src/nonconvex/: the general checks of validate_solid
// (validate.cpp) for a caller that does not want its convex shortcut.
#pragma once

#include <minksum/nonconvex.hpp>

#include <string>

namespace minksum::nonconvex_detail {

// validate_solid's checks of a surface, the same errors in the same words,
// without first trying to read the mesh as a convex polytope: for a surface
// that is rarely convex (the rounded result of a non-convex sum, checked
// before it is written), where that attempt is wasted work.  The Solid has
// `convex` false whatever its shape.
Solid validate_surface(const Mesh& mesh, const std::string& source);

// The same checks and errors, for a caller that only needs them passed (the
// rounded surface before it is written): the Solid, and with it the exact
// volume, is not made; the orientation is decided from the volume's sign,
// on intervals where they decide it.
void check_surface(const Mesh& mesh, const std::string& source);

}  // namespace minksum::nonconvex_detail
