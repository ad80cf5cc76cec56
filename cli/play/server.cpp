// The server of 'minksum play P Q' (run_play_server, in the executable
// minksum-play, which the command runs: cli/cmd_play.cpp): the interactive
// proximity application.  A page served on
// the loopback interface shows P and Q; the user drags and turns P, and the
// page asks this server, on every move, for the exact state, distance or
// penetration depth and witnesses (the same answers as 'minksum query': on
// M = P ⊕ (−Q) built once for P as given, and on the placed bodies when P
// is turned, without building M for the rotation).  docs/viewer.md describes the page and
// the protocol.
#include <minksum/feature.hpp>
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>
#include <minksum/rigid_proximity.hpp>
#include <minksum/transform.hpp>

#include <httplib.h>


#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <list>
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

// A request body, decoded (chunked or not), in bytes.
constexpr std::size_t kMaxBody = 4096;
// Bound on the integers of a rotation: M's coordinates grow with them.
const Integer kMaxQuaternion = 1000000;

// The limits of a request as a client sends it.  cpp-httplib 0.11 reads a
// header line or a chunked body whatever its length, gives each read (not
// each request) its timeout and forgets, between two requests of one
// connection, what it received beyond the first: the connection below
// (Connection, PlayServer) reads the socket itself and enforces these.
constexpr std::size_t kMaxHead = 16384;        // request line and headers, bytes as sent
constexpr std::size_t kMaxHeaderLines = 64;    // header lines
constexpr std::size_t kMaxBodySent = 16384;    // the body as sent, chunked framing included
constexpr int kRequestSeconds = 10;            // from a request's first byte to its last
constexpr int kIdleSeconds = 5;                // a connection waits this long for a request
constexpr int kWriteSeconds = 5;               // an answer must be taken within this
constexpr std::size_t kMaxConnections = 32;    // at a time; each has its own thread
constexpr std::size_t kMaxRequestsPerConnection = 100;

using Clock = std::chrono::steady_clock;

// Why a request was cut off while it was read.
enum class Cutoff { none, head_too_large, too_many_header_lines, body_too_large, too_slow, stopping };

// The answer to a request cut off (status and line), or status 0.
std::pair<int, std::string> cutoff_answer(Cutoff c) {
  switch (c) {
    case Cutoff::head_too_large:
      return {431, "request line and headers too large (at most " + std::to_string(kMaxHead) + " bytes)"};
    case Cutoff::too_many_header_lines:
      return {431, "too many header lines (at most " + std::to_string(kMaxHeaderLines) + ")"};
    case Cutoff::body_too_large:
      return {413, "request body too large (at most " + std::to_string(kMaxBody) + " bytes, " +
                       std::to_string(kMaxBodySent) + " as sent)"};
    case Cutoff::too_slow:
      return {408, "request not received whole within " + std::to_string(kRequestSeconds) + " s"};
    default:
      return {0, ""};
  }
}

const char* reason_phrase(int status) {
  switch (status) {
    case 408: return "Request Timeout";
    case 431: return "Request Header Fields Too Large";
    case 503: return "Service Unavailable";
    default: return "Error";
  }
}

// One client connection as cpp-httplib reads and writes it: the socket and
// what was received but not yet read (so that requests sent together, in one
// packet, are each answered), with the limits of the request being read.
class Connection final : public httplib::Stream {
 public:
  Connection(socket_t sock, const std::atomic<socket_t>& listener) : sock_(sock), listener_(listener) {}

  // Waits up to `seconds` for the first byte of a request (none when one
  // came with the previous request); false when none comes, the client
  // closed the connection or the server stops.
  bool wait_for_request(time_t seconds) {
    if (off_ < end_) return true;
    return wait(POLLIN, Clock::now() + std::chrono::seconds(seconds));
  }
  // A new request: its limits start.
  void begin_request() {
    deadline_ = Clock::now() + std::chrono::seconds(kRequestSeconds);
    in_body_ = false;
    taken_ = lines_ = written_ = 0;
    cutoff_ = Cutoff::none;
  }
  // The request line and headers are read: the body's limit from here.
  void begin_body() {
    in_body_ = true;
    taken_ = 0;
  }
  Cutoff cutoff() const { return cutoff_; }
  std::size_t written() const { return written_; }
  void close_after_answer() { close_ = true; }
  bool closing() const { return close_; }
  bool stopping() const { return listener_ == INVALID_SOCKET; }

  bool is_readable() const override { return off_ < end_ || wait(POLLIN, deadline_); }
  bool is_writable() const override { return wait(POLLOUT, Clock::now() + std::chrono::seconds(kWriteSeconds)); }

