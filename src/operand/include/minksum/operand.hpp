// minksum — operands as the command line names them: a file (read by
// <minksum/io.hpp>) or a catalog name (built by <minksum/catalog.hpp>).  The
// one place that decides which a name is.
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/io.hpp>
#include <minksum/polytope.hpp>

#include <iosfwd>
#include <optional>

#include <string>

namespace minksum {

// Resolve an operand as the CLI does: a path to an existing file is read and
// validated; otherwise a catalog name (see catalog.hpp).  An existing file
// whose name has no known extension but is a catalog spec (a stray file
// called "cube") does not shadow the catalog.  With `hull` the file's (or
// catalog polytope's) points are taken as a point cloud and their exact hull
// returned (faces, if any, ignored).  Throws InputError for bad data, a
// directory, an unreadable file, or a missing file named with a known
// extension ("no such file"); UsageError for a name that is neither a file
// nor a catalog name.
// `phases`, when given, receives the seconds spent reading the file (or
// building the catalog polytope) and validating it (or taking its hull).
struct LoadPhases {
  double read = 0, validate = 0;
};
// `format`, when given, is the format of an existing file whose name has no
// known extension (a name with one keeps its own format).
ConvexPolytope load_polytope(const std::string& spec, bool hull = false, LoadPhases* phases = nullptr,
                             std::optional<Format> format = std::nullopt);
// An operand read whole from a stream (standard input) in the given format,
// validated (or its hull taken) as above; `name` names it in error messages.
ConvexPolytope load_polytope(std::istream& in, Format format, const std::string& name, bool hull = false,
                             LoadPhases* phases = nullptr);

// The same, for commands that also take lower-dimensional operands
// (docs/sweeps.md): a catalog point, segment or polygon; a file holding one
// face (a flat polygon); with `hull`, the hull of the points in whatever
// dimension they span (0 to 3).  Everything else as load_polytope.
ConvexSet load_convex_set(const std::string& spec, bool hull = false, LoadPhases* phases = nullptr,
                          std::optional<Format> format = std::nullopt);
ConvexSet load_convex_set(std::istream& in, Format format, const std::string& name, bool hull = false,
                          LoadPhases* phases = nullptr);

}  // namespace minksum
