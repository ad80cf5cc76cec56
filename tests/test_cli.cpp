// The `minksum` command as users run it: exit codes, JSON keys, output files,
// and the bad-input contract (exit 3, one line on stderr naming the file and
// the problem, no output file written).
#include <gtest/gtest.h>

#include "shell.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct CmdResult {
  int status = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("minksum_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CmdResult run(const std::string& args) { return run_line(std::string(MINKSUM_BIN) + " " + args + " </dev/null"); }

  // Run a shell command line in which every "minksum" is the command under
  // test (pipes, redirections); stderr of the whole line is collected.
  CmdResult run_sh(const std::string& line) {
    std::string cmd;
    for (std::size_t at = 0;;) {
      const std::size_t next = line.find("minksum", at);
      cmd += line.substr(at, next - at);
      if (next == std::string::npos) break;
      cmd += MINKSUM_BIN;
      at = next + 7;
    }
    return run_line(cmd);
  }

  // A shell command line: out is its stdout, err its stderr (through a file).
  CmdResult run_line(const std::string& cmd) {
    fs::path err = dir_ / "stderr.txt";
    CmdResult r;
    const ShellOutput o = shell_stdout("{ " + cmd + " ; } 2>" + err.string());
    if (o.status < 0) return r;
    r.status = o.status;
    r.out = o.out;
    r.err = slurp(err);
    return r;
  }

  // Integer value of "key": N in a JSON line.
  static long json_int(const std::string& json, const std::string& key) {
    std::smatch m;
    std::regex re("\"" + key + "\": (-?[0-9]+)");
    if (!std::regex_search(json, m, re)) return -1;
    return std::stol(m[1]);
  }

  // Run the command with stdin, stdout and stderr on a new pseudo-terminal,
  // as in an interactive shell; out is everything the terminal received
  // (stdout and stderr interleaved, "\n" written as "\r\n").
  CmdResult run_pty(const std::string& args) {
    const std::string cmd = "exec " + std::string(MINKSUM_BIN) + " " + args;
    CmdResult r;
    int master = -1;
    const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
    if (pid < 0) return r;
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::array<char, 4096> buf;
    for (;;) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pid, SIGKILL);
        break;
      }
      pollfd fd{master, POLLIN, 0};
      if (::poll(&fd, 1, 100) <= 0) continue;
      const ssize_t n = ::read(master, buf.data(), buf.size());
      if (n > 0) r.out.append(buf.data(), static_cast<std::size_t>(n));
      else if (n == 0 || errno != EINTR) break;  // EIO: the child closed the terminal
    }
    ::close(master);
    int st = 0;
    ::waitpid(pid, &st, 0);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    return r;
  }

  // Two JSON outputs describe the same solid: counts and exact volume.
  static void expect_same_solid(const std::string& a, const std::string& b) {
    for (const char* key : {"vertices", "edges", "facets"}) EXPECT_EQ(json_int(a, key), json_int(b, key)) << key;
    const std::regex volume("\"volume\": \"[0-9/]+\"");
    std::smatch va, vb;
    ASSERT_TRUE(std::regex_search(a, va, volume)) << a;
    ASSERT_TRUE(std::regex_search(b, vb, volume)) << b;
    EXPECT_EQ(va.str(), vb.str());
  }

  // Value of "key": X.Y in a JSON line (-1 when absent).
  static double json_double(const std::string& json, const std::string& key) {
    std::smatch m;
    std::regex re("\"" + key + "\": ([0-9.eE+-]+)");
    if (!std::regex_search(json, m, re)) return -1;
    return std::stod(m[1]);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string data(const std::string& rel) { return std::string(MINKSUM_TEST_DATA) + "/" + rel; }

  fs::path dir_;
};

// The command line of the cubical Gaussian map: minksum cgm P [Q] [--svg OUT]
// [--stats] [--json].
class CgmCli : public Cli {};

}  // namespace

TEST_F(Cli, HelpAndVersion) {
  CmdResult r = run("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("minksum sum A B"), std::string::npos);
  for (const char* c : {"sum", "stats", "gen"}) {
    CmdResult h = run(std::string(c) + " --help");
    EXPECT_EQ(h.status, 0) << c;
    EXPECT_NE(h.out.find("Usage: minksum " + std::string(c)), std::string::npos) << c;
  }
  EXPECT_NE(run("gen --help").out.find("sphere:L"), std::string::npos);
  EXPECT_EQ(run("--version").status, 0);
}

TEST_F(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("frobnicate").status, 2);
  EXPECT_EQ(run("sum cube").status, 2);
  EXPECT_EQ(run("sum cube cube --bogus").status, 2);
  EXPECT_EQ(run("sum cube cube --method").status, 2);
  CmdResult m = run("sum cube cube --method nonsense");
  EXPECT_EQ(m.status, 2);
  EXPECT_NE(m.err.find("nonsense"), std::string::npos);
  EXPECT_EQ(run("sum cube cube -o " + path("x.xyz")).status, 2);
  EXPECT_EQ(run("sum cube cube --exact -o " + path("x.stl")).status, 2);
  EXPECT_FALSE(fs::exists(path("x.stl")));
  EXPECT_EQ(run("sum not-a-solid cube").status, 2);
  EXPECT_EQ(run("gen sphere:99 -o " + path("s.off")).status, 2);
  EXPECT_EQ(run("gen cube").status, 2);
}

TEST_F(Cli, MethodNotBuiltIsNamed) {
  for (const char* m : {"walk", "cvms", "essdms", "mssd", "cgm"}) {
    CmdResult r = run(std::string("sum cube tetra --method ") + m);
    if (r.status == 0) continue;  // implemented in this build
    EXPECT_EQ(r.status, 2) << m;
    EXPECT_NE(r.err.find(m), std::string::npos) << m;
  }
}

TEST_F(Cli, SumJsonAndOutputFile) {
  std::string out = path("sum.off");
  CmdResult r = run("sum cube octahedron --method chms --json -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"vertices\"", "\"edges\"", "\"facets\"", "\"method\": \"chms\"", "\"seconds\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  long v = json_int(r.out, "vertices"), e = json_int(r.out, "edges"), f = json_int(r.out, "facets");
  EXPECT_EQ(v - e + f, 2);
  ASSERT_TRUE(fs::exists(out));
  CmdResult s = run("stats " + out + " --json");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(json_int(s.out, "vertices"), v);
  EXPECT_EQ(json_int(s.out, "edges"), e);
  EXPECT_EQ(json_int(s.out, "facets"), f);
  // No temporary files are left beside the output.
  for (const auto& entry : fs::directory_iterator(dir_)) {
    std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "sum.off" || name == "stderr.txt") << name;
  }
}

TEST_F(Cli, ExactOutputRoundTrips) {
  // A rotated cube has rational coordinates: --exact keeps them.
  std::string exact = path("r.off"), approx = path("r_double.off");
  ASSERT_EQ(run("gen cube@rot:1,2,3,4 --exact -o " + exact).status, 0);
  ASSERT_EQ(run("sum " + exact + " tetra --exact -o " + path("s.off")).status, 0);
  CmdResult a = run("stats " + exact + " --json");
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_NE(a.out.find("\"coordinates_are_doubles\": false"), std::string::npos);
  EXPECT_NE(a.out.find("\"volume\": \"8\""), std::string::npos) << a.out;  // rotation keeps volume 8 exactly
  ASSERT_EQ(run("gen cube@rot:1,2,3,4 -o " + approx).status, 0);
  CmdResult b = run("stats " + approx + " --json");
  // Rounded to doubles the coordinates are no longer a rotation of the cube:
  // still a valid convex polytope, with a volume that is not exactly 8.
  ASSERT_EQ(b.status, 0) << b.err;  // what minksum writes reads back
  EXPECT_EQ(b.out.find("\"volume\": \"8\""), std::string::npos) << b.out;
}

