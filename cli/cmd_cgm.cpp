// minksum cgm P [Q]: the Cubical Gaussian Map of P (or of P ⊕ Q computed by
// the overlay), its per-map counts and its unfolded drawing.
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "page.hpp"
#include "scene.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {
const char* kCgmHelp = R"(Usage: minksum cgm P [Q] [--svg OUT.svg] [--html OUT.html] [-o OUT.wrl] [--stats]
                  [--json] [--hull] [--format F]

Build the Cubical Gaussian Map (Fogel & Halperin) of P: the Gaussian map
centrally projected on the six faces of the cube [-1,1]^3, six planar maps
with ids 0-5 for x=-1, y=-1, z=-1, x=1, y=1, z=1.  With Q, the map is the one
of P ⊕ Q, computed by overlaying the six pairs of planar maps.

Options:
  --stats      print, per planar map, the numbers of vertices, halfedges and
               faces (the unbounded face included) and of real (non-artificial)
               vertices and edges, like Table 2 of Fogel and Halperin (2006)
  --svg OUT    draw the unfolded map (six squares in a cross, each named by
               its id and plane); real edges solid (for a sum: P's edges red,
               Q's blue, overlapping edges purple), artificial edges dashed,
               facet normals as dots (with a zoom inset where they crowd),
               a title and a legend; written atomically
  --html OUT   a self-contained 3D page (offline; docs/viewer.md): the six
               planar maps on the faces of the cube, artificial edges dashed,
               arcs of P and Q in two named colours, the facet normals (the
               overlay's vertices) as dots, beside the polytope it encodes;
               click a facet of the polytope for its exact plane
  -o, --output OUT.wrl
               a VRML scene (docs/vrml.md) in the extended VRML of Fogel and
               Halperin: P (and Q and the sum S = P ⊕ Q) as ExactPolyhedron
               nodes with exact coordinates, and a CubicalGaussianMap node
               for each, the sum's naming P and Q as its operands, with the
               counts and facet normals of its six planar maps; 'minksum
               view OUT.wrl -o page.html' shows it; written atomically
  --json       print the counts as one JSON object
  --hull       take the exact convex hull of each operand's points instead of
               requiring a valid convex mesh
  --format F   {format_names}: the format of an operand '-' (a mesh
               on standard input) or named without a known extension
)";
}  // namespace

