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
// mesh.points (so each point is stored once, in the mesh).  Double points are
// compared by their bits (zeros unsigned), rational ones by value; the two
// kinds never coincide (a rational token equal to a double is read as it).
class Welder {
 public:
  explicit Welder(Mesh& mesh) : mesh_(mesh), slots_(64, kNoIndex) {}
  Index add(Coordinate (&c)[3]) {
    const bool dbl = !c[0].exact && !c[1].exact && !c[2].exact;
    std::uint64_t h;
    Point3 p;
    if (dbl) {
      h = 0x9e3779b97f4a7c15ULL;
      for (int k = 0; k < 3; ++k) {
        const double d = c[k].d == 0 ? 0.0 : c[k].d;
        std::uint64_t b;
        std::memcpy(&b, &d, 8);
        h = (h ^ b) * 0xbf58476d1ce4e5b9ULL;
        h ^= h >> 31;
      }
    } else {
      auto value = [](Coordinate& x) { return x.exact ? std::move(*x.exact) : Rational(x.d); };
      p = Point3(value(c[0]), value(c[1]), value(c[2]));
      h = hash_value(p);
      h ^= h >> 33;  // spread the bits: the table uses the low ones
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 33;
    }
    std::size_t mask = slots_.size() - 1;
    for (std::size_t i = h & mask;; i = (i + 1) & mask) {
      const Index s = slots_[i];
      if (s == kNoIndex) break;
      if (hashes_[s] != h || mesh_.points.is_double(s) != dbl) continue;
      if (dbl) {
        const Vec3d& q = mesh_.points.approx(s);
        if (q.x == c[0].d && q.y == c[1].d && q.z == c[2].d) return s;
      } else if (mesh_.points.exact_ref(s) == p) {
        return s;
      }
    }
    const auto index = static_cast<Index>(mesh_.points.size());
    if (dbl) mesh_.points.push_back(Vec3d{c[0].d, c[1].d, c[2].d});
    else mesh_.points.push_back(p);
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
        mesh.points.push_back(Vec3d{double(c[0]), double(c[1]), double(c[2])});
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
      Coordinate c[3];
      for (int k = 0; k < 3; ++k) {
        need("a coordinate");
        c[k] = read_coordinate(t, name, cur.token_line());
      }
      face.push_back(weld.add(c));
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
