// minksum sum with a non-convex operand (cli/cmd_sum_nonconvex.cpp).
#pragma once

#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/operand.hpp>

#include <optional>
#include <string>
#include <vector>

#include "mesh_io.hpp"

namespace minksum::cli {

// What run_nonconvex_sum computes: A ⊕ B, or A ⊖ B, (A ⊖ B) ⊕ B,
// (A ⊕ B) ⊖ B (minksum erode, open, close; B convex).
enum class SolidOperation { sum, erode, open, close };

// The sum of two operands, one or both not convex (or an erosion, opening or
// closing of a solid by a convex B): validates them as solids (exit 3 naming
// the problem; for erode, open and close also a B that is not convex),
// computes, writes the boundary to `output` and prints the summary or JSON.
// Returns the exit status.  `method` sums the pairs of convex pieces.
int run_nonconvex_sum(const std::vector<std::string>& names, const std::vector<AnyOperand>& operands,
                      const LoadPhases& load, const std::optional<MeshOutput>& output, bool json, Method method,
                      NonconvexMethod how = NonconvexMethod::sweep, SolidOperation operation = SolidOperation::sum);

// minksum gen for a non-convex solid of the catalog: validated, written like
// a sum's boundary, one summary line.
int write_nonconvex_catalog_solid(const std::string& spec, const MeshOutput& output);

// An operand that may be non-convex: '-' is standard input in `format`.
AnyOperand load_any_operand_from(const std::string& spec, LoadPhases* phases, std::optional<Format> format);

}  // namespace minksum::cli
