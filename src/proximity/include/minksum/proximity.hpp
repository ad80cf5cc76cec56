// minksum — exact proximity queries between two convex polytopes under
// translation (Fogel and Halperin 2006, §4).
//
// P is translated by u and Q by w.  With s = w − u and the configuration-space
// obstacle M = P ⊕ (−Q):
//   * P+u and Q+w intersect        ⇔ s ∈ M;
//   * they touch (boundaries only) ⇔ s ∈ ∂M;
//   * separation distance          = dist(s, M);
//   * penetration depth            = dist(s, ∂M) for s inside M;
//   * directional penetration depth along d = the smallest α ≥ 0 with
//     s − α·d outside the interior of M (P translated by α·d no longer overlaps
//     the interior of Q).  d is taken as given, not normalised.
//
// Every decision is exact (signs of exact polynomials, rational arithmetic, no
// tolerance).  Squared distances, squared depths and α are exact rationals;
// the doubles next to them are conveniences (the nearest double of the exact
// value, or of its square root).
//
// TranslationalObstacle owns M for the current orientations of P and Q and
// keeps the last witness of each query kind; the next query starts its walk
// there (spatial and temporal coherence).  Replacing or rotating P or Q
// recomputes M and forgets the witnesses.  docs/proximity.md describes the
// walks, their cost and their fall-backs.
//
// Thread safety: a TranslationalObstacle is not safe to query from two
// threads at once (queries update the cached witnesses); distinct objects are
// independent.
#pragma once

#include <minksum/minkowski.hpp>
#include <minksum/polytope.hpp>
#include <minksum/transform.hpp>  // rotations of the operands
#include <minksum/unit_plane.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace minksum {

enum class ContactStatus { separate, touching, penetrating };
// "separate", "touching", "penetrating".
const char* contact_status_name(ContactStatus s);

// Where a query was decided.  `facet` is the facet of M the query ended on:
// the facet stabbed by the ray from M's interior point through s (collision),
// a facet containing the closest point of M (distance), the nearest facet
// plane (penetration depth) or the facet through which the ray from s along
// −d leaves M (directional depth).  `m` is the smallest feature of M that
// contains the point of M the answer refers to (the closest point, the contact
// point, the exit point; for a separate collision query the stabbed facet,
// for a penetrating one the stabbed facet as well), and `p`, `q` are the
// features of P and of Q behind it: m = p ⊕ (−q), with p the face of P
// and q the face of Q (indices of P and of Q as given, not of −Q).
struct Witness {
  Index facet = kNoIndex;
  Feature m, p, q;
};

struct CollisionResult {
  ContactStatus status = ContactStatus::separate;
  Witness witness;
};

struct DistanceResult {
  ContactStatus status = ContactStatus::separate;
  Rational squared_distance;  // 0 unless separate
  double distance = 0;        // nearest double of sqrt(squared_distance)
  // Closest points of P+u and of Q+w (equal when the bodies touch or overlap:
  // then a common point).
  Point3 point_p, point_q;
  // point_q − point_p: translating P by it brings the bodies into contact.
  Point3 direction;
  Witness witness;
};

struct DepthResult {
  ContactStatus status = ContactStatus::separate;
  Rational squared_depth;  // 0 unless penetrating
  double depth = 0;        // nearest double of sqrt(squared_depth)
  // A minimal translation of P that makes the bodies touch (zero vector unless
  // penetrating); its squared length is squared_depth.  It is parallel to the
  // outer normal of the witness facet of M, pointing against it.
  Point3 direction;
  Witness witness;
};

struct DirectionalDepthResult {
  ContactStatus status = ContactStatus::separate;
  Rational t;           // α, exact (0 unless penetrating)
  double depth = 0;     // α·|d| (nearest double)
  Point3 translation;   // α·d, exact
  Witness witness;
};

// Work counters since construction (or the last reset).
struct ProximityStats {
  std::uint64_t queries = 0;
  std::uint64_t walk_steps = 0;      // facet / feature moves of the coherent walks
  std::uint64_t full_scans = 0;      // walks abandoned for a scan of all features
  std::uint64_t certified = 0;       // distance walks ended by a filtered Voronoi-region certificate
  std::uint64_t rebuilds = 0;        // computations of M
};


class TranslationalObstacle {
 public:
  // Computes M = P ⊕ (−Q) with `method` (any exact method gives the same M).
  TranslationalObstacle(ConvexPolytope p, ConvexPolytope q, Method method = Method::automatic);

  // Replace P or Q (e.g. rotated copies of the originals); recomputes M and
  // forgets the cached witnesses.
  void set_p(ConvexPolytope p);
  void set_q(ConvexPolytope q);
  void set_operands(ConvexPolytope p, ConvexPolytope q);

