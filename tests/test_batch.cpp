// `minksum batch`: JSON lines and name pairs in, one JSON line per pair out in
// input order, the same answers as `minksum sum --json` for any --threads,
// failed pairs reported in place, malformed input refused before any work.
#include <gtest/gtest.h>

#include "shell.hpp"

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct CmdResult {
  int status = -1;
  std::string out, err;
};

class Batch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("minksum_batch_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }

  // Run `minksum ARGS`, stdin from `input` (a file of that text), under
  // `wrapper` (a command and its options) when given.
  CmdResult run(const std::string& args, const std::string& input = "", const std::string& wrapper = "") {
    const fs::path in = write("stdin.txt", input), err = dir_ / "stderr.txt";
    const std::string cmd =
        wrapper + std::string(MINKSUM_BIN) + " " + args + " <" + in.string() + " 2>" + err.string();
    CmdResult r;
    const ShellOutput o = shell_stdout(cmd);
    if (o.status < 0) return r;
    r.status = o.status;
    r.out = o.out;
    std::ifstream e(err);
    std::stringstream s;
    s << e.rdbuf();
    r.err = s.str();
    return r;
  }

  static std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
  }

  // The value of "key" in a JSON line: a number or a string's content.
  static std::string field(const std::string& json, const std::string& key) {
    std::smatch m;
    if (std::regex_search(json, m, std::regex("\"" + key + "\": \"([^\"]*)\""))) return m[1];
    if (std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9.e+-]+)"))) return m[1];
    return "<none>";
  }

  fs::path dir_;
};

const char* kPairs[][2] = {{"cube", "tetra"},          {"dodecahedron", "truncated-cube"},
                           {"sphere:3", "sphere:3@rot:5"}, {"box:1:2:3", "octahedron"},
                           {"random:200:1", "random:200:2"}};

TEST_F(Batch, AgreesWithSumForOneAndTwoThreads) {
  std::string input = "# pairs\n\n";
  for (const auto& p : kPairs) input += std::string("{\"a\": \"") + p[0] + "\", \"b\": \"" + p[1] + "\"}\n";
  const CmdResult one = run("batch --threads 1", input), two = run("batch - --threads 2", input);
  ASSERT_EQ(one.status, 0) << one.err;
  ASSERT_EQ(two.status, 0) << two.err;
  const auto l1 = lines(one.out), l2 = lines(two.out);
  ASSERT_EQ(l1.size(), std::size(kPairs));
  ASSERT_EQ(l2.size(), std::size(kPairs));
  for (std::size_t i = 0; i < l1.size(); ++i) {
    SCOPED_TRACE(l1[i]);
    const CmdResult sum = run(std::string("sum ") + kPairs[i][0] + " " + kPairs[i][1] + " --json");
    ASSERT_EQ(sum.status, 0);
    EXPECT_EQ(field(l1[i], "line"), std::to_string(i + 3));
    EXPECT_EQ(field(l1[i], "a"), kPairs[i][0]);
    EXPECT_EQ(field(l1[i], "b"), kPairs[i][1]);
    for (const char* key : {"method", "vertices", "edges", "facets", "volume", "volume_double"}) {
      EXPECT_EQ(field(l1[i], key), field(sum.out, key)) << key;
      EXPECT_EQ(field(l2[i], key), field(sum.out, key)) << key;
    }
  }
}

