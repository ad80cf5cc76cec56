// minksum sum A B when an operand is not convex (docs/nonconvex.md): the
// solids validated, then minkowski_sum_nonconvex.
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/operand.hpp>

#include <chrono>
#include <cmath>
#include <future>
#include <iostream>
#include <sstream>

#include "common.hpp"
#include "mesh_io.hpp"
#include "memory.hpp"
#include "nonconvex_sum.hpp"
#include "progress.hpp"
#include "solid.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {

// An operand's counts as the convex sum's JSON gives them: its faces as
// validated (a polygon with k corners is k - 2 triangles, k - 3 of their
// edges inside it, so edges = triangles / 2 + faces), and its kind.
std::string solid_counts_json(const Solid& s) {
  return "\"vertices\": " + std::to_string(s.vertices) +
         ", \"edges\": " + std::to_string(s.triangles.faces.size() / 2 + s.faces) +
         ", \"facets\": " + std::to_string(s.faces) + ", " + kind_json(3, s.convex ? "polytope" : "solid");
}

std::string solid_json(const std::string& name, const Solid& s, std::size_t pieces) {
  return "{\"name\": \"" + json_escape(name) + "\", " + solid_counts_json(s) +
         ", \"convex\": " + (s.convex ? "true" : "false") + ", \"pieces\": " + std::to_string(pieces) + "}";
}

}  // namespace

int write_nonconvex_catalog_solid(const std::string& spec, const MeshOutput& output) {
  const Solid s = validate_solid(catalog_mesh(spec), spec);
  const Mesh m = catalog_mesh(spec);
  Mesh written_mesh;
  write_solid_mesh(output, m, &written_mesh, nullptr, "solid");
  const std::size_t written = written_mesh.faces.size();
  output.report_stream() << printable(spec) << ": " << s.vertices << " vertices, " << s.faces
                         << " faces, non-convex, written to "
                         << (output.to_stdout() ? std::string("standard output") : printable(output.path));
  if (written != s.faces) output.report_stream() << " as " << written << " triangles";
  output.report_stream() << "\n";
  return 0;
}

AnyOperand load_any_operand_from(const std::string& spec, LoadPhases* phases, std::optional<Format> format) {
  if (spec != "-") return load_any_operand(spec, phases, format);
  if (!format) throw UsageError("reading a mesh from standard input ('-') needs --format " + format_choices());
  claim_stdin("an operand");
  return load_any_operand(std::cin, *format, "<stdin>", phases);
}

