// The rotation section of bench_proximity: collision and separation
// distance of two placed convex polytopes (minksum::collide and
// minksum::distance on RigidBody / RigidPose, no M built per pose) against
// FCL's collide and distance (libccd GJK solver) on the same poses, every
// answer checked against the exact status and the exact squared distance.
//
//   bench_proximity --rotation [--poses N] [--meshes DIR]
//
// Poses: P and Q each get a random rotation (the doubles of a random unit
// quaternion, taken exactly as given); for each of K orientation pairs the
// exact M = R_P P ⊕ (−R_Q Q) is built once (for the poses' exact statuses
// and the exact contact translations, not by the timed query), and Q is
// translated by s = c + f·α*·u, c the interior point of M, u a random
// direction (doubles), α* the exact exit parameter of the ray: f = 1.5
// separated, 1 touching (s exact, a rational: FCL gets its nearest doubles),
// 1 ± 1e-9 near-touching (s rounded to doubles), 0.5 penetrating.  The
// distance table takes the separated and near-touching-out poses of the
// collision table; the exact squared distance of a pose is that of the
// orientation pair's TranslationalObstacle at s.
#include "rotation.hpp"

#include "fcl_convex.hpp"

#ifdef MINKSUM_HAVE_FCL
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/proximity.hpp>
#include <minksum/rigid_proximity.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace minksum;

namespace {

using Clock = std::chrono::steady_clock;

#ifdef MINKSUM_HAVE_FCL
fcl::Transform3d transform(const std::array<double, 9>& r, const Vec3d& t) {
  fcl::Transform3d x = fcl::Transform3d::Identity();
  fcl::Matrix3d m;
  m << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  x.linear() = m;
  x.translation() = fcl::Vector3d(t.x, t.y, t.z);
  return x;
}
#endif

struct Pose {
  int orientation;
  RigidPose q;
  Point3 s;  // its translation
  Vec3d t;   // s in doubles (FCL's input)
  ContactStatus exact;
};

double us(Clock::time_point t0, std::size_t n) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / double(n);
}

#ifdef MINKSUM_HAVE_FCL
// FCL's distance request of the translation tables (bench_proximity.cpp):
// the libccd solver, signed distance, nearest points.
fcl::DistanceRequestd fcl_distance_request() {
  fcl::DistanceRequestd r;
  r.gjk_solver_type = fcl::GST_LIBCCD;
  r.enable_signed_distance = true;
  r.enable_nearest_points = true;
  return r;
}

// An FCL distance d_F of a pose with exact squared distance sq (d = √ of
// the nearest double of sq) is wrong when the pose is separate and
// |d_F − d| > 1e-9·max(1, d), or when it is not separate and d_F > 1e-9
// (FCL reports a separation).
bool fcl_distance_wrong(double fcl, const Rational& sq) {
  if (sgn(sq) == 0) return fcl > 1e-9;
  const double d = std::sqrt(to_double(sq));
  return std::fabs(fcl - d) > 1e-9 * std::max(1.0, d);
}
#endif

// printf into a string (the distance table's rows, printed after the
// collision table).
template <class... A>
std::string format(const char* f, A... a) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}

}  // namespace

std::array<double, 9> random_rotation(std::mt19937_64& g) {
  std::normal_distribution<double> n(0, 1);
  double a = n(g), b = n(g), c = n(g), d = n(g);
  const double l = std::sqrt(a * a + b * b + c * c + d * d);
  a /= l, b /= l, c /= l, d /= l;
  return {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
          2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
          2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d};
}

std::vector<RotationPair> rotation_pairs(const std::string& meshes) {
  std::vector<RotationPair> pairs;
  for (const auto& [a, b] : std::vector<std::pair<const char*, const char*>>{{"cube", "cube"},
                                                                              {"sphere:2", "sphere:2"},
                                                                              {"random:50:1", "random:50:2"},
                                                                              {"random:500:1", "random:350:2"},
                                                                              {"sphere:4", "sphere:4"}})
    pairs.push_back({a, b, catalog_polytope(a), catalog_polytope(b), a, b, false});
  if (!meshes.empty()) {
    const auto hull = [&](const std::string& f) {
      const std::string path = (std::filesystem::path(meshes) / f).string();
      return ConvexPolytope::hull(read_mesh(path).points, path);
    };
    for (const auto& [a, b] : std::vector<std::pair<const char*, const char*>>{
             {"ur5e_forearm.stl", "ur5e_upperarm.stl"}, {"ur5e_upperarm.stl", "franka_link1.stl"},
             {"franka_link1.stl", "ur5e_forearm.stl"}}) {
      if (!std::filesystem::exists(std::filesystem::path(meshes) / a) ||
          !std::filesystem::exists(std::filesystem::path(meshes) / b))
        continue;
      pairs.push_back({std::string("hull of ") + a, std::string("hull of ") + b, hull(a), hull(b),
                       (std::filesystem::path(meshes) / a).string(), (std::filesystem::path(meshes) / b).string(), true});
    }
  }
  return pairs;
}

