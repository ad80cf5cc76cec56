// minksum bench — docs/generated/benchmarks.md and the log-log plot (hand-written SVG).
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace minksum::bench {

namespace {

// Barki, Denis and Dupont (2009), Table 1: seconds on a 2.2 GHz Intel
// Core 2 Duo with 2 GB RAM, cube ⊕ B.
struct Published {
  const char* b;
  double chms, essdms, cvms, mssd, ngm, fuk, cgm_overlay, cgm_whole;
};
const Published kTable1[] = {
    {"tetra", 0.016, 0.015, 0.015, 0.031, 0.093, 0.096, 0.015, 0.030},
    {"octahedron", 0.015, 0.015, 0.015, 0.078, 0.093, 0.100, 0.015, 0.030},
    {"truncated-cube", 0.046, 0.015, 0.015, 0.110, 0.110, 0.232, 0.015, 0.030},
    {"sphere:1", 0.046, 0.046, 0.015, 0.156, 0.203, 0.300, 0.015, 0.046},
    {"sphere:2", 0.125, 0.093, 0.031, 0.359, 0.421, 0.786, 0.047, 0.124},
    {"sphere:3", 0.546, 0.250, 0.078, 1.156, 1.438, 3.269, 0.078, 0.296},
    {"sphere:4", 2.438, 0.735, 0.266, 4.344, 5.563, 15.224, 0.203, 1.249},
    {"sphere:5", 11.407, 2.719, 1.375, 17.938, 22.625, 69.956, 0.562, 7.406},
    {"sphere:6", 77.422, 16.828, 12.234, 79.750, 94.157, 146.870, 1.921, 219.592},
};

std::string fmt(double s) {
  char buf[32];
  if (s >= 100) std::snprintf(buf, sizeof buf, "%.0f", s);
  else if (s >= 10) std::snprintf(buf, sizeof buf, "%.1f", s);
  else std::snprintf(buf, sizeof buf, "%.3g", s);
  return buf;
}

std::string fmt_ratio(double r) {
  char buf[32];
  if (r >= 100) std::snprintf(buf, sizeof buf, "%.0f×", r);
  else if (r >= 10) std::snprintf(buf, sizeof buf, "%.1f×", r);
  else std::snprintf(buf, sizeof buf, "%.2f×", r);
  return buf;
}

std::string vef(long v, long e, long f) {
  return std::to_string(v) + "/" + std::to_string(e) + "/" + std::to_string(f);
}

std::string pair_name(const Row& r) { return "`" + r.a + "` ⊕ `" + r.b + "`"; }

// Footnotes collected while a table is written.
struct Notes {
  std::vector<std::string> text;
  int add(const std::string& t) {
    auto it = std::find(text.begin(), text.end(), t);
    if (it != text.end()) return int(it - text.begin()) + 1;
    text.push_back(t);
    return int(text.size());
  }
};

std::string cell_text(const Cell& c, const Contender& who, const RowResult& rr, const RunInfo& info, Notes& notes,
                      bool with_sub) {
  switch (c.state) {
    case Cell::none: return "";
    case Cell::capped: return "> " + fmt(info.cap) + " s";
    case Cell::skipped: return "skip [" + std::to_string(notes.add(c.note)) + "]";
    case Cell::failed: return "failed [" + std::to_string(notes.add(c.note)) + "]";
    case Cell::ok: break;
  }
  std::string s = fmt(c.median);
  if (c.runs < info.runs) s += " (" + std::to_string(c.runs) + "×)";
  if (with_sub && c.sub >= 0) s += " (" + (who.sub_label.empty() ? "second phase" : who.sub_label) + " " + fmt(c.sub) + ")";
  if (rr.v < 0) {
    s += " " + vef(c.v, c.e, c.f);
  } else if (c.v < 0) {
    s += " ? [" + std::to_string(notes.add(c.note)) + "]";
  } else if (c.v == rr.v && c.e == rr.e && c.f == rr.f) {
    s += " ✓";
  } else {
    s += " ✗ " + vef(c.v, c.e, c.f);
  }
  return s;
}

const Cell* ok_cell(const RowResult& rr, const std::string& key) {
  auto it = rr.cells.find(key);
  return it != rr.cells.end() && it->second.state == Cell::ok ? &it->second : nullptr;
}

void table(std::ostream& md, const RunInfo& info, const std::vector<Contender>& cs,
           const std::vector<const RowResult*>& rows, bool ratio_column) {
  Notes notes;
  md << "| A ⊕ B | F_A | F_B | exact V/E/F |";
  if (ratio_column) md << " F/(F_A·F_B) |";
  for (const auto& c : cs) md << " " << c.label << " |";
  md << "\n|---|---:|---:|---|";
  if (ratio_column) md << "---:|";
  for (std::size_t i = 0; i < cs.size(); ++i) md << "---|";
  md << "\n";
  for (const RowResult* rr : rows) {
    md << "| " << pair_name(rr->row) << " | " << rr->fa << " | " << rr->fb << " | "
       << (rr->v >= 0 ? vef(rr->v, rr->e, rr->f) : "unknown") << " |";
    if (ratio_column) {
      char buf[32];
      if (rr->f >= 0) std::snprintf(buf, sizeof buf, "%.4g", double(rr->f) / (double(rr->fa) * double(rr->fb)));
      else std::snprintf(buf, sizeof buf, "?");
      md << " " << buf << " |";
    }
    for (const auto& c : cs) {
      auto it = rr->cells.find(c.key);
      md << " " << (it == rr->cells.end() ? std::string() : cell_text(it->second, c, *rr, info, notes, true)) << " |";
    }
    md << "\n";
  }
  if (!notes.text.empty()) {
    md << "\n";
    for (std::size_t i = 0; i < notes.text.size(); ++i) md << "[" << i + 1 << "] " << notes.text[i] << "  \n";
  }
  md << "\n";
}

double geomean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += std::log(x);
  return std::exp(s / double(v.size()));
}

const RowResult* find_row(const std::vector<RowResult>& rows, const std::string& group, const std::string& a,
                          const std::string& b) {
  for (const auto& r : rows)
    if (r.row.group == group && r.row.a == a && r.row.b == b) return &r;
  return nullptr;
}

// Why a cell has no time, in a few words.
std::string no_time(const RowResult& rr, const std::string& key, const std::string& label) {
  auto it = rr.cells.find(key);
  if (it == rr.cells.end()) return label + " not run";
  switch (it->second.state) {
    case Cell::capped: return label + " stopped at the cap";
    case Cell::skipped: return label + " skipped";
    case Cell::failed: return label + " failed";
    default: return label + " not run";
  }
}

// --- The targets of the default method walk, from this run's cells.
void walk_targets(std::ostream& md, const RunInfo& info, const std::vector<Contender>& cs,
                  const std::vector<RowResult>& rows) {
  const std::string not_measured = "not measured in this run";
  md << "## The default method `walk`: targets\n\n";
  if (std::none_of(cs.begin(), cs.end(), [](const Contender& c) { return c.key == "walk"; })) {
    md << "`walk` is not in this build: no target is measured.\n\n";
    return;
  }
  md << "walk's time, here and in every table below, is `minkowski_walk` alone: its result is the exact sum as a "
        "half-edge structure with implicit coordinates (each vertex a pair of input vertices), and the counts are "
        "read off it. The conversion to a polytope with explicit exact coordinates (`to_polytope`, "
        "what `minkowski_sum(a, b, Method::walk)` adds) is timed in every run right after the walk, as "
        "`minkowski_sum` runs them, and its median is shown as the "
        "second figure of walk's cells, `(+ conversion s)`. A ratio is the competitor's median ÷ walk's median, "
        "both measured in this run on this machine; a target whose cell did not finish in this run (or whose row "
        "is not in the " << info.suite << " suite) is " << not_measured << ".\n\n"
     << "| target | measured | goal | verdict |\n|---|---|---|---|\n";
  auto line = [&](const std::string& what, const std::string& measured, const std::string& goal,
                  const std::string& verdict) {
    md << "| " << what << " | " << measured << " | " << goal << " | " << verdict << " |\n";
  };
  auto at_least = [](double x, double goal) {
    return x >= goal ? std::string("met") : "missed by " + fmt_ratio(goal / x);
  };
  auto below = [](double x, double goal, bool strict) {
    return (strict ? x < goal : x <= goal) ? std::string("met") : "missed by " + fmt_ratio(x / goal);
  };
  auto pair_of = [](const std::string& a, const std::string& b) { return "`" + a + "` ⊕ `" + b + "`"; };

  // Speed-ups over a competitor on one row.
  auto speedup = [&](const std::string& group, const std::string& a, const std::string& b, const std::string& comp,
                     const std::string& comp_label, double goal) {
    const std::string what = pair_of(a, b) + ": " + comp_label + " ÷ walk";
    char gb[32];
    std::snprintf(gb, sizeof gb, "≥ %g×", goal);
    const std::string g = gb;
    const RowResult* rr = find_row(rows, group, a, b);
    if (!rr) return line(what, "— (row not in this suite)", g, not_measured);
    const Cell* w = ok_cell(*rr, "walk");
    const Cell* c = ok_cell(*rr, comp);
    if (!w || w->median <= 0) return line(what, "— (" + no_time(*rr, "walk", "walk") + ")", g, not_measured);
    if (!c) return line(what, "— (" + no_time(*rr, comp, comp_label) + ")", g, not_measured);
    const double r = c->median / w->median;
    line(what, fmt_ratio(r) + " (" + fmt(c->median) + " s ÷ " + fmt(w->median) + " s)", g, at_least(r, goal));
  };
  speedup("table1", "cube", "sphere:6", "qhull", "Qhull (rounded)", 20);
  speedup("table1", "cube", "sphere:6", "chms", "minksum chms", 40);
  speedup("rotated", "sphere:5", "sphere:5@rot:1", "qhull", "Qhull (rounded)", 50);

  // Time per input + output feature along the rotated series.
  std::vector<double> ns;
  const int k0 = 3, k1 = 7, k_check = 6;
  const double ns_goal = 150;
  for (int k = k0; k <= k1; ++k) {
    const std::string a = "sphere:" + std::to_string(k), b = a + "@rot:1";
    const std::string what = pair_of(a, b) + ": walk time per feature (V+E+F of A, B and the sum)";
    const std::string g = k == k_check ? "< " + fmt(ns_goal) + " ns" : "—";
    const std::string v_none = k == k_check ? not_measured : "—";
    const RowResult* rr = find_row(rows, "rotated", a, b);
    if (!rr) {
      line(what, "— (row not in this suite)", g, v_none);
      continue;
    }
    const Cell* w = ok_cell(*rr, "walk");
    if (!w || w->v < 0) {
      line(what, "— (" + no_time(*rr, "walk", "walk") + ")", g, v_none);
      continue;
    }
    const double features = double(rr->va + rr->ea + rr->fa + rr->vb + rr->eb + rr->fb + w->v + w->e + w->f);
    const double x = w->median * 1e9 / features;
    ns.push_back(x);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.1f ns (%s s ÷ %.0f features)", x, fmt(w->median).c_str(), features);
    line(what, buf, g, k == k_check ? below(x, ns_goal, true) : "—");
  }
  {
    const int want = k1 - k0 + 1;
    const std::string what = "walk time per feature, max ÷ min over `sphere:" + std::to_string(k0) + "` … `sphere:" +
                             std::to_string(k1) + "` (flat within 2×)";
    if (ns.size() < 2) {
      line(what, "— (" + std::to_string(ns.size()) + " of " + std::to_string(want) + " rows measured)", "≤ 2×",
           not_measured);
    } else {
      const auto [lo, hi] = std::minmax_element(ns.begin(), ns.end());
      const double r = *hi / *lo;
      std::string m = fmt_ratio(r);
      if (int(ns.size()) < want) m += " (only " + std::to_string(ns.size()) + " of " + std::to_string(want) + " rows)";
      line(what, m, "≤ 2×",
           int(ns.size()) < want ? not_measured + " (" + std::to_string(want - int(ns.size())) + " rows missing)"
                                 : below(r, 2, false));
    }
  }

  // Peak memory on the largest row of the series.
  {
    const std::string a = "sphere:" + std::to_string(k1), b = a + "@rot:1";
    const std::string what = pair_of(a, b) + ": peak memory of the walk cell";
    const std::string g = "< 1 GiB (1024 MiB)";
    const RowResult* rr = find_row(rows, "rotated", a, b);
    const Cell* w = rr ? ok_cell(*rr, "walk") : nullptr;
    if (!rr) line(what, "— (row not in this suite)", g, not_measured);
    else if (!w || w->peak_kb < 0) line(what, "— (" + no_time(*rr, "walk", "walk") + ")", g, not_measured);
    else {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "%.0f MiB peak (VmHWM of the cell's process: it includes the operands, built by that process "
                    "before its runs, %.0f MiB resident then; and the conversion, run in the same process)",
                    w->peak_kb / 1024.0, w->base_kb / 1024.0);
      line(what, buf, g, below(double(w->peak_kb), 1024.0 * 1024.0, true));
    }
  }

  // The explicit exact result against the walk alone, on every row where
  // walk finished: (walk + conversion) ÷ walk, the largest; and Qhull ÷
  // (walk + conversion), the geometric mean over the rows Qhull finished.
  {
    double worst = 0;
    std::string worst_row;
    std::vector<double> qhull_ratios;
    int measured = 0;
    for (const RowResult& rr : rows) {
      const Cell* w = ok_cell(rr, "walk");
      if (!w || w->median <= 0 || w->sub < 0) continue;
      ++measured;
      const double r = (w->median + w->sub) / w->median;
      if (r > worst) worst = r, worst_row = pair_of(rr.row.a, rr.row.b);
      if (const Cell* q = ok_cell(rr, "qhull")) qhull_ratios.push_back(q->median / (w->median + w->sub));
    }
    const std::string what = "`minkowski_sum` with its explicit exact result ÷ `minkowski_walk` alone, i.e. "
                             "(walk + conversion) ÷ walk, largest over the rows";
    if (measured == 0) line(what, "— (no walk cell finished)", "≤ 2×", not_measured);
    else
      line(what, fmt_ratio(worst) + " (" + worst_row + "; " + std::to_string(measured) + " rows)", "≤ 2×",
           below(worst, 2, false));
    const std::string what_q = "Qhull ÷ (walk + conversion), geometric mean over the rows";
    if (qhull_ratios.empty()) line(what_q, "— (no row with both cells)", "≥ 10×", not_measured);
    else
      line(what_q, fmt_ratio(geomean(qhull_ratios)) + " (" + std::to_string(qhull_ratios.size()) + " rows)", "≥ 10×",
           at_least(geomean(qhull_ratios), 10));
  }
  md << "\n";
}

}  // namespace

