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
//   * exactly equal vertices are welded (hashing the exact Point3), so the
//     triangles share indices; vertex indices follow first appearance.
//
// Writer: polygons are fan-triangulated (facets of a polytope are convex);
// the normal written is the unit normal of each triangle, rounded.  Ascii
// prints each coordinate as the shortest text reading back to its nearest
// double; binary STL stores 32-bit floats, so each coordinate is rounded to
// the nearest float (a coordinate beyond the float range is refused).
#include "io/readers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>
#include <unordered_map>

namespace minksum::io_detail {

namespace {

// Welds exactly equal points: an open-addressing table of indices into
// mesh.points (so each point is stored once, in the mesh).
class Welder {
 public:
  explicit Welder(Mesh& mesh) : mesh_(mesh), slots_(64, kNoIndex) {}
  Index add(Point3 p) {
    std::uint64_t h = hash_value(p);
    h ^= h >> 33;  // spread the bits: the table uses the low ones
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    std::size_t mask = slots_.size() - 1;
    for (std::size_t i = h & mask;; i = (i + 1) & mask) {
      const Index s = slots_[i];
      if (s == kNoIndex) break;
      if (hashes_[s] == h && mesh_.points[s] == p) return s;
    }
    const auto index = static_cast<Index>(mesh_.points.size());
    mesh_.points.push_back(std::move(p));
    hashes_.push_back(h);
    if (2 * hashes_.size() > slots_.size()) {
      std::vector<Index>(slots_.size() * 2, kNoIndex).swap(slots_);
      for (Index v = 0; v < hashes_.size(); ++v) place(v);
    } else {
      place(index);
    }
    return index;
  }

 private:
  void place(Index v) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = hashes_[v] & mask;
    while (slots_[i] != kNoIndex) i = (i + 1) & mask;
    slots_[i] = v;
  }

  Mesh& mesh_;
  std::vector<Index> slots_;
  std::vector<std::uint64_t> hashes_;
};

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
  // Welding on the float bit patterns is welding on exact values once -0 is
  // made +0 (NaN is rejected): two finite floats are equal iff their bits
  // are.  Open addressing over indices into `keys`.
  using Key = std::array<std::uint32_t, 3>;
  auto hash = [](const Key& k) {
    std::uint64_t h = (std::uint64_t(k[0]) << 32 | k[1]) * 0x9e3779b97f4a7c15ULL;
    h ^= k[2] + (h >> 29);
    h *= 0xff51afd7ed558ccdULL;
    return h ^ (h >> 32);
  };
  Mesh mesh;
  std::vector<Key> keys;
  std::size_t table = 64;
  while (table < 6 * count) table *= 2;  // at most 3 * count distinct points, load <= 1/2
  std::vector<Index> slots(table, kNoIndex);
  const std::size_t mask = table - 1;
  mesh.faces.reserve(count);
  for (std::uint64_t t = 0; t < count; ++t) {
    const char* rec = data.data() + 84 + 50 * t + 12;
    std::vector<Index> tri(3);
    for (int v = 0; v < 3; ++v) {
      Key key;
      float c[3];
      for (int k = 0; k < 3; ++k) {
        std::uint32_t u = le32(rec + 12 * v + 4 * k);
        std::memcpy(&c[k], &u, 4);
        if (std::isnan(c[k])) throw InputError(name, "triangle " + std::to_string(t), "coordinate is NaN");
        if (std::isinf(c[k])) throw InputError(name, "triangle " + std::to_string(t), "coordinate is infinite");
        key[k] = c[k] == 0.0f ? 0u : u;
      }
      std::size_t i = hash(key) & mask;
      while (slots[i] != kNoIndex && keys[slots[i]] != key) i = (i + 1) & mask;
      if (slots[i] == kNoIndex) {
        slots[i] = static_cast<Index>(keys.size());
        keys.push_back(key);
        mesh.points.emplace_back(double(c[0]), double(c[1]), double(c[2]));
      }
      tri[v] = slots[i];
    }
    mesh.faces.push_back(std::move(tri));
  }
  return mesh;
}

Mesh read_ascii(std::string_view data, const std::string& name) {
  TextCursor cur(data, 0);
  std::string_view t;
  Mesh mesh;
  Welder weld(mesh);
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
      Rational c[3];
      for (int k = 0; k < 3; ++k) {
        need("a coordinate");
        c[k] = parse_coordinate(t, name, here());
      }
      face.push_back(weld.add(Point3(std::move(c[0]), std::move(c[1]), std::move(c[2]))));
      if (mesh.points.size() + 1 >= kNoIndex) throw InputError(name, here(), "too many vertices");
    }
    if (face.size() < 3)
      throw InputError(name, line_place(loop_line),
                       "facet has " + std::to_string(face.size()) + " vertices (at least 3 needed)");
    expect("endfacet");
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

// Unit normal of triangle (a, b, c), rounded (readers ignore it; it is
// informative only); zero for a degenerate triangle.
Vec3d unit_normal(const Point3& a, const Point3& b, const Point3& c) {
  {
    // Usually doubles suffice; the exact computation below handles the rest
    // (overflow, underflow, cancellation to zero).
    const Vec3d p = to_double(a), q = to_double(b), r = to_double(c);
    const double u[3] = {q.x - p.x, q.y - p.y, q.z - p.z}, v[3] = {r.x - p.x, r.y - p.y, r.z - p.z};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (std::isfinite(len) && len > 1e-150 && len < 1e150) return {n[0] / len, n[1] / len, n[2] / len};
  }
  Point3 n = cross(b - a, c - a);
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
  if (begins_with_solid(data)) return read_ascii(data, name);
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
      const Point3* p[3] = {&mesh.points[a], &mesh.points[b], &mesh.points[c]};
      Vec3d n = unit_normal(*p[0], *p[1], *p[2]);
      for (int i = 0; i < 3; ++i) put_le_float(out, static_cast<float>(n[i]));
      for (const Point3* q : p)
        for (int i = 0; i < 3; ++i) put_le_float(out, rational_to_float((*q)[i]));
      put_le(out, 0, 2);
    });
    return;
  }
  out << "solid minksum\n";
  each_triangle([&](Index a, Index b, Index c) {
    const Point3* p[3] = {&mesh.points[a], &mesh.points[b], &mesh.points[c]};
    Vec3d n = unit_normal(*p[0], *p[1], *p[2]);
    out << "  facet normal " << format_double(n.x) << ' ' << format_double(n.y) << ' ' << format_double(n.z)
        << "\n    outer loop\n";
    for (const Point3* q : p)
      out << "      vertex " << double_text(q->x) << ' ' << double_text(q->y) << ' ' << double_text(q->z) << '\n';
    out << "    endloop\n  endfacet\n";
  });
  out << "endsolid minksum\n";
}

}  // namespace minksum::io_detail
