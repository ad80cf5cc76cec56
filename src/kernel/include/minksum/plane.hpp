// Canonical planes: the plane of a facet as minksum states it (Plane in
// <minksum/kernel.hpp>: primitive integers, the normal outwards).
#pragma once

#include <minksum/kernel.hpp>

namespace minksum {

// The canonical plane with (unnormalised, nonzero) normal n through p.
Plane canonical_plane(const Point3& n, const Point3& p);

}  // namespace minksum
