// Exact proximity queries (minksum::TranslationalObstacle) against libccd's
// GJK intersection, GJK+EPA penetration and MPR intersection, on the same
// pairs and the same translations (doubles, so both sides see the same input).
// When built with FCL (MINKSUM_HAVE_FCL), FCL's Convex/Convex collide and
// signed distance (libccd GJK solver) are compared as well.
// Prints a markdown section on stdout (docs/generated/benchmarks-proximity.md).
//
// Usage: bench_proximity [--steps N] [--reps R]
//        bench_proximity --count P Q F N   (FCL builds only) one pose of the table
//            (s = c + F·α*·dir), N distance, N depth and N collision queries, N FCL
//            distances, N libccd GJK+EPA and N GJK, each loop in its own function,
//            for instruction counts:
//            valgrind --tool=callgrind bench_proximity --count cube cube@rot:3 1.5 20
//            then callgrind_annotate --inclusive=yes: count_ours_distance,
//            count_ours_depth, count_ours_collide, count_fcl_distance, count_ccd_epa,
//            count_ccd_gjk, and count_ours_distance_exact / count_ours_depth_exact
//            (the queries with their exact values as quotients: squared distance
//            and closest point of P; squared depth), count_ours_distance_lowest
//            (the same distance values in lowest terms) (divide by N).
//        bench_proximity --count-trajectory P Q N   the coherent trajectory of N
//            steps: count_ours_trajectory (distance_points), count_fcl_trajectory.
//        bench_proximity --rotation [--poses N] [--meshes DIR]   collision and
//            distance under rigid motion against FCL (rotation.cpp); DIR holds the robot-link
//            meshes (ur5e_forearm.stl, ur5e_upperarm.stl, franka_link1.stl).
//        bench_proximity --python-batch [--poses N] [--meshes DIR] [--threads T] [--reps R]
//                        [--python EXE] [--pythonpath DIR]   the same N poses through the
//            C++ batch API and through Python's collide_rigid / distance_rigid
//            (python_batch.cpp, python_batch.py), and the page's targets summary.
#include <ccd/ccd.h>
#include <ccd/quat.h>

#ifdef MINKSUM_HAVE_FCL
#include <fcl/config.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#endif

#ifdef MINKSUM_HAVE_CGAL_DISTANCE
#include <CGAL/Gmpz.h>
#include <CGAL/Homogeneous.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>
#endif
#include <minksum/catalog.hpp>
#include <minksum/proximity.hpp>

#include "fcl_convex.hpp"
#include "rotation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace minksum;
using Clock = std::chrono::steady_clock;

namespace {

struct Body {
  std::vector<ccd_vec3_t> v;
  ccd_vec3_t t;
  ccd_vec3_t c;
};

void support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const Body* b = static_cast<const Body*>(obj);
  std::size_t best = 0;
  double bd = -INFINITY;
  for (std::size_t i = 0; i < b->v.size(); ++i) {
    const double d = ccdVec3Dot(&b->v[i], dir);
    if (d > bd) bd = d, best = i;
  }
  ccdVec3Copy(out, &b->v[best]);
  ccdVec3Add(out, &b->t);
}
void center(const void* obj, ccd_vec3_t* out) {
  const Body* b = static_cast<const Body*>(obj);
  ccdVec3Copy(out, &b->c);
  ccdVec3Add(out, &b->t);
}

Body body(const ConvexPolytope& p) {
  Body b;
  double cx = 0, cy = 0, cz = 0;
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Vec3d a = p.approx(v);
    ccd_vec3_t x;
    ccdVec3Set(&x, a.x, a.y, a.z);
    b.v.push_back(x);
    cx += a.x, cy += a.y, cz += a.z;
  }
  const double n = double(p.num_vertices());
  ccdVec3Set(&b.c, cx / n, cy / n, cz / n);
  ccdVec3Set(&b.t, 0, 0, 0);
  return b;
}

