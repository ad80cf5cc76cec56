// minksum — the exact stage of the predicates.
//
// Internal header of src/kernel/.  Every predicate is multilinear in its
// group vectors, so each group may be multiplied by any positive number
// without changing the sign: load() scales each group to an integer vector
// (a power of two for doubles, the lcm of the denominators for rationals)
// in a per-thread workspace, and the shape functions evaluate the
// polynomial with mpz.  No call allocates once the workspace has grown.
#pragma once

#include <array>
#include <cstddef>
#include <minksum/kernel.hpp>

namespace minksum::detail {

struct Workspace;  // this thread's mpz scratch (exact.cpp)

// Loads k ≤ 4 groups into this thread's workspace: {p, q} → p − q,
// {p, nullptr} → p.  Vec3d coordinates must be finite (assert).
Workspace& load(const std::array<const Vec3d*, 2>* groups, std::size_t k);
Workspace& load(const std::array<const Point3*, 2>* groups, std::size_t k);

// The shapes on the loaded groups g0, g1, ... (the same shapes as the
// filter's, kernel/filter.hpp).
int exact_det3(Workspace& w);             // sign ⟨g0, g1 × g2⟩
int exact_dcc(Workspace& w);              // sign ⟨g0 × g1, g2 × g3⟩
bool exact_parallel(Workspace& w);        // (g0 × g1) × (g2 × g3) = 0
bool exact_same_direction(Workspace& w);  // parallel and ⟨g0 × g1, g2 × g3⟩ > 0
int exact_dot(Workspace& w);              // sign ⟨g0, g1⟩

}  // namespace minksum::detail
