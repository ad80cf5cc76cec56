// minksum batch: many independent Minkowski sums on a pool of threads.
#include <minksum/parallel.hpp>
#include <minksum/sum.hpp>

#include <cstddef>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "json_object.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {

const char* kBatchHelp = R"(Usage: minksum batch [FILE] [options]

Compute many Minkowski sums A ⊕ B, independently, on several threads, and
print one JSON line per pair, in input order.  FILE (default, or "-":
standard input) holds one pair per line, either as a JSON object
    {"a": "cube", "b": "sphere:3", "method": "walk", "hull": false}
("method" and "hull" optional: --method and --hull give the defaults) or as
two names separated by white space
    parts/gear.off tools/ball.stl
A and B are files ({formats}) or catalog names, as for 'minksum sum': convex
polytopes, points, segments and flat polygons (docs/sweeps.md), or closed
solids that are not convex (docs/nonconvex.md; each such sum on one thread,
the pairs in parallel).  Empty
lines and lines starting with '#' are skipped; nothing but white space may
follow a JSON object, and no line may hold a NUL byte.

Options:
  --threads N        compute on N threads (default: one per hardware thread)
  --method M         {methods}.
                     All are exact and give the same polytope.
  --hull             take the convex hull of each input file's points

Output, one line per pair:
  {"line": 1, "a": "cube", "b": "sphere:3", "method": "walk", "vertices": V,
   "edges": E, "facets": F, "dimension": 3, "kind": "polytope", "volume": "p/q",
   "volume_double": x, "seconds": s}
with the result's dimension and kind as 'minksum sum' reports them (a
sum with a non-convex solid: "method": "nonconvex", "kind": "solid", its
boundary's vertices, edges and faces).  volume is exact (an integer or p/q);
seconds is the sum's computation alone.
A pair that fails (a missing or bad file, an unknown catalog name) gets
  {"line": 3, "a": "...", "b": "...", "error": "FILE: PLACE: PROBLEM", "status": 3}
(status 3: bad input data, 2: bad usage) and the other pairs go on.  Every
line is valid JSON whatever the names hold: control characters are escaped
(\n, \t, \uXXXX), and a byte that is not UTF-8 becomes U+FFFD.

Exit status: 0 when every pair succeeded; otherwise 3 if a pair had bad input
data, else 2, with one line on stderr counting the failed pairs and naming
the first (control characters and bytes that are not UTF-8 escaped, as in
every message).  A malformed line of FILE itself (bad JSON, a missing "a") is bad
input: exit status 3 before anything is computed, nothing printed.
)";

struct Pair {
  std::size_t line = 0;
  std::string a, b;
  Method method = Method::automatic;
  bool hull = false;
};

struct Outcome {
  std::string json;  // the line's fields after "line", "a", "b"
  int status = 0;    // 0, 2 or 3
  std::string error;
};

Method method_of(const std::string& text) {
  auto m = parse_method(text);
  if (!m) throw UsageError("unknown method '" + text + "' (" + method_list() + ")");
  if (!method_available(*m))
    throw UsageError(std::string("method '") + method_name(*m) + "' is not implemented in this version of minksum");
  return *m;
}

// The pairs of FILE, every line checked before anything is computed.
std::vector<Pair> read_pairs(std::istream& in, const std::string& file, Method method, bool hull) {
  std::vector<Pair> pairs;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    Pair p;
    p.line = line;
    p.method = method;
    p.hull = hull;
    JsonObjectParser parser(text, file, "line " + std::to_string(line));
    if (text[first] == '{') {
      bool has_a = false, has_b = false;
      for (const auto& [key, value, is_string] : parser.object()) {
        if ((key == "a" || key == "b" || key == "method") && (!is_string || value.empty()))
          parser.fail("\"" + key + "\" must be a non-empty string");
        if (key == "a" || key == "b") {
          (key == "a" ? p.a : p.b) = value;
          (key == "a" ? has_a : has_b) = true;
        } else if (key == "method") {
          auto m = parse_method(value);
          if (!m || !method_available(*m)) parser.fail("unknown method '" + value + "' (" + method_list() + ")");
          p.method = *m;
        } else if (key == "hull") {
          if (is_string) parser.fail("\"hull\" must be true or false");
          p.hull = value == "true";
        } else {
          parser.fail("unknown key \"" + key + "\" (a, b, method, hull)");
        }
      }
      if (!has_a || !has_b) parser.fail(std::string("missing \"") + (has_a ? "b" : "a") + "\"");
    } else {
      // No name holds a NUL byte (the JSON form refuses it too).
      if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
        parser.fail("a NUL byte at column " + std::to_string(nul + 1));
      std::istringstream words(text);
      std::string extra;
      if (!(words >> p.a >> p.b)) parser.fail("expected two names A B or a JSON object");
      if (words >> extra) parser.fail("more than two names (a name with spaces needs the JSON form)");
    }
    pairs.push_back(std::move(p));
  }
  if (in.bad()) throw InputError(file, "", "read error");
  return pairs;
}

