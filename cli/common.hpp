// The minksum command line: pieces shared by the command files.
#pragma once

#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/operand.hpp>
#include <minksum/polytope.hpp>

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "text.hpp"

namespace minksum::cli {

// An option a command accepts: "--name" (and an optional short alias such as
// "-o"), with or without a value ("--name VALUE" or "--name=VALUE").
struct OptionSpec {
  std::string name;
  std::string alias = {};
  bool takes_value = false;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;  // by long name
  std::set<std::string> flags;                // by long name
  bool help = false;

  bool flag(const std::string& name) const { return flags.count(name) != 0; }
  std::optional<std::string> value(const std::string& name) const {
    auto it = values.find(name);
    if (it == values.end()) return std::nullopt;
    return it->second;
  }
  std::string value_or(const std::string& name, const std::string& fallback) const {
    return value(name).value_or(fallback);
  }
};

// Parse a command's arguments against its options; -h/--help always
// accepted.  Throws UsageError for an unknown option or a missing value.
// A token starting with '-' followed by a digit or '.' is a positional
// (negative numbers).
Args parse_args(const std::vector<std::string>& argv, const std::string& command,
                const std::vector<OptionSpec>& options);

std::string json_escape(const std::string& s);
// "\"vertices\": V, \"edges\": E, \"facets\": F"
std::string counts_json(const ConvexPolytope& p);
// "\"dimension\": D, \"kind\": \"K\"": what a result or an operand is, in
// every command's --json (docs/json.md): K is point, segment, polygon,
// polytope (D = 0, 1, 2, 3) or solid (a closed solid that is not convex, D = 3).
std::string kind_json(int dimension, const char* kind);
// counts_json(p) and kind_json(3, "polytope").
std::string polytope_json(const ConvexPolytope& p);

// A failed write is not bad input: the command exits with status 1.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Check that `path` has a known format (and can hold exact rationals when
// `exact`), before any long computation.  Throws UsageError.
// load_polytope for a command that has --hull: a closed surface that is not
// exactly convex (NotConvexError: what a mesh rounded by another tool gives)
// is refused with a hint that --hull accepts it.
// `format` (--format) applies to '-' (standard input) and to files whose
// names have no known extension (mesh_io.hpp).
ConvexPolytope load_operand(const std::string& spec, bool hull, LoadPhases* phases,
                            std::optional<Format> format = std::nullopt);

// A help text with its table-driven parts filled in from the tables of
// formats (io.hpp) and methods (minkowski.hpp): {formats} ".off .obj .ply .stl
// .wrl", {exact_formats} ".off, .obj and .wrl", {binary_formats} ".ply / .stl",
// {format_names} "off|obj|ply|stl|wrl",
// {methods} "auto (default), walk, ...", {method_summaries} one paragraph per
// method ("walk: ...") wrapped to 79 columns under a 21-column option column.
std::string expand_help(std::string_view text);

}  // namespace minksum::cli

namespace minksum::cli {

// A double as a JSON number; JSON has no infinity or NaN, so a non-finite
// value (a double that overflowed: the exact value is beyond the double
// range) is `null`, and the command prints the exact value beside it as a
// string field.  Every double in minksum's JSON goes through it.
std::string json_number(double x);

// Flush standard output and throw OutputError ("cannot write to standard
// output: REASON") if any write to it failed.  Called after each line of
// streamed output (trajectories) and once at the end of main.
void check_stdout();

}  // namespace minksum::cli