int rotation_section(int argc, char** argv) {
  std::size_t poses = 100000;
  std::string meshes;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--poses") poses = std::strtoul(argv[i + 1], nullptr, 10);
    if (std::string(argv[i]) == "--meshes") meshes = argv[i + 1];
  }
  const std::vector<RotationPair> pairs = rotation_pairs(meshes);
  struct Config {
    const char* name;
    double f;
    bool distance;  // a row of the distance table too
    bool depth;     // a row of the depth table too
  } configs[] = {{"separated", 1.5, true, false},
                 {"touching", 1.0, false, false},
                 {"near-touching out", 1 + 1e-9, true, false},
                 {"near-touching in", 1 - 1e-9, false, true},
                 {"penetrating", 0.5, false, true}};
  const std::size_t orientations = 16;
  // Touching poses (exact rational translations) are decided by the feature
  // plane's exact stage, tens of microseconds each: fewer of them.
  const std::size_t touching_poses = std::min<std::size_t>(poses, 1000);

  std::printf("## Collision, distance and depth under rigid motion: exact minksum (no M per pose) vs FCL\n\n");
  std::printf("bench_proximity --rotation --poses %zu%s%s: per pair, %zu orientation pairs (random rotations of\n"
              "P and Q as double matrices, taken exactly), Q translated by s = c + f·α*·u (u random; f = 1.5\n"
              "separated, 1 touching with s exact, 1 ± 1e-9 near-touching, 0.5 penetrating).  %zu poses per\n"
              "configuration (%zu touching).  Times in µs per query over different poses; 'ours' warm-starts\n"
              "each query from the previous pose's witnesses.  Wrong: status differs from the exact one\n"
              "(FCL: intersecting or not, touching counted as intersecting).\n\n",
              poses, meshes.empty() ? "" : " --meshes ", meshes.empty() ? "" : "DIR", orientations, poses, touching_poses);
#ifdef MINKSUM_HAVE_FCL
  std::printf("| pair | vertices | configuration | ours µs | FCL µs | FCL/ours | ours exact-path poses | ours wrong | FCL wrong |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|\n");
#else
  std::printf("| pair | vertices | configuration | ours µs | ours exact-path poses | ours wrong |\n");
  std::printf("|---|---|---|---:|---:|---:|\n");
