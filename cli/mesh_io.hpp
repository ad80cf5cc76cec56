// The minksum command line: meshes in and out, through files, standard input
// and standard output ('-'), in the format the name tells or --format says.
#pragma once

#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <iosfwd>
#include <optional>
#include <string>

#include "common.hpp"

namespace minksum::cli {

// --format F: the format of every mesh whose name does not tell it ('-', a
// file without a known extension).  A name with a known extension keeps its
// own format.
inline const OptionSpec kFormatOption{"--format", "", true};
// The value of --format (nullopt when absent); UsageError for an unknown one.
std::optional<Format> format_option(const Args& a);
// "off|obj|ply|stl|wrl", from io's table of formats.
std::string format_choices();

// An operand: '-' is standard input (read whole, once per command) in
// `format`; anything else as load_polytope (operand.hpp), `format` applying
// to a file whose name has no known extension.  Through load_operand
// (common.hpp), which adds the --hull hint.
ConvexPolytope load_operand_from(const std::string& spec, bool hull, LoadPhases* phases,
                                 std::optional<Format> format);
// Claim standard input for `what` (an operand, a trajectory): UsageError
// when something else already did.
void claim_stdin(const std::string& what);

// Where a mesh is written: a file, or standard output for "-".
struct MeshOutput {
  std::string path;  // "-": standard output
  Format format = Format::off;
  WriteOptions options;
  bool to_stdout() const { return path == "-"; }
  // Where the command's own report goes: stderr when the mesh takes stdout.
  std::ostream& report_stream() const;
};
// -o/--output with --exact, --binary and --format, checked before anything is
// computed: nullopt without -o; UsageError for a format that cannot be told
// ('-' without --format, an unknown extension) or that cannot hold exact
// rationals.
std::optional<MeshOutput> output_option(const Args& a);

// Write p (io's write_polytope: it always reads back as a valid polytope);
// when coordinates had to be rounded, one note on stderr says how far they
// moved.  Coordinates the format cannot hold at all (overflow, a solid
// collapsing when rounded) and failed writes: OutputError (exit 1), one line
// naming the fix.  `written`, when given, receives the polytope written (p,
// or what rounding made of it).
RoundingReport write_mesh_output(const MeshOutput& out, const ConvexPolytope& p, ConvexPolytope* written = nullptr);
// `m` written as it is (no rounding, no validation) to the output, standard
// output included, with its write errors checked (OutputError); the
// writers' own errors (InputError, UnrepresentableError) are the caller's.
void write_mesh_as_is(const MeshOutput& out, const Mesh& m);
// The note write_mesh_output prints on stderr when coordinates of `name`
// were rounded (nothing otherwise); `floats`: binary STL, `exact_format`: the
// format could have held them exactly (with --exact).
void print_rounding_note(const std::string& name, const RoundingReport& r, bool floats, bool exact_format);
// The report as JSON: null when nothing was rounded, else {"coordinates": N,
// "max_displacement": D, "split": S, "hull": B, "merged": M, "dropped": K}.
std::string rounding_json(const RoundingReport& r);
// ", \"output\": OUT, \"rounding\": R}" closing a sum's JSON object: the
// output's name ("-" for standard output) or null, and rounding_json(r).
std::string output_json_tail(const std::optional<MeshOutput>& output, const RoundingReport& r);

}  // namespace minksum::cli