int run_nonconvex_sum(const std::vector<std::string>& names, const std::vector<AnyOperand>& operands,
                      const LoadPhases& load, const std::optional<MeshOutput>& output, bool json, Method method,
                      NonconvexMethod how, SolidOperation operation) {
  if (operands.size() != 2)
    throw UsageError("a sum with a non-convex operand takes exactly two operands A B (" +
                     std::to_string(operands.size()) + " given)");
  allow_thread_arenas();
  const auto v0 = std::chrono::steady_clock::now();
  std::vector<Solid> solids;
  for (std::size_t i = 0; i < 2; ++i) {
    if (operands[i].polytope) {
      solids.push_back(solid_of(*operands[i].polytope));
      continue;
    }
    solids.push_back(validate_operand_solid(operands[i].mesh, names[i] == "-" ? "<stdin>" : names[i]));
  }
  const double validate_seconds =
      load.validate + std::chrono::duration<double>(std::chrono::steady_clock::now() - v0).count();
  static const char* const kCommand[] = {"sum", "erode", "open", "close"};
  const char* command = kCommand[int(operation)];
  if (operation != SolidOperation::sum && !solids[1].convex)
    throw InputError(names[1] == "-" ? "<stdin>" : names[1], "", std::string("is not convex: 'minksum ") + command +
                     "' takes a convex polytope B (a solid A of any shape)");
  NonconvexSum r;
  {
    ProgressTicker ticker(std::string("minksum ") + command);
    const Method m = method == Method::automatic ? Method::walk : method;
    // The exact volume is computed below, while the file is written.
    SumOptions options = ticker.sum_options();
    options.volume = false;
    switch (operation) {
      case SolidOperation::sum: r = minkowski_sum_nonconvex(solids[0], solids[1], options, 0, m, how); break;
      case SolidOperation::erode: r = erode(solids[0], solids[1], options, 0, m); break;
      case SolidOperation::open: r = opening(solids[0], solids[1], options, 0, m); break;
      case SolidOperation::close: r = closing(solids[0], solids[1], options, 0, m); break;
    }
  }
  const bool empty = r.mesh.faces.empty();
  // Both only read r.mesh; the volume's thread is joined before r changes
  // (get() below, or the future's destructor when the write throws).
  std::future<Rational> volume =
      std::async(std::launch::async, [&r, empty] { return empty ? Rational(0) : mesh_volume(r.mesh); });
  const auto w0 = std::chrono::steady_clock::now();
  RoundedSolid rounding;
  if (output && empty) write_mesh_as_is(*output, r.mesh);  // (a file of the format with no faces)
  else if (output) write_solid_mesh(*output, r.mesh, nullptr, &rounding, r.operation);
  const double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  r.volume = volume.get();
  const MeshCounts c = mesh_counts(r.mesh);
  std::ostream& report = output ? output->report_stream() : std::cout;
  if (json) {
    report << "{\"operation\": \"" << r.operation << "\", \"empty\": " << (empty ? "true" : "false")
           << ", \"vertices\": " << c.vertices << ", \"edges\": " << c.edges << ", \"facets\": " << c.faces
           << ", \"dimension\": 3, \"kind\": \"solid\", \"method\": \"nonconvex\", \"pair_method\": \""
           << (r.pieces_from_maps ? "gaussian_map" : method_name(r.pair_method)) << "\", \"seconds\": " << json_number(r.seconds())
           << ", \"phases\": {\"read\": " << json_number(load.read) << ", \"validate\": " << json_number(validate_seconds)
           << ", \"decompose\": " << json_number(r.seconds_decompose) << ", \"pairs\": " << json_number(r.seconds_pairs)
           << ", \"union\": " << json_number(r.seconds_union) << ", \"boundary\": " << json_number(r.seconds_boundary)
           << ", \"write\": " << json_number(write_seconds) << "}, \"volume\": \"" << format_exact(r.volume)
           << "\", \"volume_double\": " << json_number(to_double(r.volume)) << ", \"nonconvex_method\": \"" << r.method
           << "\", \"swept\": " << (r.swept ? std::string("\"") + r.swept + "\"" : std::string("null"))
           << ", \"pieces\": {\"a\": " << r.pieces_a
           << ", \"b\": " << r.pieces_b << "}, \"pairs\": " << r.pairs << ", \"pair_vertices\": "
           << (r.pieces_from_maps ? std::string("null") : std::to_string(r.pair_vertices))
           << ", \"pair_facets\": " << r.pair_facets << ", \"candidate_facets\": " << r.candidate_facets
           << ", \"culled_facets\": " << r.culled_facets << ", \"union\": {\"clips\": " << r.clips
           << ", \"shells\": " << r.shells << ", \"non_manifold_edges\": " << r.non_manifold_edges
           << ", \"dropped_components\": " << r.dropped_components << "}"
           << ", \"a\": " << solid_json(names[0], solids[0], r.pieces_a)
           << ", \"b\": " << solid_json(names[1], solids[1], r.pieces_b) << ", \"operands\": [";
    for (std::size_t i = 0; i < 2; ++i)
      report << (i ? ", " : "") << "{\"name\": \"" << json_escape(names[i]) << "\", " << solid_counts_json(solids[i])
             << "}";
    report << "], \"output\": ";
    if (!output) report << "null";
    else report << "\"" << json_escape(output->to_stdout() ? "-" : output->path) << "\"";
    report << ", \"rounding\": " << solid_rounding_json(rounding) << "}\n";
  } else {
    static const char* const kFormula[][3] = {{"", " ⊕ ", ""}, {"", " ⊖ ", ""}, {"(", " ⊖ ", ") ⊕ B"}, {"(", " ⊕ ", ") ⊖ B"}};
    const auto& formula = kFormula[int(operation)];
    report << formula[0];
    for (std::size_t i = 0; i < 2; ++i)
      report << (i ? formula[1] : "") << printable(names[i]) << " (" << solids[i].vertices << " V, " << solids[i].faces
             << " F, "
             << (solids[i].convex ? std::string("convex")
                 : r.swept == "ab"[i] ? std::to_string(i ? r.pieces_b : r.pieces_a) + " triangles swept"
                                      : std::to_string(i ? r.pieces_b : r.pieces_a) + " convex pieces")
             << ")";
    report << formula[2];
    if (empty)
      report << "\n  = empty: B fits nowhere inside A" << (operation == SolidOperation::open ? " (A ⊖ B is empty)" : "");
    else
      report << "\n  = " << c.vertices << " vertices, " << c.edges << " edges, " << c.faces << " faces"
             << (r.shells > 1 ? ", " + std::to_string(r.shells) + " shells" : std::string())
             << (r.non_manifold_edges ? ", " + std::to_string(r.non_manifold_edges) + " non-manifold edges"
                                      : std::string());
    report << "\n  " << (operation == SolidOperation::sum ? "non-convex sum" : r.operation)
           << " (" << r.method << "): " << r.pairs << " convex pieces, "
           << (r.culled_facets ? std::to_string(r.culled_facets) + " of " + std::to_string(r.pair_facets) +
                                     " facets culled, "
                               : std::string())
           << r.clips << " facet clips, "
           << format_double(r.seconds()) << " s\n";
    if (output) report << "  written to " << (output->to_stdout() ? std::string("standard output") : printable(output->path)) << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
