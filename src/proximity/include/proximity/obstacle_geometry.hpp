// The exact data of a TranslationalObstacle that its answers keep: M = P ⊕
// (−Q), P, Q, M's facet planes as rationals and the interior point.  An
// obstacle makes a new one on every rebuild, so an answer computes its exact
// values (src/proximity/exact_values.cpp) on the M it was answered on.
#pragma once

#include <minksum/proximity.hpp>

#include <utility>
#include <vector>

namespace minksum::detail {

struct ObstacleGeometry {
  ConvexPolytope p, q, neg_q;
  SumResult sum;
  std::vector<Index> neg_to_q;    // vertex of −Q -> vertex of Q
  std::vector<Point3> normal;     // facet normals (a, b, c) as rationals
  std::vector<Rational> offset;   // d
  std::vector<Rational> norm2;    // a² + b² + c²
  Point3 center, p_center, q_center;  // center = p_center − q_center (the vertex averages)

  const ConvexPolytope& m() const { return sum.polytope; }

  // The point of the feature `feat` of M closest to s, for a feature
  // certified to hold the closest point of M (a vertex; the projection on an
  // edge's line; the projection on a facet's plane).
  Point3 closest_point(const Feature& feat, const Point3& s) const;
  // x = p − q with p in the face w.p of P and q in the face w.q of Q, for a
  // point x of the face w.m of M.
  std::pair<Point3, Point3> split(const Witness& w, const Point3& x) const;
  // The same by x's barycentric coordinates in the feature `feat` of M.
  std::pair<Point3, Point3> decompose(const Feature& feat, const Point3& x) const;
  // A common point (p, q) of P and Q + s, p − q = s, for s in M: the touching
  // point, or for s inside M the exit point of the ray from the interior
  // point through s split on the stabbed facet and scaled back to s.
  std::pair<Point3, Point3> common_point(const Witness& w, ContactStatus status, const Point3& s) const;
};

// The exact values of a DistanceResult, computed on first use.
struct DistanceExact {
  Point3 u;  // the translation of P, added to the closest points when `translated`
  bool translated = false;
  bool have_distance = false, have_points = false;
  Rational squared_distance;
  double distance = 0;
  Point3 direction, point_p, point_q;
};

// The exact values of a DepthResult, computed on first use.
struct DepthExact {
  bool have = false;
  Rational squared_depth;
  double depth = 0;
  Point3 direction;
};

}  // namespace minksum::detail
