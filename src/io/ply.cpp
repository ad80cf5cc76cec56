// PLY (Stanford polygon file format) 1.0: ascii, binary_little_endian,
// binary_big_endian.
//
// Reader:
//   * header lines: ply, format, comment, obj_info, element, property,
//     end_header ("\r\n" line ends accepted);
//   * scalar types char uchar short ushort int uint float double and their
//     aliases int8 uint8 int16 uint16 int32 uint32 float32 float64;
//   * element "vertex" must have scalar properties x, y, z (any type); other
//     vertex properties are skipped.  Binary float/double values are exact
//     rationals already and are taken exactly (NaN and Inf rejected); ascii
//     values are read with parse_number;
//   * element "face" must have a list property "vertex_indices" (or
//     "vertex_index") with integer count and index types; other properties
//     are skipped; indices are 0-based;
//   * any other element is skipped (its lists included);
//   * element counts are checked against the size of the body before anything
//     is allocated (binary: the exact minimum record size; ascii: 2 bytes per
//     value), and bytes or tokens after the last element are an error.
// Places in messages: "line N" for the header and ascii bodies, "vertex N" /
// "face N" / "byte N" (0-based) for binary bodies.
//
// Writer: x y z as double (shortest round-trip text in ascii), faces as
// "list uchar int vertex_indices" (uint counts when a face has more than 255
// vertices, uint indices beyond 2^31 - 1 vertices); binary is little-endian.
#include "io/readers.hpp"
#include "kernel/big_array.hpp"

#include <cmath>
#include <cstring>
#include <ostream>
#include <vector>

namespace minksum::io_detail {

namespace {

enum class Type { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<Type> parse_type(std::string_view s) {
  if (s == "char" || s == "int8") return Type::i8;
  if (s == "uchar" || s == "uint8") return Type::u8;
  if (s == "short" || s == "int16") return Type::i16;
  if (s == "ushort" || s == "uint16") return Type::u16;
  if (s == "int" || s == "int32") return Type::i32;
  if (s == "uint" || s == "uint32") return Type::u32;
  if (s == "float" || s == "float32") return Type::f32;
  if (s == "double" || s == "float64") return Type::f64;
  return std::nullopt;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::i8: case Type::u8: return 1;
    case Type::i16: case Type::u16: return 2;
    case Type::i32: case Type::u32: case Type::f32: return 4;
    case Type::f64: return 8;
  }
  return 1;
}

bool is_float(Type t) { return t == Type::f32 || t == Type::f64; }

struct Property {
  std::string name;
  bool list = false;
  Type type = Type::f32;        // scalar type, or the item type of a list
  Type count_type = Type::u8;   // list count type
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;
  std::vector<Property> props;
};

enum class Encoding { ascii, little, big };

// A binary scalar: integers exactly as int64, floats as the double they are.
struct Scalar {
  bool floating = false;
  std::int64_t i = 0;
  double f = 0;
};

class Binary {
 public:
  Binary(std::string_view d, std::size_t pos, bool big) : d_(d), pos_(pos), big_(big) {}
  std::size_t pos() const { return pos_; }
  std::size_t left() const { return d_.size() - pos_; }
  bool skip(std::uint64_t n) {
    if (n > left()) return false;
    pos_ += static_cast<std::size_t>(n);
    return true;
  }
  bool read(Type t, Scalar& out) {
    const std::size_t n = type_size(t);
    if (n > left()) return false;
    unsigned char b[8];
    std::memcpy(b, d_.data() + pos_, n);
    pos_ += n;
    std::uint64_t u = 0;
    for (std::size_t k = 0; k < n; ++k) {
      std::size_t idx = big_ ? k : n - 1 - k;
      u = (u << 8) | b[idx];
    }
    out.floating = is_float(t);
    switch (t) {
      case Type::i8: out.i = std::int8_t(u); break;
      case Type::u8: out.i = std::uint8_t(u); break;
      case Type::i16: out.i = std::int16_t(u); break;
      case Type::u16: out.i = std::uint16_t(u); break;
      case Type::i32: out.i = std::int32_t(std::uint32_t(u)); break;
      case Type::u32: out.i = std::uint32_t(u); break;
      case Type::f32: {
        std::uint32_t w = std::uint32_t(u);
        float f;
        std::memcpy(&f, &w, 4);
        out.f = f;
        break;
      }
      case Type::f64: {
        double f;
        std::memcpy(&f, &u, 8);
        out.f = f;
        break;
      }
    }
    return true;
  }