#endif
  std::mt19937_64 g(20261202);
  std::vector<std::string> distance_rows, depth_rows;
  for (const RotationPair& pr : pairs) {
    const RigidBody bp(pr.p), bq(pr.q);
    std::vector<std::array<double, 9>> rp, rq;
    std::vector<std::unique_ptr<TranslationalObstacle>> obs;
    for (std::size_t k = 0; k < orientations; ++k) {
      rp.push_back(random_rotation(g));
      rq.push_back(random_rotation(g));
      const PlacedMap mp(rp.back(), Vec3d{0, 0, 0}), mq(rq.back(), Vec3d{0, 0, 0});
      obs.push_back(std::make_unique<TranslationalObstacle>(placed_linear(pr.p, mp), placed_linear(pr.q, mq)));
    }
    std::vector<RigidPose> pose_p;
    for (std::size_t k = 0; k < orientations; ++k) pose_p.push_back(RigidPose::matrix(rp[k], Vec3d{0, 0, 0}));
#ifdef MINKSUM_HAVE_FCL
    fcl::CollisionObjectd fa(fcl_convex(pr.p)), fb(fcl_convex(pr.q));
    fcl::CollisionRequestd req;
    req.gjk_solver_type = fcl::GST_LIBCCD;
    const fcl::DistanceRequestd dreq = fcl_distance_request();
    const auto place_fcl = [&](const Pose& x) {  // FCL's objects at pose x
      fa.setTransform(transform(rp[x.orientation], Vec3d{0, 0, 0}));
      fb.setTransform(transform(rq[x.orientation], x.t));
    };
#endif
    std::normal_distribution<double> nd(0, 1);
    for (const Config& cf : configs) {
      const bool touching = cf.f == 1.0;
      const std::size_t n = touching ? touching_poses : poses;
      std::vector<Pose> ps;
      ps.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        const int k = int(i % orientations);
        TranslationalObstacle& ob = *obs[k];
        const Point3 u(nd(g), nd(g), nd(g));
        const Point3 c = ob.interior_point();
        const Rational alpha = ob.directional_depth_point(c, -u).t;
        Point3 s = c + (alpha * Rational(cf.f)) * u;
        if (!touching) s = Point3(to_double(s.x), to_double(s.y), to_double(s.z));
        ps.push_back({k, RigidPose::matrix(rq[k], s), s, to_double(s), ob.collide_point(s).status});
      }
      std::size_t wrong = 0;
      const RigidStats before = rigid_stats();
      RigidWarmStart warm;
      std::vector<RigidCollision> out(n);
      auto t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) out[i] = collide(bp, pose_p[ps[i].orientation], bq, ps[i].q, &warm);
      const double ours = us(t0, n);
      for (std::size_t i = 0; i < n; ++i) wrong += out[i].status != ps[i].exact;
      const std::uint64_t exact_path = rigid_stats().exact - before.exact;
#ifdef MINKSUM_HAVE_FCL
      std::size_t fcl_wrong = 0;
      std::vector<char> hit(n);
      t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) {
        place_fcl(ps[i]);
        fcl::CollisionResultd r;
        fcl::collide(&fa, &fb, req, r);
        hit[i] = r.isCollision();
      }
      const double fcl_us = us(t0, n);
      for (std::size_t i = 0; i < n; ++i) fcl_wrong += bool(hit[i]) != (ps[i].exact != ContactStatus::separate);
      std::printf("| %s / %s | %u / %u | %s | %.3g | %.3g | %.2f | %llu | %zu | %zu |\n", pr.name_p.c_str(),
                  pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(), cf.name, ours, fcl_us, fcl_us / ours,
                  (unsigned long long)exact_path, wrong, fcl_wrong);
#else
      std::printf("| %s / %s | %u / %u | %s | %.3g | %llu | %zu |\n", pr.name_p.c_str(), pr.name_q.c_str(),
                  pr.p.num_vertices(), pr.q.num_vertices(), cf.name, ours, (unsigned long long)exact_path, wrong);
