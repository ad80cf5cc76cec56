// Operand resolution: file or catalog name (see operand.hpp).
#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/operand.hpp>

#include "mesh/builder.hpp"

#include <chrono>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>

namespace minksum {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// A file operand followed by transforms, "FILE@TRANSFORM@...": the longest
// prefix of `spec` ending before an '@' that is an existing file (a name that
// itself holds '@' still reads as it is, as an existing file comes first),
// and the transforms after it; nothing when there is none.
struct FileWithTransforms {
  std::string file, transforms;
};
std::optional<FileWithTransforms> file_with_transforms(const std::string& spec) {
  struct stat st{};
  for (std::size_t at = spec.rfind('@'); at != std::string::npos && at > 0; at = spec.rfind('@', at - 1)) {
    const std::string file = spec.substr(0, at);
    // As for a plain name: a stray file called "cube" does not shadow the catalog.
    if (::stat(file.c_str(), &st) == 0 && (format_from_path(file) || !is_catalog_spec(file)))
      return FileWithTransforms{file, spec.substr(at + 1)};
  }
  return std::nullopt;
}

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
  if (!exists && file_with_transforms(spec)) return true;
  if (const std::size_t at = spec.find('@'); at != std::string::npos && at > 0 && format_from_path(spec.substr(0, at)))
    throw InputError(spec.substr(0, at), "", "no such file");  // a missing file followed by transforms
  unknown_operand(spec, format);
}

// The file's mesh, in the format of its extension or else `given`: UsageError
// for an unknown extension (and no format given); InputError for
// directories, unreadable files, bad data.  "FILE@TRANSFORM@..." is FILE's
// mesh with the transforms applied (UsageError for a bad one, before reading).
Mesh read_file_operand(const std::string& spec, std::optional<Format> given) {
  std::string file = spec, transforms;
  if (::access(spec.c_str(), F_OK) != 0)
    if (auto f = file_with_transforms(spec)) {
      file = f->file;
      transforms = f->transforms;
      Mesh probe;
      apply_transforms(probe, spec, transforms);  // a bad transform is a usage error before any reading
    }
  Mesh m = format_from_path(file) || !given ? read_mesh(file) : read_mesh(file, *given);
  if (!transforms.empty()) apply_transforms(m, spec, transforms);
  return m;
}

// What differs between loading a polytope and loading a set of any
// dimension: validating a mesh (or taking its points' hull), building a
// catalog name, taking the hull of a catalog object's points.
template <class T>
struct Kind;
template <>
struct Kind<ConvexPolytope> {
  static ConvexPolytope from_mesh(const Mesh& m, const std::string& name, bool hull) {
    return hull ? ConvexPolytope::hull(m.points, name) : ConvexPolytope::from_mesh(m, name);
  }
  static ConvexPolytope catalog(const std::string& spec) { return catalog_polytope(spec); }
  static ConvexPolytope hull_of(const ConvexPolytope& p, const std::string& spec) {
    return ConvexPolytope::hull(p.coordinates(), spec);
  }
};
template <>
struct Kind<ConvexSet> {
  static ConvexSet from_mesh(const Mesh& m, const std::string& name, bool hull) {
    return hull ? ConvexSet::hull(m.points, name) : ConvexSet::from_mesh(m, name);
  }
  static ConvexSet catalog(const std::string& spec) { return catalog_convex_set(spec); }
  static ConvexSet hull_of(const ConvexSet& s, const std::string& spec) { return ConvexSet::hull(s.vertices(), spec); }
};

// The mesh read (from t0 on) validated, or its hull taken; phases timed.
template <class T>
T validate(const Mesh& mesh, const std::string& name, bool hull, LoadPhases* phases, Clock::time_point t0) {
  const auto t1 = Clock::now();
  T p = Kind<T>::from_mesh(mesh, name, hull);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return p;
}

template <class T>
T load_stream(std::istream& in, Format format, const std::string& name, bool hull, LoadPhases* phases) {
  const auto t0 = Clock::now();
  return validate<T>(read_mesh(in, format, name), name, hull, phases, t0);
}

