// minksum sum A B: the Minkowski sum.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <chrono>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "nonconvex_sum.hpp"
#include "progress.hpp"
#include "scene.hpp"
#include "sweep.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {

const char* kSumHelp = R"(Usage: minksum sum A B [C ...] [options]

Compute the Minkowski sum A ⊕ B = { a + b : a in A, b in B } exactly and print
a summary (or JSON).  The operands are files, catalog names, or '-' for a mesh
on standard input (with --format).  With more than two operands the sum is
A ⊕ B ⊕ C ⊕ ..., taken left to right with the same options.

Options:
  -o, --output OUT   write the sum to OUT ({formats}), or
                     to standard output for '-' (the summary or JSON then
                     goes to stderr); a file is written to a temporary name
                     and renamed when complete
  --format F         {format_names}: the format of '-' and of names
                     without a known extension
  --method M         {methods}.
{method_summaries}
                     All are exact and give the same polytope.
  --exact            write coordinates as exact rationals (p/q or integers);
                     default: shortest text that reads back to the nearest
                     double.  Only {exact_formats} can hold rationals.
  --binary           binary {binary_formats} output
  --scene            with -o OUT.wrl: write a VRML scene (docs/vrml.md) that
                     holds the operands and the sum, each an ExactPolyhedron
                     node (DEF A, B, C, ... and S; operands after R are
                     T to Z, then P26, P27, ...), instead of the sum alone;
                     exact coordinates with --exact, else the nearest doubles
                     as for a .wrl file ('minksum view OUT.wrl -o page.html'
                     shows it)
  --hull             take the convex hull of each operand's points instead
                     of requiring a valid convex mesh (point clouds, and
                     non-convex files or catalog solids); points spanning
                     fewer than 3 dimensions give a point, a segment or a
                     polygon
  --json             print one JSON object: dimension (3 for a polytope, 2,
                     1, 0 for a polygon, segment, point), kind (polytope,
                     polygon, segment, point; solid for a non-convex sum),
                     vertices, edges, facets, method,
                     seconds (the computation alone, not the I/O), phases
                     (seconds spent reading the operands, validating them,
                     computing the sum, making its explicit polytope, and
                     writing OUT), volume (exact rational as a string), the
                     operands' names and counts ("operands"; also "a" and "b"
                     for two), and "rounding" (below)

Sweeps: an operand may be a point, a segment or a flat convex polygon: a
catalog name (point:X,Y,Z, segment:X,Y,Z:X,Y,Z, polygon:N, square, with @
transforms), a file holding one face, or points spanning fewer than 3
dimensions with --hull.  A polytope ⊕ a segment is the solid the polytope
sweeps along it; two lower-dimensional operands give a point, a segment, a
polygon or a polytope ("dimension" in --json, "kind" its name, "route" how it
was made).  Only walk (the default) and chms take them.  A polygon result is
written as one face, a point or a segment as its points without faces
(exactly: never rounded; not to STL).  See docs/sweeps.md.

Rounding: the file written always reads back as a valid convex polytope.
Without --exact, coordinates that are not doubles (binary STL: 32-bit floats)
are rounded to the nearest ones; facets no longer planar are split along
convex folds, and when that is not enough the exact convex hull of the
rounded vertices is written.  A note on stderr (and "rounding" in --json:
coordinates rounded, largest vertex displacement, facets split, hull taken,
vertices merged and dropped) says so.  A coordinate beyond the format's range,
or a solid that rounding collapses, is refused with exit status 1 and one line
naming the fix.

Non-convex operands: a file or catalog solid (tube, lshape, ring:N, star:N,
gear:N) that is not convex must be a closed solid: a closed, consistently
oriented 2-manifold surface of planar faces, without self-intersection, facing
outwards (else exit status 3 and one line naming the problem).  The sum of two
operands, one or both non-convex, is exact (docs/nonconvex.md): by default the
boundary sweep, which sums each triangle of the non-convex operand's surface
with the other operand (in parallel; a non-convex other operand is cut into
convex pieces first), keeps only the facets that can be on the boundary and
writes the exact union (polygons of exact coordinates, cavities as inner
shells).  Without --exact, coordinates that are not doubles (binary STL:
floats) are rounded and the result written as a valid solid: points that round
together merged, degenerate triangles removed, where the sum touches itself
its parts moved apart, and where rounding made faces cross the points there
snapped to a coarser grid; a note gives the largest displacement.  Only a sum
that cannot be represented (beyond the format's range, or thinner than its
spacing everywhere) is refused (exit 1) naming --exact.  --json then has a
convex sum's counts, "dimension", "kind" ("solid"), "volume", "a", "b",
"operands", "output" and "rounding" (null or {"coordinates": N,
"max_displacement": D, "grid": G}), "method":
"nonconvex", and "nonconvex_method", "swept", "pieces", "pairs",
"pair_vertices", "pair_facets", "candidate_facets", "culled_facets" and
"union" (clips, shells, non-manifold edges, dropped components) and the
phases decompose, pairs, union and boundary.
  --nonconvex-method sweep|decomposition
                     sweep (default), or Hachenberger's decomposition: both
                     operands cut into convex pieces (CGAL), every pair of
                     pieces summed, then the same union; slower on solids
                     with many reflex edges, the same exact result
