// minksum stats P: validate a polytope and print its numbers.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"

namespace minksum::cli {

namespace {
const char* kStatsHelp = R"(Usage: minksum stats P [--json] [--hull] [--format F]

Validate P (file, catalog name, or '-' for a mesh on standard input in the
format --format names: {format_names}; --format also gives the format of a
file whose name has no known extension) and print its numbers of vertices,
edges and facets (coplanar facets merged), its exact volume, and whether every
coordinate is exactly a double.  With --hull, P's points are a point cloud and
the statistics are those of its exact convex hull.  --json gives the volume
exactly ("volume", a string) and as the nearest double ("volume_double"; null
when beyond the double range, as JSON has no infinity), and "phases": the
seconds spent reading P (or building the catalog polytope) and validating it
(or taking its hull).
)";

}  // namespace

int run_stats(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "stats", {{"--json"}, {"--hull"}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kStatsHelp);
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'stats' needs one operand (see 'minksum stats --help')");
  LoadPhases phases;
  ConvexPolytope p = load_operand(a.positional[0], a.flag("--hull"), &phases, format_option(a));
  Rational vol = p.volume();
  Index max_fdeg = 0, max_vdeg = 0;
  for (Index f = 0; f < p.num_facets(); ++f) max_fdeg = std::max(max_fdeg, p.facet_degree(f));
  for (Index v = 0; v < p.num_vertices(); ++v) max_vdeg = std::max(max_vdeg, p.vertex_degree(v));
  if (a.flag("--json")) {
    std::cout << "{\"name\": \"" << json_escape(a.positional[0]) << "\", " << counts_json(p)
              << ", \"volume\": \"" << format_exact(vol) << "\", \"volume_double\": "
              << json_number(to_double(vol)) << ", \"max_facet_degree\": " << max_fdeg
              << ", \"max_vertex_degree\": " << max_vdeg << ", \"coordinates_are_doubles\": "
              << (p.coordinates_are_doubles() ? "true" : "false") << ", \"phases\": {\"read\": "
              << json_number(phases.read) << ", \"validate\": " << json_number(phases.validate) << "}}\n";
  } else {
    std::cout << printable(a.positional[0]) << ": " << p.num_vertices() << " vertices, " << p.num_edges() << " edges, "
              << p.num_facets() << " facets\n"
              << "  volume " << format_double(to_double(vol));
    if (!is_double(vol)) std::cout << " (exactly " << format_exact(vol) << ")";
    std::cout << "\n  largest facet has " << max_fdeg << " vertices, largest vertex degree " << max_vdeg
              << "\n  coordinates: " << (p.coordinates_are_doubles() ? "all exact doubles" : "exact rationals")
              << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
