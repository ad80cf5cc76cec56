// bench_nonconvex: A ⊕ B for non-convex A, minksum (minkowski_sum_nonconvex)
// and CGAL's Nef minkowski_sum_3 on the same exact inputs, one after the
// other in this process; prints a Markdown table (docs/nonconvex.md).
//
// Usage: bench_nonconvex [--json] [--side both|minksum|cgal] [--reps R] [--operation sum|erode] [A:B | A|B ...]
//          bench_nonconvex --check FILE
//   A:B      catalog specs (default: the table's rows)
//   A|B      each a catalog spec or a mesh file (.off .obj .ply .stl .wrl)
//   --json   one JSON object per row and line instead of the table, with the
//            exact volume and the boundary's counts (bench/nonconvex/run.py
//            reads it)
//   --side   time only minksum or only CGAL (run.py runs CGAL in a process of
//            its own, under a time limit)
//   --reps   minksum's sum R times, the median reported (default 1); CGAL
//            runs once
//   --operation  sum (default: A ⊕ B; CGAL's minkowski_sum_3) or erode
//            (A ⊖ B for a convex B: minksum's erode, CGAL's
//            reference_erosion, A minus minkowski_sum_3(box − A, −B))
//   --check  the independent check of a written sum: FILE read by minksum's
//            reader, then CGAL's Polygon_mesh_processing on a Surface_mesh of
//            exact points (is_closed, does_self_intersect,
//            is_outward_oriented, volume); one JSON line:
//            {"closed": ..., "self_intersects": ..., "outward": ...,
//             "volume": "p/q", "vertices": V, "triangles": F}
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/nonconvex.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <filesystem>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

using namespace minksum;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// "A:B" where A is a catalog name without ':' parameters or with some; split
// at the first ':' that starts a catalog name.
bool split_row(const std::string& row, std::string& a, std::string& b) {
  for (std::size_t at = row.find(':'); at != std::string::npos; at = row.find(':', at + 1))
    if (is_catalog_spec(row.substr(at + 1)) && !std::isdigit(static_cast<unsigned char>(row[at + 1]))) {
      a = row.substr(0, at);
      b = row.substr(at + 1);
      return true;
    }
  return false;
}

void json_string(const std::string& s);

// "A|B": each side a catalog spec or a file.
bool split_files(const std::string& row, std::string& a, std::string& b) {
  const std::size_t at = row.find('|');
  if (at == std::string::npos || row.find('|', at + 1) != std::string::npos) return false;
  a = row.substr(0, at);
  b = row.substr(at + 1);
  return !a.empty() && !b.empty();
}

Mesh operand_mesh(const std::string& spec) {
  if (std::filesystem::is_regular_file(spec)) return read_mesh(spec);
  return catalog_mesh(spec);
}

// --check FILE (see the usage above).
int check(const std::string& path) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  namespace PMP = CGAL::Polygon_mesh_processing;
  const Mesh m = read_mesh(path);
  std::vector<K::Point_3> points;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3 p = m.points[i];
    points.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
  }
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& f : m.faces) polygons.emplace_back(f.begin(), f.end());
  CGAL::Surface_mesh<K::Point_3> sm;
  const bool soup_ok = PMP::is_polygon_soup_a_polygon_mesh(polygons);
  if (soup_ok) PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  const bool closed = soup_ok && CGAL::is_closed(sm);
  const bool triangles = soup_ok && CGAL::is_triangle_mesh(sm);
  const bool intersects = !triangles || PMP::does_self_intersect(sm);
  const bool outward = closed && PMP::is_outward_oriented(sm);
  std::printf("{\"closed\": %s, \"self_intersects\": %s, \"outward\": %s, \"volume\": ", closed ? "true" : "false",
              intersects ? "true" : "false", outward ? "true" : "false");
  if (closed && triangles) {
    const K::FT v = PMP::volume(sm);
    const auto& e = CGAL::exact(v);
    json_string(format_exact(Rational(e)));
  } else {
    std::printf("null");
  }
  std::printf(", \"vertices\": %zu, \"triangles\": %zu}\n", m.points.size(), m.faces.size());
  return std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : 1;
}

// The minksum side of one row: R sums, the one of median time.
struct Ours {
  NonconvexSum sum;
  double seconds = 0;
  std::vector<double> runs;
};

Ours run_minksum(const Solid& sa, const Solid& sb, int reps, bool erosion) {
  std::vector<std::pair<double, NonconvexSum>> all;
  for (int r = 0; r < reps; ++r) {
    const auto t = Clock::now();
    NonconvexSum s = erosion ? erode(sa, sb) : minkowski_sum_nonconvex(sa, sb);
    all.emplace_back(since(t), std::move(s));
  }
  Ours o;
  for (const auto& [s, _] : all) o.runs.push_back(s);
  std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  o.seconds = all[all.size() / 2].first;
  o.sum = std::move(all[all.size() / 2].second);
  return o;
}