void write_markdown(const std::string& path, const std::string& svg_name, const RunInfo& info,
                    const std::vector<Contender>& cs, const std::vector<RowResult>& rows) {
  std::ostringstream md;
  std::vector<std::string> ours;
  for (const auto& c : cs)
    if (c.ours) ours.push_back(c.key);
  const bool has_walk = std::find(ours.begin(), ours.end(), "walk") != ours.end();

  md << "# Benchmarks: minksum against the tools users pick today\n\n"
     << "<!-- Generated by `" << info.command << "` (bench/main.cpp, bench/report.cpp). Do not edit by hand: "
     << "every figure below comes from that command. -->\n\n"
     << "Every minksum method that exists in this build (" ;
  for (std::size_t i = 0; i < ours.size(); ++i) md << (i ? ", " : "") << "`" << ours[i] << "`";
  md << ") and five competitors, on the same inputs, in the same run, on the machine below. "
     << "Suite: **" << info.suite << "** (`" << info.command << "`), " << rows.size() << " pairs, "
     << "total wall time " << fmt(info.wall_seconds) << " s.\n\n";

  walk_targets(md, info, cs, rows);

  md << "## Machine and software\n\n"
     << "| | |\n|---|---|\n"
     << "| date | " << info.date << " |\n"
     << "| CPU | " << info.cpu << ", " << info.cores << " cores online, " << info.mem_mb / 1024 << " GiB RAM |\n"
     << "| load average (1/5/15 min) | at start " << info.load_start << "; at end " << info.load_end << " |\n"
     << "| compiler | " << info.compiler << ", " << info.flags << " |\n"
     << "| minksum | " << info.minksum << (info.git.empty() ? "" : ", commit " + info.git) << " |\n"
     << "| CGAL | " << info.cgal << " (Debian libcgal-dev) |\n"
     << "| Qhull | " << info.qhull << " (Debian libqhull-dev, reentrant libqhull_r) |\n"
     << "| GMP | " << info.gmp << " |\n\n"
     << "The machine is shared (2 cores, other jobs compiling): absolute seconds are noisy. **The ratios between "
     << "cells of one row, measured in the same run, are what counts.**\n\n";

  md << "## How to read the tables\n\n"
     << "* A cell is the **median of " << info.runs << " runs** in seconds — of more for fast cells, which repeat "
     << "until " << fmt(info.min_total) << " s of runs (at most " << info.max_runs << " runs), so that a "
     << "millisecond cell is not the machine's noise; `(k×)` marks a cell with fewer runs "
     << "(a first run over " << fmt(info.long_run) << " s is not repeated; a cell also stops repeating before "
     << "its cap). "
     << "Times exclude file I/O and the construction of the operands.\n"
     << "* How cells are timed: each cell runs in a process of its own, started afresh (fork and exec of the "
     << "benchmark program), which builds the operands itself, untimed, before its first run — so a run costs what "
     << "the same call costs in a program of its own, not what it costs in a child forked from the large "
     << "benchmark process (which pays copy-on-write page faults on the inherited heap; `bench/qhull_standalone` "
     << "compares the two). The contenders of a row take turns, one run each per round (A, B, C, A, B, C, …), so "
     << "that a burst of load on the shared machine falls on all of them alike; the figure is the **median** of a "
     << "cell's runs, each timed with a monotonic wall clock around the call alone (the competitor's input, e.g. the "
     << "pairwise sums handed to Qhull, is prepared before the clock starts). A cell whose process grows past "
     << info.trim_mb << " MiB returns its free memory to the system between runs (untimed).\n"
     << "* `✓`: the output's vertex/edge/facet counts (coplanar facets merged) equal the exact result's. "
     << "`✗ V/E/F`: they differ, and the competitor's counts are shown. The exact result is minksum's (`chms`, the "
     << "oracle, when it ran; all minksum methods must agree, and are checked here too).\n"
     << "* `> " << fmt(info.cap) << " s`: the cell was stopped at the cap (SIGALRM in the child). `skip [n]`: not "
     << "run, for the reason in footnote n (e.g. the v_A·v_B pairwise sums would not fit; or a smaller row of the "
     << "same series already exceeded the cap, or its time times the growth of the method's cost term — v_A·v_B "
     << "for hull-of-pairwise-sums methods and Nef, f_A·v_B + f_B·v_A + e_A·e_B for cvms/essdms/mssd, the input "
     << "size for the others (cgm, walk, SGM; walk's cost is input + output size, but a row's output is not "
     << "known before its cells run, and the input size grows like it along a series) — predicts more than " << fmt(info.predict_factor) << " × the cap). `failed [n]`: "
     << "the contender threw or crashed.\n"
     << "* minksum methods: `minkowski_sum(a, b, method)`, whose result has explicit exact coordinates"
     << (std::any_of(cs.begin(), cs.end(), [](const Contender& c) { return c.key == "walk"; })
             ? "; except **walk**: `minkowski_walk(a, b)` alone, whose result is the exact sum as a half-edge "
               "structure with implicit coordinates (vertex = pair of input vertices); `(+ conversion s)` is "
               "`to_polytope`, the conversion of that result to a polytope with explicit exact coordinates "
               "(planes on demand), timed in every run right after the walk (as `minkowski_sum` runs them; its median) "
               "and not included in the first figure (walk's first "
               "figure plus its conversion is what `minkowski_sum(a, b, Method::walk)` costs)"
             : "")
     << ".\n"
     << "* Competitors:\n"
     << "  * **CGAL hull, exact sums** — `CGAL::convex_hull_3` (Epeck) on the exact pairwise sums a_i + b_j "
     << "(the same algorithm as minksum `chms`, without the exact merge of coplanar triangles, which is done "
     << "untimed for counting).\n"
     << "  * **CGAL hull, Epick (rounded)** — the pairwise sums of the nearest doubles, added in double arithmetic "
     << "(untimed), then `convex_hull_3` (timed) with `Exact_predicates_inexact_constructions_kernel`. Its counts are those of the "
     << "exact hull of the *rounded* points, coplanar triangles merged exactly.\n"
     << "  * **Qhull (rounded)** — `qh_new_qhull` with options `qhull` (default pre-merge `C-0`) on the same "
     << "rounded sums, timed alone. Counts: Qhull's merged facets and vertices, E = V + F − 2.\n"
     << "  * **CGAL Nef minkowski_sum_3** — Hachenberger's method on `Nef_polyhedron_3<Epeck>` (\"NGM\" in Barki et "
     << "al. 2009); timed: `minkowski_sum_3` alone, not the conversion of the operands to Nef polyhedra.\n"
     << "  * **CGAL SGM (build + overlay)** — the undocumented `Arr_polyhedral_sgm` (spherical Gaussian map) "
     << "with Epeck: both maps built and overlaid; `(overlay s)` is the overlay alone. Counts are read off the "
     << "map.\n"
     << "  * **polymake `minkowski_sum_fukuda`: not included.** Debian's `polymake` 4.6 package alone installs "
     << "about 105 MB and pulls perl, Singular, flint, ppl and ninja; it is outside the CI budget of this project "
     << "and is not installed.\n"
     << "* Limits of this run: cap " << fmt(info.cap) << " s per cell; address space " << info.mem_limit_mb
     << " MiB per cell; pairwise-sum methods skipped beyond " << fmt(info.exact_pair_limit)
     << " sums (exact) / " << fmt(info.float_pair_limit) << " sums (floating point).\n\n";

  auto group = [&](const std::string& g) {
    std::vector<const RowResult*> out;
    for (const auto& r : rows)
      if (r.row.group == g) out.push_back(&r);
    return out;
  };

  // --- Table 1.
  auto t1 = group("table1");
  if (!t1.empty()) {
    md << "## Barki et al. 2009, Table 1: cube ⊕ growing solids\n\n";
    table(md, info, cs, t1, false);
    md << "Barki et al.'s published seconds for the same pairs (2.2 GHz Intel Core 2 Duo, 2 GB RAM), beside this "
          "run's. NGM is CGAL's Nef `minkowski_sum_3`; CGM is Fogel and Halperin's cubical Gaussian map (the "
          "closest thing here is CGAL's spherical Gaussian map, a different but related structure); Fuk. is "
          "Weibel's implementation of Fukuda's algorithm (not run here)."
       << (has_walk ? " walk's figure, when it is the fastest, is the walk alone (implicit coordinates), "
                      "without its conversion."
                    : "")
       << "\n\n"
       << "| A ⊕ B | CHMS | ESSDMS | CVMS | MSSD | NGM | Fuk. | CGM overlay | CGM whole | this run: chms | "
          "this run: cvms | this run: fastest minksum | this run: Nef | this run: SGM |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const RowResult* rr : t1) {
      const Published* p = nullptr;
      for (const auto& q : kTable1)
        if (rr->row.b == q.b) p = &q;
      if (!p) continue;
      auto here = [&](const std::string& key) -> std::string {
        auto it = rr->cells.find(key);
        if (it == rr->cells.end()) return "n/a";
        const Cell& c = it->second;
        if (c.state == Cell::ok) return fmt(c.median);
        if (c.state == Cell::capped) return "> " + fmt(info.cap);
        return c.state == Cell::skipped ? "skipped" : "failed";
      };
      std::string best = "—";
      double bt = 1e300;
      for (const auto& k : ours)
        if (const Cell* c = ok_cell(*rr, k); c && c->median < bt) bt = c->median, best = fmt(c->median) + " (" + k + ")";
      md << "| " << pair_name(rr->row) << " | " << fmt(p->chms) << " | " << fmt(p->essdms) << " | "
         << fmt(p->cvms) << " | " << fmt(p->mssd) << " | " << fmt(p->ngm) << " | " << fmt(p->fuk) << " | "
         << fmt(p->cgm_overlay) << " | " << fmt(p->cgm_whole) << " | " << here("chms") << " | " << here("cvms")
         << " | " << best << " | " << here("nef") << " | " << here("sgm") << " |\n";
    }
    md << "\n";
  }

  struct Section {
    const char* group;
    const char* title;
    const char* text;
  };
  const Section sections[] = {
      {"rotated", "Geodesic sphere ⊕ rotated geodesic sphere",
       "`sphere:k@rot:1` is the same sphere under an exact rational rotation: its coordinates are rationals, "
       "not doubles, so the floating-point competitors see rounded inputs."},
      {"random", "Random polytopes", "`random:N:SEED` is the exact hull of N pseudo-random unit vectors (all N "
                                     "are vertices)."},
      {"dioctagonal", "Dioctagonal pyramids (Fogel and Halperin's Θ(mn) example)",
       "A squashed dioctagonal pyramid and a copy rotated by exactly 90° about the x axis."},
      {"identical", "Identical operands (A ⊕ A)",
       "Every facet of A meets its parallel twin: the sum's facets are facets of A scaled by 2, and the "
       "pairwise sums contain many coplanar points. Floating-point hulls of rounded sums are where the "
       "combinatorics break."},
  };
  for (const auto& s : sections) {
    auto g = group(s.group);
    if (g.empty()) continue;
    md << "## " << s.title << "\n\n" << s.text << "\n\n";
    table(md, info, cs, g, false);
  }
  auto cat = group("catalog");
  if (!cat.empty()) {
    md << "## Catalog pairs (after Table 4 of Fogel and Halperin, 2006)\n\n"
       << "Fogel and Halperin's Table 4 compares their CGM with Nef, Fukuda and the convex-hull method on catalog pairs and "
          "reports F/(F_A·F_B): the higher it is, the more an output-sensitive method gains over the hull of all "
          "pairwise sums. The table's figures are not legible in our copy of the paper, so only the pairs' "
          "kind is reproduced (icosahedron pairs, dioctagonal pyramids, pentagonal hexecontahedron ⊕ truncated "
          "icosidodecahedron, geodesic sphere ⊕ rotated copy), with the ratio computed here.\n\n";
    table(md, info, cs, cat, true);
  }

  // --- Ratios.
  md << "## Ratios (same run): competitor time ÷ minksum time\n\n"
     << "Per row, the fastest minksum method that finished, and each competitor's median divided by it "
        "(> 1: minksum is faster). `chms ÷ CGAL exact` compares minksum's oracle with the same algorithm run "
        "bare in CGAL.";
  if (has_walk)
    md << " walk's time is the walk alone: its exact half-edge result with implicit coordinates, without the "
          "conversion to explicit rational coordinates that the other minksum methods' results include (the "
          "conversion is shown beside it when walk is the fastest). `Qhull ÷ (walk + conversion)` compares Qhull, "
          "whose output has explicit (rounded) coordinates, with walk's explicit result.";
  md << "\n\n"
     << "| A ⊕ B | fastest minksum | Qhull ÷ | Epick hull ÷ | CGAL exact hull ÷ | Nef ÷ | SGM ÷ | CGAL exact hull ÷ "
        "chms | Qhull ÷ cvms |"
     << (has_walk ? " Qhull ÷ (walk + conversion) |" : "") << "\n|---|---|---:|---:|---:|---:|---:|---:|---:|"
     << (has_walk ? "---:|" : "") << "\n";
  std::map<std::string, std::vector<double>> all;
  for (const auto& rr : rows) {
    const Cell* best = nullptr;
    std::string bk;
    for (const auto& k : ours)
      if (const Cell* c = ok_cell(rr, k); c && (!best || c->median < best->median)) best = c, bk = k;
    if (!best) continue;
    md << "| " << pair_name(rr.row) << " | " << bk << " " << fmt(best->median) << " s"
       << (bk == "walk" && best->sub >= 0 ? " (+ conversion " + fmt(best->sub) + " s)" : "") << " |";
    auto ratio_to = [&](const std::string& comp, double base, const std::string& tag) {
      const Cell* c = ok_cell(rr, comp);
      if (!c || base <= 0) {
        md << " — |";
        return;
      }
      double r = c->median / base;
      all[tag].push_back(r);
      md << " " << fmt_ratio(r) << " |";
    };
    auto ratio = [&](const std::string& comp, const Cell* base, const std::string& tag) {
      ratio_to(comp, base ? base->median : -1, tag);
    };
    ratio("qhull", best, "qhull");
    ratio("cgal-epick", best, "epick");
    ratio("cgal-exact", best, "exact");
    ratio("nef", best, "nef");
    ratio("sgm", best, "sgm");
    ratio("cgal-exact", ok_cell(rr, "chms"), "exact/chms");
    ratio("qhull", ok_cell(rr, "cvms"), "qhull/cvms");
    if (has_walk) {
      const Cell* w = ok_cell(rr, "walk");
      ratio_to("qhull", w && w->sub >= 0 ? w->median + w->sub : -1, "qhull/walk+conv");
    }
    md << "\n";
  }
  md << "| **geometric mean** | |";
  std::vector<std::string> tags = {"qhull", "epick", "exact", "nef", "sgm", "exact/chms", "qhull/cvms"};
  if (has_walk) tags.push_back("qhull/walk+conv");
  for (const auto& tag : tags) {
    auto it = all.find(tag);
    if (it == all.end() || it->second.empty()) md << " — |";
    else md << " " << fmt_ratio(geomean(it->second)) << " (" << it->second.size() << " rows) |";
  }
  md << "\n\n";

  // --- Combinatorics of floating-point competitors.
  md << "## Where floating point changes the answer\n\n"
     << "Rows where a competitor's V/E/F differ from the exact sum (the exact result's counts first):\n\n";
  int wrong = 0;
  for (const auto& rr : rows) {
    if (rr.v < 0) continue;
    for (const auto& c : cs) {
      const Cell* cell = ok_cell(rr, c.key);
      if (!cell || cell->v < 0) continue;
      if (cell->v == rr.v && cell->e == rr.e && cell->f == rr.f) continue;
      md << "* " << pair_name(rr.row) << ": exact " << vef(rr.v, rr.e, rr.f) << ", " << c.label << " "
         << vef(cell->v, cell->e, cell->f) << "\n";
      ++wrong;
    }
  }
  if (!wrong) md << "* none in this run\n";
  md << "\nThe Epick hull is the exact hull of the *rounded* sums: an edge ⊕ edge parallelogram (or a larger "
        "planar facet) whose rounded corners are no longer coplanar becomes several triangles, and on A ⊕ A "
        "points that should lie inside a facet poke out of it. Qhull's counts often agree with the exact ones "
        "because its default pre-merge (`C-0`) merges facets that are coplanar within its roundoff estimate: "
        "a tolerance decision, not an exact one, and its vertices are the rounded points.\n\n";

  // --- Memory.
  md << "## Peak memory of the largest rows\n\n"
     << "Peak resident set (VmHWM) of each cell's process in MiB; it includes the operands, built by that process "
        "(their size, VmRSS once they were built, is in the second column)."
     << (has_walk ? " walk's cell runs the walk and then the conversion in the same process: its peak covers both."
                  : "")
     << "\n\n"
     << "| A ⊕ B | operands |";
  for (const auto& c : cs) md << " " << c.label << " |";
  md << "\n|---|---:|";
  for (std::size_t i = 0; i < cs.size(); ++i) md << "---:|";
  md << "\n";
  bool any_large = false;
  for (const auto& rr : rows) {
    if (!rr.row.large) continue;
    any_large = true;
    long base = -1;
    for (const auto& [k, c] : rr.cells)
      if (c.state == Cell::ok) base = std::max(base, c.base_kb);
    md << "| " << pair_name(rr.row) << " | " << (base >= 0 ? std::to_string(base / 1024) : "—") << " |";
    for (const auto& c : cs) {
      const Cell* cell = ok_cell(rr, c.key);
      md << " " << (cell ? std::to_string(cell->peak_kb / 1024) : "—") << " |";
    }
    md << "\n";
  }
  if (!any_large) md << "| (no large rows in this suite) | | | \n";
  md << "\n";

  md << "## Time against input + output size\n\n"
     << "Log-log plot of each contender's median time against n + m + k = F_A + F_B + F (facets of the "
        "operands and of the sum), every row of this run where the cell finished.\n\n"
     << "![time against n + m + k](" << svg_name << ")\n\n";

  md << "## Proximity queries\n\n"
        "Collision, distance and penetration depth against libccd (GJK, GJK+EPA, MPR), on the same pairs "
        "and on a coherent trajectory: [benchmarks-proximity.md](benchmarks-proximity.md), regenerated by "
        "the same `make bench`.\n\n";

  md << "## Non-convex sums\n\n"
        "Sums of non-convex solids (tube, L-bracket, gear with balls and prisms) against CGAL's "
        "`minkowski_sum_3` and Manifold's `minkowskiSum`: "
        "[benchmarks-nonconvex.md](benchmarks-nonconvex.md), regenerated by `make bench-nonconvex`.\n\n";

  md << "## Reproduce\n\n"
     << "```sh\nmake bench        # the full suite: configures build-bench/ (Release, MINKSUM_BENCH=ON, "
        "assertions off), builds, runs, rewrites this page and " << svg_name << "\n"
     << "make bench-quick  # the quick suite for development (under 2 minutes once built), "
        "written to build-bench/quick/\n"
     << "make bench-e2e    # the section \"End to end: file to file\" alone (bench/e2e.py; `make bench` runs it "
        "too)\n"
     << "build-bench/bin/qhull_standalone --runs 9            # Qhull's call on cube ⊕ sphere:6 in a program of its "
        "own\n"
     << "build-bench/bin/qhull_standalone --runs 9 --fork --ballast 500   # ... in a child forked from a large, "
        "fragmented heap\n```\n";

  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << md.str();
}

