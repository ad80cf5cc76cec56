// minksum gen NAME -o OUT: write a catalog polytope.
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "solid.hpp"
#include "text.hpp"
#include "sweep.hpp"

namespace minksum::cli {

namespace {
const char* kGenHelpHead = R"(Usage: minksum gen NAME -o OUT [--exact] [--binary] [--format F]

Write a built-in polytope to OUT ({formats}), or to standard
output for '-o -' (with --format {format_names}; the summary then
goes to stderr).  A point, a segment or a polygon is written exactly as
'minksum sum' writes one (docs/sweeps.md): a polygon as one face, a point
or a segment as its points without faces.  Use --exact for rational coordinates (rotated solids have
them); without it coordinates are written as the nearest doubles, and the file
still reads back as a valid convex polytope (see 'minksum sum --help',
Rounding).

Catalog (names are accepted anywhere a file path is):
)";


// A non-convex solid of the catalog: validated, written like a sum's
// boundary, one summary line.
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

}  // namespace

int run_gen(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "gen", {{"--output", "-o", true}, {"--exact"}, {"--binary"}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kGenHelpHead);
    auto list = [](const std::vector<CatalogEntry>& entries) {
      for (const auto& e : entries) {
        std::string syn = e.syntax;
        if (syn.size() < 22) syn.resize(22, ' ');
        std::cout << "  " << syn << " " << e.description << "\n";
      }
    };
    list(catalog_entries());
    std::cout << "\nPoints, segments and polygons (operands of sweeps, docs/sweeps.md):\n";
    list(flat_catalog_entries());
    std::cout << "\nNon-convex solids (closed, for 'minksum sum'; docs/nonconvex.md):\n";
    list(nonconvex_catalog_entries());
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'gen' needs one catalog name (see 'minksum gen --help')");
  const std::optional<MeshOutput> output = output_option(a);
  if (!output) throw UsageError("'gen' needs -o OUT");
  // catalog_convex_set names the closest catalog name when the name is unknown.
  ConvexSet set;
  try {
    set = catalog_convex_set(a.positional[0]);
  } catch (const NotConvexError&) {  // a non-convex solid of the catalog
    return write_nonconvex_catalog_solid(a.positional[0], *output);
  }
  if (!set.full()) {  // a point, a segment, a polygon (docs/sweeps.md)
    write_set_output(*output, set);
    output->report_stream() << printable(a.positional[0]) << ": a " << dimension_name(set.dimension()) << ", "
                            << set.num_vertices() << " vertices, written to "
                            << (output->to_stdout() ? std::string("standard output") : printable(output->path))
                            << "\n";
    return 0;
  }
  const ConvexPolytope& p = set.polytope();
  write_mesh_output(*output, p);
  output->report_stream() << printable(a.positional[0]) << ": " << p.num_vertices() << " vertices, " << p.num_edges()
                          << " edges, " << p.num_facets() << " facets, written to "
                          << (output->to_stdout() ? std::string("standard output") : printable(output->path)) << "\n";
  return 0;
}

}  // namespace minksum::cli
