// minksum bench — every minksum method against the tools users pick today,
// on the same inputs, in the same run.  Writes docs/generated/benchmarks.md and its plot.
//
//   minksum_bench [--suite full|quick] [--out DIR] [--command TEXT] [--only GROUP]
//                 [--contenders KEY,KEY,...] [--verbose]
//
// The operands are built once per row in the parent (catalog construction is
// not timed) for the row's sizes.  Each cell (one pair, one contender) runs in
// a process of its own, started afresh (this program with --worker), which
// builds the operands itself before its first run, so that a run costs what
// the same call costs in a program of its own.  The cells of a row take turns,
// one run each per round; a cell runs up to `runs` times (more when fast) and
// reports the median time, the output's V/E/F and its peak resident memory;
// it is killed by SIGALRM when it exceeds the cap.  --verbose prints every
// run's time and minor page faults.
#include "competitors.hpp"
#include "report.hpp"
#include "timer.hpp"

#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gmp.h>
#include <malloc.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace minksum::bench {
namespace {

struct Config {
  std::string suite = "full";
  std::string out = "docs/generated";
  std::string command = "make bench";
  std::string only;
  std::string contenders;      // comma-separated contender keys to run (empty: all)
  bool verbose = false;        // each run's seconds and minor page faults on stderr
  int runs = 5;
  double min_total = 1.0;      // fast cells repeat beyond `runs` until this many seconds of runs ...
  int max_runs = 500;          // ... or this many runs
  double cap = 120;            // seconds per cell (all runs of a cell)
  double long_run = 10;        // a first run longer than this is not repeated
  double exact_pair_limit = 1.2e7;  // v_A * v_B beyond which exact pairwise methods are skipped
  double float_pair_limit = 3e7;    // ... floating-point pairwise methods
  long mem_limit_mb = 8192;    // address-space limit of a cell's process
  long trim_mb = 1024;         // a cell's process over this resident size returns free memory between runs
  double predict_factor = 2;   // skip a cell predicted to take this many caps
};

using Runner = std::function<Outcome(const ConvexPolytope&, const ConvexPolytope&)>;

struct Entry {
  Contender c;
  Runner run;
};

std::vector<Entry> contenders() {
  std::vector<Entry> out;
  for (Method m : {Method::walk, Method::cvms, Method::essdms, Method::mssd, Method::cgm, Method::chms}) {
    if (!method_available(m)) continue;
    Contender c;
    c.key = method_name(m);
    c.label = std::string("minksum ") + method_name(m);
    c.ours = true;
    c.pairwise = (m == Method::chms);
    if (m == Method::walk) {
      // Timed: the walk alone, whose result is the exact sum as a half-edge
      // structure with implicit coordinates (vertex = pair of input vertices);
      // counts from it.  The second timing is to_polytope(), the conversion to
      // explicit exact coordinates (planes on demand), what
      // minkowski_sum(a, b, Method::walk) adds, timed in every run right after
      // the walk, as minkowski_sum runs them: each figure is a median over the
      // cell's runs, and walk + conversion is what minkowski_sum costs.
      c.sub_label = "+ conversion";
      c.sub_extra = true;
      out.push_back({c, [](const ConvexPolytope& a, const ConvexPolytope& b) {
                       Outcome o;
                       Stopwatch sw;
                       WalkSum w = minkowski_walk(a, b);
                       o.seconds = sw.seconds();
                       o.v = w.num_vertices();
                       o.e = w.num_edges();
                       o.f = w.num_facets();
                       Stopwatch conv;
                       ConvexPolytope p = to_polytope(w, a, b);
                       o.sub_seconds = conv.seconds();
                       if (p.num_vertices() != o.v || p.num_edges() != o.e || p.num_facets() != o.f)
                         throw std::logic_error("to_polytope changed the counts of the walk's result: " +
                                                std::to_string(o.v) + "/" + std::to_string(o.e) + "/" +
                                                std::to_string(o.f) + " became " +
                                                std::to_string(p.num_vertices()) + "/" +
                                                std::to_string(p.num_edges()) + "/" +
                                                std::to_string(p.num_facets()));
                       return o;
                     }});
      continue;
    }
    out.push_back({c, [m](const ConvexPolytope& a, const ConvexPolytope& b) {
                     Stopwatch sw;
                     SumResult r = minkowski_sum(a, b, m);
                     Outcome o;
                     o.seconds = sw.seconds();
                     o.v = r.polytope.num_vertices();
                     o.e = r.polytope.num_edges();
                     o.f = r.polytope.num_facets();
                     return o;
                   }});
  }
  out.push_back({{"cgal-exact", "CGAL hull, exact sums", false, true, true, "", false}, cgal_exact_hull});
  out.push_back({{"cgal-epick", "CGAL hull, Epick (rounded)", false, false, true, "", false}, cgal_epick_hull});
  out.push_back({{"qhull", "Qhull (rounded)", false, false, true, "", false}, qhull_rounded});
  out.push_back({{"nef", "CGAL Nef minkowski_sum_3", false, true, true, "", false}, cgal_nef_sum});
  out.push_back({{"sgm", "CGAL SGM (build + overlay)", false, true, false, "overlay", false}, cgal_sgm_sum});
  return out;
}

std::vector<Row> suite_rows(const std::string& suite) {
  const bool full = suite == "full";
  std::vector<Row> rows;
  auto add = [&](std::string g, std::string a, std::string b, std::string series, bool large = false) {
    Row r;
    r.group = std::move(g);
    r.a = std::move(a);
    r.b = std::move(b);
    r.series = std::move(series);
    r.large = large;
    rows.push_back(r);
  };
  // Barki et al. 2009, Table 1: the cube against growing solids.
  for (const char* b : {"tetra", "octahedron", "truncated-cube"}) add("table1", "cube", b, "table1");
  for (int l = 1; l <= (full ? 6 : 3); ++l)
    add("table1", "cube", "sphere:" + std::to_string(l), "table1", l == 6);
  // Geodesic spheres against a rotated copy (exact rational rotation).
  for (int k = 3; k <= (full ? 7 : 3); ++k) {
    std::string s = "sphere:" + std::to_string(k);
    add("rotated", s, s + "@rot:1", "rotated", k >= 6);
  }
  // Random polytopes (hulls of random unit vectors: every point is a vertex).
  for (int n : {1000, 10000, 100000}) {
    if (!full) n = 300;
    std::string ns = std::to_string(n);
    add("random", "random:" + ns + ":1", "random:" + ns + ":2", "random", n >= 10000);
    if (!full) break;
  }
  // Fogel-Halperin's Θ(mn) example: squashed dioctagonal pyramids, orthogonal.
  for (int n : {17, 257, 1025}) {
    if (!full && n > 17) break;
    std::string s = "dioctagonal:" + std::to_string(n);
    add("dioctagonal", s, s + "@rot:1,1,0,0", "dioctagonal", n >= 1025);
  }
  // A = A: every facet meets its parallel twin (the degenerate case).
  add("identical", "cube", "cube", "identical");
  add("identical", "sphere:3", "sphere:3", "identical");
  if (full) add("identical", "random:1000:1", "random:1000:1", "identical");
  if (full) add("identical", "sphere:5", "sphere:5", "identical");
  // Catalog pairs after Table 4 of Fogel and Halperin (2006) (F / (F_A F_B) from 1/F_B down).
  std::vector<std::pair<std::string, std::string>> cat = {
      {"icosahedron", "icosahedron@rot:1"},
      {"dodecahedron", "icosahedron"},
      {"pentagonal-hexecontahedron", "truncated-icosidodecahedron"},
      {"truncated-icosahedron", "pentakis-dodecahedron"},
      {"snub-cube", "snub-dodecahedron"},
      {"rhombicosidodecahedron", "disdyakis-triacontahedron"},
      {"zonotope:12:1", "zonotope:12:2"},
      {"cube", "box:1:2:3@rot:1"},
  };
  std::size_t ncat = full ? cat.size() : 2;
  for (std::size_t i = 0; i < ncat; ++i) add("catalog", cat[i].first, cat[i].second, "catalog-" + std::to_string(i));
  return rows;
}

// The term that dominates a contender's running time, used to predict a
// cell from the previous (smaller) row of its series: all pairwise sums for
// the hull methods (and Nef, whose convex case is a hull of pairwise sums),
// the f_A v_B + f_B v_A + e_A e_B of Barki et al.'s CVMS/ESSDMS/MSSD analysis,
// and input size (a lower bound for any method) for the others.  walk is
// output-sensitive (input + output size), but a row's output is not known
// before its first cell runs, so its prediction uses the input size too (the
// sums of a series grow with their operands).
const char* cost_name(const std::string& key) {
  if (key == "chms" || key == "cgal-exact" || key == "cgal-epick" || key == "qhull" || key == "nef")
    return "v_A·v_B";
  if (key == "cvms" || key == "essdms" || key == "mssd") return "f_A·v_B + f_B·v_A + e_A·e_B";
  if (key == "walk") return "input size V+E+F of A and B, standing for input + output size";
  return "input size V+E+F of A and B";
}
double cost(const std::string& key, const RowResult& r, double input) {
  const std::string name = cost_name(key);
  if (name == "v_A·v_B") return double(r.va) * double(r.vb);
  if (name[0] == 'f') return double(r.fa) * r.vb + double(r.fb) * r.va + double(r.ea) * r.eb;
  return input;
}

long proc_status_kb(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, n, field) == 0) return std::atol(line.c_str() + n);
  return -1;
}

