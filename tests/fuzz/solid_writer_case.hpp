// One input of the solid writer's fuzz target (solid_writer_fuzzer.cpp),
// shared with the normal suite, which runs every seed and regression input
// (tests/test_reliability.cpp, FuzzInputs.*): a solid of the catalog, scaled
// by m * 2^e (m a small fraction, e anywhere from far below the smallest
// float to far beyond the largest double) and moved, rounded to doubles or
// floats by round_solid and written as STL (ascii or binary) or OFF, in
// memory.  Any input must give either a RoundingError (a coordinate beyond
// the format's range, or no valid rounding) or a written file that reads
// back as a valid closed solid, its coordinates doubles (floats); never a
// signal, a sanitizer report, another exception or a hang.  (The
// command-line writer is this path: a RoundingError there is exit 1 and one
// line.)
#pragma once

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/nonconvex.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

namespace minksum_fuzz {

inline void check(bool ok, const char* what) {
  if (!ok) throw std::logic_error(std::string("property violated: ") + what);
}

// Bytes read in turn, zero past the end.
struct Bytes {
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t next() { return at < size ? data[at++] : 0; }
  std::int32_t next16() {
    const std::uint16_t high = next();
    const std::uint16_t low = next();
    return std::int32_t(std::int16_t(std::uint16_t(high << 8 | low)));
  }
};

inline minksum::Rational power_of_two(long e) {
  mpz_class p = 1;
  mpz_mul_2exp(p.get_mpz_t(), p.get_mpz_t(), static_cast<mp_bitcnt_t>(e < 0 ? -e : e));
  return e < 0 ? minksum::Rational(mpz_class(1), p) : minksum::Rational(p);
}

// One input: returns normally, or throws std::logic_error naming the
// violated property (a fuzz finding; a test failure in the normal suite).
inline void solid_writer_case(const std::uint8_t* data, std::size_t size) {
  using namespace minksum;
  static const char* const kSolids[] = {"tube", "lshape", "gear:6", "star:5", "ring:7", "torus:3:4"};
  Bytes in{data, size};
  const char* spec = kSolids[in.next() % (sizeof kSolids / sizeof *kSolids)];
  const std::uint8_t mode = in.next();
  // As the command writes: binary STL holds floats; ascii STL and OFF doubles.
  const Format format = (mode & 2) ? Format::off : Format::stl;
  const bool floats = format == Format::stl && (mode & 1);
  const bool binary = floats;
  // Scale m * 2^e: m = (1 + a) / (1 + b), e in [-1200, 1200].
  const long e = long(in.next16()) % 1201;
  const Rational m(long(in.next()) + 1, long(in.next()) + 1);
  const Rational scale = m * power_of_two(e);
  // Translation t * 2^f per axis: t a signed byte, f in [-1200, 1200].
  Point3 shift(Rational(0), Rational(0), Rational(0));
  for (int k = 0; k < 3; ++k) shift[k] = Rational(long(std::int8_t(in.next()))) * power_of_two(long(in.next16()) % 1201);

  const Mesh base = catalog_mesh(spec);
  Mesh moved;
  for (std::size_t i = 0; i < base.points.size(); ++i) moved.points.push_back(scale * base.points[i] + shift);
  moved.faces = base.faces;

  RoundedSolid rounded;
  try {
    rounded = round_solid(moved, floats, "fuzz");
  } catch (const RoundingError&) {
    return;  // refused: the command says so on one line, exit 1
  }
  // Every written coordinate is a double (a float with `floats`).
  for (std::size_t i = 0; i < rounded.mesh.points.size(); ++i) {
    const Point3 p = rounded.mesh.points[i];
    for (int k = 0; k < 3; ++k) {
      const double d = to_double(p[k]);
      check(std::isfinite(d) && Rational(d) == p[k], "a rounded coordinate is a finite double");
      if (floats) check(double(float(d)) == d, "a rounded coordinate is a float for binary STL");
    }
  }
  check(std::isfinite(rounded.max_displacement) && rounded.max_displacement >= 0, "the displacement is a number");
  std::ostringstream out;
  WriteOptions options;
  options.binary = binary;
  // As the command writes (write_solid_mesh): nothing rounded, the exact
  // polygons, cut exactly into triangles for STL (a fan of an L-shaped face
  // from a corner would cover its notch).
  const Mesh written = rounded.rounded_coordinates == 0 && format == Format::stl ? triangulate(rounded.mesh, "fuzz")
                                                                                 : rounded.mesh;
  try {
    write_mesh(out, written, format, options);
  } catch (const UnrepresentableError&) {
    check(false, "a rounded solid is representable in its format");
  }
  std::istringstream back(out.str());
  const Mesh again = read_mesh(back, format, "written");
  try {
    const Solid s = validate_solid(again, "written");
    check(sgn(s.volume) > 0, "the written solid has positive volume");
  } catch (const InputError& err) {
    throw std::logic_error(std::string("property violated: the written file reads back as a valid solid: ") +
                           err.what());
  }
}

}  // namespace minksum_fuzz
