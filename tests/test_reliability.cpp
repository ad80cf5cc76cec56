// The contract on the paths around the computation: every output channel
// checked (exit 1 and one line naming it), JSON that any strict parser reads
// (no bare inf, only UTF-8), one error one line whatever bytes a name or a
// token holds, a UTF-8 byte-order mark accepted in every text format, and the
// inputs the fuzz targets found kept as regression files.
#include <gtest/gtest.h>

#include "fuzz/solid_writer_case.hpp"
#include "shell.hpp"

#include <minksum/error.hpp>
#include <minksum/io.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct Outcome {
  int status = -1;
  std::string out, err;
};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A shell-quoted word.
std::string sh(const std::string& word) {
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::size_t lines(const std::string& text) { return std::size_t(std::count(text.begin(), text.end(), '\n')); }

// A cube with half-width h (any OFF number token), facets outward.
std::string cube_off(const std::string& h) {
  const std::string m = h[0] == '-' ? h.substr(1) : "-" + h;
  const std::string v[2] = {m, h};
  std::string s = "OFF\n8 6 0\n";
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) s += v[x] + " " + v[y] + " " + v[z] + "\n";
  return s + "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
}

class Reliability : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("minksum_reliability_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `minksum ARGS` through sh (ARGS may redirect stdout); stdout unless
  // redirected, and stderr, captured.
  Outcome run(const std::string& args) {
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd = std::string(MINKSUM_BIN) + " " + args + " 2>" + err.string() + " </dev/null";
    Outcome r;
    const ShellOutput o = shell_stdout(cmd);
    if (o.status < 0) return r;
    r.status = o.status;
    r.out = o.out;
    r.err = read_file(err);
    return r;
  }

  // True when Python's json module reads `text` as exactly one JSON value
  // per line, as strict UTF-8, refusing NaN and Infinity; the reason otherwise.
  ::testing::AssertionResult strict_json_lines(const std::string& text) {
    const fs::path in = dir_ / "json.txt", why = dir_ / "json-why.txt";
    write_file(in, text);
    const std::string code =
        "import json,sys\n"
        "def bad(c): raise ValueError('non-finite number ' + c)\n"
        "text = sys.stdin.buffer.read().decode('utf-8')\n"
        "assert text.endswith('\\n'), 'no final newline'\n"
        "for line in text.splitlines(): json.loads(line, parse_constant=bad)\n";
    const int st = std::system(("/usr/bin/python3 -c " + sh(code) + " <" + in.string() + " 2>" + why.string()).c_str());
    if (st == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "not strict JSON: " << read_file(why) << "in: " << text;
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------
// 1. Every output channel checked.

TEST_F(Reliability, StdoutOnAFullDeviceExitsOneForEveryCommand) {
  const std::string cases[] = {
      "stats cube --json",
      "stats cube",
      "sum cube cube --json",
      "sum cube cube",
      "gen cube -o " + (dir_ / "g.off").string(),
      "query collide cube cube --json",
      "query distance cube cube --translate-p 5,0,0",
      "query depth cube cube --json",
      "query ddepth cube cube --direction 1,0,0",
      "simulate --frames 4",
      "simulate --frames 4 --json",
      "cgm cube --json",
      "cgm cube cube",
      "--help",
      "--version",
      "sum --help",
      "gen --help",
  };
  for (const std::string& args : cases) {
    SCOPED_TRACE(args);
    const Outcome r = run(args + " >/dev/full");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "minksum: cannot write to standard output: No space left on device\n");
  }
}

TEST_F(Reliability, TrajectoryIntoAFullDeviceStopsWithExitOne) {
  std::string poses;
  for (int i = 0; i < 10000; ++i) poses += std::to_string(i % 7) + ",0,0\n";
  write_file(dir_ / "poses.txt", poses);
  for (const char* json : {" --json", ""}) {
    const Outcome r = run("query distance cube cube --trajectory " + (dir_ / "poses.txt").string() + json + " >/dev/full");
    EXPECT_EQ(r.status, 1) << json;
    EXPECT_EQ(r.err, "minksum: cannot write to standard output: No space left on device\n") << json;
  }
}

TEST_F(Reliability, TrajectoryThatIsADirectoryExitsThree) {
  const Outcome r = run("query collide cube cube --trajectory " + dir_.string());
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(r.err, "minksum: " + dir_.string() + ": is a directory, not a trajectory file\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(Reliability, NoteOnAFullStderrExitsOne) {
  // The note that rotated coordinates are rounded cannot be printed.
  const std::string cmd = std::string(MINKSUM_BIN) + " gen sphere:3@rot:5 -o " + (dir_ / "s.off").string() +
                          " >/dev/null 2>/dev/full";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
}

// ---------------------------------------------------------------------------
// 2. JSON never contains a non-finite number.

TEST_F(Reliability, JsonOfACubeAtTheDoubleLimitHasNullAndTheExactValue) {
  write_file(dir_ / "big.off", cube_off("1e308"));
  const std::string big = (dir_ / "big.off").string();
  const Outcome stats = run("stats " + big + " --json");
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_TRUE(strict_json_lines(stats.out));
  EXPECT_NE(stats.out.find("\"volume_double\": null"), std::string::npos) << stats.out;
  // (2e308)^3 exactly, as the nearest doubles 1e308 give it.
  EXPECT_NE(stats.out.find("\"volume\": \"8000000000000000"), std::string::npos) << stats.out;

  const Outcome sum = run("sum " + big + " cube --json");
  ASSERT_EQ(sum.status, 0) << sum.err;
  EXPECT_TRUE(strict_json_lines(sum.out));
  EXPECT_NE(sum.out.find("\"volume_double\": null"), std::string::npos) << sum.out;
}

TEST_F(Reliability, JsonDistanceBeyondTheDoubleRangeIsNull) {
  const Outcome r = run("query distance cube cube --translate-q 1.5e308,1.5e308,0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(strict_json_lines(r.out));
  EXPECT_NE(r.out.find("\"distance\": null"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"squared_distance\": \"4500000000000000"), std::string::npos) << r.out;
  // Each closest point also as exact strings: Q's corner is exactly w - (1,1,0).
  EXPECT_NE(r.out.find("\"point_p_exact\": [\"1\", \"1\", \"0\"]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"point_q_exact\": [\"1500000000000000"), std::string::npos) << r.out;

  const Outcome depth = run("query depth cube cube --translate-q 1e300,0,0 --json");
  ASSERT_EQ(depth.status, 0) << depth.err;
  EXPECT_TRUE(strict_json_lines(depth.out));
  const Outcome ddepth = run("query ddepth cube cube --direction 1e-300,0,0 --json");
  ASSERT_EQ(ddepth.status, 0) << ddepth.err;
  EXPECT_TRUE(strict_json_lines(ddepth.out));
  EXPECT_NE(ddepth.out.find("\"depth\": 2"), std::string::npos) << ddepth.out;  // t = 2e300, depth t·|d| = 2
}

TEST_F(Reliability, EveryJsonOutputIsStrictJson) {
  write_file(dir_ / "poses.txt", "0,0,0\n3,0,0 rq=1,1,0,0\n1e308,0,0\n");
  const std::string cases[] = {
      "stats cube --json",
      "stats sphere:3@rot:5 --json --hull",
      "sum cube dodecahedron --json",
      "sum sphere:2 sphere:2@rot:3 --method cgm --json",
      "query collide cube cube --json",
      "query distance cube cube --translate-p 1e-300,7,0 --json",
      "query distance cube cube --json --trajectory " + (dir_ / "poses.txt").string(),
      "simulate --frames 4 --json",
      "cgm cube cube --json",
  };
  for (const std::string& args : cases) {
    SCOPED_TRACE(args);
    const Outcome r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(strict_json_lines(r.out));
  }
}

// ---------------------------------------------------------------------------
// 3. Names and tokens echoed in messages are escaped.

TEST_F(Reliability, FileNamesWithControlCharactersAndInvalidUtf8AreEscaped) {
  const std::string name = "a\nb\x1b[31mc\x01\x7f\xff\xc3(.off";
  const std::string escaped = "a\\nb\\x1b[31mc\\x01\\x7f\\xff\\xc3(.off";
  const fs::path missing = dir_ / name;
  Outcome r = run("stats " + sh(missing.string()));
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(r.err, "minksum: " + dir_.string() + "/" + escaped + ": no such file\n");

  // The same name on a valid cube: one text line, a name JSON can hold.
  write_file(missing, cube_off("1"));
  r = run("stats " + sh(missing.string()));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines(r.out), 4u) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  r = run("stats " + sh(missing.string()) + " --json");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(strict_json_lines(r.out));
  EXPECT_NE(r.out.find("a\\nb\\u001b[31mc\\u0001\\u007f\\ufffd\\ufffd(.off"), std::string::npos) << r.out;

  // An output name: the usage error names it on one line.
  r = run("gen cube -o " + sh((dir_ / "x\ny.xyz").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("x\\ny.xyz"), std::string::npos) << r.err;
}

// cgm --svg names its operands in the picture: control characters and bytes
// that are not UTF-8 made XML that no reader accepts.
TEST_F(Reliability, SvgOfOperandsNamedWithControlCharactersIsWellFormed) {
  const fs::path cube = dir_ / "a\x1b[31m<b>&\x01\xff\xc3(\xc2\x9b.off";
  write_file(cube, cube_off("1"));
  const fs::path svg = dir_ / "map.svg";
  Outcome r = run("cgm " + sh(cube.string()) + " --svg " + sh(svg.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = read_file(svg);
  // Well-formed UTF-8, no control character but tab and newline, no C1 control.
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      EXPECT_TRUE(c >= 0x20 || c == '\n' || c == '\t') << "byte " << int(c) << " at " << i;
      ++i;
      continue;
    }
    const std::size_t len = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
    ASSERT_GT(len, 0u) << "byte " << int(c) << " at " << i;
    ASSERT_LE(i + len, text.size());
    for (std::size_t k = 1; k < len; ++k)
      ASSERT_EQ(static_cast<unsigned char>(text[i + k]) & 0xC0, 0x80) << "at " << i;
    EXPECT_FALSE(c == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0) << "a C1 control at " << i;
    i += len;
  }
  // The markup in the name is text.
  EXPECT_NE(text.find("[31m&lt;b&gt;&amp;"), std::string::npos);
  EXPECT_EQ(text.find("<b>"), std::string::npos);
}

TEST_F(Reliability, TrajectoryErrorEchoingNulAndInvalidUtf8IsOneLine) {
  write_file(dir_ / "poses.txt", std::string("0,0,0\n1,2,\0\xfe\x9b" "3\n", 16));
  const Outcome r = run("query collide cube cube --trajectory " + (dir_ / "poses.txt").string());
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find((dir_ / "poses.txt").string() + ": line 2: bad coordinate '\\x00\\xfe\\x9b3'"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(lines(r.out), 1u);  // the first pose was answered
}

TEST_F(Reliability, UsageErrorEchoingAnEscapeSequenceIsEscaped) {
  const Outcome r = run(std::string("query collide cube cube --translate-p ") + sh("1,2,\x1b]0;title\x07"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\x1b]0;title\\x07"), std::string::npos) << r.err;
}

// ---------------------------------------------------------------------------
// 4. A UTF-8 byte-order mark is accepted in the text formats.

const std::string kBom = "\xEF\xBB\xBF";

void expect_tetrahedron_with_bom(const std::string& text, minksum::Format format) {
  std::istringstream in(kBom + text);
  const minksum::Mesh m = minksum::read_mesh(in, format, "bom");
  EXPECT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.faces.size(), 4u);
  const minksum::ConvexPolytope p = minksum::ConvexPolytope::from_mesh(m);
  EXPECT_EQ(p.volume(), minksum::Rational(1, 6));
}

TEST(ByteOrderMark, Off) {
  expect_tetrahedron_with_bom("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
                              minksum::Format::off);
}

TEST(ByteOrderMark, Obj) {
  expect_tetrahedron_with_bom("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
                              minksum::Format::obj);
}

TEST(ByteOrderMark, AsciiPly) {
  expect_tetrahedron_with_bom(
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
      minksum::Format::ply);
}

TEST(ByteOrderMark, AsciiStl) {
  const char* tri[4][3] = {{"0 0 0", "0 1 0", "1 0 0"},
                           {"0 0 0", "1 0 0", "0 0 1"},
                           {"0 0 0", "0 0 1", "0 1 0"},
                           {"1 0 0", "0 1 0", "0 0 1"}};
  std::string s = "solid t\n";
  for (const auto& t : tri) {
    s += "facet normal 0 0 0\nouter loop\n";
    for (const char* v : t) s += std::string("vertex ") + v + "\n";
    s += "endloop\nendfacet\n";
  }
  expect_tetrahedron_with_bom(s + "endsolid t\n", minksum::Format::stl);
}

TEST(ByteOrderMark, Vrml) {
  expect_tetrahedron_with_bom(
      "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 0 0 1 ] }\n"
      " coordIndex [ 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1 ] } }\n",
      minksum::Format::wrl);
}

TEST_F(Reliability, ByteOrderMarkOnTheCommandLine) {
  write_file(dir_ / "bom.off", kBom + cube_off("1"));
  const Outcome r = run("stats " + (dir_ / "bom.off").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("8 vertices, 12 edges, 6 facets"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------
// 5. The fuzz targets' seed corpus and the inputs they found
// (tests/fuzz/corpus/NAME/, tests/fuzz/regressions/NAME/), in the normal suite:
// every file is read or refused with an InputError, nothing else.

namespace fuzz_inputs {

const fs::path kFuzz = fs::path(MINKSUM_TEST_DATA) / ".." / "fuzz";

std::vector<fs::path> inputs(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path dir = kFuzz / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The solid writer's seeds and findings: each a RoundingError or a written
// file that reads back as a valid solid (solid_writer_case.hpp).
TEST(FuzzInputs, EverySolidWriterInputIsWrittenValidOrRefused) {
  const auto files = inputs("solid_writer");
  EXPECT_GE(files.size(), 3u) << "solid_writer: the seed corpus is missing";
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const std::string bytes = read_file(f);
    try {
      minksum_fuzz::solid_writer_case(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(FuzzInputs, EveryReaderInputIsReadOrRefused) {
  const std::pair<const char*, minksum::Format> readers[] = {{"off", minksum::Format::off},
                                                              {"obj", minksum::Format::obj},
                                                              {"ply", minksum::Format::ply},
                                                              {"stl", minksum::Format::stl},
                                                              {"wrl", minksum::Format::wrl}};
  for (const auto& [name, format] : readers) {
    const auto files = inputs(name);
    EXPECT_GE(files.size(), 3u) << name << ": the seed corpus is missing";
    for (const fs::path& f : files) {
      SCOPED_TRACE(f.string());
      std::istringstream in(read_file(f));
      try {
        const minksum::Mesh m = minksum::read_mesh(in, format, f.string());
        try {
          (void)minksum::ConvexPolytope::from_mesh(m, f.string());
        } catch (const minksum::InputError&) {
        }
      } catch (const minksum::InputError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << "neither a mesh nor an InputError: " << e.what();
      }
    }
  }
}

TEST_F(Reliability, EveryTrajectoryInputIsAnsweredOrRefusedOnOneLine) {
  const auto files = inputs("trajectory");
  EXPECT_GE(files.size(), 2u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const Outcome r = run("query collide cube cube --json --trajectory " + sh(f.string()));
    if (r.status == 0) {
      EXPECT_EQ(r.err, "");
      if (!r.out.empty()) {
        EXPECT_TRUE(strict_json_lines(r.out));
      }
    } else {
      EXPECT_EQ(r.status, 3);
      EXPECT_EQ(lines(r.err), 1u) << r.err;
    }
  }
  for (const fs::path& f : inputs("vector")) {
    SCOPED_TRACE(f.string());
    const Outcome r = run("query collide cube cube --translate-p " + sh(read_file(f)));
    EXPECT_TRUE(r.status == 0 || r.status == 2) << r.status;
    EXPECT_EQ(lines(r.err), r.status == 0 ? 0u : 1u) << r.err;
  }
}

}  // namespace fuzz_inputs

}  // namespace
