// The rotation section of bench_proximity: collision of two placed convex
// polytopes (minksum::collide on RigidBody / RigidPose, no M built per pose)
// against FCL's collide (libccd GJK solver) on the same poses, every answer
// checked against the exact status.
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
// 1 ± 1e-9 near-touching (s rounded to doubles), 0.5 penetrating.
#include "rotation.hpp"

#include "fcl_convex.hpp"

#ifdef MINKSUM_HAVE_FCL
#include <fcl/narrowphase/collision.h>
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

std::array<double, 9> random_rotation(std::mt19937_64& g) {
  std::normal_distribution<double> n(0, 1);
  double a = n(g), b = n(g), c = n(g), d = n(g);
  const double l = std::sqrt(a * a + b * b + c * c + d * d);
  a /= l, b /= l, c /= l, d /= l;
  return {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
          2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b),
          2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d};
}

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
  Vec3d t;  // its translation in doubles (FCL's input)
  ContactStatus exact;
};

struct Pair {
  std::string name_p, name_q;
  ConvexPolytope p, q;
};

double us(Clock::time_point t0, std::size_t n) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / double(n);
}

}  // namespace

int rotation_section(int argc, char** argv) {
  std::size_t poses = 100000;
  std::string meshes;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--poses") poses = std::strtoul(argv[i + 1], nullptr, 10);
    if (std::string(argv[i]) == "--meshes") meshes = argv[i + 1];
  }
  std::vector<Pair> pairs;
  for (const auto& [a, b] : std::vector<std::pair<const char*, const char*>>{{"cube", "cube"},
                                                                              {"sphere:2", "sphere:2"},
                                                                              {"random:50:1", "random:50:2"},
                                                                              {"random:500:1", "random:350:2"},
                                                                              {"sphere:4", "sphere:4"}})
    pairs.push_back({a, b, catalog_polytope(a), catalog_polytope(b)});
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
      pairs.push_back({std::string("hull of ") + a, std::string("hull of ") + b, hull(a), hull(b)});
    }
  }
  struct Config {
    const char* name;
    double f;
  } configs[] = {{"separated", 1.5}, {"touching", 1.0}, {"near-touching out", 1 + 1e-9},
                 {"near-touching in", 1 - 1e-9}, {"penetrating", 0.5}};
  const std::size_t orientations = 16;
  // Touching poses take the exact path (M built per pose): far fewer of them.
  const std::size_t touching_poses = std::min<std::size_t>(poses, 64);

  std::printf("## Collision under rigid motion: exact minksum (no M per pose) vs FCL\n\n");
  std::printf("bench_proximity --rotation --poses %zu%s%s: per pair, %zu orientation pairs (random rotations of\n"
              "P and Q as double matrices, taken exactly), Q translated by s = c + f·α*·u (u random; f = 1.5\n"
              "separated, 1 touching with s exact, 1 ± 1e-9 near-touching, 0.5 penetrating).  %zu poses per\n"
              "configuration (%zu touching).  Times in µs per query over different poses; 'ours' warm-starts\n"
              "each query from the previous pose's witnesses.  Wrong: status differs from the exact one\n"
              "(FCL: intersecting or not, touching counted as intersecting).\n\n",
              poses, meshes.empty() ? "" : " --meshes ", meshes.c_str(), orientations, poses, touching_poses);
#ifdef MINKSUM_HAVE_FCL
  std::printf("| pair | vertices | configuration | ours µs | FCL µs | FCL/ours | ours exact-path poses | ours wrong | FCL wrong |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|\n");
#else
  std::printf("| pair | vertices | configuration | ours µs | ours exact-path poses | ours wrong |\n");
  std::printf("|---|---|---|---:|---:|---:|\n");
#endif
  std::mt19937_64 g(20261202);
  for (const Pair& pr : pairs) {
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
        ps.push_back({k, RigidPose::matrix(rq[k], s), to_double(s), ob.collide_point(s).status});
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
        fa.setTransform(transform(rp[ps[i].orientation], Vec3d{0, 0, 0}));
        fb.setTransform(transform(rq[ps[i].orientation], ps[i].t));
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
    }
  }

  // The coherent trajectory: Q turns about a fixed axis by 0.001 rad per
  // step while its centre runs along a circle through P (a third of the
  // steps penetrating, about), every query warm-started from the previous
  // one; the exact status (M built exactly) checked every 1000th step.
  std::printf("\n| pair | steps | ours µs / step | FCL µs / step | FCL/ours | steps checked exactly | ours wrong | FCL wrong (checked steps) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Pair& pr : pairs) {
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
  }
  return 0;
}
