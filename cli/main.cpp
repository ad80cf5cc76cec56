// The `minksum` command: parses arguments, calls the library, prints.
//
// Exit status: 0 success, 1 internal error or failed output write,
// 2 bad usage, 3 bad input data.
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/polytope.hpp>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace minksum;

namespace {

constexpr const char* kVersion = "0.1.0";

const char* kMainHelp = R"(minksum — exact Minkowski sums of convex polyhedra in 3D

Usage:
  minksum sum A B [-o OUT] [--method M] [--exact] [--binary] [--json] [--hull]
  minksum stats P [--json] [--hull]
  minksum gen NAME -o OUT [--exact] [--binary]
  minksum COMMAND --help          help on one command
  minksum --version

A, B, P are files (.off .obj .ply .stl .wrl, format by extension) or names of
built-in polytopes such as cube, sphere:4, dioctagonal:17, random:1000:7,
box:1:2:3, sphere:3@rot:5 (see 'minksum gen --help' for the whole catalog).

Every computation is exact: coordinates are rationals, every geometric
decision is the sign of an exact polynomial.

Exit status: 0 success, 1 internal error or output not writable,
2 bad usage, 3 bad input data (one line on stderr names the file, the place
and the problem).
)";

const char* kSumHelp = R"(Usage: minksum sum A B [options]

Compute the Minkowski sum A ⊕ B = { a + b : a in A, b in B } exactly and print
a summary (or JSON).  A and B are files or catalog names.

Options:
  -o, --output OUT   write the sum to OUT (.off .obj .ply .stl .wrl); the file
                     is written to a temporary name and renamed when complete
  --method M         auto (default), chms, cvms, walk, essdms, mssd, cgm.
                     chms: exact convex hull of all pairwise vertex sums, the
                     reference oracle.  cvms: contributing vertices (Barki et
                     al.), reports the facet types (translated, corner, edge,
                     facet_edge, facet_facet) with --json.  Methods not built
                     into this version are refused with exit status 2.
  --exact            write coordinates as exact rationals (p/q or integers);
                     default: shortest text that reads back to the nearest
                     double.  Only .off, .obj and .wrl can hold rationals.
  --binary           binary .ply / .stl output
  --hull             take the convex hull of each input file's points instead
                     of requiring a valid convex mesh (point clouds)
  --json             print one JSON object: vertices, edges, facets, method,
                     seconds (the computation alone, not the I/O), volume
                     (exact rational as a string), and the operands' counts
)";

const char* kStatsHelp = R"(Usage: minksum stats P [--json] [--hull]

Validate P (file or catalog name) and print its numbers of vertices, edges and
facets (coplanar facets merged), its exact volume, and whether every
coordinate is exactly a double.  With --hull, P's points are a point cloud and
the statistics are those of its exact convex hull.
)";

const char* kGenHelpHead = R"(Usage: minksum gen NAME -o OUT [--exact] [--binary]

Write a built-in polytope to OUT (.off .obj .ply .stl .wrl).  Use --exact for
rational coordinates (rotated solids have them); without it coordinates are
written as the nearest doubles.

Catalog (names are accepted anywhere a file path is):
)";

struct Args {
  std::vector<std::string> positional;
  std::string output;
  std::string method = "auto";
  bool exact = false, json = false, hull = false, binary = false, help = false;
};