// Every kind of operand 'minksum sum' takes: non-convex solids, points,
// segments, polygons; the same kind, counts and exact volume as the sum.
TEST_F(Batch, SolidsAndSweepsAgreeWithSum) {
  const char* pairs[][2] = {{"tube", "cube@scale:1/8"},         {"lshape", "sphere:1@scale:1/4"},
                            {"cube", "segment:0,0,0:3,1,2"},     {"segment:0,0,0:2,0,0", "segment:0,0,0:1,1,0"},
                            {"point:1,2,3", "square"}};
  std::string input;
  for (const auto& p : pairs) input += std::string(p[0]) + " " + p[1] + "\n";
  const CmdResult r = run("batch --threads 2", input);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), std::size(pairs));
  for (std::size_t i = 0; i < l.size(); ++i) {
    SCOPED_TRACE(l[i]);
    const CmdResult sum = run(std::string("sum ") + pairs[i][0] + " " + pairs[i][1] + " --json");
    ASSERT_EQ(sum.status, 0) << sum.err;
    for (const char* key : {"method", "vertices", "edges", "facets", "dimension", "kind", "volume"})
      EXPECT_EQ(field(l[i], key), field(sum.out, key)) << key;
  }
  EXPECT_EQ(field(l[0], "kind"), "solid");
  EXPECT_EQ(field(l[0], "method"), "nonconvex");
  // A cube of side 2 swept along v = (3, 1, 2): its volume plus, per axis,
  // |v_i| times the area of the faces across it, 8 + 4 · (3 + 1 + 2).
  EXPECT_EQ(field(l[2], "volume"), "32");
  EXPECT_EQ(field(l[3], "kind"), "polygon");
  EXPECT_EQ(field(l[4], "dimension"), "2");
}

TEST_F(Batch, NamePairsFileAndMethods) {
  const fs::path file = write("pairs.txt", "cube tetra\n  sphere:2   cube  \n{\"a\": \"cube\", \"b\": \"tetra\", \"method\": \"chms\"}\n");
  const CmdResult r = run("batch " + file.string() + " --method cvms --threads 2");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(field(l[0], "method"), "cvms");
  EXPECT_EQ(field(l[1], "a"), "sphere:2");
  EXPECT_EQ(field(l[1], "line"), "2");
  EXPECT_EQ(field(l[2], "method"), "chms");
  EXPECT_EQ(field(l[0], "volume"), field(l[2], "volume"));
  EXPECT_EQ(r.err, "");
}

TEST_F(Batch, FailedPairsReportedInPlaceAndExitStatus) {
  const std::string bad = std::string(MINKSUM_TEST_DATA) + "/bad/nan.off";
  const CmdResult r = run("batch --threads 2", "cube tetra\ncube " + bad + "\nnosuchsolid cube\ncube octahedron\n");
  EXPECT_EQ(r.status, 3);
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(field(l[0], "vertices"), field(run("sum cube tetra --json").out, "vertices"));
  EXPECT_EQ(field(l[1], "status"), "3");
  EXPECT_NE(field(l[1], "error").find(bad + ": line 4: "), std::string::npos) << l[1];
  EXPECT_EQ(field(l[2], "status"), "2");
  EXPECT_NE(field(l[2], "error").find("nosuchsolid"), std::string::npos) << l[2];
  EXPECT_NE(field(l[3], "facets"), "<none>");
  // One stderr line: how many failed, and the first.
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("2 of 4 pairs failed; the first, <stdin> line 2: " + bad), std::string::npos) << r.err;
  // Only usage failures: status 2.
  EXPECT_EQ(run("batch", "cube nosuchsolid\n").status, 2);
}

