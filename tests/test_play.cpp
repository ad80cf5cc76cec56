// `minksum play` as a client sees it: the server started with --no-open, its
// URL read from the first line of standard output, queries sent with
// cpp-httplib's client and their answers checked exactly against
// `minksum query` for the same poses; malformed requests get 400 and one
// line; SIGINT and SIGTERM stop it with exit status 0.  Requests a page of
// another origin or a hostile client would send (another Host, another
// Origin, text/plain, oversized, slow, pipelined) go over raw sockets.
#include <gtest/gtest.h>

#include "shell.hpp"

#include <httplib.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <memory>
#include <random>
#include <regex>
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

// Whether the exact point "[\"x\", \"y\", \"z\"]" (a JSON triple) lies in
// the body SPEC translated by T: `minksum query collide` of the point and
// the body does not say separate.
bool point_in(const std::string& triple, const std::string& spec, const std::string& t) {
  std::string xyz;
  for (char c : triple)
    if (c != '[' && c != ']' && c != '"' && c != ' ') xyz += c;
  const CmdRun r = run("query collide point:" + xyz + " " + spec + " --translate-q " + t + " --json");
  return r.status == 0 && json_field(r.out, "status") != "\"separate\"" && json_field(r.out, "status").size() > 2;
}

// Random poses on a dyadic grid (the page's grid) and rotations, some of them
// penetrating: each answer equals `minksum query distance` (and, when the
// bodies overlap, `minksum query depth`) on M of the turned operand for the
// same pose — the way play answered a turned P before it answered on the
// placed bodies — with exact values equal.  P as given is answered on M,
// with M's witnesses; a turned P on the placed bodies, with certificates
// and no M built (recomputed false, m null).
TEST(Play, AnswersEqualMinksumQueryForTheSamePoses) {
  Server s({kP, kQ});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  const unsigned seed = 20261123;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coordinate(-700, 700);  // in 1/256
  const std::vector<std::string> rotations = {"", "", "64,0,0,0", "60,12,-9,17", "60,12,-9,17", "7,1,2,3"};
  int seen[3] = {0, 0, 0}, turned_seen[3] = {0, 0, 0};
  for (int i = 0; i < 36; ++i) {
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
    // The query on M of the turned operand.
    const std::string turned_p = std::string(kP) + (rot.empty() ? "" : "@rot:" + rot);
    const std::string args = turned_p + " " + kQ + " --translate-p " + t + " --json";
    const CmdRun d = run("query distance " + args);
    ASSERT_EQ(d.status, 0) << args;
    SCOPED_TRACE(args + "\nserver: " + a + "\nquery:  " + d.out);
    const std::string status = json_field(a, "status");
    EXPECT_EQ(status, json_field(d.out, "status"));
    EXPECT_EQ(json_field(a, "squared_distance"), json_field(d.out, "squared_distance"));
    EXPECT_EQ(json_field(a, "distance"), json_field(d.out, "distance"));
    const bool penetrating = status == "\"penetrating\"";
    if (rot.empty()) {
      EXPECT_EQ(json_field(a, "certificate"), "null");
      EXPECT_EQ(json_field(a, "witness"), json_field(d.out, "witness"));
      EXPECT_EQ(json_field(a, "recomputed"), "false");
      EXPECT_NE(json_field(a, "m"), "null");
    } else {
      EXPECT_EQ(json_field(a, "witness"), "null");
      EXPECT_EQ(json_field(a, "m"), "null");
      EXPECT_EQ(json_field(a, "recomputed"), "false") << "M built for a turned pose that is not touching";
      const std::string cert = json_field(a, "certificate");
      EXPECT_EQ(cert, penetrating ? "\"simplex\"" : "\"closest_points\"");
      EXPECT_EQ(json_field(a, "depth_certificate"), penetrating ? "\"nearest_facet\"" : "null");
      ++turned_seen[penetrating ? 2 : status == "\"touching\"" ? 1 : 0];
    }
    if (!penetrating || rot.empty()) {
      // Closest points (unique for these random polytopes) or M's common point.
      EXPECT_EQ(json_field(a, "point_p_exact"), json_field(d.out, "point_p_exact"));
      EXPECT_EQ(json_field(a, "point_q_exact"), json_field(d.out, "point_q_exact"));
      EXPECT_EQ(json_field(a, "direction"), json_field(d.out, "direction"));
    } else {
      // A common point of the turned, overlapping bodies (another one than
      // M's, perhaps): in both, exactly.
      EXPECT_EQ(json_field(a, "point_p_exact"), json_field(a, "point_q_exact"));
      EXPECT_TRUE(point_in(json_field(a, "point_p_exact"), turned_p, t)) << "not in P";
      EXPECT_TRUE(point_in(json_field(a, "point_p_exact"), kQ, "0,0,0")) << "not in Q";
      EXPECT_EQ(json_field(a, "direction"), "[\"0\", \"0\", \"0\"]");
    }
    if (penetrating) {
      const CmdRun p = run("query depth " + args);
      ASSERT_EQ(p.status, 0) << args;
      EXPECT_EQ(json_field(a, "squared_depth"), json_field(p.out, "squared_depth"));
      EXPECT_EQ(json_field(a, "depth"), json_field(p.out, "depth"));
      EXPECT_EQ(json_field(a, "depth_direction"), json_field(p.out, "direction"));
      EXPECT_EQ(json_field(a, "depth_witness"), rot.empty() ? json_field(p.out, "witness") : "null");
      ++seen[2];
    } else {
      EXPECT_EQ(json_field(a, "squared_depth"), "\"0\"");
      EXPECT_EQ(json_field(a, "depth_witness"), "null");
      ++seen[status == "\"touching\"" ? 1 : 0];
    }
  }
  EXPECT_GT(seen[0], 0) << "no separate pose";
  EXPECT_GT(seen[2], 0) << "no penetrating pose";
  EXPECT_GT(turned_seen[0], 0) << "no separate pose of a turned P";
  EXPECT_GT(turned_seen[2], 0) << "no penetrating pose of a turned P";
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// A turned P touching Q exactly (cube on cube, turned by a quarter turn
// about z, face to face): the plane of the touching faces proves it without
// M (certificate "feature_plane", not recomputed), its common point on both
// faces; the next pose, separate, is certified by closest points.
TEST(Play, TurnedTouchingPoseProvedByTheFeaturePlane) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  auto r = post(c, R"({"translate_p": "2,1/2,0", "rotate_p": "1,0,0,1"})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json_field(r->body, "status"), "\"touching\"");
  EXPECT_EQ(json_field(r->body, "squared_distance"), "\"0\"");
  EXPECT_EQ(json_field(r->body, "certificate"), "\"feature_plane\"");
  EXPECT_EQ(json_field(r->body, "recomputed"), "false");
  EXPECT_EQ(json_field(json_field(r->body, "features"), "index"), "null");
  // The common point lies on both faces: x = 1, y in [-1/2, 1], z in [-1, 1].
  std::smatch m;
  const std::string common = json_field(r->body, "point_p_exact");
  ASSERT_TRUE(std::regex_search(common, m, std::regex(R"re(\["([^"]*)", "([^"]*)", "([^"]*)"\])re"))) << common;
  // n/d as a numerator and a positive denominator (small integers here).
  const auto frac = [](const std::string& t) {
    const std::size_t slash = t.find('/');
    return std::make_pair(std::stol(t.substr(0, slash)), slash == std::string::npos ? 1L : std::stol(t.substr(slash + 1)));
  };
  const auto [x, xd] = frac(m[1].str());
  const auto [y, yd] = frac(m[2].str());
  const auto [z, zd] = frac(m[3].str());
  EXPECT_EQ(x, xd) << common;
  EXPECT_TRUE(-yd <= 2 * y && y <= yd) << common;
  EXPECT_TRUE(-zd <= z && z <= zd) << common;
  EXPECT_EQ(json_field(r->body, "point_q_exact"), common);
  auto sep = post(c, R"({"translate_p": "5/2,1/2,0", "rotate_p": "1,0,0,1"})");
  ASSERT_TRUE(sep);
  EXPECT_EQ(json_field(sep->body, "status"), "\"separate\"");
  EXPECT_EQ(json_field(sep->body, "squared_distance"), "\"1/4\"");
  EXPECT_EQ(json_field(sep->body, "certificate"), "\"closest_points\"");
  EXPECT_EQ(json_field(sep->body, "recomputed"), "false");
  // The witness feature of the turned P: the face of its supporting plane,
  // placed (x = 3/2 on every vertex drawn).
  const std::string fp = json_field(json_field(sep->body, "features"), "p");
  EXPECT_NE(fp.find("\"exact\": [\"3/2 "), std::string::npos) << fp;
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

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// One answer read from a raw connection; status 0 when none came whole.
struct RawAnswer {
  int status = 0;
  std::string head, body;
};

// A raw connection to the server: bytes sent as given, answers read as they
// come (for what cpp-httplib's client does not send).
class Raw {
 public:
  explicit Raw(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~Raw() {
    if (fd_ >= 0) ::close(fd_);
  }
  Raw(const Raw&) = delete;
  Raw& operator=(const Raw&) = delete;
  bool connected() const { return connected_; }
  // The server closed (or reset) the connection.
  bool closed() const { return closed_; }

  // Sends `data` whole; false when the connection is closed or the server
  // takes nothing for 10 s.
  bool send(const std::string& data) {
    for (std::size_t at = 0; at < data.size();) {
      pollfd pf{fd_, POLLOUT, 0};
      if (::poll(&pf, 1, 10000) <= 0) return false;
      const ssize_t n = ::send(fd_, data.data() + at, data.size() - at, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
      if (n <= 0) return false;
      at += std::size_t(n);
    }
    return true;
  }

  // Reads what comes for `seconds` or until the connection closes.
  void receive_for(double seconds) {
    const auto t0 = Clock::now();
    while (!closed_ && seconds_since(t0) < seconds) receive(100);
  }

  // The next answer, whole, within `seconds` (status 0 when none came).
  RawAnswer next_answer(double seconds) {
    const auto t0 = Clock::now();
    RawAnswer a;
    while (!take_answer(a) && !closed_ && seconds_since(t0) < seconds) receive(100);
    if (a.status == 0) take_answer(a);
    return a;
  }

  // Sends `data` in pieces while no answer has come, reading at the same
  // time; stops when an answer is whole, the connection closes or `seconds`
  // pass.  *sent: the bytes the server took.
  RawAnswer send_until_answered(const std::string& data, double seconds, std::size_t* sent = nullptr) {
    const auto t0 = Clock::now();
    std::size_t at = 0;
    bool send_failed = false;
    RawAnswer a;
    while (!take_answer(a) && !closed_ && seconds_since(t0) < seconds) {
      const bool more = at < data.size() && !send_failed;
      pollfd pf{fd_, static_cast<short>(POLLIN | (more ? POLLOUT : 0)), 0};
      if (::poll(&pf, 1, 100) <= 0) continue;
      if (pf.revents & (POLLIN | POLLHUP | POLLERR)) {
        receive(0);
      } else if (pf.revents & POLLOUT) {
        const ssize_t n = ::send(fd_, data.data() + at, std::min<std::size_t>(data.size() - at, 65536),
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) at += std::size_t(n);
        else if (n < 0 && errno != EAGAIN && errno != EINTR) send_failed = true;
      }
    }
    if (sent) *sent = at;
    return a;
  }

  // Waits up to `seconds` for the server to close the connection.
  bool closed_within(double seconds) {
    receive_for(seconds);
    return closed_;
  }

 private:
  void receive(int ms) {
    pollfd pf{fd_, POLLIN, 0};
    if (::poll(&pf, 1, ms) <= 0) return;
    char buf[65536];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    if (n > 0) received_.append(buf, std::size_t(n));
    else if (n == 0 || (errno != EAGAIN && errno != EINTR)) closed_ = true;
  }
  // Takes the first answer from what was received when it is whole.
  bool take_answer(RawAnswer& a) {
    const std::size_t end = received_.find("\r\n\r\n");
    if (end == std::string::npos) return false;
    const std::string head = received_.substr(0, end);
    std::string lower = head;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const std::size_t at = lower.find("\r\ncontent-length:");
    const std::size_t length = at == std::string::npos ? 0 : std::stoul(head.substr(at + 17));
    if (received_.size() < end + 4 + length) return false;
    a.status = head.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(head.c_str() + 9) : -1;
    a.head = head;
    a.body = received_.substr(end + 4, length);
    received_.erase(0, end + 4 + length);
    return true;
  }

  int fd_ = -1;
  bool connected_ = false, closed_ = false;
  std::string received_;
};

std::string host_of(const Server& s) { return "127.0.0.1:" + std::to_string(s.port()); }

// A POST of `body` to /query with the headers `extra` (each ending in CRLF).
std::string raw_post(const Server& s, const std::string& body, const std::string& extra) {
  return "POST /query HTTP/1.1\r\nHost: " + host_of(s) + "\r\n" + extra +
         "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

// One line: the body is text ending in its only newline.
void expect_one_line(const RawAnswer& a) {
  ASSERT_FALSE(a.body.empty()) << a.head;
  EXPECT_EQ(a.body.find('\n'), a.body.size() - 1) << "not one line: " << a.body.substr(0, 300);
}

// A page whose DNS name is made to mean 127.0.0.1 (DNS rebinding) sends its
// own name as Host: the server answers only to its own address, so such a
// page reads neither the page (the operands' names and exact coordinates)
// nor an answer.
TEST(Play, ForeignHostRefused) {
  Server s({"cube", "octahedron"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string port = std::to_string(s.port());
  const std::string other_port = std::to_string(s.port() == 1 ? 2 : s.port() - 1);
  const std::vector<std::string> requests = {
      "GET / HTTP/1.1\r\nHost: rebound.example:" + port + "\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: rebound.example\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + other_port + "\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\nHost: rebound.example:" + port + "\r\n\r\n",
      "GET / HTTP/1.0\r\n\r\n",
      "POST /query HTTP/1.1\r\nHost: rebound.example:" + port +
          "\r\nContent-Type: application/json\r\nContent-Length: 24\r\n\r\n{\"translate_p\": \"4,0,0\"}",
  };
  for (const auto& request : requests) {
    SCOPED_TRACE(request);
    Raw r(s.port());
    ASSERT_TRUE(r.connected());
    ASSERT_TRUE(r.send(request));
    const RawAnswer a = r.next_answer(10);
    EXPECT_EQ(a.status, 403) << a.head;
    expect_one_line(a);
    EXPECT_NE(a.body.find("the Host header must be 127.0.0.1:" + port), std::string::npos) << a.body;
    EXPECT_EQ(a.body.find("solids"), std::string::npos);
    EXPECT_EQ(a.body.find("squared_distance"), std::string::npos);
  }
  // Its own address is answered.
  Raw r(s.port());
  ASSERT_TRUE(r.send("GET / HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\n\r\n"));
  const RawAnswer page = r.next_answer(10);
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("\"kind\": \"play\""), std::string::npos);
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// Any page can send a "simple" cross-origin POST (text/plain, no preflight):
// the server refuses a POST from another origin or site and one that is not
// application/json, before the body reaches the session (no answer of the
// session's: none of its keys in the refusal); the page's own request with
// the same body is answered, P turned on the placed bodies.
TEST(Play, CrossOriginTextPlainPostRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string body = R"({"translate_p": "4,0,0", "rotate_p": "2,1,0,0"})";
  const std::string own = "http://" + host_of(s);
  const std::vector<std::pair<std::string, int>> refused = {
      {"Origin: http://evil.example\r\nContent-Type: text/plain\r\n", 403},
      {"Origin: http://evil.example\r\nContent-Type: application/json\r\n", 403},
      {"Origin: null\r\nContent-Type: application/json\r\n", 403},
      {"Origin: " + own + "\r\nSec-Fetch-Site: cross-site\r\nContent-Type: application/json\r\n", 403},
      {"Sec-Fetch-Site: same-site\r\nContent-Type: application/json\r\n", 403},
      {"Content-Type: text/plain\r\n", 415},
      {"Origin: " + own + "\r\nContent-Type: text/plain;charset=UTF-8\r\n", 415},
      {"Content-Type: application/x-www-form-urlencoded\r\n", 415},
      {"", 415},
  };
  for (const auto& [headers, status] : refused) {
    SCOPED_TRACE(headers);
    Raw r(s.port());
    ASSERT_TRUE(r.send(raw_post(s, body, headers)));
    const RawAnswer a = r.next_answer(10);
    EXPECT_EQ(a.status, status) << a.head;
    expect_one_line(a);
    EXPECT_EQ(a.body.find("recomputed"), std::string::npos) << a.body;
  }
  // The page's own request: same origin, JSON.
  httplib::Client c("127.0.0.1", s.port());
  const httplib::Headers page_headers = {{"Origin", own}, {"Sec-Fetch-Site", "same-origin"}};
  auto r = c.Post("/query", page_headers, body, "application/json; charset=utf-8");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json_field(r->body, "status"), "\"separate\"");
  EXPECT_EQ(json_field(r->body, "certificate"), "\"closest_points\"");
  EXPECT_EQ(json_field(r->body, "recomputed"), "false");
  EXPECT_EQ(r->get_header_value("Cross-Origin-Resource-Policy"), "same-origin");
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// One chunk of a chunked body.
std::string chunk(const std::string& data) {
  char size[32];
  std::snprintf(size, sizeof size, "%zx\r\n", data.size());
  return size + data + "\r\n";
}

// A chunked body is held to the same 4096 bytes as any body: a chunk that
// announces 64 MiB, or many small chunks, get 413 once 4096 bytes are
// exceeded, and the connection is closed; a small chunked body is answered.
TEST(Play, ChunkedBodyBeyondLimitRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string head = "POST /query HTTP/1.1\r\nHost: " + host_of(s) +
                           "\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n";
  {
    Raw r(s.port());
    ASSERT_TRUE(r.send(head + chunk(R"({"translate_p")") + chunk(R"(: "4,0,0"})") + "0\r\n\r\n"));
    const RawAnswer a = r.next_answer(10);
    ASSERT_EQ(a.status, 200) << a.head << a.body;
    EXPECT_EQ(json_field(a.body, "squared_distance"), "\"4\"");
  }
  {
    SCOPED_TRACE("one chunk of 64 MiB");
    Raw r(s.port());
    const std::string data = head + "4000000\r\n{\"translate_p\": \"" + std::string(8192, '1');
    const RawAnswer a = r.send_until_answered(data, 10);
    EXPECT_EQ(a.status, 413) << a.head;
    expect_one_line(a);
    EXPECT_TRUE(r.closed_within(5));
  }
  {
    SCOPED_TRACE("many chunks of 100 bytes");
    Raw r(s.port());
    std::string data = head + chunk(R"({"translate_p": ")");
    for (int i = 0; i < 10000; ++i) data += chunk(std::string(100, '1'));
    const RawAnswer a = r.send_until_answered(data, 10);
    EXPECT_EQ(a.status, 413) << a.head;
    expect_one_line(a);
    EXPECT_TRUE(r.closed_within(5));
  }
  httplib::Client c("127.0.0.1", s.port());
  auto good = post(c, R"({"translate_p": "4,0,0"})");
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 200);
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// A header line, or the request line, that never ends: refused (431) once
// the request line and headers pass 16 KiB, not read on.
TEST(Play, HugeHeaderLineRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string endless(std::size_t(1) << 26, 'a');  // 64 MiB, no end of line
  for (const std::string& start : {"GET / HTTP/1.1\r\nHost: " + host_of(s) + "\r\nX-Big: ", std::string("GET /")}) {
    SCOPED_TRACE(start);
    Raw r(s.port());
    std::size_t sent = 0;
    const RawAnswer a = r.send_until_answered(start + endless, 10, &sent);
    EXPECT_EQ(a.status, 431) << a.head;
    expect_one_line(a);
    EXPECT_NE(a.body.find("at most 16384 bytes"), std::string::npos) << a.body;
    EXPECT_TRUE(r.closed_within(5));
    EXPECT_LT(sent, endless.size());
  }
  httplib::Client c("127.0.0.1", s.port());
  auto good = post(c, R"({"translate_p": "4,0,0"})");
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 200);
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// At most 64 header lines: 64 are answered, 65 get 431.
TEST(Play, TooManyHeaderLinesRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  auto request = [&](int lines) {
    std::string r = "GET / HTTP/1.1\r\nHost: " + host_of(s) + "\r\n";
    for (int i = 1; i < lines; ++i) r += "X-Line-" + std::to_string(i) + ": 1\r\n";
    return r + "\r\n";
  };
  {
    Raw r(s.port());
    ASSERT_TRUE(r.send(request(64)));
    EXPECT_EQ(r.next_answer(10).status, 200);
  }
  Raw r(s.port());
  ASSERT_TRUE(r.send(request(65)));
  const RawAnswer a = r.next_answer(10);
  EXPECT_EQ(a.status, 431) << a.head;
  expect_one_line(a);
  EXPECT_NE(a.body.find("too many header lines (at most 64)"), std::string::npos) << a.body;
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// Five clients send a header a byte a second for 20 s: a sixth is answered
// at once, and each slow one is cut off with 408 after 10 s.
TEST(Play, SlowClientsDoNotBlockOthers) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  struct Slow {
    int status = 0;
    double closed_after = -1;  // seconds; -1: still open after 20 s
  };
  std::vector<Slow> slow(5);
  std::vector<std::thread> threads;
  for (auto& out : slow) {
    threads.emplace_back([&s, &out] {
      const auto t0 = Clock::now();
      Raw r(s.port());
      if (!r.send("GET / HTTP/1.1\r\nHost: " + host_of(s) + "\r\nX-Slow: ")) return;
      for (int i = 0; i < 20 && !r.closed(); ++i) {
        r.send("a");
        r.receive_for(1.0);
      }
      if (r.closed()) out.closed_after = seconds_since(t0);
      out.status = r.next_answer(0).status;
    });
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  httplib::Client c("127.0.0.1", s.port());
  c.set_connection_timeout(5);
  c.set_read_timeout(5);
  c.set_write_timeout(5);
  const auto t0 = Clock::now();
  auto good = post(c, R"({"translate_p": "4,0,0"})");
  const double answered_after = seconds_since(t0);
  for (auto& t : threads) t.join();
  ASSERT_TRUE(good) << "no answer while slow clients were connected";
  EXPECT_EQ(good->status, 200);
  EXPECT_LT(answered_after, 5.0);
  for (const Slow& x : slow) {
    EXPECT_EQ(x.status, 408);
    EXPECT_GE(x.closed_after, 9.0);
    EXPECT_LT(x.closed_after, 16.0);
  }
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// Requests sent together, in one packet, are each answered, in order.
TEST(Play, PipelinedRequestsEachAnswered) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  const std::string json = "Content-Type: application/json\r\n";
  Raw r(s.port());
  ASSERT_TRUE(r.send(raw_post(s, R"({"translate_p": "4,0,0"})", json) +
                     raw_post(s, R"({"translate_p": "1/2,0,0"})", json) +
                     "GET /favicon.ico HTTP/1.1\r\nHost: " + host_of(s) + "\r\n\r\n"));
  const RawAnswer first = r.next_answer(10);
  const RawAnswer second = r.next_answer(10);
  const RawAnswer third = r.next_answer(10);
  ASSERT_EQ(first.status, 200) << first.head;
  EXPECT_EQ(json_field(first.body, "status"), "\"separate\"");
  EXPECT_EQ(json_field(first.body, "squared_distance"), "\"4\"");
  ASSERT_EQ(second.status, 200) << second.head;
  EXPECT_EQ(json_field(second.body, "status"), "\"penetrating\"");
  EXPECT_EQ(json_field(second.body, "squared_depth"), "\"9/4\"");
  EXPECT_EQ(third.status, 204) << third.head;
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// A body that is a JSON object followed by a NUL byte and more is not a
// JSON object: 400 and one line.
TEST(Play, BodyWithNulAndGarbageRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  httplib::Client c("127.0.0.1", s.port());
  const std::string body = std::string(R"({"translate_p": "4,0,0"})") + '\0' + "garbage";
  auto r = post(c, body);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  ASSERT_FALSE(r->body.empty());
  EXPECT_EQ(r->body.find('\n'), r->body.size() - 1) << "not one line: " << r->body;
  EXPECT_EQ(r->body.find("squared_distance"), std::string::npos) << r->body;
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

// At most 32 connections at a time: a 33rd is answered 503 and closed; once
// the others close, a new one is served.
TEST(Play, ConnectionsBeyondTheLimitRefused) {
  Server s({"cube", "cube"});
  ASSERT_GT(s.port(), 0) << "first line: " << s.url();
  std::vector<std::unique_ptr<Raw>> held;
  for (int i = 0; i < 32; ++i) {
    held.push_back(std::make_unique<Raw>(s.port()));
    ASSERT_TRUE(held.back()->connected());
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  {
    Raw extra(s.port());
    ASSERT_TRUE(extra.connected());
    const RawAnswer a = extra.next_answer(4);
    EXPECT_EQ(a.status, 503) << a.head;
    expect_one_line(a);
    EXPECT_TRUE(extra.closed_within(4));
  }
  held.clear();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  Raw r(s.port());
  ASSERT_TRUE(r.send("GET /favicon.ico HTTP/1.1\r\nHost: " + host_of(s) + "\r\n\r\n"));
  EXPECT_EQ(r.next_answer(10).status, 204);
  EXPECT_EQ(s.stop(SIGTERM), 0);
}

}  // namespace