 private:
  std::string_view d_;
  std::size_t pos_;
  bool big_;
};

std::string count_phrase(const Element& e, std::uint64_t n) {
  if (e.name == "vertex") return std::to_string(n) + (n == 1 ? " vertex" : " vertices");
  if (e.name == "face") return std::to_string(n) + (n == 1 ? " face" : " faces");
  return std::to_string(n) + " '" + e.name + "' element" + (n == 1 ? "" : "s");
}

}  // namespace

namespace {
void finish_points(PointList& points, std::vector<std::array<Coordinate, 3>>& coords) {
  points.reserve(coords.size());
  for (auto& c : coords) {
    Coordinate t[3] = {std::move(c[0]), std::move(c[1]), std::move(c[2])};
    push_point(points, t);
  }
  release(coords);
}
}  // namespace

Mesh read_ply(std::string_view data, const std::string& name) {
  // --- header ---------------------------------------------------------------
  std::size_t pos = 0, line_no = 0;
  auto next_line = [&](std::string_view& line) -> bool {
    if (pos >= data.size()) return false;
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) eol = data.size();
    line = data.substr(pos, eol - pos);
    pos = eol == data.size() ? eol : eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  };
  std::string_view line;
  if (!next_line(line) || line != "ply") {
    std::string_view got = data.substr(0, std::min<std::size_t>(data.size(), 8));
    if (auto nl = got.find_first_of("\r\n"); nl != std::string_view::npos) got = got.substr(0, nl);
    throw InputError(name, "line 1", "expected 'ply' magic, got " + quote(got));
  }