#endif
      std::fflush(stdout);
      if (cf.depth) {
        // Penetration depth on the same poses: the exact squared depth of
        // each from the orientation pair's obstacle (not timed).
        std::vector<Rational> exact_sq(n);
        for (std::size_t i = 0; i < n; ++i)
          exact_sq[i] = obs[ps[i].orientation]->penetration_depth_point(ps[i].s).squared_depth();
        std::vector<RigidDepth> dep(n);
        RigidWarmStart pwarm;
        t0 = Clock::now();
        for (std::size_t i = 0; i < n; ++i)
          dep[i] = penetration_depth(bp, pose_p[ps[i].orientation], bq, ps[i].q, &pwarm);
        const double ours_p = us(t0, n);
        std::size_t p_wrong = 0, p_exact_path = 0;
        for (std::size_t i = 0; i < n; ++i) {
          p_wrong += exact_values(bp, pose_p[ps[i].orientation], bq, ps[i].q, dep[i]).squared_depth != exact_sq[i];
          p_exact_path += dep[i].certificate == RigidCertificate::exact;
        }
#ifdef MINKSUM_HAVE_FCL
        fcl::CollisionRequestd creq;
        creq.gjk_solver_type = fcl::GST_LIBCCD;
        creq.enable_contact = true;
        creq.num_max_contacts = 1;
        std::vector<double> fdep(n, 0.0);
        t0 = Clock::now();
        for (std::size_t i = 0; i < n; ++i) {
          place_fcl(ps[i]);
          fcl::CollisionResultd r;
          fcl::collide(&fa, &fb, creq, r);
          if (r.numContacts() > 0) fdep[i] = r.getContact(0).penetration_depth;
        }
        const double fcl_p = us(t0, n);
        std::size_t fcl_p_wrong = 0;
        for (std::size_t i = 0; i < n; ++i) {
          const double d = std::sqrt(to_double(exact_sq[i]));
          fcl_p_wrong += std::fabs(fdep[i] - d) > 1e-9 * std::max(1.0, d);
        }
        depth_rows.push_back(format("| %s / %s | %u / %u | %s | %.3g | %.3g | %.2f | %zu | %zu | %zu |\n",
                                    pr.name_p.c_str(), pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(),
                                    cf.name, ours_p, fcl_p, fcl_p / ours_p, p_exact_path, p_wrong, fcl_p_wrong));
#else
        depth_rows.push_back(format("| %s / %s | %u / %u | %s | %.3g | %zu | %zu |\n", pr.name_p.c_str(),
                                    pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(), cf.name, ours_p,
                                    p_exact_path, p_wrong));
#endif
      }
      if (!cf.distance) continue;

      // Distance on the same poses: the exact squared distance of each from
      // the orientation pair's obstacle (not timed).
      std::vector<Rational> exact_sq(n);
      for (std::size_t i = 0; i < n; ++i)
        exact_sq[i] = obs[ps[i].orientation]->distance_point(ps[i].s).squared_distance();
      std::vector<RigidDistance> dist(n);
      RigidWarmStart dwarm;
      t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) dist[i] = distance(bp, pose_p[ps[i].orientation], bq, ps[i].q, &dwarm);
      const double ours_d = us(t0, n);
      std::vector<Rational> ours_sq(n);
      RigidWarmStart ewarm;
      t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) {
        const RigidDistance d = distance(bp, pose_p[ps[i].orientation], bq, ps[i].q, &ewarm);
        ours_sq[i] = exact_values(bp, pose_p[ps[i].orientation], bq, ps[i].q, d).squared_distance;
      }
      const double ours_de = us(t0, n);
      std::size_t d_wrong = 0, d_exact_path = 0;
      for (std::size_t i = 0; i < n; ++i) {
        d_wrong += ours_sq[i] != exact_sq[i] || (dist[i].status == ContactStatus::separate) != (sgn(exact_sq[i]) > 0);
        d_exact_path += dist[i].certificate == RigidCertificate::exact;
      }
#ifdef MINKSUM_HAVE_FCL
      std::vector<double> fd(n);
      t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) {
        place_fcl(ps[i]);
        fcl::DistanceResultd r;
        fcl::distance(&fa, &fb, dreq, r);
        fd[i] = r.min_distance;
      }
      const double fcl_d = us(t0, n);
      std::size_t fcl_d_wrong = 0;
      for (std::size_t i = 0; i < n; ++i) fcl_d_wrong += fcl_distance_wrong(fd[i], exact_sq[i]);
      distance_rows.push_back(format("| %s / %s | %u / %u | %s | %.3g | %.3g | %.3g | %.2f | %zu | %zu | %zu |\n",
                                     pr.name_p.c_str(), pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(),
                                     cf.name, ours_d, ours_de, fcl_d, fcl_d / ours_d, d_exact_path, d_wrong,
                                     fcl_d_wrong));
#else
      distance_rows.push_back(format("| %s / %s | %u / %u | %s | %.3g | %.3g | %zu | %zu |\n", pr.name_p.c_str(),
                                     pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(), cf.name, ours_d,
                                     ours_de, d_exact_path, d_wrong));
#endif
    }
  }

  std::printf("\nSeparation distance, on the separated and near-touching-out poses above: 'ours' is\n"
              "minksum::distance warm-started from the previous pose (a certified enclosure and closest\n"
              "points in doubles); '+ exact' adds exact_values (the exact squared distance and closest\n"
              "points, rationals).  Ours wrong: the exact squared distance from exact_values differs\n"
              "from that of the orientation pair's TranslationalObstacle at s, or the status differs.\n"
#ifdef MINKSUM_HAVE_FCL
              "FCL: fcl::distance with the libccd solver, signed distance and nearest points (the\n"
              "translation tables' request); wrong when |FCL distance - d| > 1e-9·max(1, d), d the exact\n"
              "distance (the square root of the nearest double of its square).\n\n"
              "| pair | vertices | configuration | ours µs | ours + exact µs | FCL µs | FCL/ours | ours exact-path poses | ours wrong | FCL wrong |\n"
              "|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
#else
              "\n| pair | vertices | configuration | ours µs | ours + exact µs | ours exact-path poses | ours wrong |\n"
              "|---|---|---|---:|---:|---:|---:|\n");