template <class T>
T load_named(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> given) {
  if (is_file_operand(spec)) {
    const auto t0 = Clock::now();
    return validate<T>(read_file_operand(spec, given), spec, hull, phases, t0);
  }
  const auto t0 = Clock::now();
  std::optional<T> p;
  bool hulled = false;
  try {
    p = Kind<T>::catalog(spec);
  } catch (const NotConvexError&) {
    if (!hull) throw;
    // --hull on a non-convex solid of the catalog: the hull of its points, as for a file.
    p = Kind<T>::from_mesh(catalog_mesh(spec), spec, true);
    hulled = true;
  }
  const auto t1 = Clock::now();
  if (hull && !hulled) p = Kind<T>::hull_of(*p, spec);
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return std::move(*p);
}
}  // namespace

ConvexPolytope load_polytope(std::istream& in, Format format, const std::string& name, bool hull,
                             LoadPhases* phases) {
  return load_stream<ConvexPolytope>(in, format, name, hull, phases);
}

ConvexPolytope load_polytope(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> given) {
  return load_named<ConvexPolytope>(spec, hull, phases, given);
}

ConvexSet load_convex_set(std::istream& in, Format format, const std::string& name, bool hull, LoadPhases* phases) {
  return load_stream<ConvexSet>(in, format, name, hull, phases);
}

ConvexSet load_convex_set(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> given) {
  return load_named<ConvexSet>(spec, hull, phases, given);
}

namespace {
// The polytope of `mesh` when it is convex, else the mesh itself.
AnyOperand convex_or_mesh(Mesh mesh, const std::string& name, LoadPhases* phases, Clock::time_point t0) {
  AnyOperand o;
  const auto t1 = Clock::now();
  try {
    if (mesh.faces.size() == 1) {
      ConvexSet set = ConvexSet::from_mesh(mesh, name);  // one face: a polygon
      if (set.full()) o.polytope = std::move(set).release_polytope();
      else o.flat = std::move(set);
    } else if (std::optional<ConvexPolytope> p = PolytopeBuilder::build_if_convex(mesh, name)) {
      o.polytope = std::move(*p);
    } else {
      o.mesh = std::move(mesh);  // a closed surface, not convex
    }
  } catch (const InputError&) {  // not a convex set: validate_solid says what it is
    o.mesh = std::move(mesh);
  }
  if (phases) *phases = {seconds(t0, t1), seconds(t1, Clock::now())};
  return o;
}
}  // namespace

AnyOperand load_any_operand(std::istream& in, Format format, const std::string& name, LoadPhases* phases) {
  const auto t0 = Clock::now();
  return convex_or_mesh(read_mesh(in, format, name), name, phases, t0);
}

AnyOperand load_any_operand(const std::string& spec, LoadPhases* phases, std::optional<Format> given) {
  const auto t0 = Clock::now();
  if (is_file_operand(spec)) return convex_or_mesh(read_file_operand(spec, given), spec, phases, t0);
  AnyOperand o;
  // A non-convex solid of the catalog is asked for as a mesh directly (no
  // NotConvexError to catch: a process's first exception costs
  // milliseconds, mesh/builder.hpp).
  if (is_nonconvex_catalog_spec(spec)) {
    o.mesh = catalog_mesh(spec);
    if (phases) *phases = {seconds(t0, Clock::now()), 0};
    return o;
  }
  ConvexSet set = catalog_convex_set(spec);
  if (set.full()) o.polytope = std::move(set).release_polytope();
  else o.flat = std::move(set);
  if (phases) *phases = {seconds(t0, Clock::now()), 0};
  return o;
}

void unknown_operand(const std::string& spec, std::optional<Format> format) {
  if (format) throw InputError(spec, "", "no such file");
  const std::string best = closest_catalog_name(spec);
  throw UsageError("'" + spec + "' is neither a file nor a catalog name" +
                   (best.empty() ? std::string() : " (did you mean '" + best + "'?)") + "; see 'minksum gen --help'");
}

}  // namespace minksum