TEST_F(Cli, HullOfAPointCloud) {
  std::string cloud = path("cloud.off");
  {
    std::ofstream o(cloud);
    o << "OFF\n9 0 0\n";
    for (int i = 0; i < 8; ++i) o << ((i & 1) ? 1 : -1) << " " << ((i & 2) ? 1 : -1) << " " << ((i & 4) ? 1 : -1) << "\n";
    o << "0 0 0\n";
  }
  CmdResult without = run("stats " + cloud);
  EXPECT_EQ(without.status, 3);
  EXPECT_NE(without.err.find("--hull"), std::string::npos);
  CmdResult r = run("stats " + cloud + " --hull --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "vertices"), 8);
  EXPECT_EQ(json_int(r.out, "facets"), 6);
}

TEST_F(Cli, UnwritableOutputExitsOne) {
  std::string out = path("no/such/dir/x.off");
  CmdResult r = run("sum cube cube -o " + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(fs::exists(out));
}

// Every malformed or invalid file in tests/data/bad/: exit 3, exactly one
// line on stderr that names the file, and no output file.
TEST_F(Cli, BadInputExitsThreeWithOneLine) {
  const char* cases[] = {
      "empty.off",          "wrong_magic.off",     "nan.off",           "inf.obj",
      "absurd_count.off",   "absurd_count_binary.ply", "lying_count.off", "out_of_range_index.obj",
      "truncated_binary.stl", "truncated.ply",     "garbage_token.off", "zero_denominator.off",
      "short_face.off",     "open_mesh.off",       "nonmanifold_edge.off", "flipped_facet.off",
      "nonplanar_facet.off", "nonconvex_lprism.off", "two_cubes.off",    "flat.off",
  };
  for (const char* c : cases) {
    SCOPED_TRACE(c);
    std::string in = data(std::string("bad/") + c);
    ASSERT_TRUE(fs::exists(in)) << in;
    std::string out = path("out.off");
    // An L prism and two disjoint cubes are closed solids: sum, stats,
    // convert and view take them (docs/nonconvex.md); the convex-only
    // commands refuse them.
    const bool solid = std::string(c) == "nonconvex_lprism.off" || std::string(c) == "two_cubes.off";
    CmdResult r = run("sum " + in + (solid ? " tube -o " : " cube -o ") + out);
    if (solid) {
      EXPECT_EQ(r.status, 0) << r.err;
      fs::remove(out);
      CmdResult st = run("stats " + in);
      EXPECT_EQ(st.status, 0) << st.err;
      CmdResult q = run("query distance " + in + " cube");
      EXPECT_EQ(q.status, 3) << q.err;
      continue;
    }
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    CmdResult s = run("stats " + in);
    EXPECT_EQ(s.status, 3) << s.err;
  }
}

// A closed surface that is not exactly convex (what a CAD tool's rounded
// export gives) is refused with a hint that --hull accepts it; with --hull it
// is accepted.  Malformed files get no such hint.
TEST_F(Cli, NotConvexInputSuggestsHull) {
  for (const char* c : {"nonplanar_facet.off", "nonconvex_lprism.off"}) {
    SCOPED_TRACE(c);
    const std::string in = data(std::string("bad/") + c);
    // sum and stats take the L prism as the solid it is (docs/nonconvex.md);
    // query, which takes convex operands only, refuses it naming --hull.
    const bool solid = std::string(c) == "nonconvex_lprism.off";
    for (const std::string& cmd : {"stats " + in, "sum " + in + " cube", "query distance " + in + " cube"}) {
      if (solid && cmd[0] == 's') {
        EXPECT_EQ(run(cmd).status, 0) << cmd;
        continue;
      }
      CmdResult r = run(cmd);
      EXPECT_EQ(r.status, 3) << r.err;
      EXPECT_NE(r.err.find("; --hull takes the convex hull of its points instead"), std::string::npos) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      CmdResult h = run(cmd + " --hull");
      EXPECT_EQ(h.status, 0) << h.err;
    }
  }
  CmdResult open = run("stats " + data("bad/open_mesh.off"));
  EXPECT_EQ(open.status, 3);
  EXPECT_EQ(open.err.find("--hull"), std::string::npos) << open.err;
}

TEST_F(Cli, RepairableInputsAreAccepted) {
  CmdResult inward = run("stats " + data("bad/inward_cube.off") + " --json");
  ASSERT_EQ(inward.status, 0) << inward.err;
  EXPECT_EQ(json_int(inward.out, "facets"), 6);
  CmdResult stl = run("stats " + data("bad/triangulated_cube.stl") + " --json");
  ASSERT_EQ(stl.status, 0) << stl.err;
  EXPECT_EQ(json_int(stl.out, "vertices"), 8);
  EXPECT_EQ(json_int(stl.out, "edges"), 12);
  EXPECT_EQ(json_int(stl.out, "facets"), 6);
}

TEST_F(Cli, GenWritesEveryFormat) {
  for (const char* ext : {"off", "obj", "ply", "stl", "wrl"}) {
    std::string out = path(std::string("d.") + ext);
    CmdResult g = run("gen dodecahedron -o " + out);
    ASSERT_EQ(g.status, 0) << ext << ": " << g.err;
    CmdResult s = run("stats " + out + " --json");
    ASSERT_EQ(s.status, 0) << ext << ": " << s.err;
    EXPECT_EQ(json_int(s.out, "vertices"), 20) << ext;
    EXPECT_EQ(json_int(s.out, "edges"), 30) << ext;
    EXPECT_EQ(json_int(s.out, "facets"), 12) << ext;
  }
}

// The progress line of `minksum sum` (stderr, after 1 s, only on a terminal).
// A sum of about 2.5 s on 2 cores: the hull of 642 × 400 = 256 800 pairwise sums.
constexpr const char* kSlowSum = "sum sphere:4 random:400:1 --method chms --json";

TEST_F(Cli, SumProgressNotPrintedWhenStderrIsNotATerminal) {
  CmdResult r = run(kSlowSum);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(json_double(r.out, "seconds"), 1.0) << "the sum is too fast to exercise the progress line";
  EXPECT_EQ(r.err, "");
}

TEST_F(Cli, SumProgressLineOnATerminal) {
  CmdResult r = run_pty(kSlowSum);
  ASSERT_EQ(r.status, 0) << r.out;
  const double seconds = json_double(r.out, "seconds");
  ASSERT_GT(seconds, 0) << r.out;
  if (seconds < 1.3) GTEST_SKIP() << "the sum took " << seconds << " s: too fast for a progress line";
  // At least one line "\rminksum sum: PHASE[ NN%] (S.S s)", each redrawn from column 0
  // and cleared to the end of the line.
  std::regex line("\rminksum sum: ([a-z][a-z0-9_-]*)( [0-9]{1,3}%)? \\([0-9]+\\.[0-9] s\\)\x1b\\[K");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out;
  RecordProperty("phase", m[1].str());  // "computing", or the phase the method reports
  // Then the line is erased, and stdout follows intact on a clean line.
  const std::size_t erase = r.out.rfind("\r\x1b[K");
  ASSERT_NE(erase, std::string::npos);
  const std::string rest = r.out.substr(erase + 4);
  EXPECT_EQ(rest.find("minksum sum:"), std::string::npos) << rest;
  EXPECT_EQ(rest.find('\x1b'), std::string::npos) << rest;
  ASSERT_FALSE(rest.empty());
  EXPECT_EQ(rest.front(), '{') << rest;
  EXPECT_EQ(rest.substr(rest.size() - 3), "}\r\n") << rest;
  EXPECT_NE(rest.find("\"method\": \"chms\""), std::string::npos) << rest;
  EXPECT_EQ(json_int(rest, "vertices"), json_int(r.out, "vertices"));
  EXPECT_GT(json_int(rest, "vertices"), 0) << rest;
  // Nothing but progress lines, their erasure and the JSON object reached the terminal.
  EXPECT_EQ(std::regex_replace(r.out.substr(0, erase), line, ""), "") << r.out;
}

TEST_F(Cli, SumProgressNotPrintedForAFastSum) {
  CmdResult r = run_pty("sum cube cube");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("minksum sum:"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
  EXPECT_EQ(r.out.rfind("cube (8 V, 6 F)", 0), 0u) << r.out;  // the summary, from the first byte
  EXPECT_NE(r.out.find("= 8 vertices, 12 edges, 6 facets"), std::string::npos) << r.out;
}

TEST_F(CgmCli, StatsOfTheOctahedron) {
  CmdResult r = run("cgm octahedron --stats");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("octahedron: 6 vertices, 12 edges, 8 facets"), std::string::npos) << r.out;
  // Every map: 4 vertices (all real, on the corners), 8 halfedges, 2 faces.
  for (const char* plane : {"x=-1", "y=-1", "z=-1", "x=+1", "y=+1", "z=+1"})
    EXPECT_NE(r.out.find(std::string(plane) + "      4     8     2       4       4"), std::string::npos) << plane;
  EXPECT_NE(r.out.find("total         24    48    12"), std::string::npos) << r.out;
  CmdResult j = run("cgm tetra --json");
  ASSERT_EQ(j.status, 0);
  EXPECT_NE(j.out.find("{\"id\": 5, \"vertices\": 4, \"halfedges\": 10, \"faces\": 3"), std::string::npos) << j.out;
}

TEST_F(CgmCli, SvgIsWellFormedAndWrittenAtomically) {
  const fs::path dir = dir_ / "svg";
  fs::create_directories(dir);
  fs::path out = dir / "sum.svg";
  CmdResult r = run("cgm cube octahedron --svg " + out.string());
  ASSERT_EQ(r.status, 0);
  const std::string svg = slurp(out);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  std::size_t groups = 0, open_g = 0, close_g = 0;
  for (std::size_t at = 0; (at = svg.find("<g id=\"map", at)) != std::string::npos; ++at) ++groups;
  for (std::size_t at = 0; (at = svg.find("<g ", at)) != std::string::npos; ++at) ++open_g;
  for (std::size_t at = 0; (at = svg.find("</g>", at)) != std::string::npos; ++at) ++close_g;
  EXPECT_EQ(groups, 6u);
  EXPECT_EQ(open_g, close_g);
  EXPECT_NE(svg.find("#d62728"), std::string::npos);            // first operand's edges
  EXPECT_NE(svg.find("#1f77b4"), std::string::npos);            // second operand's edges
  // Only the finished file is left (no temporary).
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  // The tetrahedron's maps keep their artificial square sides: dashed.
  ASSERT_EQ(run("cgm tetra --svg " + out.string()).status, 0);
  EXPECT_NE(slurp(out).find("stroke-dasharray"), std::string::npos);
  // An unwritable destination: status 1, nothing left behind.
  CmdResult bad = run("cgm cube --svg " + (dir / "no" / "such" / "x.svg").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_FALSE(fs::exists(dir / "no"));
}

// The README's CGM picture of dioctagonal:17 ⊕ dioctagonal:17@rot:100,0,0,99
// had no title, no legend and no face names, and its 64 dots of radius 2.5
// around the pole of map 5 merged into a black ring: now a title naming the
// operands, a legend (P's, Q's and both's arcs, artificial edges, facet
// normals), each square named by its map id and plane, and a zoom inset
// where the dots crowd, in which no two dots overlap.
TEST_F(CgmCli, SvgHasTitleLegendFaceNamesAndDotsThatDoNotMerge) {
  const fs::path out = dir_ / "cgm.svg";
  ASSERT_EQ(run("cgm dioctagonal:17 dioctagonal:17@rot:100,0,0,99 --svg " + out.string()).status, 0);
  const std::string svg = slurp(out);
  EXPECT_NE(svg.find("<title>Cubical Gaussian Map of P ⊕ Q</title>"), std::string::npos);
  EXPECT_NE(svg.find(">P = dioctagonal:17, Q = dioctagonal:17@rot:100,0,0,99<"), std::string::npos);
  for (const char* name : {"0: x = −1", "1: y = −1", "2: z = −1", "3: x = +1", "4: y = +1", "5: z = +1"})
    EXPECT_NE(svg.find(std::string(">") + name + "<"), std::string::npos) << name;
  for (const char* row : {"arc of P (first operand)", "arc of Q (second operand)", "arc of both", "artificial edge", "facet normal"})
    EXPECT_NE(svg.find(std::string(">") + row + "<"), std::string::npos) << row;
  // The inset: at least two dots (the closest pair), no two of them overlapping.
  const std::size_t g = svg.find("<g clip-path=\"url(#inset-clip)\">"), end = svg.find("</g>", g);
  ASSERT_NE(g, std::string::npos);
  EXPECT_NE(svg.find("map 5 magnified"), std::string::npos);
  const std::string inset = svg.substr(g, end - g);
  std::vector<std::array<double, 3>> dots;
  const std::regex circle("<circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\" r=\"([0-9.]+)\"");
  for (auto it = std::sregex_iterator(inset.begin(), inset.end(), circle); it != std::sregex_iterator(); ++it)
    dots.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
  ASSERT_GE(dots.size(), 2u);
  for (std::size_t i = 0; i < dots.size(); ++i)
    for (std::size_t j = i + 1; j < dots.size(); ++j)
      EXPECT_GT(std::hypot(dots[i][0] - dots[j][0], dots[i][1] - dots[j][1]), dots[i][2] + dots[j][2]) << i << " " << j;
  // One polytope: its name as the title, and no operand colours in the legend.
  ASSERT_EQ(run("cgm cube --svg " + out.string()).status, 0);
  const std::string one = slurp(out);
  EXPECT_NE(one.find("<title>Cubical Gaussian Map of cube</title>"), std::string::npos);
  EXPECT_EQ(one.find("arc of P"), std::string::npos);
  EXPECT_NE(one.find(">arc (an edge)<"), std::string::npos);
  EXPECT_EQ(one.find("inset"), std::string::npos);  // the cube's six dots are far apart
}

TEST_F(CgmCli, UsageAndInputErrors) {
  EXPECT_EQ(run("cgm").status, 2);
  EXPECT_EQ(run("cgm cube cube cube").status, 2);
  EXPECT_EQ(run("cgm cube --bogus").status, 2);
  EXPECT_EQ(run("cgm /nonexistent/missing.off").status, 3);
  EXPECT_EQ(run("cgm --help").status, 0);
}

TEST_F(CgmCli, SumMethodCgm) {
  CmdResult r = run("sum cube octahedron --method cgm --json");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("\"method\": \"cgm\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"facets\": 26"), std::string::npos) << r.out;
}

// Every option a command's --help lists is in that command's lines of the
// top-level usage (--output as -o); the commands are read from the usage itself.
TEST_F(Cli, TopLevelUsageNamesEveryOption) {
  const std::string usage = run("--help").out;
  std::istringstream lines(usage.substr(0, usage.find("\n\n", usage.find("Usage:"))));
  std::map<std::string, std::string> block;  // command -> its usage lines
  std::string line, current;
  const std::regex head(R"(^  minksum ([a-z]+) )");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_search(line, m, head)) current = m[1];
    else if (line.rfind("  minksum ", 0) == 0) current.clear();
    if (!current.empty()) block[current] += line + "\n";
  }
  ASSERT_GE(block.size(), 6u) << usage;
  for (const auto& [command, text] : block) {
    const CmdResult h = run(command + " --help");
    ASSERT_EQ(h.status, 0) << command;
    const std::regex option(R"((^|[\s\[,])(--[a-z][a-z-]*))");
    int seen = 0;
    for (auto it = std::sregex_iterator(h.out.begin(), h.out.end(), option); it != std::sregex_iterator(); ++it) {
      const std::string o = (*it)[2];
      if (o == "--help") continue;
      ++seen;
      const bool named = text.find(o) != std::string::npos || (o == "--output" && text.find("-o ") != std::string::npos);
      EXPECT_TRUE(named) << "'minksum " << command << " --help' lists " << o << ", the usage does not:\n" << text;
    }
    EXPECT_GT(seen, 0) << command;
  }
}

