// The server of 'minksum play P Q' (run_play_server, in the executable
// minksum-play, which the command runs: cli/cmd_play.cpp): the interactive
// proximity application.  A page served on
// the loopback interface shows P and Q; the user drags and turns P, and the
// page asks this server, on every move, for the exact state, distance or
// penetration depth and witnesses (the library's TranslationalObstacle, the
// same answers as 'minksum query').  docs/viewer.md describes the page and
// the protocol.
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>

#include <httplib.h>

#include "mesh/support.hpp"  // feature_vertices

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "../common.hpp"
#include "../json_object.hpp"
#include "../page.hpp"
#include "../pose.hpp"
#include "../play.hpp"
#include "../proximity_json.hpp"

extern char** environ;

namespace minksum::cli {

namespace {

constexpr std::size_t kMaxBody = 4096;
// Bound on the integers of a rotation: M's coordinates grow with them.
const Integer kMaxQuaternion = 1000000;

// A header value in lower case without the blanks around it.
std::string lower_trimmed(std::string t) {
  t.erase(0, t.find_first_not_of(" \t"));
  t.erase(t.find_last_not_of(" \t") + 1);
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return t;
}

// The media type of a Content-Type value, lower case, without parameters.
std::string media_type(const std::string& content_type) {
  return lower_trimmed(content_type.substr(0, content_type.find(';')));
}

// A client's text in a message: printable and not too long.
std::string quoted(const std::string& s) {
  return "'" + printable(s.size() > 100 ? s.substr(0, 100) + "..." : s) + "'";
}

// The feature of a polytope as the page draws it: its vertices' coordinates.
std::string feature_points_json(const ConvexPolytope& p, const Feature& f, const Point3& shift) {
  std::vector<Index> vs;
  if (f.index != kNoIndex) feature_vertices(p, f, vs);
  std::string xyz, exact;
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const Point3 x = p.point(vs[i]) + shift;
    xyz += (i ? ", " : "") + json_number(to_double(x.x)) + ", " + json_number(to_double(x.y)) + ", " +
           json_number(to_double(x.z));
    exact += (i ? ", \"" : "\"") + format_exact(x.x) + " " + format_exact(x.y) + " " + format_exact(x.z) + "\"";
  }
  return std::string("{\"type\": \"") + feature_type(f.dim) + "\", \"index\": " + std::to_string(f.index) +
         ", \"points\": [" + xyz + "], \"exact\": [" + exact + "]}";
}

std::string quaternion_text(const Quaternion& q) {
  return q[0].get_str() + "," + q[1].get_str() + "," + q[2].get_str() + "," + q[3].get_str();
}

// A request the server refuses (HTTP 400 with the message).
struct BadRequest : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct QueryPose {
  Point3 u, w;
  std::optional<Quaternion> rp;
};

QueryPose parse_query(const std::string& body) {
  JsonObjectParser parser(body, "request", "body");
  QueryPose pose{Point3(Rational(0), Rational(0), Rational(0)), Point3(Rational(0), Rational(0), Rational(0)), {}};
  bool has_u = false;
  std::vector<JsonMember> members;
  try {
    members = parser.object();
  } catch (const InputError& e) {
    throw BadRequest(std::string("bad JSON: ") + e.what());
  }
  for (const auto& [key, value, is_string] : members) {
    std::string why;
    if (!is_string) throw BadRequest("\"" + key + "\" must be a string");
    if (key == "translate_p" || key == "translate_q") {
      auto v = parse_vector(value, &why);
      if (!v) throw BadRequest(key + ": " + why);
      (key == "translate_p" ? pose.u : pose.w) = *v;
      has_u = has_u || key == "translate_p";
    } else if (key == "rotate_p") {
      auto q = parse_quaternion(value, &why);
      if (!q) throw BadRequest(key + ": " + why);
      for (const Integer& c : *q)
        if (abs(c) > kMaxQuaternion) throw BadRequest("rotate_p: each integer is at most 10^6 in magnitude");
      pose.rp = *q;
    } else {
      throw BadRequest("unknown key \"" + printable(key) + "\" (translate_p, rotate_p, translate_q)");
    }
  }
  if (!has_u) throw BadRequest("missing \"translate_p\"");
  return pose;
}

// The state of the session: P and Q as given, M for the current orientation
// of P.  Requests are answered one at a time.
class Session {
 public:
  Session(ConvexPolytope p, ConvexPolytope q, Method method)
      : p0_(std::move(p)), q0_(std::move(q)), obstacle_(p0_, q0_, method) {}

