// The unfolded Cubical Gaussian Map as SVG (Fogel and Halperin 2006, Figs. 2(c), 6(c), 7(c)).
//
// The cube is unfolded around the face z = +1 (map 5) in the middle: x = -1
// (map 0) on its left, x = +1 (map 3) on its right, y = +1 (map 4) above,
// y = -1 (map 1) below and z = -1 (map 2) below that, so that neighbouring
// squares of the cross share their cube edge.  Coordinates are converted to
// doubles for drawing only.
#include <minksum/cubical_gaussian_map.hpp>

#include <cstdio>
#include <sstream>

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

}  // namespace

std::string CubicalGaussianMap::to_svg() const {
  const double S = 100, M = 20;
  auto sx = [&](double u) { return (u + 3) * S + M; };
  auto sy = [&](double v) { return (3 - v) * S + M; };
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(6 * S + 2 * M) << "\" height=\""
    << num(8 * S + 2 * M) << "\" viewBox=\"0 0 " << num(6 * S + 2 * M) << " " << num(8 * S + 2 * M) << "\">\n"
    << "<title>Cubical Gaussian Map</title>\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  static const char* colour[4] = {"#000000", "#d62728", "#1f77b4", "#9467bd"};
  for (int k = 0; k < 6; ++k) {
    const PlanarMap& m = maps_[k];
    double cu, cv;
    unfold(k, 0, 0, cu, cv);
    o << "<g id=\"map" << k << "\">\n"
      << "<text x=\"" << num(sx(cu)) << "\" y=\"" << num(sy(cv)) << "\" font-size=\"14\" fill=\"#bbbbbb\" "
      << "text-anchor=\"middle\">" << k << "</text>\n";
    for (Index h = 0; h < m.halfedges.size(); h += 2) {
      const Halfedge& e = m.halfedges[h];
      const Vertex& a = m.vertices[e.origin];
      const Vertex& b = m.vertices[m.halfedges[e.twin].origin];
      double u0, v0, u1, v1;
      unfold(k, to_double(a.x), to_double(a.y), u0, v0);
      unfold(k, to_double(b.x), to_double(b.y), u1, v1);
      o << "<line x1=\"" << num(sx(u0)) << "\" y1=\"" << num(sy(v0)) << "\" x2=\"" << num(sx(u1)) << "\" y2=\""
        << num(sy(v1)) << "\" ";
      if (e.real)
        o << "stroke=\"" << colour[e.operands & 3] << "\" stroke-width=\"1.5\"/>\n";
      else
        o << "stroke=\"#999999\" stroke-width=\"1\" stroke-dasharray=\"4 3\"/>\n";
    }
    for (const Vertex& v : m.vertices) {
      if (!v.real) continue;
      double u, w;
      unfold(k, to_double(v.x), to_double(v.y), u, w);
      o << "<circle cx=\"" << num(sx(u)) << "\" cy=\"" << num(sy(w)) << "\" r=\"2.5\" fill=\"#000000\"/>\n";
    }
    o << "</g>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace minksum