  const ConvexPolytope& p() const { return p_; }
  const ConvexPolytope& q() const { return q_; }
  // M = P ⊕ (−Q) and how it was computed (vertex_origin indexes P and −Q).
  const ConvexPolytope& obstacle() const { return sum_.polytope; }
  const SumResult& sum() const { return sum_; }
  // The point of M's interior the collision rays start from (exact).
  const Point3& interior_point() const { return center_; }

  // Queries for P translated by u and Q translated by w.
  CollisionResult collide(const Point3& u, const Point3& w);
  DistanceResult distance(const Point3& u, const Point3& w);
  DepthResult penetration_depth(const Point3& u, const Point3& w);
  // Throws UsageError when d is the zero vector.
  DirectionalDepthResult directional_depth(const Point3& u, const Point3& w, const Point3& d);

  // The same queries on s = w − u directly (a point of configuration space).
  CollisionResult collide_point(const Point3& s);
  DistanceResult distance_point(const Point3& s);
  DepthResult penetration_depth_point(const Point3& s);
  DirectionalDepthResult directional_depth_point(const Point3& s, const Point3& d);

  // Trajectory (batch) queries: the answers for the configuration-space
  // points s[0], s[1], … in order, written into `out` (resized to s.size()).
  // Each walk starts from the previous query's witness, so a coherent
  // trajectory costs a few filtered moves per query; the answers are those of
  // the single queries.  distance_points assigns into the existing results,
  // so a caller that keeps `out` from one batch to the next reuses its
  // rationals' storage instead of allocating new ones.
  void collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out);
  void distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out);
  void penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out);

  // The exact squared distance from s to M by a scan of every facet s sees
  // (no walk, no filter; 0 when s is in M): an independent check of
  // distance_point, O(F·deg) rational operations.
  Rational squared_distance_by_scan(const Point3& s) const;

  const ProximityStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }

  // Witness helpers (public for tests and tools): the smallest face of M
  // containing the point x of facet f (precondition: x lies in facet f), and
  // the features of P and Q behind a feature of M.
  Feature feature_on_facet(Index f, const Point3& x) const;
  void fill_operand_features(Witness& w) const;
  // A decomposition x = p − q with p in P and q in Q, for a point x of the
  // feature `m` of M (vertices of P and Q combined with the barycentric
  // coordinates of x in m).
  std::pair<Point3, Point3> decompose(const Feature& m, const Point3& x) const;

 private:
  void rebuild();
  void distance_into(const Point3& s, DistanceResult& r);
  std::pair<Point3, Point3> split(const Witness& w, const Point3& x) const;
  // Facet of M whose cone from `apex` (strictly inside M) contains the ray
  // through `through` (≠ apex); walks from `start`.
  Index stab(const Point3& apex, const Point3& through, Index start);
  Index stab_scan(const Point3& apex, const Point3& through) const;
  struct RayApprox;  // the apex and the ray point rounded to doubles, for the filters
  bool in_cone(Index f, const Point3& apex, const Point3& through, const RayApprox& ra, Index* exit_halfedge);
  int orient_filtered(const Point3& apex, Index a, Index b, const Point3& through, const RayApprox& ra) const;
  int side_filtered(Index f, const Point3& s) const;
  // The smallest feature of M holding the point x of M closest to s (s
  // outside M), dir = s − x and d2 = |s − x|², and in `facet` a facet
  // holding x that s sees.  On entry `facet` is a facet s sees (the stabbed one); the filtered
  // walk starts from `start` (none: from that facet).
  Feature closest_feature(const Point3& s, std::optional<Feature> start, Point3& dir, Rational& d2, Index& facet);
  Feature closest_feature_scan(const Point3& s, Point3& x, Rational& d2, Index& facet) const;

  ConvexPolytope p_, q_, neg_q_;
  Method method_;
  SumResult sum_;
  std::vector<Index> neg_to_q_;       // vertex of −Q -> vertex of Q
  std::vector<Point3> normal_;        // facet normals (a, b, c) as rationals
  std::vector<Rational> offset_;      // d
  std::vector<Rational> norm2_;       // a² + b² + c²
  std::vector<std::array<double, 4>> plane_approx_;  // a, b, c, d rounded to doubles
  std::vector<Vec3d> normal_approx_;                 // (a, b, c) rounded to doubles
  std::vector<UnitPlane> unit_plane_;                // unit normals and offsets (penetration depth)
  std::vector<const Plane*> plane_ptr_;              // &obstacle().plane(f)
  Point3 center_, p_center_, q_center_;  // center_ = p_center_ − q_center_ (the vertex averages)
  Vec3d center_approx_;
  // Features of P and Q behind each facet of M, filled on first use.
  mutable std::vector<std::array<Feature, 2>> facet_features_;
  mutable std::vector<char> facet_features_known_;
  Index last_stab_ = 0, last_exit_ = 0, last_depth_ = 0;
  std::optional<Feature> last_closest_;  // none before the first distance query
  std::uint64_t rng_ = 0x9e3779b97f4a7c15ull;
  ProximityStats stats_;
};

}  // namespace minksum