Args parse_args(const std::vector<std::string>& argv, const std::string& command) {
  Args a;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    std::string s = argv[i];
    std::string value;
    bool has_value = false;
    if (s.rfind("--", 0) == 0) {
      if (auto eq = s.find('='); eq != std::string::npos) {
        value = s.substr(eq + 1);
        s = s.substr(0, eq);
        has_value = true;
      }
    }
    auto take = [&](const char* opt) {
      if (has_value) return value;
      if (i + 1 >= argv.size()) throw UsageError(std::string(opt) + " needs a value");
      return argv[++i];
    };
    if (s == "-h" || s == "--help") a.help = true;
    else if (s == "-o" || s == "--output") a.output = take("--output");
    else if (s == "--method") a.method = take("--method");
    else if (s == "--exact") a.exact = true;
    else if (s == "--json") a.json = true;
    else if (s == "--hull") a.hull = true;
    else if (s == "--binary") a.binary = true;
    else if (s.size() > 1 && s[0] == '-' && !(s.size() > 1 && (std::isdigit((unsigned char)s[1]))))
      throw UsageError("unknown option '" + argv[i] + "' for '" + command + "' (see 'minksum " + command +
                       " --help')");
    else a.positional.push_back(argv[i]);
  }
  return a;
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string counts_json(const ConvexPolytope& p) {
  std::ostringstream o;
  o << "\"vertices\": " << p.num_vertices() << ", \"edges\": " << p.num_edges()
    << ", \"facets\": " << p.num_facets();
  return o.str();
}

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

// Check the output path before any long computation (bad usage fails fast).
void check_output(const Args& a) {
  if (a.output.empty()) return;
  auto f = format_from_path(a.output);
  if (!f) throw UsageError("cannot tell the format of '" + a.output + "': use .off, .obj, .ply, .stl or .wrl");
  if (a.exact && (*f == Format::ply || *f == Format::stl))
    throw UsageError(std::string("--exact: ") + format_name(*f) +
                     " cannot store exact rationals; use .off, .obj or .wrl");
}

// A failed write is not bad input: it exits with status 1.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void write_output(const Args& a, const ConvexPolytope& p) {
  WriteOptions w;
  w.exact = a.exact;
  w.binary = a.binary;
  if (!a.exact && !p.coordinates_are_doubles())
    std::cerr << "minksum: note: " << a.output
              << ": some coordinates are not doubles and are written rounded to the nearest double "
                 "(facets may no longer be exactly planar); use --exact to keep them exact\n";
  try {
    write_mesh(a.output, p.to_mesh(), w);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
}

int cmd_sum(const Args& a) {
  if (a.help) {
    std::cout << kSumHelp;
    return 0;
  }
  if (a.positional.size() != 2)
    throw UsageError("'sum' needs two operands A B (see 'minksum sum --help')");
  auto method = parse_method(a.method);
  if (!method)
    throw UsageError("unknown method '" + a.method + "' (auto, walk, cvms, essdms, mssd, chms, cgm)");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) +
                     "' is not implemented in this version of minksum (available: auto, chms)");
  check_output(a);
  ConvexPolytope pa = load_polytope(a.positional[0], a.hull);
  ConvexPolytope pb = load_polytope(a.positional[1], a.hull);
  SumResult r = minkowski_sum(pa, pb, *method);
  if (!a.output.empty()) write_output(a, r.polytope);
  const ConvexPolytope& s = r.polytope;
  if (a.json) {
    Rational vol = s.volume();
    std::cout << "{" << counts_json(s) << ", \"method\": \"" << method_name(r.method) << "\""
              << ", \"seconds\": " << format_double(r.seconds) << ", \"volume\": \"" << format_exact(vol)
              << "\", \"volume_double\": " << format_double(to_double(vol)) << facet_types_json(r) << ", \"a\": {\"name\": \""
              << json_escape(a.positional[0]) << "\", " << counts_json(pa) << "}, \"b\": {\"name\": \""
              << json_escape(a.positional[1]) << "\", " << counts_json(pb) << "}, \"output\": ";
    if (a.output.empty()) std::cout << "null"; else std::cout << "\"" << json_escape(a.output) << "\"";
    std::cout << "}\n";
  } else {
    std::cout << a.positional[0] << " (" << pa.num_vertices() << " V, " << pa.num_facets() << " F) ⊕ "
              << a.positional[1] << " (" << pb.num_vertices() << " V, " << pb.num_facets() << " F)\n"
              << "  = " << s.num_vertices() << " vertices, " << s.num_edges() << " edges, "
              << s.num_facets() << " facets\n"
              << "  method " << method_name(r.method) << ", " << format_double(r.seconds) << " s\n";
    if (!a.output.empty()) std::cout << "  written to " << a.output << "\n";
  }
  return 0;
}