void write_all(int fd, const std::string& s) {
  std::size_t off = 0;
  while (off < s.size()) {
    ssize_t w = ::write(fd, s.data() + off, s.size() - off);
    if (w <= 0) return;
    off += std::size_t(w);
  }
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A cell's process.  Each cell of a row runs in a process of its own, started
// afresh (fork + exec of this program with --worker): it builds the operands
// itself, untimed, and then runs the contender once per "run" request on its
// standard input, answering on its standard output.  A child merely forked
// from this (large, long-lived) parent would share the parent's heap
// copy-on-write and pay a page fault for each inherited page its first run
// writes to, and would allocate from the parent's fragmented free lists: not
// what the same call costs in a program of its own (bench/qhull_standalone
// measures both).
//
// Protocol, one line each: the worker says "READY <VmRSS kB>" once the
// operands are built; "run <seconds left>" → "RUN <seconds> <sub> <v> <e> <f>"
// and a line with the note (the worker sets an alarm for the seconds left
// of the cell's cap around the run); "quit" → "PEAK <VmHWM kB>", exit.
// Errors: "ERR <message>", exit.
std::string one_line(std::string s) {
  for (char& ch : s)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return s;
}

int worker_main(const std::string& key, const std::string& spec_a, const std::string& spec_b, const Config& cfg) {
  std::signal(SIGPIPE, SIG_DFL);
  struct rlimit rl;
  rl.rlim_cur = rl.rlim_max = rlim_t(cfg.mem_limit_mb) * 1024 * 1024;
  setrlimit(RLIMIT_AS, &rl);
  signal(SIGALRM, SIG_DFL);
  std::vector<Entry> entries = contenders();
  const Entry* entry = nullptr;
  for (const auto& e : entries)
    if (e.c.key == key) entry = &e;
  auto say = [](const std::string& s) { write_all(1, s); };
  if (!entry) {
    say("ERR no contender " + key + "\n");
    return 1;
  }
  try {
    ConvexPolytope a = load_polytope(spec_a), b = load_polytope(spec_b);
    say("READY " + std::to_string(proc_status_kb("VmRSS:")) + "\n");
    std::string line;
    int r = 0;
    while (std::getline(std::cin, line)) {
      if (line.rfind("run ", 0) == 0) {
        const double left = std::atof(line.c_str() + 4);
        struct rusage ru0, ru1;
        getrusage(RUSAGE_SELF, &ru0);
        alarm(unsigned(std::max(1.0, std::ceil(left))));
        Outcome o = entry->run(a, b);
        alarm(0);
        getrusage(RUSAGE_SELF, &ru1);
        if (cfg.verbose)
          std::fprintf(stderr, "      %s run %d: %.4f s, %ld minor page faults\n", key.c_str(), ++r, o.seconds,
                       ru1.ru_minflt - ru0.ru_minflt);
        // A cell whose memory runs into gigabytes gives it back between runs (untimed), so
        // that the row's other cells, alive at the same time, are not starved of memory.
        if (proc_status_kb("VmRSS:") > cfg.trim_mb * 1024) malloc_trim(0);
        char buf[256];
        std::snprintf(buf, sizeof buf, "RUN %.9g %.9g %ld %ld %ld\n", o.seconds, o.sub_seconds, o.v, o.e, o.f);
        say(buf + one_line(o.note) + "\n");
      } else if (line == "quit") {
        say("PEAK " + std::to_string(proc_status_kb("VmHWM:")) + "\n");
        return 0;
      }
    }
  } catch (const std::bad_alloc&) {
    say("ERR out of memory (limit " + std::to_string(cfg.mem_limit_mb) + " MiB)\n");
  } catch (const std::exception& e) {
    say("ERR " + one_line(e.what()) + "\n");
  }
  return 0;
}

// The parent's side of one cell's process.
struct Worker {
  const Entry* entry = nullptr;
  pid_t pid = -1;
  FILE* in = nullptr;   // the worker's stdout
  int out = -1;         // the worker's stdin
  Cell cell;
  std::vector<double> times, subs;
  double total = 0;     // wall seconds of its runs, as the parent sees them (a run and its untimed counting)
  bool done = false;
  long v = -1, e = -1, f = -1;
  std::string note;
};

bool spawn_worker(Worker& w, const std::string& self, const Row& row, const Config& cfg) {
  int to[2], from[2];
  if (pipe(to) != 0) return false;
  if (pipe(from) != 0) {
    ::close(to[0]), ::close(to[1]);
    return false;
  }
  std::vector<std::string> args = {self,        "--worker",   w.entry->c.key, "--a", row.a, "--b", row.b,
                                   "--mem-limit", std::to_string(cfg.mem_limit_mb), "--trim",
                                   std::to_string(cfg.trim_mb)};
  if (cfg.verbose) args.push_back("--verbose");
  std::fflush(stdout);
  std::fflush(stderr);
  w.pid = fork();
  if (w.pid == 0) {
    dup2(to[0], 0);
    dup2(from[1], 1);
    ::close(to[0]), ::close(to[1]), ::close(from[0]), ::close(from[1]);
    std::vector<char*> argv;
    for (auto& s : args) argv.push_back(s.data());
    argv.push_back(nullptr);
    execv(self.c_str(), argv.data());
    _exit(127);
  }
  ::close(to[0]);
  ::close(from[1]);
  w.out = to[1];
  w.in = fdopen(from[0], "r");
  return w.pid > 0;
}

std::string read_line(FILE* in) {
  std::string s;
  int ch;
  while ((ch = std::fgetc(in)) != EOF && ch != '\n') s.push_back(char(ch));
  if (ch == EOF && s.empty()) return "\x04";  // end of file
  return s;
}

// The worker is gone or broken: reap it and say why in its cell.
void finish_worker(Worker& w, const Config& cfg, const std::string& reply) {
  if (w.out >= 0) ::close(w.out), w.out = -1;
  if (w.in) std::fclose(w.in), w.in = nullptr;
  int status = 0;
  if (w.pid > 0) waitpid(w.pid, &status, 0);
  w.pid = -1;
  w.done = true;
  if (w.cell.state == Cell::ok) return;
  if (WIFSIGNALED(status)) {
    if (WTERMSIG(status) == SIGALRM) {
      w.cell.state = Cell::capped;
      w.cell.note = "stopped after " + std::to_string(int(cfg.cap)) + " s";
    } else {
      w.cell.state = Cell::failed;
      w.cell.note = std::string("killed by signal ") + strsignal(WTERMSIG(status));
    }
  } else {
    w.cell.state = Cell::failed;
    w.cell.note = reply.rfind("ERR ", 0) == 0 ? reply.substr(4) : "no result";
  }
}

// Run a row's cells, interleaved: every cell's process is started (and builds
// the operands), then one run of each cell that still wants runs per round —
// A, B, C, A, B, C, ... — so that a burst of load on the shared machine falls
// on all contenders of the row rather than on one.  Each cell keeps the
// stopping rules of a cell run on its own: at least `runs` runs, more for a
// fast cell until min_total seconds of runs (at most max_runs), a first run
// over long_run not repeated, no run started that would likely end past the
// cap.  A cell is the median of its runs.
std::map<std::string, Cell> run_cells(const std::vector<const Entry*>& todo, const Row& row, const Config& cfg,
                                      const std::string& self) {
  std::vector<Worker> ws(todo.size());
  for (std::size_t i = 0; i < todo.size(); ++i) {
    ws[i].entry = todo[i];
    if (!spawn_worker(ws[i], self, row, cfg)) {
      ws[i].cell.state = Cell::failed;
      ws[i].cell.note = "could not start the cell's process";
      ws[i].done = true;
    }
  }
  for (auto& w : ws) {
    if (w.done) continue;
    const std::string reply = read_line(w.in);
    if (reply.rfind("READY ", 0) == 0) w.cell.base_kb = std::atol(reply.c_str() + 6);
    else finish_worker(w, cfg, reply);
  }
  for (int round = 0;; ++round) {
    bool any = false;
    for (auto& w : ws) {
      if (w.done) continue;
      any = true;
      char req[64];
      std::snprintf(req, sizeof req, "run %.3f\n", cfg.cap - w.total);
      Stopwatch sw;
      write_all(w.out, req);
      const std::string reply = read_line(w.in);
      if (reply.rfind("RUN ", 0) != 0) {
        finish_worker(w, cfg, reply);
        continue;
      }
      std::istringstream in(reply.substr(4));
      double sec = 0, sub = -1;
      in >> sec >> sub >> w.v >> w.e >> w.f;
      w.note = read_line(w.in);
      if (w.note == "\x04") w.note.clear();
      const double run = sw.seconds();
      w.total += run;
      w.times.push_back(sec);
      if (sub >= 0) w.subs.push_back(sub);
      const int r = int(w.times.size());
      // A run's length: the timed part, and the second phase when it comes on top (walk's conversion).
      const double len = sec + (w.entry->c.sub_extra && sub > 0 ? sub : 0);
      bool stop = !(r < cfg.runs || (w.total < cfg.min_total && r < cfg.max_runs));
      if (r == 1 && len > cfg.long_run) stop = true;
      // Stop before the alarm would kill a run whose predecessors finished.
      if (w.total + 1.5 * std::max(len, run) > 0.9 * cfg.cap) stop = true;
      if (stop) {
        write_all(w.out, "quit\n");
        const std::string peak = read_line(w.in);
        w.cell.state = Cell::ok;
        w.cell.median = median(w.times);
        w.cell.runs = r;
        w.cell.sub = w.subs.empty() ? -1.0 : median(w.subs);
        w.cell.v = w.v, w.cell.e = w.e, w.cell.f = w.f;
        w.cell.note = w.note;
        w.cell.peak_kb = peak.rfind("PEAK ", 0) == 0 ? std::atol(peak.c_str() + 5) : -1;
        finish_worker(w, cfg, "");
      }
    }
    if (!any) break;
  }
  std::map<std::string, Cell> out;
  for (auto& w : ws) out[w.entry->c.key] = w.cell;
  return out;
}
std::string read_first_line(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[512];
    if (std::fgets(buf, sizeof buf, p)) out = buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

RunInfo machine_info(const Config& cfg) {
  RunInfo info;
  info.suite = cfg.suite;
  info.command = cfg.command;
  info.runs = cfg.runs;
  info.min_total = cfg.min_total;
  info.max_runs = cfg.max_runs;
  info.cap = cfg.cap;
  info.long_run = cfg.long_run;
  info.predict_factor = cfg.predict_factor;
  info.exact_pair_limit = cfg.exact_pair_limit;
  info.float_pair_limit = cfg.float_pair_limit;
  info.mem_limit_mb = cfg.mem_limit_mb;
  info.trim_mb = cfg.trim_mb;
  info.date = utc_now();
  {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("model name", 0) == 0) {
        info.cpu = line.substr(line.find(':') + 2);
        break;
      }
  }
  info.cores = sysconf(_SC_NPROCESSORS_ONLN);
  info.mem_mb = long(sysconf(_SC_PHYS_PAGES) / 1024 * sysconf(_SC_PAGE_SIZE) / 1024);
#ifdef __VERSION__
  info.compiler = std::string("g++ ") + __VERSION__;
#endif
#ifdef NDEBUG
  info.flags = "Release (-O3 -DNDEBUG), MINKSUM_ASSERTIONS=OFF";
#else
  info.flags = "assertions ON (not a benchmark build)";
#endif
  info.cgal = cgal_version();
  info.qhull = qhull_version();
  info.gmp = gmp_version;
  info.minksum = "0.1.0";
  info.git = read_first_line("git rev-parse --short HEAD 2>/dev/null");
  if (!info.git.empty() && !read_first_line("git status --porcelain 2>/dev/null | head -1").empty())
    info.git += " (with uncommitted changes)";
  return info;
}

int usage(const char* msg) {
  std::cerr << "minksum_bench: " << msg
            << "\nusage: minksum_bench [--suite full|quick] [--out DIR] [--command TEXT] [--only GROUP]"
               " [--contenders KEY,...] [--verbose]\n";
  return 2;
}

}  // namespace
}  // namespace minksum::bench

