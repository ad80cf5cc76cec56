// `minksum play` as a client sees it: the server started with --no-open, its
// URL read from the first line of standard output, queries sent with
// cpp-httplib's client and their answers checked exactly against
// `minksum query` for the same poses; malformed requests get 400 and one
// line; SIGINT and SIGTERM stop it with exit status 0.
#include <gtest/gtest.h>

#include "shell.hpp"

#include <httplib.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

// The value of "key" in a flat JSON text: a string literal, an array or an
// object (brackets matched), or a bare word, as the text holds it.
std::string json_field(const std::string& json, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const std::size_t at = json.find(tag);
  if (at == std::string::npos) return "<missing " + key + ">";
  std::size_t i = at + tag.size(), j = i;
  if (json[i] == '"') {
    j = json.find('"', i + 1) + 1;
  } else if (json[i] == '[' || json[i] == '{') {
    int depth = 0;
    bool in_string = false;
    for (; j < json.size(); ++j) {
      const char c = json[j];
      if (c == '"') in_string = !in_string;
      if (in_string) continue;
      if (c == '[' || c == '{') ++depth;
      if ((c == ']' || c == '}') && --depth == 0) break;
    }
    ++j;
  } else {
    j = json.find_first_of(",}", i);
  }
  return json.substr(i, j - i);
}

using CmdRun = ShellOutput;

// A shell command line: its standard output and exit status.
CmdRun run_line(const std::string& line) { return shell_stdout(line); }

CmdRun run(const std::string& args) {
  return run_line(std::string(MINKSUM_BIN) + " " + args + " 2>/dev/null </dev/null");
}

