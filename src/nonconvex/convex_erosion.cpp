// The erosion of a convex polytope by a convex polytope as an intersection
// of half-spaces (docs/nonconvex.md, "Erosion, opening, closing": convex A),
// the construction the tests compare erode's half-space path
// (halfspace_erosion.cpp) and its sweep with.
//
// A = ∩ {n_i · x <= d_i} gives A ⊖ B = ∩ {n_i · x <= d_i - h_B(n_i)}, h_B
// B's support.  The intersection is CGAL's halfspace_intersection_3 (the
// convex hull of the dual points) on exact points (the Epeck kernel: exact
// constructions), from a point strictly inside every half-space, checked
// with exact signs: the difference of A's and B's vertex centroids, else
// the point of CGAL's linear program on the planes' doubles, which is not
// exact: when it finds none, or one that the exact check refuses (an
// erosion that is empty or thinner than the doubles can tell), the caller
// takes the sweep, which decides exactly.
#include <minksum/nonconvex.hpp>

#include "nonconvex/morphology.hpp"

#include <CGAL/Convex_hull_3/dual/halfspace_intersection_3.h>
#include <CGAL/Convex_hull_3/dual/halfspace_intersection_interior_point_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>

#include <vector>

namespace minksum::nonconvex_detail {

namespace {
using K = CGAL::Exact_predicates_exact_constructions_kernel;
}  // namespace

std::optional<ConvexPolytope> convex_erosion(const ConvexPolytope& a, const ConvexPolytope& b) {
  std::vector<Point3> normal;
  std::vector<Rational> offset;  // n_i . x <= offset_i
  std::vector<K::Plane_3> planes;
  for (Index f = 0; f < a.num_facets(); ++f) {
    const Plane& h = a.plane(f);
    const Point3 n = h.normal();
    Rational support = dot(n, b.points().front());
    for (const Point3& p : b.points()) {
      Rational s = dot(n, p);
      if (s > support) support = std::move(s);
    }
    Rational d = Rational(h.d) - support;
    // CGAL's half-space is the negative side of a x + b y + c z + D = 0.
    planes.emplace_back(K::FT(n.x), K::FT(n.y), K::FT(n.z), K::FT(Rational(-d)));
    normal.push_back(n);
    offset.push_back(std::move(d));
  }
  auto strictly_inside = [&](const Point3& q) {
    for (std::size_t i = 0; i < normal.size(); ++i)
      if (!(dot(normal[i], q) < offset[i])) return false;
    return true;
  };
  // First the difference of the vertex centroids of A and B (inside the
  // erosion for most B small against A), else the linear program's point.
  Point3 q(Rational(0), Rational(0), Rational(0));
  for (const Point3& p : a.points()) q = q + Rational(1, long(a.num_vertices())) * p;
  for (const Point3& p : b.points()) q = q - Rational(1, long(b.num_vertices())) * p;
  if (!strictly_inside(q)) {
    const boost::optional<K::Point_3> lp = CGAL::halfspace_intersection_interior_point_3(planes.begin(), planes.end());
    if (!lp) return std::nullopt;
    q = Point3(Rational(CGAL::exact(lp->x())), Rational(CGAL::exact(lp->y())), Rational(CGAL::exact(lp->z())));
    if (!strictly_inside(q)) return std::nullopt;  // the sweep decides
  }
  const K::Point_3 inside(K::FT(q.x), K::FT(q.y), K::FT(q.z));
  CGAL::Polyhedron_3<K> p;
  CGAL::halfspace_intersection_3(planes.begin(), planes.end(), p, inside);
  std::vector<Point3> corners;
  for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) {
    const K::Point_3& c = v->point();
    corners.emplace_back(Rational(CGAL::exact(c.x())), Rational(CGAL::exact(c.y())), Rational(CGAL::exact(c.z())));
  }
  return ConvexPolytope::hull(corners, "erosion");
}

}  // namespace minksum::nonconvex_detail
