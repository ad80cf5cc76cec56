// minksum simulate: Fig. 4 of Fogel and Halperin (2006) — a static obstacle and a robot moving
// along a path that first grazes the obstacle without penetrating it and then
// penetrates it; the robot rotates every other frame.  Every frame is answered
// on the placed bodies (rigid_proximity.hpp): no M is built for a turn.
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>
#include <minksum/rigid_proximity.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "page.hpp"

namespace minksum::cli {

namespace {

const char* kSimulateHelp = R"(Usage: minksum simulate [options]

Fig. 4 of Fogel and Halperin (2006): a static obstacle Q at the origin and a robot P moving in
the x-y plane.  In the first pass the robot slides along a horizontal line
whose height is computed exactly so that the robot grazes the obstacle
(touching, never penetrating) at one frame; in the second pass it slides back
through the obstacle.  The robot turns about the z axis (exact rational
rotation) every other frame.  Each frame is answered on the placed bodies
(the rigid-motion queries of docs/proximity.md): no M = P ⊕ (−Q) is built
for a turn (touching frames are proved by the plane of the touching
features, certificate "feature_plane"), and M is built, for one pose, only
where no certificate settles the answer without it (certificate "exact").  Each frame
prints its status (separate / touching / penetrating), the exact distance or
penetration depth, the time of its query and the certificate that proved
it; a last line sums up (time per query, answers certified without M).

Options:
  --obstacle SPEC   the obstacle Q (file or catalog name; default dodecahedron@scale:2)
  --robot SPEC      the robot P (default cube@scale:1/2)
  --hull            take the exact convex hull of the obstacle's and the
                    robot's points instead of requiring valid convex meshes
  --frames N        number of frames, 4 <= N <= 10000 (default 40)
  --turn A,B,C,D    the rotation applied every other frame, an integer
                    quaternion (default 10,0,0,1: about z by ≈ 11.4°)
  -o, --output OUT  write a picture of the trail (.svg), or the 3D player
                    (.html, as --html); written to a temporary file and renamed
  --html OUT        write the motion as a self-contained 3D page (offline;
                    docs/viewer.md): play/pause, a timeline slider with the
                    frames where the state changes marked, speed; the robot
                    coloured by its state, each frame's exact translation and
                    squared distance or depth
  --show-m          in the --html page, also the configuration-space obstacle
                    of the frame's orientation, Q ⊕ (−P) = −M (the robot
                    meets Q exactly when its reference point is in it), and
                    that point; M of each orientation is then built for
                    the drawing only (the answers do not use it)
  --json            one JSON object per frame instead of text (no summary):
                    frame, orientation, rotation (the robot's integer
                    quaternion), translation, status, squared_distance or
                    squared_depth (exact), certificate, query_seconds;
                    rebuilt is true when M was built for the frame's pose
                    (certificate exact; its time is in query_seconds) and
                    build_seconds is 0
)";

struct Frame {
  Point3 u;         // translation of the robot
  std::size_t orientation = 0;
  bool turned = false;  // the first frame of a new orientation
  ContactStatus status = ContactStatus::separate;
  RigidCertificate certificate = RigidCertificate::exact;  // how the frame's answer was proved
  Rational value;   // squared distance or squared depth
  double query_seconds = 0;
};

std::string quaternion_text(const Quaternion& q) {
  return q[0].get_str() + "," + q[1].get_str() + "," + q[2].get_str() + "," + q[3].get_str();
}

