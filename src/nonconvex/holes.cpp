// Triangulation of a planar face with holes for the union's boundary
// (union.cpp): CGAL's constrained Delaunay triangulation on the exact (u, v)
// coordinates of the face's plane, triangles inside the region kept by their
// nesting level (odd: inside).  The loops meet only in shared vertices, so no
// intersection point is ever constructed.
#include "nonconvex/union.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <list>
#include <map>

namespace minksum::nonconvex_detail {

namespace {
using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<int, K>;  // nesting level, -1: not yet visited
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
}  // namespace

std::vector<std::array<Index, 3>> triangulate_region(const std::vector<std::vector<PlanePoint>>& loops) {
  CDT cdt;
  std::map<Index, CDT::Vertex_handle> handle;
  for (const auto& loop : loops)
    for (const PlanePoint& p : loop) {
      auto [it, fresh] = handle.emplace(p.id, CDT::Vertex_handle());
      if (!fresh) continue;
      it->second = cdt.insert(K::Point_2(K::FT(p.u), K::FT(p.v)));
      it->second->info() = p.id;
    }
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < (loop.size() == 2 ? 1 : loop.size()); ++i)
      cdt.insert_constraint(handle.at(loop[i].id), handle.at(loop[(i + 1) % loop.size()].id));
  // Nesting levels: the infinite faces' component is level 0; crossing a
  // constrained edge adds one.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::list<CDT::Edge> border;
  auto flood = [&](CDT::Face_handle start, int level) {
    std::list<CDT::Face_handle> queue{start};
    while (!queue.empty()) {
      CDT::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        CDT::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(CDT::Edge(f, i)))
          border.push_back(CDT::Edge(f, i));
        else
          queue.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    CDT::Edge e = border.front();
    border.pop_front();
    CDT::Face_handle n = e.first->neighbor(e.second);
    if (n->info() == -1) flood(n, e.first->info() + 1);
  }
  std::vector<std::array<Index, 3>> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1) out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return out;
}

}  // namespace minksum::nonconvex_detail
