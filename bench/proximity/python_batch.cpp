// The Python batch table of bench_proximity: the same N poses through the
// C++ batch API (collide and distance on spans of RigidPose, as the Python
// module calls them) and through Python's minksum.collide_rigid and
// minksum.distance_rigid, one call each with numpy arrays, back to back.
//
//   bench_proximity --python-batch [--poses N] [--meshes DIR] [--threads T] [--reps R]
//                   [--python EXE] [--pythonpath DIR]
//
// Per pair of the rotation section (rotation_pairs), the poses are drawn
// here (a fixed seed) and written as .npy files to a temporary directory:
// rotations of both bodies as (N, 4) int64 quaternions and, separately, as
// (N, 3, 3) float64 matrices (the doubles of random rotations), and
// translations of both as (N, 3) float64 arrays (the same for both kinds of
// rotation).  The C++ side builds its RigidPose spans from those numbers
// (outside its timing; the time is reported apart), then times the batch
// calls; python_batch.py (run by EXE, /usr/bin/python3 by default, with
// PYTHONPATH=DIR, by default the build's python/ next to bin/) loads the
// same files and times the Python calls, each the whole call from numpy
// arrays to numpy arrays.  Both take the best of R calls (3) on T threads
// (0, the default: one per hardware thread, what both APIs do by
// default).  The Python side also checks that its answers are the C++
// answers: the same statuses and the same doubles (distance, lower, upper).
#include "rotation.hpp"

#include <minksum/rigid_proximity.hpp>
#include <minksum/transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#ifndef MINKSUM_BENCH_PROXIMITY_DIR
#define MINKSUM_BENCH_PROXIMITY_DIR "bench/proximity"
#endif

using namespace minksum;

namespace {

using Clock = std::chrono::steady_clock;

// A little-endian .npy file (format 1.0) of `count` items of `descr`
// ('<i8', '<f8', '|i1') with the given shape.
void write_npy(const std::filesystem::path& path, const char* descr, const std::vector<std::size_t>& shape,
               const void* data, std::size_t bytes) {
  std::string dims;
  for (std::size_t d : shape) dims += std::to_string(d) + ",";
  if (shape.size() > 1) dims.pop_back();
  std::string header = std::string("{'descr': '") + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::ofstream f(path, std::ios::binary);
  f.write("\x93NUMPY\x01\x00", 8);
  const auto len = static_cast<std::uint16_t>(header.size());
  const char l[2] = {char(len & 0xff), char(len >> 8)};
  f.write(l, 2);
  f.write(header.data(), std::streamsize(header.size()));
  f.write(static_cast<const char*>(data), std::streamsize(bytes));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

template <class T>
void write_npy(const std::filesystem::path& path, const char* descr, const std::vector<std::size_t>& shape,
               const std::vector<T>& v) {
  write_npy(path, descr, shape, v.data(), v.size() * sizeof(T));
}

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// 'text' quoted for the shell.
std::string shell_quoted(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

double radius(const ConvexPolytope& p) {
  double r = 0;
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Vec3d a = p.approx(v);
    r = std::max(r, std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z));
  }
  return r;
}

// The C++ side's figures for one kind of rotation.
struct Timing {
  double poses = 0, collide = 1e300, distance = 1e300;  // ms; the calls: best of reps
};

}  // namespace