  std::string answer(const QueryPose& pose) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto t0 = std::chrono::steady_clock::now();
    const bool recompute = pose.rp != rp_;
    if (recompute) {
      obstacle_.set_p(pose.rp ? rotated(p0_, *pose.rp) : p0_);
      rp_ = pose.rp;
    }
    const DistanceResult d = obstacle_.distance(pose.u, pose.w);
    std::optional<DepthResult> depth;
    if (d.status == ContactStatus::penetrating) depth = obstacle_.penetration_depth(pose.u, pose.w);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The features drawn: the distance's witness, or the depth's when the bodies overlap.
    const Witness& w = depth ? depth->witness : d.witness;
    const Point3 zero(Rational(0), Rational(0), Rational(0));
    std::string o = "{\"status\": \"" + std::string(contact_status_name(d.status)) + "\", \"pose\": {\"translate_p\": " +
                    exact_vector_json(pose.u) + ", \"rotate_p\": " +
                    (pose.rp ? "\"" + quaternion_text(*pose.rp) + "\"" : std::string("null")) +
                    ", \"translate_q\": " + exact_vector_json(pose.w) + "}";
    o += ", \"squared_distance\": \"" + format_exact(d.squared_distance()) + "\", \"distance\": " +
         json_number(d.distance());
    o += ", \"squared_depth\": \"" + (depth ? format_exact(depth->squared_depth()) : std::string("0")) +
         "\", \"depth\": " + json_number(depth ? depth->depth() : 0.0);
    o += ", \"point_p\": " + double_vector_json(d.point_p()) + ", \"point_p_exact\": " + exact_vector_json(d.point_p());
    o += ", \"point_q\": " + double_vector_json(d.point_q()) + ", \"point_q_exact\": " + exact_vector_json(d.point_q());
    o += ", \"direction\": " + exact_vector_json(d.direction());
    o += ", \"depth_direction\": " + exact_vector_json(depth ? depth->direction() : zero) +
         ", \"depth_direction_double\": " + double_vector_json(depth ? depth->direction() : zero);
    o += ", \"witness\": " + witness_json(d.witness);
    o += ", \"depth_witness\": " + (depth ? witness_json(depth->witness) : std::string("null"));
    o += ", \"features\": {\"p\": " + feature_points_json(obstacle_.p(), w.p, pose.u) +
         ", \"q\": " + feature_points_json(obstacle_.q(), w.q, pose.w) + "}";
    o += ", \"m\": {" + counts_json(obstacle_.obstacle()) + "}, \"recomputed\": " + (recompute ? "true" : "false");
    o += ", \"seconds\": " + json_number(seconds) + "}";
    return o;
  }

 private:
  std::mutex mutex_;
  ConvexPolytope p0_, q0_;
  TranslationalObstacle obstacle_;
  std::optional<Quaternion> rp_;
};

// Opens the URL with xdg-open when there is one; says so otherwise.
void open_in_browser(const std::string& url) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  std::string program = "xdg-open";
  char* args[] = {program.data(), const_cast<char*>(url.c_str()), nullptr};
  // The browser opener gets the signals as usual (this process blocks
  // SIGINT and SIGTERM and ignores SIGPIPE).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid;
  const int err = posix_spawnp(&pid, "xdg-open", &actions, &attr, args, environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) std::cerr << "minksum play: no xdg-open to open a browser; open " << url << " in one\n";
  // The child is reaped when the server stops (it outlives nothing).
}

}  // namespace