ccd_t make_ccd() {
  ccd_t c;
  CCD_INIT(&c);
  c.support1 = support;
  c.support2 = support;
  c.center1 = center;
  c.center2 = center;
  c.max_iterations = 500;
  c.epa_tolerance = 1e-9;
  c.mpr_tolerance = 1e-9;
  return c;
}

Point3 dpoint(double x, double y, double z) { return Point3(x, y, z); }

double now_us(Clock::time_point t0, long n) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / double(n);
}

#ifdef MINKSUM_HAVE_FCL
struct Fcl {
  fcl::CollisionObjectd a, b;
  fcl::CollisionRequestd creq;
  fcl::DistanceRequestd dreq;
  Fcl(const ConvexPolytope& p, const ConvexPolytope& q) : a(fcl_convex(p)), b(fcl_convex(q)) {
    creq.gjk_solver_type = fcl::GST_LIBCCD;
    dreq.gjk_solver_type = fcl::GST_LIBCCD;
    dreq.enable_signed_distance = true;
    dreq.enable_nearest_points = true;
  }
  void at(double x, double y, double z) { b.setTranslation(fcl::Vector3d(x, y, z)); }
  bool collide() {
    fcl::CollisionResultd r;
    fcl::collide(&a, &b, creq, r);
    return r.isCollision();
  }
  double distance() {  // signed: < 0 when penetrating
    fcl::DistanceResultd r;
    fcl::distance(&a, &b, dreq, r);
    return r.min_distance;
  }
};
#endif

#ifdef MINKSUM_HAVE_CGAL_DISTANCE
// CGAL's Polytope_distance_d (Gärtner's QP solver) with exact integers: the
// vertices of P and of Q + s as homogeneous integer points (exact, one
// denominator per point).
using PdKernel = CGAL::Homogeneous<CGAL::Gmpz>;
using PdPoint = PdKernel::Point_3;
using PdDistance = CGAL::Polytope_distance_d<CGAL::Polytope_distance_d_traits_3<PdKernel>>;
PdPoint pd_point(const Point3& x) {
  Integer l;
  mpz_lcm(l.get_mpz_t(), x.x.get_den_mpz_t(), x.y.get_den_mpz_t());
  mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), x.z.get_den_mpz_t());
  auto h = [&](const Rational& c) { return CGAL::Gmpz(Integer(c.get_num() * (l / c.get_den())).get_mpz_t()); };
  return PdPoint(h(x.x), h(x.y), h(x.z), CGAL::Gmpz(l.get_mpz_t()));
}
// The exact squared distance between P and Q + s (0 when they intersect).
Rational cgal_squared_distance(const ConvexPolytope& p, const ConvexPolytope& q, const Point3& s) {
  std::vector<PdPoint> a, b;
  for (Index v = 0; v < p.num_vertices(); ++v) a.push_back(pd_point(p.point(v)));
  for (Index v = 0; v < q.num_vertices(); ++v) b.push_back(pd_point(q.point(v) + s));
  PdDistance pd(a.begin(), a.end(), b.begin(), b.end());
  Rational r(Integer(pd.squared_distance_numerator().mpz()), Integer(pd.squared_distance_denominator().mpz()));
  r.canonicalize();
  return r;
}
#endif
bool rel_off(double a, double b) { return std::fabs(a - b) > 1e-6 * std::max(std::fabs(b), 1e-300); }

}  // namespace

