// The steps of the non-convex sum done with CGAL's exact Nef polyhedra
// (Hachenberger, Algorithmica 2009): convex decomposition and the union of
// the pair sums, plus the self-intersection test of validation.  The only
// CGAL translation unit of the layer.
#include <minksum/error.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/parallel.hpp>

#include "nonconvex/nef.hpp"
#include "nonconvex/triangles_meet.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <CGAL/minkowski_sum_3.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <iterator>
#include <map>

namespace minksum::nonconvex_detail {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using KPoint = K::Point_3;
using Polyhedron = CGAL::Polyhedron_3<K>;
using Nef = CGAL::Nef_polyhedron_3<K>;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

KPoint to_cgal(const Point3& p) { return KPoint(K::FT(p.x), K::FT(p.y), K::FT(p.z)); }

Point3 from_cgal(const KPoint& p) {
  const auto& e = CGAL::exact(p);
  return Point3(Rational(e.x()), Rational(e.y()), Rational(e.z()));
}

std::vector<KPoint> cgal_points(const PointList& points) {
  std::vector<KPoint> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out.push_back(to_cgal(points[i]));
  return out;
}

Polyhedron polyhedron_of(const Mesh& m) {
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(m.faces.size());
  for (const auto& f : m.faces) faces.emplace_back(f.begin(), f.end());
  Polyhedron p;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(cgal_points(m.points), faces, p);
  return p;
}

Nef nef_of(const ConvexPolytope& p) {
  Polyhedron poly = polyhedron_of(p.to_mesh());
  return Nef(poly);
}

struct FirstHit {};

// The shells of a closed 2-manifold triangle mesh: its connected components
// (triangles linked by shared edges), each as a mesh of its own, faces
// turned outwards (a cavity's shell faces into the cavity: reversed).
std::vector<Mesh> outward_shells(const Mesh& triangles) {
  const std::size_t n = triangles.faces.size();
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<std::pair<Index, Index>, std::size_t> edge;
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      Index a = triangles.faces[t][k], b = triangles.faces[t][(k + 1) % 3];
      auto [it, fresh] = edge.emplace(std::make_pair(std::min(a, b), std::max(a, b)), t);
      if (!fresh) parent[find(t)] = find(it->second);
    }
  std::map<std::size_t, Mesh> by_root;
  for (std::size_t t = 0; t < n; ++t) by_root[find(t)].faces.push_back(triangles.faces[t]);
  std::vector<Mesh> shells;
  for (auto& [root, m] : by_root) {
    std::map<Index, Index> renum;  // the shell's own vertices only
    for (auto& f : m.faces)
      for (Index& v : f) {
        auto [it, fresh] = renum.emplace(v, Index(m.points.size()));
        if (fresh) m.points.push_from(triangles.points, v);
        v = it->second;
      }
    if (sgn(mesh_volume(m)) < 0)
      for (auto& f : m.faces) std::reverse(f.begin(), f.end());
    shells.push_back(std::move(m));
  }
  return shells;
}

// The solid bounded by a validated triangle mesh as a Nef polyhedron: the
// points inside an odd number of its shells (its shells are disjoint and
// nested), i.e. the symmetric difference of the shells' interiors.
Nef solid_nef(const Mesh& triangles) {
  std::optional<Nef> nef;
  for (const Mesh& shell : outward_shells(triangles)) {
    Polyhedron poly = polyhedron_of(shell);
    Nef n(poly);
    nef = nef ? nef->symmetric_difference(n) : n;
  }
  return nef->regularization();
}

}  // namespace

namespace {
// The first pair of triangles that meet (triangles_meet), in the order in
// which CGAL's self_intersections reports them: the same boxes in the same
// order (one per triangle, the sum of its points' bboxes, identified by
// their addresses), the same box_self_intersection_d call (cutoff 2000),
// whose callback sees the pairs of meeting boxes in a fixed order; a
// collinear triangle, which has no box, is reported as (f, f) before any
// pair.  CGAL builds a Surface_mesh to find the triangles sharing an edge
// through its halfedges; in a closed 2-manifold triangle mesh (validation
// checks that first) two triangles with two points in common are exactly
// the two across that edge, so the triangles' point indices tell the same
// without the mesh.  The pairs of boxes are collected in batches and, with
// `threads` other than 1, tested on threads (the kernel's predicates are
// then those of doubles, which hold no shared state); the first meeting
// pair of the first batch holding one is the answer.
template <class IK>
std::optional<std::pair<Index, Index>> first_hit(const std::vector<typename IK::Point_3>& p, const Mesh& triangles,
                                                 unsigned threads) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index, CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
  using Tri = std::array<Index, 3>;
  std::vector<Tri> tris;
  tris.reserve(triangles.faces.size());
  for (const auto& f : triangles.faces) tris.push_back(Tri{f[0], f[1], f[2]});
  std::vector<Box> boxes;
  boxes.reserve(tris.size());
  for (Index f = 0; f < tris.size(); ++f) {
    const auto &a = p[tris[f][0]], &b = p[tris[f][1]], &c = p[tris[f][2]];
    if (CGAL::collinear(a, b, c)) return std::make_pair(f, f);
    boxes.push_back(Box(a.bbox() + b.bbox() + c.bbox(), f));
  }
  std::vector<const Box*> box_ptr;
  box_ptr.reserve(boxes.size());
  for (const Box& b : boxes) box_ptr.push_back(&b);

