// minksum query collide|distance|depth|ddepth P Q: exact proximity queries
// under translation (Fogel and Halperin 2006, §4), one pose or a trajectory of poses.
#include <minksum/io.hpp>
#include <minksum/operand.hpp>
#include <minksum/proximity.hpp>
#include <minksum/rigid_proximity.hpp>

#include <chrono>
#include <cmath>
#include <optional>
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
#include "proximity_json.hpp"
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
  --hull                take the exact convex hull of each operand's points
                        instead of requiring a valid convex mesh (a robot's
                        collision mesh that is not exactly convex, a point
                        cloud, a non-convex solid of the catalog)
  --trajectory FILE     read one pose per line from FILE ('-': stdin) and
                        answer the query for each, reusing the previous
                        answer as the start of the next (coherence).  A line
                        is "PX,PY,PZ [QX,QY,QZ] [rp=A,B,C,D] [rq=A,B,C,D]":
                        the translation of P, optionally of Q (else
                        --translate-q), optional rotations of P and Q relative
                        to their input orientation.  Blank lines and lines
                        starting with '#' are skipped.  Output: one line (or
                        JSON object) per pose.
                        The poses are answered in batches (the library's
                        trajectory API: up to 4096 poses, or as many as the
                        input has ready); seconds is then the batch's query
                        time per pose (exact values are computed when
                        printed).
  Under a rotation (--rotate-p, --rotate-q, or rp=/rq= in effect on a
  trajectory line) every query is answered on the placed bodies without
  computing M (exact, certified: a separating plane, a
  tetrahedron of P − Q holding the origin, closest points whose planes
  support both bodies, a closed star of triangles of P − Q around the origin
  whose nearest plane supports it, the triangle of P − Q the ray leaves by,
  or M built exactly where the search cannot decide — touching poses); the
  answer names its certificate instead of a facet of M.
  --json                print JSON: query, status, squared_distance /
                        squared_depth / t as exact rationals in strings
                        ("p/q" or an integer), distance / depth (double;
                        null when beyond the double range: JSON has no
                        infinity), direction (exact strings), point_p /
                        point_q (doubles) and point_p_exact / point_q_exact
                        (exact strings) for distance, witness (or
                        certificate under a rotation), seconds

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

std::string witness_text(const Witness& w) {
  return std::string("facet ") + std::to_string(w.facet) + " of M; " + feature_type(w.m.dim) + " " +
         std::to_string(w.m.index) + " of M = " + feature_type(w.p.dim) + " " + std::to_string(w.p.index) +
         " of P ⊕ −(" + feature_type(w.q.dim) + " " + std::to_string(w.q.index) + " of Q)";
}

std::string vector_text(const Point3& p) {
  return "(" + format_exact(p.x) + ", " + format_exact(p.y) + ", " + format_exact(p.z) + ")";
}

// The output line of one answer (JSON or text, no newline); `sec` is the
// query's time.  The exact values of distance and depth answers are
// computed here, on first use (DistanceResult, DepthResult); u is added to
// the closest points of an answer given for s = w − u.
std::string format_answer(const CollisionResult& r, double sec, bool json, const char* kind_name) {
  std::ostringstream o;
  if (json)
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
      << "\", \"witness\": " << witness_json(r.witness) << ", \"seconds\": " << json_number(sec) << "}";
  else
    o << contact_status_name(r.status) << "  [" << witness_text(r.witness) << "]";
  return o.str();
}

std::string format_answer(const DistanceResult& r, const Point3& u, double sec, bool json, const char* kind_name) {
  std::ostringstream o;
  const Point3 pp = r.point_p() + u, pq = r.point_q() + u;
  if (json)
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
      << "\", \"squared_distance\": \"" << format_exact(r.squared_distance())
      << "\", \"distance\": " << json_number(r.distance()) << ", \"direction\": " << exact_vector_json(r.direction())
      << ", \"point_p\": " << double_vector_json(pp) << ", \"point_p_exact\": " << exact_vector_json(pp)
      << ", \"point_q\": " << double_vector_json(pq) << ", \"point_q_exact\": " << exact_vector_json(pq)
      << ", \"witness\": " << witness_json(r.witness) << ", \"seconds\": " << json_number(sec) << "}";
  else
    o << contact_status_name(r.status) << "  distance² = " << format_exact(r.squared_distance())
      << "  distance ≈ " << format_double(r.distance()) << "  closest points " << vector_text(pp) << " on P, "
      << vector_text(pq) << " on Q  [" << witness_text(r.witness) << "]";
  return o.str();
}