int python_batch_section(int argc, char** argv) {
  std::size_t n = 100000;
  unsigned threads = 0;
  int reps = 3;
  std::string meshes, python = "/usr/bin/python3", pythonpath;
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--poses") n = std::strtoul(argv[i + 1], nullptr, 10);
    if (a == "--meshes") meshes = argv[i + 1];
    if (a == "--threads") threads = unsigned(std::strtoul(argv[i + 1], nullptr, 10));
    if (a == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    if (a == "--python") python = argv[i + 1];
    if (a == "--pythonpath") pythonpath = argv[i + 1];
  }
  if (pythonpath.empty()) {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    pythonpath = ec ? "python" : (exe.parent_path().parent_path() / "python").string();
  }
  const std::string script = std::string(MINKSUM_BENCH_PROXIMITY_DIR) + "/python_batch.py";
  const unsigned used = threads ? threads : std::max(1u, std::thread::hardware_concurrency());

  char tmpl[] = "/tmp/minksum-python-batch.XXXXXX";
  if (!mkdtemp(tmpl)) {
    std::perror("bench_proximity --python-batch: mkdtemp");
    return 1;
  }
  const std::filesystem::path dir(tmpl);

  std::printf("## Python batch: one call for %zu poses against the C++ batch\n\n", n);
  std::printf(
      "bench_proximity --python-batch --poses %zu%s%s: per pair of the rotation section, %zu poses of both\n"
      "bodies (drawn by the bench with a fixed seed, written as .npy files that the Python side loads, so\n"
      "both sides answer the same numbers): rotations as (N, 4) integer quaternions (components in\n"
      "[-50, 50]) and, separately, as (N, 3, 3) float matrices (the doubles of random rotations, taken\n"
      "exactly); translations (N, 3) floats, b at a random direction from a, its distance (0.3 to 1.3)·(r_a +\n"
      "r_b) (r: the largest vertex norm), so that a third to a half of the poses are separate.  C++: the batch calls\n"
      "collide(a, poses_a, b, poses_b, out, threads) and distance(...) on spans of RigidPose built from\n"
      "those arrays beforehand ('C++ poses': the time to build them, not in the calls' times).  Python\n"
      "(bench/proximity/python_batch.py): minksum.collide_rigid(a, b, t_b, r_b, t_a, r_a, threads=...)\n"
      "and distance_rigid(...), each one call from the numpy arrays to the numpy arrays of results, right\n"
      "after the C++ calls on the same poses.  Both on %u threads (the default of both APIs: one per\n"
      "hardware thread), best of %d calls, ms per call of N poses.  Same answers: Python's statuses and\n"
      "its distance, lower and upper are the C++ batch's, bit for bit.\n\n",
      n, meshes.empty() ? "" : " --meshes ", meshes.empty() ? "" : "DIR", n, used, reps);
  std::printf(
      "| pair | vertices | rotations | C++ poses ms | C++ collide ms | Python collide ms | Python/C++ collide | C++ "
      "distance ms | Python distance ms | Python/C++ distance | same answers |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  std::fflush(stdout);

  std::mt19937_64 g(20261206);
  std::size_t rows = 0, within = 0;
  int status = 0;
  for (const RotationPair& pr : rotation_pairs(meshes)) {
    const RigidBody bp(pr.p), bq(pr.q);
    // The poses.
    std::vector<std::int64_t> qa(4 * n), qb(4 * n);
    std::vector<double> ma(9 * n), mb(9 * n), ta(3 * n), tb(3 * n);
    std::uniform_int_distribution<int> qi(-50, 50);
    std::uniform_real_distribution<double> uni(0, 1);
    std::normal_distribution<double> nd(0, 1);
    const double ra = radius(pr.p), rb = radius(pr.q);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::vector<std::int64_t>* q : {&qa, &qb}) {
        std::int64_t* x = q->data() + 4 * i;
        do {
          for (int k = 0; k < 4; ++k) x[k] = qi(g);
        } while (!x[0] && !x[1] && !x[2] && !x[3]);
      }
      const auto r1 = random_rotation(g), r2 = random_rotation(g);
      std::copy(r1.begin(), r1.end(), ma.begin() + std::ptrdiff_t(9 * i));
      std::copy(r2.begin(), r2.end(), mb.begin() + std::ptrdiff_t(9 * i));
      double u[3] = {nd(g), nd(g), nd(g)};
      const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double rho = (0.3 + uni(g)) * (ra + rb);
      for (int k = 0; k < 3; ++k) {
        ta[3 * i + k] = (2 * uni(g) - 1) * ra;
        tb[3 * i + k] = ta[3 * i + k] + rho * u[k] / l;
      }
    }
    write_npy(dir / "quaternion_r_a.npy", "<i8", {n, 4}, qa);
    write_npy(dir / "quaternion_r_b.npy", "<i8", {n, 4}, qb);
    write_npy(dir / "matrix_r_a.npy", "<f8", {n, 3, 3}, ma);
    write_npy(dir / "matrix_r_b.npy", "<f8", {n, 3, 3}, mb);
    write_npy(dir / "t_a.npy", "<f8", {n, 3}, ta);
    write_npy(dir / "t_b.npy", "<f8", {n, 3}, tb);
    for (const auto& [name, poly] : {std::pair{"a", &pr.p}, std::pair{"b", &pr.q}}) {
      std::vector<double> v;
      for (Index k = 0; k < poly->num_vertices(); ++k) {
        const Vec3d x = poly->approx(k);
        v.insert(v.end(), {x.x, x.y, x.z});
      }
      write_npy(dir / (std::string(name) + "_vertices.npy"), "<f8", {poly->num_vertices(), 3}, v);
    }

    // The C++ batch, on each kind of rotation.
    std::map<std::string, Timing> cpp;
    for (const char* kind : {"quaternion", "matrix"}) {
      const bool quaternions = kind == std::string("quaternion");
      Timing& tm = cpp[kind];
      auto t0 = Clock::now();
      std::vector<RigidPose> pa, pb;
      pa.reserve(n), pb.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        if (quaternions) {
          const auto quat = [](const std::int64_t* x) {
            return Quaternion{Integer(static_cast<long>(x[0])), Integer(static_cast<long>(x[1])),
                              Integer(static_cast<long>(x[2])), Integer(static_cast<long>(x[3]))};
          };
          pa.push_back(RigidPose::quaternion(quat(&qa[4 * i]), Vec3d{ta[3 * i], ta[3 * i + 1], ta[3 * i + 2]}));
          pb.push_back(RigidPose::quaternion(quat(&qb[4 * i]), Vec3d{tb[3 * i], tb[3 * i + 1], tb[3 * i + 2]}));
        } else {
          std::array<double, 9> a, b;
          std::copy_n(ma.begin() + std::ptrdiff_t(9 * i), 9, a.begin());
          std::copy_n(mb.begin() + std::ptrdiff_t(9 * i), 9, b.begin());
          pa.push_back(RigidPose::matrix(a, Vec3d{ta[3 * i], ta[3 * i + 1], ta[3 * i + 2]}));
          pb.push_back(RigidPose::matrix(b, Vec3d{tb[3 * i], tb[3 * i + 1], tb[3 * i + 2]}));
        }
      }
      tm.poses = ms_since(t0);
      std::vector<RigidCollision> out(n);
      std::vector<RigidDistance> dist(n);
      for (int r = 0; r < reps; ++r) {
        t0 = Clock::now();
        collide(bp, pa, bq, pb, out, threads);
        tm.collide = std::min(tm.collide, ms_since(t0));
      }
      for (int r = 0; r < reps; ++r) {
        t0 = Clock::now();
        distance(bp, pa, bq, pb, dist, threads);
        tm.distance = std::min(tm.distance, ms_since(t0));
      }
      std::vector<std::int8_t> cs(n), ds(n);
      std::vector<double> dv(3 * n);
      for (std::size_t i = 0; i < n; ++i) {
        cs[i] = static_cast<std::int8_t>(out[i].status);
        ds[i] = static_cast<std::int8_t>(dist[i].status);
        dv[3 * i] = dist[i].distance, dv[3 * i + 1] = dist[i].lower, dv[3 * i + 2] = dist[i].upper;
      }
      write_npy(dir / (std::string(kind) + "_collide.npy"), "|i1", {n}, cs);
      write_npy(dir / (std::string(kind) + "_distance_status.npy"), "|i1", {n}, ds);
      write_npy(dir / (std::string(kind) + "_distance.npy"), "<f8", {n, 3}, dv);
    }

    // The Python side, right after, on the same files.
    const std::string cmd = "PYTHONDONTWRITEBYTECODE=1 PYTHONPATH=" + shell_quoted(pythonpath) + " " + shell_quoted(python) + " " +
                            shell_quoted(script) + " --dir " + shell_quoted(dir.string()) + " --a " + shell_quoted(pr.spec_p) +
                            " --b " + shell_quoted(pr.spec_q) + (pr.hull ? " --hull" : "") + " --threads " +
                            std::to_string(threads) + " --reps " + std::to_string(reps);
    std::map<std::string, std::string> py;
    FILE* f = popen(cmd.c_str(), "r");
    if (f) {
      char line[512];
      while (std::fgets(line, sizeof line, f)) {
        std::istringstream s(line);
        std::string key, value;
        if (s >> key >> value) py[key] = value;
      }
      if (pclose(f) != 0) py.clear();
    }
    if (py.empty()) {
      std::fprintf(stderr, "bench_proximity --python-batch: %s failed (is the Python module built in %s?)\n",
                   cmd.c_str(), pythonpath.c_str());
      status = 1;
      break;
    }
    for (const char* kind : {"quaternion", "matrix"}) {
      const Timing& c = cpp[kind];
      const double pc = std::atof(py[std::string(kind) + ".collide"].c_str()),
                   pd = std::atof(py[std::string(kind) + ".distance"].c_str());
      const bool same = py[std::string(kind) + ".same"] == "yes";
      ++rows;
      within += pc <= 2 * c.collide && pd <= 2 * c.distance;
      std::printf("| %s / %s | %u / %u | %s | %.3g | %.3g | %.3g | %.2f | %.3g | %.3g | %.2f | %s |\n",
                  pr.name_p.c_str(), pr.name_q.c_str(), pr.p.num_vertices(), pr.q.num_vertices(),
                  kind == std::string("quaternion") ? "quaternions (N, 4) int" : "matrices (N, 3, 3) float",
                  c.poses, c.collide, pc, pc / c.collide, c.distance, pd, pd / c.distance, same ? "yes" : "no");
      std::fflush(stdout);
    }
  }
  std::filesystem::remove_all(dir);
  if (status) return status;
  std::printf("\n## Targets\n\n");
  std::printf("* Python batch within 2× of C++ (collide_rigid and distance_rigid, %zu poses in one call, each at most\n"
              "  twice the C++ batch call's time on the same poses): %zu of %zu rows.\n",
              n, within, rows);
  return 0;
}
