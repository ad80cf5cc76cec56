// The exact data of a TranslationalObstacle that its answers keep: M = P ⊕
// (−Q), P, Q, M's facet planes as rationals and the interior point.  An
// obstacle makes a new one on every rebuild, so an answer computes its exact
// values (src/proximity/exact_values.cpp) on the M it was answered on.
#pragma once

#include <minksum/proximity.hpp>

#include <utility>
#include <vector>

namespace minksum::detail {

// A rational point as integers over one positive denominator, (x, y, z) / w,
// in no particular lowest terms: HomPoint, the public QuotientPoint.  The
// exact values of an answer are formed in this form (integer products and
// sums, no gcd on the way) and reduced only when a lowest-terms accessor
// asks (exact_values.cpp).
// The exact point (any rational point; the double form is read from the
// doubles' mantissas and exponents, with shifts, no rational arithmetic),
// written into h's storage.
void hom_point(HomPoint& h, const Point3& a);
void hom_point(HomPoint& h, const Vec3d& a);  // precondition: finite
HomPoint hom_point(const Point3& a);
HomPoint hom_point(const Vec3d& a);
// x/w, y/w, z/w in lowest terms.
Point3 to_point(const HomPoint& a);

// Integers the exact values are computed in, kept from one answer to the
// next (GMP integers keep their limbs when assigned): no allocation once
// they have grown to the sizes of an obstacle's values.
struct ExactScratch {
  HomPoint h[8];
  Integer k[12];
};

struct ObstacleGeometry {
  ConvexPolytope p, q, neg_q;
  SumResult sum;
  std::vector<Index> neg_to_q;    // vertex of −Q -> vertex of Q
  std::vector<Point3> normal;     // facet normals (a, b, c) as rationals
  std::vector<Rational> offset;   // d
  std::vector<Rational> norm2;    // a² + b² + c²
  Point3 center, p_center, q_center;  // center = p_center − q_center (the vertex averages)
  // The same data over common denominators, for the exact values: P's and
  // Q's vertices (one denominator per polytope where it stays short), the
  // interior point and its point of P, |n|² of each facet's integer normal.
  std::vector<HomPoint> p_hom, q_hom;
  HomPoint center_hom, p_center_hom;
  std::vector<Integer> n2;

  // Fills p_hom … n2 (the rebuild, once M, P, Q and the centres are set).
  void prepare_exact();
  // Vertex v of M = p − q over one denominator.
  HomPoint m_hom(Index v) const;
  void m_hom(HomPoint& out, Index v) const;  // the same into out's storage

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

// The exact values of an answer by rational arithmetic on every step
// (closest_point, split, common_point above, each intermediate a reduced
// rational): the reference the fast values are tested against.
struct ReferenceDistance {
  Rational squared_distance;
  Point3 direction, point_p, point_q;
};
ReferenceDistance reference_values(const DistanceResult& r);
struct ReferenceDepth {
  Rational squared_depth;
  Point3 direction;
};
ReferenceDepth reference_values(const DepthResult& r);

// The exact values of a DistanceResult, each computed on first use: the
// offset s − x and the points over common denominators, and each
// lowest-terms value only when its accessor asks for it.
struct DistanceExact {
  Point3 u;  // the translation of P, added to the closest points when `translated`
  bool translated = false;
  bool have_s = false, have_offset = false, have_p = false, have_q = false;  // the HomPoints
  bool have_distance = false;
  bool have_squared_distance = false, have_direction = false, have_point_p = false, have_point_q = false;  // lowest terms
  HomPoint s;       // s
  HomPoint offset;  // s − x (zero unless separate)
  HomPoint p, q;    // the closest points of P + u and of Q + w
  Quotient squared_distance_q;
  Rational squared_distance;
  double distance = 0;
  Point3 direction, point_p, point_q;
  ExactScratch scratch;

  // Forget the values (the storage is kept for the next answer).
  void reset() {
    translated = have_s = have_offset = have_p = have_q = have_distance = false;
    have_squared_distance = have_direction = have_point_p = have_point_q = false;
  }
};

// The exact values of a DepthResult, computed on first use: the gap
// g = d·w − ⟨n, S⟩ over w·|n|² (s = S / w), the squared depth, and the
// translation when asked for.
struct DepthExact {
  bool have = false, have_depth = false, have_direction_q = false, have_squared_depth = false, have_direction = false;
  HomPoint s;
  Integer gap, w;
  Quotient squared_depth_q;
  HomPoint direction_q;
  Rational squared_depth;
  double depth = 0;
  Point3 direction;

  void reset() { have = have_depth = have_direction_q = have_squared_depth = have_direction = false; }
};

}  // namespace minksum::detail