// `minksum play ARGS --no-open` as a child process; its first stdout line.
class Server {
 public:
  explicit Server(const std::vector<std::string>& args) {
    int fds[2];
    if (::pipe(fds) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(fds[1], 1);
      const int null = ::open("/dev/null", O_RDWR);
      ::dup2(null, 0);
      ::dup2(null, 2);
      ::close(fds[0]);
      ::close(fds[1]);
      std::vector<std::string> all = {MINKSUM_BIN, "play"};
      all.insert(all.end(), args.begin(), args.end());
      all.push_back("--no-open");
      std::vector<char*> argv;
      for (auto& a : all) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(MINKSUM_BIN, argv.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    out_ = fds[0];
    // The first line, within a minute (M of small polytopes takes milliseconds).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (first_line_.find('\n') == std::string::npos && std::chrono::steady_clock::now() < deadline) {
      pollfd pf{out_, POLLIN, 0};
      if (::poll(&pf, 1, 200) <= 0) continue;
      char c[256];
      const ssize_t n = ::read(out_, c, sizeof c);
      if (n <= 0) break;
      first_line_.append(c, std::size_t(n));
    }
    first_line_ = first_line_.substr(0, first_line_.find('\n'));
    const std::string prefix = "http://127.0.0.1:";
    if (first_line_.rfind(prefix, 0) == 0) port_ = std::atoi(first_line_.c_str() + prefix.size());
  }
  ~Server() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_ >= 0) ::close(out_);
  }
  int port() const { return port_; }
  const std::string& url() const { return first_line_; }
  // Sends `sig` and returns the exit status (-1: did not exit within 20 s).
  int stop(int sig) {
    ::kill(pid_, sig);
    for (int i = 0; i < 400; ++i) {
      int st = 0;
      if (::waitpid(pid_, &st, WNOHANG) == pid_) {
        waited_ = true;
        return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  int out_ = -1, port_ = 0;
  bool waited_ = false;
  std::string first_line_;
};

const char* kP = "random:24:3";
const char* kQ = "random:30:11@rot:7";

httplib::Result post(httplib::Client& c, const std::string& body) {
  return c.Post("/query", body, "application/json");
}

TEST(Play, ServesThePageOnLoopbackAndStopsOnSigterm) {
  Server s({kP, kQ});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  EXPECT_EQ(s.url(), "http://127.0.0.1:" + std::to_string(s.port()) + "/");
  httplib::Client c("127.0.0.1", s.port());
  auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("\"kind\": \"play\""), std::string::npos);
  EXPECT_NE(page->body.find("connect-src 'self'"), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Type").find("text/html"), std::string::npos);
  auto missing = c.Get("/nothing-here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

TEST(Play, StopsOnSigintWithStatusZero) {
  Server s({"cube", "octahedron"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  auto r = post(c, R"({"translate_p": "3,0,0"})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(s.stop(SIGINT), 0);
}

// Random poses on a dyadic grid (the page's grid) and rotations, some of them
// penetrating: each answer equals `minksum query distance` (and, when the
// bodies overlap, `minksum query depth`) for the same pose.
TEST(Play, AnswersEqualMinksumQueryForTheSamePoses) {
  Server s({kP, kQ});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  const unsigned seed = 20261123;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coordinate(-700, 700);  // in 1/256
  const std::vector<std::string> rotations = {"", "", "64,0,0,0", "60,12,-9,17", "60,12,-9,17", "7,1,2,3"};
  std::string previous;  // the server starts with P as given
  int seen[3] = {0, 0, 0};
  for (int i = 0; i < 24; ++i) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", pose " + std::to_string(i));
    const std::string t = std::to_string(coordinate(rng)) + "/256," + std::to_string(coordinate(rng)) + "/256," +
                          std::to_string(coordinate(rng) / 2) + "/256";
    const std::string rot = rotations[std::size_t(i) % rotations.size()];
    std::string body = "{\"translate_p\": \"" + t + "\"";
    if (!rot.empty()) body += ", \"rotate_p\": \"" + rot + "\"";
    body += "}";
    auto r = post(c, body);
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    const std::string& a = r->body;
    const std::string args = std::string(kP) + " " + kQ + " --translate-p " + t + (rot.empty() ? "" : " --rotate-p " + rot) + " --json";
    const CmdRun d = run("query distance " + args);
    ASSERT_EQ(d.status, 0) << args;
    SCOPED_TRACE(args + "\nserver: " + a + "\nquery:  " + d.out);
    const std::string status = json_field(a, "status");
    EXPECT_EQ(status, json_field(d.out, "status"));
    EXPECT_EQ(json_field(a, "squared_distance"), json_field(d.out, "squared_distance"));
    EXPECT_EQ(json_field(a, "distance"), json_field(d.out, "distance"));
    EXPECT_EQ(json_field(a, "point_p_exact"), json_field(d.out, "point_p_exact"));
    EXPECT_EQ(json_field(a, "point_q_exact"), json_field(d.out, "point_q_exact"));
    EXPECT_EQ(json_field(a, "direction"), json_field(d.out, "direction"));
    EXPECT_EQ(json_field(a, "witness"), json_field(d.out, "witness"));
    if (status == "\"penetrating\"") {
      const CmdRun p = run("query depth " + args);
      ASSERT_EQ(p.status, 0) << args;
      EXPECT_EQ(json_field(a, "squared_depth"), json_field(p.out, "squared_depth"));
      EXPECT_EQ(json_field(a, "depth"), json_field(p.out, "depth"));
      EXPECT_EQ(json_field(a, "depth_direction"), json_field(p.out, "direction"));
      EXPECT_EQ(json_field(a, "depth_witness"), json_field(p.out, "witness"));
      ++seen[2];
    } else {
      EXPECT_EQ(json_field(a, "squared_depth"), "\"0\"");
      EXPECT_EQ(json_field(a, "depth_witness"), "null");
      ++seen[status == "\"touching\"" ? 1 : 0];
    }
    // M is computed again exactly when the rotation changes.
    EXPECT_EQ(json_field(a, "recomputed"), rot == previous ? "false" : "true");
    previous = rot;
  }
  EXPECT_GT(seen[0], 0) << "no separate pose";
  EXPECT_GT(seen[2], 0) << "no penetrating pose";
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// A pose where the bodies touch: cube against cube, face to face.
TEST(Play, TouchingCubesAnswerTouchingWithZeroDistance) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  auto r = post(c, R"({"translate_p": "2,1/2,0", "translate_q": "0,0,0"})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json_field(r->body, "status"), "\"touching\"");
  EXPECT_EQ(json_field(r->body, "squared_distance"), "\"0\"");
  auto sep = post(c, R"({"translate_p": "5/2,0,0", "rotate_p": "1,0,0,0"})");
  ASSERT_TRUE(sep);
  EXPECT_EQ(json_field(sep->body, "status"), "\"separate\"");
  EXPECT_EQ(json_field(sep->body, "squared_distance"), "\"1/4\"");
  EXPECT_EQ(json_field(sep->body, "point_p_exact").substr(0, 6), "[\"3/2\"");
  auto deep = post(c, R"({"translate_p": "1/2,0,0"})");
  ASSERT_TRUE(deep);
  EXPECT_EQ(json_field(deep->body, "status"), "\"penetrating\"");
  EXPECT_EQ(json_field(deep->body, "squared_depth"), "\"9/4\"");
  EXPECT_EQ(json_field(deep->body, "depth"), "1.5");
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// Malformed requests: HTTP 400 (413 when too large) with one line saying
// why, and the server answers the next good request.
TEST(Play, MalformedRequestsGet400AndOneLine) {
  Server s({"cube", "tetra"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"", "bad JSON"},
      {"{", "bad JSON"},
      {"not json", "bad JSON"},
      {R"({"translate_p": "1,2,3"} trailing)", "text after the JSON object"},
      {R"({"translate_p": "1,2,3", "translate_p": "1,2,3"})", "given twice"},
      {R"({"translate_p": true})", "must be a string"},
      {R"({"translate_p": 1})", "bad JSON"},
      {R"({"translate_p": "1,2"})", "translate_p: expected three comma-separated numbers"},
      {R"({"translate_p": "1,2,x"})", "bad coordinate"},
      {R"({"translate_p": "1,2,3/0"})", "bad coordinate"},
      {R"({"translate_p": "1,2,nan"})", "bad coordinate"},
      {R"({"rotate_p": "1,0,0,0"})", "missing \"translate_p\""},
      {R"({"translate_p": "0,0,0", "rotate_p": "0,0,0,0"})", "non-zero quaternion"},
      {R"({"translate_p": "0,0,0", "rotate_p": "1,0,0"})", "four integers"},
      {R"({"translate_p": "0,0,0", "rotate_p": "1.5,0,0,0"})", "four integers"},
      {R"({"translate_p": "0,0,0", "rotate_p": "1000001,0,0,0"})", "at most 10^6"},
      {R"({"translate_p": "0,0,0", "scale": "2"})", "unknown key \"scale\""},
      {"{\"translate_p\": \"0,0,0\x01\"}", "bad JSON"},
  };
  for (const auto& [body, reason] : bad) {
    SCOPED_TRACE(body);
    auto r = post(c, body);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_NE(r->body.find(reason), std::string::npos) << r->body;
    ASSERT_FALSE(r->body.empty());
    EXPECT_EQ(r->body.find('\n'), r->body.size() - 1) << "not one line: " << r->body;
  }
  auto big = post(c, "{\"translate_p\": \"" + std::string(5000, '1') + ",0,0\"}");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  auto wrong_method = c.Get("/query");
  ASSERT_TRUE(wrong_method);
  EXPECT_EQ(wrong_method->status, 404);
  auto good = post(c, R"({"translate_p": "4,0,0"})");
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 200);
  EXPECT_EQ(json_field(good->body, "status"), "\"separate\"");
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// The URL cannot be written: nothing is served, exit status 1.
TEST(Play, UnwritableStandardOutputExitsWithStatusOne) {
  EXPECT_EQ(run_line("timeout 60 " + std::string(MINKSUM_BIN) + " play cube cube --no-open >/dev/full 2>/dev/null").status, 1);
}

TEST(Play, UsageAndInputErrors) {
  EXPECT_EQ(run("play cube").status, 2);
  EXPECT_EQ(run("play cube cube --port 70000").status, 2);
  EXPECT_EQ(run("play cube cube --port x").status, 2);
  EXPECT_EQ(run("play cube cube --method nosuch").status, 2);
  EXPECT_EQ(run("play cube /nonexistent/p.off").status, 3);
  const CmdRun help = run("play --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("POST /query"), std::string::npos);
}

// A port that is taken: exit status 1 and one line (not a second server
// sharing the port, as SO_REUSEPORT would allow).
TEST(Play, PortInUseExitsWithStatusOne) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string err_file = ::testing::TempDir() + "/minksum_play_port.txt";
  const std::string cmd = "timeout 60 " + std::string(MINKSUM_BIN) + " play cube cube --no-open --port " + std::to_string(s.port()) +
                          " </dev/null >/dev/null 2>" + err_file;
  const int st = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(st), 1);
  FILE* f = std::fopen(err_file.c_str(), "r");
  ASSERT_TRUE(f);
  std::string err;
  char buf[512];
  while (std::fgets(buf, sizeof buf, f)) err += buf;
  std::fclose(f);
  EXPECT_NE(err.find("cannot listen on 127.0.0.1:"), std::string::npos) << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

}  // namespace

namespace {

// The command runs the server from beside itself: a copy of the command
// alone says so on one line and exits with status 1 (but answers --help and
// usage errors itself).
TEST(Play, CommandWithoutItsServerBesideItExitsWithStatusOne) {
  const std::string dir = ::testing::TempDir() + "/minksum_play_alone_" + std::to_string(::getpid());
  ASSERT_EQ(std::system(("mkdir -p " + dir + " && cp " + MINKSUM_BIN + " " + dir + "/minksum").c_str()), 0);
  const CmdRun r = run_line(dir + "/minksum play cube cube --no-open 2>&1 </dev/null");
  // Help and usage errors need no server.
  const CmdRun help = run_line(dir + "/minksum play --help 2>&1 </dev/null");
  const CmdRun usage = run_line(dir + "/minksum play cube --no-open 2>&1 </dev/null");
  std::system(("rm -rf " + dir).c_str());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("cannot run the server of 'minksum play'"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("Usage: minksum play P Q"), std::string::npos) << help.out;
  EXPECT_EQ(usage.status, 2) << usage.out;
}

}  // namespace