namespace {
#ifdef MINKSUM_HAVE_FCL
// Instruction counts (see the usage): the loops, each in a function of its own.
__attribute__((noinline)) void count_ours_distance(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) ob.distance_point(s);
}
__attribute__((noinline)) void count_ours_depth(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) ob.penetration_depth_point(s);
}
// The queries with their exact values (as the table's "+ exact" column:
// quotients of integers) and with the same values in lowest terms (the
// "+ lowest terms" column: rationals).
__attribute__((noinline)) void count_ours_distance_exact(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) {
    const DistanceResult d = ob.distance_point(s);
    d.squared_distance_quotient();
    d.point_p_quotient();
  }
}
__attribute__((noinline)) void count_ours_distance_lowest(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) {
    const DistanceResult d = ob.distance_point(s);
    d.squared_distance();
    d.point_p();
  }
}
__attribute__((noinline)) void count_ours_depth_exact(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) ob.penetration_depth_point(s).squared_depth_quotient();
}
__attribute__((noinline)) int count_ccd_epa(Body& p, Body& q, ccd_t& c, int n) {
  int ret = 0;
  ccd_real_t depth;
  ccd_vec3_t dir, pos;
  for (int i = 0; i < n; ++i) ret += ccdGJKPenetration(&p, &q, &c, &depth, &dir, &pos);
  return ret;
}
__attribute__((noinline)) int count_ccd_gjk(Body& p, Body& q, ccd_t& c, int n) {
  int ret = 0;
  for (int i = 0; i < n; ++i) ret += ccdGJKIntersect(&p, &q, &c);
  return ret;
}
__attribute__((noinline)) void count_ours_collide(TranslationalObstacle& ob, const Point3& s, int n) {
  for (int i = 0; i < n; ++i) ob.collide_point(s);
}
__attribute__((noinline)) double count_fcl_distance(Fcl& f, int n) {
  double d = 0;
  for (int i = 0; i < n; ++i) d = f.distance();
  return d;
}
__attribute__((noinline)) void count_ours_trajectory(TranslationalObstacle& ob, const std::vector<Point3>& t,
                                                     std::vector<DistanceResult>& out) {
  ob.distance_points(t, out);
}
__attribute__((noinline)) double count_fcl_trajectory(Fcl& f, const std::vector<Vec3d>& t) {
  double d = 0;
  for (const Vec3d& v : t) {
    f.at(v.x, v.y, v.z);
    d += f.distance();
  }
  return d;
}
// The coherent trajectory of the benchmark: s(i) = c + α*·(1.1 cos θ, 0.9 sin θ, 0.2 sin 3θ).
void trajectory(TranslationalObstacle& ob, long steps, std::vector<Point3>& traj, std::vector<Vec3d>& trajd);
int count_main(int argc, char** argv) {
  const std::string mode = argv[1];
  if ((mode == "--count" && argc != 6) || (mode == "--count-trajectory" && argc != 5)) {
    std::fprintf(stderr, "usage: bench_proximity --count P Q F N | --count-trajectory P Q N\n");
    return 2;
  }
  const ConvexPolytope p = catalog_polytope(argv[2]), q = catalog_polytope(argv[3]);
  TranslationalObstacle ob(p, q);
  Fcl fc(p, q);
  if (mode == "--count-trajectory") {
    std::vector<Point3> traj;
    std::vector<Vec3d> trajd;
    trajectory(ob, std::atol(argv[4]), traj, trajd);
    std::vector<DistanceResult> out;
    count_ours_trajectory(ob, traj, out);
    const double fd = count_fcl_trajectory(fc, trajd);
    long separate = 0;
    for (const DistanceResult& r : out) separate += r.status == ContactStatus::separate;
    std::printf("%s / %s: %zu steps, %ld separate, %llu certified, %llu scans (FCL sum %g)\n", argv[2], argv[3],
                out.size(), separate, (unsigned long long)ob.stats().certified,
                (unsigned long long)ob.stats().full_scans, fd);
    return 0;
  }
  const double factor = std::atof(argv[4]);
  const int n = std::atoi(argv[5]);
  const Point3 dir = dpoint(1, 0.375, 0.1875);
  const Point3 c = ob.interior_point();
  const double alpha = to_double(ob.directional_depth_point(c, -dir).t);
  const Vec3d cd = to_double(c);
  const Point3 s = dpoint(cd.x + factor * alpha * 1.0, cd.y + factor * alpha * 0.375, cd.z + factor * alpha * 0.1875);
  const Vec3d sd = to_double(s);
  fc.at(sd.x, sd.y, sd.z);
  const DistanceResult d = ob.distance_point(s);  // the witnesses, as in the table
  ob.penetration_depth_point(s);
  // One answer with its exact values, as in the table: d holds the
  // obstacle's first spare storage, this one makes the spare that the loops'
  // answers reuse (a steady state, not the first allocation, is counted).
  ob.distance_point(s).point_p_quotient();
  ob.penetration_depth_point(s).squared_depth_quotient();
  count_ours_distance(ob, s, n);
  count_ours_depth(ob, s, n);
  count_ours_collide(ob, s, n);
  count_ours_distance_exact(ob, s, n);
  count_ours_distance_lowest(ob, s, n);
  count_ours_depth_exact(ob, s, n);
  const double fd = count_fcl_distance(fc, n);
  Body bp = body(p), bq = body(q);
  ccdVec3Set(&bq.t, sd.x, sd.y, sd.z);
  ccd_t ccd = make_ccd();
  count_ccd_epa(bp, bq, ccd, n);
  count_ccd_gjk(bp, bq, ccd, n);
  std::printf("%s / %s, f = %g: %s, distance %.17g (FCL %.17g)\n", argv[2], argv[3], factor,
              contact_status_name(d.status), d.distance(), fd);
  return 0;
}
#endif

