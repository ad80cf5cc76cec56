// The minksum command line: convex polytopes or closed solids (solid.hpp).
#include "solid.hpp"

#include <chrono>
#include <iostream>
#include <iterator>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "common.hpp"
#include "memory.hpp"
#include "text.hpp"

namespace minksum::cli {

SolidOperand load_solid_operand(const std::string& spec, bool hull, LoadPhases* phases,
                                std::optional<Format> format) {
  SolidOperand o;
  if (hull) {
    o.polytope = load_operand(spec, true, phases, format);
    return o;
  }
  // Standard input is read once, kept, so that a point, segment or polygon
  // can be refused below exactly as load_operand refuses it.
  std::string input;
  if (spec == "-") {
    if (!format) throw UsageError("reading a mesh from standard input ('-') needs --format " + format_choices());
    claim_stdin("an operand");
    input.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  }
  const std::string name = spec == "-" ? "<stdin>" : spec;
  LoadPhases load;
  auto loaded = [&] {
    const OperandOptions options{false, format, [] { allow_thread_arenas(); }};
    if (spec != "-") return Operand::load(spec, options, &load);
    std::istringstream in(input);
    return Operand::load(in, *format, name, options, &load);
  }();
  if (loaded.set()) {  // not a solid: load_operand's refusal
    if (spec != "-") {
      o.polytope = load_operand(spec, false, &load, format);
    } else {
      std::istringstream in(input);
      try {
        o.polytope = load_polytope(in, *format, name, false, &load);
      } catch (const NotConvexError& e) {
        throw InputError(e.file(), e.place(), e.problem() + "; --hull takes the convex hull of its points instead");
      }
    }
  } else if (loaded.polytope()) {
    o.polytope = std::get<ConvexPolytope>(std::move(loaded).release());
  } else {
    o.solid = std::get<Solid>(std::move(loaded).release());
  }
  if (phases) *phases = load;
  return o;
}

std::string solid_rounding_json(const RoundedSolid& r) {
  if (!r.rounded_coordinates && r.max_displacement == 0) return "null";
  return "{\"coordinates\": " + std::to_string(r.rounded_coordinates) +
         ", \"max_displacement\": " + json_number(r.max_displacement) + ", \"grid\": " + json_number(r.grid) + "}";
}

MeshCounts mesh_counts(const Mesh& m) {
  MeshCounts c;
  c.vertices = m.points.size();
  c.faces = m.faces.size();
  std::size_t corners = 0;
  for (const auto& f : m.faces) corners += f.size();
  c.edges = corners / 2;  // every edge has as many faces on each side
  return c;
}

std::size_t write_solid_mesh(const MeshOutput& out, const Mesh& mesh, Mesh* written_out, RoundedSolid* rounded_out,
                             const std::string& what) {
  const std::string name = out.to_stdout() ? "<stdout>" : out.path;
  const bool floats = out.format == Format::stl && out.options.binary;
  const std::string exact_hint = "; use --exact with " + extension_list(", ", " or ", true) + " to write exact rationals";
  // Without --exact: coordinates that are not doubles (binary STL: floats)
  // rounded, the surface kept a valid solid (writable_solid, docs/nonconvex.md).
  RoundedSolid rounded;
  Mesh written;
  try {
    written = writable_solid(mesh, out.format, out.options, name, &rounded);
  } catch (const RoundingError& e) {
    throw OutputError("cannot write " + name + ": " + e.what() + exact_hint);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
  const bool changed = rounded.rounded_coordinates > 0 || rounded.max_displacement > 0;
  try {
    write_mesh_as_is(out, written);
  } catch (const UnrepresentableError& e) {
    throw OutputError("cannot write " + name + ": " + e.problem() + exact_hint);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
  if (rounded.rounded_coordinates) {
    std::cerr << "minksum: note: " << printable(name) << ": " << rounded.rounded_coordinates << " coordinates are not "
              << (floats ? "32-bit floats" : "doubles") << ", written rounded (largest displacement "
              << format_double(rounded.max_displacement);
    if (rounded.grid > 0) std::cerr << ", some points snapped to multiples of " << format_double(rounded.grid);
    std::cerr << "), the faces as triangles; the written surface is a closed solid without self-intersection "
                 "(checked exactly); --exact writes the exact "
              << what << "\n";
  } else if (changed) {
    std::cerr << "minksum: note: " << printable(name) << ": the " << what
              << " touches itself, and its parts were moved apart "
              << "to write it as a valid solid (largest displacement " << format_double(rounded.max_displacement);
    std::cerr << "), the faces as triangles; the written surface is a closed solid without self-intersection "
                 "(checked exactly); --exact writes the exact "
              << what << "\n";
  }
  const std::size_t count = rounded.rounded_coordinates;
  if (written_out) *written_out = std::move(written);
  if (rounded_out) *rounded_out = std::move(rounded);
  return count;
}

}  // namespace minksum::cli
