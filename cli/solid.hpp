// The minksum command line: operands that are convex polytopes or closed
// solids (docs/nonconvex.md), for the commands that take either: stats,
// convert and view (and the non-convex path of sum).
#pragma once

#include <minksum/nonconvex.hpp>
#include <minksum/operand.hpp>
#include <minksum/solid_io.hpp>
#include <minksum/sum.hpp>
#include <minksum/polytope.hpp>

#include <cstddef>
#include <optional>
#include <string>

#include "mesh_io.hpp"

namespace minksum::cli {

// An operand of stats, convert and view: without `hull`, the convex
// polytope when the mesh is one (exactly as load_operand gives it), else
// the validated closed solid; with `hull`, the convex hull of its points
// (load_operand).  A point, segment or polygon, or a mesh that is neither
// a convex polytope nor a valid solid, is refused (InputError) as
// load_operand refuses it.  '-' is standard input in `format`.
struct SolidOperand {
  std::optional<ConvexPolytope> polytope;
  std::optional<Solid> solid;  // when the operand is not convex
};
SolidOperand load_solid_operand(const std::string& spec, bool hull, LoadPhases* phases,
                                std::optional<Format> format);

// Writes a solid's boundary `mesh` (exact, or rounded to a valid solid by
// round_solid, docs/nonconvex.md) to `out`, with a note on stderr when it was
// rounded (`what` names it there: "sum", "solid"); OutputError naming
// --exact when it cannot be represented.  Returns how many coordinates were
// rounded; `written`, when given, receives the mesh written (triangles where
// the format or the rounding needs them), `rounded`, the rounding itself.
std::size_t write_solid_mesh(const MeshOutput& out, const Mesh& mesh, Mesh* written = nullptr,
                             RoundedSolid* rounded = nullptr, const std::string& what = "sum");

// The rounding of a solid written, as "rounding" in --json: null when
// nothing moved, else {"coordinates": N, "max_displacement": D, "grid": G}
// (G: 0, or the coarsest grid points were snapped to).
std::string solid_rounding_json(const RoundedSolid& r);

// Vertices, edges and faces of a closed polygon mesh.
struct MeshCounts {
  std::size_t vertices = 0, edges = 0, faces = 0;
};
MeshCounts mesh_counts(const Mesh& m);

}  // namespace minksum::cli