struct P2 {
  double x, y;
};
std::vector<P2> hull2(std::vector<P2> pts) {  // drawing only (doubles)
  std::sort(pts.begin(), pts.end(), [](P2 a, P2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (pts.size() < 3) return pts;
  auto cross = [](P2 o, P2 a, P2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  std::vector<P2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

std::string svg_polygon(const std::vector<P2>& h, const std::string& style) {
  std::ostringstream o;
  o << "<polygon points=\"";
  for (const auto& p : h) o << format_double(p.x) << "," << format_double(-p.y) << " ";
  o << "\" style=\"" << style << "\"/>\n";
  return o.str();
}

std::vector<P2> outline(const ConvexPolytope& p, const Point3& t) {
  std::vector<P2> pts;
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Vec3d a = p.approx(v);
    pts.push_back({a.x + to_double(t.x), a.y + to_double(t.y)});
  }
  return hull2(pts);
}

const char* status_colour(ContactStatus s) {
  return s == ContactStatus::separate ? "#2a8f3a" : s == ContactStatus::touching ? "#e08a00" : "#d02020";
}

}  // namespace

int run_simulate(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "simulate",
                            {{"--obstacle", "", true}, {"--robot", "", true}, {"--frames", "", true},
                             {"--turn", "", true}, {"--output", "-o", true}, {"--html", "", true},
                             {"--show-m", "", false}, {"--json", "", false}, {"--hull", "", false}});
  if (a.help) {
    std::cout << kSimulateHelp;
    return 0;
  }
  if (!a.positional.empty()) throw UsageError("'simulate' takes no operands (see 'minksum simulate --help')");
  const std::string frames_text = a.value_or("--frames", "40");
  auto frames_num = parse_number(frames_text);
  if (!frames_num || frames_num->get_den() != 1 || *frames_num < 4 || *frames_num > 10000)
    throw UsageError("--frames needs an integer 4 <= N <= 10000, got '" + frames_text + "'");
  const long frames = frames_num->get_num().get_si();
  std::string output = a.value_or("--output", "");
  std::string html_output = a.value_or("--html", "");
  if (a.value("--html")) check_html_path(html_output, "--html");
  const bool show_m = a.flag("--show-m");
  if (!output.empty()) {
    const std::string ext = output.size() >= 5 ? output.substr(output.size() - 5) : "";
    if (ext == ".html") {
      if (!html_output.empty()) throw UsageError("-o OUT.html and --html both ask for the page; give one");
      html_output = output, output.clear();
    } else if (output.size() < 4 || output.substr(output.size() - 4) != ".svg") {
      throw UsageError("--output: the picture is .svg or .html, got '" + output + "'");
    }
  }
  if (show_m && html_output.empty()) throw UsageError("--show-m needs the page: --html OUT.html");
  Quaternion turn = {Integer(10), Integer(0), Integer(0), Integer(1)};
  if (auto t = a.value("--turn")) {
    std::vector<std::string> parts;
    std::stringstream ss(*t);
    for (std::string x; std::getline(ss, x, ',');) parts.push_back(x);
    bool ok = parts.size() == 4;
    for (int i = 0; ok && i < 4; ++i) {
      auto v = parse_number(parts[i]);
      ok = v && v->get_den() == 1;
      if (ok) turn[i] = v->get_num();
    }
    if (!ok || (sgn(turn[0]) == 0 && sgn(turn[1]) == 0 && sgn(turn[2]) == 0 && sgn(turn[3]) == 0))
      throw UsageError("--turn needs a non-zero integer quaternion A,B,C,D, got '" + *t + "'");
  }
  const bool json = a.flag("--json");
  const bool hull = a.flag("--hull");
  const ConvexPolytope obstacle = load_operand(a.value_or("--obstacle", "dodecahedron@scale:2"), hull, nullptr);
  const ConvexPolytope robot = load_operand(a.value_or("--robot", "cube@scale:1/2"), hull, nullptr);

  // Orientation k (frames 2k, 2k+1): the robot turned k times.
  const std::size_t orientations = std::size_t((frames + 1) / 2);
  // The turned robot P_k as a polytope, for the drawings and the M_k they
  // show (the queries place the robot themselves), made on first use.
  std::vector<std::optional<ConvexPolytope>> turned_robots;
  std::vector<Quaternion> turns;  // orientation k: robot rotated by turns[k]
  Quaternion q = {Integer(1), Integer(0), Integer(0), Integer(0)};
  for (std::size_t k = 0; k < orientations; ++k) {
    turned_robots.emplace_back();
    turns.push_back(q);
    q = quaternion_product(turn, q);
  }
  const auto robots = [&](std::size_t k) -> const ConvexPolytope& {
    if (!turned_robots[k]) turned_robots[k] = k == 0 ? robot : rotated(robot, turns[k]);
    return *turned_robots[k];
  };

  // x positions: pass 1 from −X to X, pass 2 back; X clears both bodies.
  double reach = 0;
  for (Index v = 0; v < obstacle.num_vertices(); ++v)
    reach = std::max({reach, std::fabs(obstacle.approx(v).x), std::fabs(obstacle.approx(v).y)});
  double rreach = 0;
  for (Index v = 0; v < robot.num_vertices(); ++v)
    rreach = std::max({rreach, std::fabs(robot.approx(v).x), std::fabs(robot.approx(v).y), std::fabs(robot.approx(v).z)});
  const long X = long(std::ceil(reach + 2 * rreach)) + 1;
  const long pass1 = frames / 2, pass2 = frames - pass1;
  auto xpos = [&](long i) -> Rational {
    Rational step = i < pass1 ? Rational(2 * X * i, pass1 - 1) : Rational(2 * X * (i - pass1), pass2 > 1 ? pass2 - 1 : 1);
    step.canonicalize();
    if (i < pass1) return Rational(-X) + step;
    return Rational(X) - step;
  };

  const RigidBody body_p(robot), body_q(obstacle);
  const RigidPose pose_q;  // the obstacle at the origin, as given
  const auto pose_p = [&](std::size_t k, const Point3& u) {
    return k == 0 ? RigidPose::translation(u) : RigidPose::quaternion(turns[k], u);
  };

  // Grazing height: the robot flies at the highest height at which it meets
  // Q at some frame of the first pass, so it touches at one frame and never
  // penetrates.  For the frame at x with orientation k, that height is the
  // top of the segment where the line L = {(x, h, 0)} meets S_k = {u : P_k +
  // u meets Q} = Q ⊕ (−P_k) (an interval: S_k is convex), found on the
  // placed bodies.  A separate probe at height h gives the closest points,
  // hence v = point_q − point_p with h + v the point of S_k nearest the
  // probe, and S_k lies in the half-space v · (u − (x, h, 0)) ≥ |v|²: on L,
  // every point of S_k is at or below h + |v|²/v_y when v_y < 0, at or above
  // it when v_y > 0, and there is none when v_y = 0.  These cuts bound the
  // interval; the next probe is below the upper bound (by half the last
  // step) or between the bounds.  A penetrating probe is interior to S_k:
  // from there the directional depth along +y is the exact distance to the
  // top.  A line that meets no interior point of S_k (it touches S_k in a
  // point or along its boundary: no probe can penetrate), a probe that
  // touches, or 64 probes without a penetrating one, and the top is read
  // off the section of M_k instead (built for that orientation alone):
  // M_k's half-spaces cut L exactly.
  const Point3 up(Rational(0), Rational(1), Rational(0));
  RigidWarmStart probe_warm;
  std::vector<std::optional<TranslationalObstacle>> sections(orientations);
  const auto top_on_m = [&](std::size_t k, const Rational& x) -> std::optional<Rational> {
    if (!sections[k]) sections[k].emplace(robots(k), obstacle);
    const ConvexPolytope& m = sections[k]->obstacle();  // P+u meets Q iff s = −u ∈ M
    const Rational sx = -x;
    bool have_lo = false, have_hi = false;
    Rational lo, hi;
    for (Index f = 0; f < m.num_facets(); ++f) {
      const Plane& pl = m.plane(f);
      const Rational rhs = Rational(pl.d) - Rational(pl.a) * sx;  // b·y <= rhs on s = (−x, y, 0)
      if (sgn(pl.b) == 0) {
        if (sgn(rhs) < 0) return std::nullopt;
      } else if (sgn(pl.b) > 0) {
        Rational b = rhs / Rational(pl.b);
        if (!have_hi || b < hi) hi = b, have_hi = true;
      } else {
        Rational b = rhs / Rational(pl.b);
        if (!have_lo || b > lo) lo = b, have_lo = true;
      }
    }
    if (!have_lo || (have_hi && hi < lo)) return std::nullopt;
    return Rational(-lo);
  };
  const auto top = [&](std::size_t k, const Rational& x) -> std::optional<Rational> {
    std::optional<Rational> upper, lower;  // L ∩ S_k lies within [lower, upper]
    Rational h(X);                          // above both bodies
    for (int probe = 0; probe < 64; ++probe) {
      const RigidPose pp = pose_p(k, Point3(x, h, Rational(0)));
      const RigidDistance d = distance(body_p, pp, body_q, pose_q, &probe_warm);
      if (d.status == ContactStatus::penetrating) {
        const RigidDirectionalDepth r = directional_depth(body_p, pp, body_q, pose_q, up, &probe_warm);
        return Rational(h + exact_values(body_p, pp, body_q, pose_q, up, r));
      }
      if (d.status == ContactStatus::touching) break;
      const RigidDistanceExact e = exact_values(body_p, pp, body_q, pose_q, d);
      const Point3 v = e.point_q - e.point_p;
      if (sgn(v.y) == 0) return std::nullopt;
      const Rational cut = h + dot(v, v) / v.y;
      if (sgn(v.y) < 0) {
        if (!upper || cut < *upper) upper = cut;
      } else if (!lower || cut > *lower) {
        lower = cut;
      }
      if (upper && lower && *lower > *upper) return std::nullopt;
      if (upper && lower) h = (*lower + *upper) / 2;
      else if (upper) h = *upper - (h - *upper) / 2;
      else h = *lower + (*lower - h) / 2;
    }
    return top_on_m(k, x);
  };
  Rational height;
  bool have_height = false;
  for (long j = 0; j < pass1; ++j)
    if (const auto t = top(std::size_t(j / 2), xpos(j)); t && (!have_height || *t > height))
      height = *t, have_height = true;
  if (!have_height) height = Rational(X);
  std::size_t sections_built = 0;
  for (const auto& m : sections) sections_built += m.has_value();

  // Every frame is answered on the placed bodies (rigid_proximity.hpp): the
  // robot under its frame's rotation and translation, the obstacle fixed.
  // No M is built for a turn; the library builds M for one pose only when
  // it cannot certify the answer otherwise (certificate "exact").  The frames form one coherent trajectory: each query starts from
  // the previous one's witnesses (RigidWarmStart).
  RigidWarmStart warm;
  long frames_on_m = 0;
  std::vector<Frame> trail;
  double total_seconds = 0;
  for (long i = 0; i < frames; ++i) {
    Frame fr;
    fr.orientation = std::size_t(i / 2);
    fr.turned = fr.orientation > 0 && i % 2 == 0;
    fr.u = Point3(xpos(i), i < pass1 ? height : Rational(0), Rational(0));
    const RigidPose pp = pose_p(fr.orientation, fr.u);
    const auto t0 = std::chrono::steady_clock::now();
    const RigidDistance d = distance(body_p, pp, body_q, pose_q, &warm);
    std::optional<RigidDepth> depth;
    if (d.status == ContactStatus::penetrating) depth = penetration_depth(body_p, pp, body_q, pose_q, &warm);
    fr.query_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total_seconds += fr.query_seconds;
    fr.status = d.status;
    fr.certificate = depth ? depth->certificate : d.certificate;
    // The exact values, after the timing (as `query` prints them).
    fr.value = depth ? exact_values(body_p, pp, body_q, pose_q, *depth).squared_depth
                     : exact_values(body_p, pp, body_q, pose_q, d).squared_distance;
    // M built for this pose alone: a query that could not certify its answer without it.
    const bool on_m =
        d.certificate == RigidCertificate::exact || (depth && depth->certificate == RigidCertificate::exact);
    frames_on_m += on_m;
    if (json) {
      std::cout << "{\"frame\": " << i << ", \"orientation\": " << fr.orientation << ", \"rotation\": \""
                << quaternion_text(turns[fr.orientation]) << "\", \"rebuilt\": " << (on_m ? "true" : "false")
                << ", \"translation\": [\"" << format_exact(fr.u.x) << "\", \"" << format_exact(fr.u.y) << "\", \""
                << format_exact(fr.u.z) << "\"], \"status\": \"" << contact_status_name(fr.status) << "\", \""
                << (fr.status == ContactStatus::penetrating ? "squared_depth" : "squared_distance") << "\": \""
                << format_exact(fr.value) << "\", \"certificate\": \"" << rigid_certificate_name(fr.certificate)
                << "\", \"query_seconds\": " << json_number(fr.query_seconds) << ", \"build_seconds\": 0}\n";
    } else {
      std::cout << "frame " << i << (i < pass1 ? " (pass 1)" : " (pass 2)") << "  x = "
                << format_double(to_double(fr.u.x)) << "  y = " << format_double(to_double(fr.u.y)) << "  "
                << contact_status_name(fr.status);
      if (fr.status == ContactStatus::separate)
        std::cout << "  distance ≈ " << format_double(std::sqrt(to_double(fr.value)));
      else if (fr.status == ContactStatus::penetrating)
        std::cout << "  depth ≈ " << format_double(std::sqrt(to_double(fr.value)));
      std::cout << "  query " << format_double(std::round(fr.query_seconds * 1e7) / 10) << " µs  ["
                << rigid_certificate_name(fr.certificate) << (on_m ? "; M built exactly for this pose]" : "]");
      if (fr.turned) std::cout << "  (robot turned)";
      std::cout << "\n";
    }
    trail.push_back(std::move(fr));
  }
  if (!json) {
    char us[32];
    std::snprintf(us, sizeof us, "%.2f", total_seconds / double(frames) * 1e6);
    std::cout << frames << " frames, " << us << " µs per query, " << frames - frames_on_m
              << " certified without M, " << frames_on_m << " on M built exactly for the pose";
    if (sections_built > 0)
      std::cout << "; the grazing height read off M of " << sections_built << " orientation"
                << (sections_built == 1 ? "" : "s");
    std::cout << "\n";
  }

  if (!output.empty()) {
    // The x-y plane seen from above (+z), x right, y up: the picture is cut
    // to the outlines drawn, with a title above and a legend below.
    std::vector<std::pair<std::vector<P2>, std::string>> shapes;
    shapes.push_back({outline(obstacle, Point3(Rational(0), Rational(0), Rational(0))),
                      "fill:#9db4d6;stroke:#2b4a7a;stroke-width:0.04"});
    for (const Frame& fr : trail)
      shapes.push_back({outline(robots(fr.orientation), fr.u),
                        std::string("fill:none;stroke-width:0.03;stroke:") + status_colour(fr.status)});
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    for (const auto& [poly, style] : shapes)
      for (const P2& p : poly) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    const double margin = 0.5, head = 1.1, foot = 1.3;
    const double left = x0 - margin, top = -y1 - margin - head;  // SVG y is −y
    const double w = std::max(x1 - x0 + 2 * margin, 15.0), h = y1 - y0 + 2 * margin + head + foot;
    std::ostringstream svg;
    auto text = [&](double x, double y, const std::string& t, const char* extra = "") {
      svg << "<text x=\"" << format_double(x) << "\" y=\"" << format_double(y) << "\" font-size=\"0.36\" "
          << "font-family=\"sans-serif\"" << extra << ">" << t << "</text>\n";
    };
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" << format_double(left) << " " << format_double(top)
        << " " << format_double(w) << " " << format_double(h) << "\" width=\"900\" height=\"" << int(900 * h / w)
        << "\">\n<title>minksum simulate: the robot's trail past the obstacle, top view (x right, y up)</title>\n"
        << "<rect x=\"" << format_double(left) << "\" y=\"" << format_double(top) << "\" width=\"" << format_double(w)
        << "\" height=\"" << format_double(h) << "\" fill=\"white\"/>\n";
    text(left + 0.3, top + 0.7, "Top view (x right, y up): pass 1 grazes Q, pass 2 goes through it",
         " font-weight=\"bold\"");
    for (const auto& [poly, style] : shapes) svg << svg_polygon(poly, style);
    const double ly = -y0 + margin + 0.75;
    double lx = left + 0.3;
    const std::pair<const char*, const char*> legend[] = {{"#9db4d6", "obstacle Q"},
                                                          {status_colour(ContactStatus::separate), "robot P separate"},
                                                          {status_colour(ContactStatus::touching), "touching"},
                                                          {status_colour(ContactStatus::penetrating), "penetrating"}};
    for (const auto& [colour, label] : legend) {
      svg << "<rect x=\"" << format_double(lx) << "\" y=\"" << format_double(ly - 0.35) << "\" width=\"0.4\" "
          << "height=\"0.4\" fill=\"" << colour << "\" stroke=\"#333\" stroke-width=\"0.02\"/>\n";
      text(lx + 0.55, ly, label);
      lx += 0.55 + 0.21 * double(std::string(label).size()) + 0.4;
    }
    svg << "</svg>\n";
    const std::string body = svg.str();
    try {
      write_file_atomically(output, [&](std::ostream& out) { out << body; });
    } catch (const InputError& e) {
      throw OutputError(e.what());
    }
    if (!json) std::cout << "picture written to " << printable(output) << "\n";
  }
  if (!html_output.empty()) {
    std::vector<MotionFrame> frames_shown;
    for (std::size_t i = 0; i < trail.size(); ++i)
      frames_shown.push_back({trail[i].u, trail[i].orientation, int(trail[i].status), trail[i].value,
                              long(i) < pass1 ? 1 : 2});
    // --show-m: M of each orientation, built here for the drawing only
    // (the answers above never use it).
    std::vector<ConvexPolytope> c_obstacles;  // −M_k = Q ⊕ (−P_k) per orientation
    if (show_m)
      for (std::size_t k = 0; k < orientations; ++k)
        c_obstacles.push_back(TranslationalObstacle(robots(k), obstacle).obstacle().negated());
    write_motion_page(html_output, "minksum simulate: a robot passing an obstacle", obstacle, robot, turns,
                      frames_shown, 8, c_obstacles);
    if (!json) std::cout << "player written to " << html_output << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
