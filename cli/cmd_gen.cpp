// minksum gen NAME -o OUT: write a catalog polytope.
#include <minksum/catalog.hpp>

#include <iostream>

#include "commands.hpp"
#include "common.hpp"

namespace minksum::cli {

namespace {
const char* kGenHelpHead = R"(Usage: minksum gen NAME -o OUT [--exact] [--binary]

Write a built-in polytope to OUT ({formats}).  Use --exact for
rational coordinates (rotated solids have them); without it coordinates are
written as the nearest doubles.

Catalog (names are accepted anywhere a file path is):
)";

}  // namespace

int run_gen(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "gen", {{"--output", "-o", true}, {"--exact"}, {"--binary"}});
  if (a.help) {
    std::cout << expand_help(kGenHelpHead);
    for (const auto& e : catalog_entries()) {
      std::string syn = e.syntax;
      if (syn.size() < 22) syn.resize(22, ' ');
      std::cout << "  " << syn << " " << e.description << "\n";
    }
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'gen' needs one catalog name (see 'minksum gen --help')");
  const std::string output = a.value_or("--output", "");
  if (output.empty()) throw UsageError("'gen' needs -o OUT");
  check_output_path(output, a.flag("--exact"));
  if (!is_catalog_spec(a.positional[0]))
    throw UsageError("'" + a.positional[0] + "' is not a catalog name (see 'minksum gen --help')");
  ConvexPolytope p = catalog_polytope(a.positional[0]);
  write_output(output, p, a.flag("--exact"), a.flag("--binary"));
  std::cout << printable(a.positional[0]) << ": " << p.num_vertices() << " vertices, " << p.num_edges() << " edges, "
            << p.num_facets() << " facets, written to " << printable(output) << "\n";
  return 0;
}

}  // namespace minksum::cli