int main(int argc, char** argv) {
  using namespace minksum;
  using namespace minksum::bench;
  Config cfg;
  std::string worker, spec_a, spec_b;  // --worker KEY --a SPEC --b SPEC: one cell's process (see run_cells)
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--suite") cfg.suite = value();
    else if (a == "--out") cfg.out = value();
    else if (a == "--command") cfg.command = value();
    else if (a == "--only") cfg.only = value();
    else if (a == "--contenders") cfg.contenders = value();
    else if (a == "--verbose") cfg.verbose = true;
    else if (a == "--worker") worker = value();
    else if (a == "--a") spec_a = value();
    else if (a == "--b") spec_b = value();
    else if (a == "--mem-limit") cfg.mem_limit_mb = std::atol(value().c_str());
    else if (a == "--trim") cfg.trim_mb = std::atol(value().c_str());
    else if (a == "-h" || a == "--help") {
      std::cout << "usage: minksum_bench [--suite full|quick] [--out DIR] [--command TEXT] [--only GROUP]\n"
                   "                     [--contenders KEY,...] [--verbose]\n"
                   "Runs every minksum method and the competitors (CGAL hulls, Qhull, CGAL Nef, CGAL SGM) on the\n"
                   "suite's pairs and writes DIR/benchmarks.md and DIR/benchmarks-plot.svg.\n"
                   "GROUP: table1 rotated random dioctagonal identical catalog\n"
                   "KEY: walk cvms essdms mssd cgm chms cgal-exact cgal-epick qhull nef sgm (default: all)\n"
                   "--verbose: each run's seconds and minor page faults on stderr\n";
      return 0;
    }
    else return usage(("unknown argument " + a).c_str());
  }
  if (!worker.empty()) return worker_main(worker, spec_a, spec_b, cfg);
  std::signal(SIGPIPE, SIG_IGN);  // a cell's process that died is noticed on its pipe, not by a signal
  std::string self;
  {
    std::error_code ec;
    self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (ec || self.empty()) self = argv[0];
  }
  if (cfg.suite == "quick") {
    cfg.runs = 3;
    cfg.min_total = 0.2;
    cfg.cap = 5;
    cfg.long_run = 0.5;
    cfg.predict_factor = 1;
    cfg.exact_pair_limit = 1e6;
    cfg.float_pair_limit = 4e6;
    cfg.mem_limit_mb = 4096;
  } else if (cfg.suite != "full") {
    return usage("--suite must be full or quick");
  }

  Stopwatch wall;
  RunInfo info = machine_info(cfg);
  info.load_start = load_average();
  std::vector<Entry> entries = contenders();
  if (!cfg.contenders.empty()) {
    const std::string list = "," + cfg.contenders + ",";
    std::erase_if(entries, [&](const Entry& e) { return list.find("," + e.c.key + ",") == std::string::npos; });
  }
  std::vector<Contender> cs;
  for (const auto& e : entries) cs.push_back(e.c);

  struct SeriesState {
    bool capped = false;
    double seconds = 0, size = 0;
  };
  std::map<std::string, SeriesState> series;  // series + "/" + contender key

  std::vector<RowResult> results;
  for (const Row& row : suite_rows(cfg.suite)) {
    if (!cfg.only.empty() && row.group != cfg.only) continue;
    RowResult rr;
    rr.row = row;
    Stopwatch load;
    ConvexPolytope a = load_polytope(row.a), b = load_polytope(row.b);
    rr.load_seconds = load.seconds();
    rr.va = a.num_vertices(), rr.ea = a.num_edges(), rr.fa = a.num_facets();
    rr.vb = b.num_vertices(), rr.eb = b.num_edges(), rr.fb = b.num_facets();
    std::cerr << "[" << int(wall.seconds()) << " s] " << row.a << " + " << row.b << "  (V " << rr.va << " + "
              << rr.vb << ")\n";
    const double pairs = double(rr.va) * double(rr.vb);
    const double input = double(rr.va + rr.ea + rr.fa + rr.vb + rr.eb + rr.fb);
    // Which cells run (decided from the previous rows of each series), then all of them, interleaved.
    std::map<std::string, Cell> cells;
    std::vector<const Entry*> todo;
    for (const Entry& entry : entries) {
      const Contender& c = entry.c;
      const double size = cost(c.key, rr, input);
      Cell cell;
      SeriesState& st = series[row.series + "/" + c.key];
      const double limit = c.exact ? cfg.exact_pair_limit : cfg.float_pair_limit;
      char why[256];
      if (c.pairwise && pairs > limit) {
        cell.state = Cell::skipped;
        std::snprintf(why, sizeof why, "%.3g pairwise sums (limit %.3g): memory and time beyond the cap", pairs,
                      limit);
        cell.note = why;
      } else if (st.capped) {
        cell.state = Cell::skipped;
        cell.note = "over the cap (measured or predicted) on a smaller row of the same series";
      } else if (st.size > 0 && st.seconds * (size / st.size) > cfg.predict_factor * cfg.cap) {
        cell.state = Cell::skipped;
        std::snprintf(why, sizeof why,
                      "predicted %.0f s (over %.0f × the cap): %.3g s on the previous row of the series times "
                      "the growth %.3g of the method's cost term (%s)",
                      st.seconds * (size / st.size), cfg.predict_factor, st.seconds, size / st.size,
                      cost_name(c.key));
        cell.note = why;
      } else {
        todo.push_back(&entry);
        continue;
      }
      cells[c.key] = cell;
    }
    for (auto& [key, cell] : run_cells(todo, row, cfg, self)) cells[key] = cell;
    for (const Entry& entry : entries) {
      const Contender& c = entry.c;
      const double size = cost(c.key, rr, input);
      SeriesState& st = series[row.series + "/" + c.key];
      const Cell cell = cells[c.key];
      if (cell.state == Cell::capped || (cell.state == Cell::skipped && cell.note.rfind("predicted", 0) == 0) ||
          (cell.state == Cell::skipped && st.capped))
        st.capped = true;
      if (cell.state == Cell::ok) {
        // The cell's whole run (walk: with its conversion) is what the cap bounds.
        st.seconds = cell.median + (c.sub_extra && cell.sub > 0 ? cell.sub : 0);
        st.size = size;
      }
      std::cerr << "    " << c.key << ": ";
      if (cell.state == Cell::ok)
        std::cerr << cell.median << " s x" << cell.runs
                  << (cell.sub >= 0 ? " (" + c.sub_label + " " + std::to_string(cell.sub) + " s)" : std::string())
                  << "  V/E/F " << cell.v << "/" << cell.e << "/" << cell.f
                  << "  " << cell.peak_kb / 1024 << " MiB";
      else
        std::cerr << (cell.state == Cell::capped ? "capped" : cell.state == Cell::skipped ? "skipped" : "failed")
                  << " (" << cell.note << ")";
      std::cerr << "\n";
      rr.cells[c.key] = cell;
    }
    // The exact result: chms (the oracle) if it ran, else any minksum method.
    for (const char* key : {"chms", "walk", "cvms", "essdms", "mssd", "cgm"}) {
      auto it = rr.cells.find(key);
      if (it != rr.cells.end() && it->second.state == Cell::ok) {
        rr.v = it->second.v, rr.e = it->second.e, rr.f = it->second.f;
        break;
      }
    }
    results.push_back(rr);
  }
  info.load_end = load_average();
  info.wall_seconds = wall.seconds();
  // The output directory may not exist yet (--out /tmp/x): create it rather than lose the run.
  std::error_code ec;
  std::filesystem::create_directories(cfg.out, ec);
  const std::string md = cfg.out + "/benchmarks.md";
  const std::string svg_name = "benchmarks-plot.svg";
  write_svg(cfg.out + "/" + svg_name, cs, results);
  write_markdown(md, svg_name, info, cs, results);
  std::cerr << "wrote " << md << " and " << cfg.out << "/" << svg_name << " in " << int(wall.seconds()) << " s\n";
  return 0;
}