  constexpr std::size_t kBatch = std::size_t(1) << 20, kChunk = 512;
  std::vector<std::pair<Index, Index>> batch;
  batch.reserve(std::min(kBatch, 16 * boxes.size() + 16));
  std::optional<std::pair<Index, Index>> hit;
  // The first meeting pair of the batch, if any.
  auto test = [&] {
    const std::size_t chunks = (batch.size() + kChunk - 1) / kChunk;
    const unsigned workers = batch.size() >= parallel_items() ? parallel_threads(threads, chunks) : 1;
    std::atomic<std::size_t> first{batch.size()};
    parallel_for(chunks, workers, [&](std::size_t c) {
      const std::size_t end = std::min(batch.size(), (c + 1) * kChunk);
      for (std::size_t k = c * kChunk; k < end && k < first.load(std::memory_order_relaxed); ++k)
        if (triangles_meet<IK>(tris[batch[k].first], tris[batch[k].second], p)) {
          std::size_t seen = first.load();
          while (k < seen && !first.compare_exchange_weak(seen, k)) {
          }
          return;
        }
    });
    if (first.load() < batch.size()) {
      const auto [a, b] = batch[first.load()];
      hit = std::make_pair(std::min(a, b), std::max(a, b));
    }
    batch.clear();
    return bool(hit);
  };
  auto callback = [&](const Box* a, const Box* b) {
    batch.emplace_back(a->info(), b->info());
    if (batch.size() == kBatch && test()) throw FirstHit{};
  };
  try {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(box_ptr.begin(), box_ptr.end(), callback, std::ptrdiff_t(2000));
    test();
  } catch (const FirstHit&) {
  }
  return hit;
}
}  // namespace

// The test needs exact predicates only (do two triangles meet?): when every
// coordinate is a double (a rounded output, most files read), CGAL's kernel
// of exact predicates on doubles decides it exactly without building exact
// rational points, on every hardware thread; otherwise the exact kernel, on
// one thread (its lazily computed exact values are not shared across
// threads).
std::optional<std::pair<Index, Index>> first_self_intersection(const Mesh& triangles) {
  if (triangles.points.all_doubles()) {
    using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
    std::vector<IK::Point_3> points;
    points.reserve(triangles.points.size());
    for (std::size_t i = 0; i < triangles.points.size(); ++i) {
      const Vec3d& d = triangles.points.approx(i);
      points.emplace_back(d.x, d.y, d.z);
    }
    return first_hit<IK>(points, triangles, 0);
  }
  return first_hit<K>(cgal_points(triangles.points), triangles, 1);
}

namespace {
// The convex pieces of a Nef polyhedron: convex_decomposition_3, then every
// marked volume but the first (the unbounded outside) is one convex piece.
std::vector<ConvexPolytope> convex_pieces(Nef& nef) {
  CGAL::convex_decomposition_3(nef);
  std::vector<ConvexPolytope> pieces;
  for (auto c = std::next(nef.volumes_begin()); c != nef.volumes_end(); ++c) {
    if (!c->mark()) continue;
    Polyhedron piece;
    nef.convert_inner_shell_to_polyhedron(c->shells_begin(), piece);
    std::vector<Point3> points;
    for (auto v = piece.vertices_begin(); v != piece.vertices_end(); ++v) points.push_back(from_cgal(v->point()));
    pieces.push_back(ConvexPolytope::hull(points, "convex piece"));
  }
  return pieces;
}
}  // namespace

std::vector<ConvexPolytope> nef_convex_pieces(const Mesh& triangles) {
  Nef nef = solid_nef(triangles);
  return convex_pieces(nef);
}

namespace {
// The boundary of a Nef polyhedron as polygons, counter-clockwise seen from
// outside, exactly equal points one vertex.
Mesh boundary_mesh(const Nef& u) {
  Mesh out;
  std::vector<KPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
  CGAL::convert_nef_polyhedron_to_polygon_soup(u, points, polygons, false);
  std::map<Point3, Index> index;
  std::vector<Index> renum(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point3 p = from_cgal(points[i]);
    auto [it, fresh] = index.emplace(p, Index(out.points.size()));
    if (fresh) out.points.push_back(std::move(p));
    renum[i] = it->second;
  }
  for (const auto& poly : polygons) {
    std::vector<Index> f;
    for (std::size_t v : poly) f.push_back(renum[v]);
    out.faces.push_back(std::move(f));
  }
  return out;
}
}  // namespace