TEST_F(Batch, MalformedLinesAreBadInputBeforeAnyWork) {
  const std::pair<const char*, const char*> cases[] = {
      {"cube tetra\n{\"a\": \"cube\"\n", "<stdin>: line 2: expected '}'"},
      {"{\"a\": \"cube\"}\n", "<stdin>: line 1: missing \"b\""},
      {"{\"a\": \"cube\", \"b\": \"tetra\", \"x\": \"1\"}\n", "unknown key \"x\""},
      {"{\"a\": \"cube\", \"b\": \"tetra\", \"method\": \"fast\"}\n", "unknown method 'fast'"},
      {"{\"a\": \"cube\", \"b\": true}\n", "\"b\" must be a non-empty string"},
      {"{\"a\": \"cube\", \"a\": \"tetra\"}\n", "\"a\" given twice"},
      {"{\"a\": \"cube\", \"b\": \"tetra\"} x\n", "text after the JSON object"},
      {"{\"a\": \"cu\\qbe\", \"b\": \"tetra\"}\n", "bad escape"},
      {"cube\n", "line 1: expected two names"},
      {"cube tetra octahedron\n", "more than two names"},
  };
  for (const auto& [input, message] : cases) {
    SCOPED_TRACE(input);
    const CmdResult r = run("batch", input);
    EXPECT_EQ(r.status, 3);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

// A line of 10^6 keys (16 MB), the last a duplicate of the first, is refused
// ("k0" given twice: the whole line was read) in linear time.  Comparing each
// key with every key before it is quadratic: 47 s for 160 000 keys, so about
// half an hour for these.  The command runs under `timeout -s KILL 30` so that
// such code fails here (status 137, 30 s) instead of hanging the suite;
// linear parsing takes under a second, and the 10 s bound leaves room for a
// loaded machine or a sanitizer build.
TEST_F(Batch, MillionKeyLineIsLinear) {
  std::string line = "{";
  for (int k = 0; k < 1000000; ++k) line += "\"k" + std::to_string(k) + "\": \"x\", ";
  line += "\"k0\": \"x\"}\n";
  const fs::path file = write("keys.jsonl", "cube tetra\n" + line);
  const auto t0 = std::chrono::steady_clock::now();
  const CmdResult r = run("batch " + file.string() + " --threads 1", "", "timeout -s KILL 30 ");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "a line of 10^6 keys refused in " << seconds << " s\n";
  EXPECT_LT(seconds, 10.0);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find(file.string() + ": line 2: \"k0\" given twice"), std::string::npos) << r.err.substr(0, 300);
}

// Names with control characters and bytes that are not UTF-8: the stderr line
// escapes them exactly as 'minksum sum' does in its message about the same
// name (\x1b, \r, \x07, \n, \xff), and the JSON line on stdout stays valid
// JSON (control characters as \u00XX, the bytes that are not UTF-8 as U+FFFD).
TEST_F(Batch, ControlCharactersInNamesEscaped) {
  // ESC [31m, CR, BEL, newline, two bytes that are not UTF-8, a C1 control (U+009B, CSI).
  const std::string name = (dir_ / "x\x1b[31mred\r\x07\ny\xff\xfe\xc2\x9bz.off").string();
  std::string json_name;  // the name as a JSON string's content, written by hand
  for (unsigned char c : name) {
    if (c == '\x1b') json_name += "\\u001b";
    else if (c == '\r') json_name += "\\r";
    else if (c == '\x07') json_name += "\\u0007";
    else if (c == '\n') json_name += "\\n";
    else json_name += char(c);
  }
  const CmdResult r = run("batch", "{\"a\": \"" + json_name + "\", \"b\": \"tetra\"}\n");
  EXPECT_EQ(r.status, 3) << r.err;
  const std::string shown = (dir_ / "x\\x1b[31mred\\r\\x07\\ny\\xff\\xfe\\xc2\\x9bz.off").string();
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("the first, <stdin> line 1: " + shown + ": "), std::string::npos) << r.err;
  // 'minksum sum' with the same name (built by printf: the shell's own octal escapes).
  const std::string dir = dir_.string();
  const ShellOutput sum = shell_stdout(std::string(MINKSUM_BIN) + " sum \"$(printf '" + dir +
                                       "/x\\033[31mred\\r\\007\\ny\\377\\376\\302\\233z.off')\" tetra 2>&1");
  EXPECT_EQ(sum.status, 3) << sum.out;
  EXPECT_NE(sum.out.find("minksum: " + shown + ": "), std::string::npos) << sum.out;
  // Neither output holds a control byte but the line ends, nor a byte that is not UTF-8.
  for (const std::string* text : {&r.err, &r.out}) {
    for (std::size_t i = 0; i < text->size(); ++i) {
      const unsigned char c = (*text)[i];
      EXPECT_TRUE(c >= 0x20 || c == '\n') << "byte " << int(c) << " at " << i;
      EXPECT_TRUE(c != 0x7f && c != 0xff && c != 0xfe) << "byte " << int(c) << " at " << i;
      EXPECT_FALSE(c == 0xc2 && i + 1 < text->size() && (unsigned char)(*text)[i + 1] >= 0x80 &&
                   (unsigned char)(*text)[i + 1] <= 0x9f) << "a C1 control at " << i;
    }
  }
  ASSERT_EQ(lines(r.out).size(), 1u) << r.out;
  const std::string json_shown = (dir_ / "x\\u001b[31mred\\u000d\\u0007\\ny\\ufffd\\ufffd\\u009bz.off").string();
  EXPECT_NE(r.out.find("\"a\": \"" + json_shown + "\", \"b\": \"tetra\", \"error\": \""), std::string::npos) << r.out;
  EXPECT_EQ(field(r.out, "status"), "3");
}