  std::optional<Encoding> encoding;
  std::vector<Element> elements;
  bool ended = false;
  std::vector<std::string_view> tok;
  while (next_line(line)) {
    const std::string place = line_place(line_no);
    tok.clear();
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && is_space(line[i])) ++i;
      std::size_t s = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > s) tok.push_back(line.substr(s, i - s));
    }
    if (tok.empty()) continue;
    const std::string_view key = tok[0];
    if (key == "end_header") {
      if (tok.size() != 1) throw InputError(name, place, "unexpected token " + quote(tok[1]) + " after end_header");
      ended = true;
      break;
    } else if (key == "comment" || key == "obj_info") {
      continue;
    } else if (key == "format") {
      if (encoding) throw InputError(name, place, "second 'format' line");
      if (tok.size() != 3) throw InputError(name, place, "expected 'format <encoding> 1.0'");
      if (tok[1] == "ascii") encoding = Encoding::ascii;
      else if (tok[1] == "binary_little_endian") encoding = Encoding::little;
      else if (tok[1] == "binary_big_endian") encoding = Encoding::big;
      else throw InputError(name, place, "unknown PLY format " + quote(tok[1]));
      if (tok[2] != "1.0" && tok[2] != "1")
        throw InputError(name, place, "unsupported PLY version " + quote(tok[2]) + " (1.0 expected)");
    } else if (key == "element") {
      if (tok.size() != 3) throw InputError(name, place, "expected 'element <name> <count>'");
      auto n = parse_unsigned(tok[2]);
      if (!n) throw InputError(name, place, "expected an element count, got " + quote(tok[2]));
      for (const auto& e : elements)
        if (e.name == tok[1]) throw InputError(name, place, "second element named " + quote(tok[1]));
      elements.push_back({std::string(tok[1]), *n, line_no, {}});
    } else if (key == "property") {
      if (elements.empty()) throw InputError(name, place, "property before any element");
      Property p;
      if (tok.size() >= 2 && tok[1] == "list") {
        if (tok.size() != 5) throw InputError(name, place, "expected 'property list <count type> <item type> <name>'");
        auto ct = parse_type(tok[2]);
        auto it = parse_type(tok[3]);
        if (!ct) throw InputError(name, place, "unknown property type " + quote(tok[2]));
        if (!it) throw InputError(name, place, "unknown property type " + quote(tok[3]));
        if (is_float(*ct)) throw InputError(name, place, "list count type must be an integer type");
        p.list = true;
        p.count_type = *ct;
        p.type = *it;
        p.name = std::string(tok[4]);
      } else {
        if (tok.size() != 3) throw InputError(name, place, "expected 'property <type> <name>'");
        auto t = parse_type(tok[1]);
        if (!t) throw InputError(name, place, "unknown property type " + quote(tok[1]));
        p.type = *t;
        p.name = std::string(tok[2]);
      }
      for (const auto& q : elements.back().props)
        if (q.name == p.name) throw InputError(name, place, "second property named " + quote(p.name));
      elements.back().props.push_back(std::move(p));
    } else {
      throw InputError(name, place, "unexpected header line starting with " + quote(key));
    }
  }
  if (!ended) throw InputError(name, "header", "header has no 'end_header' line");
  if (!encoding) throw InputError(name, "header", "header has no 'format' line");

  // --- the elements that matter -----------------------------------------------
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  int coord_prop[3] = {-1, -1, -1};
  int index_prop = -1;
  for (const auto& e : elements) {
    if (e.name == "vertex") {
      vertex = &e;
      for (std::size_t i = 0; i < e.props.size(); ++i)
        for (int k = 0; k < 3; ++k)
          if (e.props[i].name == std::string(1, char('x' + k))) {
            if (e.props[i].list)
              throw InputError(name, line_place(e.line), "vertex property '" + e.props[i].name + "' is a list");
            coord_prop[k] = int(i);
          }
      for (int k = 0; k < 3; ++k)
        if (coord_prop[k] < 0)
          throw InputError(name, line_place(e.line),
                           std::string("vertex element has no '") + char('x' + k) + "' property");
    } else if (e.name == "face") {
      face = &e;
      for (std::size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].list && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index")) {
          index_prop = int(i);
          break;
        }
      if (index_prop < 0)
        throw InputError(name, line_place(e.line), "face element has no list property 'vertex_indices'");
      if (is_float(e.props[std::size_t(index_prop)].type))
        throw InputError(name, line_place(e.line), "face vertex indices must have an integer type");
    }
  }
  if (!vertex) throw InputError(name, "header", "header has no 'vertex' element");
  const std::uint64_t nv = vertex->count;

  // --- counts against the body size, before allocating ------------------------
  const std::size_t body = pos;
  const std::uint64_t body_size = data.size() - body;
  {
    using U128 = unsigned __int128;
    U128 need = 0;
    for (const auto& e : elements) {
      std::uint64_t per = 0;
      for (const auto& p : e.props)
        per += *encoding == Encoding::ascii ? 2 : type_size(p.list ? p.count_type : p.type);
      need += U128(per) * e.count;
      U128 avail = U128(body_size) + (*encoding == Encoding::ascii ? 1 : 0);
      if (need > avail)
        throw InputError(name, line_place(e.line),
                         "header announces " + count_phrase(e, e.count) + " but only " + std::to_string(body_size) +
                             (body_size == 1 ? " byte follows" : " bytes follow") + " the header");
    }
    if (nv >= kNoIndex) throw InputError(name, line_place(vertex->line), "too many vertices");
  }

  Mesh mesh;
  // Coordinates as read (properties may come in any order), pushed once complete.
  std::vector<std::array<Coordinate, 3>> coords(nv);  // bounded by the body size (checked above)
  if (face) mesh.faces.reserve(face->count);

  auto face_error = [&](std::uint64_t f, std::int64_t v, const std::string& place) {
    if (v < 0)
      throw InputError(name, place, "face " + std::to_string(f) + " has negative vertex index " + std::to_string(v));
    throw InputError(name, place,
                     "face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + " but there are " +
                         std::to_string(nv) + " vertices");
  };

  if (*encoding == Encoding::ascii) {
    TextCursor cur(data, 0, body, line_no + 1);
    std::string_view t;
    for (const auto& e : elements) {
      if (e.props.empty()) continue;
      const bool is_vertex = &e == vertex, is_face = &e == face;
      for (std::uint64_t n = 0; n < e.count; ++n) {
        auto need = [&]() {
          if (!cur.next(t))
            throw InputError(name, line_place(cur.line()),
                             "file ends after " + std::to_string(n) + " of " + count_phrase(e, e.count));
        };
        std::vector<Index> indices;
        for (std::size_t pi = 0; pi < e.props.size(); ++pi) {
          const Property& p = e.props[pi];
          need();
          if (!p.list) {
            int k = -1;
            if (is_vertex)
              for (int c = 0; c < 3; ++c)
                if (coord_prop[c] == int(pi)) k = c;
            if (k >= 0) {
              coords[n][k] = read_coordinate(t, name, cur.token_line());
            } else if (!looks_numeric(t)) {
              throw InputError(name, line_place(cur.token_line()), "expected a number, got " + quote(t));
            }
            continue;
          }
          auto len = parse_unsigned(t);
          if (!len) throw InputError(name, line_place(cur.token_line()), "expected a list length, got " + quote(t));
          const bool is_index = is_face && int(pi) == index_prop;
          if (is_index && *len < 3)
            throw InputError(name, line_place(cur.token_line()),
                             "face " + std::to_string(n) + " has " + std::to_string(*len) +
                                 " vertices (at least 3 needed)");
          for (std::uint64_t j = 0; j < *len; ++j) {
            need();
            if (is_index) {
              auto v = parse_signed(t);
              if (!v) throw InputError(name, line_place(cur.token_line()), "expected a vertex index, got " + quote(t));
              if (*v < 0 || std::uint64_t(*v) >= nv) face_error(n, *v, line_place(cur.token_line()));
              indices.push_back(static_cast<Index>(*v));
            } else if (!looks_numeric(t)) {
              throw InputError(name, line_place(cur.token_line()), "expected a number, got " + quote(t));
            }
          }
        }
        if (is_face) mesh.faces.push_back(std::move(indices));
      }
    }
    if (cur.next(t))
      throw InputError(name, line_place(cur.token_line()),
                       "unexpected token " + quote(t) + " after the last element");
    finish_points(mesh.points, coords);
    return mesh;
  }

  Binary in(data, body, *encoding == Encoding::big);
  Scalar s;
  for (const auto& e : elements) {
    if (e.props.empty()) continue;
    const bool is_vertex = &e == vertex, is_face = &e == face;
    const char* what = is_vertex ? "vertex " : is_face ? "face " : nullptr;
    for (std::uint64_t n = 0; n < e.count; ++n) {
      const std::size_t start = in.pos();
      auto place = [&]() { return what ? what + std::to_string(n) : "byte " + std::to_string(start); };
      auto truncated = [&]() {
        throw InputError(name, place(), "file ends after " + std::to_string(n) + " of " + count_phrase(e, e.count));
      };
      std::vector<Index> indices;
      for (std::size_t pi = 0; pi < e.props.size(); ++pi) {
        const Property& p = e.props[pi];
        if (!p.list) {
          int k = -1;
          if (is_vertex)
            for (int c = 0; c < 3; ++c)
              if (coord_prop[c] == int(pi)) k = c;
          if (k < 0) {
            if (!in.skip(type_size(p.type))) truncated();
            continue;
          }
          if (!in.read(p.type, s)) truncated();
          if (s.floating) {
            if (std::isnan(s.f)) throw InputError(name, place(), "coordinate is NaN");
            if (std::isinf(s.f)) throw InputError(name, place(), "coordinate is infinite");
            coords[n][k] = {s.f, std::nullopt};
          } else if (s.i < (std::int64_t(1) << 53) && s.i > -(std::int64_t(1) << 53)) {
            coords[n][k] = {double(s.i), std::nullopt};
          } else {
            coords[n][k] = {0.0, Rational(static_cast<long>(s.i))};
          }
          continue;
        }
        if (!in.read(p.count_type, s)) truncated();
        if (s.i < 0)
          throw InputError(name, place(), "negative list length " + std::to_string(s.i));
        const auto len = static_cast<std::uint64_t>(s.i);
        const bool is_index = is_face && int(pi) == index_prop;
        if (is_index && len < 3)
          throw InputError(name, place(),
                           "face " + std::to_string(n) + " has " + std::to_string(len) + " vertices (at least 3 needed)");
        if (len > in.left() / type_size(p.type)) truncated();
        if (!is_index) {
          in.skip(len * type_size(p.type));
          continue;
        }
        indices.reserve(len);
        for (std::uint64_t j = 0; j < len; ++j) {
          in.read(p.type, s);
          if (s.i < 0 || std::uint64_t(s.i) >= nv) face_error(n, s.i, place());
          indices.push_back(static_cast<Index>(s.i));
        }
      }
      if (is_face) mesh.faces.push_back(std::move(indices));
    }
  }
  if (in.left() != 0)
    throw InputError(name, "byte " + std::to_string(in.pos()),
                     std::to_string(in.left()) + " bytes of unexpected data after the last element");
  finish_points(mesh.points, coords);
  return mesh;
}

