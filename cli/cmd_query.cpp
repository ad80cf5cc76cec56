// minksum query collide|distance|depth|ddepth P Q: exact proximity queries
// under translation (Fogel and Halperin 2006, §4), one pose or a trajectory of poses.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>

#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "pose.hpp"
#include "sweep.hpp"

namespace minksum::cli {

namespace {

const char* kQueryHelp = R"(Usage: minksum query KIND P Q [options]

Exact proximity queries between the convex polytopes P and Q (files or
catalog names) under translation, through the configuration-space obstacle
M = P ⊕ (−Q), which is computed once for the given orientations.
P or Q may also be a point, a segment or a flat polygon (docs/sweeps.md):
then M is computed by the sweep and each query answered exactly by a scan
of M (no witness, no --trajectory or rotations); a segment Q asks whether P
meets the path it stands for ("penetrating": it passes through P's inside).

KIND:
  collide    separate, touching (boundaries meet, interiors disjoint) or
             penetrating, decided exactly; witness: the facet of M stabbed by
             the ray from an interior point of M through s = w − u
  distance   exact squared separation distance, its double, the closest
             points of P and Q and their features
  depth      exact squared penetration depth and a minimal translation of P
             that separates the interiors
  ddepth     directional penetration depth along --direction d: the smallest
             t >= 0 such that P translated by t·d no longer overlaps the
             interior of Q (d is not normalised; depth = t·|d|)

Options:
  --translate-p X,Y,Z   translation u of P (default 0,0,0)
  --translate-q X,Y,Z   translation w of Q (default 0,0,0)
  --rotate-p A,B,C,D    rotate P by the integer quaternion A+Bi+Cj+Dk (exact:
                        the same matrix as the catalog's @rot:A,B,C,D)
  --rotate-q A,B,C,D    rotate Q likewise
  --direction X,Y,Z     the direction d of ddepth (non-zero)
  --method M            how M = P ⊕ (−Q) is computed: any method of `minksum sum`
                        (default auto, i.e. walk)
  --trajectory FILE     read one pose per line from FILE ('-': stdin) and
                        answer the query for each, reusing the previous
                        answer as the start of the next (coherence).  A line
                        is "PX,PY,PZ [QX,QY,QZ] [rp=A,B,C,D] [rq=A,B,C,D]":
                        the translation of P, optionally of Q (else
                        --translate-q), optional rotations of P and Q relative
                        to their input orientation (M is recomputed when one
                        changes).  Blank lines and lines starting with '#' are
                        skipped.  Output: one line (or JSON object) per pose.
  --json                print JSON: query, status, squared_distance /
                        squared_depth / t as exact rationals in strings
                        ("p/q" or an integer), distance / depth (double;
                        null when beyond the double range: JSON has no
                        infinity), direction (exact strings), point_p /
                        point_q (doubles) and point_p_exact / point_q_exact
                        (exact strings) for distance, witness, seconds

Coordinates accept integers, exact rationals (1/3,0,-2/7) and decimals (the
nearest double, then exact).

P or Q may be '-': a mesh read from standard input, in the format that
--format F names ({format_names}; --format also gives the format of a
file whose name has no known extension).  Standard input is read once: not
with --trajectory -.
)";

enum class Kind { collide, distance, depth, ddepth };

Point3 vector_option(const Args& a, const std::string& name, const Point3& fallback) {
  auto v = a.value(name);
  if (!v) return fallback;
  std::string why;
  auto p = parse_vector(*v, &why);
  if (!p) throw UsageError(name + ": " + why);
  return *p;
}

std::optional<Quaternion> rotation_option(const Args& a, const std::string& name) {
  auto v = a.value(name);
  if (!v) return std::nullopt;
  std::string why;
  auto q = parse_quaternion(*v, &why);
  if (!q) throw UsageError(name + ": " + why);
  return q;
}

const char* feature_type(FeatureDim dim) {
  return dim == FeatureDim::vertex ? "vertex" : dim == FeatureDim::edge ? "edge" : "facet";
}

std::string feature_json(const Feature& f) {
  return std::string("{\"type\": \"") + feature_type(f.dim) + "\", \"index\": " + std::to_string(f.index) + "}";
}

std::string witness_json(const Witness& w) {
  return "{\"facet\": " + std::to_string(w.facet) + ", \"m\": " + feature_json(w.m) + ", \"p\": " +
         feature_json(w.p) + ", \"q\": " + feature_json(w.q) + "}";
}

std::string witness_text(const Witness& w) {
  return std::string("facet ") + std::to_string(w.facet) + " of M; " + feature_type(w.m.dim) + " " +
         std::to_string(w.m.index) + " of M = " + feature_type(w.p.dim) + " " + std::to_string(w.p.index) +
         " of P ⊕ −(" + feature_type(w.q.dim) + " " + std::to_string(w.q.index) + " of Q)";
}

std::string exact_vector_json(const Point3& p) {
  return "[\"" + format_exact(p.x) + "\", \"" + format_exact(p.y) + "\", \"" + format_exact(p.z) + "\"]";
}
std::string double_vector_json(const Point3& p) {
  return "[" + json_number(to_double(p.x)) + ", " + json_number(to_double(p.y)) + ", " +
         json_number(to_double(p.z)) + "]";
}
std::string vector_text(const Point3& p) {
  return "(" + format_exact(p.x) + ", " + format_exact(p.y) + ", " + format_exact(p.z) + ")";
}

// Answer one query and return its output line (JSON or text, no newline).
std::string answer(TranslationalObstacle& ob, Kind kind, const Point3& u, const Point3& w, const Point3& d,
                   bool json, const char* kind_name) {
  const auto t0 = std::chrono::steady_clock::now();
  std::ostringstream o;
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  switch (kind) {
    case Kind::collide: {
      CollisionResult r = ob.collide(u, w);
      const double sec = seconds();
      if (json)
        o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
          << "\", \"witness\": " << witness_json(r.witness) << ", \"seconds\": " << json_number(sec) << "}";
      else
        o << contact_status_name(r.status) << "  [" << witness_text(r.witness) << "]";
      break;
    }
    case Kind::distance: {
      DistanceResult r = ob.distance(u, w);
      const double sec = seconds();
      if (json)
        o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
          << "\", \"squared_distance\": \"" << format_exact(r.squared_distance)
          << "\", \"distance\": " << json_number(r.distance) << ", \"direction\": " << exact_vector_json(r.direction)
          << ", \"point_p\": " << double_vector_json(r.point_p) << ", \"point_p_exact\": " << exact_vector_json(r.point_p)
          << ", \"point_q\": " << double_vector_json(r.point_q) << ", \"point_q_exact\": " << exact_vector_json(r.point_q)
          << ", \"witness\": " << witness_json(r.witness) << ", \"seconds\": " << json_number(sec) << "}";
      else
        o << contact_status_name(r.status) << "  distance² = " << format_exact(r.squared_distance)
          << "  distance ≈ " << format_double(r.distance) << "  closest points " << vector_text(r.point_p) << " on P, "
          << vector_text(r.point_q) << " on Q  [" << witness_text(r.witness) << "]";
      break;
    }
    case Kind::depth: {
      DepthResult r = ob.penetration_depth(u, w);
      const double sec = seconds();
      if (json)
        o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
          << "\", \"squared_depth\": \"" << format_exact(r.squared_depth) << "\", \"depth\": " << json_number(r.depth)
          << ", \"direction\": " << exact_vector_json(r.direction) << ", \"witness\": " << witness_json(r.witness)
          << ", \"seconds\": " << json_number(sec) << "}";
      else
        o << contact_status_name(r.status) << "  depth² = " << format_exact(r.squared_depth) << "  depth ≈ "
          << format_double(r.depth) << "  translate P by " << vector_text(r.direction) << "  ["
          << witness_text(r.witness) << "]";
      break;
    }
    case Kind::ddepth: {
      DirectionalDepthResult r = ob.directional_depth(u, w, d);
      const double sec = seconds();
      if (json)
        o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status) << "\", \"t\": \""
          << format_exact(r.t) << "\", \"depth\": " << json_number(r.depth)
          << ", \"direction\": " << exact_vector_json(r.translation) << ", \"witness\": " << witness_json(r.witness)
          << ", \"seconds\": " << json_number(sec) << "}";
      else
        o << contact_status_name(r.status) << "  t = " << format_exact(r.t) << "  depth ≈ " << format_double(r.depth)
          << "  translate P by " << vector_text(r.translation) << "  [" << witness_text(r.witness) << "]";
      break;
    }
  }
  return o.str();
}

}  // namespace

int run_query(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "query",
                            {{"--translate-p", "", true}, {"--translate-q", "", true}, {"--rotate-p", "", true},
                             {"--rotate-q", "", true}, {"--direction", "", true}, {"--method", "", true},
                             {"--trajectory", "", true}, {"--json", "", false}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kQueryHelp);
    return 0;
  }
  if (a.positional.size() != 3)
    throw UsageError("'query' needs KIND P Q, KIND one of collide, distance, depth, ddepth (see 'minksum query --help')");
  const std::string kind_name = a.positional[0];
  Kind kind;
  if (kind_name == "collide") kind = Kind::collide;
  else if (kind_name == "distance") kind = Kind::distance;
  else if (kind_name == "depth") kind = Kind::depth;
  else if (kind_name == "ddepth") kind = Kind::ddepth;
  else throw UsageError("unknown query '" + kind_name + "' (collide, distance, depth, ddepth)");

