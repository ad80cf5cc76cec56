// minksum play P Q: the interactive proximity application.  The command
// checks its command line and prints its help; the server
// (cli/play/server.cpp) links cpp-httplib, which Debian ships as a shared
// library only, while the command is linked statically (it starts faster):
// so the build makes a second, dynamically linked executable, minksum-play,
// from the same sources plus the server, and 'minksum play ARGS' becomes
// 'minksum-play play ARGS' (exec: the same process id, standard output and
// signals).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "play.hpp"

namespace minksum::cli {

namespace {

const char* kPlayHelp = R"(Usage: minksum play P Q [--port N] [--no-open] [--method M] [--hull]

Serve an interactive page on this machine's loopback interface (127.0.0.1
only) where the convex polytope P can be dragged and turned with the mouse
against the fixed polytope Q.  On every move the page asks the server, which
answers with the library, exactly: the state (separate, touching or
penetrating, in colour), the squared distance or squared penetration depth as
an exact rational and its square root as a double, the closest points (or a
common point) of P and Q with exact coordinates, the minimal translation of P
that separates them, and the witness features of P and Q (drawn in the scene).
M = P ⊕ (−Q) is computed once, for P as given, and answers the poses that
move P without turning it.  A turned P is answered on the placed bodies
(the rigid-motion queries of docs/proximity.md, as 'minksum query' answers
a rotated operand): the same exact values, each answer proved by a certificate
that the page names, and no M built for the rotation; M is built, for that
pose alone, only where the search certifies no answer without it (touching
poses, and poses it leaves undecided: certificate "exact").

The first line on standard output is the page's URL (http://127.0.0.1:PORT/).
Ctrl-C (SIGINT) or SIGTERM stops the server; it then exits with status 0.

In the page: drag P to move it in the view plane, shift-drag P to turn it
about its origin (the origin of its coordinates), drag elsewhere to turn the
view, wheel to zoom.

Exact poses: a translation is three exact rationals (the page moves P on a
grid of 1/2^k steps); a rotation is an integer quaternion A+Bi+Cj+Dk, the
rotation with the rational matrix of the catalog's @rot:A,B,C,D (the page
rounds the orientation it turns to a quaternion of norm about 64, so the
drawn and the computed P are the same).  The page shows each pose in the
syntax of 'minksum query' (X,Y,Z and A,B,C,D), which answers it alike.

Options:
  --port N     listen on port N (default 0: a free port the system chooses)
  --no-open    do not open the page in a browser (else xdg-open is tried)
  --method M   how M (of P as given) is computed: {methods}
  --hull       take the convex hull of each input file's points

The server: GET / is the page; POST /query takes a JSON object
  {"translate_p": "X,Y,Z", "rotate_p": "A,B,C,D", "translate_q": "X,Y,Z"}
(rotate_p and translate_q optional; the syntax of 'minksum query') and
answers a JSON object (status, squared_distance, distance, squared_depth,
depth, point_p, point_p_exact, point_q, point_q_exact, direction,
depth_direction, witness, depth_witness, certificate, depth_certificate,
features, m, recomputed, pose, seconds).  P as given: witness and m (M's
counts), certificate null; P turned: certificate (and depth_certificate
when the bodies overlap), witness and m null, recomputed true when M was
built for that pose.  A rotation's integers are at most 10^6 in
magnitude; a bad request gets HTTP 400 and one line saying why.

What the server refuses, with one line saying why (an error answer closes
the connection):
  403  a Host header other than 127.0.0.1:PORT, its own address (so a page
       whose name is made to mean 127.0.0.1 reads nothing), an Origin
       other than http://127.0.0.1:PORT, and a POST whose Sec-Fetch-Site
       is not same-origin (so other pages' requests change nothing)
  415  a POST whose Content-Type is not application/json, or that has a
       Content-Encoding
  411  a POST with neither Content-Length nor Transfer-Encoding: chunked
       (400: another Transfer-Encoding, or both)
  413  a body over 4096 bytes (chunked or not), or over 16384 as sent
  431  a request line and headers over 16384 bytes, or over 64 header lines
  400  a header line over 8192 bytes; 414: a request line over 8192 bytes
  408  a request not received whole within 10 s of its first byte
  503  a connection beyond 32 at a time (each has its own thread, so a
       slow client holds only its own)
A connection with no request for 5 s is closed; requests sent one after
another on a connection without waiting are answered in order.

Exit status: 0 after Ctrl-C or SIGTERM, 1 when the port cannot be bound or
standard output cannot be written, 2 bad usage, 3 bad input data.
)";

int port_option(const Args& a) {
  const auto v = a.value("--port");
  if (!v) return 0;
  std::string why;
  const auto n = parse_number(*v, &why);
  if (!n || n->get_den() != 1 || *n < 0 || *n > 65535 || v->find_first_of(".eEx/") != std::string::npos)
    throw UsageError("--port: expected an integer from 0 to 65535, got '" + printable(*v) + "'");
  return int(n->get_num().get_si());
}

}  // namespace

int run_play(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "play",
                            {{"--port", "", true}, {"--no-open"}, {"--method", "", true}, {"--hull"}});
  if (a.help) {
    std::cout << expand_help(kPlayHelp);
    return 0;
  }
  if (a.positional.size() != 2) throw UsageError("'play' needs two operands P Q (see 'minksum play --help')");
  PlayOptions o;
  o.p = a.positional[0];
  o.q = a.positional[1];
  o.port = port_option(a);
  o.open = !a.flag("--no-open");
  o.hull = a.flag("--hull");
  const std::string method_text = a.value_or("--method", "auto");
  const auto method = parse_method(method_text);
  if (!method) throw UsageError("unknown method '" + method_text + "' (" + method_list() + ")");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) + "' is not implemented in this version of minksum");
  o.method = *method;
  if (run_play_server) return run_play_server(o);

  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot find the minksum command's own path: " + ec.message());
  const std::string server = (self.parent_path() / "minksum-play").string();
  std::vector<std::string> all = {server, "play"};
  all.insert(all.end(), argv.begin(), argv.end());
  std::vector<char*> args;
  for (auto& x : all) args.push_back(x.data());
  args.push_back(nullptr);
  std::cout.flush();
  ::execv(server.c_str(), args.data());
  throw OutputError("cannot run the server of 'minksum play', " + server + ": " + std::strerror(errno) +
                    " (it is built and installed beside minksum)");
}

}  // namespace minksum::cli
