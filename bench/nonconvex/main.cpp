// bench_nonconvex: A ⊕ B for non-convex A, minksum (minkowski_sum_nonconvex)
// and CGAL's Nef minkowski_sum_3 on the same exact inputs, one after the
// other in this process; prints a Markdown table (docs/nonconvex.md).
// Usage: bench_nonconvex [A:B ...]   (catalog specs; default: the table's rows)
#include <minksum/catalog.hpp>
#include <minksum/nonconvex.hpp>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

using namespace minksum;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> rows;
  for (int i = 1; i < argc; ++i) rows.push_back(argv[i]);
  if (rows.empty())
    rows = {"tube:sphere:1@scale:1/4", "tube:sphere:2@scale:1/4", "tube:sphere:3@scale:1/4",
            "lshape:sphere:2@scale:1/4", "gear:8:cube@scale:1/16@rot:3", "tube:lshape@scale:1/4@rot:7"};
  std::printf("| A ⊕ B | V(B) | pieces | pairs | minksum s (decompose / pairs / union / boundary) | CGAL minkowski_sum_3 s | "
              "ratio | same volume |\n|---|---|---|---|---|---|---|---|\n");
  for (const std::string& row : rows) {
    // "A:B" where A is a catalog name without ':' parameters or with one; split at the
    // first ':' that starts a catalog name.
    std::size_t cut = std::string::npos;
    for (std::size_t at = row.find(':'); at != std::string::npos; at = row.find(':', at + 1))
      if (is_catalog_spec(row.substr(at + 1)) && !std::isdigit(static_cast<unsigned char>(row[at + 1]))) {
        cut = at;
        break;
      }
    if (cut == std::string::npos) {
      std::fprintf(stderr, "bench_nonconvex: '%s' is not A:B\n", row.c_str());
      return 2;
    }
    const std::string a = row.substr(0, cut), b = row.substr(cut + 1);
    const Solid sa = validate_solid(catalog_mesh(a), a), sb = validate_solid(catalog_mesh(b), b);
    auto t = Clock::now();
    const NonconvexSum r = minkowski_sum_nonconvex(sa, sb);
    const double ours = since(t);
    double cgal = 0;
    const Mesh m = reference_minkowski_sum(sa, sb, &cgal);
    std::printf("| %s ⊕ %s | %zu | %zu + %zu | %zu | %.3f (%.3f / %.3f / %.3f / %.3f) | %.3f | %.1f× | %s |\n", a.c_str(),
                b.c_str(), sb.vertices, r.pieces_a, r.pieces_b, r.pairs, ours, r.seconds_decompose, r.seconds_pairs,
                r.seconds_union, r.seconds_boundary, cgal, cgal / ours, mesh_volume(m) == r.volume ? "yes" : "NO");
    std::fflush(stdout);
  }
  std::printf("\n%u hardware threads.\n", std::thread::hardware_concurrency());
  return 0;
}