Outcome compute(const Pair& p) {
  Outcome o;
  try {
    // Any kind of operand (<minksum/sum.hpp>): convex polytopes, points,
    // segments, polygons, closed solids; the pairs already run in parallel.
    std::vector<Operand> operands;
    operands.push_back(Operand::load(p.a, {p.hull, std::nullopt, {}}));
    operands.push_back(Operand::load(p.b, {p.hull, std::nullopt, {}}));
    SumRequest request;
    request.method = p.method;
    request.threads = 1;
    request.provenance = false;
    const SumReport r = minkowski_sum(operands, request).report;
    const Rational volume = r.volume ? *r.volume : Rational(0);
    o.json = ", \"method\": \"" + json_escape(r.method) + "\", \"vertices\": " + std::to_string(r.vertices) +
             ", \"edges\": " + std::to_string(r.edges) + ", \"facets\": " + std::to_string(r.facets) + ", " +
             kind_json(r.dimension, r.kind) + ", \"volume\": \"" + format_exact(volume) +
             "\", \"volume_double\": " + json_number(to_double(volume)) + ", \"seconds\": " + json_number(r.seconds);
  } catch (const InputError& e) {
    o.status = 3;
    o.error = e.what();
  } catch (const UsageError& e) {
    o.status = 2;
    o.error = e.what();
  }
  if (o.status) o.json = ", \"error\": \"" + json_escape(o.error) + "\", \"status\": " + std::to_string(o.status);
  return o;
}

}  // namespace

int run_batch(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "batch", {{"--threads", "", true}, {"--method", "", true}, {"--hull"}});
  if (a.help) {
    std::cout << expand_help(kBatchHelp);
    return 0;
  }
  if (a.positional.size() > 1) throw UsageError("'batch' reads one FILE (see 'minksum batch --help')");
  const Method method = method_of(a.value_or("--method", "auto"));
  unsigned threads = 0;
  if (auto t = a.value("--threads")) {
    std::size_t used = 0;
    long n = 0;
    try {
      n = std::stol(*t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != t->size() || n < 1 || n > 1024) throw UsageError("--threads needs a whole number from 1 to 1024");
    threads = static_cast<unsigned>(n);
  }
  const std::string file = a.positional.empty() ? "-" : a.positional[0];
  std::vector<Pair> pairs;
  if (file == "-") {
    pairs = read_pairs(std::cin, "<stdin>", method, a.flag("--hull"));
  } else {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file, "", "cannot open the file");
    pairs = read_pairs(in, file, method, a.flag("--hull"));
  }

  std::vector<Outcome> outcomes(pairs.size());
  parallel_for(pairs.size(), threads, [&](std::size_t i) { outcomes[i] = compute(pairs[i]); });

  std::size_t failed = 0;
  int status = 0;
  const Outcome* first = nullptr;
  const Pair* first_pair = nullptr;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const Outcome& o = outcomes[i];
    std::cout << "{\"line\": " << p.line << ", \"a\": \"" << json_escape(p.a) << "\", \"b\": \"" << json_escape(p.b)
              << "\"" << o.json << "}\n";
    if (o.status) {
      ++failed;
      status = std::max(status, o.status);
      if (!first) first = &o, first_pair = &p;
    }
  }
  std::cout.flush();
  if (!std::cout) throw OutputError("cannot write the results to standard output");
  // The names in it are escaped as in every message (printable): no control
  // character or byte that is not UTF-8 reaches the terminal.
  if (first)
    std::cerr << "minksum: batch: " << failed << " of " << pairs.size() << " pairs failed; the first, "
              << printable(file == "-" ? "<stdin>" : file) << " line " << first_pair->line << ": "
              << printable(first->error) << "\n";
  return status;
}

}  // namespace minksum::cli