  ssize_t read(char* ptr, std::size_t size) override {
    if (size == 0) return 0;
    const std::size_t limit = in_body_ ? kMaxBodySent : kMaxHead;
    if (taken_ >= limit) return cut(in_body_ ? Cutoff::body_too_large : Cutoff::head_too_large);
    if (off_ == end_) {
      if (!wait(POLLIN, deadline_)) return cut(stopping() ? Cutoff::stopping : Cutoff::too_slow);
      ssize_t n;
      do n = ::recv(sock_, buffer_, sizeof buffer_, 0);
      while (n < 0 && errno == EINTR);
      if (n <= 0) return n;
      off_ = 0;
      end_ = std::size_t(n);
    }
    const std::size_t n = std::min({size, end_ - off_, limit - taken_});
    if (!in_body_) {
      // The request line, the header lines and the blank line that ends them.
      const std::size_t lines = lines_ + std::size_t(std::count(buffer_ + off_, buffer_ + off_ + n, '\n'));
      if (lines > kMaxHeaderLines + 2) return cut(Cutoff::too_many_header_lines);
      lines_ = lines;
    }
    std::memcpy(ptr, buffer_ + off_, n);
    off_ += n;
    taken_ += n;
    return ssize_t(n);
  }

  using httplib::Stream::write;
  ssize_t write(const char* ptr, std::size_t size) override {
    if (!is_writable()) return -1;
    ssize_t n;
    do n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    while (n < 0 && errno == EINTR);
    if (n > 0) written_ += std::size_t(n);
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(true, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(false, ip, port); }
  socket_t socket() const override { return sock_; }

  // Answers with `status` and one line, and closes after it (for what
  // cpp-httplib does not answer: a request cut off in its request line, a
  // connection beyond the limit).
  void refuse(int status, const std::string& line) {
    const std::string body = line + "\n";
    const std::string text = "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) +
                             "\r\nContent-Type: text/plain; charset=utf-8\r\nContent-Length: " +
                             std::to_string(body.size()) + "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n" +
                             body;
    for (std::size_t at = 0; at < text.size();) {
      const ssize_t n = write(text.data() + at, text.size() - at);
      if (n <= 0) break;
      at += std::size_t(n);
    }
    close_ = true;
  }

  // Ends the connection.  What the client still sends is read and dropped
  // for up to `linger_seconds` first: closing a socket with unread data
  // resets the connection, and the client could lose the answer.
  void finish(int linger_seconds) {
    ::shutdown(sock_, SHUT_WR);
    const auto until = Clock::now() + std::chrono::seconds(linger_seconds);
    for (std::size_t dropped = 0; dropped < (std::size_t(1) << 20);) {
      const ssize_t n = ::recv(sock_, buffer_, sizeof buffer_, MSG_DONTWAIT);
      if (n > 0) {
        dropped += std::size_t(n);
      } else if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) || !wait(POLLIN, until)) {
        break;
      }
    }
    ::close(sock_);
  }

 private:
  ssize_t cut(Cutoff why) {
    cutoff_ = why;
    return -1;
  }
  // Polls for `events` until `deadline`, in slices of 100 ms so that a
  // server that stops is noticed.
  bool wait(short events, Clock::time_point deadline) const {
    for (;;) {
      if (stopping()) return false;
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) return false;
      pollfd pf{sock_, events, 0};
      const int r = ::poll(&pf, 1, int(std::min<long long>(left, 100)));
      if (r > 0) return true;  // ready, or closed or failed: recv and send say which
      if (r < 0 && errno != EINTR) return false;
    }
  }
  void address(bool remote, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t len = sizeof a;
    auto* sa = reinterpret_cast<sockaddr*>(&a);
    if ((remote ? ::getpeername(sock_, sa, &len) : ::getsockname(sock_, sa, &len)) != 0) return;
    char text[INET6_ADDRSTRLEN] = "";
    if (a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
      port = ntohs(v4->sin_port);
    } else if (a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
      port = ntohs(v6->sin6_port);
    }
    ip = text;
  }

  socket_t sock_;
  const std::atomic<socket_t>& listener_;
  char buffer_[4096];
  std::size_t off_ = 0, end_ = 0;  // the received bytes not yet read: buffer_[off_, end_)
  Clock::time_point deadline_ = Clock::now();
  bool in_body_ = false, close_ = false;
  std::size_t taken_ = 0, lines_ = 0, written_ = 0;
  Cutoff cutoff_ = Cutoff::none;
};

// The connection the current thread serves (the handlers read its limits).
thread_local Connection* t_connection = nullptr;
// Set while a connection beyond kMaxConnections is refused.
thread_local bool t_over_limit = false;