// Each option of 'query --help' starts its own sentence (two options once
// shared one sentence split across their lines).
TEST_F(Cli, QueryHelpRotateOptionsEachExplained) {
  const std::string h = run("query --help").out;
  const std::regex rotate_q(R"(--rotate-q A,B,C,D +([^\n]*))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(h, m, rotate_q)) << h;
  EXPECT_TRUE(std::isupper(static_cast<unsigned char>(m[1].str()[0])) || m[1].str().rfind("rotate", 0) == 0)
      << m[1];
  EXPECT_EQ(m[1].str().find(')'), std::string::npos) << "continues the sentence of --rotate-p: " << m[1];
}

// query --json gives the closest points exactly, as the text output does,
// and their doubles beside.
TEST_F(Cli, QueryJsonClosestPointsExact) {
  const CmdResult r = run("query distance cube cube --translate-q 3,1/3,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(R"("point_p_exact": ["1", "1/6", "0"])"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"("point_q_exact": ["2", "1/6", "0"])"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"("point_p": [1, 0.16666666666666666, 0])"), std::string::npos) << r.out;
  const CmdResult t = run("query distance cube cube --translate-q 3,1/3,0");
  EXPECT_NE(t.out.find("closest points (1, 1/6, 0) on P, (2, 1/6, 0) on Q"), std::string::npos) << t.out;
}

// Under --rotate-q, collide, distance and depth are answered on the placed bodies
// (no M): the same exact values as on M of the rotated operand, with the
// certificate named; a trajectory that turns does not compute M.
TEST_F(Cli, QueryUnderRotationWithoutM) {
  const CmdResult rigid = run("query distance cube dodecahedron --rotate-q 1,2,3,4 --translate-q 4,1/3,0 --json");
  const CmdResult on_m = run("query distance cube dodecahedron@rot:1,2,3,4 --translate-q 4,1/3,0 --json");
  ASSERT_EQ(rigid.status, 0) << rigid.err;
  ASSERT_EQ(on_m.status, 0) << on_m.err;
  EXPECT_NE(rigid.out.find(R"("certificate": "closest_points")"), std::string::npos) << rigid.out;
  EXPECT_EQ(rigid.out.find("witness"), std::string::npos) << rigid.out;
  const auto field = [](const std::string& out, const std::string& key) {
    const std::size_t at = out.find("\"" + key + "\": ");
    return at == std::string::npos ? std::string("missing") : out.substr(at, out.find(']', at) - at);
  };
  for (const char* key : {"squared_distance", "point_p_exact", "point_q_exact", "direction"})
    EXPECT_EQ(field(rigid.out, key), field(on_m.out, key)) << key << "\n" << rigid.out << "\n" << on_m.out;
  const CmdResult deep = run("query depth cube dodecahedron --rotate-q 1,2,3,4 --translate-q 1/2,1/3,0 --json");
  const CmdResult deep_m = run("query depth cube dodecahedron@rot:1,2,3,4 --translate-q 1/2,1/3,0 --json");
  EXPECT_NE(deep.out.find(R"("certificate": "nearest_facet")"), std::string::npos) << deep.out;
  for (const char* key : {"squared_depth", "direction"})
    EXPECT_EQ(field(deep.out, key), field(deep_m.out, key)) << key << "\n" << deep.out << "\n" << deep_m.out;
  const std::string dd = " --translate-q 1/2,1/3,0 --direction 1,2,0 --json";
  const CmdResult dir = run("query ddepth cube dodecahedron --rotate-q 1,2,3,4" + dd);
  const CmdResult dir_m = run("query ddepth cube dodecahedron@rot:1,2,3,4" + dd);
  EXPECT_NE(dir.out.find(R"("certificate": "exit_facet")"), std::string::npos) << dir.out;
  for (const char* key : {"t", "direction"})
    EXPECT_EQ(field(dir.out, key), field(dir_m.out, key)) << key << "\n" << dir.out << "\n" << dir_m.out;
  // Touching corner to corner: proved by the plane of the touching features,
  // without M; the common point is the corner (1, 1, 1).
  const CmdResult touch = run("query collide cube cube --rotate-q 1,0,0,0 --translate-q 2,2,2");
  EXPECT_NE(touch.out.find("touching  [certificate: feature_plane, without M]"), std::string::npos) << touch.out;
  const CmdResult corner = run("query distance cube cube --rotate-q 1,0,0,0 --translate-q 2,2,2 --json");
  EXPECT_NE(corner.out.find(R"("point_p_exact": ["1", "1", "1"], "point_q": [1, 1, 1], "point_q_exact": ["1", "1", "1"], "certificate": "feature_plane")"),
            std::string::npos)
      << corner.out;
  std::ofstream(path("poses.txt")) << "3,0,0 rq=1,2,3,4\n3,1/10,0\n1/2,0,0 rq=2,0,0,1\n";
  const CmdResult traj = run("query distance cube cube --trajectory " + path("poses.txt"));
  ASSERT_EQ(traj.status, 0) << traj.err;
  EXPECT_NE(traj.out.find("3 poses"), std::string::npos) << traj.out;
  EXPECT_NE(traj.out.find("3 under rotation (3 certified without M, 0 on M built exactly)"), std::string::npos)
      << traj.out;
  EXPECT_EQ(traj.out.find("computations of M"), std::string::npos) << traj.out;
  EXPECT_NE(traj.out.find("pose 3 (line 3): penetrating"), std::string::npos) << traj.out;
}

// A misspelt catalog name as an operand or for gen gets the catalog's
// suggestion (docs/catalog.md shows it).
TEST_F(Cli, MisspeltCatalogNameSuggestsClosest) {
  for (const std::string& cmd : std::vector<std::string>{"stats tetrahedra", "sum tetrahedra cube", "gen tetrahedra -o " + path("t.off")}) {
    const CmdResult r = run(cmd);
    EXPECT_EQ(r.status, 2) << cmd;
    EXPECT_NE(r.err.find("(did you mean 'tetrahedron'?)"), std::string::npos) << cmd << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(fs::exists(path("t.off")));
  const CmdResult far = run("stats zzzzzzzzzz");
  EXPECT_EQ(far.status, 2);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

// --- output that reads back, chaining, pipes, convert -------------------------

namespace {
// Every output a command can ask for: extension and --binary.
const std::vector<std::pair<std::string, bool>> kEveryOutput = {
    {"off", false}, {"obj", false}, {"ply", false}, {"ply", true}, {"stl", false}, {"stl", true}, {"wrl", false}};
std::string output_flags(const std::pair<std::string, bool>& o) { return o.second ? " --binary" : ""; }
std::size_t lines(const std::string& s) { return std::size_t(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

// minksum sum sphere:4 sphere:4@rot:5 -o s.off used to write doubles whose
// facets were not exactly planar ('stats s.off': "facet 2560: is not
// planar"; as .stl, a reflex edge).  Every format now reads back; the note
// says how far the vertices moved, on one line.
TEST_F(Cli, RoundedSphereSumReadsBack) {
  for (const auto& o : kEveryOutput) {
    SCOPED_TRACE(o.first + output_flags(o));
    const std::string out = path("s." + o.first);
    CmdResult r = run("sum sphere:4 sphere:4@rot:5 --json -o " + out + output_flags(o));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("minksum: note: " + out + ": "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("largest vertex displacement"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("\"rounding\": {\"coordinates\": "), std::string::npos) << r.out;
    EXPECT_GT(json_double(r.out, "max_displacement"), 0) << r.out;
    EXPECT_LT(json_double(r.out, "max_displacement"), o.second && o.first == "stl" ? 1e-6 : 1e-15) << r.out;
    CmdResult s = run("stats " + out + " --json");
    ASSERT_EQ(s.status, 0) << s.err;
    EXPECT_EQ(s.err, "");
    EXPECT_EQ(json_int(s.out, "vertices") - json_int(s.out, "edges") + json_int(s.out, "facets"), 2);
  }
  // --exact keeps every coordinate: read back, the same polytope exactly.
  CmdResult e = run("sum sphere:4 sphere:4@rot:5 --json --exact -o " + path("e.off"));
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(e.err, "");
  EXPECT_NE(e.out.find("\"rounding\": null"), std::string::npos) << e.out;
  CmdResult s = run("stats " + path("e.off") + " --json");
  ASSERT_EQ(s.status, 0) << s.err;
  expect_same_solid(s.out, e.out);
}

// Every writer, every catalog family, rounded and exact, through the command.
TEST_F(Cli, EveryWriterEveryFamilyReadsBack) {
  for (const char* spec : {"dodecahedron@rot:3", "snub-cube", "pentagonal-hexecontahedron@rot:1", "sphere:3@rot:5",
                           "dioctagonal:17@rot:2", "random:100:3@rot:4", "zonotope:6:1@rot:5", "box:1/3:1/7:2@rot:9"}) {
    for (const auto& o : kEveryOutput) {
      SCOPED_TRACE(std::string(spec) + " ." + o.first + output_flags(o));
      const std::string out = path("g." + o.first);
      CmdResult g = run(std::string("gen ") + spec + " -o " + out + output_flags(o));
      ASSERT_EQ(g.status, 0) << g.err;
      EXPECT_LE(lines(g.err), 1u) << g.err;
      CmdResult s = run("stats " + out);
      EXPECT_EQ(s.status, 0) << s.err;
      if (o.first == "ply" || o.first == "stl") continue;
      ASSERT_EQ(run(std::string("gen ") + spec + " --exact -o " + out).status, 0);
      CmdResult x = run("stats " + out + " --json"), c = run(std::string("stats ") + spec + " --json");
      ASSERT_EQ(x.status, 0) << x.err;
      auto facts = [](const std::string& json) {  // counts, exact volume, degrees: not the times
        const std::size_t from = json.find("\"vertices\""), to = json.find("\"phases\"");
        return json.substr(from, to - from);
      };
      EXPECT_EQ(facts(x.out), facts(c.out)) << "exact output differs from the catalog polytope";
    }
  }
}

// The note suggests --exact only where --exact works.
TEST_F(Cli, RoundingNoteSuggestsExactOnlyWhereItWorks) {
  for (const auto& o : kEveryOutput) {
    SCOPED_TRACE(o.first + output_flags(o));
    CmdResult g = run("gen cube@rot:1,2,3,4 -o " + path("c." + o.first) + output_flags(o));
    ASSERT_EQ(g.status, 0) << g.err;
    ASSERT_EQ(lines(g.err), 1u) << g.err;
    if (o.first == "off" || o.first == "obj" || o.first == "wrl")
      EXPECT_NE(g.err.find("; --exact keeps them exact"), std::string::npos) << g.err;
    else
      EXPECT_NE(g.err.find("--exact with .off, .obj or .wrl"), std::string::npos) << g.err;
  }
  EXPECT_EQ(run("gen cube -o " + path("c.off")).err, "");  // nothing rounded: no note
}

// Coordinates that do not survive the format: exit 1, one line naming the
// fix, no file (issue: a subnormal cube written to binary STL as zeros with
// exit 0; 1/7^1000 written as zeros to .off).
TEST_F(Cli, SubnormalCubeToBinaryStlIsRefused) {
  ASSERT_EQ(run("gen cube@scale:1e-310 -o " + path("sub.off")).status, 0);
  CmdResult r = run("sum " + path("sub.off") + " " + path("sub.off") + " --binary -o " + path("x.stl"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("write ascii STL (without --binary)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("x.stl")));
  CmdResult ascii = run("sum " + path("sub.off") + " " + path("sub.off") + " -o " + path("x.stl"));
  ASSERT_EQ(ascii.status, 0) << ascii.err;
  EXPECT_EQ(run("stats " + path("x.stl")).status, 0);
}

TEST_F(Cli, TinyRationalCubeToOffIsRefusedWithoutExact) {
  std::string n = "1";  // 7^1000 in decimal, by schoolbook multiplication
  for (int i = 0; i < 1000; ++i) {
    int carry = 0;
    for (auto it = n.rbegin(); it != n.rend(); ++it) {
      const int d = (*it - '0') * 7 + carry;
      *it = char('0' + d % 10);
      carry = d / 10;
    }
    while (carry) n.insert(n.begin(), char('0' + carry % 10)), carry /= 10;
  }
  {
    std::ofstream o(path("tiny.off"));
    o << "OFF\n8 6 12\n";
    for (int i = 0; i < 8; ++i)
      o << ((i & 1) ? "" : "-") << "1/" << n << " " << ((i & 2) ? "" : "-") << "1/" << n << " "
        << ((i & 4) ? "" : "-") << "1/" << n << "\n";
    o << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  }
  for (const char* ext : {"off", "ply"}) {
    CmdResult r = run("sum " + path("tiny.off") + " " + path("tiny.off") + " -o " + path(std::string("t.") + ext));
    EXPECT_EQ(r.status, 1) << ext;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("no longer make a solid"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::string(ext) == "off" ? "use --exact to write" : "use --exact with .off, .obj or .wrl"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(path(std::string("t.") + ext)));
  }
  CmdResult e = run("sum " + path("tiny.off") + " " + path("tiny.off") + " --exact -o " + path("t.off"));
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(run("stats " + path("t.off")).status, 0);
}

// Overflow used to exit 2 (usage) with two lines (the note, then the error).
TEST_F(Cli, CoordinateBeyondDoubleRangeExitsOneWithOneLine) {
  {
    std::ofstream o(path("big.off"));
    o << "OFF\n8 6 12\n";
    const std::string big = "1" + std::string(330, '0');  // 10^330 > DBL_MAX
    for (int i = 0; i < 8; ++i)
      o << ((i & 1) ? "" : "-") << big << " " << ((i & 2) ? 1 : -1) << " " << ((i & 4) ? 1 : -1) << "\n";
    o << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  }
  for (const char* ext : {"off", "stl"}) {
    CmdResult r = run("sum " + path("big.off") + " cube -o " + path(std::string("b.") + ext));
    EXPECT_EQ(r.status, 1) << ext;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("does not fit in a double"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--exact"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path(std::string("b.") + ext)));
  }
  EXPECT_EQ(run("sum " + path("big.off") + " cube --exact -o " + path("b.off")).status, 0);
}

// minksum sum A B C ...: A ⊕ B ⊕ C, the same as chaining through exact files.
TEST_F(Cli, SumOfThreeOrMoreOperands) {
  CmdResult r = run("sum cube tetra octahedron@rot:3 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"operands\": [{\"name\": \"cube\", \"vertices\": 8, \"edges\": 12, \"facets\": 6, "
                       "\"dimension\": 3, \"kind\": \"polytope\"}, {\"name\": \"tetra\", \"vertices\": 4, \"edges\": 6, \"facets\": 4, "
                       "\"dimension\": 3, \"kind\": \"polytope\"}, {\"name\": \"octahedron@rot:3\""),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("\"a\": "), std::string::npos) << r.out;
  ASSERT_EQ(run("sum cube tetra --exact -o " + path("ab.off")).status, 0);
  CmdResult c = run("sum " + path("ab.off") + " octahedron@rot:3 --json");
  ASSERT_EQ(c.status, 0) << c.err;
  expect_same_solid(r.out, c.out);
  CmdResult text = run("sum cube tetra octahedron dodecahedron --method chms");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_EQ(text.out.rfind("cube (8 V, 6 F) ⊕ tetra (4 V, 4 F) ⊕ octahedron (6 V, 8 F) ⊕ dodecahedron (20 V, 12 F)\n", 0), 0u)
      << text.out;
  EXPECT_EQ(run("sum cube").status, 2);
}

// The operands are freed before the sum is written (without --scene): the
// report still names them with their counts, and --json's facet types are
// those of the sum written.
TEST_F(Cli, SumReportAfterTheOperandsAreFreed) {
  CmdResult r = run("sum cube sphere:2 -o " + path("cs.off") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"a\": {\"name\": \"cube\", \"vertices\": 8, \"edges\": 12, \"facets\": 6, \"dimension\": 3, \"kind\": \"polytope\"}, "
                       "\"b\": {\"name\": \"sphere:2\", \"vertices\": 42, \"edges\": 120, \"facets\": 80, \"dimension\": 3, \"kind\": \"polytope\"}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"facet_types\": {\"translated\": 6, \"corner\": 56, \"edge\": 12, \"facet_edge\": 24, "
                       "\"facet_facet\": 0}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"facets\": 98"), std::string::npos) << r.out;
  CmdResult text = run("sum cube sphere:2 -o " + path("cs2.off"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_EQ(text.out.rfind("cube (8 V, 6 F) ⊕ sphere:2 (42 V, 80 F)\n", 0), 0u) << text.out;
  // --scene keeps them: A and B are written beside S.
  CmdResult scene = run("sum cube sphere:2 --scene -o " + path("cs.wrl") + " --json");
  ASSERT_EQ(scene.status, 0) << scene.err;
  const std::string wrl = slurp(path("cs.wrl"));
  for (const char* node : {"DEF A ExactPolyhedron", "DEF B ExactPolyhedron", "DEF S ExactPolyhedron"})
    EXPECT_NE(wrl.find(node), std::string::npos) << node;
  EXPECT_NE(scene.out.find("\"b\": {\"name\": \"sphere:2\", \"vertices\": 42"), std::string::npos) << scene.out;
}

// minksum sum A B -o s.EXT && minksum sum s.EXT C, for every format.
TEST_F(Cli, ChainingThroughEveryFormat) {
  for (const auto& o : kEveryOutput) {
    SCOPED_TRACE(o.first + output_flags(o));
    const std::string s = path("s." + o.first);
    ASSERT_EQ(run("sum sphere:3 dodecahedron@rot:5 -o " + s + output_flags(o)).status, 0);
    CmdResult c = run("sum " + s + " cube@rot:2 -o " + path("t." + o.first) + output_flags(o));
    ASSERT_EQ(c.status, 0) << c.err;
    EXPECT_EQ(run("stats " + path("t." + o.first)).status, 0);
  }
}

// -: a mesh on standard input or standard output, with --format.
TEST_F(Cli, GenPipesIntoStats) {
  CmdResult r = run_sh("minksum gen sphere:3 -o - --format off | minksum stats - --format off --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json_int(r.out, "vertices"), 162);
  EXPECT_EQ(json_int(r.out, "facets"), 320);
  EXPECT_NE(r.err.find("sphere:3: 162 vertices, 480 edges, 320 facets, written to standard output"), std::string::npos)
      << r.err;
  for (const auto& o : kEveryOutput) {
    SCOPED_TRACE(o.first + output_flags(o));
    CmdResult p = run_sh("minksum gen truncated-octahedron -o - --format " + o.first + output_flags(o) +
                         " | minksum stats - --json --format " + o.first);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(json_int(p.out, "vertices"), 24);
    EXPECT_EQ(json_int(p.out, "edges"), 36);
    EXPECT_EQ(json_int(p.out, "facets"), 14);
  }
}

TEST_F(Cli, MeshOnStdoutKeepsTheSummaryOffIt) {
  CmdResult g = run("gen cube -o - --format off");
  ASSERT_EQ(g.status, 0) << g.err;
  EXPECT_EQ(g.out.rfind("OFF\n8 6 12\n", 0), 0u) << g.out;
  EXPECT_NE(g.err.find("written to standard output"), std::string::npos) << g.err;
  CmdResult s = run("sum cube tetra -o - --format stl --binary --json");
  ASSERT_EQ(s.status, 0) << s.err;
  // A binary STL of the 16 vertices (2V - 4 = 28 triangles), nothing else.
  EXPECT_EQ(s.out.size(), 84u + 50u * 28u);
  EXPECT_EQ(s.err.rfind("{\"vertices\": 16", 0), 0u) << s.err;
  EXPECT_NE(s.err.find("\"output\": \"-\""), std::string::npos) << s.err;
  CmdResult c = run_sh("minksum sum cube tetra -o - --format obj | minksum sum - octahedron --format obj --json");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("{\"name\": \"-\", \"vertices\": 16"), std::string::npos) << c.out;
}

// A mesh that cannot be written to standard output (a full device): exit 1,
// one line, not success.
TEST_F(Cli, MeshToAFullStandardOutputExitsOne) {
  for (const std::string cmd : {"minksum gen cube -o - --format off", "minksum gen sphere:6 -o - --format stl --binary",
                                   "minksum sum cube tetra -o - --format obj --json"}) {
    SCOPED_TRACE(cmd);
    CmdResult r = run_sh(cmd + " >/dev/full");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "minksum: cannot write the mesh to standard output: write error\n");
  }
}

TEST_F(Cli, StandardStreamsNeedAFormat) {
  CmdResult in = run("stats -");
  EXPECT_EQ(in.status, 2);
  EXPECT_EQ(in.err, "minksum: reading a mesh from standard input ('-') needs --format off|obj|ply|stl|wrl\n");
  CmdResult out = run("gen cube -o -");
  EXPECT_EQ(out.status, 2);
  EXPECT_EQ(out.err, "minksum: writing a mesh to standard output (-o -) needs --format off|obj|ply|stl|wrl\n");
  EXPECT_EQ(out.out, "");
  CmdResult bad = run("gen cube -o - --format xyz");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err, "minksum: unknown format 'xyz' for --format (off|obj|ply|stl|wrl)\n");
  CmdResult twice = run_sh("minksum gen cube -o - --format off | minksum sum - - --format off");
  EXPECT_EQ(twice.status, 2);
  EXPECT_NE(twice.err.find("standard input ('-') can be read only once"), std::string::npos) << twice.err;
  CmdResult exact = run("gen cube -o - --format stl --exact");
  EXPECT_EQ(exact.status, 2);
  EXPECT_NE(exact.err.find("cannot store exact rationals"), std::string::npos) << exact.err;
  // Bad data on standard input: exit 3, one line naming <stdin>.
  CmdResult data = run_sh("printf 'OFF\\n3 1 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 2\\n' | minksum stats - --format off");
  EXPECT_EQ(data.status, 3);
  EXPECT_EQ(lines(data.err), 1u) << data.err;
  EXPECT_EQ(data.err.rfind("minksum: <stdin>: ", 0), 0u) << data.err;
  // --format for a file whose name does not tell; a known extension keeps its own.
  ASSERT_EQ(run("gen cube -o " + path("c.off")).status, 0);
  fs::rename(path("c.off"), path("c.dat"));
  EXPECT_EQ(run("stats " + path("c.dat")).status, 2);
  EXPECT_EQ(run("stats " + path("c.dat") + " --format off").status, 0);
  ASSERT_EQ(run("gen cube -o " + path("d.dat") + " --format ply").status, 0);
  EXPECT_EQ(run("stats " + path("d.dat") + " --format ply").status, 0);
}

TEST_F(Cli, QueryAndCgmReadStandardInput) {
  CmdResult q = run_sh("minksum gen cube -o - --format ply | minksum query distance - cube --translate-q 3,0,0 --format ply");
  ASSERT_EQ(q.status, 0) << q.err;
  CmdResult d = run("query distance cube cube --translate-q 3,0,0");
  EXPECT_EQ(q.out, d.out);
  CmdResult c = run_sh("minksum gen octahedron -o - --format wrl | minksum cgm - --stats --format wrl");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("6 vertices, 12 edges, 8 facets"), std::string::npos) << c.out;
  CmdResult t = run_sh("echo '0,0,0' | minksum query collide - cube --trajectory - --format off");
  EXPECT_EQ(t.status, 2);
  EXPECT_NE(t.err.find("already the trajectory"), std::string::npos) << t.err;
}

// minksum convert IN -o OUT: every format to every format, cleaned.
TEST_F(Cli, ConvertEveryFormatToEveryFormat) {
  for (const auto& from : kEveryOutput) {
    const std::string in = path("in." + from.first);
    ASSERT_EQ(run("gen truncated-cube -o " + in + output_flags(from)).status, 0);
    for (const auto& to : kEveryOutput) {
      SCOPED_TRACE(from.first + output_flags(from) + " -> " + to.first + output_flags(to));
      const std::string out = path("out." + to.first);
      CmdResult c = run("convert " + in + " -o " + out + output_flags(to) + " --json");
      ASSERT_EQ(c.status, 0) << c.err;
      EXPECT_EQ(json_int(c.out, "vertices"), 24) << c.out;
      EXPECT_EQ(json_int(c.out, "facets"), 14) << c.out;
      CmdResult s = run("stats " + out + " --json");
      ASSERT_EQ(s.status, 0) << s.err;
      EXPECT_EQ(json_int(s.out, "facets"), 14);
    }
  }
  // A triangulated STL becomes one polygon per facet.
  CmdResult t = run("convert " + data("bad/triangulated_cube.stl") + " -o " + path("cube.off"));
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(slurp(path("cube.off")).rfind("OFF\n8 6 12\n", 0), 0u);
  // Through pipes, with a format on each side.
  CmdResult p = run_sh("minksum gen cube -o - --format stl | minksum convert - --from stl -o - --format off");
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_EQ(p.out.rfind("OFF\n8 6 12\n", 0), 0u) << p.out;
  // Not convex: written as the solid it is, naming no --hull; with --hull its hull.
  CmdResult n = run("convert " + data("bad/nonconvex_lprism.off") + " -o " + path("l.off"));
  EXPECT_EQ(n.status, 0) << n.err;
  EXPECT_EQ(n.err.find("--hull"), std::string::npos) << n.err;
  EXPECT_EQ(run("convert " + data("bad/nonconvex_lprism.off") + " -o " + path("h.off") + " --hull").status, 0);
  CmdResult h = run("stats " + path("h.off") + " --json");
  EXPECT_EQ(h.status, 0);
  EXPECT_EQ(h.out.find("genus"), std::string::npos) << h.out;  // convex
  // Usage.
  EXPECT_EQ(run("convert cube").status, 2);
  EXPECT_EQ(run("convert -o " + path("x.off")).status, 2);
  EXPECT_EQ(run("convert cube -o " + path("x.stl") + " --exact").status, 2);
  EXPECT_EQ(run("convert --help").status, 0);
}

// STL files as OpenSCAD exports them (6 significant digits; written by
// tests/data/cad/make_cad_meshes.py): not exactly convex, so refused with
// one line naming --hull; with --hull, their exact hull.  Every point of
// these convex solids is a vertex of the hull: V is the number of distinct
// points; the rotated cube's six squares, no longer planar, are 12 triangles.
TEST_F(Cli, CadMeshesAreRefusedNamingHullAndAcceptedWithIt) {
  struct Case {
    const char* file;
    long vertices, edges, facets;  // of the hull; -1: not known in closed form
  };
  for (const Case& c : {Case{"cube.stl", 8, 18, 12}, Case{"cylinder.stl", 96, -1, -1}, Case{"sphere.stl", 1152, -1, -1},
                        Case{"hull.stl", 332, -1, -1}}) {
    SCOPED_TRACE(c.file);
    const std::string in = data(std::string("cad/") + c.file);
    // sum, stats and convert take them as the non-convex solids they are
    // (docs/nonconvex.md): one shell of genus 0 through all the points.
    CmdResult solid = run("stats " + in + " --json");
    ASSERT_EQ(solid.status, 0) << solid.err;
    EXPECT_NE(solid.out.find("\"convex\": false"), std::string::npos) << solid.out;
    EXPECT_EQ(json_int(solid.out, "vertices"), c.vertices);
    EXPECT_EQ(json_int(solid.out, "genus"), 0);
    EXPECT_EQ(json_int(solid.out, "shells"), 1);
    // query takes convex operands only: refused, naming --hull.
    CmdResult r = run("query distance " + in + " cube");
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("minksum: " + in + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("; --hull takes the convex hull of its points instead"), std::string::npos) << r.err;
    CmdResult h = run("stats " + in + " --hull --json");
    ASSERT_EQ(h.status, 0) << h.err;
    const long v = json_int(h.out, "vertices"), e = json_int(h.out, "edges"), f = json_int(h.out, "facets");
    EXPECT_EQ(v, c.vertices);
    if (c.edges >= 0) {
      EXPECT_EQ(e, c.edges);
    }
    if (c.facets >= 0) {
      EXPECT_EQ(f, c.facets);
    }
    EXPECT_EQ(v - e + f, 2);
    // The hull written exactly reads back, without --hull, as the same solid.
    ASSERT_EQ(run("convert " + in + " --hull -o " + path("h.off")).status, 0);
    CmdResult back = run("stats " + path("h.off") + " --json");
    ASSERT_EQ(back.status, 0) << back.err;
    EXPECT_EQ(back.out.substr(back.out.find("\"vertices\""), back.out.find("\"phases\"") - back.out.find("\"vertices\"")),
              h.out.substr(h.out.find("\"vertices\""), h.out.find("\"phases\"") - h.out.find("\"vertices\"")));
    // Summed with --hull: the walk agrees with the chms oracle (the exact hull of pairwise sums).
    CmdResult walk = run("sum " + in + " dodecahedron --hull --method walk --json");
    CmdResult chms = run("sum " + in + " dodecahedron --hull --method chms --json");
    ASSERT_EQ(walk.status, 0) << walk.err;
    ASSERT_EQ(chms.status, 0) << chms.err;
    expect_same_solid(walk.out, chms.out);
  }
}

// VRML scenes (docs/vrml.md): 'cgm P Q -o cgm.wrl' and 'sum A B -o s.wrl
// --scene' write them, 'view scene.wrl' shows them, every node is checked.
class SceneCli : public Cli {
 protected:
  // `text` with the first occurrence of `from` replaced by `to`, written to `name`.
  std::string edited(const std::string& text, const std::string& from, const std::string& to, const std::string& name) {
    std::string t = text;
    const std::size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) t.replace(at, from.size(), to);
    std::ofstream(path(name)) << t;
    return path(name);
  }
  // Exit status 3 and one line naming the file, `place` and `problem`.
  void expect_bad_scene(const std::string& file, const std::string& place, const std::string& problem) {
    CmdResult r = run("view " + file + " -o " + path("bad.html"));
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(file + ": " + place + ": "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("bad.html")));
  }
  static std::size_t line_of(const std::string& text, const std::string& what) {
    return std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find(what)), '\n')) + 1;
  }
};

TEST_F(SceneCli, CgmSceneHoldsThePolytopesTheirMapsAndTheSum) {
  const std::string scene = path("cgm.wrl");
  CmdResult w = run("cgm truncated-cube@rot:2 octahedron@rot:1,2,3,7 -o " + scene);
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_NE(w.out.find("wrote " + scene), std::string::npos) << w.out;
  const std::string text = slurp(scene);
  for (const char* node : {"DEF P ExactPolyhedron", "DEF Q ExactPolyhedron", "DEF S ExactPolyhedron",
                           "DEF CGM_P CubicalGaussianMap", "DEF CGM_Q CubicalGaussianMap",
                           "DEF CGM_S CubicalGaussianMap", "operands [ USE P, USE Q ]", "ratPoint ["})
    EXPECT_NE(text.find(node), std::string::npos) << node;
  EXPECT_EQ(text.find(" Coordinate {"), std::string::npos);  // exact coordinates only
  EXPECT_EQ(text.find(" point ["), std::string::npos);
  // Read back and checked: the sum's counts are those of 'sum', each map's those of 'cgm --json'.
  CmdResult v = run("view " + scene + " -o " + path("scene.html") + " --json");
  ASSERT_EQ(v.status, 0) << v.err;
  CmdResult s = run("sum truncated-cube@rot:2 octahedron@rot:1,2,3,7 --json");
  ASSERT_EQ(s.status, 0) << s.err;
  const std::string sum_shape = v.out.substr(v.out.find("{\"kind\": \"polytope\", \"name\": \"S\""));
  for (const char* key : {"vertices", "edges", "facets"}) EXPECT_EQ(json_int(sum_shape, key), json_int(s.out, key)) << key;
  EXPECT_EQ(std::count(v.out.begin(), v.out.end(), '{') - 1, 6) << v.out;  // 6 shapes
  EXPECT_NE(v.out.find("{\"kind\": \"cgm\", \"name\": \"CGM_S\""), std::string::npos) << v.out;
  EXPECT_TRUE(fs::exists(path("scene.html")));
  // The file holds three polytopes: commands that read one say so.
  CmdResult st = run("stats " + scene);
  EXPECT_EQ(st.status, 3) << st.err;
  EXPECT_NE(st.err.find("the scene holds 3 polytopes"), std::string::npos) << st.err;
  // One polytope and its map: reads as that polytope anywhere.
  ASSERT_EQ(run("cgm dodecahedron -o " + path("one.wrl")).status, 0);
  CmdResult one = run("stats " + path("one.wrl") + " --json");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(json_int(one.out, "facets"), 12);
}

TEST_F(SceneCli, SumSceneWritesOperandsAndSumThatReadBackExactly) {
  const std::string scene = path("s.wrl");
  CmdResult w = run("sum cube@rot:1 tetrahedron@rot:3 -o " + scene + " --scene --exact --json");
  ASSERT_EQ(w.status, 0) << w.err;
  const std::string text = slurp(scene);
  EXPECT_NE(text.find("# A = cube@rot:1"), std::string::npos);
  EXPECT_NE(text.find("# S = A ⊕ B"), std::string::npos);
  // The sum node, cut out as a file of its own, is the sum 'sum --exact' writes.
  const std::size_t s_at = text.find("# S = ");
  ASSERT_NE(s_at, std::string::npos);
  std::ofstream(path("s_only.wrl")) << "#VRML V2.0 utf8\n" << text.substr(s_at);
  ASSERT_EQ(run("sum cube@rot:1 tetrahedron@rot:3 -o " + path("s.off") + " --exact").status, 0);
  CmdResult a = run("stats " + path("s_only.wrl") + " --json"), b = run("stats " + path("s.off") + " --json");
  ASSERT_EQ(a.status, 0) << a.err;
  expect_same_solid(a.out, b.out);
  CmdResult v = run("view " + scene + " -o " + path("s.html") + " --json");
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_EQ(json_int(v.out.substr(v.out.find("\"name\": \"S\"")), "facets"), json_int(w.out, "facets")) << v.out;
  // Without --exact: the nearest doubles, rounded so that each reads back as a convex polytope.
  CmdResult d = run("sum cube@rot:1 tetrahedron@rot:3 -o " + path("d.wrl") + " --scene");
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.err.find("coordinates are not doubles"), std::string::npos) << d.err;
  EXPECT_EQ(slurp(path("d.wrl")).find("ratPoint"), std::string::npos);
  EXPECT_EQ(run("view " + path("d.wrl") + " -o " + path("d.html")).status, 0);
  // To standard output with --format wrl.
  CmdResult o = run("sum cube tetrahedron -o - --format wrl --scene");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("DEF S ExactPolyhedron"), std::string::npos);
}

// Regression: the 19th operand was node S, as the sum is (two DEF S).
TEST_F(SceneCli, SumSceneOfNineteenOrMoreOperandsNamesEveryNodeOnce) {
  std::string cmd = "sum";
  for (int i = 0; i < 27; ++i) cmd += " tetrahedron";
  CmdResult w = run(cmd + " --scene -o " + path("many.wrl") + " --json");
  ASSERT_EQ(w.status, 0) << w.err;
  const std::string text = slurp(path("many.wrl"));
  std::vector<std::string> names;
  for (std::size_t at = text.find("DEF "); at != std::string::npos; at = text.find("DEF ", at + 4))
    names.push_back(text.substr(at + 4, text.find(' ', at + 4) - at - 4));
  std::vector<std::string> expected;
  for (char c = 'A'; c <= 'Z'; ++c)
    if (c != 'S') expected.push_back(std::string(1, c));
  expected.push_back("P26");
  expected.push_back("P27");
  expected.push_back("S");
  EXPECT_EQ(names, expected);
  EXPECT_NE(text.find("# T = tetrahedron"), std::string::npos);
  EXPECT_NE(text.find("# S = A ⊕ B ⊕ C"), std::string::npos);
  EXPECT_NE(text.find("⊕ Z ⊕ P26 ⊕ P27\n"), std::string::npos);
  // view reads it back: the same 28 polytopes in the same order.
  CmdResult v = run("view " + path("many.wrl") + " -o " + path("many.html") + " --json");
  ASSERT_EQ(v.status, 0) << v.err;
  std::vector<std::string> shown;
  const std::string key = "\"kind\": \"polytope\", \"name\": \"";
  for (std::size_t at = v.out.find(key); at != std::string::npos; at = v.out.find(key, at + 1)) {
    const std::size_t from = at + key.size();
    shown.push_back(v.out.substr(from, v.out.find('"', from) - from));
  }
  EXPECT_EQ(shown, expected) << v.out;
}

TEST_F(SceneCli, UsageErrors) {
  EXPECT_EQ(run("sum cube cube --scene").status, 2);
  EXPECT_EQ(run("sum cube cube --scene -o " + path("s.off")).status, 2);
  EXPECT_FALSE(fs::exists(path("s.off")));
  EXPECT_EQ(run("cgm cube -o " + path("c.off")).status, 2);
  ASSERT_EQ(run("cgm cube octahedron -o " + path("c.wrl")).status, 0);
  EXPECT_EQ(run("view " + path("c.wrl") + " --method walk -o " + path("c.html")).status, 2);
  EXPECT_EQ(run("cgm cube -o /nonexistent-dir/c.wrl").status, 1);
}

// A scene whose nodes disagree with what they claim: exit 3, one line, the node's line.
TEST_F(SceneCli, MalformedSceneNodesExitThreeNamingTheLine) {
  ASSERT_EQ(run("cgm cube octahedron -o " + path("c.wrl")).status, 0);
  const std::string text = slurp(path("c.wrl"));
  // A mapCounts entry changed.
  const std::size_t counts_line = line_of(text, "mapCounts");
  const std::size_t c0 = text.find("mapCounts [ ") + 12;
  const std::string counts = text.substr(c0, text.find(' ', c0) - c0);
  expect_bad_scene(edited(text, "mapCounts [ " + counts + " ", "mapCounts [ 99 ", "counts.wrl"), "line " + std::to_string(counts_line),
                   "'mapCounts' gives map 0 99 vertices, the map of its polytope has");
  // A facet normal moved.
  const std::size_t point_line = line_of(text, "mapPoint");
  const std::size_t first = text.find("mapPoint [\n") + 11;
  const std::string entry = text.substr(first, text.find(',', first) - first);  // "      k x y"
  std::string moved = entry;
  moved.replace(moved.find_last_of(' ') + 1, std::string::npos, "1/7");
  expect_bad_scene(edited(text, entry + ",", moved + ",", "point.wrl"), "line " + std::to_string(point_line),
                   "is not a facet normal on map");
  // The sum's polytope replaced by another: not the sum of its operands.
  const std::size_t cgm_s = line_of(text, "DEF CGM_S");
  expect_bad_scene(edited(text, "polytope USE S", "polytope USE P", "notsum.wrl"), "line " + std::to_string(cgm_s),
                   "is not the Minkowski sum of its operands P and Q");
  // A polytope that is not convex: the node's line, then the polytope's own place.
  const std::size_t p_line = line_of(text, "DEF P ");
  const std::size_t coords = text.find("ratPoint [\n") + 11;
  const std::string p0 = text.substr(coords, text.find(',', coords) - coords);
  expect_bad_scene(edited(text, p0 + ",", "        0 0 0,", "concave.wrl"), "line " + std::to_string(p_line),
                   "ExactPolyhedron 'P': ");
  // Syntax: an unknown field.
  expect_bad_scene(edited(text, "polytope USE S", "polytope USE S colour 1", "field.wrl"), "line " + std::to_string(cgm_s + 1),
                   "unknown field 'colour'");
}

// ---------------------------------------------------------------------------
// Non-convex operands (docs/nonconvex.md).

// Exactly the closed form of tube ⊕ [-1/4,1/4]^3 ([-5/4,5/4]^3 minus a hole
// of side 1/2): volume 125/8 - 5/8 = 15, with the pieces, pairs and union
// work in --json; the exact output reads back as the same solid.
TEST_F(Cli, NonConvexSumJsonAndExactOutput) {
  CmdResult r = run("sum tube box:1/2:1/2:1/2 --json --exact -o " + path("s.off"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("\"method\": \"nonconvex\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"volume\": \"15\""), std::string::npos) << r.out;
  EXPECT_EQ(json_int(r.out, "vertices"), 16);
  EXPECT_EQ(json_int(r.out, "facets"), 24);
  const std::string work = r.out.substr(r.out.find("\"pieces\""));  // after the phases' seconds
  EXPECT_EQ(json_int(work, "b"), 1);  // "pieces": {"a": N, "b": 1}
  EXPECT_GE(json_int(work, "a"), 2);
  EXPECT_EQ(json_int(work, "pairs"), json_int(work, "a"));
  EXPECT_GE(json_int(work, "clips"), 1);  // the pieces around the hole overlap
  EXPECT_EQ(json_int(r.out, "shells"), 1);
  EXPECT_EQ(json_int(r.out, "non_manifold_edges"), 0);
  for (const char* key : {"decompose", "pairs", "union", "boundary", "pair_facets"})
    EXPECT_NE(r.out.find(std::string("\"") + key + "\""), std::string::npos) << key;
  // Read back, a valid solid again: ⊕ [-1/4,1/4]^3 closes its hole (1/2)
  // exactly, leaving the cube [-3/2,3/2]^3.
  CmdResult back = run("sum " + path("s.off") + " box:1/2:1/2:1/2 --json");
  ASSERT_EQ(back.status, 0) << back.err;
  EXPECT_NE(back.out.find("\"volume\": \"27\""), std::string::npos) << back.out;
  EXPECT_EQ(json_int(back.out, "facets"), 6);
  // A ⊕ B = B ⊕ A, with the pairs of the decomposition summed by another
  // method; the sweep's pieces (a triangle and a box) by chms, or from the
  // Gaussian maps when another method is asked for (pair_method says which).
  CmdResult ba = run("sum box:1/2:1/2:1/2 tube --method cvms --nonconvex-method decomposition --json");
  ASSERT_EQ(ba.status, 0) << ba.err;
  EXPECT_NE(ba.out.find("\"volume\": \"15\""), std::string::npos) << ba.out;
  EXPECT_NE(ba.out.find("\"pair_method\": \"cvms\""), std::string::npos) << ba.out;
  EXPECT_NE(ba.out.find("\"nonconvex_method\": \"decomposition\""), std::string::npos) << ba.out;
  CmdResult chms = run("sum box:1/2:1/2:1/2 tube --method chms --json");
  ASSERT_EQ(chms.status, 0) << chms.err;
  EXPECT_NE(chms.out.find("\"volume\": \"15\""), std::string::npos) << chms.out;
  EXPECT_NE(chms.out.find("\"pair_method\": \"chms\""), std::string::npos) << chms.out;
  EXPECT_NE(chms.out.find("\"nonconvex_method\": \"sweep\", \"swept\": \"b\""), std::string::npos) << chms.out;
  CmdResult cvms = run("sum box:1/2:1/2:1/2 tube --method cvms --json");
  ASSERT_EQ(cvms.status, 0) << cvms.err;
  EXPECT_NE(cvms.out.find("\"pair_method\": \"gaussian_map\""), std::string::npos) << cvms.out;
  EXPECT_NE(cvms.out.find("\"pair_vertices\": null"), std::string::npos) << cvms.out;
  CmdResult bad = run("sum box:1/2:1/2:1/2 tube --nonconvex-method hull");
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("unknown --nonconvex-method 'hull' (sweep, decomposition)"), std::string::npos) << bad.err;
  EXPECT_NE(r.out.find("\"pair_method\": \"gaussian_map\""), std::string::npos) << r.out;
}

// Two diagonal unit cubes, each ⊕ [-1/2,1/2]^3: the sums touch along the edge
// x = y = 3/2, every coordinate a double.  Without --exact the two parts are
// moved apart (a valid solid of two shells, with a note); with --exact the
// edge of four faces is kept.
TEST_F(Cli, NonConvexSumTouchingItselfIsWrittenApart) {
  std::ofstream(path("two.off")) << "OFF\n16 12 0\n"
                                    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                    "2 2 0\n3 2 0\n3 3 0\n2 3 0\n2 2 1\n3 2 1\n3 3 1\n2 3 1\n"
                                    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"
                                    "4 8 11 10 9\n4 12 13 14 15\n4 8 9 13 12\n4 9 10 14 13\n4 10 11 15 14\n"
                                    "4 11 8 12 15\n";
  CmdResult r = run("sum " + path("two.off") + " box:1:1:1 -o " + path("apart.off"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("minksum: note: " + path("apart.off") +
                       ": the sum touches itself, and its parts were moved apart to write it as a valid solid "
                       "(largest displacement "),
            std::string::npos)
      << r.err;
  EXPECT_EQ(lines(r.err), 1u);
  // It reads back as a valid solid: two boxes of 8 points each, a hair
  // apart, their faces as triangles.
  CmdResult back = run("sum " + path("apart.off") + " tetra@scale:1/8 --json");
  ASSERT_EQ(back.status, 0) << back.err;
  EXPECT_NE(back.out.find("\"a\": {\"name\": \"" + path("apart.off") + "\", \"vertices\": 16, \"edges\": 36, \"facets\": 24,"),
            std::string::npos)
      << back.out;
  CmdResult exact = run("sum " + path("two.off") + " box:1:1:1 --exact --json -o " + path("exact.off"));
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_EQ(json_int(exact.out, "non_manifold_edges"), 1);
  EXPECT_NE(exact.out.find("\"volume\": \"16\""), std::string::npos) << exact.out;
}

// Without --exact: doubles written as they are; other coordinates rounded
// into a valid solid (round_solid), with a note naming the largest
// displacement.
TEST_F(Cli, NonConvexSumWrittenWithoutExact) {
  CmdResult r = run("sum lshape cube -o " + path("l.obj"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  CmdResult s = run("sum " + path("l.obj") + " tetra --json");
  ASSERT_EQ(s.status, 0) << s.err;
  // STL holds triangles: the L-shaped caps are cut exactly (a fan from one
  // corner would cover the notch), and the file reads back as the same solid.
  ASSERT_EQ(run("sum lshape cube -o " + path("l.stl")).status, 0);
  CmdResult st = run("sum " + path("l.stl") + " tetra --json");
  ASSERT_EQ(st.status, 0) << st.err;
  const auto volume = [](const std::string& json) { return json.substr(json.find("\"volume\""), 40); };
  EXPECT_EQ(volume(st.out), volume(s.out));
  // 1/3 is no double: the faces are written as triangles of rounded points,
  // still a valid solid, with a note; the file reads back as a solid.
  CmdResult third = run("sum lshape cube@scale:1/3 -o " + path("third.off"));
  ASSERT_EQ(third.status, 0) << third.err;
  EXPECT_NE(third.err.find("minksum: note: " + path("third.off") + ": 36 coordinates are not doubles, written "
                           "rounded (largest displacement "),
            std::string::npos)
      << third.err;
  EXPECT_NE(third.err.find("), the faces as triangles; the written surface is a closed solid without "
                           "self-intersection (checked exactly); --exact writes the exact sum"),
            std::string::npos)
      << third.err;
  EXPECT_EQ(lines(third.err), 1u);
  CmdResult back = run("sum " + path("third.off") + " tetra --json");
  ASSERT_EQ(back.status, 0) << back.err;
  EXPECT_EQ(json_int(back.out, "vertices"), 20);
}

// A solid beyond the range of 32-bit floats, written as binary STL: exit 1,
// one line naming --exact, no file (it was SIGFPE in the solid writer).
TEST_F(Cli, NonConvexWriteBeyondFloatRangeExitsOne) {
  for (const std::string& cmd : {"gen tube@scale:1e300 -o " + path("x.stl") + " --binary",
                                "sum tube@scale:1e39 cube -o " + path("x.stl") + " --binary"}) {
    CmdResult r = run(cmd);
    EXPECT_EQ(r.status, 1) << cmd << ": " << r.err;
    EXPECT_EQ(r.err, "minksum: cannot write " + path("x.stl") +
                         ": a coordinate is beyond the range of 32-bit floats; use --exact with .off, .obj or .wrl "
                         "to write exact rationals\n")
        << cmd;
    EXPECT_FALSE(std::filesystem::exists(path("x.stl"))) << cmd;
  }
}

// Bad solids: exit 3, one line naming the file, the place and the problem.
TEST_F(Cli, NonConvexBadSolidsExitThree) {
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(path(name)) << text;
    return path(name);
  };
  // An L prism (tests/data/bad/nonconvex_lprism.off) with one face dropped,
  // with one face reversed, and with every face reversed.
  const std::string l = slurp(data("bad/nonconvex_lprism.off"));
  const std::size_t faces_at = [&] {
    std::size_t at = 0;
    for (int line = 0; line < 2 + 12; ++line) at = l.find('\n', at) + 1;
    return at;
  }();
  std::vector<std::string> face_lines;
  {
    std::istringstream in(l.substr(faces_at));
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) face_lines.push_back(line);
  }
  ASSERT_EQ(face_lines.size(), 8u);
  auto reversed = [](const std::string& line) {
    std::istringstream in(line);
    int n;
    in >> n;
    std::vector<std::string> v(n);
    for (auto& x : v) in >> x;
    std::string out = std::to_string(n);
    for (int i = n; i-- > 0;) out += " " + v[i];
    return out;
  };
  std::string head = l.substr(0, faces_at);
  std::string open = head, flipped = head, inverted = head;
  open.replace(open.find("12 8 0"), 6, "12 7 0");
  for (std::size_t i = 0; i < face_lines.size(); ++i) {
    if (i != 0) open += face_lines[i] + "\n";
    flipped += (i == 3 ? reversed(face_lines[i]) : face_lines[i]) + "\n";
    inverted += reversed(face_lines[i]) + "\n";
  }
  struct Case {
    std::string file, problem;
  };
  for (const Case& c : {Case{write("open.off", open), "open mesh: the edge belongs to facet"},
                        Case{write("flipped.off", flipped), "inconsistent orientation"},
                        Case{write("inverted.off", inverted), "oriented inwards"},
                        Case{write("crossing.off", "OFF\n16 12 0\n"
                                                   "0 0 0\n2 0 0\n0 2 0\n2 2 0\n0 0 2\n2 0 2\n0 2 2\n2 2 2\n"
                                                   "1 1 1\n3 1 1\n1 3 1\n3 3 1\n1 1 3\n3 1 3\n1 3 3\n3 3 3\n"
                                                   "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n"
                                                   "4 8 10 11 9\n4 12 13 15 14\n4 8 9 13 12\n4 10 14 15 11\n"
                                                   "4 8 12 14 10\n4 9 11 15 13\n"),
                             "intersect (the surface intersects itself)"}}) {
    SCOPED_TRACE(c.file);
    CmdResult r = run("sum " + c.file + " cube --json -o " + path("out.off"));
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("minksum: " + c.file + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.problem), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(path("out.off")));
  }
  // Usage: three operands with a non-convex one.
  EXPECT_EQ(run("sum tube cube cube").status, 2);
}

// Shells whose orientation disagrees with their nesting (the red team's two
// cases): exit 3 and one line naming the shell, where they used to be summed
// (volume 124 for nested outward cubes, 133 for an inverted cube beside a
// cube).
TEST_F(Cli, ShellsOrientedAgainstTheirNestingExitThree) {
  auto box = [](int x0, int x1, int y0, int off, bool flip) {
    std::string v, f;
    for (int i = 0; i < 8; ++i)
      v += std::to_string(i & 1 ? x1 : x0) + " " + std::to_string(i & 2 ? x1 - x0 + y0 : y0) + " " +
           std::to_string(i & 4 ? x1 - x0 + y0 : y0) + "\n";
    const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& face : q) {
      f += "4";
      for (int k = 0; k < 4; ++k) f += " " + std::to_string(off + face[flip ? 3 - k : k]);
      f += "\n";
    }
    return std::make_pair(v, f);
  };
  struct Case {
    std::string name, problem;
    std::pair<std::string, std::string> a, b;
  };
  const Case cases[] = {
      {"nested.off", "the shell of facet 6: faces outwards but lies inside another shell, in the solid",
       box(0, 4, 0, 0, false), box(1, 3, 1, 8, false)},
      {"inverted_beside.off", "the shell of facet 6: faces inwards but lies inside no other shell",
       box(0, 4, 0, 0, false), box(6, 7, 0, 8, true)}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::ofstream(path(c.name)) << "OFF\n16 12 0\n" << c.a.first << c.b.first << c.a.second << c.b.second;
    CmdResult r = run("sum " + path(c.name) + " cube -o " + path("out.off"));
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("minksum: " + path(c.name) + ": " + c.problem, 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(path("out.off")));
  }
  // The same two cubes, the inner one facing in, are a hollow solid: summed.
  const auto outer = box(0, 4, 0, 0, false), cavity = box(1, 3, 1, 8, true);
  std::ofstream(path("hollow.off")) << "OFF\n16 12 0\n" << outer.first << cavity.first << outer.second << cavity.second;
  CmdResult h = run("sum " + path("hollow.off") + " cube@scale:1/4 --json");
  ASSERT_EQ(h.status, 0) << h.err;
  // [0,4]^3 minus [1,3]^3, each grown or shrunk by 1/4: 4.5^3 - 1.5^3.
  EXPECT_NE(h.out.find("\"volume\": \"351/4\""), std::string::npos) << h.out;
}

// An STL has no vertex numbers: an open edge is located by its coordinates,
// and worded alike by 'sum' (non-convex validation) and 'stats' (the
// polytope builder).
TEST_F(Cli, OpenStlEdgeLocatedByCoordinatesAndWordedAlike) {
  for (const char* solid : {"tube", "cube"}) {
    SCOPED_TRACE(solid);
    ASSERT_EQ(run(std::string("gen ") + solid + " -o " + path("whole.stl")).status, 0);
    const std::string text = slurp(path("whole.stl"));
    // Drop the fourth facet.
    std::size_t at = 0;
    for (int k = 0; k < 3; ++k) at = text.find("endfacet\n", at) + 9;
    const std::size_t end = text.find("endfacet\n", at) + 9;
    std::ofstream(path("open.stl")) << text.substr(0, at) << text.substr(end);
    for (const char* cmd : {"sum ", "stats "}) {
      CmdResult r = run(cmd + path("open.stl") + (std::string(cmd) == "sum " ? " cube" : ""));
      EXPECT_EQ(r.status, 3) << cmd << r.err;
      EXPECT_EQ(lines(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find(": edge "), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(" from ("), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(") to ("), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("): open mesh: the edge belongs to facet "), std::string::npos) << r.err;
    }
  }
}

// --hull takes the hull of a non-convex catalog solid's points, as of a
// file's (it told the user to use --hull, which was given).
TEST_F(Cli, HullOfANonConvexCatalogSolid) {
  CmdResult r = run("sum tube cube --hull --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"volume\": \"64\""), std::string::npos) << r.out;  // [-2,2]^3
  CmdResult q = run("sum tube cube");
  EXPECT_EQ(q.status, 0) << q.err;
}

// query and cgm take --hull, which their refusals of a non-convex operand
// suggest (a collision mesh refused by query with a hint query rejected).
TEST_F(Cli, QueryAndCgmTakeTheHullTheirRefusalsSuggest) {
  CmdResult refused = run("query distance tube cube@scale:1/2 --translate-p 4,0,0");
  EXPECT_EQ(refused.status, 3);
  EXPECT_NE(refused.err.find("--hull takes the convex hull of its points instead"), std::string::npos) << refused.err;
  // The hull of the tube is [-1,1]^3, P moved by 4 along x; Q = [-1/2,1/2]^3: 4 - 1 - 1/2 = 5/2.
  CmdResult q = run("query distance tube cube@scale:1/2 --translate-p 4,0,0 --hull --json");
  ASSERT_EQ(q.status, 0) << q.err;
  EXPECT_NE(q.out.find("\"squared_distance\": \"25/4\""), std::string::npos) << q.out;
  CmdResult c = run("cgm tube --hull --json");
  ASSERT_EQ(c.status, 0) << c.err;
  CmdResult cube = run("cgm cube --json");
  ASSERT_EQ(cube.status, 0) << cube.err;
  // The hull of the tube is the cube [-1,1]^3: the same maps, the name aside.
  EXPECT_EQ(c.out.substr(c.out.find("\"vertices\"")), cube.out.substr(cube.out.find("\"vertices\"")));
  EXPECT_EQ(run("cgm tube").status, 3);
}

// '@' transforms on files (they worked on catalog names only: "part.stl@neg
// is neither a file nor a catalog name"), convex and non-convex, a bad
// transform, a missing file, and a file whose own name holds '@'.
TEST_F(Cli, TransformsApplyToFiles) {
  ASSERT_EQ(run("gen truncated-cube -o " + path("T.off")).status, 0);
  ASSERT_EQ(run("gen tube --exact -o " + path("tube.off")).status, 0);
  auto volume = [&](const std::string& args) {
    CmdResult r = run(args + " --json");
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    const std::size_t at = r.out.find("\"volume\": \"");
    EXPECT_NE(at, std::string::npos) << r.out;
    return r.out.substr(at, r.out.find('"', at + 11) - at);
  };
  EXPECT_EQ(volume("sum " + path("T.off") + "@neg " + path("T.off") + "@rot:1,1,0,0@scale:1/2"),
            volume("sum truncated-cube@neg truncated-cube@rot:1,1,0,0@scale:1/2"));
  EXPECT_EQ(volume("sum " + path("tube.off") + "@translate:1,0,0@rot:3 cube"),
            volume("sum tube@translate:1,0,0@rot:3 cube"));
  CmdResult st = run("stats " + path("T.off") + "@scale:2");
  ASSERT_EQ(st.status, 0) << st.err;
  CmdResult sc = run("stats truncated-cube@scale:2");
  ASSERT_EQ(sc.status, 0) << sc.err;
  EXPECT_EQ(st.out.substr(st.out.find(':')), sc.out.substr(sc.out.find(':')));
  CmdResult bad = run("stats " + path("T.off") + "@frob");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("operand '" + path("T.off") + "@frob': unknown transform 'frob'"), std::string::npos) << bad.err;
  CmdResult missing = run("stats " + path("nothere.off") + "@neg");
  EXPECT_EQ(missing.status, 3);
  EXPECT_NE(missing.err.find(path("nothere.off") + ": no such file"), std::string::npos) << missing.err;
  fs::copy_file(path("T.off"), path("a@b.off"));
  EXPECT_EQ(volume("sum " + path("a@b.off") + " cube"), volume("sum truncated-cube cube"));
  EXPECT_EQ(volume("sum " + path("a@b.off") + "@neg cube"), volume("sum truncated-cube@neg cube"));
}

