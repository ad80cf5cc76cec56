// VRML 2.0 (.wrl): one IndexedFaceSet per file, or a scene of Fogel and
// Halperin's ExactPolyhedron and CubicalGaussianMap nodes (docs/vrml.md).
//
// Reader (read_scene; read_wrl takes the scene's one polytope):
//   * the file must begin with "#VRML V2.0 utf8";
//   * the scene graph is scanned for IndexedFaceSet, ExactPolyhedron and
//     CubicalGaussianMap nodes, wherever they are (Shape, Transform, Group,
//     children ...).  ExactPolyhedron has the fields of IndexedFaceSet that
//     matter here (coord, coordIndex, ccw).  read_wrl reads one polytope per
//     file: a second polytope node is an error there ("more than one
//     IndexedFaceSet or ExactPolyhedron").  A geometry reused through USE is
//     not a second node and is not read again;
//   * CubicalGaussianMap { polytope NODE  operands [ NODE NODE ]
//     mapCounts [ 18 integers ]  mapPoint [ k x y, ... ] }, NODE an
//     ExactPolyhedron or IndexedFaceSet (DEF'd or not) or USE of an earlier
//     one; unknown fields are errors;
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
// Coordinate { point [...] } as shortest round-trip doubles.  write_scene:
// the polytopes as DEF'd ExactPolyhedron nodes, then the CubicalGaussianMap
// nodes that USE them.
#include "io/readers.hpp"

#include <minksum/scene.hpp>