// Each connection on a thread of its own, at most kMaxConnections at a time,
// so that a client that sends slowly holds only its own; a connection beyond
// that is answered 503 at once and closed.
class ConnectionThreads final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override {
    reap();
    if (workers_.size() < kMaxConnections) {
      try {
        Worker& w = workers_.emplace_back();
        std::atomic<bool>& done = w.done;
        w.thread = std::thread([fn, &done] {
          fn();
          done = true;
        });
        return;
      } catch (const std::system_error&) {  // no thread: refused as beyond the limit
        workers_.pop_back();
      }
    }
    t_over_limit = true;
    fn();
    t_over_limit = false;
  }
  void shutdown() override {
    for (auto& w : workers_) w.thread.join();
    workers_.clear();
  }

 private:
  struct Worker {
    std::thread thread;
    std::atomic<bool> done{false};
  };
  void reap() {
    for (auto it = workers_.begin(); it != workers_.end();) {
      if (it->done) {
        it->thread.join();
        it = workers_.erase(it);
      } else {
        ++it;
      }
    }
  }
  std::list<Worker> workers_;  // used by the listening thread only
};

// cpp-httplib's server with connections as above: each request of a
// connection is read from the same Connection, within its limits.
class PlayServer final : public httplib::Server {
 public:
  // cpp-httplib listens with a backlog of 5: connections that come together
  // beyond it wait a second for their SYN to be sent again.
  bool widen_backlog(int n) { return ::listen(svr_sock_, n) == 0; }

 private:
  bool process_and_close_socket(socket_t sock) override {
    Connection c(sock, svr_sock_);
    if (t_over_limit) {
      c.refuse(503, "too many connections (at most " + std::to_string(kMaxConnections) + " at a time)");
      c.finish(0);
      return true;
    }
    t_connection = &c;
    bool ok = true;
    for (std::size_t left = keep_alive_max_count_; left > 0 && !c.stopping(); --left) {
      if (!c.wait_for_request(keep_alive_timeout_sec_)) break;
      c.begin_request();
      bool closed = false;
      ok = process_request(c, left == 1, closed, nullptr);
      // A request cut off in its request line gets no answer from cpp-httplib.
      if (!ok && c.written() == 0) {
        const auto [status, line] = cutoff_answer(c.cutoff());
        if (status != 0) c.refuse(status, line);
      }
      if (!ok || closed || c.closing()) break;
    }
    t_connection = nullptr;
    c.finish(c.stopping() ? 0 : 1);
    return ok;
  }
};

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

// The feature of a polytope as the page draws it: its vertices' coordinates
// where the polytope is placed (rotated by `turn` when given, then shifted).
std::string feature_points_json(const ConvexPolytope& p, const Feature& f, const Point3& shift,
                                const std::optional<Quaternion>& turn = std::nullopt) {
  const std::vector<Index> vs = f.index != kNoIndex ? feature_vertices(p, f) : std::vector<Index>();
  std::string xyz, exact;
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const Point3 x = (turn ? rotate(*turn, p.point(vs[i])) : p.point(vs[i])) + shift;
    xyz += (i ? ", " : "") + json_number(to_double(x.x)) + ", " + json_number(to_double(x.y)) + ", " +
           json_number(to_double(x.z));
    exact += (i ? ", \"" : "\"") + format_exact(x.x) + " " + format_exact(x.y) + " " + format_exact(x.z) + "\"";
  }
  return std::string("{\"type\": \"") + feature_type(f.dim) + "\", \"index\": " +
         (f.index != kNoIndex ? std::to_string(f.index) : std::string("null")) + ", \"points\": [" + xyz +
         "], \"exact\": [" + exact + "]}";
}

