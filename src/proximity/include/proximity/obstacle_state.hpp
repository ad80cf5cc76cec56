// The machinery of a TranslationalObstacle (<minksum/proximity.hpp>): its
// queries, walks, caches and recycled storage.  The obstacle forwards every
// query to its state (src/proximity/obstacle.cpp).
#pragma once

#include <minksum/proximity.hpp>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace minksum::detail {

struct ObstacleState {
  // TranslationalObstacle's queries (documented in <minksum/proximity.hpp>).
  ObstacleState(ConvexPolytope p, ConvexPolytope q, Method method);
  ObstacleState(ConvexPolytope p, ConvexPolytope q, Method method, const SumOptions& options);

  void set_p(ConvexPolytope p);
  void set_q(ConvexPolytope q);
  void set_operands(ConvexPolytope p, ConvexPolytope q);

  const ConvexPolytope& p() const;
  const ConvexPolytope& q() const;
  const ConvexPolytope& obstacle() const;
  const SumResult& sum() const;
  const Point3& interior_point() const;

  CollisionResult collide(const Point3& u, const Point3& w);
  DistanceResult distance(const Point3& u, const Point3& w);
  DepthResult penetration_depth(const Point3& u, const Point3& w);
  DirectionalDepthResult directional_depth(const Point3& u, const Point3& w, const Point3& d);

  CollisionResult collide_point(const Point3& s);
  DistanceResult distance_point(const Point3& s);
  DepthResult penetration_depth_point(const Point3& s);
  DirectionalDepthResult directional_depth_point(const Point3& s, const Point3& d);

  void collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out);
  void distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out);
  void penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out);

  Rational squared_distance_by_scan(const Point3& s) const;

  const ProximityStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }

  Feature feature_on_facet(Index f, const Point3& x) const;
  void fill_operand_features(Witness& w) const;
  std::pair<Point3, Point3> decompose(const Feature& m, const Point3& x) const;

  // The machinery.
  void rebuild(ConvexPolytope p, ConvexPolytope q, const SumOptions& options = {});
  // `single`: a single query (not a batch), see spare_distance_.
  void distance_into(const Point3& s, DistanceResult& r, bool single);
  void depth_into(const Point3& s, DepthResult& r, bool single);
  // Collision on s with its rounding sd (computed once per query).
  CollisionResult collide_rounded(const Point3& s, const Vec3d& sd);
  // Facet of M whose cone from `apex` (strictly inside M) contains the ray
  // through `through` (≠ apex); walks from `start`.
  struct RayApprox;  // the apex and the ray point rounded to doubles, for the filters
  Index stab(const Point3& apex, const Point3& through, const RayApprox& ra, Index start);
  Index stab_scan(const Point3& apex, const Point3& through) const;
  bool in_cone(Index f, const Point3& apex, const Point3& through, const RayApprox& ra, Index* exit_halfedge);
  int orient_filtered(const Point3& apex, Index a, Index b, const Point3& through, const RayApprox& ra) const;
  int side_filtered(Index f, const Point3& s, const Vec3d& sd) const;
  // orient3d(interior point, origin(h), target(h), s) by the plane through
  // the three (computed on first use).
  int center_side(Index h, const Point3& s, const Vec3d& sd, bool usable);
  // The smallest feature of M holding the point x of M closest to s (s
  // outside M), and in `facet` a facet holding x that s sees.  On entry
  // `facet` is a facet s sees (the stabbed one); the filtered walk starts
  // from `start` (none: from that facet).  With `first` (s not yet known
  // to be outside M, no stabbed facet): a feature only when its certificate
  // proves s ≠ x, i.e. s outside M; else a vertex of index kNoIndex.
  Feature closest_feature(const Point3& s, const Vec3d& sd, std::optional<Feature> start, Index& facet, bool first);
  Feature closest_feature_scan(const Point3& s, Point3& x, Rational& d2, Index& facet) const;
  // The smallest face of facet f holding the foot of s on f's plane (which
  // lies in the facet): its edges with edge_normal_side 0 for s.
  Feature foot_feature(Index f, const Point3& s, const Vec3d& sd) const;
  // Keeps s in an answer: its doubles when it is exactly a double, else the
  // rational point (in `exact`'s storage when no other answer shares it).
  static void keep_point(const Point3& s, const Vec3d& sd, Vec3d& kept, std::shared_ptr<Point3>& exact);

  std::shared_ptr<detail::ObstacleGeometry> g_;  // shared with the answers
  Method method_;
  std::vector<std::array<double, 4>> plane_approx_;  // a, b, c, d rounded to doubles
  std::vector<Vec3d> normal_approx_;                 // (a, b, c) rounded to doubles
  std::vector<UnitPlane> unit_plane_;                // unit normals and offsets (penetration depth)
  std::vector<const Plane*> plane_ptr_;              // &obstacle().plane(f)
  Vec3d center_approx_;
  // Features of P and Q behind each facet and each edge of M, filled on first use.
  mutable std::vector<std::array<Feature, 2>> facet_features_, edge_features_;
  mutable std::vector<char> facet_features_known_, edge_features_known_;
  // Per halfedge of M: the plane through the interior point and the edge.
  std::vector<Plane> center_plane_;
  std::vector<std::array<double, 4>> center_plane_approx_;
  std::vector<char> center_plane_known_;
  Index last_stab_ = 0, last_exit_ = 0, last_depth_ = 0;
  std::optional<Feature> last_closest_;  // none before the first distance query
  bool last_separate_ = false;           // the last distance answer was separate
  std::uint64_t rng_ = 0x9e3779b97f4a7c15ull;
  // Storage for the exact values of the answers, handed to a new answer
  // when no answer holds it any more (its integers keep their limbs: no
  // allocation per query); see attach_spare in obstacle.cpp.
  std::array<std::shared_ptr<detail::DistanceExact>, 4> spare_distance_;
  std::array<std::shared_ptr<detail::DepthExact>, 4> spare_depth_;
  ProximityStats stats_;
};

}  // namespace minksum::detail
