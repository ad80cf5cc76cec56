// VRML 2.0 (.wrl): one IndexedFaceSet per file.
//
// Reader:
//   * the file must begin with "#VRML V2.0 utf8";
//   * the scene graph is scanned for the IndexedFaceSet node, wherever it is
//     (Shape, Transform, Group, children ...); a second IndexedFaceSet is an
//     error ("more than one IndexedFaceSet"): one polytope per file.  A
//     geometry reused through USE is not a second node and is not read again;
//   * transforms are not applied.  An IndexedFaceSet inside a Transform whose
//     translation, rotation (non-zero angle) or scale (not 1 1 1) is not the
//     identity is rejected with an error, rather than read at the wrong place
//     (center and scaleOrientation have no effect when those three are the
//     identity);
//   * coord Coordinate { point [ x y z, ... ] } - numbers read with
//     parse_number (so p/q tokens are exact too);
//   * coord ExactCoordinate { ratPoint [ n/d n/d n/d, ... ] } - Fogel and
//     Halperin's extension for exact coordinates: each coordinate is one
//     token, "n/d" or a plain integer (any length);
//   * coord DEF name ... defines, coord USE name reuses, an earlier coordinate
//     node of an IndexedFaceSet;
//   * coordIndex [ i, j, k, -1, ... ] - 0-based, -1 ends a polygon, the last
//     -1 is optional; ccw FALSE reverses every polygon (keeping its first
//     vertex first); other fields (normal,
//     color, texCoord, solid, convex, creaseAngle, ...) are skipped;
//   * commas are white space, '#' starts a comment, PROTO and EXTERNPROTO
//     declarations are skipped.
//
// Writer: one Shape with an IndexedFaceSet; with exact = true the points go
// into ExactCoordinate { ratPoint [...] } (integers or p/q), otherwise into
// Coordinate { point [...] } as shortest round-trip doubles.
#include "io/readers.hpp"

#include <algorithm>
#include <map>
#include <ostream>
#include <vector>

namespace minksum::io_detail {

namespace {

struct Tok {
  std::string_view text;
  std::size_t line = 0;
  bool string = false;
};

class Lexer {
 public:
  Lexer(std::string_view data, const std::string& name) : d_(data), name_(name) {}

  bool next(Tok& t) {
    skip();
    if (pos_ >= d_.size()) return false;
    t.line = line_;
    t.string = false;
    const char c = d_[pos_];
    if (c == '{' || c == '}' || c == '[' || c == ']') {
      t.text = d_.substr(pos_++, 1);
      return true;
    }
    if (c == '"') {
      std::size_t start = pos_++;
      for (;;) {
        if (pos_ >= d_.size()) throw InputError(name_, line_place(t.line), "unterminated string");
        char s = d_[pos_++];
        if (s == '\n') ++line_;
        if (s == '\\' && pos_ < d_.size()) {
          if (d_[pos_] == '\n') ++line_;
          ++pos_;
        } else if (s == '"') {
          break;
        }
      }
      t.text = d_.substr(start, pos_ - start);
      t.string = true;
      return true;
    }
    std::size_t start = pos_;
    while (pos_ < d_.size()) {
      char s = d_[pos_];
      if (is_space(s) || s == ',' || s == '#' || s == '"' || s == '{' || s == '}' || s == '[' || s == ']') break;
      ++pos_;
    }
    t.text = d_.substr(start, pos_ - start);
    return true;
  }

  bool peek(Tok& t) {
    std::size_t p = pos_, l = line_;
    bool ok = next(t);
    pos_ = p;
    line_ = l;
    return ok;
  }

  std::size_t line() const { return line_; }

