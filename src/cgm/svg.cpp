// The unfolded Cubical Gaussian Map as SVG (Fogel and Halperin 2006, Figs. 2(c), 6(c), 7(c)).
//
// The cube is unfolded around the face z = +1 (map 5) in the middle: x = -1
// (map 0) on its left, x = +1 (map 3) on its right, y = +1 (map 4) above,
// y = -1 (map 1) below and z = -1 (map 2) below that, so that neighbouring
// squares of the cross share their cube edge.  Coordinates are converted to
// doubles for drawing only.
#include <minksum/cubical_gaussian_map.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <vector>

namespace minksum {

namespace {

// Layout coordinates (u, v) of the map point (X, Y) in the unfolded cross.
void unfold(int k, double X, double Y, double& u, double& v) {
  switch (k) {
    case 0: u = -2 + X, v = Y; break;
    case 1: u = X, v = -2 + Y; break;
    case 2: u = Y, v = -4 - X; break;
    case 3: u = 2 - Y, v = X; break;
    case 4: u = Y, v = 2 - X; break;
    default: u = X, v = Y; break;
  }
}

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

// Text for XML 1.0 content and attributes: markup characters as references;
// control characters (which XML 1.0 does not allow, tab and newline aside)
// and bytes that are not UTF-8 (an operand's file name may hold any) as
// U+FFFD, so the file stays well-formed whatever the names hold.
std::string xml_escape(const std::string& s) {
  static const char* const kReplacement = "\xEF\xBF\xBD";
  std::string out;
  const auto* b = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = b[i];
    if (c < 0x80) {
      if (c == '<') out += "&lt;";
      else if (c == '>') out += "&gt;";
      else if (c == '&') out += "&amp;";
      else if (c == '"') out += "&quot;";
      else if (c < 0x20 && c != '\t' && c != '\n') out += kReplacement;
      else out += char(c);
      ++i;
      continue;
    }
    // A well-formed UTF-8 sequence (no overlong forms, no surrogates, at
    // most U+10FFFF) is copied; anything else is one U+FFFD per byte.
    std::size_t len = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
    if (c > 0xF4) len = 0;
    bool ok = len > 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k) ok = (b[i + k] & 0xC0) == 0x80;
    if (ok && len == 3) ok = !(c == 0xE0 && b[i + 1] < 0xA0) && !(c == 0xED && b[i + 1] >= 0xA0);
    if (ok && len == 4) ok = !(c == 0xF0 && b[i + 1] < 0x90) && !(c == 0xF4 && b[i + 1] >= 0x90);
    // C1 controls (U+0080..U+009F) are discouraged in XML 1.0: replaced too.
    if (ok && len == 2 && c == 0xC2 && b[i + 1] < 0xA0) ok = false;
    if (!ok) {
      out += kReplacement;
      i += (len == 2 && c == 0xC2 && i + 1 < n && (b[i + 1] & 0xC0) == 0x80) ? 2 : 1;
      continue;
    }
    out.append(s, i, len);
    i += len;
  }
  return out;
}

struct Dot {
  double x, y;
};
struct Pair {
  double distance = HUGE_VAL;  // infinity for fewer than two dots
  Dot mid{0, 0};
};
// The two closest dots: sweep in x, comparing each dot with the next ones
// while their x gap is below the best distance so far.
Pair closest_pair(std::vector<Dot> d) {
  std::sort(d.begin(), d.end(), [](const Dot& a, const Dot& b) { return a.x < b.x; });
  Pair best;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = i + 1; j < d.size() && d[j].x - d[i].x < best.distance; ++j)
      if (double e = std::hypot(d[j].x - d[i].x, d[j].y - d[i].y); e < best.distance)
        best = {e, {(d[i].x + d[j].x) / 2, (d[i].y + d[j].y) / 2}};
  return best;
}

}  // namespace

