// minksum view: one self-contained HTML page showing a polytope, or two
// operands and their Minkowski sum, in 3D (cli/page.hpp, web/src/viewer.js).
#include <minksum/operand.hpp>

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "memory.hpp"
#include "sum_command.hpp"
#include "page.hpp"
#include "progress.hpp"
#include "scene.hpp"
#include "solid.hpp"
#include "text.hpp"
#include "sweep.hpp"

namespace minksum::cli {

namespace {

const char* kViewHelp = R"(Usage: minksum view A [B] -o OUT.html [--method M] [--hull] [--title T] [--json]
       minksum view SCENE.wrl -o OUT.html [--title T] [--json]

Write one self-contained HTML page that shows, in 3D, the polytope A, or the
operands A, B and their Minkowski sum A ⊕ B.  The page needs no network and
no other file: its script and three.js (with its licence) are inlined, and
the data it shows is embedded as JSON with every coordinate, plane and volume
as an exact rational string.  Open it in any browser with WebGL.

In the page: drag to turn, wheel to zoom, right-drag (or shift-drag) to pan;
checkboxes show or hide each solid, switch wireframe and transparency, and
lay the solids side by side or at their true positions (overlaid).  The
sum's facets are coloured by provenance: a translated facet of A (facet of
A ⊕ vertex of B), of B (vertex of A ⊕ facet of B), edge ⊕ edge, and the
parallel cases facet ⊕ edge and facet ⊕ facet.  Clicking a facet shows its
exact plane a x + b y + c z = d, its provenance and its vertices' exact
coordinates.  With one operand the page shows its counts and exact volume.
docs/viewer.md describes the page.

A non-convex operand must be a closed solid (docs/nonconvex.md; else exit
status 3 and one line naming the problem), such as 'minksum sum' writes for a
non-convex sum: alone it is shown with its faces as given, its counts and
exact volume; with a second operand the page shows A, B and their exact
non-convex sum as 'minksum sum' computes it (the boundary sweep; --method
sums the convex pieces as there), its facets not coloured by provenance.

A VRML scene (docs/vrml.md) with several shapes or with CubicalGaussianMap
nodes, such as 'minksum cgm P Q -o cgm.wrl' writes, is shown whole: every ExactPolyhedron (or IndexedFaceSet) as
a solid, every CubicalGaussianMap as its cube with the six planar maps and
the polytope it encodes beside it.  Every node is checked first (exit
status 3 and one line naming the file, the line and the problem).

Options:
  -o, --output OUT   the page to write (.html); written to a temporary file
                     and renamed when complete
  --method M         the method of the sum ({methods}); walk
                     records every facet's provenance, for the others it is
                     computed afterwards (left out above 2·10^8 vertex tests)
  --hull             take the convex hull of each input file's points
                     (a non-convex solid is shown as it is without it)
  --title T          the page's title (default: the operands' names)
  --json             print the counts (and the sum's facet types) as JSON
)";

// Above this many vertex-against-facet tests the provenance of a method that
// does not record it is not computed (facet_provenance is O(F (V_A + V_B))).
constexpr double kProvenanceBudget = 2e8;

