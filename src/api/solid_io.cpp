// Writing a solid's boundary (<minksum/solid_io.hpp>).
#include <minksum/solid_io.hpp>

#include <minksum/polytope.hpp>

#include <optional>

namespace minksum {

namespace {

// The solid bounded by `boundary` as a convex polytope, when it is one: the
// boundary validated as a convex polytope's, or else the exact hull of its
// points when the hull's volume equals the solid's (the solid lies in its
// hull; two closed regular sets, one inside the other, of equal volume are
// equal).
std::optional<ConvexPolytope> convex_solid(const Mesh& boundary, const std::string& name) {
  try {
    return ConvexPolytope::from_mesh(boundary, name);
  } catch (const std::exception&) {
  }
  try {
    ConvexPolytope hull = ConvexPolytope::hull(boundary.points.to_points(), name);
    if (hull.volume() == mesh_volume(boundary)) return hull;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// A convex solid (the erosion or the opening of a convex part) whose
// rounding folds its thin faces over: written as a convex polytope is, the
// exact convex hull of its rounded vertices (writable_polytope), which is a
// valid solid within the largest rounding displacement of the exact one.
std::optional<Mesh> writable_convex_solid(const Mesh& boundary, Format format, const WriteOptions& options,
                                          const std::string& name, RoundedSolid* rounded_out) {
  const std::optional<ConvexPolytope> convex = convex_solid(boundary, name);
  if (!convex) return std::nullopt;
  RoundingReport report;
  ConvexPolytope written;
  try {
    written = writable_polytope(*convex, format, options, &report);
  } catch (const UnrepresentableError&) {
    return std::nullopt;  // beyond the format's range: round_solid's error stands
  }
  if (rounded_out) {
    rounded_out->rounded_coordinates = report.coordinates;
    rounded_out->max_displacement = report.max_displacement;
    rounded_out->grid = 0;
  }
  Mesh out = written.to_mesh();
  return format == Format::stl ? triangulate(out, name) : out;
}

}  // namespace

Mesh writable_solid(const Mesh& boundary, Format format, const WriteOptions& options, const std::string& name,
                    RoundedSolid* rounded_out) {
  RoundedSolid rounded;
  if (!options.exact) {
    try {
      rounded = round_solid(boundary, format == Format::stl && options.binary, name);
    } catch (const RoundingError&) {
      if (auto convex = writable_convex_solid(boundary, format, options, name, rounded_out)) return std::move(*convex);
      throw;
    }
  }
  // round_solid's mesh also when nothing was rounded but the surface,
  // touching itself, was cut apart (points moved).
  const bool changed = rounded.rounded_coordinates > 0 || rounded.max_displacement > 0;
  Mesh out = changed ? std::move(rounded.mesh) : format == Format::stl ? triangulate(boundary, name) : boundary;
  if (rounded_out) {
    rounded_out->rounded_coordinates = rounded.rounded_coordinates;
    rounded_out->max_displacement = rounded.max_displacement;
    rounded_out->grid = rounded.grid;
  }
  return out;
}

RoundedSolid write_solid(const std::string& path, const Mesh& boundary, const WriteOptions& options) {
  const Format format = output_format(path, options);
  if (boundary.faces.empty()) {  // nothing left (an erosion): a file of the format with no faces
    write_mesh(path, boundary, options);
    return {};
  }
  RoundedSolid rounded;
  write_mesh(path, writable_solid(boundary, format, options, path, &rounded), options);
  return rounded;
}

}  // namespace minksum
