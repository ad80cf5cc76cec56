// Wavefront OBJ, polygonal subset.
//
// Reader (line based; '#' starts a comment; a line ending in '\' continues on
// the next one):
//   * "v x y z"          a vertex; coordinates read with parse_number, so
//                        integers of any length and p/q are exact;
//   * "v x y z w"        a homogeneous vertex: w = 1 is ignored, any other
//                        non-zero w divides x, y and z exactly (the result is
//                        the rational x/w, y/w, z/w); w = 0 is an error;
//   * "v x y z r g b [a]" the common vertex-colour extension: the colour
//                        numbers are ignored;
//   * "f a b c ..."      a polygon; each token is i, i/j, i//k or i/j/k, only
//                        the vertex index i is used; indices are 1-based,
//                        negative ones count back from the last vertex
//                        defined so far (-1 = the latest); "fo" is taken as f;
//   * vt vn vp g o s usemtl mtllib l p mg maplib usemap lod bevel c_interp
//     d_interp shadow_obj trace_obj ctech stech are ignored;
//   * free-form geometry (cstype, curv, surf, ...) is refused, and any other
//     statement is an error ("unexpected token").
// Messages number faces and vertices from 1, as OBJ does.
#include "io/readers.hpp"

#include <array>
#include <ostream>
#include <vector>

