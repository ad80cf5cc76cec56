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
//         rejected with an InputError.  A scene of Fogel and Halperin's
//         ExactPolyhedron / CubicalGaussianMap nodes (<minksum/scene.hpp>)
//         reads as its one polytope; a scene of several is an InputError
//
// A UTF-8 byte-order mark at the start of a file is skipped in every text
// format (OFF, OBJ, PLY's header, ascii STL, VRML).
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
// write_polytope goes further: what it writes always reads back as a valid
// convex polytope (see writable_polytope below).
// OFF, OBJ and VRML carry exact rationals natively (VRML through
// ExactCoordinate); PLY and STL are written with doubles only (exact is
// refused with a UsageError for them), and binary STL with 32-bit floats
// (each coordinate rounded to the nearest float).  A coordinate beyond the
// double (binary STL: float) range is refused with an UnrepresentableError (a
// UsageError) rather than written as infinity.  STL is triangles only: polygons are fan-triangulated.
// write_mesh(path, ...) writes to a temporary file in the same directory and
// renames it over `path`, so a failed write never leaves a half-written file.
// An unknown extension is a UsageError, for reading and for writing.
#pragma once

#include <minksum/error.hpp>
#include <minksum/polytope.hpp>

#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace minksum {

enum class Format { off, obj, ply, stl, wrl };

// The formats, one row each: every name, extension and capability that
// parsing, help texts and error messages mention comes from this table.
struct FormatInfo {
  Format format;
  const char* extension;  // without the dot: "off"
  const char* name;       // "OFF"
  bool exact;             // can hold exact rationals (WriteOptions::exact)
  bool binary;            // has a binary encoding (WriteOptions::binary)
};
// Every format, in the order help texts list them.
std::span<const FormatInfo> formats();
const FormatInfo& format_info(Format f);

// Format from a path's extension (case-insensitive); nullopt if the
// extension is not known.
std::optional<Format> format_from_path(const std::string& path);
const char* format_name(Format f);
// The extensions (with their dots) of the formats that have every capability
// asked for, joined: extension_list(", ", " or ") = ".off, .obj, .ply, .stl
// or .wrl"; extension_list(", ", " or ", true) = ".off, .obj or .wrl".
std::string extension_list(std::string_view separator, std::string_view last_separator, bool exact = false,
                           bool binary = false);

struct WriteOptions {
  bool exact = false;   // exact rationals instead of doubles
  bool binary = false;  // PLY / STL: binary instead of ascii
};

// Coordinates that cannot be written in the format asked for: a coordinate
// beyond its range (overflow), or a solid whose vertices, rounded to the
// format's numbers, no longer span a solid (underflow to zero, denormals
// collapsing).  A UsageError (the request cannot be honoured), detected
// before anything is written.  problem() says what happened without a
// remedy; what() adds one (exact rationals in .off, .obj or .wrl; for binary
// STL, ascii STL when the doubles would do).
class UnrepresentableError : public UsageError {
 public:
  UnrepresentableError(const std::string& problem, bool floats_only);
  const std::string& problem() const { return problem_; }
  // True when only the 32-bit floats of binary STL are too small: every
  // double-based format (ascii STL included) could hold the solid.
  bool floats_only() const { return floats_only_; }

 private:
  std::string problem_;
  bool floats_only_;
};

// What writing a polytope did to its coordinates (writable_polytope).
struct RoundingReport {
  std::size_t coordinates = 0;  // coordinates not representable in the format, rounded
  double max_displacement = 0;  // largest distance from an exact vertex to its rounded point (about)
  std::size_t split = 0;        // facets no longer planar, split along convex folds
  bool hull = false;            // splitting did not make a convex polytope: the hull was taken
  std::size_t merged = 0;       // vertices rounded onto the point of another vertex
  std::size_t dropped = 0;      // other rounded points that are not vertices of what is written
  bool rounded() const { return coordinates != 0; }
};

// The polytope that `format` (with `options`) writes exactly, so that the
// file reads back as a valid closed convex polytope:
//   * p itself when the format holds every coordinate (exact rationals with
//     options.exact; doubles; the 32-bit floats of binary STL);
//   * else p with each vertex rounded to the nearest representable point,
//     each facet whose rounded points are no longer coplanar split into the
//     facets of the upper side of their own exact hull (a quadrilateral along
//     the diagonal that folds outwards), when the result is exactly a convex
//     polytope (validated as a file being read; coplanar facets merged);
//   * else the exact convex hull of the rounded points.
// Every rounded point lies in the result and every vertex of the result is a
// rounded point, so the result is within max_displacement of p (Hausdorff
// distance).  Throws UnrepresentableError when a coordinate is beyond the
// format's range or the rounded points no longer span a solid.  `report`,
// when given, says what was rounded.
ConvexPolytope writable_polytope(const ConvexPolytope& p, Format format, const WriteOptions& options,
                                 RoundingReport* report = nullptr);

// The format of an output path, checked against the options before anything
// is computed or written: UsageError for an unknown extension or for exact
// coordinates in a format that cannot hold them.  `format`, when given, is
// the format of a path whose extension is not a known one.
Format output_format(const std::string& path, const WriteOptions& options,
                     std::optional<Format> format = std::nullopt);

// Read a mesh from a file (format from the extension).
Mesh read_mesh(const std::string& path);
// Read a mesh from a stream; `name` is used in error messages.
Mesh read_mesh(std::istream& in, Format format, const std::string& name);
// Read a file in the given format, whatever its name says.
Mesh read_mesh(const std::string& path, Format format);

// Write atomically (temporary file + rename).  Requests the format cannot
// honour (exact PLY/STL, a face index out of range, a coordinate beyond the
// double range when writing doubles) throw UsageError; the first two are
// detected before the file system is touched.
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});
// Write a polytope: writable_polytope(p, ...) written as write_mesh(path,
// q.to_mesh(), options) would, without building the intermediate mesh where
// the format allows (OFF); the file always reads back as a valid polytope
// (exactly p when nothing was rounded).  `format` overrides the path's
// extension.  `report`, when given, says what was rounded.
void write_polytope(const std::string& path, const ConvexPolytope& p, const WriteOptions& options = {},
                    RoundingReport* report = nullptr, std::optional<Format> format = std::nullopt);
// The same to a stream (standard output): nothing is written when
// writable_polytope throws.
void write_polytope(std::ostream& out, const ConvexPolytope& p, Format format, const WriteOptions& options = {},
                    RoundingReport* report = nullptr);
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

}  // namespace minksum
