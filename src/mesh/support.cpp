// The support of a direction and the face of a vertex set (mesh/support.hpp).
#include "mesh/support.hpp"

#include <minksum/predicates.hpp>

namespace minksum {

namespace {

// higher(x, y) for an exact direction: sign <n, p(x) − p(y)>, as
// dot_sign(p(y), p(x), 0, n) on the polytope's cached roundings and n's
// (no rational converted per comparison).
struct Along {
  const ConvexPolytope& p;
  const Point3& n;
  Vec3d n_approx = to_double(n);
  Point3 zero{Rational(0), Rational(0), Rational(0)};
  Vec3d zero_approx{0, 0, 0};
  Along(const ConvexPolytope& polytope, const Point3& direction) : p(polytope), n(direction) {}
  int operator()(Index x, Index y) const {
    return dot_sign(RoundedPoint3{p.point(y), p.approx(y)}, RoundedPoint3{p.point(x), p.approx(x)},
                    RoundedPoint3{zero, zero_approx}, RoundedPoint3{n, n_approx});
  }
};

}  // namespace

Support support(const ConvexPolytope& p, const Point3& n, Index start) {
  const Along higher(p, n);
  const Index b = climb(p, start, higher);
  const std::optional<Feature> face = support_face_at(p, b, higher);
  if (!face) throw std::logic_error("support: hill climbing stopped below the top");
  return {b, *face};
}

std::vector<Index> support_vertices(const ConvexPolytope& p, const Point3& n) {
  return support_scan(p, Along(p, n));
}

Feature feature_of_vertices(const ConvexPolytope& p, const std::vector<Index>& vs) {
  if (vs.size() == 1) return Feature::vertex(vs[0]);
  if (vs.empty()) throw std::logic_error("feature_of_vertices: no vertex");
  if (vs.size() == 2) {
    const Index h = halfedge_between(p, vs[0], vs[1]);
    if (h == kNoIndex) throw std::logic_error("feature_of_vertices: two vertices not joined by an edge");
    return Feature::edge(ConvexPolytope::edge(h));
  }
  const Index h0 = p.vertex_halfedge(vs[0]);
  Index h = h0;
  // Two facets share at most an edge: the facet around vs[0] holding vs[1]
  // and vs[2] is the only one holding all three.
  do {
    const Index f = p.facet(h);
    bool has1 = false, has2 = false;
    const Index g0 = p.facet_halfedge(f);
    Index g = g0;
    do {
      has1 = has1 || p.origin(g) == vs[1];
      has2 = has2 || p.origin(g) == vs[2];
      g = p.next(g);
    } while (g != g0);
    if (has1 && has2) {
      if (p.facet_degree(f) != vs.size()) break;
      return Feature::facet(f);
    }
    h = p.next_around_vertex(h);
  } while (h != h0);
  throw std::logic_error("feature_of_vertices: the vertices are not those of a facet");
}

std::vector<Index> feature_vertices(const ConvexPolytope& p, const Feature& f) {
  std::vector<Index> out;
  feature_vertices(p, f, out);
  return out;
}

bool share_a_vertex(const std::vector<Index>& x, const std::vector<Index>& y) {
  std::size_t i = 0, j = 0;
  while (i < x.size() && j < y.size()) {
    if (x[i] == y[j]) return true;
    if (x[i] < y[j]) ++i;
    else ++j;
  }
  return false;
}

}  // namespace minksum