namespace minksum::io_detail {

namespace {

bool is_one_of(std::string_view s, std::initializer_list<std::string_view> list) {
  for (auto x : list)
    if (s == x) return true;
  return false;
}

void split(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

}  // namespace

Mesh read_obj(std::string_view data, const std::string& name) {
  Mesh mesh;
  std::vector<std::size_t> face_line;  // for the deferred range check
  std::vector<std::string_view> tokens;
  std::string joined;                  // storage for continued lines
  std::size_t pos = 0, line_no = 0;

  while (pos < data.size()) {
    // One logical line, possibly continued with a trailing backslash.
    ++line_no;
    const std::size_t first_line = line_no;
    std::size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) eol = data.size();
    std::string_view line = data.substr(pos, eol - pos);
    pos = eol + 1;
    auto strip_end = [](std::string_view s) {
      while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
      return s;
    };
    std::string_view trimmed = strip_end(line);
    if (!trimmed.empty() && trimmed.back() == '\\' && trimmed.find('#') == std::string_view::npos) {
      joined.assign(trimmed.substr(0, trimmed.size() - 1));
      while (pos < data.size()) {
        ++line_no;
        eol = data.find('\n', pos);
        if (eol == std::string_view::npos) eol = data.size();
        std::string_view more = strip_end(data.substr(pos, eol - pos));
        pos = eol + 1;
        joined += ' ';
        if (!more.empty() && more.back() == '\\' && more.find('#') == std::string_view::npos) {
          joined.append(more.substr(0, more.size() - 1));
          continue;
        }
        joined.append(more);
        break;
      }
      line = joined;
    }
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    split(line, tokens);
    if (tokens.empty()) continue;
    const std::string place = line_place(first_line);
    const std::string_view key = tokens[0];

    if (key == "v") {
      const std::size_t n = tokens.size() - 1;
      if (n < 3)
        throw InputError(name, place, "vertex has " + std::to_string(n) + " coordinates (3 needed)");
      if (n == 5 || n > 7)
        throw InputError(name, place, "unexpected token " + quote(tokens[n == 5 ? 5 : 8]) + " after the vertex");
      Coordinate c[3];
      for (int k = 0; k < 3; ++k) c[k] = read_coordinate(tokens[1 + k], name, place);
      if (n == 4) {
        Rational w = parse_coordinate(tokens[4], name, place);
        if (sgn(w) == 0) throw InputError(name, place, "vertex has w = 0 (a point at infinity)");
        if (w != 1)
          for (auto& x : c) {
            Rational v = x.exact ? *x.exact : Rational(x.d);
            v /= w;
            x.exact = std::move(v);
          }
      } else if (n >= 6) {
        for (std::size_t k = 4; k <= n; ++k)
          if (!looks_numeric(tokens[k]))
            throw InputError(name, place, "expected a colour number, got " + quote(tokens[k]));
      }
      if (mesh.points.size() + 1 >= kNoIndex) throw InputError(name, place, "too many vertices");
      push_point(mesh.points, c);
    } else if (key == "f" || key == "fo") {
      const std::size_t face_no = mesh.faces.size() + 1;
      const std::size_t n = tokens.size() - 1;
      if (n < 3)
        throw InputError(name, place,
                         "face " + std::to_string(face_no) + " has " + std::to_string(n) +
                             " vertices (at least 3 needed)");
      std::vector<Index> face;
      face.reserve(n);
      for (std::size_t k = 1; k <= n; ++k) {
        std::string_view t = tokens[k];
        // Split i[/j[/k]].
        std::array<std::string_view, 3> part{};
        std::size_t parts = 0, start = 0;
        for (std::size_t i = 0; i <= t.size(); ++i) {
          if (i == t.size() || t[i] == '/') {
            if (parts == 3)
              throw InputError(name, place, "expected a face vertex i, i/j, i//k or i/j/k, got " + quote(t));
            part[parts++] = t.substr(start, i - start);
            start = i + 1;
          }
        }
        if (part[0].empty() || (parts >= 2 && !part[1].empty() && !parse_signed(part[1])) ||
            (parts == 3 && !part[2].empty() && !parse_signed(part[2])) || (parts == 3 && part[2].empty()))
          throw InputError(name, place, "expected a face vertex i, i/j, i//k or i/j/k, got " + quote(t));
        auto idx = parse_signed(part[0]);
        if (!idx) throw InputError(name, place, "expected a vertex index, got " + quote(part[0]));
        std::int64_t v;
        const auto defined = static_cast<std::int64_t>(mesh.points.size());
        if (*idx == 0)
          throw InputError(name, place, "face " + std::to_string(face_no) +
                                            " has vertex index 0 (OBJ indices start at 1)");
        if (*idx < 0) {
          v = defined + *idx;
          if (v < 0)
            throw InputError(name, place,
                             "face " + std::to_string(face_no) + " refers to vertex " + std::to_string(*idx) +
                                 " but only " + std::to_string(defined) + " vertices are defined so far");
        } else {
          v = *idx - 1;  // range checked when all vertices are known
          if (v >= std::int64_t(kNoIndex))
            throw InputError(name, place,
                             "face " + std::to_string(face_no) + " refers to vertex " + std::to_string(*idx) +
                                 " but there are " + std::to_string(defined) + " vertices");
        }
        face.push_back(static_cast<Index>(v));
      }
      mesh.faces.push_back(std::move(face));
      face_line.push_back(first_line);
    } else if (is_one_of(key, {"vt", "vn", "vp", "g", "o", "s", "usemtl", "mtllib", "l", "p", "mg",
                               "maplib", "usemap", "lod", "bevel", "c_interp", "d_interp", "shadow_obj",
                               "trace_obj", "ctech", "stech"})) {
      // ignored
    } else if (is_one_of(key, {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim",
                               "hole", "scrv", "sp", "end", "con"})) {
      throw InputError(name, place, "free-form geometry (" + quote(key) + ") is not supported");
    } else if (looks_numeric(key) && mesh.points.size() == 0 && mesh.faces.empty()) {
      // Some OBJ writers (FCL's test meshes among them) put the vertex and
      // face counts on a line of their own before the statements.
      throw InputError(name, place,
                       "unexpected token " + quote(key) +
                           " (a line of numbers before the first statement, like a vertex and face count, is not "
                           "OBJ: remove that line and the rest reads as OBJ)");
    } else {
      throw InputError(name, place, "unexpected token " + quote(key));
    }
  }

  const std::size_t nv = mesh.points.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (Index v : mesh.faces[f])
      if (v >= nv)
        throw InputError(name, line_place(face_line[f]),
                         "face " + std::to_string(f + 1) + " refers to vertex " + std::to_string(std::uint64_t(v) + 1) +
                             " but there are " + std::to_string(nv) + " vertices");
  return mesh;
}

void write_obj(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  out << "# minksum: " << mesh.points.size() << " vertices, " << mesh.faces.size() << " faces";
  if (options.exact) out << "; coordinates are exact rationals (integers or p/q)";
  out << '\n';
  std::string line;
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    line.assign("v ");
    append_point(line, mesh.points, i, options.exact);
    out.write(line.data(), std::streamsize(line.size()));
  }
  for (const auto& f : mesh.faces) {
    line.assign("f");
    for (Index v : f) {
      line += ' ';
      append_index(line, std::uint64_t(v) + 1);
    }
    line += '\n';
    out.write(line.data(), std::streamsize(line.size()));
  }
}

}  // namespace minksum::io_detail