// The page of a VRML scene: data "kind": "scene", "solids" (the polytope
// shapes), "cgms" (per CubicalGaussianMap: "name", "operands" for a sum,
// "maps" as on the page of 'cgm --html', "solid" its polytope).
int view_scene(const Args& a, const LoadedScene& scene, const std::string& output) {
  if (a.value("--method") || a.flag("--hull"))
    throw UsageError(std::string(a.value("--method") ? "--method" : "--hull") + " does not apply to a VRML scene");
  const std::string& file = a.positional[0];
  const std::string title = a.value_or("--title", file);
  std::string data = "{\"kind\": \"scene\", \"title\": " + json_string(title) +
                     ", \"origins\": " + origin_names_json() + ", \"solids\": [";
  std::string shapes_json;
  // What each polytope is in the scene, for its colour and its line in the
  // legend: an operand or the polytope of a CubicalGaussianMap sum, or alone.
  std::vector<std::string> role(scene.polytopes.size(), "polytope"), caption(scene.polytopes.size());
  for (const LoadedCgm& c : scene.cgms) {
    if (c.operand_nodes.size() != 2) continue;
    const std::string sum = (c.polytope_node != kNoNode ? scene.names[c.polytope_node] + " = " : std::string()) +
                            c.operands[0] + " ⊕ " + c.operands[1];
    for (std::size_t k = 0; k < 2; ++k)
      if (caption[c.operand_nodes[k]].empty()) {
        role[c.operand_nodes[k]] = k ? "b" : "a";
        caption[c.operand_nodes[k]] = std::string(k ? "second" : "first") + " operand of " + sum;
      }
    if (c.polytope_node != kNoNode) role[c.polytope_node] = "sum", caption[c.polytope_node] = "the sum " + sum;
  }
  // What the comments of 'minksum sum --scene' say ("# A = cube", "# S = A ⊕ B ⊕ C"): the sum
  // and its operands, in the colours of a sum's page; any other comment as the caption.
  for (std::size_t i = 0; i < scene.polytopes.size(); ++i) {
    const std::string& text = scene.comments[i];
    if (text.empty() || !caption[i].empty()) continue;
    std::vector<std::size_t> terms;
    for (std::size_t at = 0;;) {
      const std::size_t end = text.find(" ⊕ ", at);
      const std::string term = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
      const auto it = std::find(scene.names.begin(), scene.names.end(), term);
      if (it == scene.names.end() || std::size_t(it - scene.names.begin()) == i) {
        terms.clear();
        break;
      }
      terms.push_back(std::size_t(it - scene.names.begin()));
      if (end == std::string::npos) break;
      at = end + std::string(" ⊕ ").size();
    }
    if (terms.size() < 2) {
      caption[i] = text;
      continue;
    }
    const std::string sum = scene.names[i] + " = " + text;
    role[i] = "sum";
    caption[i] = "the sum " + sum;
    static const char* const kOrdinal[] = {"first", "second", "third"};
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const std::size_t t = terms[k];
      if (!caption[t].empty() && role[t] != "polytope") continue;
      role[t] = k ? "b" : "a";
      const std::string which =
          k < 3 ? std::string(kOrdinal[k]) + " operand of " : "operand " + std::to_string(k + 1) + " of ";
      caption[t] = (scene.comments[t].empty() ? std::string() : scene.comments[t] + ", ") + which + sum;
    }
  }
  std::string roles_json;
  bool first = true;
  for (const SceneShape& sh : scene.shapes) {
    if (sh.kind != SceneShape::Kind::polytope) continue;
    if (!first) data += ", ", roles_json += ", ";
    append_solid_json(data, scene.polytopes[sh.index], scene.names[sh.index], role[sh.index]);
    roles_json += "{\"role\": " + json_string(role[sh.index]) + ", \"caption\": " + json_string(caption[sh.index]) + "}";
    first = false;
  }
  data += "], \"roles\": [" + roles_json;
  data += "], \"cgms\": [";
  for (std::size_t i = 0; i < scene.cgms.size(); ++i) {
    const LoadedCgm& c = scene.cgms[i];
    const bool sum = c.operands.size() == 2;
    data += (i ? ", {" : "{") + std::string("\"name\": ") + json_string(c.name);
    if (sum) data += ", \"operands\": [" + json_string(c.operands[0]) + ", " + json_string(c.operands[1]) + "]";
    data += ", \"maps\": ";
    const bool with_origin = sum && c.provenance.size() == c.polytope.num_facets();
    append_cgm_maps_json(data, c.map, with_origin ? &c.provenance : nullptr);
    data += ", \"solid\": ";
    append_solid_json(data, c.polytope, sum ? c.operands[0] + " ⊕ " + c.operands[1] : c.name, sum ? "sum" : "polytope",
                      with_origin ? &c.provenance : nullptr);
    data += "}";
  }
  data += "]}";
  write_page(output, title, data);
  for (const SceneShape& sh : scene.shapes) {
    const bool poly = sh.kind == SceneShape::Kind::polytope;
    const ConvexPolytope& p = poly ? scene.polytopes[sh.index] : scene.cgms[sh.index].polytope;
    const std::string& name = poly ? scene.names[sh.index] : scene.cgms[sh.index].name;
    if (!shapes_json.empty()) shapes_json += ", ";
    shapes_json += "{\"kind\": \"" + std::string(poly ? "polytope" : "cgm") + "\", \"name\": \"" + json_escape(name) +
                   "\", " + counts_json(p) + "}";
  }
  if (a.flag("--json")) {
    std::cout << "{\"page\": \"scene\", \"name\": \"" << json_escape(file) << "\", \"shapes\": [" << shapes_json
              << "], \"output\": \"" << json_escape(output) << "\"}\n";
  } else {
    std::cout << printable(file) << ": a scene of " << scene.shapes.size() << " shapes\n";
    for (const SceneShape& sh : scene.shapes) {
      const bool poly = sh.kind == SceneShape::Kind::polytope;
      const ConvexPolytope& p = poly ? scene.polytopes[sh.index] : scene.cgms[sh.index].polytope;
      std::cout << "  " << (poly ? "polytope " : "CubicalGaussianMap ")
                << printable(poly ? scene.names[sh.index] : scene.cgms[sh.index].name) << ": " << p.num_vertices()
                << " vertices, " << p.num_edges() << " edges, " << p.num_facets() << " facets\n";
    }
    std::cout << "  page written to " << printable(output) << "\n";
  }
  return 0;
}