std::string format_answer(const DepthResult& r, double sec, bool json, const char* kind_name) {
  std::ostringstream o;
  if (json)
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status)
      << "\", \"squared_depth\": \"" << format_exact(r.squared_depth()) << "\", \"depth\": " << json_number(r.depth())
      << ", \"direction\": " << exact_vector_json(r.direction()) << ", \"witness\": " << witness_json(r.witness)
      << ", \"seconds\": " << json_number(sec) << "}";
  else
    o << contact_status_name(r.status) << "  depth² = " << format_exact(r.squared_depth()) << "  depth ≈ "
      << format_double(r.depth()) << "  translate P by " << vector_text(r.direction()) << "  ["
      << witness_text(r.witness) << "]";
  return o.str();
}

std::string format_answer(const DirectionalDepthResult& r, double sec, bool json, const char* kind_name) {
  std::ostringstream o;
  if (json)
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r.status) << "\", \"t\": \""
      << format_exact(r.t) << "\", \"depth\": " << json_number(r.depth)
      << ", \"direction\": " << exact_vector_json(r.translation) << ", \"witness\": " << witness_json(r.witness)
      << ", \"seconds\": " << json_number(sec) << "}";
  else
    o << contact_status_name(r.status) << "  t = " << format_exact(r.t) << "  depth ≈ " << format_double(r.depth)
      << "  translate P by " << vector_text(r.translation) << "  [" << witness_text(r.witness) << "]";
  return o.str();
}

// The output line of an answer under rigid motion (collide or distance).
std::string format_rigid(ContactStatus status, const char* certificate, const RigidDistanceExact* e, double sec,
                         bool json, const char* kind_name) {
  std::ostringstream o;
  if (json) {
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(status) << "\"";
    if (e) {
      const double dist = std::sqrt(to_double(e->squared_distance));
      o << ", \"squared_distance\": \"" << format_exact(e->squared_distance) << "\", \"distance\": "
        << json_number(dist) << ", \"direction\": " << exact_vector_json(e->point_q - e->point_p)
        << ", \"point_p\": " << double_vector_json(e->point_p) << ", \"point_p_exact\": "
        << exact_vector_json(e->point_p) << ", \"point_q\": " << double_vector_json(e->point_q)
        << ", \"point_q_exact\": " << exact_vector_json(e->point_q);
    }
    o << ", \"certificate\": \"" << certificate << "\", \"seconds\": " << json_number(sec) << "}";
  } else {
    o << contact_status_name(status);
    if (e)
      o << "  distance² = " << format_exact(e->squared_distance) << "  distance ≈ "
        << format_double(std::sqrt(to_double(e->squared_distance))) << "  closest points "
        << vector_text(e->point_p) << " on P, " << vector_text(e->point_q) << " on Q";
    o << "  [certificate: " << certificate
      << (std::string(certificate) == "exact" ? ", M built exactly for this pose]" : ", without M]");
  }
  return o.str();
}

std::string format_rigid_depth(ContactStatus status, const char* certificate, const RigidDepthExact& e, double sec,
                               bool json, const char* kind_name) {
  std::ostringstream o;
  const double depth = std::sqrt(to_double(e.squared_depth));
  if (json)
    o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(status)
      << "\", \"squared_depth\": \"" << format_exact(e.squared_depth) << "\", \"depth\": " << json_number(depth)
      << ", \"direction\": " << exact_vector_json(e.direction) << ", \"certificate\": \"" << certificate
      << "\", \"seconds\": " << json_number(sec) << "}";
  else
    o << contact_status_name(status) << "  depth² = " << format_exact(e.squared_depth) << "  depth ≈ "
      << format_double(depth) << "  translate P by " << vector_text(e.direction) << "  [certificate: " << certificate
      << (std::string(certificate) == "exact" ? ", M built exactly for this pose]" : ", without M]");
  return o.str();
}