std::string CubicalGaussianMap::to_svg(const std::string& title, const std::string& subtitle) const {
  const double S = 100, M = 20, T = 40;  // square side, margin, title band
  auto sx = [&](double u) { return (u + 3) * S + M; };
  auto sy = [&](double v) { return (3 - v) * S + M + T; };
  const std::string name = xml_escape(title);
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(6 * S + 2 * M) << "\" height=\""
    << num(8 * S + 2 * M + T) << "\" viewBox=\"0 0 " << num(6 * S + 2 * M) << " " << num(8 * S + 2 * M + T)
    << "\" font-family=\"sans-serif\">\n"
    << "<title>" << name << "</title>\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << num(M) << "\" y=\"" << num(M + 12) << "\" font-size=\"15\" font-weight=\"bold\">" << name
    << "</text>\n<text x=\"" << num(M) << "\" y=\"" << num(M + 30) << "\" font-size=\"12\">" << xml_escape(subtitle)
    << "</text>\n";
  static const char* colour[4] = {"#000000", "#d62728", "#1f77b4", "#9467bd"};
  static const char* plane[6] = {"x = −1", "y = −1", "z = −1", "x = +1", "y = +1", "z = +1"};
  bool operands = false;
  for (const PlanarMap& m : maps_)
    for (const Halfedge& e : m.halfedges) operands = operands || e.operands != 0;
  // Where the dots crowd most: the map and its closest pair, zoomed in an inset.
  int crowded = -1;
  Pair crowd;
  // The segments of map k in the drawing, for the map and the inset.
  auto segments = [&](int k, const std::function<void(double, double, double, double, const Halfedge&)>& out) {
    const PlanarMap& m = maps_[k];
    for (Index h = 0; h < m.halfedges.size(); h += 2) {
      const Halfedge& e = m.halfedges[h];
      const Vertex& a = m.vertices[e.origin];
      const Vertex& b = m.vertices[m.halfedges[e.twin].origin];
      double u0, v0, u1, v1;
      unfold(k, to_double(a.x), to_double(a.y), u0, v0);
      unfold(k, to_double(b.x), to_double(b.y), u1, v1);
      out(sx(u0), sy(v0), sx(u1), sy(v1), e);
    }
  };
  auto line_style = [&](const Halfedge& e, double width) {
    return e.real ? std::string("stroke=\"") + colour[e.operands & 3] + "\" stroke-width=\"" + num(1.5 * width) + "\"/>\n"
                  : "stroke=\"#999999\" stroke-width=\"" + num(width) + "\" stroke-dasharray=\"4 3\"/>\n";
  };
  std::vector<std::vector<Dot>> map_dots(6);
  for (int k = 0; k < 6; ++k) {
    const PlanarMap& m = maps_[k];
    // The square's top-left corner in the drawing, where its name goes.
    double u0 = HUGE_VAL, v1 = -HUGE_VAL;
    for (double X : {-1.0, 1.0})
      for (double Y : {-1.0, 1.0}) {
        double u, v;
        unfold(k, X, Y, u, v);
        u0 = std::min(u0, u), v1 = std::max(v1, v);
      }
    o << "<g id=\"map" << k << "\">\n"
      << "<text x=\"" << num(sx(u0) + 4) << "\" y=\"" << num(sy(v1) + 13) << "\" font-size=\"11\" fill=\"#666666\">"
      << k << ": " << plane[k] << "</text>\n";
    segments(k, [&](double x0, double y0, double x1, double y1, const Halfedge& e) {
      o << "<line x1=\"" << num(x0) << "\" y1=\"" << num(y0) << "\" x2=\"" << num(x1) << "\" y2=\"" << num(y1) << "\" "
        << line_style(e, 1);
    });
    std::vector<Dot>& dots = map_dots[k];
    for (const Vertex& v : m.vertices) {
      if (!v.real) continue;
      double u, w;
      unfold(k, to_double(v.x), to_double(v.y), u, w);
      dots.push_back({sx(u), sy(w)});
    }
    const Pair pair = closest_pair(dots);
    if (pair.distance < crowd.distance) crowd = pair, crowded = k;
    const std::string r = num(std::clamp(pair.distance / 3, 0.4, 2.5));
    for (const Dot& d : dots)
      o << "<circle cx=\"" << num(d.x) << "\" cy=\"" << num(d.y) << "\" r=\"" << r << "\" fill=\"#000000\"/>\n";
    o << "</g>\n";
  }
  // Dots closer than 7.5 units (three radii): a zoom inset, in the empty
  // corner right of the lower arm, magnifying the crowded map around its
  // closest pair until the closest dots are 12 units apart; an orange circle
  // on the map shows where.
  if (crowded >= 0 && crowd.distance < 7.5) {
    const double side = 180, ix = sx(1) + 10, iy = sy(-1) + 10;
    const double zoom = std::max(2.0, 12 / std::max(crowd.distance, 1e-12));
    auto tx = [&](double x) { return ix + side / 2 + (x - crowd.mid.x) * zoom; };
    auto ty = [&](double y) { return iy + side / 2 + (y - crowd.mid.y) * zoom; };
    o << "<g id=\"inset\">\n<clipPath id=\"inset-clip\"><rect x=\"" << num(ix) << "\" y=\"" << num(iy) << "\" width=\""
      << num(side) << "\" height=\"" << num(side) << "\"/></clipPath>\n"
      << "<circle cx=\"" << num(crowd.mid.x) << "\" cy=\"" << num(crowd.mid.y) << "\" r=\""
      << num(std::max(4.0, side / 2 / zoom)) << "\" fill=\"none\" stroke=\"#ff8c00\" stroke-width=\"1\"/>\n"
      << "<g clip-path=\"url(#inset-clip)\">\n";
    segments(crowded, [&](double x0, double y0, double x1, double y1, const Halfedge& e) {
      o << "<line x1=\"" << num(tx(x0)) << "\" y1=\"" << num(ty(y0)) << "\" x2=\"" << num(tx(x1)) << "\" y2=\""
        << num(ty(y1)) << "\" " << line_style(e, 1);
    });
    for (const Dot& d : map_dots[crowded])
      if (std::fabs(tx(d.x) - ix - side / 2) < side && std::fabs(ty(d.y) - iy - side / 2) < side)
        o << "<circle cx=\"" << num(tx(d.x)) << "\" cy=\"" << num(ty(d.y)) << "\" r=\"3\" fill=\"#000000\"/>\n";
    char caption[96];
    std::snprintf(caption, sizeof caption, "map %d magnified %.3g times", crowded, zoom);
    o << "</g>\n<rect x=\"" << num(ix) << "\" y=\"" << num(iy) << "\" width=\"" << num(side) << "\" height=\""
      << num(side) << "\" fill=\"none\" stroke=\"#ff8c00\" stroke-width=\"1.5\"/>\n<text x=\"" << num(ix) << "\" y=\""
      << num(iy + side + 14) << "\" font-size=\"11\">" << caption << "</text>\n<text x=\"" << num(ix) << "\" y=\""
      << num(iy + side + 28) << "\" font-size=\"11\">around the orange circle</text>\n</g>\n";
  }
  // The legend, in the empty corner left of the lower arm of the cross.
  o << "<g id=\"legend\" font-size=\"12\">\n";
  double y = sy(-1) + 24;
  auto row = [&](const std::string& swatch, const std::string& text) {
    o << swatch << "<text x=\"" << num(M + 30) << "\" y=\"" << num(y + 4) << "\">" << text << "</text>\n";
    y += 20;
  };
  auto line = [&](const char* stroke, const char* extra) {
    return "<line x1=\"" + num(M) + "\" y1=\"" + num(y) + "\" x2=\"" + num(M + 22) + "\" y2=\"" + num(y) +
           "\" stroke=\"" + stroke + "\" " + extra + "/>\n";
  };
  if (operands) {
    row(line(colour[1], "stroke-width=\"2\""), "arc of P (first operand)");
    row(line(colour[2], "stroke-width=\"2\""), "arc of Q (second operand)");
    row(line(colour[3], "stroke-width=\"2\""), "arc of both");
  } else {
    row(line(colour[0], "stroke-width=\"1.5\""), "arc (an edge)");
  }
  row(line("#999999", "stroke-width=\"1\" stroke-dasharray=\"4 3\""), "artificial edge");
  row("<circle cx=\"" + num(M + 11) + "\" cy=\"" + num(y) + "\" r=\"2.5\" fill=\"#000000\"/>\n", "facet normal");
  o << "</g>\n</svg>\n";
  return o.str();
}

}  // namespace minksum
