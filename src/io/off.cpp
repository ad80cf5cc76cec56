// OFF (Geomview Object File Format), text only.
//
// Reader:
//   * magic "OFF", optionally with Geomview's prefixes ST, C, N (in that
//     order: "COFF", "NOFF", "CNOFF", "STOFF"...); "4OFF"/"nOFF" (other
//     dimensions) and binary OFF are refused;
//   * the counts "V F E" may follow the magic on the same line; E is ignored
//     and may be omitted;
//   * '#' starts a comment anywhere;
//   * a vertex is 3 coordinates read with parse_number (integers of any
//     length and p/q exactly, decimals as the nearest double); with a
//     C/N/ST prefix, further numbers on the vertex line (colour, normal,
//     texture coordinates) are skipped, with plain "OFF" they are an error;
//   * a face is "k i0 ... i(k-1)" with 0-based indices, optionally followed on
//     the same line by up to 4 colour numbers, which are ignored.
// Counts are checked against the bytes that follow them before anything is
// allocated: a vertex needs at least 6 bytes ("0 0 0\n"); a face is only
// charged 2 (its count and a separator), so that a short or truncated face
// is reported as such rather than as an implausible count.
#include "io/readers.hpp"
#include "kernel/big_array.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <minksum/parallel.hpp>
#include <ostream>