// The answers for rigid poses (collide, distance or depth), one line each:
// the library's batch over the poses on the calling thread, warm-started
// from pose to pose.
std::vector<std::string> answer_rigid(const RigidBody& bp, const RigidBody& bq, Kind kind,
                                      const std::vector<RigidPose>& pp, const std::vector<RigidPose>& pq,
                                      const Point3& d, bool json, const char* kind_name, double& total,
                                      RigidWarmStart& warm) {
  std::vector<std::string> lines(pp.size());
  const auto t0 = std::chrono::steady_clock::now();
  auto per_query = [&] {
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total += sec;
    return pp.empty() ? 0.0 : sec / double(pp.size());
  };
  if (kind == Kind::collide) {
    std::vector<RigidCollision> r(pp.size());
    for (std::size_t i = 0; i < pp.size(); ++i) r[i] = collide(bp, pp[i], bq, pq[i], &warm);
    const double sec = per_query();
    for (std::size_t i = 0; i < pp.size(); ++i)
      lines[i] = format_rigid(r[i].status, rigid_certificate_name(r[i].certificate), nullptr, sec, json, kind_name);
  } else if (kind == Kind::ddepth) {
    std::vector<RigidDirectionalDepth> r(pp.size());
    for (std::size_t i = 0; i < pp.size(); ++i) r[i] = directional_depth(bp, pp[i], bq, pq[i], d, &warm);
    const double sec = per_query();
    for (std::size_t i = 0; i < pp.size(); ++i) {
      const Rational t = exact_values(bp, pp[i], bq, pq[i], d, r[i]);
      const Point3 move = t * d;
      const double depth = std::sqrt(to_double(dot(move, move)));
      const char* cert = rigid_certificate_name(r[i].certificate);
      std::ostringstream o;
      if (json)
        o << "{\"query\": \"" << kind_name << "\", \"status\": \"" << contact_status_name(r[i].status)
          << "\", \"t\": \"" << format_exact(t) << "\", \"depth\": " << json_number(depth)
          << ", \"direction\": " << exact_vector_json(move) << ", \"certificate\": \"" << cert
          << "\", \"seconds\": " << json_number(sec) << "}";
      else
        o << contact_status_name(r[i].status) << "  t = " << format_exact(t) << "  depth ≈ " << format_double(depth)
          << "  translate P by " << vector_text(move) << "  [certificate: " << cert
          << (std::string(cert) == "exact" ? ", M built exactly for this pose]" : ", without M]");
      lines[i] = o.str();
    }
  } else if (kind == Kind::depth) {
    std::vector<RigidDepth> r(pp.size());
    for (std::size_t i = 0; i < pp.size(); ++i) r[i] = penetration_depth(bp, pp[i], bq, pq[i], &warm);
    const double sec = per_query();
    for (std::size_t i = 0; i < pp.size(); ++i) {
      const RigidDepthExact e = exact_values(bp, pp[i], bq, pq[i], r[i]);
      lines[i] = format_rigid_depth(r[i].status, rigid_certificate_name(r[i].certificate), e, sec, json, kind_name);
    }
  } else {
    std::vector<RigidDistance> r(pp.size());
    for (std::size_t i = 0; i < pp.size(); ++i) r[i] = distance(bp, pp[i], bq, pq[i], &warm);
    const double sec = per_query();
    for (std::size_t i = 0; i < pp.size(); ++i) {
      const RigidDistanceExact e = exact_values(bp, pp[i], bq, pq[i], r[i]);
      lines[i] = format_rigid(r[i].status, rigid_certificate_name(r[i].certificate), &e, sec, json, kind_name);
    }
  }
  return lines;
}

