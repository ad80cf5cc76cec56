// minksum — reading and writing polytopes (one source file per format in src/io/).
//
// Formats, chosen by file extension (case-insensitive):
//   .off  OFF (also COFF/NOFF/STOFF headers, counts on the magic line, '#'
//         comments; integers of any length and p/q tokens read exactly;
//         decimal tokens mean the nearest double; trailing face colours
//         ignored)
//   .obj  Wavefront OBJ (v and f; vt/vn/vp/g/o/s/usemtl/mtllib/l ignored;
//         i, i/j, i//k, i/j/k face tokens; negative indices; "v x y z w"
//         divides by w exactly, w = 0 is an error; free-form geometry refused)
//   .ply  PLY 1.0: ascii, binary_little_endian, binary_big_endian; vertex
//         x y z of any scalar type (binary floats taken exactly); face list
//         "vertex_indices" or "vertex_index"; other properties and elements
//         skipped
//   .stl  STL: ascii and binary (detected by content: a file of exactly
//         84 + 50 * count bytes is binary even if it begins with "solid");
//         exactly equal vertices are welded; normals ignored
//   .wrl  VRML 2.0, one IndexedFaceSet per file (Coordinate point [...] or
//         the extended ExactCoordinate { ratPoint [ p/q p/q p/q, ... ] } node
//         of Fogel and Halperin, one token per coordinate; coordIndex with -1
//         separators).  Transforms are not applied: an IndexedFaceSet under a
//         Transform with a non-identity translation, rotation or scale is
//         rejected with an InputError
//
// Readers return a raw Mesh (no topology checks: that is
// ConvexPolytope::from_mesh's job; a mesh with no faces is a valid point
// cloud) and throw InputError(FILE, PLACE, PROBLEM) on any malformed input:
// empty file, bad magic, NaN or Inf, counts that lie or are absurd (a header
// announcing more elements than the file's size can hold is rejected before
// anything is allocated), indices out of range, faces with fewer than 3
// vertices, truncated data, trailing garbage.  PLACE is "line N" (1-based)
// for text, "byte N", "vertex N", "face N", "triangle N" or "header" for
// binary data.  Face and vertex numbers in messages follow the file format's
// own indexing: from 0 in OFF, PLY, STL and VRML, from 1 in OBJ.
//
// Writers print each coordinate as the shortest text that reads back to the
// same double (a coordinate that is not a double, e.g. 1/3, is rounded to the
// nearest one) or, with exact = true, as exact rationals (integers or p/q).
// OFF, OBJ and VRML carry exact rationals natively (VRML through
// ExactCoordinate); PLY and STL are written with doubles only (exact is
// refused with a UsageError for them), and binary STL with 32-bit floats
// (each coordinate rounded to the nearest float).  A coordinate beyond the
// double (binary STL: float) range is refused with a UsageError rather than
// written as infinity.  STL is triangles only: polygons are fan-triangulated.
// write_mesh(path, ...) writes to a temporary file in the same directory and
// renames it over `path`, so a failed write never leaves a half-written file.
// An unknown extension is a UsageError, for reading and for writing.
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

// Write atomically (temporary file + rename).  Requests the format cannot
// honour (exact PLY/STL, a face index out of range, a coordinate beyond the
// double range when writing doubles) throw UsageError; the first two are
// detected before the file system is touched.
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});
// Write a polytope: the same file as write_mesh(path, p.to_mesh(), options),
// without building the intermediate mesh where the format allows (OFF).
void write_polytope(const std::string& path, const ConvexPolytope& p, const WriteOptions& options = {});
// Write to a stream in the given format.
void write_mesh(std::ostream& out, const Mesh& mesh, Format format, const WriteOptions& options = {});

// Atomic file write helper used by every writer: calls `fill` with a stream on
// a temporary file beside `path` (created with the usual permissions, or the
// existing file's), flushes, checks for errors, renames (no fsync: the
// rename is what makes the write atomic).  On any I/O
// failure the temporary is removed and InputError(path, "", reason) thrown;
// an exception thrown by `fill` itself removes the temporary and propagates
// unchanged.  Either way `path` keeps its previous content.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill);

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
ConvexPolytope load_polytope(const std::string& spec, bool hull = false, LoadPhases* phases = nullptr);

}  // namespace minksum