namespace minksum::io_detail {

namespace {

struct Magic {
  bool ok = false;
  bool extras = false;  // vertex lines may carry more numbers
  std::string problem;
};

Magic parse_magic(std::string_view t) {
  Magic m;
  std::string_view s = t;
  bool st = false, c = false, n = false, four = false, ndim = false;
  if (s.substr(0, 2) == "ST") st = true, s.remove_prefix(2);
  if (s.substr(0, 1) == "C") c = true, s.remove_prefix(1);
  if (s.substr(0, 1) == "N") n = true, s.remove_prefix(1);
  if (s.substr(0, 1) == "4") four = true, s.remove_prefix(1);
  if (s.substr(0, 1) == "n") ndim = true, s.remove_prefix(1);
  if (s == "OFF" || s == "OFFBINARY") {
    if (s == "OFFBINARY") {
      m.problem = "binary OFF is not supported";
    } else if (four || ndim) {
      m.problem = "only 3-dimensional OFF is supported, got " + quote(t);
    } else {
      m.ok = true;
      m.extras = st || c || n;
    }
    return m;
  }
  m.problem = "expected 'OFF' magic, got " + quote(t);
  return m;
}

std::string plural(std::uint64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The fast paths below read the common lines in place, without tokens: a
// vertex line of three plain numbers, a face line of a count and indices,
// separated by spaces or tabs and ending the line.  They accept exactly
// what the general path accepts and give the same values; on anything else
// (a comment, a line break inside the element, extra numbers, a rational, a
// long integer, an error) they return nullptr and the general path reads
// the element, with its messages.

inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

// After the last number of an element: blanks, an optional '\r', then the
// line end (the pointer after it) or the end of the data; else nullptr.
inline const char* line_end(const char* p, const char* end) {
  while (p != end && is_blank(*p)) ++p;
  if (p != end && *p == '\r') ++p;
  if (p == end) return p;
  return *p == '\n' ? p + 1 : nullptr;
}

// One coordinate at p, as read_coordinate's fast path takes it: a token
// starting with a digit, '-' or '.', read whole by from_chars as a finite
// double, not an integer of more than 15 digits (those are exact only on
// the general path).  The end of the token, or nullptr.
inline const char* fast_coordinate(const char* p, const char* end, double& d) {
  if (p == end) return nullptr;
  const char c0 = *p;
  if (!((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '.')) return nullptr;
  const auto r = std::from_chars(p, end, d);
  if (r.ec != std::errc() || !std::isfinite(d)) return nullptr;
  const char* q = r.ptr;
  if (q != end && !is_space(*q)) return nullptr;  // the token goes on ('#', a letter, '/'...)
  if (std::size_t(q - p) - (c0 == '-') > 15 && std::find_if(p, q, [](char c) {
                                                   return c == '.' || c == 'e' || c == 'E';
                                                 }) == q)
    return nullptr;
  return q;
}

// "x y z" ending the line at p: the three doubles and the start of the
// next line, or nullptr.
const char* fast_vertex_line(const char* p, const char* end, Coordinate (&c)[3]) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) {
      if (p == end || !is_blank(*p)) return nullptr;
      while (p != end && is_blank(*p)) ++p;
    }
    double d;
    p = fast_coordinate(p, end, d);
    if (!p) return nullptr;
    c[k].d = d;
  }
  return line_end(p, end);
}

// A decimal index (digits only, at most 9: below kNoIndex) at p; the end of
// its digits, or nullptr.
inline const char* fast_index(const char* p, const char* end, std::uint32_t& v) {
  const char* const start = p;
  std::uint32_t x = 0;
  while (p != end && *p >= '0' && *p <= '9' && p - start < 10) x = x * 10 + std::uint32_t(*p++ - '0');
  if (p == start || p - start > 9) return nullptr;
  v = x;
  return p;
}

// "k i0 ... i(k-1)" ending the line at p, with 3 <= k <= 64 and every
// index below nv: the face in `face` and the start of the next line, or
// nullptr.
const char* fast_face_line(const char* p, const char* end, std::uint64_t nv, std::vector<Index>& face) {
  std::uint32_t k = 0;
  p = fast_index(p, end, k);
  if (!p || k < 3 || k > 64) return nullptr;
  face.resize(k);
  for (std::uint32_t j = 0; j < k; ++j) {
    if (p == end || !is_blank(*p)) return nullptr;
    while (p != end && is_blank(*p)) ++p;
    std::uint32_t idx = 0;
    p = fast_index(p, end, idx);
    if (!p || idx >= nv || (p != end && !is_space(*p))) return nullptr;
    face[j] = idx;
  }
  return line_end(p, end);
}

// The faces of files of parallel_items() faces or more, read ahead on a
// second thread while the vertices are read, for the common layout: one
// vertex per line, then the faces, one per line, all on the fast path.
// Their section is assumed to start after nv line ends from the first
// vertex; read_off uses them only when its own reading of the vertices ends
// exactly there, and reads the faces itself otherwise (any other layout, a
// comment, an error: the messages are its own).
struct FacesAhead {
  bool ok = false;
  const char* start = nullptr;  // the first face's first character
  const char* end = nullptr;    // after the last face's line
  std::size_t lines = 0;        // line ends from start to end
  std::vector<std::vector<Index>> faces;
};

FacesAhead read_faces_ahead(const char* p, const char* end, std::uint64_t nv, std::uint64_t nf) {
  FacesAhead a;
  for (std::uint64_t i = 0; i < nv; ++i) {
    const void* nl = std::memchr(p, '\n', std::size_t(end - p));
    if (!nl) return a;
    p = static_cast<const char*>(nl) + 1;
  }
  while (p != end && is_space(*p)) ++p;
  a.start = p;
  a.faces.reserve(nf);
  for (std::uint64_t f = 0; f < nf; ++f) {
    for (; p != end && is_space(*p); ++p) a.lines += *p == '\n';
    if (p == end) return a;
    std::vector<Index> face;
    const char* next = fast_face_line(p, end, nv, face);
    if (!next) return a;
    a.lines += next[-1] == '\n';
    a.faces.push_back(std::move(face));
    p = next;
  }
  a.end = p;
  a.ok = true;
  return a;
}

}  // namespace