  const Point3 origin(Rational(0), Rational(0), Rational(0));
  const Point3 u = vector_option(a, "--translate-p", origin);
  const Point3 w = vector_option(a, "--translate-q", origin);
  const Point3 d = vector_option(a, "--direction", origin);
  if (kind == Kind::ddepth && !a.value("--direction")) throw UsageError("'query ddepth' needs --direction X,Y,Z");
  if (kind == Kind::ddepth && is_zero(d)) throw UsageError("--direction must not be the zero vector");
  const auto rp = rotation_option(a, "--rotate-p");
  const auto rq = rotation_option(a, "--rotate-q");
  const std::string method_text = a.value_or("--method", "auto");
  auto method = parse_method(method_text);
  if (!method) throw UsageError("unknown method '" + method_text + "'");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) + "' is not implemented in this version of minksum");
  const bool json = a.flag("--json");

  if (a.value("--trajectory") == "-") claim_stdin("the trajectory");
  const auto format = format_option(a);
  const ConvexSet ps = load_set_operand(a.positional[1], false, nullptr, format);
  const ConvexSet qs = load_set_operand(a.positional[2], false, nullptr, format);
  if (!ps.full() || !qs.full()) {  // points, segments, polygons: docs/sweeps.md
    if (rp || rq || a.value("--trajectory"))
      throw UsageError("--rotate-p, --rotate-q and --trajectory take 3-dimensional polytopes only; P or Q is a point, "
                       "a segment or a polygon");
    return query_sets(kind_name, ps, qs, u, w, d, *method, json);
  }
  const ConvexPolytope& p0 = ps.polytope();
  const ConvexPolytope& q0 = qs.polytope();
  TranslationalObstacle ob(rp ? rotated(p0, *rp) : p0, rq ? rotated(q0, *rq) : q0, *method);

  const auto trajectory = a.value("--trajectory");
  if (!trajectory) {
    std::cout << answer(ob, kind, u, w, d, json, kind_name.c_str()) << "\n";
    return 0;
  }

  std::ifstream file;
  std::istream* in = &std::cin;
  const std::string source = *trajectory == "-" ? std::string("<stdin>") : *trajectory;
  if (*trajectory != "-") {
    std::error_code ec;
    if (std::filesystem::is_directory(*trajectory, ec))
      throw InputError(*trajectory, "", "is a directory, not a trajectory file");
    file.open(*trajectory);
    if (!file) throw InputError(*trajectory, "", "cannot open the trajectory file: " + std::string(std::strerror(errno)));
    in = &file;
  }
  std::optional<Quaternion> cur_rp = rp, cur_rq = rq;
  std::string line;
  long line_no = 0, poses = 0;
  double total = 0;
  while (std::getline(*in, line)) {
    ++line_no;
    const auto pose = parse_pose_line(line, source, line_no);
    if (!pose) continue;
    const std::optional<Quaternion> nrp = pose->rp ? pose->rp : cur_rp, nrq = pose->rq ? pose->rq : cur_rq;
    if (nrp != cur_rp || nrq != cur_rq) {
      ob.set_operands(nrp ? rotated(p0, *nrp) : p0, nrq ? rotated(q0, *nrq) : q0);
      cur_rp = nrp, cur_rq = nrq;
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::string out = answer(ob, kind, pose->p, pose->q.value_or(w), d, json, kind_name.c_str());
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++poses;
    if (json) std::cout << out << "\n";
    else std::cout << "pose " << poses << " (line " << line_no << "): " << out << "\n";
    // A failed write stops the run at once (exit 1), not after the whole trajectory.
    if (!std::cout) check_stdout();
  }
  if (in->bad()) throw InputError(source, "line " + std::to_string(line_no + 1), "read error");
  if (!json && poses > 0) {
    char us[32];
    std::snprintf(us, sizeof us, "%.2f", total / double(poses) * 1e6);
    std::cout << poses << " poses, " << us << " µs per query, "
              << ob.stats().walk_steps << " walk steps, " << ob.stats().full_scans << " full scans, "
              << ob.stats().rebuilds << " computations of M\n";
  }
  return 0;
}

}  // namespace minksum::cli
