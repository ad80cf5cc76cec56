// STL, ascii and binary.
//
// Detection by content: a file of exactly 84 + 50 * count bytes, count being
// the little-endian uint32 at byte 80, is binary even when its 80-byte header
// begins with "solid"; otherwise a file beginning with "solid" is ascii, and
// anything else is taken as binary (and rejected if its size does not match).
//
// Reader:
//   * binary: 80-byte header, uint32 count, then per triangle a normal (3
//     float32, ignored), 3 vertices (9 float32, taken exactly; NaN and Inf
//     rejected) and a 2-byte attribute (ignored);
//   * ascii: "solid [name]" { "facet normal nx ny nz" "outer loop"
//     ("vertex x y z")+ "endloop" "endfacet" } "endsolid [name]", keywords in
//     any case; coordinates read with parse_number; the normal is ignored; a
//     loop with more than 3 vertices is read as one polygon; several
//     solid ... endsolid blocks in one file are read as one mesh;
//   * exactly equal vertices are welded (weld_exact, by exact value), so the
//     triangles share indices; vertex indices follow first appearance.
//
// Writer: polygons are fan-triangulated (facets of a polytope are convex);
// the normal written is the unit normal of each triangle, rounded.  Ascii
// prints each coordinate as the shortest text reading back to its nearest
// double; binary STL stores 32-bit floats, so each coordinate is rounded to
// the nearest float (a coordinate beyond the float range is refused).
#include "io/readers.hpp"
#include "mesh/weld.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>

