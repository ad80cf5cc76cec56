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

// An operand that may be non-convex or lower-dimensional, for sums: the
// polytope when the mesh (file or catalog_mesh) is a convex polytope; the
// point, segment or polygon (docs/sweeps.md: a catalog name, a file holding
// one face) as `flat`; else the mesh as read, not yet validated
// (validate_solid in <minksum/nonconvex.hpp> does that, and says what is
// wrong with it).  Errors as load_polytope's, except that a mesh that is not
// a convex polytope is no error here.
struct AnyOperand {
  std::optional<ConvexPolytope> polytope;
  std::optional<ConvexSet> flat;  // a point, a segment or a polygon
  Mesh mesh;                      // when there is neither
};
AnyOperand load_any_operand(const std::string& spec, LoadPhases* phases = nullptr,
                            std::optional<Format> format = std::nullopt);
AnyOperand load_any_operand(std::istream& in, Format format, const std::string& name, LoadPhases* phases = nullptr);

// The error for a name that is neither an existing file nor a catalog spec:
// InputError "no such file" when it has a known extension, else UsageError
// with the closest catalog name.
[[noreturn]] void unknown_operand(const std::string& spec, std::optional<Format> format);

}  // namespace minksum