void json_string(const std::string& s) {
  std::putchar('"');
  for (char c : s) {
    if (c == '"' || c == '\\') std::putchar('\\');
    std::putchar(c);
  }
  std::putchar('"');
}

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr,
               "bench_nonconvex: %s\nusage: bench_nonconvex [--json] [--side both|minksum|cgal] [--reps R] "
               "[--operation sum|erode] [A:B ...]\n",
               problem.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> rows;
  bool json = false, ours = true, theirs = true, erosion = false;
  int reps = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json") {
      json = true;
    } else if (arg == "--side") {
      const std::string side = i + 1 < argc ? argv[++i] : "";
      if (side != "both" && side != "minksum" && side != "cgal") usage("--side needs both, minksum or cgal");
      ours = side != "cgal";
      theirs = side != "minksum";
    } else if (arg == "--operation") {
      const std::string op = i + 1 < argc ? argv[++i] : "";
      if (op != "sum" && op != "erode") usage("--operation needs sum or erode");
      erosion = op == "erode";
    } else if (arg == "--reps") {
      const std::string r = i + 1 < argc ? argv[++i] : "";
      reps = r.size() >= 1 && r.size() <= 3 && std::all_of(r.begin(), r.end(), ::isdigit) ? std::stoi(r) : 0;
      if (reps < 1) usage("--reps needs an integer 1..999, got '" + r + "'");
    } else if (arg == "--check") {
      if (i + 2 != argc) usage("--check takes one file and nothing else");
      try {
        return check(argv[i + 1]);
      } catch (const InputError& e) {
        std::fprintf(stderr, "bench_nonconvex: %s\n", e.what());
        return 3;
      }
    } else if (arg.rfind("--", 0) == 0) {
      usage("unknown option '" + arg + "'");
    } else {
      rows.push_back(arg);
    }
  }
  if (rows.empty())
    rows = {"tube:sphere:1@scale:1/4", "tube:sphere:2@scale:1/4", "tube:sphere:3@scale:1/4",
            "lshape:sphere:2@scale:1/4", "gear:8:cube@scale:1/16@rot:3", "tube:lshape@scale:1/4@rot:7"};
  if (!json)
    std::printf("| A ⊕ B (⊖ for --operation erode) | V(B) | pieces | pairs | minksum s (decompose / pairs / union / boundary) | CGAL s | "
                "ratio | same volume |\n|---|---|---|---|---|---|---|---|\n");
  for (const std::string& row : rows) {
    std::string a, b;
    if (!split_files(row, a, b) && !split_row(row, a, b)) usage("'" + row + "' is not A:B or A|B");
    Solid sa, sb;
    try {
      sa = validate_solid(operand_mesh(a), a);
      sb = validate_solid(operand_mesh(b), b);
    } catch (const UsageError& e) {
      usage(e.what());
    } catch (const InputError& e) {
      std::fprintf(stderr, "bench_nonconvex: %s\n", e.what());
      return 3;
    }
    Ours o;
    if (erosion && !sb.convex) usage("--operation erode needs a convex B, not '" + b + "'");
    if (ours) o = run_minksum(sa, sb, reps, erosion);
    const NonconvexSum& r = o.sum;
    double cgal = 0;
    Mesh m;
    if (theirs) m = erosion ? reference_erosion(sa, sb, &cgal) : reference_minkowski_sum(sa, sb, &cgal);
    if (json) {
      std::printf("{\"a\": ");
      json_string(a);
      std::printf(", \"b\": ");
      json_string(b);
      std::printf(", \"vertices_a\": %zu, \"vertices_b\": %zu, \"threads\": %u", sa.vertices, sb.vertices,
                  std::thread::hardware_concurrency());
      if (ours) {
        std::printf(", \"minksum\": {\"seconds\": %.6f, \"runs\": [", o.seconds);
        for (std::size_t k = 0; k < o.runs.size(); ++k) std::printf("%s%.6f", k ? ", " : "", o.runs[k]);
        std::printf("], \"decompose\": %.6f, \"pairs_s\": %.6f, \"union\": %.6f, \"boundary\": %.6f, \"pieces_a\": %zu, "
                    "\"pieces_b\": %zu, \"pairs\": %zu, \"volume\": ",
                    r.seconds_decompose, r.seconds_pairs, r.seconds_union, r.seconds_boundary, r.pieces_a, r.pieces_b,
                    r.pairs);
        json_string(format_exact(r.volume));
        std::printf(", \"volume_double\": %.17g, \"vertices\": %zu, \"faces\": %zu}", to_double(r.volume),
                    r.mesh.points.size(), r.mesh.faces.size());
      }
      if (theirs) {
        std::printf(", \"cgal\": {\"seconds\": %.6f, \"volume\": ", cgal);
        json_string(format_exact(mesh_volume(m)));
        std::printf(", \"vertices\": %zu, \"faces\": %zu}", m.points.size(), m.faces.size());
      }
      std::printf("}\n");
    } else if (ours && theirs) {
      std::printf("| %s %s %s | %zu | %zu + %zu | %zu | %.3f (%.3f / %.3f / %.3f / %.3f) | %.3f | %.1f× | %s |\n",
                  a.c_str(), erosion ? "⊖" : "⊕", b.c_str(), sb.vertices, r.pieces_a, r.pieces_b, r.pairs, o.seconds, r.seconds_decompose,
                  r.seconds_pairs, r.seconds_union, r.seconds_boundary, cgal, cgal / o.seconds,
                  mesh_volume(m) == r.volume ? "yes" : "NO");
    } else {
      std::printf("| %s %s %s | %zu | %s | %s | %s | %s | | |\n", a.c_str(), erosion ? "⊖" : "⊕", b.c_str(), sb.vertices,
                  ours ? (std::to_string(r.pieces_a) + " + " + std::to_string(r.pieces_b)).c_str() : "",
                  ours ? std::to_string(r.pairs).c_str() : "", ours ? std::to_string(o.seconds).c_str() : "",
                  theirs ? std::to_string(cgal).c_str() : "");
    }
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      std::fprintf(stderr, "bench_nonconvex: cannot write standard output\n");
      return 1;
    }
  }
  if (!json) std::printf("\n%u hardware threads.\n", std::thread::hardware_concurrency());
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "bench_nonconvex: cannot write standard output\n");
    return 1;
  }
  return 0;
}