namespace minksum::io_detail {

namespace {

// The mesh of the corners read (raw, one point per corner, faces on them)
// with exactly equal points welded (weld_exact): vertex numbers follow
// first appearance.
Mesh welded_mesh(const PointList& raw, std::vector<std::vector<Index>>&& faces) {
  Welded w = welded(raw, weld_exact(raw));
  for (auto& face : faces)
    for (Index& v : face) v = w.id[v];
  Mesh mesh;
  mesh.points = std::move(w.points);
  mesh.faces = std::move(faces);
  return mesh;
}

std::uint32_t le32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

bool begins_with_solid(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && is_space(data[i])) ++i;
  if (data.size() - i < 5 || !iequals(data.substr(i, 5), "solid")) return false;
  return data.size() - i == 5 || is_space(data[i + 5]);
}

Mesh read_binary(std::string_view data, const std::string& name) {
  const std::uint64_t count = le32(data.data() + 80);
  const std::uint64_t need = 84 + 50 * count;
  if (data.size() < need) {
    const std::uint64_t whole = (data.size() - 84) / 50;
    if (whole == 0 || count > 2 * whole + 16)
      throw InputError(name, "byte 80",
                       "header announces " + std::to_string(count) + " triangles but the file has only " +
                           std::to_string(data.size()) + " bytes");
    throw InputError(name, "byte " + std::to_string(84 + 50 * whole),
                     "file ends after " + std::to_string(whole) + " of " + std::to_string(count) + " triangles");
  }
  if (data.size() > need)
    throw InputError(name, "byte " + std::to_string(need),
                     std::to_string(data.size() - need) + " bytes of unexpected data after the last of " +
                         std::to_string(count) + " triangles");
  // The floats as doubles (exact; PointList stores zeros unsigned), welded
  // after: two finite floats are equal iff their doubles are (NaN is
  // rejected).
  PointList raw;
  raw.reserve(3 * count);
  std::vector<std::vector<Index>> faces;
  faces.reserve(count);
  for (std::uint64_t t = 0; t < count; ++t) {
    const char* rec = data.data() + 84 + 50 * t + 12;
    std::vector<Index> tri(3);
    for (int v = 0; v < 3; ++v) {
      float c[3];
      for (int k = 0; k < 3; ++k) {
        std::uint32_t u = le32(rec + 12 * v + 4 * k);
        std::memcpy(&c[k], &u, 4);
        if (std::isnan(c[k])) throw InputError(name, "triangle " + std::to_string(t), "coordinate is NaN");
        if (std::isinf(c[k])) throw InputError(name, "triangle " + std::to_string(t), "coordinate is infinite");
      }
      tri[v] = static_cast<Index>(raw.size());
      raw.push_back(Vec3d{double(c[0]), double(c[1]), double(c[2])});
    }
    faces.push_back(std::move(tri));
  }
  return welded_mesh(raw, std::move(faces));
}

Mesh read_ascii(std::string_view data, const std::string& name) {
  TextCursor cur(data, 0);
  std::string_view t;
  PointList raw;  // one point per corner, welded at the end
  std::vector<std::vector<Index>> faces;
  auto here = [&] { return line_place(cur.token_line()); };
  auto need = [&](const char* what) {
    if (!cur.next(t))
      throw InputError(name, line_place(cur.line()), std::string("file ends where ") + what + " was expected");
  };
  auto expect = [&](const char* keyword) {
    need(keyword[0] == 'e' ? "'endsolid'" : "a keyword");
    if (!iequals(t, keyword))
      throw InputError(name, here(), std::string("expected '") + keyword + "', got " + quote(t));
  };
  auto skip_rest_of_line = [&] {
    while (cur.next_on_line(t)) {
    }
  };

  cur.next(t);  // "solid" (checked by the caller)
  skip_rest_of_line();
  for (;;) {
    if (!cur.next(t)) throw InputError(name, line_place(cur.line()), "file ends before 'endsolid'");
    if (iequals(t, "endsolid")) {
      skip_rest_of_line();
      if (!cur.next(t)) break;
      if (iequals(t, "solid")) {
        skip_rest_of_line();
        continue;
      }
      throw InputError(name, here(), "unexpected token " + quote(t) + " after 'endsolid'");
    }
    if (!iequals(t, "facet"))
      throw InputError(name, here(), "expected 'facet' or 'endsolid', got " + quote(t));
    need("'normal' or 'outer'");
    if (iequals(t, "normal")) {
      for (int k = 0; k < 3; ++k) {
        need("a normal coordinate");
        if (!looks_numeric(t)) throw InputError(name, here(), "expected a normal coordinate, got " + quote(t));
      }
      need("'outer'");
    }
    if (!iequals(t, "outer")) throw InputError(name, here(), "expected 'outer', got " + quote(t));
    expect("loop");
    std::vector<Index> face;
    std::size_t loop_line = cur.token_line();
    for (;;) {
      need("'vertex' or 'endloop'");
      if (iequals(t, "endloop")) break;
      if (!iequals(t, "vertex"))
        throw InputError(name, here(), "expected 'vertex' or 'endloop', got " + quote(t));
      Coordinate c[3];
      for (int k = 0; k < 3; ++k) {
        need("a coordinate");
        c[k] = read_coordinate(t, name, cur.token_line());
      }
      face.push_back(static_cast<Index>(raw.size()));
      if (c[0].exact || c[1].exact || c[2].exact) {
        auto value = [](Coordinate& x) { return x.exact ? std::move(*x.exact) : Rational(x.d); };
        raw.push_back(Point3(value(c[0]), value(c[1]), value(c[2])));
      } else {
        raw.push_back(Vec3d{c[0].d, c[1].d, c[2].d});
      }
      if (raw.size() + 1 >= kNoIndex) throw InputError(name, here(), "too many vertices");
    }
    if (face.size() < 3)
      throw InputError(name, line_place(loop_line),
                       "facet has " + std::to_string(face.size()) + " vertices (at least 3 needed)");
    expect("endfacet");
    faces.push_back(std::move(face));
  }
  return welded_mesh(raw, std::move(faces));
}

// Unit normal of triangle (a, b, c), rounded (readers ignore it; it is
// informative only); zero for a degenerate triangle.
Vec3d unit_normal(const PointList& pts, Index ia, Index ib, Index ic) {
  {
    // Usually doubles suffice; the exact computation below handles the rest
    // (overflow, underflow, cancellation to zero).
    const Vec3d p = pts.approx(ia), q = pts.approx(ib), r = pts.approx(ic);
    const double u[3] = {q.x - p.x, q.y - p.y, q.z - p.z}, v[3] = {r.x - p.x, r.y - p.y, r.z - p.z};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (std::isfinite(len) && len > 1e-150 && len < 1e150) return {n[0] / len, n[1] / len, n[2] / len};
  }
  const Point3 a = pts.exact(ia);
  Point3 n = cross(pts.exact(ib) - a, pts.exact(ic) - a);
  if (is_zero(n)) return {};
  // Scale by a power of two so that the largest component is near 1 before
  // rounding, which keeps huge and tiny coordinates out of overflow/underflow.
  long e = std::numeric_limits<long>::min();
  for (int i = 0; i < 3; ++i)
    if (sgn(n[i]) != 0)
      e = std::max(e, long(mpz_sizeinbase(n[i].get_num_mpz_t(), 2)) - long(mpz_sizeinbase(n[i].get_den_mpz_t(), 2)));
  double d[3];
  for (int i = 0; i < 3; ++i) {
    Rational s = n[i];
    if (e > 0) mpq_div_2exp(s.get_mpq_t(), s.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
    else if (e < 0) mpq_mul_2exp(s.get_mpq_t(), s.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
    d[i] = to_double(s);
  }
  double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {d[0] / len, d[1] / len, d[2] / len};
}

}  // namespace

Mesh read_stl(std::string_view data, const std::string& name) {
  if (data.size() >= 84) {
    const std::uint64_t count = le32(data.data() + 80);
    if (84 + 50 * count == data.size()) return read_binary(data, name);
  }
  if (const std::string_view text = without_utf8_bom(data); begins_with_solid(text)) return read_ascii(text, name);
  if (data.size() < 84)
    throw InputError(name, "",
                     "not an STL file: shorter than a binary STL header (" + std::to_string(data.size()) +
                         " bytes) and does not begin with 'solid'");
  return read_binary(data, name);
}

void write_stl(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  std::uint64_t triangles = 0;
  for (const auto& f : mesh.faces)
    if (f.size() >= 3) triangles += f.size() - 2;
  auto each_triangle = [&](auto&& emit) {
    for (const auto& f : mesh.faces)
      for (std::size_t i = 1; i + 1 < f.size(); ++i) emit(f[0], f[i], f[i + 1]);
  };

  if (options.binary) {
    if (triangles > 0xffffffffu) throw UsageError("too many triangles for binary STL");
    char header[80] = {};
    const char* text = "minksum binary STL";
    std::memcpy(header, text, std::strlen(text));
    out.write(header, 80);
    put_le(out, triangles, 4);
    each_triangle([&](Index a, Index b, Index c) {
      Vec3d n = unit_normal(mesh.points, a, b, c);
      for (int i = 0; i < 3; ++i) put_le_float(out, static_cast<float>(n[i]));
      for (Index q : {a, b, c})
        for (int i = 0; i < 3; ++i) put_le_float(out, coordinate_float(mesh.points, q, i));
      put_le(out, 0, 2);
    });
    return;
  }
  out << "solid minksum\n";
  each_triangle([&](Index a, Index b, Index c) {
    Vec3d n = unit_normal(mesh.points, a, b, c);
    std::string text = "  facet normal " + format_double(n.x) + ' ' + format_double(n.y) + ' ' +
                       format_double(n.z) + "\n    outer loop\n";
    for (Index q : {a, b, c}) {
      text += "      vertex ";
      append_point(text, mesh.points, q, false);
    }
    text += "    endloop\n  endfacet\n";
    out.write(text.data(), std::streamsize(text.size()));
  });
  out << "endsolid minksum\n";
}

}  // namespace minksum::io_detail
