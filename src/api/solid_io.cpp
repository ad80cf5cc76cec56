// Writing a solid's boundary (<minksum/solid_io.hpp>).
#include <minksum/solid_io.hpp>

namespace minksum {

Mesh writable_solid(const Mesh& boundary, Format format, const WriteOptions& options, const std::string& name,
                    RoundedSolid* rounded_out) {
  RoundedSolid rounded;
  if (!options.exact) rounded = round_solid(boundary, format == Format::stl && options.binary, name);
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
