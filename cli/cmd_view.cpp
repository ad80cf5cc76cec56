// minksum view: one self-contained HTML page showing a polytope, or two
// operands and their Minkowski sum, in 3D (cli/page.hpp, web/src/viewer.js).
#include <minksum/operand.hpp>

#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "page.hpp"
#include "progress.hpp"
#include "sweep.hpp"

namespace minksum::cli {

namespace {

const char* kViewHelp = R"(Usage: minksum view A [B] -o OUT.html [--method M] [--hull] [--title T] [--json]

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

Options:
  -o, --output OUT   the page to write (.html); written to a temporary file
                     and renamed when complete
  --method M         the method of the sum ({methods}); walk
                     records every facet's provenance, for the others it is
                     computed afterwards (left out above 2·10^8 vertex tests)
  --hull             take the convex hull of each input file's points
  --title T          the page's title (default: the operands' names)
  --json             print the counts (and the sum's facet types) as JSON
)";

// Above this many vertex-against-facet tests the provenance of a method that
// does not record it is not computed (facet_provenance is O(F (V_A + V_B))).
constexpr double kProvenanceBudget = 2e8;

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
  // Points, segments, polygons (docs/sweeps.md): drawn by cmd_sweep.cpp.
  std::vector<ConvexSet> sets;
  {
    for (const std::string& name : a.positional) sets.push_back(load_set_operand(name, hull, nullptr, std::nullopt));
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
      std::cout << "{\"kind\": \"polytope\", \"name\": \"" << json_escape(a.positional[0]) << "\", " << counts_json(pa)
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
    std::cout << "{\"kind\": \"sum\", " << counts_json(s) << ", \"method\": \"" << method_name(r.method)
              << "\", \"volume\": \"" << format_exact(s.volume()) << "\", \"a\": {\"name\": \""
              << json_escape(a.positional[0]) << "\", " << counts_json(pa) << "}, \"b\": {\"name\": \""
              << json_escape(a.positional[1]) << "\", " << counts_json(pb) << "}, \"output\": \""
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