int run_cgm(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "cgm", {{"--svg", "", true}, {"--html", "", true}, {"--output", "-o", true}, {"--stats", "", false}, {"--json", "", false}, {"--hull", "", false}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kCgmHelp);
    return 0;
  }
  if (a.positional.empty() || a.positional.size() > 2)
    throw UsageError("'cgm' needs one or two operands (see 'minksum cgm --help')");
  const auto svg = a.value("--svg");
  if (svg && svg->empty()) throw UsageError("--svg needs a file name");
  const auto html = a.value("--html");
  if (html) check_html_path(*html, "--html");
  const auto scene_path = a.value("--output");
  if (scene_path && format_from_path(*scene_path) != Format::wrl)
    throw UsageError("-o: the Cubical Gaussian Map is written as a VRML scene, a .wrl file; got '" + *scene_path +
                     "' (--svg and --html write pictures)");
  const auto format = format_option(a);
  const bool hull = a.flag("--hull");
  ConvexPolytope p = load_operand(a.positional[0], hull, nullptr, format);
  CubicalGaussianMap g;
  std::string label = a.positional[0];
  double seconds = 0;
  ConvexPolytope shown = p;
  std::vector<FacetProvenance> provenance;
  Scene scene;  // for -o: P [Q S], then their maps
  std::vector<std::string> comments;
  if (scene_path) {
    scene.polytopes.push_back(polytope_node(p, "P"));
    comments.push_back("P = " + printable(a.positional[0]));
  }
  if (a.positional.size() == 2) {
    ConvexPolytope q = load_operand(a.positional[1], hull, nullptr, format);
    if (scene_path) {
      scene.polytopes.push_back(polytope_node(q, "Q"));
      comments.push_back("Q = " + printable(a.positional[1]));
      scene.cgms.push_back(cgm_node(CubicalGaussianMap::from_polytope(p), "CGM_P", 0));
      scene.cgms.push_back(cgm_node(CubicalGaussianMap::from_polytope(q), "CGM_Q", 1));
    }
    label += " + " + a.positional[1];
    SumResult r = minkowski_sum(p, q, Method::cgm);
    seconds = r.seconds;
    g = CubicalGaussianMap::from_polytope(r.polytope);
    g.set_operands(r.vertex_origin, r.polytope);
    shown = r.polytope;
    if (scene_path) {
      scene.polytopes.push_back(polytope_node(r.polytope, "S"));
      comments.push_back("S = P ⊕ Q");
      scene.cgms.push_back(cgm_node(g, "CGM_S", 2, {0, 1}));
    }
    if (html) provenance = r.facet_provenance.empty() ? facet_provenance(p, q, r.polytope) : r.facet_provenance;
  } else {
    g = CubicalGaussianMap::from_polytope(p);
    if (scene_path) scene.cgms.push_back(cgm_node(g, "CGM_P", 0));
  }
  if (scene_path) write_scene_output(*scene_path, scene, true, comments);
  if (svg) {
    try {
      const bool sum = a.positional.size() == 2;
      const std::string text =
          sum ? g.to_svg("Cubical Gaussian Map of P ⊕ Q", "P = " + a.positional[0] + ", Q = " + a.positional[1])
              : g.to_svg("Cubical Gaussian Map of " + a.positional[0]);
      write_file_atomically(*svg, [&](std::ostream& o) { o << text; });
    } catch (const InputError& e) {
      throw OutputError(std::string("cannot write ") + e.what());
    }
  }
  if (html) {
    std::vector<std::string> operands;
    if (a.positional.size() == 2) operands = a.positional;
    write_cgm_page(*html, label, g, shown, operands, provenance);
  }
  if (a.flag("--json")) {
    std::cout << "{\"name\": \"" << json_escape(label) << "\", " << polytope_json(shown) << ", \"maps\": [";
    for (int k = 0; k < 6; ++k) {
      auto c = g.counts(k);
      std::cout << (k ? ", " : "") << "{\"id\": " << k << ", \"vertices\": " << c.vertices
                << ", \"halfedges\": " << c.halfedges << ", \"faces\": " << c.faces
                << ", \"real_vertices\": " << g.map(k).num_real_vertices()
                << ", \"real_edges\": " << g.map(k).num_real_edges() << "}";
    }
    std::cout << "]";
    if (a.positional.size() == 2) std::cout << ", \"seconds\": " << json_number(seconds);
    std::cout << "}\n";
    return 0;
  }
  std::cout << printable(label) << ": " << shown.num_vertices() << " vertices, " << shown.num_edges() << " edges, "
            << shown.num_facets() << " facets\n";
  if (a.flag("--stats") || (!svg && !html && !scene_path)) {
    static const char* plane[6] = {"x=-1", "y=-1", "z=-1", "x=+1", "y=+1", "z=+1"};
    std::cout << "  map  plane     V    HE     F  real V  real E\n";
    Index tv = 0, th = 0, tf = 0;
    for (int k = 0; k < 6; ++k) {
      auto c = g.counts(k);
      tv += c.vertices, th += c.halfedges, tf += c.faces;
      char line[128];
      std::snprintf(line, sizeof line, "  %3d  %-5s %5u %5u %5u  %6u  %6u\n", k, plane[k], c.vertices, c.halfedges,
                    c.faces, g.map(k).num_real_vertices(), g.map(k).num_real_edges());
      std::cout << line;
    }
    char line[128];
    std::snprintf(line, sizeof line, "  total      %5u %5u %5u\n", tv, th, tf);
    std::cout << line;
  }
  if (svg) std::cout << "  wrote " << printable(*svg) << "\n";
  if (html) std::cout << "  wrote " << printable(*html) << "\n";
  if (scene_path) std::cout << "  wrote " << printable(*scene_path) << "\n";
  return 0;
}

}  // namespace minksum::cli
