// minksum — reading and writing polytopes (one source file per format in src/io/).
//
// Formats, chosen by file extension (case-insensitive):
//   .off  OFF (also COFF/NOFF headers; integers of any length and p/q tokens
//         read exactly; decimal tokens mean the nearest double)
//   .obj  Wavefront OBJ (v and f; vt/vn/g/o/s/usemtl ignored; v/vt/vn face
//         tokens; negative indices)
//   .ply  PLY: ascii, binary_little_endian, binary_big_endian; vertex x y z of
//         any numeric type; face list "vertex_indices" or "vertex_index"
//   .stl  STL: ascii and binary (detected by content); exactly equal
//         vertices are welded
//   .wrl  VRML 2.0 IndexedFaceSet (Coordinate point [...] or the extended
//         ExactCoordinate { ratPoint [ p/q p/q p/q, ... ] } node, coordIndex
//         with -1 separators)
//
// Readers return a raw Mesh and throw InputError("FILE", "line N" / "byte N"
// / "header" ..., "what is wrong") on any malformed input: bad magic, NaN or
// Inf, counts that lie or are absurd (a header announcing more elements than
// the file's size can hold is rejected before anything is allocated), indices
// out of range, truncated data, trailing garbage.
//
// Writers print each coordinate as the shortest text that reads back to the
// same double ("%.17g" style) or, with exact = true, as exact rationals
// (integers or p/q).  OFF, OBJ and VRML carry exact rationals natively (VRML
// through ExactCoordinate); PLY and STL are written with doubles only (exact
// is refused with a UsageError for them).  write_mesh(path, ...) writes to a
// temporary file in the same directory and renames it over `path`, so a
// failed write never leaves a half-written file.
#pragma once

#include <minksum/polytope.hpp>

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

namespace minksum {

enum class Format { off, obj, ply, stl, wrl };

// Format from a path's extension; nullopt if the extension is not known.
std::optional<Format> format_from_path(const std::string& path);
const char* format_name(Format f);

struct WriteOptions {
  bool exact = false;   // exact rationals instead of doubles
  bool binary = false;  // PLY / STL: binary instead of ascii
};

// Read a mesh from a file (format from the extension).
Mesh read_mesh(const std::string& path);
// Read a mesh from a stream; `name` is used in error messages.
Mesh read_mesh(std::istream& in, Format format, const std::string& name);

// Write atomically (temporary file + rename).
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});
// Write to a stream in the given format.
void write_mesh(std::ostream& out, const Mesh& mesh, Format format, const WriteOptions& options = {});

// Atomic file write helper used by every writer: calls `fill` with a stream on
// a temporary file beside `path`, flushes, checks for errors, renames.  On any
// failure the temporary is removed and InputError(path, "", reason) thrown.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill);

// Resolve an operand as the CLI does: a path to an existing file is read and
// validated; otherwise a catalog name (see catalog.hpp).  With `hull` the
// file's points are taken as a point cloud and their exact hull returned
// (faces, if any, ignored).  Throws InputError for bad data, UsageError for a
// name that is neither an existing file nor a catalog name.
ConvexPolytope load_polytope(const std::string& spec, bool hull = false);

}  // namespace minksum
