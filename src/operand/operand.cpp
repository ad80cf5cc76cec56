// Operand resolution: file or catalog name (see operand.hpp).
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include <chrono>
#include <sys/stat.h>

namespace minksum {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// True when `spec` names a file to read: an existing file, unless its name
// has no known extension and is a catalog spec (a stray file called "cube"
// does not shadow the catalog).  False for a catalog spec; for neither, the
// error: InputError "no such file" for a name with a known extension, else
// UsageError with the closest catalog name.
bool is_file_operand(const std::string& spec) {
  const auto format = format_from_path(spec);
  struct stat st{};
  const bool exists = ::stat(spec.c_str(), &st) == 0;
  if (exists && (format || !is_catalog_spec(spec))) return true;
  if (is_catalog_spec(spec)) return false;
  if (format) throw InputError(spec, "", "no such file");
  const std::string best = closest_catalog_name(spec);
  throw UsageError("'" + spec + "' is neither a file nor a catalog name" +
                   (best.empty() ? std::string() : " (did you mean '" + best + "'?)") + "; see 'minksum gen --help'");
}

// The file's mesh, in the format of its extension or else `given`: UsageError
// for an unknown extension (and no format given); InputError for
// directories, unreadable files, bad data.
Mesh read_file_operand(const std::string& spec, std::optional<Format> given) {
  return format_from_path(spec) || !given ? read_mesh(spec) : read_mesh(spec, *given);
}

// The mesh read (from t0 on) validated, or its hull taken; phases timed.
ConvexPolytope validate(const Mesh& mesh, const std::string& name, bool hull, LoadPhases* phases,
                        Clock::time_point t0) {
  const auto t1 = Clock::now();
  ConvexPolytope p = hull ? ConvexPolytope::hull(mesh.points, name) : ConvexPolytope::from_mesh(mesh, name);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return p;
}

// The same for a set of any dimension (load_convex_set).
ConvexSet validate_set(const Mesh& mesh, const std::string& name, bool hull, LoadPhases* phases,
                       Clock::time_point t0) {
  const auto t1 = Clock::now();
  ConvexSet s = hull ? ConvexSet::hull(mesh.points, name) : ConvexSet::from_mesh(mesh, name);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return s;
}
}  // namespace

ConvexSet load_convex_set(std::istream& in, Format format, const std::string& name, bool hull,
                          LoadPhases* phases) {
  const auto t0 = Clock::now();
  return validate_set(read_mesh(in, format, name), name, hull, phases, t0);
}

ConvexSet load_convex_set(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> given) {
  if (is_file_operand(spec)) {
    const auto t0 = Clock::now();
    return validate_set(read_file_operand(spec, given), spec, hull, phases, t0);
  }
  const auto t0 = Clock::now();
  ConvexSet s = catalog_convex_set(spec);
  const auto t1 = Clock::now();
  if (hull) s = ConvexSet::hull(s.vertices(), spec);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return s;
}

ConvexPolytope load_polytope(std::istream& in, Format format, const std::string& name, bool hull,
                             LoadPhases* phases) {
  const auto t0 = Clock::now();
  return validate(read_mesh(in, format, name), name, hull, phases, t0);
}

ConvexPolytope load_polytope(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> given) {
  if (is_file_operand(spec)) {
    const auto t0 = Clock::now();
    return validate(read_file_operand(spec, given), spec, hull, phases, t0);
  }
  const auto t0 = Clock::now();
  ConvexPolytope p = catalog_polytope(spec);
  const auto t1 = Clock::now();
  if (hull) p = ConvexPolytope::hull(p.coordinates(), spec);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return p;
}

}  // namespace minksum