// Nothing but white space after the JSON object, and no NUL byte anywhere:
// exit 3 before any work, one line naming the file, the line and the problem.
TEST_F(Batch, TrailingNulGarbageRefused) {
  using namespace std::string_literals;
  const std::pair<std::string, std::string> cases[] = {
      {"{\"a\": \"cube\", \"b\": \"tetra\"}\0garbage\n"s, "line 2: a NUL byte at column 28"},
      {"{\"a\": \"cube\", \"b\": \"tetra\"}\0\n"s, "line 2: a NUL byte at column 28"},
      {"{\"a\": \"cube\", \"b\": \"tetra\"}  \0\n"s, "line 2: a NUL byte at column 30"},
      {"{\"a\": \"cube\", \"b\": \"tetra\"}garbage\n"s, "line 2: text after the JSON object at column 28"},
      {"{\"a\": \"cube\", \"b\": \"tetra\"} {}\n"s, "line 2: text after the JSON object at column 29"},
      {"{\"a\": \"cu\0be\", \"b\": \"tetra\"}\n"s, "line 2: a NUL byte at column 10"},
      {"{\"a\": \"cube\\\0\", \"b\": \"tetra\"}\n"s, "line 2: a NUL byte at column 13"},
      {"{\"a\": \"cube\",\0 \"b\": \"tetra\"}\n"s, "line 2: a NUL byte at column 14"},
      {"cube tetra\0garbage\n"s, "line 2: a NUL byte at column 11"},
      {"cube\0 tetra\n"s, "line 2: a NUL byte at column 5"},
  };
  for (const auto& [line, message] : cases) {
    SCOPED_TRACE(line);
    const fs::path file = write("pairs.jsonl", "cube tetra\n" + line + "cube octahedron\n");
    const CmdResult r = run("batch " + file.string());
    EXPECT_EQ(r.status, 3);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(file.string() + ": " + message), std::string::npos) << r.err;
  }
  // White space after the object (a CRLF line too) is no garbage.
  const CmdResult ok = run("batch", "{\"a\": \"cube\", \"b\": \"tetra\"} \t \r\n");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(field(ok.out, "a"), "cube");
}

TEST_F(Batch, JsonEscapesInNames) {
  const CmdResult r = run("batch", "{\"a\": \"\\u0063ube\", \"b\": \"tet\\u0072a\"}\n");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(field(r.out, "a"), "cube");
  EXPECT_EQ(field(r.out, "b"), "tetra");
}

TEST_F(Batch, UsageErrors) {
  EXPECT_EQ(run("batch --threads 0").status, 2);
  EXPECT_EQ(run("batch --threads two").status, 2);
  EXPECT_EQ(run("batch --method fast").status, 2);
  EXPECT_EQ(run("batch a.txt b.txt").status, 2);
  const CmdResult missing = run("batch " + (dir_ / "none.txt").string());
  EXPECT_EQ(missing.status, 3);
  EXPECT_NE(missing.err.find("none.txt"), std::string::npos);
}

TEST_F(Batch, HelpAndEmptyInput) {
  const CmdResult h = run("batch --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.out.find("--threads N"), std::string::npos);
  EXPECT_NE(h.out.find("walk"), std::string::npos);  // the method list filled in
  EXPECT_NE(run("--help").out.find("minksum batch"), std::string::npos);
  const CmdResult empty = run("batch", "# nothing\n\n");
  EXPECT_EQ(empty.status, 0);
  EXPECT_EQ(empty.out, "");
}

TEST_F(Batch, OutputNotWritableExitsOne) {
  const CmdResult r = run("batch >/dev/full", "cube tetra\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
}

}  // namespace
