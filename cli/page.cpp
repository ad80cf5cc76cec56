// The viewer pages (page.hpp).
#include "page.hpp"

#include <minksum/io.hpp>
#include <minksum/nonconvex.hpp>

#include <algorithm>
#include <ostream>
#include <string_view>

#include "common.hpp"
#include "text.hpp"

// The viewer's script bundled with three.js (web/src/viewer.js, bundled by
// esbuild at build time) and three.js's licence, linked into the command by
// the generated viewer_assets.cpp (CMakeLists.txt).
extern "C" const char minksum_viewer_js[], minksum_viewer_js_end[];
extern "C" const char minksum_three_licence[], minksum_three_licence_end[];

namespace minksum::cli {

namespace {

std::string_view asset(const char* begin, const char* end) { return {begin, std::size_t(end - begin)}; }

void append_exact(std::string& out, const Rational& q) { out += format_exact(q); }

const char* feature_dim_code(FeatureDim d) { return d == FeatureDim::vertex ? "0" : d == FeatureDim::edge ? "1" : "2"; }

}  // namespace

void check_html_path(const std::string& path, const std::string& option) {
  if (path.size() < 6 || path.compare(path.size() - 5, 5, ".html") != 0)
    throw UsageError(option + ": the page is an .html file, got '" + path + "'");
}

std::string json_string(const std::string& s) { return "\"" + json_escape(s) + "\""; }

std::string script_safe_json(std::string_view json) {
  // In JSON text these characters stand only inside strings (no token holds
  // them), where \uXXXX means the same character.
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<') out += "\\u003c";
    else if (c == '>') out += "\\u003e";
    else if (c == '&') out += "\\u0026";
    else if (c == '\xe2' && i + 2 < json.size() && json[i + 1] == '\x80' && (json[i + 2] == '\xa8' || json[i + 2] == '\xa9'))
      out += json[i + 2] == '\xa8' ? "\\u2028" : "\\u2029", i += 2;
    else out += c;
  }
  return out;
}

std::string html_text(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length(s, i, &cp);
    if (n == 0 || (cp < 0x20 && cp != '\t' && cp != '\n') || (cp >= 0x7f && cp <= 0x9f)) out += "\xef\xbf\xbd";  // U+FFFD
    else if (cp == '<') out += "&lt;";
    else if (cp == '>') out += "&gt;";
    else if (cp == '&') out += "&amp;";
    else if (cp == '"') out += "&quot;";
    else if (cp == '\'') out += "&#39;";
    else out.append(s, i, n);
    i += std::max<std::size_t>(n, 1);
  }
  return out;
}

std::string origin_names_json() {
  std::string out = "[";
  constexpr FacetOrigin kinds[] = {FacetOrigin::translated, FacetOrigin::corner, FacetOrigin::edge,
                                   FacetOrigin::facet_edge, FacetOrigin::facet_facet};
  for (std::size_t i = 0; i < std::size(kinds); ++i) out += (i ? ", \"" : "\"") + std::string(facet_origin_name(kinds[i])) + "\"";
  return out + "]";
}

void append_solid_json(std::string& out, const ConvexPolytope& p, const std::string& name, const std::string& role,
                       const std::vector<FacetProvenance>* provenance) {
  out += "{\"name\": " + json_string(name) + ", \"role\": " + json_string(role) + ", \"counts\": {" + counts_json(p) +
         "}, \"volume\": \"" + format_exact(p.volume()) + "\", \"xyz\": [";
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Vec3d& a = p.approx(v);
    out += (v ? "," : "") + json_number(a.x) + "," + json_number(a.y) + "," + json_number(a.z);
  }
  out += "], \"exact\": [";
  for (Index v = 0; v < p.num_vertices(); ++v) {
    const Point3& q = p.point(v);
    out += v ? ",\"" : "\"";
    append_exact(out, q.x), out += ' ', append_exact(out, q.y), out += ' ', append_exact(out, q.z);
    out += '"';
  }
  out += "], \"facets\": [";
  for (Index f = 0; f < p.num_facets(); ++f) {
    out += f ? ",[" : "[";
    const Index h0 = p.facet_halfedge(f);
    Index h = h0;
    bool first = true;
    do {
      out += (first ? "" : ",") + std::to_string(p.origin(h));
      first = false;
      h = p.next(h);
    } while (h != h0);
    out += ']';
  }
  out += "], \"planes\": [";
  for (Index f = 0; f < p.num_facets(); ++f) {
    const Plane& pl = p.plane(f);
    out += (f ? ",\"" : "\"") + pl.a.get_str() + " " + pl.b.get_str() + " " + pl.c.get_str() + " " + pl.d.get_str() + "\"";
  }
  out += "]";
  if (provenance && provenance->size() == p.num_facets()) {
    out += ", \"origin\": [";
    for (Index f = 0; f < p.num_facets(); ++f) out += (f ? "," : "") + std::to_string(int((*provenance)[f].origin()));
    out += "], \"from\": [";
    for (Index f = 0; f < p.num_facets(); ++f) {
      const FacetProvenance& fp = (*provenance)[f];
      out += f ? "," : "";
      out += feature_dim_code(fp.a.dim), out += ",", out += std::to_string(fp.a.index), out += ",";
      out += feature_dim_code(fp.b.dim), out += ",", out += std::to_string(fp.b.index);
    }
    out += "]";
  }
  out += "}";
}

