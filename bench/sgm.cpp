// minksum bench — CGAL's (undocumented) spherical Gaussian map,
// Arr_polyhedral_sgm: build the map of each operand, overlay them.
#include "competitors.hpp"
#include "timer.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm_polyhedron_3.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm_traits.h>

namespace minksum::bench {

namespace {
using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Gm_traits = CGAL::Arr_polyhedral_sgm_traits<K>;
using Sgm = CGAL::Arr_polyhedral_sgm<Gm_traits>;
using Polyhedron = CGAL::Arr_polyhedral_sgm_polyhedron_3<Sgm, K>;
using Initializer = CGAL::Arr_polyhedral_sgm_initializer<Sgm, Polyhedron>;

struct Soup {
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> faces;
};
Soup to_soup(const ConvexPolytope& p) {
  Soup s;
  for (const auto& q : p.points()) s.points.emplace_back(K::FT(q.x), K::FT(q.y), K::FT(q.z));
  for (Index f = 0; f < p.num_facets(); ++f) {
    auto loop = p.facet_vertices(f);
    s.faces.emplace_back(loop.begin(), loop.end());
  }
  return s;
}
void build(Sgm& sgm, const Soup& s) {
  Initializer init(sgm);
  init(s.points.begin(), s.points.end(), s.points.size(), s.faces.begin(), s.faces.end(), s.faces.size());
}
}  // namespace

Outcome cgal_sgm_sum(const ConvexPolytope& a, const ConvexPolytope& b) {
  Soup sa = to_soup(a), sb = to_soup(b);
  Outcome o;
  Sgm sum;
  {
    Stopwatch sw;
    Sgm ga, gb;
    build(ga, sa);
    build(gb, sb);
    Stopwatch overlay;
    sum.minkowski_sum(ga, gb);
    o.sub_seconds = overlay.seconds();
    o.seconds = sw.seconds();
  }
  o.v = long(sum.number_of_vertices());
  o.e = long(sum.number_of_edges());
  o.f = long(sum.number_of_facets());
  o.note = "counts read off the Gaussian map";
  return o;
}

}  // namespace minksum::bench