Mesh read_off(std::string_view data, const std::string& name) {
  TextCursor cur(data, '#');
  std::string_view tok;
  if (!cur.next(tok))
    throw InputError(name, line_place(cur.line()), "expected 'OFF' magic, found only blanks and comments");
  Magic magic = parse_magic(tok);
  if (!magic.ok) throw InputError(name, line_place(cur.token_line()), magic.problem);
  // "OFF BINARY" is refused; any other token on the magic line is the vertex count.
  bool pending = false;
  if (cur.next_on_line(tok)) {
    if (tok == "BINARY") throw InputError(name, line_place(cur.token_line()), "binary OFF is not supported");
    pending = true;
  }

  auto read_count = [&](const char* what) -> std::uint64_t {
    if (pending)
      pending = false;  // tok already holds it
    else if (!cur.next(tok))
      throw InputError(name, line_place(cur.line()), std::string("file ends before the ") + what + " count");
    auto v = parse_unsigned(tok);
    if (!v) {
      if (!tok.empty() && tok[0] == '-' && parse_signed(tok))
        throw InputError(name, line_place(cur.token_line()), std::string("negative ") + what + " count " + quote(tok));
      throw InputError(name, line_place(cur.token_line()),
                       std::string("expected the ") + what + " count, got " + quote(tok));
    }
    return *v;
  };
  const std::uint64_t nv = read_count("vertex");
  const std::uint64_t nf = read_count("face");
  const std::size_t count_line = cur.token_line();
  if (cur.next_on_line(tok)) {  // the edge count, ignored (some writers put -1)
    if (!parse_signed(tok))
      throw InputError(name, line_place(cur.token_line()), "expected the edge count, got " + quote(tok));
  }
  if (cur.next_on_line(tok))
    throw InputError(name, line_place(cur.token_line()), "unexpected token " + quote(tok) + " after the counts");

  // Plausibility of the counts against the bytes that follow, before any allocation.
  cur.at_end();  // skip to the first vertex token
  const std::uint64_t rest = data.size() - cur.pos();
  using U128 = unsigned __int128;
  if (U128(nv) * 6 > U128(rest) + 1)
    throw InputError(name, line_place(count_line),
                     "header announces " + plural(nv, "vertex", "vertices") + " but only " +
                         plural(rest, "byte follows", "bytes follow") + " the header");
  if (U128(nv) * 6 + U128(nf) * 2 > U128(rest) + 1)
    throw InputError(name, line_place(count_line),
                     "header announces " + plural(nv, "vertex", "vertices") + " and " +
                         plural(nf, "face", "faces") + " but only " +
                         plural(rest, "byte follows", "bytes follow") + " the header");
  if (nv >= kNoIndex)
    throw InputError(name, line_place(count_line), "too many vertices (" + std::to_string(nv) + ")");

  Mesh mesh;
  mesh.points.reserve(nv);
  auto read_vertices = [&] {
    for (std::uint64_t i = 0; i < nv; ++i) {
      Coordinate c[3];
      if (!cur.at_end()) {
        if (const char* next = fast_vertex_line(cur.here(), cur.end(), c)) {
          cur.advance_to(next, next[-1] == '\n');
          push_point(mesh.points, c);
          continue;
        }
      }
      for (int k = 0; k < 3; ++k) {
        if (!cur.next(tok))
          throw InputError(name, line_place(cur.line()),
                           "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
        c[k] = read_coordinate(tok, name, cur.token_line());
      }
      while (cur.next_on_line(tok)) {
        if (!magic.extras || !looks_numeric(tok))
          throw InputError(name, line_place(cur.token_line()),
                           "unexpected token " + quote(tok) + " after vertex " + std::to_string(i));
      }
      push_point(mesh.points, c);
    }
  };
  FacesAhead ahead;
  if (nf >= parallel_items() && nv > 0) {
    const char* first_vertex = cur.here();
    parallel_for(2, 2, [&](std::size_t job) {
      if (job == 0) read_vertices();
      else ahead = read_faces_ahead(first_vertex, cur.end(), nv, nf);
    });
  } else {
    read_vertices();
  }

  cur.at_end();  // (skips to the first face token)
  if (ahead.ok && cur.here() == ahead.start) {
    mesh.faces = std::move(ahead.faces);
    cur.advance_to(ahead.end, ahead.lines);
  }
  ahead = {};
  mesh.faces.reserve(nf);
  for (std::uint64_t f = mesh.faces.size(); f < nf; ++f) {
    if (!cur.at_end()) {
      std::vector<Index> face;
      if (const char* next = fast_face_line(cur.here(), cur.end(), nv, face)) {
        cur.advance_to(next, next[-1] == '\n');
        mesh.faces.push_back(std::move(face));
        continue;
      }
    }
    if (!cur.next(tok))
      throw InputError(name, line_place(cur.line()),
                       "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::size_t face_line = cur.token_line();
    auto k = parse_unsigned(tok);
    if (!k)
      throw InputError(name, line_place(face_line),
                       "expected the vertex count of face " + std::to_string(f) + ", got " + quote(tok));
    if (*k < 3)
      throw InputError(name, line_place(face_line),
                       "face " + std::to_string(f) + " has " + std::to_string(*k) +
                           " vertices (at least 3 needed)");
    const std::uint64_t left = data.size() - cur.pos();
    if (U128(*k) * 2 > U128(left) + 1)
      throw InputError(name, line_place(face_line),
                       "face " + std::to_string(f) + " announces " + std::to_string(*k) +
                           " vertices but only " + plural(left, "byte follows", "bytes follow"));
    std::vector<Index> face;
    face.reserve(*k);
    for (std::uint64_t j = 0; j < *k; ++j) {
      if (!cur.next(tok))
        throw InputError(name, line_place(cur.line()),
                         "file ends inside face " + std::to_string(f) + " (after " + std::to_string(j) +
                             " of " + std::to_string(*k) + " indices)");
      auto idx = parse_unsigned(tok);
      if (!idx) {
        if (auto s = parse_signed(tok); s && *s < 0)
          throw InputError(name, line_place(cur.token_line()),
                           "face " + std::to_string(f) + " has negative vertex index " + std::to_string(*s));
        throw InputError(name, line_place(cur.token_line()),
                         "expected a vertex index in face " + std::to_string(f) + ", got " + quote(tok));
      }
      if (*idx >= nv)
        throw InputError(name, line_place(cur.token_line()),
                         "face " + std::to_string(f) + " refers to vertex " + std::to_string(*idx) +
                             " but there are " + std::to_string(nv) + " vertices");
      face.push_back(static_cast<Index>(*idx));
    }
    int colours = 0;
    while (cur.next_on_line(tok)) {
      if (++colours > 4 || !looks_numeric(tok))
        throw InputError(name, line_place(cur.token_line()),
                         "unexpected token " + quote(tok) + " after face " + std::to_string(f));
    }
    mesh.faces.push_back(std::move(face));
  }
  if (cur.next(tok))
    throw InputError(name, line_place(cur.token_line()),
                     "unexpected token " + quote(tok) + " after the last face");
  return mesh;
}

void write_off(std::ostream& out, const Mesh& mesh, const WriteOptions& options) {
  // Number of distinct undirected edges, for the header's E: an
  // open-addressing set of (min, max) pairs.
  std::size_t total = 0;
  for (const auto& f : mesh.faces) total += f.size();
  std::size_t cap = 16;
  while (cap < 2 * total + 2) cap *= 2;
  std::vector<std::uint64_t> set(cap, ~std::uint64_t(0));
  std::size_t ne = 0;
  for (const auto& f : mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      std::uint64_t a = f[i], b = f[(i + 1) % f.size()];
      if (a > b) std::swap(a, b);
      const std::uint64_t key = a << 32 | b;
      std::uint64_t h = key * 0x9e3779b97f4a7c15ULL;
      for (std::size_t j = (h ^ (h >> 29)) & (cap - 1);; j = (j + 1) & (cap - 1)) {
        if (set[j] == key) break;
        if (set[j] == ~std::uint64_t(0)) {
          set[j] = key;
          ++ne;
          break;
        }
      }
    }
  release(set);

  out << "OFF\n";
  if (options.exact) out << "# coordinates are exact rationals (integers or p/q)\n";
  out << mesh.points.size() << ' ' << mesh.faces.size() << ' ' << ne << '\n';
  write_point_lines(out, mesh.points, options.exact);
  write_counted_face_lines(out, mesh.faces);
}

void write_off(std::ostream& out, const ConvexPolytope& p, const WriteOptions& options) {
  out << "OFF\n";
  if (options.exact) out << "# coordinates are exact rationals (integers or p/q)\n";
  out << p.num_vertices() << ' ' << p.num_facets() << ' ' << p.num_edges() << '\n';
  write_point_lines(out, p.coordinates(), options.exact);
  write_lines(
      out, p.num_facets(), [&](std::size_t f) { return 21 * (std::size_t(p.facet_degree(Index(f))) + 1); },
      [&](char* c, std::size_t f) {
        c = put_index(c, p.facet_degree(Index(f)));
        const Index h0 = p.facet_halfedge(Index(f));
        Index h = h0;
        do {
          *c++ = ' ';
          c = put_index(c, p.origin(h));
          h = p.next(h);
        } while (h != h0);
        *c++ = '\n';
        return c;
      });
}

}  // namespace minksum::io_detail