void write_ply(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  std::size_t max_k = 0;
  for (const auto& f : mesh.faces) max_k = std::max(max_k, f.size());
  const bool wide_count = max_k > 255;
  const bool wide_index = mesh.points.size() > 0x7fffffffu;
  out << "ply\n"
      << "format " << (options.binary ? "binary_little_endian" : "ascii") << " 1.0\n"
      << "comment minksum\n"
      << "element vertex " << mesh.points.size() << '\n'
      << "property double x\nproperty double y\nproperty double z\n"
      << "element face " << mesh.faces.size() << '\n'
      << "property list " << (wide_count ? "uint" : "uchar") << ' ' << (wide_index ? "uint" : "int")
      << " vertex_indices\n"
      << "end_header\n";
  if (options.binary) {
    for (std::size_t v = 0; v < mesh.points.size(); ++v)
      for (int i = 0; i < 3; ++i) put_le_double(out, coordinate_double(mesh.points, v, i));
    for (const auto& f : mesh.faces) {
      put_le(out, f.size(), wide_count ? 4 : 1);
      for (Index v : f) put_le(out, v, 4);
    }
    return;
  }
  write_point_lines(out, mesh.points, false);
  write_counted_face_lines(out, mesh.faces);
}

}  // namespace minksum::io_detail
