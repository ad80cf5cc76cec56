// minksum sum / erode / open / close once parsed (sum_command.hpp).
#include "sum_command.hpp"

#include <minksum/io.hpp>
#include <minksum/scene.hpp>

#include <algorithm>
#include <chrono>
#include <future>
#include <iostream>
#include <memory>
#include <sstream>

#include "common.hpp"
#include "memory.hpp"
#include "progress.hpp"
#include "scene.hpp"
#include "solid.hpp"
#include "sweep.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {

std::string counts_json(const OperandReport& o) {
  return "\"vertices\": " + std::to_string(o.vertices) + ", \"edges\": " + std::to_string(o.edges) +
         ", \"facets\": " + std::to_string(o.facets) + ", " + kind_json(o.dimension, o.kind);
}

std::string pairs_json(const char* key, const std::vector<std::pair<std::string, long long>>& v) {
  std::string o = std::string(", \"") + key + "\": {";
  for (std::size_t i = 0; i < v.size(); ++i)
    o += (i ? ", \"" : "\"") + json_escape(v[i].first) + "\": " + std::to_string(v[i].second);
  return o + "}";
}

// --scene: the operands and the sum as ExactPolyhedron nodes A, B, ... (no
// operand is named S) and S, each rounded as write_mesh_output would round it
// alone; the report adds up what was rounded.
RoundingReport write_scene_of_sum(const MeshOutput& out, const std::vector<std::string>& names,
                                  const std::vector<Operand>& operands, const ConvexPolytope& sum) {
  const std::string name = out.to_stdout() ? "<stdout>" : out.path;
  Scene scene;
  std::vector<std::string> comments;
  RoundingReport total;
  auto add = [&](const ConvexPolytope& p, const std::string& node, const std::string& comment) {
    RoundingReport r;
    try {
      scene.polytopes.push_back(polytope_node(writable_polytope(p, Format::wrl, out.options, &r), node));
    } catch (const UnrepresentableError& e) {
      throw OutputError("cannot write " + name + ": " + e.problem() + "; use --exact to write exact rationals");
    }
    comments.push_back(comment);
    total.coordinates += r.coordinates;
    total.max_displacement = std::max(total.max_displacement, r.max_displacement);
    total.split += r.split;
    total.hull = total.hull || r.hull;
    total.merged += r.merged;
    total.dropped += r.dropped;
  };
  std::string sum_text;
  for (std::size_t i = 0; i < operands.size(); ++i) {
    // A, B, ..., Z without S (the sum's node), then P26, P27, ...
    const std::string node =
        i < 25 ? std::string(1, char('A' + i + (i >= 18))) : std::string("P").append(std::to_string(i + 1));
    add(*operands[i].polytope(), node, node + " = " + printable(names[i]));
    sum_text += (i ? " ⊕ " : "") + node;
  }
  add(sum, "S", "S = " + sum_text);
  if (out.to_stdout()) {
    write_scene(std::cout, scene, out.options.exact, comments);
    std::cout.flush();
    if (!std::cout) throw OutputError("cannot write the scene to standard output: write error");
  } else {
    write_scene_output(out.path, scene, out.options.exact, comments);
  }
  print_rounding_note(name, total, false, true);
  return total;
}