#endif
  for (const std::string& r : distance_rows) std::fputs(r.c_str(), stdout);
  std::printf("\nPenetration depth, on the near-touching-in and penetrating poses above: 'ours' is\n"
              "minksum::penetration_depth warm-started from the previous pose (status, a certified enclosure\n"
              "of the depth and the facet pairs; EPA certified exactly, no M).  Ours wrong: the exact squared\n"
              "depth from exact_values differs from that of the orientation pair's TranslationalObstacle.\n"
#ifdef MINKSUM_HAVE_FCL
              "FCL: fcl::collide with contacts (libccd GJK + EPA), its contact's penetration depth; wrong\n"
              "when |FCL depth - d| > 1e-9·max(1, d), d the exact depth (the square root of the nearest\n"
              "double of its square).\n\n"
              "| pair | vertices | configuration | ours µs | FCL µs | FCL/ours | ours exact-path poses | ours wrong | FCL wrong |\n"
              "|---|---|---|---:|---:|---:|---:|---:|---:|\n");
#else
              "\n| pair | vertices | configuration | ours µs | ours exact-path poses | ours wrong |\n"
              "|---|---|---|---:|---:|---:|\n");
#endif
  for (const std::string& r : depth_rows) std::fputs(r.c_str(), stdout);
  std::fflush(stdout);

  // The coherent trajectory: Q turns about a fixed axis by 0.001 rad per
  // step while its centre runs along a circle through P (a third of the
  // steps penetrating, about), every query warm-started from the previous
  // one; the exact status (M built exactly) checked every 1000th step.
  std::printf("\n| pair | steps | ours µs / step | FCL µs / step | FCL/ours | steps checked exactly | ours wrong | FCL wrong (checked steps) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> trajectory_distance_rows;
  for (const RotationPair& pr : pairs) {
    const RigidBody bp(pr.p), bq(pr.q);
    double radius = 0;
    for (const ConvexPolytope* x : {&pr.p, &pr.q})
      for (Index v = 0; v < x->num_vertices(); ++v)
        radius = std::max(radius, std::sqrt(x->approx(v).x * x->approx(v).x + x->approx(v).y * x->approx(v).y +
                                             x->approx(v).z * x->approx(v).z));
    std::vector<std::array<double, 9>> rot(poses);
    std::vector<Vec3d> tr(poses);
    std::vector<RigidPose> traj;
    traj.reserve(poses);
    for (std::size_t i = 0; i < poses; ++i) {
      const double a = 0.001 * double(i), c = std::cos(a), sn = std::sin(a);
      // About the axis (1, 2, 2)/3 (Rodrigues).
      const double x = 1.0 / 3, y = 2.0 / 3, z = 2.0 / 3, k = 1 - c;
      rot[i] = {c + x * x * k,     x * y * k - z * sn, x * z * k + y * sn, y * x * k + z * sn, c + y * y * k,
                y * z * k - x * sn, z * x * k - y * sn, z * y * k + x * sn, c + z * z * k};
      const double th = 2 * M_PI * double(i) / double(poses);
      tr[i] = {2.2 * radius * std::cos(th) + 1.1 * radius, 1.6 * radius * std::sin(th), 0.1 * radius};
      traj.push_back(RigidPose::matrix(rot[i], tr[i]));
    }
    const RigidPose id;
    std::vector<RigidCollision> out(poses);
    RigidWarmStart warm;
    auto t0 = Clock::now();
    for (std::size_t i = 0; i < poses; ++i) out[i] = collide(bp, id, bq, traj[i], &warm);
    const double ours = us(t0, poses);
    std::size_t checked = 0, wrong = 0;
    std::vector<std::size_t> check;
    for (std::size_t i = 0; i < poses; i += 1000) check.push_back(i);
    std::vector<ContactStatus> exact(check.size());
    for (std::size_t k = 0; k < check.size(); ++k) {
      exact[k] = collide_exact(bp, id, bq, traj[check[k]]);
      ++checked;
      wrong += out[check[k]].status != exact[k];
    }
#ifdef MINKSUM_HAVE_FCL
    fcl::CollisionObjectd fa(fcl_convex(pr.p)), fb(fcl_convex(pr.q));
    fcl::CollisionRequestd req;
    req.gjk_solver_type = fcl::GST_LIBCCD;
    std::vector<char> hit(poses);
    t0 = Clock::now();
    for (std::size_t i = 0; i < poses; ++i) {
      fb.setTransform(transform(rot[i], tr[i]));
      fcl::CollisionResultd r;
      fcl::collide(&fa, &fb, req, r);
      hit[i] = r.isCollision();
    }
    const double fcl_us = us(t0, poses);
    std::size_t fcl_wrong = 0;
    for (std::size_t k = 0; k < check.size(); ++k) fcl_wrong += bool(hit[check[k]]) != (exact[k] != ContactStatus::separate);
    std::printf("| %s / %s | %zu | %.3g | %.3g | %.2f | %zu | %zu | %zu |\n", pr.name_p.c_str(), pr.name_q.c_str(), poses,
                ours, fcl_us, fcl_us / ours, checked, wrong, fcl_wrong);
#else
    std::printf("| %s / %s | %zu | %.3g | | | %zu | %zu | |\n", pr.name_p.c_str(), pr.name_q.c_str(), poses, ours,
                checked, wrong);
#endif
    std::fflush(stdout);

    // Distance along the same trajectory; the exact squared distance (M
    // built exactly, distance_exact) at the same checked steps.
    std::vector<RigidDistance> dist(poses);
    RigidWarmStart dwarm;
    t0 = Clock::now();
    for (std::size_t i = 0; i < poses; ++i) dist[i] = distance(bp, id, bq, traj[i], &dwarm);
    const double ours_d = us(t0, poses);
    std::size_t d_wrong = 0, d_exact_path = 0;
    std::vector<Rational> exact_sq(check.size());
    for (std::size_t k = 0; k < check.size(); ++k) {
      const std::size_t i = check[k];
      exact_sq[k] = distance_exact(bp, id, bq, traj[i]).squared_distance;
      d_wrong += exact_values(bp, id, bq, traj[i], dist[i]).squared_distance != exact_sq[k] ||
                 (dist[i].status == ContactStatus::separate) != (sgn(exact_sq[k]) > 0);
    }
    for (const RigidDistance& d : dist) d_exact_path += d.certificate == RigidCertificate::exact;
#ifdef MINKSUM_HAVE_FCL
    const fcl::DistanceRequestd dreq = fcl_distance_request();
    std::vector<double> fd(poses);
    t0 = Clock::now();
    for (std::size_t i = 0; i < poses; ++i) {
      fb.setTransform(transform(rot[i], tr[i]));
      fcl::DistanceResultd r;
      fcl::distance(&fa, &fb, dreq, r);
      fd[i] = r.min_distance;
    }
    const double fcl_d = us(t0, poses);
    std::size_t fcl_d_wrong = 0;
    for (std::size_t k = 0; k < check.size(); ++k) fcl_d_wrong += fcl_distance_wrong(fd[check[k]], exact_sq[k]);
    trajectory_distance_rows.push_back(format("| %s / %s | %zu | %.3g | %.3g | %.2f | %zu | %zu | %zu | %zu |\n",
                                              pr.name_p.c_str(), pr.name_q.c_str(), poses, ours_d, fcl_d,
                                              fcl_d / ours_d, d_exact_path, checked, d_wrong, fcl_d_wrong));
#else
    trajectory_distance_rows.push_back(format("| %s / %s | %zu | %.3g | | | %zu | %zu | %zu | |\n", pr.name_p.c_str(),
                                              pr.name_q.c_str(), poses, ours_d, d_exact_path, checked, d_wrong));
#endif
  }

  std::printf("\nDistance along the same trajectory, warm-started; checked against the exact squared distance\n"
              "(M built exactly) at the steps the collision table checks (FCL: the rule of the distance\n"
              "table; at a step that is not separate FCL is wrong when its signed distance is > 1e-9).\n\n"
              "| pair | steps | ours µs / step | FCL µs / step | FCL/ours | ours exact-path steps | steps checked exactly | ours wrong | FCL wrong (checked steps) |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& r : trajectory_distance_rows) std::fputs(r.c_str(), stdout);
  return 0;
}