// The page of one non-convex solid, or of A, B and A ⊕ B when an operand is
// not convex (validated as 'sum' validates it, summed by the boundary sweep).
int view_nonconvex(const Args& a, const std::string& output, const std::vector<Operand>& operands, Method method) {
  const std::vector<std::string>& names = a.positional;
  const bool json = a.flag("--json");
  // A solid's JSON for the page: a convex operand as 'view' shows polytopes.
  auto append_operand = [&](std::string& data, std::size_t i, const std::string& role) {
    if (const ConvexPolytope* p = operands[i].polytope()) append_solid_json(data, *p, names[i], role);
    else append_mesh_solid_json(data, solid_faces(*operands[i].solid()), operands[i].solid()->volume, names[i], role);
  };
  auto counts_of = [&](std::size_t i) {
    const Operand& o = operands[i];
    return MeshCounts{o.num_vertices(), o.num_edges(), o.num_facets()};
  };
  auto counts_text = [](const MeshCounts& c, bool convex) {
    return "\"vertices\": " + std::to_string(c.vertices) + ", \"edges\": " + std::to_string(c.edges) +
           ", \"facets\": " + std::to_string(c.faces) + ", " + kind_json(3, convex ? "polytope" : "solid");
  };
  if (names.size() == 1) {
    const std::string title = a.value_or("--title", names[0]);
    std::string data = "{\"kind\": \"solid\", \"title\": " + json_string(title) + ", \"solids\": [";
    append_operand(data, 0, "polytope");
    data += "]}";
    write_page(output, title, data);
    const MeshCounts c = counts_of(0);
    if (json)
      std::cout << "{\"page\": \"solid\", \"name\": \"" << json_escape(names[0]) << "\", " << counts_text(c, false)
                << ", \"volume\": \"" << format_exact(operands[0].solid()->volume) << "\", \"convex\": false, \"output\": \""
                << json_escape(output) << "\"}\n";
    else
      std::cout << printable(names[0]) << ": " << c.vertices << " vertices, " << c.edges << " edges, " << c.faces
                << " facets, a non-convex solid\n  page written to " << printable(output) << "\n";
    return 0;
  }
  allow_thread_arenas();
  SumRequest request;
  request.method = method;
  OperandSum sum;
  {
    ProgressTicker ticker("minksum view");
    request.options = ticker.sum_options();
    sum = minkowski_sum(operands, request);
  }
  const NonconvexSum& r = std::get<NonconvexSum>(sum.result);
  const std::string sum_name = names[0] + " ⊕ " + names[1];
  const std::string title = a.value_or("--title", sum_name);
  std::string data = "{\"kind\": \"sum\", \"title\": " + json_string(title) +
                     ", \"method\": \"nonconvex\", \"provenance\": \"nonconvex\", \"origins\": " +
                     origin_names_json() + ", \"solids\": [";
  append_operand(data, 0, "a");
  data += ", ";
  append_operand(data, 1, "b");
  data += ", ";
  append_mesh_solid_json(data, r.mesh, r.volume, sum_name, "sum");
  data += "]}";
  write_page(output, title, data);
  const MeshCounts c = mesh_counts(r.mesh);
  if (json) {
    std::cout << "{\"page\": \"sum\", " << counts_text(c, false) << ", \"method\": \"nonconvex\", \"volume\": \""
              << format_exact(r.volume) << "\", \"a\": {\"name\": \"" << json_escape(names[0]) << "\", "
              << counts_text(counts_of(0), std::string(operands[0].kind_name()) == "polytope") << "}, \"b\": {\"name\": \"" << json_escape(names[1])
              << "\", " << counts_text(counts_of(1), std::string(operands[1].kind_name()) == "polytope") << "}, \"output\": \"" << json_escape(output)
              << "\"}\n";
  } else {
    std::cout << printable(sum_name) << " = " << c.vertices << " vertices, " << c.edges << " edges, " << c.faces
              << " facets (non-convex sum, " << r.method << ")\n  page written to " << printable(output) << "\n";
  }
  return 0;
}

}  // namespace