void nef_union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out) {
  auto t0 = Clock::now();
  std::vector<Nef> level;
  level.reserve(parts.size());
  for (const auto& p : parts) level.push_back(nef_of(p));
  // A balanced tree of joins: each round joins neighbours pairwise, so the
  // operands of a join have similar sizes.
  const std::size_t total = parts.empty() ? 0 : parts.size() - 1;
  std::size_t done = 0;
  options.report("union", 0.0);
  while (level.size() > 1) {
    std::vector<Nef> next;
    next.reserve((level.size() + 1) / 2);
    for (std::size_t i = 0; i + 1 < level.size(); i += 2) {
      next.push_back(level[i].join(level[i + 1]));
      ++done;
      options.report("union", total ? double(done) / double(total) : 1.0);
    }
    if (level.size() % 2) next.push_back(std::move(level.back()));
    level = std::move(next);
  }
  out.seconds_union = since(t0);

  t0 = Clock::now();
  options.report("boundary", -1.0);
  out.mesh = Mesh{};
  if (level.empty()) return;
  const Nef& u = level[0];
  out.mesh = boundary_mesh(u);
  // Shells: the volumes' first shells that the conversion visits; edges at
  // more than two faces are where the solid touches itself.
  std::size_t shells = 0;
  for (auto c = std::next(u.volumes_begin()); c != u.volumes_end(); ++c) ++shells;
  out.shells = shells;
  std::map<std::pair<Index, Index>, int> edge_faces;
  for (const auto& f : out.mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      Index a = f[i], b = f[(i + 1) % f.size()];
      ++edge_faces[{std::min(a, b), std::max(a, b)}];
    }
  out.non_manifold_edges = 0;
  for (const auto& [e, c] : edge_faces)
    if (c > 2) ++out.non_manifold_edges;
  out.seconds_boundary = since(t0);
}

Rational nef_union_volume(const std::vector<ConvexPolytope>& parts) {
  std::optional<Nef> u;
  for (const auto& p : parts) u = u ? u->join(nef_of(p)) : nef_of(p);
  Rational volume = 0;
  for (const auto& piece : convex_pieces(*u)) volume += piece.volume();
  return volume;
}

}  // namespace minksum::nonconvex_detail

namespace minksum {

Mesh reference_minkowski_sum(const Solid& a, const Solid& b, double* seconds) {
  using namespace nonconvex_detail;
  Nef na = solid_nef(a.triangles), nb = solid_nef(b.triangles);
  const auto t0 = Clock::now();
  Nef s = CGAL::minkowski_sum_3(na, nb);
  if (seconds) *seconds = since(t0);
  return boundary_mesh(s);
}

Mesh reference_erosion(const Solid& a, const Solid& b, double* seconds) {
  using namespace nonconvex_detail;
  if (!b.convex) throw std::invalid_argument("reference_erosion: B is not convex");
  // A box around A ⊕ B and A ⊕ (−B): within A, the complement of A and the
  // box minus A have the same sum with −B.
  Rational reach = 1;
  for (const Point3& p : b.convex->points())
    for (int k = 0; k < 3; ++k) {
      const Rational r = abs(p[k]) + 1;
      if (r > reach) reach = r;
    }
  Point3 lo = a.triangles.points[0], hi = lo;
  for (std::size_t i = 0; i < a.triangles.points.size(); ++i) {
    const Point3 p = a.triangles.points[i];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  std::vector<Point3> corners;
  for (int c = 0; c < 8; ++c) {
    Point3 q;
    for (int k = 0; k < 3; ++k) q[k] = (c >> k & 1) ? Rational(hi[k] + reach) : Rational(lo[k] - reach);
    corners.push_back(q);
  }
  // B moved so that its vertex centroid c is the origin, and the result
  // moved back by -c (A ⊖ (B' + c) = (A ⊖ B') - c): minkowski_sum_3 of the
  // box minus A (A a cavity in it) with a -B that does not contain the
  // origin loses volume (lshape ⊖ cube@scale:1/10@translate:1/8,0,0 gives
  // 439/250 instead of 224/125).
  Point3 c(Rational(0), Rational(0), Rational(0));
  for (const Point3& p : b.convex->points()) c = c + p;
  c = Rational(1, long(b.convex->num_vertices())) * c;
  const Nef na = solid_nef(a.triangles);
  Nef outside = (nef_of(ConvexPolytope::hull(corners)) - na).regularization();
  Nef negated = nef_of(b.convex->translated(-c).negated());
  const auto t0 = Clock::now();
  const Nef swept = CGAL::minkowski_sum_3(outside, negated);
  const Nef e = (na - swept).regularization();
  if (seconds) *seconds = since(t0);
  Mesh m = boundary_mesh(e);
  Mesh out;
  for (std::size_t i = 0; i < m.points.size(); ++i) out.points.push_back(m.points[i] - c);
  out.faces = std::move(m.faces);
  return out;
}

}  // namespace minksum