namespace {
// The oriented plane of a planar polygon in canonical integers (kernel.hpp's
// Plane): its normal by Newell's sum of cross products (exact, nonzero for a
// simple polygon, pointing to the side it turns counter-clockwise around),
// scaled to integers and divided by their gcd.
Plane polygon_plane(const Mesh& m, const std::vector<Index>& loop) {
  Point3 n(Rational(0), Rational(0), Rational(0));
  const Point3 p0 = m.points.exact(loop[0]);
  Point3 prev = p0;
  for (std::size_t i = 1; i <= loop.size(); ++i) {
    const Point3 p = i < loop.size() ? m.points.exact(loop[i]) : p0;
    n = n + cross(prev - p0, p - p0);
    prev = p;
  }
  Rational c[4] = {n.x, n.y, n.z, dot(n, p0)};
  Integer den = 1;
  for (const Rational& q : c) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), q.get_den_mpz_t());
  Integer k[4], g = 0;
  for (int i = 0; i < 4; ++i) {
    k[i] = c[i].get_num() * (den / c[i].get_den());
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), k[i].get_mpz_t());
  }
  if (g != 0)
    for (Integer& x : k) x /= g;
  return Plane{k[0], k[1], k[2], k[3]};
}
}  // namespace

void append_mesh_solid_json(std::string& out, const Mesh& faces, const Rational& volume, const std::string& name,
                            const std::string& role) {
  std::size_t corners = 0;
  for (const auto& f : faces.faces) corners += f.size();
  out += "{\"name\": " + json_string(name) + ", \"role\": " + json_string(role) + ", \"counts\": {\"vertices\": " +
         std::to_string(faces.points.size()) + ", \"edges\": " + std::to_string(corners / 2) +
         ", \"facets\": " + std::to_string(faces.faces.size()) + "}, \"volume\": \"" + format_exact(volume) +
         "\", \"xyz\": [";
  for (std::size_t v = 0; v < faces.points.size(); ++v) {
    const Vec3d& a = faces.points.approx(v);
    out += (v ? "," : "") + json_number(a.x) + "," + json_number(a.y) + "," + json_number(a.z);
  }
  out += "], \"exact\": [";
  for (std::size_t v = 0; v < faces.points.size(); ++v) {
    const Point3 q = faces.points.exact(v);
    out += v ? ",\"" : "\"";
    append_exact(out, q.x), out += ' ', append_exact(out, q.y), out += ' ', append_exact(out, q.z);
    out += '"';
  }
  out += "], \"facets\": [";
  for (std::size_t f = 0; f < faces.faces.size(); ++f) {
    out += f ? ",[" : "[";
    for (std::size_t i = 0; i < faces.faces[f].size(); ++i) out += (i ? "," : "") + std::to_string(faces.faces[f][i]);
    out += ']';
  }
  out += "], \"planes\": [";
  for (std::size_t f = 0; f < faces.faces.size(); ++f) {
    const Plane pl = polygon_plane(faces, faces.faces[f]);
    out += (f ? ",\"" : "\"") + pl.a.get_str() + " " + pl.b.get_str() + " " + pl.c.get_str() + " " + pl.d.get_str() + "\"";
  }
  // Each face cut into triangles alone (a triangle as it is), its corners
  // mapped back to the mesh's vertices.
  std::string tri_facet;
  out += "], \"triangles\": [";
  bool first = true;
  for (std::size_t f = 0; f < faces.faces.size(); ++f) {
    const std::vector<Index>& loop = faces.faces[f];
    std::vector<std::vector<Index>> tris;
    if (loop.size() == 3) {
      tris.push_back(loop);
    } else {
      Mesh one;
      std::vector<Index> local;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        one.points.push_back(faces.points.exact(loop[i]));
        local.push_back(Index(i));
      }
      one.faces.push_back(std::move(local));
      for (const auto& t : triangulate(one, name).faces) tris.push_back({loop[t[0]], loop[t[1]], loop[t[2]]});
    }
    for (const auto& t : tris) {
      out += (first ? "" : ",") + std::to_string(t[0]) + "," + std::to_string(t[1]) + "," + std::to_string(t[2]);
      tri_facet += (first ? "" : ",") + std::to_string(f);
      first = false;
    }
  }
  out += "], \"triangle_facet\": [" + tri_facet + "]}";
}

