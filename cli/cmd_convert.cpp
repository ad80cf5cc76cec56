// minksum convert IN -o OUT: read, validate (or take the hull) and write a
// polytope or a closed solid in another format, or the same one cleaned.
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "solid.hpp"

namespace minksum::cli {

namespace {
const char* kConvertHelp = R"(Usage: minksum convert IN -o OUT [--hull] [--exact] [--binary] [--format F]
                       [--from F] [--json]

Read IN (a file, a catalog name, or '-' for a mesh on standard input), check
that it is a closed convex polytope exactly (or a closed solid, below), and
write it to OUT ({formats}, or '-' for standard output) cleaned:
exactly equal vertices welded, coplanar facets merged into one polygon,
vertices in the middle of an edge dropped, facets oriented outwards.  What
is written reads back as a valid convex polytope (see 'minksum sum --help',
Rounding).

A non-convex IN (without --hull) must be a closed solid (docs/nonconvex.md;
else exit status 3 and one line naming the problem), such as 'minksum sum'
writes for a non-convex sum: it is written with its faces as given (exactly
equal vertices welded; as triangles to STL), exactly with --exact, else as
'minksum sum' writes a non-convex sum: coordinates that are not doubles
(binary STL: floats) rounded, the surface kept a valid solid, a note giving
the largest displacement.  --json then has "convex": false and "rounding"
null or {"coordinates": N, "max_displacement": D, "grid": G} (G: 0, or the
coarsest grid points were snapped to).

Options:
  -o, --output OUT   where to write ('-': standard output; the summary or
                     JSON then goes to stderr); a file is written to a
                     temporary name and renamed when complete
  --hull             take the exact convex hull of IN's points instead of
                     requiring a valid convex mesh (a point cloud, or a mesh
                     a CAD tool rounded to a few digits)
  --exact            write exact rationals (p/q or integers); only
                     {exact_formats} can hold them
  --binary           binary {binary_formats} output
  --format F         {format_names}: the format of '-' and of names
                     without a known extension (IN and OUT)
  --from F           the format of IN alone, when it differs from OUT's
                     (convert - --from stl -o - --format off)
  --json             print one JSON object: the input's name, the counts of
                     what was written, output, and rounding (null, or what
                     rounding to the format's numbers did)
)";

// convert of a non-convex solid: its faces written as a sum's boundary is.
int convert_solid(const std::string& in, const Solid& solid, const MeshOutput& output, bool json) {
  const Mesh faces = solid_faces(solid);
  Mesh written;
  RoundedSolid r;
  write_solid_mesh(output, faces, &written, &r, "solid");
  const MeshCounts c = mesh_counts(written);
  std::ostream& report = output.report_stream();
  const std::string out_name = output.to_stdout() ? "-" : output.path;
  if (json) {
    report << "{\"name\": \"" << json_escape(in) << "\", \"vertices\": " << c.vertices << ", \"edges\": " << c.edges
           << ", \"facets\": " << c.faces << ", " << kind_json(3, "solid") << ", \"convex\": false, \"output\": \"" << json_escape(out_name)
           << "\", \"format\": \"" << format_info(output.format).extension
           << "\", \"rounding\": " << solid_rounding_json(r) << "}\n";
  } else {
    const MeshCounts given = mesh_counts(faces);
    report << printable(in) << ": " << given.vertices << " vertices, " << given.edges << " edges, " << given.faces
           << " facets, a non-convex solid, written to "
           << (output.to_stdout() ? std::string("standard output") : printable(output.path)) << " ("
           << format_name(output.format) << ")";
    if (c.faces != given.faces) report << " as " << c.faces << " triangles";
    report << "\n";
  }
  return 0;
}

}  // namespace

int run_convert(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "convert",
                            {{"--output", "-o", true}, {"--hull"}, {"--exact"}, {"--binary"}, {"--json"},
                             kFormatOption, {"--from", "", true}});
  if (a.help) {
    std::cout << expand_help(kConvertHelp);
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'convert' needs one input IN (see 'minksum convert --help')");
  const std::optional<MeshOutput> output = output_option(a);
  if (!output) throw UsageError("'convert' needs -o OUT ('-' for standard output)");
  std::optional<Format> from = format_option(a);
  if (const auto f = a.value("--from")) {
    Args only;
    only.values["--format"] = *f;
    from = format_option(only);
  }
  const std::string& in = a.positional[0];
  SolidOperand operand = load_solid_operand(in, a.flag("--hull"), nullptr, from);
  if (operand.solid) return convert_solid(in, *operand.solid, *output, a.flag("--json"));
  const ConvexPolytope p = std::move(*operand.polytope);
  ConvexPolytope written;
  const RoundingReport r = write_mesh_output(*output, p, &written);
  std::ostream& report = output->report_stream();
  const std::string out_name = output->to_stdout() ? "-" : output->path;
  if (a.flag("--json")) {
    // The counts of what was written (what stats gives for OUT).
    report << "{\"name\": \"" << json_escape(in) << "\", " << polytope_json(written) << ", \"output\": \""
           << json_escape(out_name) << "\", \"format\": \"" << format_info(output->format).extension
           << "\", \"rounding\": " << rounding_json(r) << "}\n";
  } else {
    report << in << ": " << p.num_vertices() << " vertices, " << p.num_edges() << " edges, " << p.num_facets()
           << " facets, written to " << (output->to_stdout() ? "standard output" : output->path) << " ("
           << format_name(output->format) << ")\n";
  }
  return 0;
}

}  // namespace minksum::cli