// The answers for the poses (u[i], w[i]) in order, one line each, through
// the library's trajectory API (one batch: the walks carry their witnesses
// from pose to pose).  `seconds` is the batch's query time over its size.
std::vector<std::string> answer_batch(TranslationalObstacle& ob, Kind kind, const std::vector<Point3>& u,
                                      const std::vector<Point3>& w, const Point3& d, bool json,
                                      const char* kind_name, double& total) {
  std::vector<Point3> s(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) s[i] = w[i] - u[i];
  std::vector<std::string> lines(u.size());
  const auto t0 = std::chrono::steady_clock::now();
  auto per_query = [&] {
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total += sec;
    return s.empty() ? 0.0 : sec / double(s.size());
  };
  switch (kind) {
    case Kind::collide: {
      std::vector<CollisionResult> r;
      ob.collide_points(s, r);
      const double sec = per_query();
      for (std::size_t i = 0; i < s.size(); ++i) lines[i] = format_answer(r[i], sec, json, kind_name);
      break;
    }
    case Kind::distance: {
      std::vector<DistanceResult> r;
      ob.distance_points(s, r);
      const double sec = per_query();
      for (std::size_t i = 0; i < s.size(); ++i) lines[i] = format_answer(r[i], u[i], sec, json, kind_name);
      break;
    }
    case Kind::depth: {
      std::vector<DepthResult> r;
      ob.penetration_depth_points(s, r);
      const double sec = per_query();
      for (std::size_t i = 0; i < s.size(); ++i) lines[i] = format_answer(r[i], sec, json, kind_name);
      break;
    }
    case Kind::ddepth: {
      std::vector<DirectionalDepthResult> r;
      r.reserve(s.size());
      for (const Point3& si : s) r.push_back(ob.directional_depth_point(si, d));
      const double sec = per_query();
      for (std::size_t i = 0; i < s.size(); ++i) lines[i] = format_answer(r[i], sec, json, kind_name);
      break;
    }
  }
  return lines;
}

}  // namespace

