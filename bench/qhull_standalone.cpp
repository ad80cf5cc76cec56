// qhull_standalone — Qhull on the rounded pairwise sums of two catalog
// polytopes, timed on its own, and the same call under the conditions of a
// benchmark cell, so that anyone can check that a cell of docs/generated/benchmarks.md
// costs what the call costs in a program of its own.
//
//   qhull_standalone [A B] [--runs N] [--fork] [--ballast MB] [--cell]
//
// Default: A = cube, B = sphere:6.  The operands are built and the points
// (a_i + b_j in double arithmetic, the same array as bench/qhull.cpp) are
// written before any timing; then N runs of
//     qh_new_qhull(qh, 3, n, points, False, "qhull", nullptr, stderr)
// each followed (untimed) by qh_freeqhull + qh_memfreeshort.  Each run
// prints its seconds and the minor page faults it took; the last line gives
// min and median.
//
//   --fork        run the timed loop in a forked child (a benchmark cell)
//   --ballast MB  before forking (or running), allocate MB MiB of small heap
//                 blocks, touch them, and free every other one: a large,
//                 fragmented parent heap, as a benchmark parent has after
//                 building many operands
//   --cell        time bench/qhull.cpp's qhull_rounded() instead (its timed
//                 region is whatever the benchmark cell times)
#include "competitors.hpp"
#include "timer.hpp"

#include <minksum/io.hpp>
#include <minksum/operand.hpp>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

long minor_faults() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_minflt;
}

double qhull_once(std::vector<double>& pts) {
  qhT qh_qh;
  qhT* qh = &qh_qh;
  QHULL_LIB_CHECK
  char options[] = "qhull";
  minksum::bench::Stopwatch sw;
  qh_zero(qh, stderr);
  int code = qh_new_qhull(qh, 3, int(pts.size() / 3), pts.data(), False, options, nullptr, stderr);
  double s = sw.seconds();
  if (code != 0) std::fprintf(stderr, "qhull failed with code %d\n", code);
  qh_freeqhull(qh, !qh_ALL);
  int curlong, totlong;
  qh_memfreeshort(qh, &curlong, &totlong);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string sa = "cube", sb = "sphere:6";
  int runs = 9;
  bool fork_child = false, cell = false;
  long ballast_mb = 0;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) runs = std::atoi(argv[++i]);
    else if (a == "--fork") fork_child = true;
    else if (a == "--cell") cell = true;
    else if (a == "--ballast" && i + 1 < argc) ballast_mb = std::atol(argv[++i]);
    else if (a == "-h" || a == "--help") {
      std::printf("usage: qhull_standalone [A B] [--runs N] [--fork] [--ballast MB] [--cell]\n");
      return 0;
    } else pos.push_back(a);
  }
  if (pos.size() == 2) sa = pos[0], sb = pos[1];

  minksum::ConvexPolytope a = minksum::load_polytope(sa), b = minksum::load_polytope(sb);
  std::vector<double> pts;
  pts.reserve(3 * std::size_t(a.num_vertices()) * std::size_t(b.num_vertices()));
  for (minksum::Index i = 0; i < a.num_vertices(); ++i)
    for (minksum::Index j = 0; j < b.num_vertices(); ++j) {
      const auto &p = a.approx(i), &q = b.approx(j);
      pts.push_back(p.x + q.x);
      pts.push_back(p.y + q.y);
      pts.push_back(p.z + q.z);
    }
  std::printf("%s + %s: %zu points; %s%s%s\n", sa.c_str(), sb.c_str(), pts.size() / 3,
              cell ? "bench qhull_rounded()" : "qh_new_qhull alone", fork_child ? ", in a forked child" : "",
              ballast_mb ? (", after " + std::to_string(ballast_mb) + " MiB of fragmented heap").c_str() : "");

  std::vector<std::unique_ptr<char[]>> ballast;
  if (ballast_mb > 0) {
    const std::size_t block = 96;  // small blocks, like a mesh's nodes and GMP limbs
    const std::size_t n = std::size_t(ballast_mb) * 1024 * 1024 / block;
    ballast.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      ballast.emplace_back(new char[block]);
      std::memset(ballast.back().get(), int(i), block);
    }
    for (std::size_t i = 0; i < n; i += 2) ballast[i].reset();
  }

  auto loop = [&] {
    std::vector<double> t;
    for (int r = 0; r < runs; ++r) {
      const long f0 = minor_faults();
      double s = cell ? minksum::bench::qhull_rounded(a, b).seconds : qhull_once(pts);
      const long f1 = minor_faults();
      t.push_back(s);
      std::printf("  run %d: %.4f s, %ld minor page faults\n", r + 1, s, f1 - f0);
    }
    std::vector<double> u = t;
    std::sort(u.begin(), u.end());
    std::printf("  min %.4f s, median %.4f s over %d runs\n", u.front(), u[u.size() / 2], runs);
    std::fflush(stdout);
  };
  if (fork_child) {
    std::fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
      loop();
      _exit(0);
    }
    int st = 0;
    waitpid(pid, &st, 0);
  } else {
    loop();
  }
  return 0;
}
