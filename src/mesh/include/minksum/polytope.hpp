// minksum — validated convex polytopes with half-edge connectivity.
//
// A ConvexPolytope is a closed, convex, 3-dimensional polytope with exact
// rational vertex coordinates, stored in their cheapest exact form (a
// PointList: doubles, exact pairs of doubles, or GMP rationals; see
// point_list.hpp).  It is only ever built through a validating constructor:
//   * from_mesh(): vertices + polygons (any file format, the catalog).  The
//     mesh must be a closed connected 2-manifold of sphere topology with
//     consistently oriented, exactly planar polygons and no reflex edge.  A
//     consistently inward-facing mesh is flipped.  Coplanar adjacent facets
//     are merged into one polygon and vertices in the middle of an edge are
//     dropped, so a triangulated STL of a cube becomes 8 vertices, 12 edges,
//     6 facets.  Exactly equal vertices are welded; unused vertices dropped.
//   * hull(): the exact convex hull of a point cloud.
// Both throw InputError (file, place, problem) when the data is not a convex
// polytope, and recognise the degenerate cases (empty, a point, collinear,
// coplanar, zero volume) with a message saying which.
//
// Invariants of a built polytope (checked exactly, no tolerance):
//   * facets are convex polygons, counter-clockwise seen from outside;
//   * no two adjacent facets are coplanar, no vertex has degree 2;
//   * every edge is strictly convex;
//   * V - E + F = 2.
//
// Half-edge conventions (all O(1)):
//   * halfedge h runs origin(h) -> target(h); facet(h) lies on its left seen
//     from outside, i.e. next(h) continues facet(h) counter-clockwise;
//   * twin(h) = h ^ 1, edge(h) = h >> 1, the two halfedges of edge e are
//     2e and 2e + 1;
//   * around a vertex, next_around_vertex(h) = twin(prev(h)) is the next
//     outgoing halfedge counter-clockwise seen from outside.
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/point_list.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace minksum {

using Index = std::uint32_t;
inline constexpr Index kNoIndex = 0xffffffffu;

// A face of a convex polytope, by its dimension and its index among the
// polytope's vertices, edges (ConvexPolytope::edge) or facets.
enum class FeatureDim : std::uint32_t { vertex = 0, edge = 1, facet = 2 };
struct Feature {
  FeatureDim dim = FeatureDim::vertex;
  Index index = kNoIndex;
  static constexpr Feature vertex(Index v) { return {FeatureDim::vertex, v}; }
  static constexpr Feature edge(Index e) { return {FeatureDim::edge, e}; }
  static constexpr Feature facet(Index f) { return {FeatureDim::facet, f}; }
  friend bool operator==(const Feature&, const Feature&) = default;
};

// Raw polygon soup, as read from a file or made by the catalog: no
// guarantees at all until ConvexPolytope::from_mesh() validates it.
struct Mesh {
  PointList points;
  std::vector<std::vector<Index>> faces;  // indices into points
};

class ConvexPolytope {
 public:
  ConvexPolytope() = default;

  // Validate `mesh` and build the polytope.  `source` names the input in
  // error messages (a file path or a catalog name).
  static ConvexPolytope from_mesh(const Mesh& mesh, const std::string& source = "");
  // Exact convex hull of `points` (CGAL convex_hull_3 on exact points, then
  // coplanar facets merged).  Throws InputError if the points do not span
  // 3 dimensions.
  static ConvexPolytope hull(const std::vector<Point3>& points, const std::string& source = "");
  static ConvexPolytope hull(const PointList& points, const std::string& source = "");

  // Counts.
  Index num_vertices() const { return static_cast<Index>(coords_.size()); }
  Index num_facets() const { return static_cast<Index>(facet_he_.size()); }
  Index num_halfedges() const { return static_cast<Index>(he_origin_.size()); }
  Index num_edges() const { return num_halfedges() / 2; }

  // Geometry.  What each accessor costs:
  //   coordinates(), approx(v):  O(1), no allocation (approx(v) is the
  //       nearest double point, exact when coordinates_are_doubles());
  //   point(v), points():  the exact rational point.  Free for rational
  //       coordinates; for double coordinates the first call builds every
  //       exact point once (O(V) GMP rationals, then cached, thread-safe) —
  //       use approx(v) or coordinates() where doubles suffice;
  //   plane(f):  the canonical integer plane, computed on the first call for
  //       that facet from three of its vertices (integer arithmetic on the
  //       doubles' mantissas, GMP only for rational coordinates), then
  //       cached; safe when several threads read the same polytope.
  const PointList& coordinates() const { return coords_; }
  const Vec3d& approx(Index v) const { return coords_.approx(v); }
  const Point3& point(Index v) const;
  const std::vector<Point3>& points() const;
  const Plane& plane(Index f) const;
  // True when every vertex coordinate is exactly a double.
  bool coordinates_are_doubles() const { return coords_.all_doubles(); }
  // Index of vertex v in the mesh or point list this polytope was built from.
  Index source_vertex(Index v) const { return source_vertex_[v]; }

  // Half-edge connectivity.
  Index origin(Index h) const { return he_origin_[h]; }
  Index target(Index h) const { return he_origin_[h ^ 1u]; }
  Index facet(Index h) const { return he_facet_[h]; }
  Index next(Index h) const { return he_next_[h]; }
  Index prev(Index h) const { return he_prev_[h]; }
  static Index twin(Index h) { return h ^ 1u; }
  static Index edge(Index h) { return h >> 1; }
  Index next_around_vertex(Index h) const { return twin(prev(h)); }
  Index facet_halfedge(Index f) const { return facet_he_[f]; }    // one halfedge of f
  Index vertex_halfedge(Index v) const { return vertex_he_[v]; }  // one outgoing halfedge
  Index facet_degree(Index f) const;
  Index vertex_degree(Index v) const;

  // Vertex loop of facet f, counter-clockwise seen from outside.
  std::vector<Index> facet_vertices(Index f) const;
  // Neighbours of v, counter-clockwise seen from outside.
  std::vector<Index> vertex_neighbours(Index v) const;

  // Exact volume (positive).  For double and double-pair coordinates it is
  // computed in integers scaled by a power of two (no rational arithmetic).
  Rational volume() const;
  // Euler characteristic V - E + F (always 2 for a built polytope).
  long euler_characteristic() const {
    return long(num_vertices()) - long(num_edges()) + long(num_facets());
  }

  // Back to a polygon mesh (one polygon per facet, CCW from outside).
  Mesh to_mesh() const;

  // Every vertex translated by t (exact), or negated (-P, the point reflection).
  ConvexPolytope translated(const Point3& t) const;
  ConvexPolytope negated() const;

  // Check every invariant listed at the top of this header again, from
  // scratch; returns an empty string when all hold, else the first failure.
  // For tests and debugging (O(n) exact arithmetic).
  std::string check_invariants() const;

 private:
  friend class PolytopeBuilder;
  struct Cache;  // lazily computed exact points and planes (polytope.cpp)
  // Fresh caches; every constructor calls it once the geometry is final.
  void reset_cache();

  PointList coords_;
  std::vector<Index> source_vertex_;
  std::vector<Index> he_origin_, he_facet_, he_next_, he_prev_;
  std::vector<Index> facet_he_, vertex_he_;
  // Shared by copies (the geometry is immutable once built).
  std::shared_ptr<Cache> cache_;
};

}  // namespace minksum