void write_svg(const std::string& path, const std::vector<Contender>& cs, const std::vector<RowResult>& rows) {
  const double W = 900, H = 560, L = 80, R = 250, T = 30, B = 60;
  struct Pt {
    double x, y;
  };
  std::vector<std::vector<Pt>> lines(cs.size());
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const auto& rr : rows) {
    if (rr.f < 0) continue;
    double x = double(rr.fa + rr.fb + rr.f);
    for (std::size_t i = 0; i < cs.size(); ++i) {
      auto it = rr.cells.find(cs[i].key);
      if (it == rr.cells.end() || it->second.state != Cell::ok || it->second.median <= 0) continue;
      double y = it->second.median;
      lines[i].push_back({x, y});
      xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
  }
  if (xmax <= 0) xmin = 1, xmax = 10, ymin = 1e-3, ymax = 1;
  const int dx0 = int(std::floor(std::log10(xmin))), dx1 = int(std::ceil(std::log10(xmax)));
  const int dy0 = int(std::floor(std::log10(ymin))), dy1 = int(std::ceil(std::log10(ymax)));
  const int nx = std::max(1, dx1 - dx0), ny = std::max(1, dy1 - dy0);
  auto X = [&](double x) { return L + (std::log10(x) - dx0) / nx * (W - L - R); };
  auto Y = [&](double y) { return H - B - (std::log10(y) - dy0) / ny * (H - T - B); };
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2",
                          "#7f7f7f", "#bcbd22", "#17becf", "#ff7f0e", "#000000", "#aec7e8"};
  std::ostringstream s;
  char buf[256];
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // Grid and ticks.
  for (int d = dx0; d <= dx0 + nx; ++d) {
    for (int m = 1; m <= 9; ++m) {
      double v = m * std::pow(10.0, d);
      if (d == dx0 + nx && m > 1) break;
      double x = X(v);
      std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\"/>\n", x,
                    T, x, H - B, m == 1 ? "#bbb" : "#eee");
      s << buf;
    }
    std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">10<tspan dy=\"-6\" "
                  "font-size=\"9\">%d</tspan></text>\n", X(std::pow(10.0, d)), H - B + 18, d);
    s << buf;
  }
  for (int d = dy0; d <= dy0 + ny; ++d) {
    for (int m = 1; m <= 9; ++m) {
      double v = m * std::pow(10.0, d);
      if (d == dy0 + ny && m > 1) break;
      double y = Y(v);
      std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\"/>\n", L,
                    y, W - R, y, m == 1 ? "#bbb" : "#eee");
      s << buf;
    }
    std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">10<tspan dy=\"-6\" "
                  "font-size=\"9\">%d</tspan></text>\n", L - 8, Y(std::pow(10.0, d)) + 4, d);
    s << buf;
  }
  std::snprintf(buf, sizeof buf, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
                "stroke=\"black\"/>\n", L, T, W - L - R, H - T - B);
  s << buf;
  std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">n + m + k = F_A + F_B + F "
                "(facets of operands and sum)</text>\n", (L + W - R) / 2, H - 15);
  s << buf;
  std::snprintf(buf, sizeof buf, "<text transform=\"translate(18,%.1f) rotate(-90)\" text-anchor=\"middle\">"
                "median seconds</text>\n", (T + H - B) / 2);
  s << buf;
  // One polyline per contender, points in order of x.
  for (std::size_t i = 0; i < cs.size(); ++i) {
    auto& pts = lines[i];
    std::sort(pts.begin(), pts.end(), [](const Pt& a, const Pt& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const char* col = colors[i % 12];
    if (!pts.empty()) {
      s << "<polyline fill=\"none\" stroke=\"" << col << "\" stroke-width=\"1.5\" points=\"";
      for (const auto& p : pts) {
        std::snprintf(buf, sizeof buf, "%.1f,%.1f ", X(p.x), Y(p.y));
        s << buf;
      }
      s << "\"/>\n";
      for (const auto& p : pts) {
        std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"%s\"/>\n", X(p.x),
                      Y(p.y), col);
        s << buf;
      }
    }
    double ly = T + 10 + 20 * double(i);
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                  "stroke-width=\"2\"/><text x=\"%.1f\" y=\"%.1f\">", W - R + 15, ly, W - R + 40, ly, col,
                  W - R + 46, ly + 4);
    s << buf << cs[i].label << "</text>\n";
  }
  s << "</svg>\n";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << s.str();
}

}  // namespace minksum::bench
