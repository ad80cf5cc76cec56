// Operand resolution: file or catalog name (see operand.hpp).
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <chrono>
#include <sys/stat.h>

namespace minksum {

ConvexPolytope load_polytope(const std::string& spec, bool hull, LoadPhases* phases) {
  using clock = std::chrono::steady_clock;
  auto seconds = [](clock::time_point a, clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  auto format = format_from_path(spec);
  struct stat st{};
  bool exists = ::stat(spec.c_str(), &st) == 0;
  // An existing file is read, unless its name has no known extension and is
  // a catalog spec (a stray file called "cube" does not shadow the catalog).
  if (exists && (format || !is_catalog_spec(spec))) {
    const auto t0 = clock::now();
    Mesh mesh = read_mesh(spec);  // UsageError for an unknown extension; InputError for directories, unreadable files, bad data
    const auto t1 = clock::now();
    ConvexPolytope p = hull ? ConvexPolytope::hull(mesh.points, spec) : ConvexPolytope::from_mesh(mesh, spec);
    if (phases) *phases = {seconds(t0, t1), seconds(t1, clock::now())};
    return p;
  }
  if (is_catalog_spec(spec)) {
    const auto t0 = clock::now();
    ConvexPolytope p = catalog_polytope(spec);
    const auto t1 = clock::now();
    if (hull) p = ConvexPolytope::hull(p.coordinates(), spec);
    if (phases) *phases = {seconds(t0, t1), seconds(t1, clock::now())};
    return p;
  }
  if (format) throw InputError(spec, "", "no such file");
  const std::string best = closest_catalog_name(spec);
  throw UsageError("'" + spec + "' is neither a file nor a catalog name" +
                   (best.empty() ? std::string() : " (did you mean '" + best + "'?)") + "; see 'minksum gen --help'");
}

}  // namespace minksum