--method sums the convex pieces of the decomposition (walk by default); the
sweep's pieces, a triangle and a polytope, are built from their Gaussian maps,
or with --method chms as the exact hull of their vertex sums ("pair_method" in
--json names the construction: "gaussian_map", "chms" or a method); a sum with
a non-convex operand takes exactly two operands.

Progress: when stderr is a terminal and the sum takes more than a second, one
line is rewritten in place on stderr every 0.2 s and erased when the sum is
done: the phase, the fraction done when the method measures it, and the time
so far, for example
    minksum sum: walk 42% (2.3 s)
Nothing is printed when stderr is redirected to a file or a pipe.
)";

// ", \"facet_types\": {...}" for methods that record where each facet comes from.
std::string facet_types_json(const SumResult& r) {
  if (r.facet_provenance.empty()) return "";
  constexpr FacetOrigin kinds[] = {FacetOrigin::translated, FacetOrigin::corner, FacetOrigin::edge,
                                   FacetOrigin::facet_edge, FacetOrigin::facet_facet};
  std::map<FacetOrigin, long> count;
  for (const auto& p : r.facet_provenance) ++count[p.origin()];
  std::ostringstream o;
  o << ", \"facet_types\": {";
  for (std::size_t i = 0; i < std::size(kinds); ++i)
    o << (i ? ", " : "") << "\"" << facet_origin_name(kinds[i]) << "\": " << count[kinds[i]];
  o << "}";
  return o.str();
}

// ", \"facet_cases\": {...}, \"counters\": {...}" when the method records them.
std::string method_detail_json(const SumResult& r) {
  std::ostringstream o;
  if (!r.facet_case.empty()) {
    std::vector<long> count(r.facet_case_names.size(), 0);
    for (auto c : r.facet_case) ++count.at(c);
    o << ", \"facet_cases\": {";
    for (std::size_t i = 0; i < count.size(); ++i)
      o << (i ? ", " : "") << "\"" << json_escape(r.facet_case_names[i]) << "\": " << count[i];
    o << "}";
  }
  if (!r.counters.empty()) {
    o << ", \"counters\": {";
    for (std::size_t i = 0; i < r.counters.size(); ++i)
      o << (i ? ", " : "") << "\"" << json_escape(r.counters[i].first) << "\": " << r.counters[i].second;
    o << "}";
  }
  return o.str();
}

// --scene: the operands and the sum as ExactPolyhedron nodes A, B, ... (no
// operand is named S) and S, each rounded as write_mesh_output would round it
// alone; the report adds up what was rounded.
RoundingReport write_scene_of_sum(const MeshOutput& out, const std::vector<std::string>& names,
                                  const std::vector<ConvexPolytope>& operands, const ConvexPolytope& sum) {
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
    add(operands[i], node, node + " = " + printable(names[i]));
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

}  // namespace