// The text summary of a convex sum, of a sum with a point, segment or
// polygon, and of a solid's sum, erosion, opening or closing.
void print_text(std::ostream& report, const SumReport& r, const std::vector<std::string>& names,
                const std::optional<MeshOutput>& output, SumOperation operation) {
  const std::string written =
      output ? "  written to " + (output->to_stdout() ? std::string("standard output") : printable(output->path))
             : std::string();
  if (r.nonconvex) {
    const NonconvexSum& n = *r.nonconvex;
    static const char* const kFormula[][3] = {
        {"", " ⊕ ", ""}, {"", " ⊖ ", ""}, {"(", " ⊖ ", ") ⊕ B"}, {"(", " ⊕ ", ") ⊖ B"}};
    const auto& formula = kFormula[int(operation)];
    report << formula[0];
    for (std::size_t i = 0; i < 2; ++i) {
      const OperandReport& o = r.operands[i];
      const bool convex = std::string(o.kind) == "polytope";
      report << (i ? formula[1] : "") << printable(names[i]) << " (" << o.vertices << " V, " << o.facets << " F, "
             << (convex                ? std::string("convex")
                 : n.swept == "ab"[i] ? std::to_string(i ? n.pieces_b : n.pieces_a) + " polygons swept"
                                      : std::to_string(i ? n.pieces_b : n.pieces_a) + " convex pieces")
             << ")";
    }
    report << formula[2];
    if (r.empty)
      report << "\n  = empty: B fits nowhere inside A" << (operation == SumOperation::open ? " (A ⊖ B is empty)" : "");
    else
      report << "\n  = " << r.vertices << " vertices, " << r.edges << " edges, " << r.facets << " faces"
             << (n.shells > 1 ? ", " + std::to_string(n.shells) + " shells" : std::string())
             << (n.non_manifold_edges ? ", " + std::to_string(n.non_manifold_edges) + " non-manifold edges"
                                      : std::string());
    report << "\n  " << (operation == SumOperation::sum ? "non-convex sum" : n.operation) << " (" << n.method
           << "): " << n.pairs << " convex pieces, "
           << (n.culled_facets ? std::to_string(n.culled_facets) + " of " + std::to_string(n.pair_facets) +
                                     " facets culled, "
                               : std::string())
           << n.clips << " facet clips, " << format_double(r.seconds) << " s\n";
    if (output) report << written << "\n";
    return;
  }
  if (r.route) {  // with a point, segment or polygon
    for (std::size_t i = 0; i < names.size(); ++i)
      report << (i ? " ⊕ " : "") << printable(names[i]) << " (" << dimension_name(r.operands[i].dimension) << ", "
             << r.operands[i].vertices << " V)";
    report << "\n  = a " << dimension_name(r.dimension) << ": " << r.vertices << " vertices, " << r.edges
           << (r.edges == 1 ? " edge, " : " edges, ") << r.facets << (r.facets == 1 ? " facet\n" : " facets\n")
           << "  method " << r.method << " (" << r.route << "), " << format_double(r.seconds) << " s\n";
    if (output)
      report << written
             << (r.dimension == 3 ? "" : r.dimension == 2 ? " (one face)" : " (its points, no faces)") << "\n";
    return;
  }
  for (std::size_t i = 0; i < names.size(); ++i)
    report << (i ? " ⊕ " : "") << printable(names[i]) << " (" << r.operands[i].vertices << " V, "
           << r.operands[i].facets << " F)";
  report << "\n  = " << r.vertices << " vertices, " << r.edges << " edges, " << r.facets << " facets\n"
         << "  method " << r.method << ", " << format_double(r.seconds) << " s\n";
  if (output) report << written << "\n";
}

}  // namespace

Operand load_command_operand(const std::string& spec, bool hull, std::optional<Format> format, LoadPhases* phases) {
  // A solid's validation and sum run on worker threads that allocate
  // constantly: each gets a malloc arena of its own, set up before the
  // first of them runs (memory.hpp).
  const OperandOptions options{hull, format, [] { allow_thread_arenas(); }};
  if (spec != "-") return Operand::load(spec, options, phases);
  if (!format) throw UsageError("reading a mesh from standard input ('-') needs --format " + format_choices());
  claim_stdin("an operand");
  return Operand::load(std::cin, *format, "<stdin>", options, phases);
}

std::string sum_report_json(const SumReport& r, const std::vector<std::string>& names, const LoadPhases& load,
                            double write_seconds, const std::optional<MeshOutput>& output,
                            const std::string& rounding_json) {
  std::ostringstream o;
  o << "{";
  if (r.nonconvex) o << "\"operation\": \"" << r.operation << "\", \"empty\": " << (r.empty ? "true" : "false") << ", ";
  o << "\"vertices\": " << r.vertices << ", \"edges\": " << r.edges << ", \"facets\": " << r.facets << ", "
    << kind_json(r.dimension, r.kind) << ", \"method\": \"" << json_escape(r.method) << "\"";
  if (r.nonconvex)
    o << ", \"pair_method\": \""
      << (r.nonconvex->pieces_from_maps ? "gaussian_map" : method_name(r.nonconvex->pair_method)) << "\"";
  if (r.route) o << ", \"route\": \"" << r.route << "\"";
  o << ", \"seconds\": " << json_number(r.seconds) << ", \"phases\": {\"read\": " << json_number(load.read)
    << ", \"validate\": " << json_number(load.validate);
  for (const auto& [phase, seconds] : r.phases) o << ", \"" << phase << "\": " << json_number(seconds);
  o << ", \"write\": " << json_number(write_seconds) << "}";
  const Rational volume = r.volume ? *r.volume : Rational(0);
  o << ", \"volume\": \"" << format_exact(volume) << "\", \"volume_double\": " << json_number(to_double(volume));
  if (r.nonconvex) {
    const NonconvexSum& n = *r.nonconvex;
    o << ", \"nonconvex_method\": \"" << n.method
      << "\", \"swept\": " << (n.swept ? std::string("\"") + n.swept + "\"" : std::string("null"))
      << ", \"pieces\": {\"a\": " << n.pieces_a << ", \"b\": " << n.pieces_b << "}, \"pairs\": " << n.pairs
      << ", \"pair_vertices\": " << (n.pieces_from_maps ? std::string("null") : std::to_string(n.pair_vertices))
      << ", \"pair_facets\": " << n.pair_facets << ", \"candidate_facets\": " << n.candidate_facets
      << ", \"culled_facets\": " << n.culled_facets << ", \"union\": {\"clips\": " << n.clips
      << ", \"shells\": " << n.shells << ", \"non_manifold_edges\": " << n.non_manifold_edges
      << ", \"dropped_components\": " << n.dropped_components << "}";
  }
  if (!r.facet_types.empty()) o << pairs_json("facet_types", r.facet_types);
  if (!r.facet_cases.empty()) o << pairs_json("facet_cases", r.facet_cases);
  if (!r.counters.empty()) o << pairs_json("counters", r.counters);
  if (names.size() == 2) {
    for (std::size_t i = 0; i < 2; ++i) {
      o << ", \"" << "ab"[i] << "\": {\"name\": \"" << json_escape(names[i]) << "\", " << counts_json(r.operands[i]);
      if (r.nonconvex)
        o << ", \"convex\": " << (std::string(r.operands[i].kind) == "polytope" ? "true" : "false")
          << ", \"pieces\": " << (i ? r.nonconvex->pieces_b : r.nonconvex->pieces_a);
      o << "}";
    }
  }
  o << ", \"operands\": [";
  for (std::size_t i = 0; i < names.size(); ++i)
    o << (i ? ", " : "") << "{\"name\": \"" << json_escape(names[i]) << "\", " << counts_json(r.operands[i]) << "}";
  o << "], \"output\": ";
  if (!output) o << "null";
  else o << "\"" << json_escape(output->to_stdout() ? "-" : output->path) << "\"";
  o << ", \"rounding\": " << rounding_json << "}";
  return o.str();
}