std::string page_html(const std::string& title, const std::string& data, bool connect_self) {
  const std::string_view script = asset(minksum_viewer_js, minksum_viewer_js_end);
  const std::string_view licence = asset(minksum_three_licence, minksum_three_licence_end);
  // The Content-Security-Policy forbids every request (the page works offline
  // or not at all), but, for a page its own server serves, requests to that server.
  std::string o;
  o.reserve(script.size() + licence.size() + data.size() + 1024);
  o += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n";
  o += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
       "style-src 'unsafe-inline'; img-src data: blob:";
  if (connect_self) o += "; connect-src 'self'";
  o += "\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += "<meta name=\"generator\" content=\"minksum\">\n<title>" + html_text(title) + "</title></head>\n<body>\n";
  o += "<noscript>This page draws with JavaScript and WebGL.</noscript>\n";
  o += "<script type=\"application/json\" id=\"minksum-data\">" + script_safe_json(data) + "</script>\n";
  o += "<script>\n/* The viewer of minksum, bundled with three.js (https://threejs.org), whose licence follows.\n\n";
  o += licence;
  o += "*/\n";
  o += script;
  o += "\n</script>\n</body></html>\n";
  return o;
}

void write_page(const std::string& path, const std::string& title, const std::string& data) {
  const std::string html = page_html(title, data);
  try {
    write_file_atomically(path, [&](std::ostream& o) { o << html; });
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
}

void write_cgm_page(const std::string& path, const std::string& title, const CubicalGaussianMap& g,
                    const ConvexPolytope& shown, const std::vector<std::string>& operands,
                    const std::vector<FacetProvenance>& provenance) {
  const bool sum = operands.size() == 2;
  const bool with_origin = sum && provenance.size() == shown.num_facets();
  std::string data = "{\"kind\": \"cgm\", \"title\": " + json_string(title) + ", \"origins\": " + origin_names_json();
  if (sum) data += ", \"operands\": [" + json_string(operands[0]) + ", " + json_string(operands[1]) + "]";
  data += ", \"maps\": ";
  append_cgm_maps_json(data, g, with_origin ? &provenance : nullptr);
  data += ", \"solids\": [";
  append_solid_json(data, shown, title, sum ? "sum" : "polytope", with_origin ? &provenance : nullptr);
  data += "]}";
  write_page(path, title, data);
}

void append_cgm_maps_json(std::string& data, const CubicalGaussianMap& g,
                          const std::vector<FacetProvenance>* provenance) {
  const bool with_origin = provenance != nullptr;
  data += "[";
  for (int k = 0; k < 6; ++k) {
    const CubicalGaussianMap::PlanarMap& m = g.map(k);
    const auto c = g.counts(k);
    data += (k ? ", {" : "{") + std::string("\"id\": ") + std::to_string(k) + ", \"counts\": {\"vertices\": " +
            std::to_string(c.vertices) + ", \"halfedges\": " + std::to_string(c.halfedges) + ", \"faces\": " +
            std::to_string(c.faces) + ", \"real_vertices\": " + std::to_string(m.num_real_vertices()) +
            ", \"real_edges\": " + std::to_string(m.num_real_edges()) + "}, \"xyz\": [";
    for (Index v = 0; v < m.vertices.size(); ++v) {
      const Point3 p = g.lift(k, v);
      data += (v ? "," : "") + json_number(to_double(p.x)) + "," + json_number(to_double(p.y)) + "," +
              json_number(to_double(p.z));
    }
    data += "], \"exact\": [";
    for (Index v = 0; v < m.vertices.size(); ++v)
      data += (v ? ",\"" : "\"") + format_exact(m.vertices[v].x) + " " + format_exact(m.vertices[v].y) + "\"";
    data += "], \"facet\": [";
    for (Index v = 0; v < m.vertices.size(); ++v)
      data += (v ? "," : "") + (m.vertices[v].real ? std::to_string(m.vertices[v].facet) : std::string("-1"));
    if (with_origin) {
      data += "], \"origin\": [";
      for (Index v = 0; v < m.vertices.size(); ++v)
        data += (v ? "," : "") + (m.vertices[v].real ? std::to_string(int((*provenance)[m.vertices[v].facet].origin()))
                                                     : std::string("-1"));
    }
    data += "], \"edges\": [";
    bool first = true;
    for (Index h = 0; h < m.halfedges.size(); ++h) {
      const auto& e = m.halfedges[h];
      if (e.twin < h) continue;  // each edge once
      const int kind = !e.real ? 0 : e.operands == 0 ? 1 : e.operands == 1 ? 2 : e.operands == 2 ? 3 : 4;
      data += (first ? "" : ",") + std::to_string(e.origin) + "," + std::to_string(m.halfedges[e.twin].origin) + "," +
              std::to_string(kind);
      first = false;
    }
    data += "]}";
  }
  data += "]";
}

void write_motion_page(const std::string& path, const std::string& title, const ConvexPolytope& obstacle,
                       const ConvexPolytope& robot, const std::vector<Quaternion>& turns,
                       const std::vector<MotionFrame>& frames, int fps,
                       const std::vector<ConvexPolytope>& c_obstacles) {
  std::string data = "{\"kind\": \"motion\", \"title\": " + json_string(title) + ", \"fps\": " + std::to_string(fps) +
                     ", \"obstacle\": ";
  append_solid_json(data, obstacle, "obstacle Q", "obstacle");
  data += ", \"robot\": ";
  append_solid_json(data, robot, "robot P", "robot");
  data += ", \"shapes\": [";
  for (std::size_t k = 0; k < turns.size(); ++k) {
    data += k ? ",[" : "[";
    for (Index v = 0; v < robot.num_vertices(); ++v) {
      const Point3 p = rotate(turns[k], robot.point(v));
      data += (v ? "," : "") + json_number(to_double(p.x)) + "," + json_number(to_double(p.y)) + "," +
              json_number(to_double(p.z));
    }
    data += "]";
  }
  data += "], \"frames\": [";
  std::string events;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const MotionFrame& f = frames[i];
    const Point3& t = f.translation;
    data += (i ? ",{" : "{") + std::string("\"t\": [") + json_number(to_double(t.x)) + "," +
            json_number(to_double(t.y)) + "," + json_number(to_double(t.z)) + "], \"exact\": [\"" +
            format_exact(t.x) + "\", \"" + format_exact(t.y) + "\", \"" + format_exact(t.z) + "\"], \"o\": " +
            std::to_string(f.orientation) + ", \"status\": " + std::to_string(f.status) + ", \"value\": \"" +
            format_exact(f.value) + "\", \"pass\": " + std::to_string(f.pass) + "}";
    if (i > 0 && f.status != frames[i - 1].status) events += (events.empty() ? "" : ",") + std::to_string(i);
  }
  data += "], \"events\": [" + events + "]";
  if (!c_obstacles.empty()) {
    data += ", \"cobstacles\": [";
    for (std::size_t k = 0; k < c_obstacles.size(); ++k) {
      if (k) data += ", ";
      append_solid_json(data, c_obstacles[k], "Q ⊕ (−P), orientation " + std::to_string(k), "cobstacle");
    }
    data += "]";
  }
  data += "}";
  write_page(path, title, data);
}

}  // namespace minksum::cli