int run_sum(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "sum",
                            {{"--output", "-o", true}, {"--method", "", true}, {"--exact"}, {"--binary"},
                             {"--json"}, {"--hull"}, {"--scene"}, {"--nonconvex-method", "", true}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kSumHelp);
    return 0;
  }
  if (a.positional.size() < 2)
    throw UsageError("'sum' needs two or more operands A B [C ...] (see 'minksum sum --help')");
  const std::string method_text = a.value_or("--method", "auto");
  const bool json = a.flag("--json"), hull = a.flag("--hull");
  auto method = parse_method(method_text);
  if (!method)
    throw UsageError("unknown method '" + method_text + "' (" + method_list() + ")");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) + "' is not implemented in this version of minksum");
  const std::string nonconvex_text = a.value_or("--nonconvex-method", "sweep");
  NonconvexMethod nonconvex_method = NonconvexMethod::sweep;
  if (nonconvex_text == "decomposition")
    nonconvex_method = NonconvexMethod::decomposition;
  else if (nonconvex_text != "sweep")
    throw UsageError("unknown --nonconvex-method '" + nonconvex_text + "' (sweep, decomposition)");
  const auto format = format_option(a);
  const std::optional<MeshOutput> output = output_option(a);
  const bool scene = a.flag("--scene");
  if (scene && (!output || output->format != Format::wrl))
    throw UsageError("--scene writes a VRML scene: it needs -o OUT.wrl (or -o - --format wrl)");
  const std::vector<std::string>& names = a.positional;
  std::vector<ConvexSet> sets;
  LoadPhases load;
  if (!hull) {  // operands that may be non-convex (docs/nonconvex.md) or lower-dimensional (docs/sweeps.md)
    std::vector<AnyOperand> any;
    bool convex = true, flat = false;
    for (const std::string& name : names) {
      LoadPhases l;
      any.push_back(load_any_operand_from(name, &l, format));
      convex = convex && (any.back().polytope || any.back().flat);
      flat = flat || any.back().flat;
      load.read += l.read;
      load.validate += l.validate;
    }
    if (!convex && flat)
      throw UsageError("a point, segment or polygon operand is summed with convex operands only, not with a "
                       "non-convex solid (docs/sweeps.md)");
    if (!convex) return run_nonconvex_sum(names, any, load, output, json, *method, nonconvex_method);
    for (auto& o : any) sets.push_back(o.flat ? std::move(*o.flat) : ConvexSet(std::move(*o.polytope)));
  }
  for (std::size_t i = 0; hull && i < names.size(); ++i) {
    LoadPhases l;
    sets.push_back(load_set_operand(names[i], hull, &l, format));
    load.read += l.read;
    load.validate += l.validate;
  }
  // Points, segments, polygons: docs/sweeps.md.
  for (const ConvexSet& s : sets)
    if (!s.full()) return sum_sets(names, sets, *method, output, json, load);
  std::vector<ConvexPolytope> operands;
  for (ConvexSet& s : sets) operands.push_back(std::move(s).release_polytope());
  // A ⊕ B ⊕ C ... left to right; the times add up, the method's details are
  // those of the last step.
  SumResult r;
  double seconds = 0, explicit_seconds = 0;
  {
    ProgressTicker ticker("minksum sum");  // a progress line on a terminal after 1 s; erased when done
    for (std::size_t i = 1; i < operands.size(); ++i) {
      r = minkowski_sum(i == 1 ? operands[0] : r.polytope, operands[i], *method, ticker.sum_options());
      seconds += r.seconds;
      explicit_seconds += r.explicit_seconds;
    }
  }
  // The report needs only the operands' counts; without --scene the
  // operands are freed before the sum is rounded and written, so that the
  // process's peak memory is the sum's, not the sum's plus the operands'.
  std::vector<std::string> operand_counts, operand_summary;
  for (const ConvexPolytope& p : operands) {
    operand_counts.push_back(polytope_json(p));
    operand_summary.push_back(std::to_string(p.num_vertices()) + " V, " + std::to_string(p.num_facets()) + " F");
  }
  // --json reports the exact volume: by mixed volumes from the two operands
  // while they are here (sum_volume), a fraction of what the sum's own
  // triangles cost.
  std::optional<Rational> volume;
  if (json && operands.size() == 2) volume = sum_volume(operands[0], operands[1], r);
  if (!scene) std::vector<ConvexPolytope>().swap(operands);  // freed now (clear() keeps the memory)
  // Likewise the per-facet and per-vertex records, once summed up for --json.
  const std::string details = names.size() == 2 ? facet_types_json(r) + method_detail_json(r) : "";
  decltype(r.facet_provenance)().swap(r.facet_provenance);
  decltype(r.vertex_origin)().swap(r.vertex_origin);
  const auto w0 = std::chrono::steady_clock::now();
  RoundingReport rounding;
  if (output && scene) rounding = write_scene_of_sum(*output, names, operands, r.polytope);
  else if (output) rounding = write_mesh_output(*output, r.polytope);
  const double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  const ConvexPolytope& s = r.polytope;
  std::ostream& report = output ? output->report_stream() : std::cout;
  if (json) {
    const Rational vol = volume ? *volume : s.volume();
    report << "{" << polytope_json(s) << ", \"method\": \"" << method_name(r.method) << "\""
           << ", \"seconds\": " << json_number(seconds) << ", \"phases\": {\"read\": " << json_number(load.read)
           << ", \"validate\": " << json_number(load.validate)
           << ", \"sum\": " << json_number(seconds - explicit_seconds)
           << ", \"explicit\": " << json_number(explicit_seconds) << ", \"write\": " << json_number(write_seconds)
           << "}, \"volume\": \"" << format_exact(vol) << "\", \"volume_double\": " << json_number(to_double(vol));
    if (names.size() == 2) {
      report << details << ", \"a\": {\"name\": \"" << json_escape(names[0])
             << "\", " << operand_counts[0] << "}, \"b\": {\"name\": \"" << json_escape(names[1]) << "\", "
             << operand_counts[1] << "}";
    }
    report << ", \"operands\": [";
    for (std::size_t i = 0; i < names.size(); ++i)
      report << (i ? ", " : "") << "{\"name\": \"" << json_escape(names[i]) << "\", " << operand_counts[i] << "}";
    report << "]" << output_json_tail(output, rounding) << "\n";
  } else {
    for (std::size_t i = 0; i < names.size(); ++i)
      report << (i ? " ⊕ " : "") << printable(names[i]) << " (" << operand_summary[i] << ")";
    report << "\n  = " << s.num_vertices() << " vertices, " << s.num_edges() << " edges, " << s.num_facets()
           << " facets\n"
           << "  method " << method_name(r.method) << ", " << format_double(seconds) << " s\n";
    if (output) report << "  written to " << (output->to_stdout() ? std::string("standard output") : printable(output->path)) << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
