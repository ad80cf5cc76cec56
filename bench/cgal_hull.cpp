// minksum bench — CGAL convex_hull_3 on the pairwise sums: exact (Epeck) and
// floating point (Epick on rounded sums).  Also the shared exact counter.
#include "competitors.hpp"
#include "timer.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/version.h>

#include <unordered_map>

namespace minksum::bench {

void count_exact(const Mesh& m, Outcome& o) {
  try {
    ConvexPolytope p = ConvexPolytope::from_mesh(m, "competitor output");
    o.v = p.num_vertices();
    o.e = p.num_edges();
    o.f = p.num_facets();
  } catch (const std::exception& e) {
    o.note = std::string("output is not a valid convex polytope: ") + e.what();
  }
}

std::string cgal_version() { return CGAL_VERSION_STR; }

namespace {
template <class SM, class ToPoint>
Mesh surface_mesh_to_mesh(const SM& sm, ToPoint to_point) {
  Mesh m;
  std::unordered_map<std::size_t, Index> id;
  for (auto v : sm.vertices()) {
    id[std::size_t(v)] = Index(m.points.size());
    m.points.push_back(to_point(sm.point(v)));
  }
  for (auto f : sm.faces()) {
    std::vector<Index> poly;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) poly.push_back(id[std::size_t(v)]);
    m.faces.push_back(std::move(poly));
  }
  return m;
}
}  // namespace

Outcome cgal_exact_hull(const ConvexPolytope& a, const ConvexPolytope& b) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::vector<K::Point_3> pa, pb;
  for (const auto& p : a.points()) pa.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
  for (const auto& p : b.points()) pb.emplace_back(K::FT(p.x), K::FT(p.y), K::FT(p.z));
  Outcome o;
  CGAL::Surface_mesh<K::Point_3> sm;
  {
    Stopwatch sw;
    std::vector<K::Point_3> sums;
    sums.reserve(pa.size() * pb.size());
    for (const auto& p : pa)
      for (const auto& q : pb) sums.push_back(p + (q - CGAL::ORIGIN));
    CGAL::convex_hull_3(sums.begin(), sums.end(), sm);
    o.seconds = sw.seconds();
  }
  Mesh m = surface_mesh_to_mesh(sm, [](const K::Point_3& p) {
    const auto& e = CGAL::exact(p);
    return Point3(Rational(e.x()), Rational(e.y()), Rational(e.z()));
  });
  count_exact(m, o);
  return o;
}

Outcome cgal_epick_hull(const ConvexPolytope& a, const ConvexPolytope& b) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Vec3d> da(a.num_vertices()), db(b.num_vertices());
  for (Index i = 0; i < a.num_vertices(); ++i) da[i] = a.approx(i);
  for (Index i = 0; i < b.num_vertices(); ++i) db[i] = b.approx(i);
  // The rounded sums, prepared before the clock starts, as for Qhull.
  std::vector<K::Point_3> sums;
  sums.reserve(da.size() * db.size());
  for (const auto& p : da)
    for (const auto& q : db) sums.emplace_back(p.x + q.x, p.y + q.y, p.z + q.z);
  Outcome o;
  CGAL::Surface_mesh<K::Point_3> sm;
  {
    Stopwatch sw;
    CGAL::convex_hull_3(sums.begin(), sums.end(), sm);
    o.seconds = sw.seconds();
  }
  Mesh m = surface_mesh_to_mesh(sm, [](const K::Point_3& p) { return Point3(p.x(), p.y(), p.z()); });
  count_exact(m, o);
  return o;
}

}  // namespace minksum::bench