int run_play_server(const PlayOptions& o) {
  // SIGINT and SIGTERM are taken by one thread (sigwait), which stops the
  // server; every other thread has them blocked, including the worker
  // threads a computation of M may start, so they are blocked from here on
  // (a signal that comes while the operands load stops the server once it runs).
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  const ConvexPolytope p = load_operand(o.p, o.hull, nullptr);
  const ConvexPolytope q = load_operand(o.q, o.hull, nullptr);
  Session session(p, q, o.method);

  const std::string title = o.p + " against " + o.q;
  std::string data = "{\"kind\": \"play\", \"title\": " + json_string(title) + ", \"solids\": [";
  append_solid_json(data, p, o.p, "p");
  data += ", ";
  append_solid_json(data, q, o.q, "q");
  data += "]}";
  const std::string html = page_html(title, data, true);

  // A browser that closes a connection must not kill the server.
  signal(SIGPIPE, SIG_IGN);

  httplib::Server server;
  server.new_task_queue = [] { return new httplib::ThreadPool(4); };
  server.set_payload_max_length(kMaxBody);
  server.set_read_timeout(5);
  server.set_write_timeout(5);
  server.set_keep_alive_timeout(2);
  server.set_tcp_nodelay(true);
  // SO_REUSEADDR only: cpp-httplib's default also sets SO_REUSEPORT, with
  // which a second server could bind the same port and share its connections.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });

  const int port = o.port;
  const int bound = port == 0 ? server.bind_to_any_port("127.0.0.1") : (server.bind_to_port("127.0.0.1", port) ? port : -1);
  if (bound < 0)
    throw OutputError("cannot listen on 127.0.0.1:" + std::to_string(port) + " (the port is taken or not allowed)");
  // The only name the server answers to (against DNS rebinding: a page whose
  // name comes to mean 127.0.0.1 sends its own name as Host) and the only
  // origin whose requests it takes (against other pages' requests).
  const std::string authority = "127.0.0.1:" + std::to_string(bound);
  const std::string origin = "http://" + authority;

  auto fail = [](httplib::Response& res, int status, const std::string& message) {
    res.status = status;
    res.set_content(printable(message) + "\n", "text/plain; charset=utf-8");
  };
  using httplib::Server;
  server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
    const std::string host = req.get_header_value("Host");
    if (req.get_header_value_count("Host") != 1 || host != authority) {
      fail(res, 403, "refused: the Host header must be " + authority + ", this server's address (got " +
                         (req.has_header("Host") ? quoted(host) : std::string("none")) + ")");
      return Server::HandlerResponse::Handled;
    }
    if (req.has_header("Origin") &&
        (req.get_header_value_count("Origin") != 1 || req.get_header_value("Origin") != origin)) {
      fail(res, 403, "refused: a request from another origin, " + quoted(req.get_header_value("Origin")) +
                         " (this server takes requests from " + origin + " only)");
      return Server::HandlerResponse::Handled;
    }
    if (req.method != "POST") return Server::HandlerResponse::Unhandled;
    const std::string site = req.get_header_value("Sec-Fetch-Site");
    if (req.has_header("Sec-Fetch-Site") && site != "same-origin") {
      fail(res, 403, "refused: a POST from another site (Sec-Fetch-Site: " + quoted(site) + ")");
      return Server::HandlerResponse::Handled;
    }
    const std::string type = req.get_header_value("Content-Type");
    if (media_type(type) != "application/json") {
      fail(res, 415, "a POST takes Content-Type: application/json (got " +
                         (req.has_header("Content-Type") ? quoted(type) : std::string("none")) + ")");
      return Server::HandlerResponse::Handled;
    }
    if (req.has_header("Content-Encoding")) {
      fail(res, 415, "a POST body is taken as sent, without Content-Encoding (got " +
                         quoted(req.get_header_value("Content-Encoding")) + ")");
      return Server::HandlerResponse::Handled;
    }
    const bool chunked = req.has_header("Transfer-Encoding");
    if (chunked && (req.get_header_value_count("Transfer-Encoding") != 1 ||
                    lower_trimmed(req.get_header_value("Transfer-Encoding")) != "chunked" ||
                    req.has_header("Content-Length"))) {
      fail(res, 400, "Transfer-Encoding: only chunked, alone and without Content-Length");
      return Server::HandlerResponse::Handled;
    }
    if (!chunked && req.get_header_value_count("Content-Length") != 1) {
      fail(res, 411, "a POST needs one Content-Length header (or Transfer-Encoding: chunked)");
      return Server::HandlerResponse::Handled;
    }
    return Server::HandlerResponse::Unhandled;
  });
  // Every answer: not to be read by other origins' pages; an error answer
  // asks the client to close the connection.
  server.set_post_routing_handler([&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cross-Origin-Resource-Policy", "same-origin");
    res.set_header("X-Content-Type-Options", "nosniff");
    if (res.status >= 400) {
      res.headers.erase("Keep-Alive");
      if (!res.has_header("Connection")) res.set_header("Connection", "close");
    }
  });
  server.Get("/", [&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(html, "text/html; charset=utf-8");
  });
  server.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  server.Post("/query", [&](const httplib::Request& req, httplib::Response& res) {
    try {
      res.set_header("Cache-Control", "no-store");
      res.set_content(session.answer(parse_query(req.body)), "application/json");
    } catch (const BadRequest& e) {
      fail(res, 400, e.what());
    } catch (const std::bad_alloc&) {
      fail(res, 500, "out of memory");
    } catch (const std::exception& e) {
      fail(res, 500, std::string("internal error: ") + e.what());
    }
  });
  server.set_exception_handler([&](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    fail(res, 500, "internal error");
  });
  server.set_error_handler([&](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 404) fail(res, 404, "no such page: " + req.method + " " + req.path + " (GET /, POST /query)");
    else if (res.status == 413) fail(res, 413, "request too large (at most " + std::to_string(kMaxBody) + " bytes)");
    else fail(res, res.status, "bad request");
  });

  const std::string url = "http://127.0.0.1:" + std::to_string(bound) + "/";
  std::cout << url << std::endl;
  check_stdout();
  std::cerr << "minksum play: " << printable(o.p) << " against " << printable(o.q)
            << " at " << url << " (Ctrl-C stops)" << std::endl;
  if (o.open) open_in_browser(url);

  std::atomic<bool> listening_done{false}, stop_requested{false};
  std::thread stopper([&] {
    int sig = 0;
    sigwait(&stop_signals, &sig);
    stop_requested = true;
    // stop() before the server runs would be lost: repeat until it returns.
    while (!listening_done) {
      server.stop();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const bool ok = server.listen_after_bind();
  listening_done = true;
  if (!stop_requested) pthread_kill(stopper.native_handle(), SIGTERM);
  stopper.join();
  while (waitpid(-1, nullptr, WNOHANG) > 0) {
  }
  if (!ok && !stop_requested) throw OutputError("the server on " + url + " stopped: " + std::strerror(errno));
  return 0;
}

}  // namespace minksum::cli
