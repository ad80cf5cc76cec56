// Facet provenance by brute force: for each facet normal n of S, the faces of
// A and B maximising <x, n>, found by scanning every vertex.
#include <minksum/minkowski.hpp>

#include "mesh/support.hpp"
#include "sum/faces.hpp"

namespace minksum {

FacetOrigin FacetProvenance::origin() const {
  using enum FeatureDim;
  if (a.dim == facet && b.dim == facet) return FacetOrigin::facet_facet;
  if (a.dim == facet && b.dim == vertex) return FacetOrigin::translated;
  if (a.dim == vertex && b.dim == facet) return FacetOrigin::corner;
  if (a.dim == edge && b.dim == edge) return FacetOrigin::edge;
  return FacetOrigin::facet_edge;
}

Feature face_of_vertices(const ConvexPolytope& p, const std::vector<Index>& vs, const Point3& n) {
  if (vs.size() == 1) return Feature::vertex(vs[0]);
  if (vs.size() == 2) {
    Index h = p.vertex_halfedge(vs[0]);
    do {
      if (p.target(h) == vs[1]) return Feature::edge(ConvexPolytope::edge(h));
      h = p.next_around_vertex(h);
    } while (h != p.vertex_halfedge(vs[0]));
    return Feature::edge(kNoIndex);  // not adjacent: cannot happen for a supporting face
  }
  // A facet: the one around vs[0] whose outward normal points along n.
  Index h = p.vertex_halfedge(vs[0]);
  do {
    Index f = p.facet(h);
    Point3 m = p.plane(f).normal();
    if (is_zero(cross(m, n)) && sgn(dot(m, n)) > 0) return Feature::facet(f);
    h = p.next_around_vertex(h);
  } while (h != p.vertex_halfedge(vs[0]));
  return Feature::facet(kNoIndex);
}

std::vector<FacetProvenance> facet_provenance(const ConvexPolytope& a, const ConvexPolytope& b,
                                              const ConvexPolytope& s) {
  std::vector<FacetProvenance> out;
  out.reserve(s.num_facets());
  for (Index f = 0; f < s.num_facets(); ++f) {
    Point3 n = s.plane(f).normal();
    out.push_back({face_of_vertices(a, support_vertices(a, n), n), face_of_vertices(b, support_vertices(b, n), n)});
  }
  return out;
}

}  // namespace minksum
