// minksum bench — results of one suite run and the page generated from them.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace minksum::bench {

// One contender: a minksum method or a competitor.
struct Contender {
  std::string key;     // "cvms", "qhull", ...
  std::string label;   // column heading
  bool ours = false;   // a minksum method
  bool exact = true;   // exact arithmetic (false: floating point on rounded sums)
  bool pairwise = false;  // works on all v_A * v_B pairwise sums
  // The cell's second timing (Cell::sub), when the contender has one: how it
  // is labelled in a cell ("overlay" for CGAL SGM: a phase included in the
  // median; "+ conversion" for walk: a further phase after the timed result),
  // and whether it comes on top of the median (true) or is part of it.
  std::string sub_label;
  bool sub_extra = false;
};

struct Cell {
  enum State { none, ok, capped, skipped, failed } state = none;
  double median = 0;    // seconds, median of `runs`
  double sub = -1;      // median of the second timing, if any
  int runs = 0;
  long v = -1, e = -1, f = -1;
  long peak_kb = -1;    // VmHWM of the cell's process
  long base_kb = -1;    // its VmRSS once it had built the operands, before its first run
  std::string note;     // skip/failure reason, or a remark
};

struct Row {
  std::string group;   // "table1", "rotated", "random", "dioctagonal", "identical", "catalog"
  std::string a, b;    // catalog specs
  std::string series;  // rows of one series grow in size; caps carry over
  bool large = false;  // peak memory reported
};

struct RowResult {
  Row row;
  long va = 0, ea = 0, fa = 0, vb = 0, eb = 0, fb = 0;
  long v = -1, e = -1, f = -1;  // the exact sum (minksum), -1 if no minksum method finished
  double load_seconds = 0;
  std::map<std::string, Cell> cells;
};

struct RunInfo {
  std::string suite;       // "full" or "quick"
  std::string command;     // the make target that produced the page
  int runs = 5;
  double min_total = 1.0;     // fast cells repeat until this many seconds of runs
  int max_runs = 500;
  double cap = 120;
  double long_run = 10;       // a first run longer than this is not repeated
  double predict_factor = 2;  // cells predicted over this many caps are skipped
  double exact_pair_limit = 0, float_pair_limit = 0;
  long mem_limit_mb = 0;
  long trim_mb = 0;        // a cell's process over this size returns free memory between runs
  std::string date, cpu, compiler, flags, cgal, qhull, gmp, minksum, git;
  long cores = 0, mem_mb = 0;
  std::string load_start, load_end;
  double wall_seconds = 0;
};

void write_markdown(const std::string& path, const std::string& svg_name, const RunInfo& info,
                    const std::vector<Contender>& contenders, const std::vector<RowResult>& rows);
void write_svg(const std::string& path, const std::vector<Contender>& contenders,
               const std::vector<RowResult>& rows);

}  // namespace minksum::bench
