// minksum — a convex set of any dimension: a point, a segment, a flat convex
// polygon in any plane of 3D space, or a full-dimensional ConvexPolytope
// (docs/sweeps.md).
//
// A ConvexSet is what an operand of a sweep is and what a sum involving one
// returns.  Full-dimensional sets hold a ConvexPolytope, untouched (every
// method works on it as before); the lower-dimensional ones hold their
// vertices only, exact:
//   * dimension 0: one point;
//   * dimension 1: the two distinct endpoints of a segment;
//   * dimension 2: the vertices of a strictly convex polygon (no three
//     consecutive ones collinear), in order, counter-clockwise seen from the
//     tip of normal(); all in one plane.
// Like ConvexPolytope, it is only built through validating constructors, and
// they throw InputError (source, place, problem) for data that is not a
// convex set of the kind asked for.
#pragma once

#include <minksum/polytope.hpp>

#include <string>
#include <vector>

namespace minksum {

class ConvexSet {
 public:
  ConvexSet() = default;
  // A full-dimensional set (dimension 3).
  explicit ConvexSet(ConvexPolytope p);

  static ConvexSet point(const Point3& p);
  // The segment [a, b]; InputError naming `source` when a == b (a zero-length
  // segment is refused: docs/sweeps.md).
  static ConvexSet segment(const Point3& a, const Point3& b, const std::string& source = "");
  // A flat convex polygon from its vertex loop (either orientation): equal
  // consecutive points are welded and points in the middle of an edge
  // dropped; InputError when the points are not coplanar, the loop is not a
  // convex polygon, or it spans fewer than 2 dimensions.
  static ConvexSet polygon(const std::vector<Point3>& loop, const std::string& source = "");
  // The exact convex hull of `points`, of whatever dimension they span
  // (0 to 3); InputError for no points at all.
  static ConvexSet hull(const std::vector<Point3>& points, const std::string& source = "");
  static ConvexSet hull(const PointList& points, const std::string& source = "");
  // A mesh with exactly one face is a flat polygon (that face; the mesh's
  // other points are ignored); any other mesh goes through
  // ConvexPolytope::from_mesh.
  static ConvexSet from_mesh(const Mesh& mesh, const std::string& source = "");

  // 0 (point), 1 (segment), 2 (polygon) or 3 (polytope).
  int dimension() const { return dim_; }
  bool full() const { return dim_ == 3; }
  // Dimension 3 only.
  const ConvexPolytope& polytope() const { return polytope_; }
  // The same, moved out of a set about to be dropped (no copy).
  ConvexPolytope release_polytope() && { return std::move(polytope_); }
  // Every vertex, exact (dimension 3: the polytope's points).
  const std::vector<Point3>& vertices() const { return dim_ == 3 ? polytope_.points() : vertices_; }
  // Dimension 2 only: a normal of the polygon's plane (not normalised), the
  // loop being counter-clockwise seen from its tip.
  const Point3& normal() const { return normal_; }

  Index num_vertices() const;
  Index num_edges() const;   // 0, 1, the polygon's vertex count, the polytope's edges
  Index num_facets() const;  // 0, 0, 1 (the polygon itself), the polytope's facets

  // The polygon mesh (dimension 3: one polygon per facet; 2: the polygon as
  // one face; 1 and 0: the points without faces).
  Mesh to_mesh() const;
  // Exact volume (0 below dimension 3).
  Rational volume() const;
  // Exact area of a polygon, squared (dimension 2; else 0): |normal-weighted
  // shoelace|^2 / 4, kept squared so it stays rational.
  Rational area_squared() const;

  ConvexSet translated(const Point3& t) const;
  ConvexSet negated() const;

  // Same set: same dimension and vertex set (any order, any loop start, any
  // orientation of a polygon's loop).
  friend bool same_set(const ConvexSet& a, const ConvexSet& b);

 private:
  // A polygon from a loop already known to be strictly convex.
  static ConvexSet convex_polygon(std::vector<Point3> loop);

  int dim_ = 0;
  ConvexPolytope polytope_;
  std::vector<Point3> vertices_;
  Point3 normal_;
};

// "point", "segment", "polygon" or "polytope".
const char* dimension_name(int dimension);

}  // namespace minksum