// The smallest face of p that holds the vertices vs: the vertices of P (or
// of Q) among a certificate's pairs, which lie on one face of the body (the
// face its certified supporting plane touches).  No vertex: index kNoIndex.
Feature face_of(const ConvexPolytope& p, std::vector<Index> vs) {
  std::sort(vs.begin(), vs.end());
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  if (vs.empty()) return {FeatureDim::vertex, kNoIndex};
  if (vs.size() == 1) return Feature::vertex(vs[0]);
  const Index h0 = p.vertex_halfedge(vs[0]);
  if (vs.size() == 2) {
    Index h = h0;
    do {
      if (p.target(h) == vs[1]) return Feature::edge(ConvexPolytope::edge(h));
      h = p.next_around_vertex(h);
    } while (h != h0);
  }
  Index h = h0;
  do {
    const std::vector<Index> fv = p.facet_vertices(p.facet(h));
    if (std::all_of(vs.begin(), vs.end(), [&](Index v) { return std::find(fv.begin(), fv.end(), v) != fv.end(); }))
      return Feature::facet(p.facet(h));
    h = p.next_around_vertex(h);
  } while (h != h0);
  return Feature::vertex(vs[0]);
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

// The state of the session: P and Q as given, M = P ⊕ (−Q) for P as given
// (built once) and P and Q prepared for the queries under rigid motion.
// A pose without a rotation is answered on M; a pose that turns P on the
// placed bodies (rigid_proximity.hpp), without building M for the rotation.
// Requests are answered one at a time.
class Session {
 public:
  Session(ConvexPolytope p, ConvexPolytope q, Method method)
      : p0_(std::move(p)), q0_(std::move(q)), obstacle_(p0_, q0_, method), body_p_(p0_), body_q_(q0_) {}

  std::string answer(const QueryPose& pose) {
    std::lock_guard<std::mutex> lock(mutex_);
    return pose.rp ? answer_rigid(pose) : answer_on_m(pose);
  }

 private:
  static std::string pose_json(const QueryPose& pose) {
    return "{\"translate_p\": " + exact_vector_json(pose.u) + ", \"rotate_p\": " +
           (pose.rp ? "\"" + quaternion_text(*pose.rp) + "\"" : std::string("null")) +
           ", \"translate_q\": " + exact_vector_json(pose.w) + "}";
  }

  std::string answer_on_m(const QueryPose& pose) {
    const auto t0 = std::chrono::steady_clock::now();
    const DistanceResult d = obstacle_.distance(pose.u, pose.w);
    std::optional<DepthResult> depth;
    if (d.status == ContactStatus::penetrating) depth = obstacle_.penetration_depth(pose.u, pose.w);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The features drawn: the distance's witness, or the depth's when the bodies overlap.
    const Witness& w = depth ? depth->witness : d.witness;
    const Point3 zero(Rational(0), Rational(0), Rational(0));
    std::string o = "{\"status\": \"" + std::string(contact_status_name(d.status)) + "\", \"pose\": " + pose_json(pose);
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
    o += ", \"certificate\": null, \"depth_certificate\": null";
    o += ", \"features\": {\"p\": " + feature_points_json(obstacle_.p(), w.p, pose.u) +
         ", \"q\": " + feature_points_json(obstacle_.q(), w.q, pose.w) + "}";
    o += ", \"m\": {" + counts_json(obstacle_.obstacle()) + "}, \"recomputed\": false";
    o += ", \"seconds\": " + json_number(seconds) + "}";
    return o;
  }

  // P turned: distance (and depth when the bodies overlap) on the placed
  // bodies, warm-started from the previous turned pose.  The answer names
  // its certificates instead of M's witnesses; M is built only when a query
  // cannot certify its answer otherwise (certificate "exact": a touching
  // pose), and then for that pose alone ("recomputed").
  std::string answer_rigid(const QueryPose& pose) {
    const RigidPose pp = RigidPose::quaternion(*pose.rp, pose.u), pq = RigidPose::translation(pose.w);
    const auto t0 = std::chrono::steady_clock::now();
    const RigidDistance d = distance(body_p_, pp, body_q_, pq, &warm_);
    std::optional<RigidDepth> depth;
    if (d.status == ContactStatus::penetrating) depth = penetration_depth(body_p_, pp, body_q_, pq, &warm_);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const RigidDistanceExact e = exact_values(body_p_, pp, body_q_, pq, d);
    std::optional<RigidDepthExact> de;
    if (depth) de = exact_values(body_p_, pp, body_q_, pq, *depth);
    const bool on_m =
        d.certificate == RigidCertificate::exact || (depth && depth->certificate == RigidCertificate::exact);
    // The features drawn: the faces of P and Q the certified plane touches
    // (the depth's when the bodies overlap); none for an answer on M or by the feature plane.
    std::vector<Index> fp, fq;
    if (depth) {
      for (int j = 0; j < 3; ++j)
        if (depth->p[j] != kNoIndex) fp.push_back(depth->p[j]), fq.push_back(depth->q[j]);
    } else if (d.certificate == RigidCertificate::closest_points) {
      for (int j = 0; j < d.k; ++j) fp.push_back(d.p[j]), fq.push_back(d.q[j]);
    }
    const Point3 zero(Rational(0), Rational(0), Rational(0));
    const Rational sq_depth = de ? de->squared_depth : Rational(0);
    const Point3 depth_direction = de ? de->direction : zero;
    std::string o = "{\"status\": \"" + std::string(contact_status_name(d.status)) + "\", \"pose\": " + pose_json(pose);
    o += ", \"squared_distance\": \"" + format_exact(e.squared_distance) + "\", \"distance\": " +
         json_number(std::sqrt(to_double(e.squared_distance)));
    o += ", \"squared_depth\": \"" + format_exact(sq_depth) + "\", \"depth\": " + json_number(std::sqrt(to_double(sq_depth)));
    o += ", \"point_p\": " + double_vector_json(e.point_p) + ", \"point_p_exact\": " + exact_vector_json(e.point_p);
    o += ", \"point_q\": " + double_vector_json(e.point_q) + ", \"point_q_exact\": " + exact_vector_json(e.point_q);
    o += ", \"direction\": " + exact_vector_json(e.point_q - e.point_p);
    o += ", \"depth_direction\": " + exact_vector_json(depth_direction) +
         ", \"depth_direction_double\": " + double_vector_json(depth_direction);
    o += ", \"witness\": null, \"depth_witness\": null";
    o += ", \"certificate\": \"" + std::string(rigid_certificate_name(d.certificate)) + "\", \"depth_certificate\": " +
         (depth ? "\"" + std::string(rigid_certificate_name(depth->certificate)) + "\"" : std::string("null"));
    o += ", \"features\": {\"p\": " + feature_points_json(p0_, face_of(p0_, fp), pose.u, pose.rp) +
         ", \"q\": " + feature_points_json(q0_, face_of(q0_, fq), pose.w) + "}";
    o += ", \"m\": null, \"recomputed\": " + std::string(on_m ? "true" : "false");
    o += ", \"seconds\": " + json_number(seconds) + "}";
    return o;
  }

  std::mutex mutex_;
  ConvexPolytope p0_, q0_;
  TranslationalObstacle obstacle_;
  RigidBody body_p_, body_q_;
  RigidWarmStart warm_;
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

  PlayServer server;
  server.new_task_queue = [] { return new ConnectionThreads; };
  server.set_payload_max_length(kMaxBody);
  server.set_read_timeout(kRequestSeconds);
  server.set_write_timeout(kWriteSeconds);
  server.set_keep_alive_timeout(kIdleSeconds);
  server.set_keep_alive_max_count(kMaxRequestsPerConnection);
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
  server.widen_backlog(int(2 * kMaxConnections));
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
    // The request line and headers are read; what follows is the body.
    if (t_connection) t_connection->begin_body();
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
  // Every answer: not to be read by other origins' pages; an error closes
  // the connection (what the client sent after it is not read).
  server.set_post_routing_handler([&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cross-Origin-Resource-Policy", "same-origin");
    res.set_header("X-Content-Type-Options", "nosniff");
    if (res.status >= 400) {
      res.headers.erase("Keep-Alive");
      if (!res.has_header("Connection")) res.set_header("Connection", "close");
      if (t_connection) t_connection->close_after_answer();
    }
  });
  server.Get("/", [&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(html, "text/html; charset=utf-8");
  });
  server.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  server.Post("/query", [&](const httplib::Request&, httplib::Response& res, const httplib::ContentReader& read) {
    // The body, decoded (chunked or not), at most kMaxBody bytes.
    std::string body;
    bool too_large = false;
    const bool whole = read([&](const char* data, std::size_t n) {
      if (body.size() + n > kMaxBody) {
        too_large = true;
        return false;
      }
      body.append(data, n);
      return true;
    });
    if (!whole) {
      const auto [status, line] = cutoff_answer(t_connection ? t_connection->cutoff() : Cutoff::none);
      if (status != 0) fail(res, status, line);
      else if (too_large || res.status == 413) fail(res, 413, cutoff_answer(Cutoff::body_too_large).second);
      else fail(res, 400, "bad request body (its chunked framing or its length)");
      return;
    }
    try {
      res.set_header("Cache-Control", "no-store");
      res.set_content(session.answer(parse_query(body)), "application/json");
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
    const auto [status, line] = cutoff_answer(t_connection ? t_connection->cutoff() : Cutoff::none);
    if (status != 0) fail(res, status, line);
    else if (res.status == 404) fail(res, 404, "no such page: " + req.method + " " + req.path + " (GET /, POST /query)");
    else if (res.status == 413) fail(res, 413, cutoff_answer(Cutoff::body_too_large).second);
    else if (res.status == 414) fail(res, 414, "request line too long (at most 8192 bytes)");
    else if (res.status == 400) fail(res, 400, "bad request: a malformed request line or header, or a header line over 8192 bytes");
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
