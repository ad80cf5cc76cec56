// minksum bench — CGAL::minkowski_sum_3 on Nef polyhedra (Hachenberger's
// method, "NGM" in Barki et al.'s Table 1).  Slow to compile and to run: its own
// translation unit, and the harness runs it under a time cap.
#include "competitors.hpp"
#include "timer.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/minkowski_sum_3.h>

#include <map>

namespace minksum::bench {

namespace {
using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Polyhedron = CGAL::Polyhedron_3<K>;
using Nef = CGAL::Nef_polyhedron_3<K>;

Polyhedron to_polyhedron(const ConvexPolytope& p) {
  std::vector<K::Point_3> pts;
  for (const auto& q : p.points()) pts.emplace_back(K::FT(q.x), K::FT(q.y), K::FT(q.z));
  std::vector<std::vector<std::size_t>> faces;
  for (Index f = 0; f < p.num_facets(); ++f) {
    auto loop = p.facet_vertices(f);
    faces.emplace_back(loop.begin(), loop.end());
  }
  Polyhedron poly;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, faces, poly);
  return poly;
}
}  // namespace

Outcome cgal_nef_sum(const ConvexPolytope& a, const ConvexPolytope& b) {
  Polyhedron pa = to_polyhedron(a), pb = to_polyhedron(b);
  Nef na(pa), nb(pb);
  Outcome o;
  Stopwatch sw;
  Nef s = CGAL::minkowski_sum_3(na, nb);
  o.seconds = sw.seconds();
  if (!s.is_simple()) {
    o.note = "result is not a simple polyhedron";
    return o;
  }
  Polyhedron out;
  s.convert_to_polyhedron(out);
  Mesh m;
  std::map<Polyhedron::Vertex_const_handle, Index> id;
  for (auto v = out.vertices_begin(); v != out.vertices_end(); ++v) {
    id[v] = Index(m.points.size());
    const auto& e = CGAL::exact(v->point());
    m.points.emplace_back(Rational(e.x()), Rational(e.y()), Rational(e.z()));
  }
  for (auto f = out.facets_begin(); f != out.facets_end(); ++f) {
    std::vector<Index> poly;
    auto h = f->facet_begin();
    do {
      poly.push_back(id[h->vertex()]);
    } while (++h != f->facet_begin());
    m.faces.push_back(std::move(poly));
  }
  count_exact(m, o);
  return o;
}

}  // namespace minksum::bench