int cmd_stats(const Args& a) {
  if (a.help) {
    std::cout << kStatsHelp;
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'stats' needs one operand (see 'minksum stats --help')");
  ConvexPolytope p = load_polytope(a.positional[0], a.hull);
  Rational vol = p.volume();
  Index max_fdeg = 0, max_vdeg = 0;
  for (Index f = 0; f < p.num_facets(); ++f) max_fdeg = std::max(max_fdeg, p.facet_degree(f));
  for (Index v = 0; v < p.num_vertices(); ++v) max_vdeg = std::max(max_vdeg, p.vertex_degree(v));
  if (a.json) {
    std::cout << "{\"name\": \"" << json_escape(a.positional[0]) << "\", " << counts_json(p)
              << ", \"volume\": \"" << format_exact(vol) << "\", \"volume_double\": "
              << format_double(to_double(vol)) << ", \"max_facet_degree\": " << max_fdeg
              << ", \"max_vertex_degree\": " << max_vdeg << ", \"coordinates_are_doubles\": "
              << (p.coordinates_are_doubles() ? "true" : "false") << "}\n";
  } else {
    std::cout << a.positional[0] << ": " << p.num_vertices() << " vertices, " << p.num_edges() << " edges, "
              << p.num_facets() << " facets\n"
              << "  volume " << format_double(to_double(vol));
    if (!is_double(vol)) std::cout << " (exactly " << format_exact(vol) << ")";
    std::cout << "\n  largest facet has " << max_fdeg << " vertices, largest vertex degree " << max_vdeg
              << "\n  coordinates: " << (p.coordinates_are_doubles() ? "all exact doubles" : "exact rationals")
              << "\n";
  }
  return 0;
}

int cmd_gen(const Args& a) {
  if (a.help) {
    std::cout << kGenHelpHead;
    for (const auto& e : catalog_entries()) {
      std::string syn = e.syntax;
      if (syn.size() < 22) syn.resize(22, ' ');
      std::cout << "  " << syn << " " << e.description << "\n";
    }
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("'gen' needs one catalog name (see 'minksum gen --help')");
  if (a.output.empty()) throw UsageError("'gen' needs -o OUT");
  check_output(a);
  if (!is_catalog_spec(a.positional[0]))
    throw UsageError("'" + a.positional[0] + "' is not a catalog name (see 'minksum gen --help')");
  ConvexPolytope p = catalog_polytope(a.positional[0]);
  write_output(a, p);
  std::cout << a.positional[0] << ": " << p.num_vertices() << " vertices, " << p.num_edges() << " edges, "
            << p.num_facets() << " facets, written to " << a.output << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::ios::sync_with_stdio(false);
  std::string command;
  try {
    if (args.empty()) {
      std::cerr << kMainHelp;
      return 2;
    }
    command = args[0];
    std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "-h" || command == "--help" || command == "help") {
      if (!rest.empty()) {
        Args h;
        h.help = true;
        if (rest[0] == "sum") return cmd_sum(h);
        if (rest[0] == "stats") return cmd_stats(h);
        if (rest[0] == "gen") return cmd_gen(h);
      }
      std::cout << kMainHelp;
      return 0;
    }
    if (command == "--version" || command == "version") {
      std::cout << "minksum " << kVersion << "\n";
      return 0;
    }
    if (command == "sum") return cmd_sum(parse_args(rest, command));
    if (command == "stats") return cmd_stats(parse_args(rest, command));
    if (command == "gen") return cmd_gen(parse_args(rest, command));
    throw UsageError("unknown command '" + command + "' (sum, stats, gen; see 'minksum --help')");
  } catch (const UsageError& e) {
    std::cerr << "minksum: " << e.what() << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "minksum: " << e.what() << "\n";
    return 3;
  } catch (const OutputError& e) {
    std::cerr << "minksum: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "minksum: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "minksum: internal error: " << e.what() << "\n";
    return 1;
  }
}
