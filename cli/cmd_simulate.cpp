// minksum simulate: Fig. 4 of Fogel and Halperin (2006) — a static obstacle and a robot moving
// along a path that first grazes the obstacle without penetrating it and then
// penetrates it; the robot rotates every other frame (M is recomputed then).
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
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
rotation) every other frame; M = P ⊕ (−Q) is recomputed then.  Each frame
prints its status (separate / touching / penetrating), the exact distance or
penetration depth, and the time of the query (and of M's computation).  The
frames of one orientation are answered as one batch of the library's
trajectory API; a frame's query time is the batch's time per frame.

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
                    that point
  --json            one JSON object per frame instead of text
)";

struct Frame {
  Point3 u;         // translation of the robot
  std::size_t orientation;
  ContactStatus status;
  Rational value;   // squared distance or squared depth
  double query_seconds = 0, build_seconds = 0;
  bool rebuilt = false;
};

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
  std::vector<ConvexPolytope> robots;
  std::vector<Quaternion> turns;  // orientation k: robot rotated by turns[k]
  Quaternion q = {Integer(1), Integer(0), Integer(0), Integer(0)};
  for (std::size_t k = 0; k < orientations; ++k) {
    robots.push_back(k == 0 ? robot : rotated(robot, q));
    turns.push_back(q);
    q = quaternion_product(turn, q);
  }

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

  // Grazing height: P+u meets Q iff s = −u ∈ M.  On the line s = (−x, y, 0)
  // the lowest y inside M_k is an exact rational (intersection of M_k's
  // half-spaces with the line); the robot flies at the highest of these over
  // the first pass, so it touches at one frame and never penetrates.
  Rational height;
  bool have_height = false;
  {
    for (std::size_t k = 0; long(2 * k) < pass1; ++k) {
      TranslationalObstacle ob(robots[k], obstacle);
      const ConvexPolytope& m = ob.obstacle();
      for (long j = long(2 * k); j < std::min(long(2 * k + 2), pass1); ++j) {
        const Rational sx = -xpos(j);
        bool feasible = true, have_lo = false, have_hi = false;
        Rational lo, hi;
        for (Index f = 0; f < m.num_facets() && feasible; ++f) {
          const Plane& pl = m.plane(f);
          const Rational rhs = Rational(pl.d) - Rational(pl.a) * sx;  // b·y <= rhs
          if (sgn(pl.b) == 0) {
            if (sgn(rhs) < 0) feasible = false;
          } else if (sgn(pl.b) > 0) {
            Rational b = rhs / Rational(pl.b);
            if (!have_hi || b < hi) hi = b, have_hi = true;
          } else {
            Rational b = rhs / Rational(pl.b);
            if (!have_lo || b > lo) lo = b, have_lo = true;
          }
        }
        if (!feasible || !have_lo || (have_hi && hi < lo)) continue;
        if (!have_height || -lo > height) height = -lo, have_height = true;
      }
    }
    if (!have_height) height = Rational(X);
  }

  TranslationalObstacle ob(robots[0], obstacle);
  std::vector<ConvexPolytope> c_obstacles;  // −M_k per orientation, for --show-m
  if (show_m) c_obstacles.push_back(ob.obstacle().negated());
  std::vector<Frame> trail;
  std::size_t current = 0;
  // The frames of one orientation are one batch of the trajectory API
  // (distance_points, then penetration_depth_points on the penetrating
  // poses); each frame's query time is the batch's time per frame.
  std::vector<Frame> batch;
  std::vector<Point3> batch_s, inside_s;
  std::vector<DistanceResult> dist;
  std::vector<DepthResult> depth;
  for (long i = 0; i < frames; ++i) {
    if (batch.empty()) {
      const std::size_t orientation = std::size_t(i / 2);
      Frame first;
      if (orientation != current) {
        const auto t0 = std::chrono::steady_clock::now();
        ob.set_p(robots[orientation]);
        first.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        first.rebuilt = true;
        current = orientation;
        if (show_m) c_obstacles.push_back(ob.obstacle().negated());
      }
      batch_s.clear();
      for (long k = i; k < frames && std::size_t(k / 2) == orientation; ++k) {
        Frame fr = batch.empty() ? first : Frame{};
        fr.orientation = orientation;
        fr.u = Point3(xpos(k), k < pass1 ? height : Rational(0), Rational(0));
        batch_s.push_back(-fr.u);  // s = w − u with Q (w = 0) fixed
        batch.push_back(std::move(fr));
      }
      const auto t0 = std::chrono::steady_clock::now();
      ob.distance_points(batch_s, dist);
      inside_s.clear();
      for (std::size_t k = 0; k < dist.size(); ++k)
        if (dist[k].status == ContactStatus::penetrating) inside_s.push_back(batch_s[k]);
      ob.penetration_depth_points(inside_s, depth);
      const double per_frame =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / double(batch.size());
      for (std::size_t k = 0, j = 0; k < batch.size(); ++k) {
        batch[k].status = dist[k].status;
        batch[k].value = dist[k].status == ContactStatus::penetrating ? depth[j++].squared_depth()
                                                                       : dist[k].squared_distance();
        batch[k].query_seconds = per_frame;
      }
      std::reverse(batch.begin(), batch.end());  // taken from the back, in frame order
    }
    Frame fr = std::move(batch.back());
    batch.pop_back();
    if (json) {
      std::cout << "{\"frame\": " << i << ", \"orientation\": " << fr.orientation << ", \"rebuilt\": "
                << (fr.rebuilt ? "true" : "false") << ", \"translation\": [\"" << format_exact(fr.u.x) << "\", \""
                << format_exact(fr.u.y) << "\", \"" << format_exact(fr.u.z) << "\"], \"status\": \""
                << contact_status_name(fr.status) << "\", \""
                << (fr.status == ContactStatus::penetrating ? "squared_depth" : "squared_distance") << "\": \""
                << format_exact(fr.value) << "\", \"query_seconds\": " << json_number(fr.query_seconds)
                << ", \"build_seconds\": " << json_number(fr.build_seconds) << "}\n";
    } else {
      std::cout << "frame " << i << (i < pass1 ? " (pass 1)" : " (pass 2)") << "  x = "
                << format_double(to_double(fr.u.x)) << "  y = " << format_double(to_double(fr.u.y)) << "  "
                << contact_status_name(fr.status);
      if (fr.status == ContactStatus::separate)
        std::cout << "  distance ≈ " << format_double(std::sqrt(to_double(fr.value)));
      else if (fr.status == ContactStatus::penetrating)
        std::cout << "  depth ≈ " << format_double(std::sqrt(to_double(fr.value)));
      std::cout << "  query " << format_double(std::round(fr.query_seconds * 1e7) / 10) << " µs";
      if (fr.rebuilt)
        std::cout << "  (robot turned, M recomputed in " << format_double(std::round(fr.build_seconds * 1e5) / 100)
                  << " ms)";
      std::cout << "\n";
    }
    trail.push_back(std::move(fr));
  }

  if (!output.empty()) {
    // The x-y plane seen from above (+z), x right, y up: the picture is cut
    // to the outlines drawn, with a title above and a legend below.
    std::vector<std::pair<std::vector<P2>, std::string>> shapes;
    shapes.push_back({outline(obstacle, Point3(Rational(0), Rational(0), Rational(0))),
                      "fill:#9db4d6;stroke:#2b4a7a;stroke-width:0.04"});
    for (const Frame& fr : trail)
      shapes.push_back({outline(robots[fr.orientation], fr.u),
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
    write_motion_page(html_output, "minksum simulate: a robot passing an obstacle", obstacle, robot, turns,
                      frames_shown, 8, c_obstacles);
    if (!json) std::cout << "player written to " << html_output << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