#include <algorithm>
#include <map>
#include <ostream>
#include <stdexcept>
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

  Scene run() {
    struct Frame {
      bool transform = false;
      bool contains_ifs = false;  // holds a geometry node that is read
      std::string node;           // the type of the first such node
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
          fail(f.nonidentity_line, "the " + f.node + " is inside a Transform with a non-identity '" + f.nonidentity +
                                       "', which is not supported (apply the transform to the coordinates)");
        if (f.contains_ifs) {
          stack.back().contains_ifs = true;
          if (stack.back().node.empty()) stack.back().node = f.node;
        }
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
        if (s == "DEF") {
          // DEF name ExactPolyhedron { ... }: the geometry node keeps its name.
          const std::string def(t.text);
          Tok n, b;
          if (lex_.peek(n) && is_geometry(n)) {
            lex_.next(n);
            if (lex_.peek(b) && !b.string && b.text == "{") {
              geometry_node(n, def, stack.back());
              continue;
            }
            prev = n.text;
          }
        }
      } else if (is_geometry(t) && lex_.peek(t) && t.text == "{") {
        Tok n;
        n.text = s;
        n.line = t.line;
        geometry_node(n, "", stack.back());
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
    return std::move(scene_);
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

  template <class Frame>
  void geometry_node(const Tok& type, const std::string& def, Frame& frame) {
    frame.contains_ifs = true;
    if (frame.node.empty()) frame.node = std::string(type.text);
    if (type.text == "CubicalGaussianMap") {
      scene_.shapes.push_back({SceneShape::Kind::cgm, parse_cgm(type.line, def)});
    } else {
      scene_.shapes.push_back({SceneShape::Kind::polytope, parse_polytope(type, def)});
    }
  }

  static bool is_geometry(const Tok& t) {
    return !t.string && (t.text == "IndexedFaceSet" || t.text == "ExactPolyhedron" || t.text == "CubicalGaussianMap");
  }

  // An IndexedFaceSet or ExactPolyhedron node whose type token is `type`
  // (the '{' follows): its index in scene_.polytopes.
  std::size_t parse_polytope(const Tok& type, const std::string& def) {
    ScenePolytope p;
    p.name = def;
    p.line = type.line;
    p.exact_node = type.text == "ExactPolyhedron";
    node_ = p.exact_node ? "ExactPolyhedron" : "IndexedFaceSet";
    mesh_ = Mesh{};
    face_line_.clear();
    parse_ifs(type.line);
    p.mesh = std::move(mesh_);
    scene_.polytopes.push_back(std::move(p));
    if (!def.empty()) polytope_defs_[def] = scene_.polytopes.size() - 1;
    return scene_.polytopes.size() - 1;
  }

  // The value of an SFNode field of a CubicalGaussianMap that names a
  // polytope: [DEF name] ExactPolyhedron|IndexedFaceSet { ... }, or USE name.
  std::size_t polytope_value(const char* field) {
    Tok t;
    need(t, "a polytope node");
    std::string def;
    if (!t.string && t.text == "USE") {
      need(t, "a node name");
      auto it = polytope_defs_.find(std::string(t.text));
      if (it == polytope_defs_.end())
        fail(t.line, std::string("'") + field + "' USE " + quote(t.text) +
                         " names no earlier ExactPolyhedron or IndexedFaceSet");
      return it->second;
    }
    if (!t.string && t.text == "DEF") {
      need(t, "a node name");
      def = std::string(t.text);
      need(t, "a polytope node");
    }
    if (t.string || (t.text != "ExactPolyhedron" && t.text != "IndexedFaceSet"))
      fail(t.line, std::string("'") + field + "' needs an ExactPolyhedron (or IndexedFaceSet) node or USE, got " +
                       quote(t.text));
    Tok b;
    if (!lex_.peek(b) || b.string || b.text != "{") fail(t.line, "expected '{' after " + quote(t.text));
    return parse_polytope(t, def);
  }

  // A non-negative integer of a CubicalGaussianMap list.
  std::uint64_t count_value(const Tok& t, const char* field) {
    auto v = t.string ? std::nullopt : parse_unsigned(t.text);
    if (!v || *v >= kNoIndex)
      fail(t.line, std::string("'") + field + "' needs non-negative integers, got " + quote(t.text));
    return *v;
  }

  // The tokens of an MF field: [ a b c ... ] or a single value; strings refused.
  std::vector<Tok> list_value(const char* field) {
    std::vector<Tok> v;
    Tok t;
    need(t, "a list");
    if (t.string || t.text != "[") fail(t.line, std::string("'") + field + "' needs a list '[ ... ]'");
    for (;;) {
      need(t, "']'");
      if (!t.string && t.text == "]") break;
      if (t.string || t.text == "[" || t.text == "{" || t.text == "}")
        fail(t.line, std::string("unexpected ") + quote(t.text) + " in '" + field + "'");
      v.push_back(t);
    }
    return v;
  }

  std::size_t parse_cgm(std::size_t line, const std::string& def) {
    expect("{");
    SceneCgm g;
    g.name = def;
    g.line = line;
    bool have_polytope = false, have_operands = false;
    Tok t;
    for (;;) {
      if (!lex_.next(t)) fail(lex_.line(), "file ends inside the CubicalGaussianMap");
      if (!t.string && t.text == "}") break;
      if (!is_identifier(t)) fail(t.line, "unexpected " + quote(t.text) + " in the CubicalGaussianMap");
      auto once = [&](bool seen) {
        if (seen) fail(t.line, "the CubicalGaussianMap has two " + quote(t.text) + " fields");
      };
      if (t.text == "polytope") {
        once(have_polytope);
        have_polytope = true;
        g.polytope = polytope_value("polytope");
      } else if (t.text == "operands") {
        once(have_operands);
        have_operands = true;
        const std::size_t at = t.line;
        expect("[");
        Tok n;
        for (;;) {
          if (!lex_.peek(n)) fail(lex_.line(), "file ends where ']' was expected");
          if (!n.string && n.text == "]") {
            lex_.next(n);
            break;
          }
          g.operands.push_back(polytope_value("operands"));
        }
        if (g.operands.size() != 2)
          fail(at, "'operands' lists " + std::to_string(g.operands.size()) +
                       " polytopes; two are needed (the map is that of their Minkowski sum)");
      } else if (t.text == "mapCounts") {
        once(g.map_counts.has_value());
        g.map_counts_line = t.line;
        std::vector<Tok> v = list_value("mapCounts");
        if (v.size() != 18)
          fail(t.line, "'mapCounts' has " + std::to_string(v.size()) +
                           " integers; 18 are needed (vertices, halfedges, faces of maps 0 to 5)");
        std::array<Index, 18> c{};
        for (std::size_t i = 0; i < 18; ++i) c[i] = Index(count_value(v[i], "mapCounts"));
        g.map_counts = c;
      } else if (t.text == "mapPoint") {
        once(g.map_points.has_value());
        g.map_points_line = t.line;
        std::vector<Tok> v = list_value("mapPoint");
        if (v.size() % 3 != 0)
          fail(t.line, "'mapPoint' has " + std::to_string(v.size()) + " numbers, not a multiple of 3 (map x y)");
        std::vector<SceneMapPoint> pts;
        pts.reserve(v.size() / 3);
        for (std::size_t i = 0; i < v.size(); i += 3) {
          const std::uint64_t k = count_value(v[i], "mapPoint");
          if (k > 5) fail(v[i].line, "'mapPoint' names map " + std::to_string(k) + " (maps are 0 to 5)");
          SceneMapPoint p;
          p.map = int(k);
          p.x = parse_coordinate(v[i + 1].text, name_, line_place(v[i + 1].line));
          p.y = parse_coordinate(v[i + 2].text, name_, line_place(v[i + 2].line));
          if (abs(p.x) > 1 || abs(p.y) > 1)
            fail(v[i + 1].line, "'mapPoint' " + format_exact(p.x) + " " + format_exact(p.y) +
                                    " lies outside the square [-1,1]^2 of a planar map");
          pts.push_back(std::move(p));
        }
        g.map_points = std::move(pts);
      } else {
        fail(t.line, "unknown field " + quote(t.text) +
                         " in the CubicalGaussianMap (polytope, operands, mapCounts, mapPoint)");
      }
    }
    if (!have_polytope && !have_operands) fail(line, "the CubicalGaussianMap has neither 'polytope' nor 'operands'");
    scene_.cgms.push_back(std::move(g));
    return scene_.cgms.size() - 1;
  }

  void parse_ifs(std::size_t ifs_line) {
    expect("{");
    bool have_coord = false, have_index = false, ccw = true;
    PointList pts;
    Tok t;
    for (;;) {
      if (!lex_.next(t)) fail(lex_.line(), "file ends inside the " + node_);
      if (!t.string && t.text == "}") break;
      if (!is_identifier(t)) fail(t.line, "unexpected " + quote(t.text) + " in the " + node_);
      if (t.text == "coord") {
        if (have_coord) fail(t.line, "the " + node_ + " has two 'coord' fields");
        have_coord = true;
        pts = parse_coord();
      } else if (t.text == "coordIndex") {
        if (have_index) fail(t.line, "the " + node_ + " has two 'coordIndex' fields");
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
    if (!have_coord) fail(ifs_line, "the " + node_ + " has no 'coord' field");
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
  Mesh mesh_;  // of the polytope node being read
  std::vector<std::size_t> face_line_;
  std::string node_ = "IndexedFaceSet";  // its type
  std::map<std::string, PointList> defs_;
  std::map<std::string, std::size_t> polytope_defs_;
  Scene scene_;
};

}  // namespace

Scene read_wrl_scene(std::string_view data, const std::string& name) {
  constexpr std::string_view magic = "#VRML V2.0 utf8";
  if (data.substr(0, magic.size()) != magic) {
    if (data.substr(0, 10) == "#VRML V1.0")
      throw InputError(name, "line 1", "VRML 1.0 is not supported (expected '#VRML V2.0 utf8')");
    throw InputError(name, "line 1", "expected '#VRML V2.0 utf8' header");
  }
  return Reader(data, name).run();
}

Mesh read_wrl(std::string_view data, const std::string& name) {
  Scene s = read_wrl_scene(data, name);
  if (s.polytopes.empty()) {
    if (!s.cgms.empty()) throw InputError(name, "", "no IndexedFaceSet or ExactPolyhedron found");
    throw InputError(name, "", "no IndexedFaceSet found");
  }
  if (s.polytopes.size() > 1)
    throw InputError(name, line_place(s.polytopes[1].line),
                     "more than one IndexedFaceSet or ExactPolyhedron: the scene holds " +
                         std::to_string(s.polytopes.size()) +
                         " polytopes, this command reads one polytope per file ('minksum view' shows a scene)");
  return std::move(s.polytopes[0].mesh);
}

namespace {

// The coord and coordIndex fields of an IndexedFaceSet or ExactPolyhedron,
// each line indented by `indent`.
void write_faces(std::ostream& out, const Mesh& mesh, bool exact, const std::string& indent) {
  out << indent << "coord " << (exact ? "ExactCoordinate" : "Coordinate") << " {\n"
      << indent << "  " << (exact ? "ratPoint" : "point") << " [\n";
  std::string line;
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    line.assign(indent).append("    ");
    append_point(line, mesh.points, i, exact, ' ', i + 1 < mesh.points.size() ? ",\n" : "\n");
    out.write(line.data(), std::streamsize(line.size()));
  }
  out << indent << "  ]\n"
      << indent << "}\n"
      << indent << "coordIndex [\n";
  for (const auto& f : mesh.faces) {
    out << indent << "  ";
    for (Index v : f) out << v << ", ";
    out << "-1,\n";
  }
  out << indent << "]\n";
}

}  // namespace

void write_wrl(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  out << "#VRML V2.0 utf8\n";
  if (options.exact)
    out << "# ExactCoordinate.ratPoint holds exact rational coordinates (integers or p/q)\n";
  out << "Shape {\n"
      << "  geometry IndexedFaceSet {\n";
  write_faces(out, mesh, options.exact, "    ");
  out << "  }\n"
      << "}\n";
}

}  // namespace minksum::io_detail

namespace minksum {

void write_scene(std::ostream& out, const Scene& scene, bool exact, const std::vector<std::string>& comments) {
  using namespace io_detail;
  auto name_of = [&](std::size_t i) -> const std::string& {
    if (i >= scene.polytopes.size() || scene.polytopes[i].name.empty())
      throw std::logic_error("write_scene: every polytope needs a name");
    return scene.polytopes[i].name;
  };
  out << "#VRML V2.0 utf8\n"
      << "# A scene of Fogel and Halperin's extended VRML: ExactPolyhedron and CubicalGaussianMap nodes\n"
      << "# (minksum's docs/vrml.md defines their fields).\n";
  for (std::size_t i = 0; i < scene.polytopes.size(); ++i) {
    const ScenePolytope& p = scene.polytopes[i];
    if (i < comments.size() && !comments[i].empty()) out << "# " << comments[i] << "\n";
    out << "Shape {\n  geometry DEF " << name_of(i) << " ExactPolyhedron {\n";
    for (const auto& f : p.mesh.faces)
      for (Index v : f)
        if (v >= p.mesh.points.size()) throw std::logic_error("write_scene: a face index is out of range");
    write_faces(out, p.mesh, exact, "    ");
    out << "  }\n}\n";
  }
  for (const SceneCgm& g : scene.cgms) {
    out << "Shape {\n  geometry " << (g.name.empty() ? "" : "DEF " + g.name + " ") << "CubicalGaussianMap {\n";
    if (g.polytope != kNoNode) out << "    polytope USE " << name_of(g.polytope) << "\n";
    if (!g.operands.empty()) {
      out << "    operands [";
      for (std::size_t k = 0; k < g.operands.size(); ++k) out << (k ? ", USE " : " USE ") << name_of(g.operands[k]);
      out << " ]\n";
    }
    if (g.map_counts) {
      out << "    mapCounts [";
      for (std::size_t k = 0; k < 18; ++k) out << (k % 3 ? " " : k ? ",  " : " ") << (*g.map_counts)[k];
      out << " ]\n";
    }
    if (g.map_points) {
      out << "    mapPoint [\n";
      std::string line;
      for (std::size_t k = 0; k < g.map_points->size(); ++k) {
        const SceneMapPoint& m = (*g.map_points)[k];
        line.assign("      ");
        append_index(line, std::uint64_t(m.map));
        line.append(" ").append(format_exact(m.x)).append(" ").append(format_exact(m.y));
        line.append(k + 1 < g.map_points->size() ? ",\n" : "\n");
        out.write(line.data(), std::streamsize(line.size()));
      }
      out << "    ]\n";
    }
    out << "  }\n}\n";
  }
}

}  // namespace minksum