// 'gen' of a non-convex solid says how many triangles it wrote when the
// faces were written as triangles (it said "96 faces" and wrote 192).
TEST_F(Cli, GenOfANonConvexSolidCountsTheWrittenTriangles) {
  CmdResult g = run("gen gear:6 -o " + path("gear.stl"));
  ASSERT_EQ(g.status, 0) << g.err;
  EXPECT_NE(g.out.find("gear:6: 96 vertices, 96 faces, non-convex, written to " + path("gear.stl") + " as 192 triangles"),
            std::string::npos)
      << g.out;
  std::size_t facets = 0;
  const std::string stl = slurp(path("gear.stl"));
  for (std::size_t at = 0; (at = stl.find("endfacet", at)) != std::string::npos; at += 8) ++facets;
  EXPECT_EQ(facets, 192u);
  CmdResult t = run("gen tube --exact -o " + path("tube.off"));
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("tube: 16 vertices, 16 faces, non-convex, written to " + path("tube.off") + "\n"),
            std::string::npos)
      << t.out;
}

TEST_F(Cli, NonConvexCatalogSolidsGenAndHelp) {
  CmdResult h = run("gen --help");
  ASSERT_EQ(h.status, 0);
  for (const char* n : {"tube:H", "lshape", "ring:N", "star:N", "gear:N"}) EXPECT_NE(h.out.find(n), std::string::npos) << n;
  CmdResult g = run("gen gear:4 -o " + path("gear.off"));
  ASSERT_EQ(g.status, 0) << g.err;
  EXPECT_NE(g.out.find("gear:4: 64 vertices, 64 faces, non-convex"), std::string::npos) << g.out;
  // Not convex: a solid of genus 1 (the bore), its faces as written
  // (rounded to doubles: triangles).
  CmdResult st = run("stats " + path("gear.off") + " --json");
  ASSERT_EQ(st.status, 0) << st.err;
  EXPECT_EQ(json_int(st.out, "vertices"), 64);
  EXPECT_EQ(json_int(st.out, "facets"), 128);
  EXPECT_EQ(json_int(st.out, "genus"), 1);
  CmdResult exact = run("stats gear:4 --json");
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_EQ(json_int(exact.out, "facets"), 64);
  EXPECT_EQ(json_int(exact.out, "genus"), 1);
  CmdResult s = run("sum " + path("gear.off") + " cube@scale:1/16 --json");
  ASSERT_EQ(s.status, 0) << s.err;
  CmdResult t = run("sum gear:4 cube@scale:1/16 --json");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(s.out.substr(0, s.out.find("\"method\"")), t.out.substr(0, t.out.find("\"method\"")));
  EXPECT_EQ(run("gen gear:2 -o " + path("x.off")).status, 2);
  CmdResult help = run("sum --help");
  EXPECT_NE(help.out.find("Non-convex operands"), std::string::npos);
}

