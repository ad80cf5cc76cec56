// The minksum command line: meshes through files, standard input and output.
#include "mesh_io.hpp"

#include <cctype>
#include <iostream>
#include <sstream>

namespace minksum::cli {

namespace {
std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
// What standard input was claimed for ("" while unclaimed).
std::string stdin_owner;
}  // namespace

std::string format_choices() {
  std::string s;
  for (const FormatInfo& f : formats()) s += (s.empty() ? "" : "|") + std::string(f.extension);
  return s;
}

std::optional<Format> format_option(const Args& a) {
  const auto v = a.value("--format");
  if (!v) return std::nullopt;
  for (const FormatInfo& f : formats())
    if (lower(*v) == f.extension) return f.format;
  throw UsageError("unknown format '" + *v + "' for --format (" + format_choices() + ")");
}

void claim_stdin(const std::string& what) {
  if (!stdin_owner.empty())
    throw UsageError("standard input ('-') can be read only once: it is already " + stdin_owner);
  stdin_owner = what;
}

ConvexPolytope load_operand_from(const std::string& spec, bool hull, LoadPhases* phases,
                                 std::optional<Format> format) {
  if (spec != "-") return load_polytope(spec, hull, phases, format);
  if (!format)
    throw UsageError("reading a mesh from standard input ('-') needs --format " + format_choices());
  claim_stdin("an operand");
  return load_polytope(std::cin, *format, "<stdin>", hull, phases);
}

std::ostream& MeshOutput::report_stream() const { return to_stdout() ? std::cerr : std::cout; }

std::optional<MeshOutput> output_option(const Args& a) {
  const auto path = a.value("--output");
  if (!path) return std::nullopt;
  if (path->empty()) throw UsageError("--output needs a file name (or '-' for standard output)");
  MeshOutput out;
  out.path = *path;
  out.options.exact = a.flag("--exact");
  out.options.binary = a.flag("--binary");
  const auto format = format_option(a);
  if (out.to_stdout() && !format)
    throw UsageError("writing a mesh to standard output (-o -) needs --format " + format_choices());
  out.format = output_format(out.to_stdout() ? std::string() : out.path, out.options, format);
  return out;
}

std::string rounding_json(const RoundingReport& r) {
  if (!r.rounded()) return "null";
  std::ostringstream o;
  o << "{\"coordinates\": " << r.coordinates << ", \"max_displacement\": " << json_number(r.max_displacement)
    << ", \"split\": " << r.split << ", \"hull\": " << (r.hull ? "true" : "false") << ", \"merged\": " << r.merged
    << ", \"dropped\": " << r.dropped << "}";
  return o.str();
}

std::string output_json_tail(const std::optional<MeshOutput>& output, const RoundingReport& r) {
  std::string o = ", \"output\": ";
  if (!output) o += "null";
  else o += "\"" + json_escape(output->to_stdout() ? "-" : output->path) + "\"";
  return o + ", \"rounding\": " + rounding_json(r) + "}";
}

void write_mesh_as_is(const MeshOutput& out, const Mesh& m) {
  if (out.to_stdout()) {
    write_mesh(std::cout, m, out.format, out.options);
    std::cout.flush();
    if (!std::cout) throw OutputError("cannot write the mesh to standard output: write error");
  } else {
    write_mesh(out.path, m, out.options);
  }
}

RoundingReport write_mesh_output(const MeshOutput& out, const ConvexPolytope& p, ConvexPolytope* written) {
  const std::string name = out.to_stdout() ? "<stdout>" : out.path;
  const bool floats = out.format == Format::stl && out.options.binary;
  const bool exact_format = format_info(out.format).exact;
  const std::string exact_formats = extension_list(", ", " or ", true);
  RoundingReport r;
  try {
    // Rounded once here, so the caller can have what was written; the
    // writer then finds every coordinate representable.
    const ConvexPolytope q = writable_polytope(p, out.format, out.options, &r);
    if (out.to_stdout()) {
      write_polytope(std::cout, q, out.format, out.options);
      std::cout.flush();
      if (!std::cout) throw OutputError("cannot write the mesh to standard output: write error");
    } else {
      write_polytope(out.path, q, out.options, nullptr, out.format);
    }
    if (written) *written = q;
  } catch (const UnrepresentableError& e) {
    std::string fix = e.floats_only() ? "write ascii STL (without --binary) or another format"
                      : exact_format  ? "use --exact to write exact rationals"
                                      : "use --exact with " + exact_formats + " to write exact rationals";
    throw OutputError("cannot write " + name + ": " + e.problem() + "; " + fix);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
  print_rounding_note(name, r, floats, exact_format);
  return r;
}

void print_rounding_note(const std::string& name, const RoundingReport& r, bool floats, bool exact_format) {
  const std::string exact_formats = extension_list(", ", " or ", true);
  if (r.rounded()) {
    std::ostringstream note;
    note << "minksum: note: " << name << ": " << r.coordinates << " coordinates are not "
         << (floats ? "32-bit floats" : "doubles") << ", written rounded to the nearest ones"
         << (r.hull ? " as the exact convex hull of the rounded vertices (their facets were no longer exactly "
                      "planar and convex)"
                    : "");
    if (r.split) note << " (" << r.split << " facets no longer planar, split along convex folds)";
    note
         << "; largest vertex displacement " << format_double(r.max_displacement);
    if (r.merged) note << ", " << r.merged << " vertices merged";
    if (r.dropped) note << ", " << r.dropped << " vertices dropped";
    if (floats)
      note << "; ascii STL keeps every double, --exact with " << exact_formats << " every rational";
    else if (exact_format)
      note << "; --exact keeps them exact";
    else
      note << "; --exact with " << exact_formats << " keeps them exact";
    std::cerr << note.str() << "\n";
  }
}

}  // namespace minksum::cli
