// Internal to src/nonconvex/: whether two triangles of a closed 2-manifold
// triangle mesh meet other than in their shared edge or vertex, decided as
// CGAL's Polygon_mesh_processing::self_intersections decides it (its
// do_faces_intersect), on points of a CGAL kernel.  Used by the
// self-intersection test of validation (nef.cpp) and by the repair of a
// rounded surface (round.cpp).
#pragma once

#include <minksum/polytope.hpp>

#include <CGAL/intersections.h>

#include <array>
#include <vector>

namespace minksum::nonconvex_detail {

// h and g: two distinct triangles (indices into p, three distinct points
// each).  In a closed 2-manifold mesh every edge belongs to exactly two
// triangles, so two triangles with two points in common are the two across
// that edge, as CGAL finds them through the halfedges: they meet when the
// four points are coplanar and the third points lie on the same side of the
// edge.  With one point in common, when the edge of either opposite the
// shared point meets the other triangle; with none, when the triangles
// meet.  Three points in common: the same triangle twice (facing opposite
// ways), which CGAL reports.
template <class GT>
bool triangles_meet(const std::array<Index, 3>& h, const std::array<Index, 3>& g,
                    const std::vector<typename GT::Point_3>& p) {
  int shared = 0, hi = -1, gi = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (h[i] == g[j]) {
        if (shared == 0) hi = i, gi = j;
        ++shared;
      }
  if (shared == 3) return true;
  if (shared == 2) {
    Index e0 = 0, e1 = 0, r = 0, s = 0;
    for (int i = 0; i < 3; ++i) {
      const bool in_g = h[i] == g[0] || h[i] == g[1] || h[i] == g[2];
      if (!in_g) r = h[i];
      const bool in_h = g[i] == h[0] || g[i] == h[1] || g[i] == h[2];
      if (!in_h) s = g[i];
    }
    for (int i = 0; i < 3; ++i)
      if (h[i] != r && h[(i + 1) % 3] != r) e0 = h[i], e1 = h[(i + 1) % 3];
    const GT gt;
    return gt.coplanar_3_object()(p[e0], p[e1], p[r], p[s]) &&
           gt.coplanar_orientation_3_object()(p[e0], p[e1], p[r], p[s]) == CGAL::POSITIVE;
  }
  using Triangle = typename GT::Triangle_3;
  using Segment = typename GT::Segment_3;
  const Triangle th(p[h[0]], p[h[1]], p[h[2]]), tg(p[g[0]], p[g[1]], p[g[2]]);
  if (shared == 1)
    return CGAL::do_intersect(th, Segment(p[g[(gi + 1) % 3]], p[g[(gi + 2) % 3]])) ||
           CGAL::do_intersect(tg, Segment(p[h[(hi + 1) % 3]], p[h[(hi + 2) % 3]]));
  return CGAL::do_intersect(th, tg);
}

}  // namespace minksum::nonconvex_detail