int run_sum_command(const SumCommand& c) {
  std::vector<Operand> operands;
  LoadPhases load;
  for (const std::string& name : c.names) {
    LoadPhases l;
    operands.push_back(load_command_operand(name, c.hull, c.format, &l));
    load.read += l.read;
    load.validate += l.validate;
  }
  bool solid = c.request.operation != SumOperation::sum;
  for (const Operand& o : operands) solid = solid || o.solid();
  if (solid) allow_thread_arenas();
  static const char* const kCommand[] = {"sum", "erode", "open", "close"};
  SumRequest request = c.request;
  // The per-facet records are counted in the report and dropped: the peak
  // memory is the sum's.
  request.provenance = false;
  OperandSum s;
  // A solid sum's working data (SumOptions::release: the pieces, the
  // union's faces): dead once the sum is made, left to the end of the
  // process (leave_to_exit), where it costs nothing to free.
  {
    ProgressTicker ticker(std::string("minksum ") + kCommand[int(c.request.operation)]);
    request.options = ticker.sum_options();
    // The volume is for --json only; a solid's is computed below, on its own
    // thread while the file is written.
    request.options.volume = c.json && !solid;
    if (solid) request.options.release = [](std::shared_ptr<void> data) { leave_to_exit(std::move(data)); };
    s = minkowski_sum(operands, request);
  }
  // The operands are freed before the sum is rounded and written (only
  // --scene needs them), so that the peak memory is the sum's.
  // A scene holds polytopes: with a point, segment or polygon operand
  // (docs/sweeps.md) the sum alone is written.
  bool scene = c.scene && s.polytope();
  for (const Operand& o : operands) scene = scene && o.polytope();
  if (!scene) std::vector<Operand>().swap(operands);
  const Mesh* boundary = s.solid();
  const bool empty = boundary && boundary->faces.empty();
  // A solid's exact volume is for --json only (the text report does not
  // give it).  Both only read the boundary; the volume's thread is joined
  // before s changes (get() below, or the future's destructor when the write
  // throws).
  std::future<Rational> volume;
  const bool with_volume = boundary && c.json;
  if (with_volume) volume = std::async(std::launch::async, [&s] { return result_volume(s); });
  const auto w0 = std::chrono::steady_clock::now();
  std::string rounding = "null";
  if (c.output) {
    const MeshOutput& out = *c.output;
    if (const ConvexPolytope* p = s.polytope()) {
      rounding = rounding_json(scene ? write_scene_of_sum(out, c.names, operands, *p) : write_mesh_output(out, *p));
    } else if (const ConvexSet* set = s.set()) {
      rounding = rounding_json(write_set_output(out, *set));
    } else if (empty) {
      write_mesh_as_is(out, *boundary);  // (a file of the format with no faces)
    } else if (const auto& convex = std::get<NonconvexSum>(s.result).convex) {
      // Written as the convex path writes a polytope, reported as a solid's rounding.
      const RoundingReport p = write_mesh_output(out, *convex);
      RoundedSolid r;
      r.rounded_coordinates = p.coordinates;
      r.max_displacement = p.max_displacement;
      rounding = solid_rounding_json(r);
    } else {
      RoundedSolid r;
      write_solid_mesh(out, *boundary, nullptr, &r, std::get<NonconvexSum>(s.result).operation);
      rounding = solid_rounding_json(r);
    }
  }
  const double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  if (with_volume) s.report.volume = volume.get();
  std::ostream& report = c.output ? c.output->report_stream() : std::cout;
  if (c.json)
    report << sum_report_json(s.report, c.names, load, write_seconds, c.output, rounding) << "\n";
  else
    print_text(report, s.report, c.names, c.output, c.request.operation);
  return 0;
}

}  // namespace minksum::cli