int run_query(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "query",
                            {{"--translate-p", "", true}, {"--translate-q", "", true}, {"--rotate-p", "", true},
                             {"--rotate-q", "", true}, {"--direction", "", true}, {"--method", "", true},
                             {"--trajectory", "", true}, {"--json", "", false}, {"--hull", "", false}, kFormatOption});
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
  const bool hull = a.flag("--hull");
  const ConvexSet ps = load_set_operand(a.positional[1], hull, nullptr, format);
  const ConvexSet qs = load_set_operand(a.positional[2], hull, nullptr, format);
  if (!ps.full() || !qs.full()) {  // points, segments, polygons: docs/sweeps.md
    if (rp || rq || a.value("--trajectory"))
      throw UsageError("--rotate-p, --rotate-q and --trajectory take 3-dimensional polytopes only; P or Q is a point, "
                       "a segment or a polygon");
    return query_sets(kind_name, ps, qs, u, w, d, *method, json);
  }
  const ConvexPolytope& p0 = ps.polytope();
  const ConvexPolytope& q0 = qs.polytope();
  // collide and distance under a rotation: on the placed bodies (no M).
  const bool rigid_kind = true;  // every kind is answered on the placed bodies under a rotation
  std::optional<RigidBody> bp, bq;
  const auto rigid_pose = [](const std::optional<Quaternion>& r, const Point3& t) {
    return r ? RigidPose::quaternion(*r, t) : RigidPose::translation(t);
  };
  // M for the current rotations, computed on first need.
  std::optional<TranslationalObstacle> ob;
  std::optional<Quaternion> ob_rp = rp, ob_rq = rq;
  const auto obstacle = [&](const std::optional<Quaternion>& r1, const std::optional<Quaternion>& r2)
      -> TranslationalObstacle& {
    if (!ob) ob.emplace(r1 ? rotated(p0, *r1) : p0, r2 ? rotated(q0, *r2) : q0, *method);
    else if (r1 != ob_rp || r2 != ob_rq) ob->set_operands(r1 ? rotated(p0, *r1) : p0, r2 ? rotated(q0, *r2) : q0);
    ob_rp = r1, ob_rq = r2;
    return *ob;
  };
  const auto rigid_for = [&](const std::optional<Quaternion>& r1, const std::optional<Quaternion>& r2) {
    if (!rigid_kind || (!r1 && !r2)) return false;
    if (!bp) bp.emplace(p0), bq.emplace(q0);
    return true;
  };
  RigidWarmStart warm;

  const auto trajectory = a.value("--trajectory");
  if (!trajectory) {
    double total = 0;
    if (rigid_for(rp, rq))
      std::cout << answer_rigid(*bp, *bq, kind, {rigid_pose(rp, u)}, {rigid_pose(rq, w)}, d, json, kind_name.c_str(),
                                total, warm)[0]
                << "\n";
    else
      std::cout << answer_batch(obstacle(rp, rq), kind, {u}, {w}, d, json, kind_name.c_str(), total)[0] << "\n";
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
  // Poses are answered in batches (the trajectory API): a batch ends at a
  // change of rotation, after kBatch poses, and whenever the input has no
  // more characters ready (so a pipe fed pose by pose is answered pose by
  // pose).
  constexpr std::size_t kBatch = 4096;
  std::vector<Point3> bu, bw;
  std::vector<long> blines;
  std::uint64_t rigid_poses = 0;
  const RigidStats rigid_before = rigid_stats();
  auto flush = [&] {
    std::vector<std::string> out;
    if (bu.empty()) {
    } else if (rigid_for(cur_rp, cur_rq)) {
      std::vector<RigidPose> pp, pq;
      for (std::size_t i = 0; i < bu.size(); ++i)
        pp.push_back(rigid_pose(cur_rp, bu[i])), pq.push_back(rigid_pose(cur_rq, bw[i]));
      out = answer_rigid(*bp, *bq, kind, pp, pq, d, json, kind_name.c_str(), total, warm);
      rigid_poses += bu.size();
    } else {
      out = answer_batch(obstacle(cur_rp, cur_rq), kind, bu, bw, d, json, kind_name.c_str(), total);
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
      ++poses;
      if (json) std::cout << out[i] << "\n";
      else std::cout << "pose " << poses << " (line " << blines[i] << "): " << out[i] << "\n";
      // A failed write stops the run at once (exit 1), not after the whole trajectory.
      if (!std::cout) check_stdout();
    }
    if (!out.empty()) std::cout.flush();
    if (!std::cout) check_stdout();
    bu.clear(), bw.clear(), blines.clear();
  };
  while (std::getline(*in, line)) {
    ++line_no;
    decltype(parse_pose_line(line, source, line_no)) pose;
    try {
      pose = parse_pose_line(line, source, line_no);
    } catch (...) {
      flush();  // the poses before a bad line are answered, as they would be one by one
      throw;
    }
    if (pose) {
      const std::optional<Quaternion> nrp = pose->rp ? pose->rp : cur_rp, nrq = pose->rq ? pose->rq : cur_rq;
      if (nrp != cur_rp || nrq != cur_rq) {
        flush();
        cur_rp = nrp, cur_rq = nrq;
      }
      bu.push_back(pose->p);
      bw.push_back(pose->q.value_or(w));
      blines.push_back(line_no);
    }
    if (bu.size() >= kBatch || in->rdbuf()->in_avail() <= 0) flush();
  }
  flush();
  if (in->bad()) throw InputError(source, "line " + std::to_string(line_no + 1), "read error");
  if (!json && poses > 0) {
    char us[32];
    std::snprintf(us, sizeof us, "%.2f", total / double(poses) * 1e6);
    std::cout << poses << " poses, " << us << " µs per query";
    if (ob)
      std::cout << ", " << ob->stats().walk_steps << " walk steps, " << ob->stats().full_scans << " full scans, "
                << ob->stats().rebuilds << " computations of M";
    if (rigid_poses > 0) {
      const RigidStats st = rigid_stats();
      const std::uint64_t on_m = st.exact - rigid_before.exact;
      std::cout << ", " << rigid_poses << " under rotation (" << rigid_poses - on_m << " certified without M, "
                << on_m << " on M built exactly)";
    }
    std::cout << "\n";
  }
  return 0;
}

}  // namespace minksum::cli
