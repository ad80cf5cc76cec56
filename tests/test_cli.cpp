// The `minksum` command as users run it: exit codes, JSON keys, output files,
// and the bad-input contract (exit 3, one line on stderr naming the file and
// the problem, no output file written).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>

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

  CmdResult run(const std::string& args) {
    fs::path err = dir_ / "stderr.txt";
    std::string cmd = std::string(MINKSUM_BIN) + " " + args + " 2>" + err.string() + " </dev/null";
    CmdResult r;
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
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

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string data(const std::string& rel) { return std::string(MINKSUM_TEST_DATA) + "/" + rel; }

  fs::path dir_;
};

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
  if (b.status == 0) EXPECT_EQ(b.out.find("\"volume\": \"8\""), std::string::npos) << b.out;
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
    CmdResult r = run("sum " + in + " cube -o " + out);
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    CmdResult s = run("stats " + in);
    EXPECT_EQ(s.status, 3) << s.err;
  }
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