// ---------------------------------------------------------------------------
// stats, convert and view take closed solids that are not convex (they
// refused the file 'sum' writes for a non-convex sum, with a hint at --hull
// that would have destroyed the shape).

// An exact string field "key": "value" of a JSON line ("" when absent).
static std::string json_text(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": \"";
  const std::size_t at = json.find(k);
  if (at == std::string::npos) return "";
  const std::size_t from = at + k.size();
  return json.substr(from, json.find('"', from) - from);
}

// The stats of what 'sum' wrote for a non-convex sum are the sum's own:
// counts and exact volume; tube ⊕ a small sphere has the tube's genus 1.
TEST_F(Cli, StatsOfTheFileSumWritesForANonConvexSum) {
  CmdResult s = run("sum tube sphere:2@scale:1/4 --exact --json -o " + path("x.off"));
  ASSERT_EQ(s.status, 0) << s.err;
  CmdResult st = run("stats " + path("x.off") + " --json");
  ASSERT_EQ(st.status, 0) << st.err;
  EXPECT_EQ(json_text(st.out, "volume"), json_text(s.out, "volume")) << st.out;
  EXPECT_FALSE(json_text(st.out, "volume").empty());
  for (const char* key : {"vertices", "edges", "facets"}) EXPECT_EQ(json_int(st.out, key), json_int(s.out, key)) << key;
  EXPECT_EQ(json_int(st.out, "genus"), 1) << st.out;
  EXPECT_EQ(json_int(st.out, "shells"), 1) << st.out;
  EXPECT_NE(st.out.find("\"convex\": false"), std::string::npos) << st.out;
  // V - E + F = 2 - 2 genus.
  EXPECT_EQ(json_int(st.out, "vertices") - json_int(st.out, "edges") + json_int(st.out, "facets"), 0);
  // The text names the same numbers; no hint at --hull.
  CmdResult text = run("stats " + path("x.off"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find(std::to_string(json_int(s.out, "facets")) + " facets, a non-convex solid\n"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("  genus 1, 1 shell\n"), std::string::npos) << text.out;
  EXPECT_EQ(text.err.find("--hull"), std::string::npos) << text.err;
}

// The catalog's tube ([-1,1]^3 with a square hole of side 1 along z): 16
// vertices, 32 edges, 16 faces, volume 8 - 1·2 = 6, genus 1, its box exactly
// [-1,1]^3; a torus (genus 1); two disjoint cubes (two shells); a cube with
// a cubic cavity (two shells, volume 64 - 8).
TEST_F(Cli, StatsOfNonConvexSolidsGenusShellsAndBox) {
  CmdResult t = run("stats tube --json");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(json_int(t.out, "vertices"), 16);
  EXPECT_EQ(json_int(t.out, "edges"), 32);
  EXPECT_EQ(json_int(t.out, "facets"), 16);
  EXPECT_EQ(json_text(t.out, "volume"), "6");
  EXPECT_EQ(json_int(t.out, "genus"), 1);
  EXPECT_EQ(json_int(t.out, "shells"), 1);
  EXPECT_NE(t.out.find("\"bounding_box\": {\"min\": [\"-1\", \"-1\", \"-1\"], \"max\": [\"1\", \"1\", \"1\"], "
                       "\"min_double\": [-1, -1, -1], \"max_double\": [1, 1, 1]}"),
            std::string::npos)
      << t.out;
  CmdResult text = run("stats tube@scale:1/3");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("tube@scale:1/3: 16 vertices, 32 edges, 16 facets, a non-convex solid\n"), std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("(exactly 2/9)"), std::string::npos) << text.out;  // 6 / 27
  EXPECT_NE(text.out.find("    exactly [-1/3, 1/3] × [-1/3, 1/3] × [-1/3, 1/3]\n"), std::string::npos) << text.out;
  CmdResult torus = run("stats torus:8:4 --json");
  ASSERT_EQ(torus.status, 0) << torus.err;
  EXPECT_EQ(json_int(torus.out, "vertices"), 32);
  EXPECT_EQ(json_int(torus.out, "facets"), 64);
  EXPECT_EQ(json_int(torus.out, "edges"), 96);
  EXPECT_EQ(json_int(torus.out, "genus"), 1);
  CmdResult two = run("stats " + data("bad/two_cubes.off") + " --json");
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(json_int(two.out, "shells"), 2);
  EXPECT_EQ(json_int(two.out, "genus"), 0);
  // A cube [-2,2]^3 facing outwards around a cavity [-1,1]^3 facing into it.
  std::ofstream(path("cavity.off")) << "OFF\n16 12 0\n"
                                    << "-2 -2 -2\n2 -2 -2\n2 2 -2\n-2 2 -2\n-2 -2 2\n2 -2 2\n2 2 2\n-2 2 2\n"
                                    << "-1 -1 -1\n1 -1 -1\n1 1 -1\n-1 1 -1\n-1 -1 1\n1 -1 1\n1 1 1\n-1 1 1\n"
                                    << "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"
                                    << "4 8 9 10 11\n4 12 15 14 13\n4 8 12 13 9\n4 9 13 14 10\n4 10 14 15 11\n"
                                    << "4 11 15 12 8\n";
  CmdResult cav = run("stats " + path("cavity.off") + " --json");
  ASSERT_EQ(cav.status, 0) << cav.err;
  EXPECT_EQ(json_text(cav.out, "volume"), "56");
  EXPECT_EQ(json_int(cav.out, "shells"), 2);
  EXPECT_EQ(json_int(cav.out, "genus"), 0);
  EXPECT_EQ(json_int(cav.out, "facets"), 12);
  // Through standard input.
  CmdResult in = run_sh("minksum gen tube --exact -o - --format off | minksum stats - --format off --json");
  ASSERT_EQ(in.status, 0) << in.err;
  EXPECT_EQ(json_int(in.out, "genus"), 1);
  EXPECT_NE(in.out.find("\"name\": \"-\""), std::string::npos) << in.out;
}

// Convex inputs keep their stats exactly (the keys of a polytope, no genus;
// the kind of every result, docs/json.md).
TEST_F(Cli, StatsOfAConvexPolytopeUnchangedBySolids) {
  CmdResult c = run("stats cube --json");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_EQ(c.out.rfind("{\"name\": \"cube\", \"vertices\": 8, \"edges\": 12, \"facets\": 6, "
                        "\"dimension\": 3, \"kind\": \"polytope\", \"volume\": \"8\", "
                        "\"volume_double\": 8, \"max_facet_degree\": 4, \"max_vertex_degree\": 3, "
                        "\"coordinates_are_doubles\": true, \"phases\": {",
                        0),
            0u)
      << c.out;
  CmdResult t = run("stats cube");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(t.out, "cube: 8 vertices, 12 edges, 6 facets\n  volume 8\n  largest facet has 4 vertices, largest vertex "
                   "degree 3\n  coordinates: all exact doubles\n");
}

// convert writes a solid in every format: exactly to OFF/OBJ/WRL with
// --exact (read back: the same exact volume), rounded otherwise (a note, a
// valid solid read back), as triangles to STL.
TEST_F(Cli, ConvertWritesNonConvexSolids) {
  ASSERT_EQ(run("sum tube sphere:2@scale:1/4 --exact -o " + path("x.off")).status, 0);
  CmdResult st = run("stats " + path("x.off") + " --json");
  ASSERT_EQ(st.status, 0) << st.err;
  const std::string volume = json_text(st.out, "volume");
  for (const char* ext : {"obj", "wrl", "off"}) {
    SCOPED_TRACE(ext);
    const std::string out = path(std::string("y.") + ext);
    CmdResult c = run("convert " + path("x.off") + " --exact --json -o " + out);
    ASSERT_EQ(c.status, 0) << c.err;
    EXPECT_NE(c.out.find("\"convex\": false"), std::string::npos) << c.out;
    EXPECT_NE(c.out.find("\"rounding\": null"), std::string::npos) << c.out;
    EXPECT_EQ(json_int(c.out, "facets"), json_int(st.out, "facets"));
    CmdResult back = run("stats " + out + " --json");
    ASSERT_EQ(back.status, 0) << back.err;
    EXPECT_EQ(json_text(back.out, "volume"), volume);
    EXPECT_EQ(json_int(back.out, "genus"), 1);
  }
  // Without --exact the coordinates that are not doubles are rounded, the
  // written surface a valid solid of genus 1.
  for (const char* ext : {"stl", "ply", "obj"}) {
    SCOPED_TRACE(ext);
    const std::string out = path(std::string("r.") + ext);
    CmdResult c = run("convert " + path("x.off") + " --json -o " + out);
    ASSERT_EQ(c.status, 0) << c.err;
    EXPECT_NE(c.err.find("written rounded"), std::string::npos) << c.err;
    EXPECT_GE(json_int(c.out, "coordinates"), 1) << c.out;
    CmdResult back = run("stats " + out + " --json");
    ASSERT_EQ(back.status, 0) << back.err;
    EXPECT_EQ(json_int(back.out, "genus"), 1);
    EXPECT_EQ(json_int(back.out, "facets"), json_int(c.out, "facets"));
  }
  // The tube's integer coordinates are written as they are; to STL its 16
  // faces as 32 triangles.
  CmdResult tube = run("convert tube -o " + path("t.stl"));
  ASSERT_EQ(tube.status, 0) << tube.err;
  EXPECT_EQ(tube.err, "");
  EXPECT_EQ(tube.out, "tube: 16 vertices, 32 edges, 16 facets, a non-convex solid, written to " + path("t.stl") +
                          " (STL) as 32 triangles\n");
  CmdResult t = run("stats " + path("t.stl") + " --json");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(json_text(t.out, "volume"), "6");
  EXPECT_EQ(json_int(t.out, "facets"), 32);
  // Bad solids are still refused: exit 3, one line, no file.
  const std::string l = slurp(data("bad/nonconvex_lprism.off"));
  std::ofstream(path("open.off")) << l.substr(0, l.rfind('\n', l.size() - 2) + 1);
  CmdResult bad = run("convert " + path("open.off") + " -o " + path("bad.off"));
  EXPECT_EQ(bad.status, 3) << bad.err;
  EXPECT_EQ(lines(bad.err), 1u) << bad.err;
  EXPECT_FALSE(fs::exists(path("bad.off")));
}

// view shows a non-convex solid, alone or in a sum with the sum's exact
// volume; the page's data gives the triangles of the faces.
TEST_F(Cli, ViewShowsNonConvexSolids) {
  CmdResult one = run("view tube -o " + path("tube.html") + " --json");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(one.out, "{\"page\": \"solid\", \"name\": \"tube\", \"vertices\": 16, \"edges\": 32, \"facets\": 16, "
                     "\"dimension\": 3, \"kind\": \"solid\", \"volume\": \"6\", \"convex\": false, \"output\": \"" +
                         path("tube.html") + "\"}\n");
  const std::string page = slurp(path("tube.html"));
  EXPECT_NE(page.find("\"triangle_facet\""), std::string::npos);
  EXPECT_NE(page.find("\"kind\": \"solid\""), std::string::npos);
  CmdResult sum = run("sum tube box:1/2:1/2:1/2 --json");
  ASSERT_EQ(sum.status, 0) << sum.err;
  CmdResult two = run("view tube box:1/2:1/2:1/2 -o " + path("sum.html") + " --json");
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(json_text(two.out, "volume"), "15");
  EXPECT_EQ(json_int(two.out, "facets"), json_int(sum.out, "facets"));
  EXPECT_TRUE(fs::exists(path("sum.html")));
  CmdResult text = run("view tube -o " + path("t2.html"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_EQ(text.out, "tube: 16 vertices, 32 edges, 16 facets, a non-convex solid\n  page written to " +
                          path("t2.html") + "\n");
}

// A refusal of a non-convex operand names --hull, and every command that
// takes convex operands has it: cgm (which refused without the hint),
// query, simulate (which had no --hull); batch, which takes solids, names it
// for a point cloud.
TEST_F(Cli, RefusalsNameHullOnlyWhereTheCommandHasIt) {
  const std::string hint = "; --hull takes the convex hull of its points instead";
  for (const std::string& cmd : std::vector<std::string>{"cgm tube", "cgm cube tube", "query collide tube cube"}) {
    SCOPED_TRACE(cmd);
    CmdResult r = run(cmd);
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(hint), std::string::npos) << r.err;
    EXPECT_EQ(run(cmd + " --hull").status, 0) << cmd;
  }
  // batch takes solids as sum does; a point cloud is refused naming --hull.
  CmdResult b = run_sh("echo 'tube cube' | minksum batch");
  EXPECT_EQ(b.status, 0) << b.err;
  EXPECT_NE(b.out.find("\"kind\": \"solid\""), std::string::npos) << b.out;
  EXPECT_EQ(b.out.find("--hull"), std::string::npos) << b.out;
  std::ofstream(path("cloud.off")) << "OFF\n4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  std::ofstream(path("pairs.txt")) << "cube " << path("cloud.off") << "\n";
  CmdResult cloud = run("batch " + path("pairs.txt"));
  EXPECT_EQ(cloud.status, 3) << cloud.err;
  EXPECT_NE(cloud.out.find(hint), std::string::npos) << cloud.out;
  EXPECT_EQ(run("batch " + path("pairs.txt") + " --hull").status, 0);
  CmdResult sim = run("simulate --obstacle tube --frames 4");
  EXPECT_EQ(sim.status, 3) << sim.err;
  EXPECT_EQ(lines(sim.err), 1u) << sim.err;
  EXPECT_NE(sim.err.find(hint), std::string::npos) << sim.err;
  EXPECT_EQ(run("simulate --obstacle tube --frames 4 --hull").status, 0);
  CmdResult robot = run("simulate --robot tube --frames 4");
  EXPECT_NE(robot.err.find(hint), std::string::npos) << robot.err;
  // The commands that take solids take a valid one without a word of --hull.
  for (const std::string& cmd : std::vector<std::string>{"stats tube", "convert tube -o " + path("t.off"),
                                                        "view tube -o " + path("t.html"), "sum tube cube",
                                                        "erode tube cube@scale:1/8"}) {
    SCOPED_TRACE(cmd);
    CmdResult r = run(cmd);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ((r.out + r.err).find("--hull"), std::string::npos) << r.out << r.err;
  }
}

// A non-convex sum's --json has the keys of a convex sum's (it had "faces"
// and "rounded_coordinates", no "dimension", no "operands"), "kind"
// names the result in both (as for sums with points, segments, polygons), the
// operands' counts those of 'stats', and "rounding" what was rounded.
TEST_F(Cli, NonConvexSumJsonHasTheConvexSumsKeys) {
  CmdResult convex = run("sum cube box:1/2:1/2:1/2 --json");
  ASSERT_EQ(convex.status, 0) << convex.err;
  CmdResult solid = run("sum tube box:1/2:1/2:1/2 --json");
  ASSERT_EQ(solid.status, 0) << solid.err;
  for (const char* key : {"vertices", "edges", "facets", "dimension", "kind", "method", "seconds", "phases",
                          "volume", "volume_double", "a", "b", "operands", "output", "rounding"}) {
    SCOPED_TRACE(key);
    const std::string k = std::string("\"") + key + "\": ";
    EXPECT_NE(convex.out.find(k), std::string::npos) << convex.out;
    EXPECT_NE(solid.out.find(k), std::string::npos) << solid.out;
  }
  EXPECT_EQ(json_int(solid.out, "dimension"), 3);
  EXPECT_NE(solid.out.find("\"dimension\": 3, \"kind\": \"solid\", \"method\": \"nonconvex\""), std::string::npos)
      << solid.out;
  EXPECT_NE(convex.out.find("\"dimension\": 3, \"kind\": \"polytope\", \"method\": \"walk\""), std::string::npos)
      << convex.out;
  EXPECT_NE(solid.out.find("\"operands\": [{\"name\": \"tube\", \"vertices\": 16, \"edges\": 32, \"facets\": 16, "
                           "\"dimension\": 3, \"kind\": \"solid\"}, {\"name\": \"box:1/2:1/2:1/2\", \"vertices\": 8, "
                           "\"edges\": 12, \"facets\": 6, \"dimension\": 3, \"kind\": \"polytope\"}]"),
            std::string::npos)
      << solid.out;
  EXPECT_NE(solid.out.find("\"output\": null, \"rounding\": null}"), std::string::npos)
      << solid.out;
  // Rounded: 1/3 is no double.
  CmdResult third = run("sum lshape cube@scale:1/3 --json -o " + path("third.off"));
  ASSERT_EQ(third.status, 0) << third.err;
  const std::string rounding = third.out.substr(third.out.find("\"rounding\": "));
  EXPECT_EQ(json_int(rounding, "coordinates"), 36) << third.out;
  // Each quantity under one name: the operands' faces are their facets, the
  // rounded coordinates those of "rounding" (docs/json.md).
  for (const char* gone : {"\"faces\"", "\"rounded_coordinates\""})
    EXPECT_EQ(third.out.find(gone), std::string::npos) << gone << " in " << third.out;
}

// minksum erode / open / close (docs/nonconvex.md, "Erosion, opening,
// closing"): exact results, JSON, the empty erosion, bad input and usage.
TEST_F(Cli, ErodeOpenCloseJsonExactAndEmpty) {
  // The L prism [-1,1]^2 minus (0,1]^2, height 1, eroded by [-1/4,1/4]^3:
  // an L of arms 1/2 wide, 1/2 high: volume 5/8.
  CmdResult e = run("erode lshape cube@scale:1/4 --json --exact -o " + path("e.off"));
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(e.err, "");
  EXPECT_NE(e.out.find("\"operation\": \"erosion\", \"empty\": false"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("\"volume\": \"5/8\""), std::string::npos) << e.out;
  EXPECT_EQ(json_int(e.out, "facets"), 8);
  EXPECT_EQ(json_int(e.out, "shells"), 1);
  for (const char* key : {"decompose", "pairs", "union", "boundary", "candidate_facets", "culled_facets", "clips"})
    EXPECT_NE(e.out.find(std::string("\"") + key + "\""), std::string::npos) << key;
  CmdResult back = run("stats " + path("e.off") + " --json");
  ASSERT_EQ(back.status, 0) << back.err;
  EXPECT_NE(back.out.find("\"volume\": \"5/8\""), std::string::npos) << back.out;
  // Opened and closed by the smaller cube: the L itself (volume 3).
  for (const char* op : {"open", "close"}) {
    CmdResult o = run(std::string(op) + " lshape cube@scale:1/4 --json -o " + path("o.stl") + " --binary");
    ASSERT_EQ(o.status, 0) << op << o.err;
    EXPECT_NE(o.out.find(std::string("\"operation\": \"") + (op[0] == 'o' ? "opening" : "closing") + "\""),
              std::string::npos) << o.out;
    EXPECT_NE(o.out.find("\"volume\": \"3\""), std::string::npos) << o.out;
  }
  // The summary names the operation.
  CmdResult text = run("close tube sphere:1@scale:1/4");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("(tube ("), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(") ⊖ B"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("closing (sweep)"), std::string::npos) << text.out;
  // B fits nowhere: an empty result, exit 0, a file with no faces.
  CmdResult empty = run("erode cube cube@scale:2 --json -o " + path("empty.off"));
  ASSERT_EQ(empty.status, 0) << empty.err;
  EXPECT_NE(empty.out.find("\"operation\": \"erosion\", \"empty\": true"), std::string::npos) << empty.out;
  EXPECT_NE(empty.out.find("\"volume\": \"0\""), std::string::npos) << empty.out;
  EXPECT_EQ(json_int(empty.out, "facets"), 0);
  EXPECT_NE(slurp(path("empty.off")).find("0 0 0"), std::string::npos) << slurp(path("empty.off"));
  CmdResult summary = run("open lshape cube@scale:3/4");
  ASSERT_EQ(summary.status, 0) << summary.err;
  EXPECT_NE(summary.out.find("= empty: B fits nowhere inside A (A ⊖ B is empty)"), std::string::npos) << summary.out;
  // B not convex: bad input, one line naming B.
  CmdResult notconvex = run("erode cube lshape");
  EXPECT_EQ(notconvex.status, 3) << notconvex.err;
  EXPECT_NE(notconvex.err.find("lshape: is not convex: 'minksum erode' takes a convex polytope B"), std::string::npos)
      << notconvex.err;
  EXPECT_EQ(std::count(notconvex.err.begin(), notconvex.err.end(), '\n'), 1);
  // A bad A: the sum's validation message, exit 3.
  std::ofstream(path("open.off")) << "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n";
  CmdResult bad = run("open " + path("open.off") + " cube");
  EXPECT_EQ(bad.status, 3) << bad.err;
  EXPECT_NE(bad.err.find("open.off"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::ifstream(path("never.off")).good());
  // Usage.
  EXPECT_EQ(run("erode cube").status, 2);
  EXPECT_EQ(run("erode cube cube --method cvms").status, 2);
  EXPECT_EQ(run("erode cube segment:0,0,0:1,0,0").status, 2);
  CmdResult help = run("erode --help");
  ASSERT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("A ⊖ B = { x : x + B ⊆ A }"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("empty"), std::string::npos);
}

// A convex A: the erosion is the intersection of A's moved half-spaces (one
// pair, no union), the opening its convex sum with B; both written as binary
// STL that reads back as a closed solid, and the exact volume of the cube ⊖
// the cube of side 1/2 (side 3/2).
TEST_F(Cli, ErodeAndOpenAConvexATakeTheHalfSpacePath) {
  CmdResult e = run("erode cube cube@scale:1/4 --json --exact -o " + path("ce.off"));
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_NE(e.out.find("\"volume\": \"27/8\""), std::string::npos) << e.out;
  EXPECT_EQ(json_int(e.out, "facets"), 6);
  EXPECT_NE(e.out.find("\"pieces\": {\"a\": 1, \"b\": 1}, \"pairs\": 1,"), std::string::npos) << e.out;
  EXPECT_EQ(json_int(e.out, "pair_facets"), 6);
  EXPECT_EQ(json_int(e.out, "clips"), 0);
  EXPECT_NE(e.out.find("\"nonconvex_method\": \"decomposition\""), std::string::npos) << e.out;
  for (const char* op : {"erode", "open", "close"}) {
    SCOPED_TRACE(op);
    CmdResult o = run(std::string(op) + " dodecahedron sphere:2@scale:1/10 --json -o " + path("c.stl") + " --binary");
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_EQ(json_int(o.out, "clips"), 0);
    CmdResult back = run("stats " + path("c.stl"));
    EXPECT_EQ(back.status, 0) << back.err;
  }
}
