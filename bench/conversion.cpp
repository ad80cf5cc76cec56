// minksum bench_conversion — the walk against the conversion of its result
// (to_polytope: explicit exact coordinates), side by side on the same pairs.
//
//   bench_conversion [--runs N] A B [A B ...]
//
// For each pair (operands named as on the command line: catalog names or
// files), N rounds of: one minkowski_walk, then one to_polytope of its
// result, alternating so that both see the same machine load.  Prints one
// Markdown row per pair: the sum's vertex count, the median seconds of the
// walk and of the conversion, their ratio, and the first conversion alone
// (the one minkowski_sum makes on fresh operands).
#include <minksum/operand.hpp>
#include <minksum/walk.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "timer.hpp"

using namespace minksum;
using minksum::bench::Stopwatch;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

int usage(const char* why) {
  std::fprintf(stderr, "bench_conversion: %s\nusage: bench_conversion [--runs N] A B [A B ...]\n", why);
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  int runs = 21;
  std::vector<std::string> specs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs") {
      if (i + 1 == argc) return usage("--runs needs a number");
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end || n < 1 || n > 100000) return usage("--runs must be a whole number from 1 to 100000");
      runs = int(n);
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "bench_conversion [--runs N] A B [A B ...]\n"
          "  For each pair of operands (catalog names or files): N alternating rounds of the walk\n"
          "  (minkowski_walk) and of the conversion of its result to a ConvexPolytope with exact\n"
          "  coordinates (to_polytope); prints median seconds of each and their ratio (default N = 21).\n");
      return 0;
    } else {
      specs.push_back(a);
    }
  }
  if (specs.empty() || specs.size() % 2) return usage("give operands in pairs");
  try {
    std::printf("| A | B | vertices of A ⊕ B | walk (s) | conversion (s) | conversion ÷ walk | first conversion (s) |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|\n");
    for (std::size_t k = 0; k < specs.size(); k += 2) {
      const ConvexPolytope a = load_polytope(specs[k]), b = load_polytope(specs[k + 1]);
      std::vector<double> walk, conv;
      double first = 0;
      Index nv = 0;
      for (int r = 0; r < runs; ++r) {
        Stopwatch sw;
        const WalkSum w = minkowski_walk(a, b);
        walk.push_back(sw.seconds());
        Stopwatch sc;
        const ConvexPolytope p = to_polytope(w, a, b);
        conv.push_back(sc.seconds());
        if (r == 0) first = conv.back();
        nv = p.num_vertices();
        if (nv != w.num_vertices()) throw std::logic_error("to_polytope changed the vertex count");
      }
      const double mw = median(walk), mc = median(conv);
      std::printf("| %s | %s | %u | %.2e | %.2e | %.2f | %.2e |\n", specs[k].c_str(), specs[k + 1].c_str(),
                  unsigned(nv), mw, mc, mc / mw, first);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_conversion: %s\n", e.what());
    return 1;
  }
  return 0;
}