void trajectory(TranslationalObstacle& ob, long steps, std::vector<Point3>& traj, std::vector<Vec3d>& trajd) {
  const Point3 c = ob.interior_point();
  const double alpha = to_double(ob.directional_depth_point(c, dpoint(-1, 0, 0)).t);
  const Vec3d cd = to_double(c);
  traj.reserve(std::size_t(steps));
  for (long i = 0; i < steps; ++i) {
    const double th = 2 * M_PI * 3.0 * double(i) / double(steps);
    const Vec3d v{cd.x + alpha * 1.1 * std::cos(th), cd.y + alpha * 0.9 * std::sin(th),
                  cd.z + alpha * 0.2 * std::sin(3 * th)};
    trajd.push_back(v);
    traj.push_back(dpoint(v.x, v.y, v.z));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--rotation") return rotation_section(argc, argv);
  if (argc > 1 && std::string(argv[1]) == "--python-batch") return python_batch_section(argc, argv);
#ifdef MINKSUM_HAVE_FCL
  if (argc > 1 && std::string(argv[1]).rfind("--count", 0) == 0) return count_main(argc, argv);
#endif
  long steps = 100000, reps = 2000;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--steps") steps = std::atol(argv[i + 1]);
    else if (std::string(argv[i]) == "--reps") reps = std::atol(argv[i + 1]);
  }
  const char* pairs[][2] = {{"cube", "cube@rot:3"},
                            {"sphere:2", "sphere:2@rot:1"},
                            {"random:50:1", "random:50:2"},
                            {"random:500:1", "random:350:2"},
                            {"sphere:4", "sphere:4@rot:1"}};
  struct Config {
    const char* name;
    double factor;  // s = c + factor · α* · dir, α*: the exact exit parameter
  } configs[] = {{"separated", 1.5}, {"touching", 1.0}, {"near-touching out", 1 + 1e-9},
                 {"near-touching in", 1 - 1e-9}, {"penetrating", 0.5}};

#ifdef MINKSUM_HAVE_FCL
  std::printf("## Proximity queries: exact minksum vs libccd and FCL\n\n");
#else
  std::printf("## Proximity queries: exact minksum vs libccd\n\n");
#endif
  std::printf("<!-- Generated by `make bench` (bench/proximity/run.sh, bench/proximity/bench_proximity.cpp). "
              "Do not edit by hand: every figure below comes from that command. -->\n\n");
  std::printf("Command: `bench/proximity/run.sh` (bench_proximity --steps %ld --reps %ld).  P is at the origin,\n"
              "Q is translated by s (doubles, the same for both libraries).  Our answers are exact;\n"
              "a libccd answer is *wrong* when its status differs (GJK/MPR: intersecting or not;\n"
              "touching counts as intersecting) or its depth is off by more than 1e-6 relative.\n"
              "Times are microseconds per query (same query repeated %ld times; ours reuses its witness).\n"
              "Configurations: s = c + f·α*·dir with c inside M and α* the exact exit parameter of the ray,\n"
              "f = 1.5 (separated), 1 (touching), 1 ± 1e-9 (near-touching), 0.5 (penetrating); s is then\n"
              "rounded to doubles, so the 'touching' point's exact status is whatever the rounding gives.\n"
              "Distance: a walk on M whose every move and final Voronoi-region certificate are filtered exact\n"
              "predicates on doubles; the answer holds the certified feature, and its exact squared distance\n"
              "and closest points are computed on first use: 'ours distance' is the query (status and certified\n"
              "witness feature); 'ours distance + exact' the query, its exact squared distance and the exact\n"
              "closest point of P as a user calling squared_distance_quotient() and point_p_quotient() gets them\n"
              "(integer numerators over a positive common denominator, not reduced: no gcd); '+ lowest terms'\n"
              "the query and the same two values in lowest terms, squared_distance() and point_p() (rationals:\n"
              "the quotients and one gcd per number).  Each timed answer is a new DistanceResult, destroyed\n"
              "before the next query.  Depth: a scan of M's unit facet planes with a derived\n"
              "error bound, exact comparisons among the planes it cannot rule out (the squared depth, a\n"
              "rational, on first use as well).\n",
              steps, reps, reps);
#ifdef MINKSUM_HAVE_FCL
  std::printf("FCL %s: fcl::Convexd pairs (same vertices and facets), fcl::collide and fcl::distance with\n"
              "the libccd GJK solver and signed distance.  An FCL collide answer is wrong when its status\n"
              "differs; an FCL distance answer is wrong when its sign differs (> 0 separate, <= 0 touching or\n"
              "penetrating) or, for separate/penetrating, |distance| is off from the exact distance/depth\n"
              "by more than 1e-6 relative.\n\n",
              FCL_VERSION);
#ifdef MINKSUM_HAVE_CGAL_DISTANCE
  std::printf("CGAL %s: Polytope_distance_d (exact integers, homogeneous points) on the vertex sets, in the\n"
              "separated configurations; 'CGAL agrees' compares its exact squared distance with ours.\n\n",
              CGAL_VERSION_STR);
#endif
  std::printf("| pair | configuration | exact status | ours collide µs | ours depth µs | ours distance µs | "
              "ours distance + exact µs | + lowest terms µs | GJK µs | GJK+EPA µs | MPR µs | FCL collide µs | FCL distance µs | "
              "CGAL distance µs (agrees) | "
              "GJK/ours collide | libccd wrong (GJK, EPA, MPR) | FCL wrong (collide, distance) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|---|\n");
#else
  std::printf("\n");
  std::printf("| pair | configuration | exact status | ours collide µs | ours depth µs | ours distance µs | "
              "ours distance + exact µs | + lowest terms µs | GJK µs | GJK+EPA µs | MPR µs | GJK/ours collide | "
              "libccd wrong (GJK, EPA, MPR) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
#endif

  for (auto& pr : pairs) {
    const ConvexPolytope p = catalog_polytope(pr[0]), q = catalog_polytope(pr[1]);
    TranslationalObstacle ob(p, q);
    Body bp = body(p), bq = body(q);
    ccd_t ccd = make_ccd();
    const Point3 dir = dpoint(1, 0.375, 0.1875);
    // Exit parameter of the ray c + α dir.
    const Point3 c = ob.interior_point();
    DirectionalDepthResult exitr = ob.directional_depth_point(c, -dir);
    const double alpha = to_double(exitr.t);
    const Vec3d cd = to_double(c);
    for (const Config& cf : configs) {
      const Point3 s = dpoint(cd.x + cf.factor * alpha * 1.0, cd.y + cf.factor * alpha * 0.375,
                              cd.z + cf.factor * alpha * 0.1875);
      const Vec3d sd = to_double(s);
      ccdVec3Set(&bq.t, sd.x, sd.y, sd.z);
      const ContactStatus exact = ob.collide_point(s).status;
      const DepthResult dr = ob.penetration_depth_point(s);
      const DistanceResult sr = ob.distance_point(s);
      // sr keeps the obstacle's spare storage for exact values; one answer
      // with its exact values makes the spare the timed answers reuse.
      ob.distance_point(s).point_p_quotient();
      ob.penetration_depth_point(s).squared_depth_quotient();

      auto t0 = Clock::now();
      for (long r = 0; r < reps; ++r) ob.collide_point(s);
      const double us_collide = now_us(t0, reps);
      t0 = Clock::now();
      for (long r = 0; r < reps / 10 + 1; ++r) ob.penetration_depth_point(s);
      const double us_depth = now_us(t0, reps / 10 + 1);
      t0 = Clock::now();
      for (long r = 0; r < reps / 10 + 1; ++r) ob.distance_point(s);
      const double us_dist = now_us(t0, reps / 10 + 1);
      t0 = Clock::now();
      for (long r = 0; r < reps / 10 + 1; ++r) {
        const DistanceResult d = ob.distance_point(s);
        d.squared_distance_quotient();
        d.point_p_quotient();
      }
      const double us_dist_exact = now_us(t0, reps / 10 + 1);
      t0 = Clock::now();
      for (long r = 0; r < reps / 10 + 1; ++r) {
        const DistanceResult d = ob.distance_point(s);
        d.squared_distance();
        d.point_p();
      }
      const double us_dist_lowest = now_us(t0, reps / 10 + 1);

      int gjk = 0, mpr = 0, epa_ret = 0;
      ccd_real_t depth = 0;
      ccd_vec3_t pdir, ppos;
      t0 = Clock::now();
      for (long r = 0; r < reps; ++r) gjk = ccdGJKIntersect(&bp, &bq, &ccd);
      const double us_gjk = now_us(t0, reps);
      t0 = Clock::now();
      for (long r = 0; r < reps; ++r) epa_ret = ccdGJKPenetration(&bp, &bq, &ccd, &depth, &pdir, &ppos);
      const double us_epa = now_us(t0, reps);
      t0 = Clock::now();
      for (long r = 0; r < reps; ++r) mpr = ccdMPRIntersect(&bp, &bq, &ccd);
      const double us_mpr = now_us(t0, reps);

      const bool inter = exact != ContactStatus::separate;
      const int wrong_gjk = (gjk != 0) != inter;
      const int wrong_mpr = (mpr != 0) != inter;
      int wrong_epa = (epa_ret == 0) != inter;
      if (!wrong_epa && epa_ret == 0 && exact == ContactStatus::penetrating) wrong_epa = rel_off(depth, dr.depth());
#ifdef MINKSUM_HAVE_FCL
      Fcl fc(p, q);
      fc.at(sd.x, sd.y, sd.z);
      bool fcol = false;
      double fdist = 0;
      t0 = Clock::now();
      for (long r = 0; r < reps; ++r) fcol = fc.collide();
      const double us_fcol = now_us(t0, reps);
      t0 = Clock::now();
      for (long r = 0; r < reps; ++r) fdist = fc.distance();
      const double us_fdist = now_us(t0, reps);
      const int wrong_fcol = fcol != inter;
      int wrong_fdist = (fdist <= 0) != inter;
      if (!wrong_fdist && exact == ContactStatus::separate) wrong_fdist = rel_off(fdist, sr.distance());
      if (!wrong_fdist && exact == ContactStatus::penetrating) wrong_fdist = rel_off(-fdist, dr.depth());
      std::string cgal = "–";
#ifdef MINKSUM_HAVE_CGAL_DISTANCE
      if (exact == ContactStatus::separate) {
        const long n = reps / 200 + 1;
        Rational d2;
        t0 = Clock::now();
        for (long r = 0; r < n; ++r) d2 = cgal_squared_distance(p, q, s);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.2f (%s)", now_us(t0, n), d2 == sr.squared_distance() ? "yes" : "NO");
        cgal = buf;
      }
#endif
      std::printf("| %s / %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %.2f | %d, %d, %d | %d, %d |\n",
                  pr[0], pr[1], cf.name, contact_status_name(exact), us_collide, us_depth, us_dist, us_dist_exact,
                  us_dist_lowest, us_gjk, us_epa,
                  us_mpr, us_fcol, us_fdist, cgal.c_str(), us_gjk / us_collide, wrong_gjk, wrong_epa, wrong_mpr,
                  wrong_fcol, wrong_fdist);
#else
      (void)sr;
      std::printf("| %s / %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %d, %d, %d |\n", pr[0],
                  pr[1], cf.name, contact_status_name(exact), us_collide, us_depth, us_dist, us_dist_exact, us_dist_lowest,
                  us_gjk, us_epa, us_mpr,
                  us_gjk / us_collide, wrong_gjk, wrong_epa, wrong_mpr);
#endif
    }
  }

  // Coherent trajectory: s follows a smooth closed curve that crosses ∂M.
  std::printf("\n### Coherent trajectory (%ld steps)\n\n", steps);
  std::printf("s(i) = c + α*·(1.1 cos θ, 0.9 sin θ, 0.2 sin 3θ) with θ = 2π·3i/N (three laps, crossing the boundary\n"
              "of M twice per lap).  Our statuses are checked against a scan of all facet planes on every step.\n"
              "Distance along the same trajectory: TranslationalObstacle::distance_points (one batch, witnesses\n"
              "carried along); its statuses are checked on every step and its exact squared distance every\n"
              "1000th step against an exact scan of all the facets of M the pose sees ('ours wrong' counts\n"
              "both); an FCL distance is wrong when its sign differs or it is off by more than 1e-6 relative.\n\n");
#ifdef MINKSUM_HAVE_FCL
  std::printf("| pair | ours collide µs | GJK µs | MPR µs | FCL collide µs | GJK / ours | ours wrong | GJK wrong | "
              "MPR wrong | FCL wrong | walk moves / query | full scans | ours distance µs | FCL distance µs | "
              "distance certified / separate | FCL distance wrong |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
#else
  std::printf("| pair | ours collide µs | GJK µs | MPR µs | GJK / ours | ours wrong | GJK wrong | MPR wrong | "
              "walk moves / query | full scans |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
#endif
  for (auto& pr : pairs) {
    const ConvexPolytope p = catalog_polytope(pr[0]), q = catalog_polytope(pr[1]);
    TranslationalObstacle ob(p, q);
    Body bp = body(p), bq = body(q);
    ccd_t ccd = make_ccd();
    std::vector<Point3> traj;
    std::vector<Vec3d> trajd;
    trajectory(ob, steps, traj, trajd);
    std::vector<ContactStatus> ours(static_cast<std::size_t>(steps));
    ob.reset_stats();
    auto t0 = Clock::now();
    for (long i = 0; i < steps; ++i) ours[std::size_t(i)] = ob.collide_point(traj[std::size_t(i)]).status;
    const double us_ours = now_us(t0, steps);
    const double walk = double(ob.stats().walk_steps) / double(steps);
    const auto scans = ob.stats().full_scans;
    std::vector<int> gjk(static_cast<std::size_t>(steps)), mpr(static_cast<std::size_t>(steps));
    t0 = Clock::now();
    for (long i = 0; i < steps; ++i) {
      ccdVec3Set(&bq.t, trajd[std::size_t(i)].x, trajd[std::size_t(i)].y, trajd[std::size_t(i)].z);
      gjk[std::size_t(i)] = ccdGJKIntersect(&bp, &bq, &ccd);
    }
    const double us_gjk = now_us(t0, steps);
    t0 = Clock::now();
    for (long i = 0; i < steps; ++i) {
      ccdVec3Set(&bq.t, trajd[std::size_t(i)].x, trajd[std::size_t(i)].y, trajd[std::size_t(i)].z);
      mpr[std::size_t(i)] = ccdMPRIntersect(&bp, &bq, &ccd);
    }
    const double us_mpr = now_us(t0, steps);
    long wrong_ours = 0, wrong_gjk = 0, wrong_mpr = 0, wrong_fcl = 0;
#ifdef MINKSUM_HAVE_FCL
    Fcl fc(p, q);
    std::vector<char> fcol(static_cast<std::size_t>(steps));
    t0 = Clock::now();
    for (long i = 0; i < steps; ++i) {
      fc.at(trajd[std::size_t(i)].x, trajd[std::size_t(i)].y, trajd[std::size_t(i)].z);
      fcol[std::size_t(i)] = fc.collide();
    }
    const double us_fcl = now_us(t0, steps);
#endif
    const ConvexPolytope& m = ob.obstacle();
    for (long i = 0; i < steps; ++i) {
      int worst = -1;
      for (Index f = 0; f < m.num_facets() && worst <= 0; ++f) worst = std::max(worst, m.plane(f).side(traj[std::size_t(i)]));
      const ContactStatus want =
          worst > 0 ? ContactStatus::separate : worst == 0 ? ContactStatus::touching : ContactStatus::penetrating;
      wrong_ours += ours[std::size_t(i)] != want;
      const bool inter = want != ContactStatus::separate;
      wrong_gjk += (gjk[std::size_t(i)] != 0) != inter;
      wrong_mpr += (mpr[std::size_t(i)] != 0) != inter;
#ifdef MINKSUM_HAVE_FCL
      wrong_fcl += (fcol[std::size_t(i)] != 0) != inter;
#endif
    }
#ifdef MINKSUM_HAVE_FCL
    // Distance along the same trajectory: the batch API (witnesses carried
    // along), then FCL's signed distance at the same poses.
    std::vector<DistanceResult> dist;
    ob.reset_stats();
    t0 = Clock::now();
    ob.distance_points(traj, dist);
    const double us_dist = now_us(t0, steps);
    const auto certified = ob.stats().certified;
    std::vector<double> fdist(static_cast<std::size_t>(steps));
    t0 = Clock::now();
    for (long i = 0; i < steps; ++i) {
      fc.at(trajd[std::size_t(i)].x, trajd[std::size_t(i)].y, trajd[std::size_t(i)].z);
      fdist[std::size_t(i)] = fc.distance();
    }
    const double us_fdist = now_us(t0, steps);
    long separate = 0, wrong_fdist = 0;
    for (long i = 0; i < steps; ++i) {
      const DistanceResult& d = dist[std::size_t(i)];
      const bool sep = d.status == ContactStatus::separate;
      separate += sep;
      wrong_ours += d.status != ours[std::size_t(i)];
      const double f = fdist[std::size_t(i)];
      wrong_fdist += (f > 0) != sep || (sep && rel_off(f, d.distance()));
    }
    // Every 1000th separate pose: the exact squared distance against an exact
    // scan of all the facets of M the pose sees (no walk, no filter).
    for (long i = 0; i < steps; i += 1000)
      if (dist[std::size_t(i)].status == ContactStatus::separate)
        wrong_ours += dist[std::size_t(i)].squared_distance() != ob.squared_distance_by_scan(traj[std::size_t(i)]);
    std::printf("| %s / %s | %.2f | %.2f | %.2f | %.2f | %.2f | %ld | %ld | %ld | %ld | %.4f | %llu | %.2f | %.2f | "
                "%llu / %ld | %ld |\n",
                pr[0], pr[1], us_ours, us_gjk, us_mpr, us_fcl, us_gjk / us_ours, wrong_ours, wrong_gjk, wrong_mpr,
                wrong_fcl, walk, (unsigned long long)scans, us_dist, us_fdist, (unsigned long long)certified, separate,
                wrong_fdist);
#else
    (void)wrong_fcl;
    std::printf("| %s / %s | %.2f | %.2f | %.2f | %.2f | %ld | %ld | %ld | %.4f | %llu |\n", pr[0], pr[1], us_ours, us_gjk,
                us_mpr, us_gjk / us_ours, wrong_ours, wrong_gjk, wrong_mpr, walk, (unsigned long long)scans);
#endif
  }
#ifndef MINKSUM_HAVE_FCL
  std::printf("\nFCL is not compared: this build did not find FCL (libfcl-dev).\n");
#endif
  return 0;
}
