// minksum stats P: validate a polytope and print its numbers.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "solid.hpp"

namespace minksum::cli {

namespace {
const char* kStatsHelp = R"(Usage: minksum stats P [--json] [--hull] [--format F]

Validate P (file, catalog name, or '-' for a mesh on standard input in the
format --format names: {format_names}; --format also gives the format of a
file whose name has no known extension) as a convex polytope or, when it is
not convex, a closed solid (below), and print its numbers of vertices, edges
and facets (coplanar facets merged), its exact volume, and whether every
coordinate is exactly a double.  With --hull, P's points are a point cloud and
the statistics are those of its exact convex hull.  --json gives the volume
exactly ("volume", a string) and as the nearest double ("volume_double"; null
when beyond the double range, as JSON has no infinity), and "phases": the
seconds spent reading P (or building the catalog polytope) and validating it
(or taking its hull).

Without --hull, a non-convex P must be a closed solid (docs/nonconvex.md:
a closed, consistently oriented 2-manifold surface of planar faces without
self-intersection, facing outwards; else exit status 3 and one line naming
the problem), such as 'minksum sum' writes for a non-convex sum.  Its numbers
are those of its faces as given (exactly equal vertices welded, coplanar
faces not merged): the counts, the exact volume, its genus (summed over its
shells: a torus has genus 1), its shells (the connected parts of its surface:
a cavity is one) and its exact bounding box.  --json then has "convex":
false, "genus", "shells" and "bounding_box" ("min" and "max": [x, y, z] as
exact strings; "min_double" and "max_double": their nearest doubles) instead
of the largest facet and vertex degrees.
)";

// (Appended piece by piece: GCC 12 warns, wrongly, about overlapping copies
// in a chain of operator+ that starts with a literal.)
std::string exact_triple(const Point3& p) {
  std::string s = "[";
  for (int k = 0; k < 3; ++k) {
    s += k ? ", \"" : "\"";
    s += format_exact(p[k]);
    s += "\"";
  }
  return s + "]";
}
std::string double_triple(const Point3& p) {
  std::string s = "[";
  for (int k = 0; k < 3; ++k) {
    if (k) s += ", ";
    s += json_number(to_double(p[k]));
  }
  return s + "]";
}
// "[x0, x1] × [y0, y1] × [z0, z1]" by `number`.
template <class F>
std::string box_text(const Point3& lo, const Point3& hi, F number) {
  std::string s;
  for (int k = 0; k < 3; ++k) s += (k ? " × [" : "[") + number(lo[k]) + ", " + number(hi[k]) + "]";
  return s;
}

int print_solid_stats(const std::string& name, const Solid& solid, const LoadPhases& phases, bool json) {
  const Mesh faces = solid_faces(solid);
  const SolidStats st = solid_stats(faces);
  const Rational& vol = solid.volume;
  const bool doubles = faces.points.all_doubles();
  if (json) {
    std::cout << "{\"name\": \"" << json_escape(name) << "\", \"vertices\": " << st.vertices
              << ", \"edges\": " << st.edges << ", \"facets\": " << st.facets << ", " << kind_json(3, "solid")
              << ", \"volume\": \""
              << format_exact(vol) << "\", \"volume_double\": " << json_number(to_double(vol))
              << ", \"convex\": false, \"genus\": " << st.genus << ", \"shells\": " << st.shells
              << ", \"bounding_box\": {\"min\": " << exact_triple(st.min) << ", \"max\": " << exact_triple(st.max)
              << ", \"min_double\": " << double_triple(st.min) << ", \"max_double\": " << double_triple(st.max)
              << "}, \"coordinates_are_doubles\": " << (doubles ? "true" : "false")
              << ", \"phases\": {\"read\": " << json_number(phases.read)
              << ", \"validate\": " << json_number(phases.validate) << "}}\n";
    return 0;
  }
  auto decimal = [](const Rational& q) { return format_double(to_double(q)); };
  bool box_exact = true;
  for (int k = 0; k < 3; ++k) box_exact = box_exact && is_double(st.min[k]) && is_double(st.max[k]);
  std::cout << printable(name) << ": " << st.vertices << " vertices, " << st.edges << " edges, " << st.facets
            << " facets, a non-convex solid\n"
            << "  volume " << decimal(vol);
  if (!is_double(vol)) std::cout << " (exactly " << format_exact(vol) << ")";
  std::cout << "\n  genus " << st.genus << ", " << st.shells << (st.shells == 1 ? " shell" : " shells")
            << "\n  bounding box " << box_text(st.min, st.max, decimal);
  if (!box_exact) std::cout << "\n    exactly " << box_text(st.min, st.max, [](const Rational& q) { return format_exact(q); });
  std::cout << "\n  coordinates: " << (doubles ? "all exact doubles" : "exact rationals") << "\n";
  return 0;
}

}  // namespace

int run_stats(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "stats", {{"--json"}, {"--hull"}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kStatsHelp);
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'stats' needs one operand (see 'minksum stats --help')");
  LoadPhases phases;
  SolidOperand operand = load_solid_operand(a.positional[0], a.flag("--hull"), &phases, format_option(a));
  if (operand.solid) return print_solid_stats(a.positional[0], *operand.solid, phases, a.flag("--json"));
  ConvexPolytope p = std::move(*operand.polytope);
  Rational vol = p.volume();
  Index max_fdeg = 0, max_vdeg = 0;
  for (Index f = 0; f < p.num_facets(); ++f) max_fdeg = std::max(max_fdeg, p.facet_degree(f));
  for (Index v = 0; v < p.num_vertices(); ++v) max_vdeg = std::max(max_vdeg, p.vertex_degree(v));
  if (a.flag("--json")) {
    std::cout << "{\"name\": \"" << json_escape(a.positional[0]) << "\", " << polytope_json(p)
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
