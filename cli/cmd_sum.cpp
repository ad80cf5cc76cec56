// minksum sum A B: the Minkowski sum.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <chrono>
#include <iostream>
#include <map>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace minksum::cli {

namespace {

const char* kSumHelp = R"(Usage: minksum sum A B [options]

Compute the Minkowski sum A ⊕ B = { a + b : a in A, b in B } exactly and print
a summary (or JSON).  A and B are files or catalog names.

Options:
  -o, --output OUT   write the sum to OUT ({formats}); the file
                     is written to a temporary name and renamed when complete
  --method M         {methods}.
{method_summaries}
                     All are exact and give the same polytope.
  --exact            write coordinates as exact rationals (p/q or integers);
                     default: shortest text that reads back to the nearest
                     double.  Only {exact_formats} can hold rationals.
  --binary           binary {binary_formats} output
  --hull             take the convex hull of each input file's points instead
                     of requiring a valid convex mesh (point clouds)
  --json             print one JSON object: vertices, edges, facets, method,
                     seconds (the computation alone, not the I/O), phases
                     (seconds spent reading both operands, validating them,
                     computing the sum, making its explicit polytope, and
                     writing OUT), volume (exact rational as a string), and
                     the operands' counts

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

}  // namespace

int run_sum(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "sum",
                            {{"--output", "-o", true}, {"--method", "", true}, {"--exact"}, {"--binary"},
                             {"--json"}, {"--hull"}});
  if (a.help) {
    std::cout << expand_help(kSumHelp);
    return 0;
  }
  if (a.positional.size() != 2)
    throw UsageError("'sum' needs two operands A B (see 'minksum sum --help')");
  const std::string method_text = a.value_or("--method", "auto");
  const std::string output = a.value_or("--output", "");
  const bool exact = a.flag("--exact"), json = a.flag("--json"), hull = a.flag("--hull");
  auto method = parse_method(method_text);
  if (!method)
    throw UsageError("unknown method '" + method_text + "' (" + method_list() + ")");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) + "' is not implemented in this version of minksum");
  check_output_path(output, exact);
  LoadPhases la, lb;
  ConvexPolytope pa = load_operand(a.positional[0], hull, &la);
  ConvexPolytope pb = load_operand(a.positional[1], hull, &lb);
  SumResult r = [&] {
    ProgressTicker ticker("minksum sum");  // a progress line on a terminal after 1 s; erased when done
    return minkowski_sum(pa, pb, *method, ticker.sum_options());
  }();
  const auto w0 = std::chrono::steady_clock::now();
  if (!output.empty()) write_output(output, r.polytope, exact, a.flag("--binary"));
  const double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  const ConvexPolytope& s = r.polytope;
  if (json) {
    Rational vol = s.volume();
    std::cout << "{" << counts_json(s) << ", \"method\": \"" << method_name(r.method) << "\""
              << ", \"seconds\": " << json_number(r.seconds) << ", \"phases\": {\"read\": "
              << json_number(la.read + lb.read) << ", \"validate\": " << json_number(la.validate + lb.validate)
              << ", \"sum\": " << json_number(r.seconds - r.explicit_seconds)
              << ", \"explicit\": " << json_number(r.explicit_seconds) << ", \"write\": " << json_number(write_seconds)
              << "}, \"volume\": \"" << format_exact(vol)
              << "\", \"volume_double\": " << json_number(to_double(vol)) << facet_types_json(r) << method_detail_json(r)
              << ", \"a\": {\"name\": \"" << json_escape(a.positional[0]) << "\", " << counts_json(pa)
              << "}, \"b\": {\"name\": \"" << json_escape(a.positional[1]) << "\", " << counts_json(pb)
              << "}, \"output\": ";
    if (output.empty()) std::cout << "null"; else std::cout << "\"" << json_escape(output) << "\"";
    std::cout << "}\n";
  } else {
    std::cout << printable(a.positional[0]) << " (" << pa.num_vertices() << " V, " << pa.num_facets() << " F) ⊕ "
              << printable(a.positional[1]) << " (" << pb.num_vertices() << " V, " << pb.num_facets() << " F)\n"
              << "  = " << s.num_vertices() << " vertices, " << s.num_edges() << " edges, "
              << s.num_facets() << " facets\n"
              << "  method " << method_name(r.method) << ", " << format_double(r.seconds) << " s\n";
    if (!output.empty()) std::cout << "  written to " << printable(output) << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
