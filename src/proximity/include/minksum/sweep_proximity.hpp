// minksum — proximity under translation when P or Q is a point, a segment or
// a flat polygon (docs/sweeps.md).
//
// The configuration-space obstacle M = P ⊕ (−Q) is a convex set of any
// dimension (minkowski_sum_sets); with s = w − u (P translated by u, Q by w):
//   * separate when s ∉ M; touching when s ∈ ∂M; penetrating when s is in
//     the interior of M (P's interior meets Q: for a segment Q, the segment
//     passes through P's interior; when M is lower-dimensional it has no
//     interior and contact is touching at most);
//   * the separation distance is dist(s, M), the penetration depth
//     dist(s, ∂M) for s inside M, the directional depth along d the smallest
//     t ≥ 0 with s − t·d outside the interior of M.
// Every answer is exact (signs and values of rational expressions), found by
// a scan of M's facets: O(size of M) per query, without the coherent walks
// and witnesses of TranslationalObstacle (<minksum/proximity.hpp>), which
// stays the tool for two polytopes.
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/proximity.hpp>  // ContactStatus
#include <minksum/sweep.hpp>

namespace minksum {

class SetObstacle {
 public:
  // M = P ⊕ (−Q) by minkowski_sum_sets with `method` (walk or chms when an
  // operand is not full-dimensional).
  SetObstacle(const ConvexSet& p, const ConvexSet& q, Method method = Method::automatic);

  const ConvexSet& obstacle() const { return m_; }

  // Queries on s = w − u.
  ContactStatus contact(const Point3& s) const;
  // Exact squared distance from s to M (0 when s is in M).
  Rational squared_distance(const Point3& s) const;
  // Exact squared distance from s to the boundary of M when s is in its
  // interior, else 0.
  Rational squared_depth(const Point3& s) const;
  // The smallest t >= 0 with s − t·d outside the interior of M (0 when s is
  // not in the interior).  UsageError for d = 0.
  Rational directional_depth(const Point3& s, const Point3& d) const;

 private:
  ConvexSet m_;
  std::vector<Plane> planes_;  // M's facet planes (dimension 3)
};

}  // namespace minksum