int run_view(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "view",
                            {{"--output", "-o", true}, {"--method", "", true}, {"--hull"}, {"--title", "", true},
                             {"--json"}});
  if (a.help) {
    std::cout << expand_help(kViewHelp);
    return 0;
  }
  if (a.positional.empty() || a.positional.size() > 2)
    throw UsageError("'view' needs one or two operands (see 'minksum view --help')");
  const auto output = a.value("--output");
  if (!output) throw UsageError("'view' needs -o OUT.html (see 'minksum view --help')");
  check_html_path(*output, "--output");
  const std::string method_text = a.value_or("--method", "auto");
  const auto method = parse_method(method_text);
  if (!method) throw UsageError("unknown method '" + method_text + "' (" + method_list() + ")");
  if (a.positional.size() == 1 && a.value("--method"))
    throw UsageError("--method needs two operands A B");
  const bool hull = a.flag("--hull"), json = a.flag("--json");

  std::string data = "{";
  std::string title;
  if (a.positional.size() == 1 && is_scene_file(a.positional[0])) {
    const LoadedScene scene = load_scene(a.positional[0]);
    if (scene.shapes.size() != 1 || scene.shapes[0].kind != SceneShape::Kind::polytope)
      return view_scene(a, scene, *output);
  }
  // Points, segments, polygons (docs/sweeps.md): drawn by cmd_sweep.cpp.
  std::vector<ConvexSet> sets;
  if (!hull) {  // operands that may be non-convex solids (docs/nonconvex.md)
    std::vector<Operand> operands;
    bool convex = true;
    for (const std::string& name : a.positional) {
      operands.push_back(load_command_operand(name, false, std::nullopt));
      convex = convex && !operands.back().solid();
    }
    if (!convex) return view_nonconvex(a, *output, operands, *method);
    for (const Operand& o : operands) sets.push_back(o.to_set());
  }
  {
    for (std::size_t i = 0; hull && i < a.positional.size(); ++i)
      sets.push_back(load_set_operand(a.positional[i], hull, nullptr, std::nullopt));
    bool lower = false;
    for (const ConvexSet& s : sets) lower = lower || !s.full();
    if (lower) {
      std::string names = a.positional[0];
      if (sets.size() == 2) names += " ⊕ " + a.positional[1];
      return view_sets(*output, a.value_or("--title", names), a.positional, sets, *method, json);
    }
  }
  const ConvexPolytope pa = sets[0].polytope();
  if (a.positional.size() == 1) {
    title = a.value_or("--title", a.positional[0]);
    data += "\"kind\": \"polytope\", \"title\": " + json_string(title) + ", \"solids\": [";
    append_solid_json(data, pa, a.positional[0], "polytope");
    data += "]}";
    write_page(*output, title, data);
    if (json)
      std::cout << "{\"page\": \"polytope\", \"name\": \"" << json_escape(a.positional[0]) << "\", " << polytope_json(pa)
                << ", \"volume\": \"" << format_exact(pa.volume()) << "\", \"output\": \"" << json_escape(*output)
                << "\"}\n";
    else
      std::cout << a.positional[0] << ": " << pa.num_vertices() << " vertices, " << pa.num_edges() << " edges, "
                << pa.num_facets() << " facets\n  page written to " << *output << "\n";
    return 0;
  }

  const ConvexPolytope pb = sets[1].polytope();
  SumResult r = [&] {
    ProgressTicker ticker("minksum view");
    return minkowski_sum(pa, pb, *method, ticker.sum_options());
  }();
  const ConvexPolytope& s = r.polytope;
  bool provenance_computed = false;
  if (r.facet_provenance.empty() &&
      double(s.num_facets()) * (double(pa.num_vertices()) + double(pb.num_vertices())) <= kProvenanceBudget) {
    r.facet_provenance = facet_provenance(pa, pb, s);
    provenance_computed = true;
  }
  title = a.value_or("--title", a.positional[0] + " ⊕ " + a.positional[1]);
  data += "\"kind\": \"sum\", \"title\": " + json_string(title) + ", \"method\": \"" + method_name(r.method) +
          "\", \"provenance\": \"" +
          (r.facet_provenance.empty() ? "none" : provenance_computed ? "computed" : "recorded") +
          "\", \"origins\": " + origin_names_json() + ", \"solids\": [";
  append_solid_json(data, pa, a.positional[0], "a");
  data += ", ";
  append_solid_json(data, pb, a.positional[1], "b");
  data += ", ";
  append_solid_json(data, s, a.positional[0] + " ⊕ " + a.positional[1], "sum", &r.facet_provenance);
  data += "]}";
  write_page(*output, title, data);
  if (json) {
    std::cout << "{\"page\": \"sum\", " << polytope_json(s) << ", \"method\": \"" << method_name(r.method)
              << "\", \"volume\": \"" << format_exact(s.volume()) << "\", \"a\": {\"name\": \""
              << json_escape(a.positional[0]) << "\", " << polytope_json(pa) << "}, \"b\": {\"name\": \""
              << json_escape(a.positional[1]) << "\", " << polytope_json(pb) << "}, \"output\": \""
              << json_escape(*output) << "\"}\n";
  } else {
    std::cout << a.positional[0] << " ⊕ " << a.positional[1] << " = " << s.num_vertices() << " vertices, "
              << s.num_edges() << " edges, " << s.num_facets() << " facets (method " << method_name(r.method)
              << ")\n";
    if (r.facet_provenance.empty())
      std::cout << "  provenance not shown: method " << method_name(r.method)
                << " does not record it and computing it would take long (use --method walk)\n";
    std::cout << "  page written to " << *output << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
