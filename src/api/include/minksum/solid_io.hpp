// minksum — writing the boundary of a solid (a non-convex sum's, an
// erosion's, a Solid's faces) to a file that reads back as a valid solid:
// the one writer of `minksum sum`, `erode`, `open`, `close`, `gen` and
// Python's Solid.save.
#pragma once

#include <minksum/io.hpp>
#include <minksum/nonconvex.hpp>

#include <string>

namespace minksum {

// The mesh that holds `boundary` in the numbers of `format`: the boundary
// itself with options.exact (exact rationals); else round_solid's valid
// solid (docs/nonconvex.md, "Output": coordinates rounded to doubles, floats
// for binary STL, the surface cut apart where it touches itself, checked
// exactly), or the boundary as it is when nothing had to move.  A convex
// solid whose rounding round_solid cannot repair (thin faces of an erosion
// of a convex part folding over at float spacing) is written as a convex
// polytope is: the exact convex hull of its rounded vertices (within the
// largest displacement of the exact solid).  STL holds
// triangles only: the faces are then cut exactly (triangulate).  `rounded`,
// when given, receives what rounding did (its mesh left empty).  `name`
// names the output in errors.  Throws RoundingError when the solid cannot be
// represented, InputError for a face that is not a simple polygon.
Mesh writable_solid(const Mesh& boundary, Format format, const WriteOptions& options, const std::string& name,
                    RoundedSolid* rounded = nullptr);

// writable_solid written atomically to `path` (its format from the
// extension): errors as writable_solid's and write_mesh's (UsageError for an
// unknown extension or a request the format cannot honour, InputError when
// the file system refuses).  An empty boundary (an erosion that left
// nothing) is a file of the format with no faces.  Returns what rounding did.
RoundedSolid write_solid(const std::string& path, const Mesh& boundary, const WriteOptions& options = {});

}  // namespace minksum