 private:
  void skip() {
    while (pos_ < d_.size()) {
      char c = d_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c) || c == ',') {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < d_.size() && d_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view d_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

bool is_identifier(const Tok& t) {
  if (t.string || t.text.empty()) return false;
  char c = t.text[0];
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

bool is_value(const Tok& t) {
  if (t.string) return true;
  if (t.text == "TRUE" || t.text == "FALSE") return true;
  if (t.text.empty()) return false;
  char c = t.text[0];
  return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
}

class Reader {
 public:
  Reader(std::string_view data, const std::string& name) : lex_(data, name), name_(name) {}

  Mesh run() {
    struct Frame {
      bool transform = false;
      bool contains_ifs = false;
      int brackets = 0;
      std::string nonidentity;  // first non-identity field, if any
      std::size_t nonidentity_line = 0;
    };
    std::vector<Frame> stack(1);
    std::string_view prev;  // the identifier before a '{' is the node type
    Tok t;
    while (lex_.next(t)) {
      if (t.string) {
        prev = {};
        continue;
      }
      const std::string_view s = t.text;
      if (s == "{") {
        Frame f;
        f.transform = prev == "Transform";
        stack.push_back(f);
        prev = {};
      } else if (s == "}") {
        if (stack.size() == 1) fail(t.line, "unmatched '}'");
        Frame f = std::move(stack.back());
        stack.pop_back();
        if (f.brackets != 0) fail(t.line, "'}' closes a node inside an unclosed '['");
        if (f.transform && f.contains_ifs && !f.nonidentity.empty())
          fail(f.nonidentity_line, "the IndexedFaceSet is inside a Transform with a non-identity '" + f.nonidentity +
                                       "', which is not supported (apply the transform to the coordinates)");
        if (f.contains_ifs) stack.back().contains_ifs = true;
        prev = {};
      } else if (s == "[") {
        ++stack.back().brackets;
        prev = {};
      } else if (s == "]") {
        if (stack.back().brackets == 0) fail(t.line, "unmatched ']'");
        --stack.back().brackets;
        prev = {};
      } else if (s == "PROTO") {
        need(t, "a PROTO name");
        expect("[");
        skip_balanced();
        expect("{");
        skip_balanced();
        prev = {};
      } else if (s == "EXTERNPROTO") {
        need(t, "an EXTERNPROTO name");
        expect("[");
        skip_balanced();
        need(t, "an EXTERNPROTO url");
        if (t.text == "[") skip_balanced();
        else if (!t.string) fail(t.line, "expected an EXTERNPROTO url, got " + quote(t.text));
        prev = {};
      } else if (s == "DEF" || s == "USE") {
        need(t, "a node name");
        prev = {};
      } else if (s == "IndexedFaceSet" && lex_.peek(t) && t.text == "{") {
        if (found_) fail(t.line, "more than one IndexedFaceSet (one polytope per file)");
        parse_ifs(t.line);
        found_ = true;
        stack.back().contains_ifs = true;
        prev = {};
      } else if (stack.back().transform && stack.back().brackets == 0 &&
                 (s == "translation" || s == "rotation" || s == "scale")) {
        const std::size_t line = t.line;
        const int n = s == "rotation" ? 4 : 3;
        Rational v[4];
        for (int i = 0; i < n; ++i) {
          need(t, "a number");
          v[i] = parse_coordinate(t.text, name_, line_place(t.line));
        }
        bool identity = s == "translation" ? (sgn(v[0]) == 0 && sgn(v[1]) == 0 && sgn(v[2]) == 0)
                        : s == "rotation"  ? sgn(v[3]) == 0
                                           : (v[0] == 1 && v[1] == 1 && v[2] == 1);
        Frame& top = stack.back();
        if (!identity && top.nonidentity.empty()) {
          top.nonidentity = std::string(s);
          top.nonidentity_line = line;
        }
        prev = {};
      } else {
        prev = s;
      }
    }
    if (stack.size() != 1) fail(lex_.line(), "file ends inside a node (missing '}')");
    if (stack.back().brackets != 0) fail(lex_.line(), "file ends inside a list (missing ']')");
    if (!found_) throw InputError(name_, "", "no IndexedFaceSet found");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& problem) {
    throw InputError(name_, line_place(line), problem);
  }

  void need(Tok& t, const char* what) {
    if (!lex_.next(t)) fail(lex_.line(), std::string("file ends where ") + what + " was expected");
  }

  void expect(std::string_view s) {
    Tok t;
    need(t, "a bracket");
    if (t.string || t.text != s)
      fail(t.line, "expected '" + std::string(s) + "', got " + quote(t.text));
  }

  // After an opening '{' or '[': skip to the matching closing one.
  void skip_balanced() {
    int depth = 1;
    Tok t;
    while (depth > 0) {
      need(t, "a closing bracket");
      if (t.string) continue;
      if (t.text == "{" || t.text == "[") ++depth;
      else if (t.text == "}" || t.text == "]") --depth;
    }
  }

  // Skip one field value: an MF list, a node (possibly DEF/USE/NULL) or SF
  // values (numbers, strings, TRUE/FALSE).
  void skip_value() {
    Tok t;
    need(t, "a field value");
    if (!t.string && (t.text == "[")) {
      skip_balanced();
    } else if (!t.string && t.text == "DEF") {
      need(t, "a node name");
      need(t, "a node type");
      expect("{");
      skip_balanced();
    } else if (!t.string && t.text == "USE") {
      need(t, "a node name");
    } else if (!t.string && t.text == "NULL") {
    } else if (is_value(t)) {
      Tok p;
      while (lex_.peek(p) && is_value(p)) lex_.next(p);
    } else if (is_identifier(t)) {
      expect("{");
      skip_balanced();
    } else {
      fail(t.line, "unexpected " + quote(t.text));
    }
  }

  // Numbers of a point / ratPoint field, 3 per point.
  PointList parse_points(const char* field) {
    std::vector<Coordinate> v;
    Tok t;
    need(t, "a point list");
    std::size_t end_line = t.line;
    if (!t.string && t.text == "[") {
      for (;;) {
        need(t, "']'");
        if (!t.string && t.text == "]") {
          end_line = t.line;
          break;
        }
        if (t.string) fail(t.line, "expected a number, got a string");
        v.push_back(read_coordinate(t.text, name_, t.line));
      }
    } else {
      for (int i = 0; i < 3; ++i) {
        if (i > 0) need(t, "a number");
        v.push_back(read_coordinate(t.text, name_, t.line));
      }
    }
    if (v.size() % 3 != 0)
      fail(end_line, std::string(field) + " list has " + std::to_string(v.size()) + " numbers, not a multiple of 3");
    if (v.size() / 3 >= kNoIndex) fail(end_line, "too many vertices");
    PointList pts;
    pts.reserve(v.size() / 3);
    for (std::size_t i = 0; i < v.size(); i += 3) {
      Coordinate c[3] = {std::move(v[i]), std::move(v[i + 1]), std::move(v[i + 2])};
      push_point(pts, c);
    }
    return pts;
  }

  PointList parse_coord() {
    Tok t;
    need(t, "a coordinate node");
    std::string def;
    if (!t.string && t.text == "DEF") {
      need(t, "a node name");
      def = std::string(t.text);
      need(t, "a coordinate node");
    } else if (!t.string && t.text == "USE") {
      need(t, "a node name");
      auto it = defs_.find(std::string(t.text));
      if (it == defs_.end())
        fail(t.line, "coord USE " + quote(t.text) + " names no earlier Coordinate or ExactCoordinate");
      return it->second;
    } else if (!t.string && t.text == "NULL") {
      return {};
    }
    if (t.string || (t.text != "Coordinate" && t.text != "ExactCoordinate"))
      fail(t.line, "unsupported coord node " + quote(t.text) + " (expected Coordinate or ExactCoordinate)");
    const bool exact = t.text == "ExactCoordinate";
    expect("{");
    PointList pts;
    for (;;) {
      need(t, "'}'");
      if (!t.string && t.text == "}") break;
      if (!t.string && (t.text == "point" || t.text == "ratPoint")) pts = parse_points(exact ? "ratPoint" : "point");
      else if (is_identifier(t)) skip_value();
      else fail(t.line, "unexpected " + quote(t.text) + " in " + (exact ? "ExactCoordinate" : "Coordinate"));
    }
    if (!def.empty()) defs_[def] = pts;
    return pts;
  }

  void close_face(std::vector<Index>& face, std::size_t line) {
    if (face.size() < 3)
      fail(line, "face " + std::to_string(mesh_.faces.size()) + " has " + std::to_string(face.size()) +
                     " vertices (at least 3 needed)");
    mesh_.faces.push_back(std::move(face));
    face_line_.push_back(line);
    face.clear();
  }

  void parse_coord_index() {
    Tok t;
    need(t, "a coordIndex list");
    std::vector<Index> face;
    std::size_t first = t.line;
    auto take = [&](const Tok& x) {
      if (x.string) fail(x.line, "expected an index, got a string");
      auto v = parse_signed(x.text);
      if (!v) fail(x.line, "expected an index, got " + quote(x.text));
      if (*v == -1) {
        close_face(face, first);
        return;
      }
      if (*v < -1) fail(x.line, "coordIndex has negative index " + std::to_string(*v));
      if (face.empty()) first = x.line;
      if (*v >= std::int64_t(kNoIndex))
        fail(x.line, "face " + std::to_string(mesh_.faces.size()) + " refers to vertex " + std::to_string(*v) +
                         " but there are fewer vertices");
      face.push_back(static_cast<Index>(*v));
    };
    if (!t.string && t.text == "[") {
      for (;;) {
        need(t, "']'");
        if (!t.string && t.text == "]") break;
        take(t);
      }
    } else {
      take(t);
    }
    if (!face.empty()) close_face(face, first);
  }

  void parse_ifs(std::size_t ifs_line) {
    expect("{");
    bool have_coord = false, have_index = false, ccw = true;
    PointList pts;
    Tok t;
    for (;;) {
      if (!lex_.next(t)) fail(lex_.line(), "file ends inside the IndexedFaceSet");
      if (!t.string && t.text == "}") break;
      if (!is_identifier(t)) fail(t.line, "unexpected " + quote(t.text) + " in the IndexedFaceSet");
      if (t.text == "coord") {
        if (have_coord) fail(t.line, "the IndexedFaceSet has two 'coord' fields");
        have_coord = true;
        pts = parse_coord();
      } else if (t.text == "coordIndex") {
        if (have_index) fail(t.line, "the IndexedFaceSet has two 'coordIndex' fields");
        have_index = true;
        parse_coord_index();
      } else if (t.text == "ccw") {
        need(t, "TRUE or FALSE");
        if (t.text == "TRUE") ccw = true;
        else if (t.text == "FALSE") ccw = false;
        else fail(t.line, "expected TRUE or FALSE after 'ccw', got " + quote(t.text));
      } else {
        skip_value();
      }
    }
    if (!have_coord) fail(ifs_line, "the IndexedFaceSet has no 'coord' field");
    for (std::size_t f = 0; f < mesh_.faces.size(); ++f)
      for (Index v : mesh_.faces[f])
        if (v >= pts.size())
          fail(face_line_[f], "face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                  " but there are " + std::to_string(pts.size()) + " vertices");
    if (!ccw)
      for (auto& f : mesh_.faces) std::reverse(f.begin() + 1, f.end());  // keep the first vertex
    mesh_.points = std::move(pts);
  }

  Lexer lex_;
  const std::string& name_;
  Mesh mesh_;
  std::vector<std::size_t> face_line_;
  std::map<std::string, PointList> defs_;
  bool found_ = false;
};

}  // namespace

Mesh read_wrl(std::string_view data, const std::string& name) {
  constexpr std::string_view magic = "#VRML V2.0 utf8";
  if (data.substr(0, magic.size()) != magic) {
    if (data.substr(0, 10) == "#VRML V1.0")
      throw InputError(name, "line 1", "VRML 1.0 is not supported (expected '#VRML V2.0 utf8')");
    throw InputError(name, "line 1", "expected '#VRML V2.0 utf8' header");
  }
  return Reader(data, name).run();
}

void write_wrl(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  out << "#VRML V2.0 utf8\n";
  if (options.exact)
    out << "# ExactCoordinate.ratPoint holds exact rational coordinates (integers or p/q)\n";
  out << "Shape {\n"
      << "  geometry IndexedFaceSet {\n"
      << "    coord " << (options.exact ? "ExactCoordinate" : "Coordinate") << " {\n"
      << "      " << (options.exact ? "ratPoint" : "point") << " [\n";
  std::string line;
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    line.assign("        ");
    append_point(line, mesh.points, i, options.exact, ' ', i + 1 < mesh.points.size() ? ",\n" : "\n");
    out.write(line.data(), std::streamsize(line.size()));
  }
  out << "      ]\n"
      << "    }\n"
      << "    coordIndex [\n";
  for (const auto& f : mesh.faces) {
    out << "      ";
    for (Index v : f) out << v << ", ";
    out << "-1,\n";
  }
  out << "    ]\n"
      << "  }\n"
      << "}\n";
}

}  // namespace minksum::io_detail
