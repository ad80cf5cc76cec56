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
#include <compare>
#include <cstdint>
#include <memory>
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

// An exact rational number as an integer numerator over a positive integer
// denominator, not necessarily in lowest terms (in the spirit of CGAL's
// Quotient): the form in which the exact values of the answers below are
// computed.  Its value is exact; lowest terms are a presentation, paid for
// (one gcd) only by to_rational() and to_string().
class Quotient {
 public:
  Integer num = 0, den = 1;  // den > 0

  Quotient() = default;
  // Throws std::invalid_argument when d is zero; a negative d moves its sign
  // to the numerator.
  Quotient(Integer n, Integer d);
  explicit Quotient(const Rational& q) : num(q.get_num()), den(q.get_den()) {}

  // −1, 0 or 1 (the numerator's sign).
  int sign() const { return sgn(num); }
  // The value in lowest terms (one gcd).
  Rational to_rational() const;
  // The nearest double (ties to even), from num and den as they are (a
  // division of the integers; no gcd).
  double to_double() const;
  // "p/q" in lowest terms, or "p" for an integer (format_exact of
  // to_rational()).
  std::string to_string() const;

  // Exact comparisons by cross-multiplication (two products, no gcd).
  friend int cmp(const Quotient& a, const Quotient& b);
  friend bool operator==(const Quotient& a, const Quotient& b) { return cmp(a, b) == 0; }
  friend std::strong_ordering operator<=>(const Quotient& a, const Quotient& b) { return cmp(a, b) <=> 0; }
  friend bool operator==(const Quotient& a, const Rational& b);
};

// An exact rational point as integer numerators over one positive common
// denominator, (x/w, y/w, z/w), not necessarily in lowest terms.
struct QuotientPoint {
  Integer x = 0, y = 0, z = 0, w = 1;  // w > 0

  // Each coordinate in lowest terms (three gcds).
  Point3 to_point() const;
  // The nearest double of each coordinate.
  Vec3d to_double() const;
  // Exact equality by cross-multiplication (no gcd).
  friend bool operator==(const QuotientPoint& a, const QuotientPoint& b);
  friend bool operator==(const QuotientPoint& a, const Point3& b);
};

class DistanceResult;
class DepthResult;
class TranslationalObstacle;
namespace detail {
struct ObstacleGeometry;  // M, P, Q and their exact data, shared by an obstacle and its answers
struct ObstacleState;     // an obstacle's machinery
struct DistanceExact;     // a distance answer's exact values, allocated on first use
struct DepthExact;        // a depth answer's
struct ReferenceDistance;
struct ReferenceDepth;
using HomPoint = QuotientPoint;  // the exact values' working form
// The exact values by rational arithmetic on every step (for tests).
ReferenceDistance reference_values(const DistanceResult& r);
ReferenceDepth reference_values(const DepthResult& r);
}

// A separation-distance answer.  The query decides `status` and `witness`
// (filtered exact predicates, no rational arithmetic on the common path) and
// keeps the configuration point; the exact values are computed from the
// certified witness on the first call of an accessor and kept in the result
// (later calls return them at no cost).
//
// Two forms of each value:
//   * the *_quotient() accessors give it as integers over a common positive
//     denominator (Quotient, QuotientPoint), exact but not in lowest terms:
//     the integer products named below and nothing else (no gcd).  The
//     vertices of P and Q are kept over one denominator each by the obstacle,
//     s is read off its doubles with shifts, and the integers live in storage
//     the obstacle recycles from one answer to the next (no allocation per
//     query once the answers it recycles are gone);
//   * the Rational / Point3 accessors give the same values in lowest terms:
//     the quotient's work plus one gcd per number (three per point).
// A result stays valid after its obstacle is rebuilt or destroyed: it shares
// the exact data of M, P and Q it was answered on.  Reading the exact values
// of one result from two threads at once is not safe (the first call fills
// the cache).
class DistanceResult {
 public:
  ContactStatus status = ContactStatus::separate;
  Witness witness;

  // |s − x|², x the closest point of M: 0 unless separate.  s − x on the
  // witness feature (a vertex; the projection on an edge's line; on a
  // facet's plane, t·n with one integer t): about a dozen integer products.
  const Quotient& squared_distance_quotient() const;
  // The same in lowest terms: the quotient and one gcd.
  const Rational& squared_distance() const;
  // The nearest double of sqrt(squared_distance()): the quotient's work, a
  // division to the nearest double and a square root.
  double distance() const;
  // The closest points of P+u and of Q+w (equal when the bodies touch or
  // overlap: then a common point).  The squared distance's work (separate
  // answers), then the point of P behind x (a translate when Q's face behind
  // x is a vertex, P's vertex, Cramer's rule on two skew edges, else
  // barycentric coordinates; for overlapping bodies the same on the exit
  // point of the ray from the interior point): a few dozen integer products.
  // point_q of a separate answer adds s − x to the point of P (three more
  // products when their denominators differ).
  const QuotientPoint& point_p_quotient() const;
  const QuotientPoint& point_q_quotient() const;
  // The same in lowest terms: the quotient's work and three gcds.
  const Point3& point_p() const;
  const Point3& point_q() const;
  // point_q() − point_p(): translating P by it brings the bodies into
  // contact (zero unless separate).  The squared distance's work; three gcds
  // for the Point3.
  const QuotientPoint& direction_quotient() const;
  const Point3& direction() const;

 private:
  friend struct detail::ObstacleState;
  friend detail::ReferenceDistance detail::reference_values(const DistanceResult&);
  detail::DistanceExact& exact() const;
  // The offset s − x and |s − x|² (the squared distance's work), then the
  // point of P (the split's).
  detail::DistanceExact& compute_offset() const;
  detail::DistanceExact& compute_p() const;
  const detail::HomPoint& s_hom(detail::DistanceExact& e) const;  // s over one denominator, kept
  Point3 point() const;  // s
  std::shared_ptr<const detail::ObstacleGeometry> geo_;
  // s = w − u: its doubles when it is exactly a double (no rational kept),
  // else the rational point.
  Vec3d sd_;
  std::shared_ptr<Point3> s_exact_;
  // The translation u of P (added to the closest points) and the values
  // computed so far; copies of a result share them.  The obstacle attaches
  // storage it recycles (proximity/obstacle_state.hpp).
  mutable std::shared_ptr<detail::DistanceExact> exact_;
};

// A penetration-depth answer: `status` and `witness` (the nearest facet of M
// and the smallest face of M holding the foot of s on it) are decided by the
// query; the exact values are computed on first use, in the two forms of
// DistanceResult's.
class DepthResult {
 public:
  ContactStatus status = ContactStatus::separate;
  Witness witness;

  // (d − n·s)² / |n|² for the witness facet's plane n·x = d: 0 unless
  // penetrating.  g = d·w − n·S for s = S / w (four integer products), g²
  // over w²·|n|² (three more).
  const Quotient& squared_depth_quotient() const;
  // The same in lowest terms (one gcd more).
  const Rational& squared_depth() const;
  // The nearest double of sqrt(squared_depth()) (computes it).
  double depth() const;
  // A minimal translation of P that makes the bodies touch (zero vector
  // unless penetrating); its squared length is squared_depth().  It is
  // parallel to the outer normal of the witness facet of M, pointing against
  // it.  The squared depth's work and three products; three gcds for the
  // Point3.
  const QuotientPoint& direction_quotient() const;
  const Point3& direction() const;

 private:
  friend struct detail::ObstacleState;
  friend detail::ReferenceDepth detail::reference_values(const DepthResult&);
  detail::DepthExact& exact() const;
  Point3 point() const;  // s
  std::shared_ptr<const detail::ObstacleGeometry> geo_;  // none unless penetrating
  Vec3d sd_;                          // s, when exactly a double
  std::shared_ptr<Point3> s_exact_;   // else s
  mutable std::shared_ptr<detail::DepthExact> exact_;  // computed on first use; shared by copies
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
  // The same, the sum reporting progress to and polled for cancellation by
  // `options` (a set SumOptions::cancel throws Cancelled: no obstacle).
  TranslationalObstacle(ConvexPolytope p, ConvexPolytope q, Method method, const SumOptions& options);

  // Replace P or Q (e.g. rotated copies of the originals); recomputes M and
  // forgets the cached witnesses.  Answers given before keep the M they were
  // answered on.
  void set_p(ConvexPolytope p);
  void set_q(ConvexPolytope q);
  void set_operands(ConvexPolytope p, ConvexPolytope q);

  const ConvexPolytope& p() const;
  const ConvexPolytope& q() const;
  // M = P ⊕ (−Q) and how it was computed (vertex_origin indexes P and −Q).
  const ConvexPolytope& obstacle() const;
  const SumResult& sum() const;
  // The point of M's interior the collision rays start from (exact).
  const Point3& interior_point() const;

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
  // the single queries.  distance_points and penetration_depth_points assign
  // into the existing results, so a caller that keeps `out` from one batch
  // to the next reuses their storage instead of allocating new ones.
  void collide_points(std::span<const Point3> s, std::vector<CollisionResult>& out);
  void distance_points(std::span<const Point3> s, std::vector<DistanceResult>& out);
  void penetration_depth_points(std::span<const Point3> s, std::vector<DepthResult>& out);

  // The exact squared distance from s to M by a scan of every facet s sees
  // (no walk, no filter; 0 when s is in M): an independent check of
  // distance_point, O(F·deg) rational operations.
  Rational squared_distance_by_scan(const Point3& s) const;

  const ProximityStats& stats() const;
  void reset_stats();

  // Witness helpers (public for tests and tools): the smallest face of M
  // containing the point x of facet f (precondition: x lies in facet f), and
  // the features of P and Q behind a feature of M.
  Feature feature_on_facet(Index f, const Point3& x) const;
  void fill_operand_features(Witness& w) const;
  // A decomposition x = p − q with p in P and q in Q, for a point x of the
  // feature `m` of M (vertices of P and Q combined with the barycentric
  // coordinates of x in m).
  std::pair<Point3, Point3> decompose(const Feature& m, const Point3& x) const;

  // Copies share nothing but the answers' exact data (as the answers do).
  TranslationalObstacle(const TranslationalObstacle& o);
  TranslationalObstacle(TranslationalObstacle&&) noexcept;
  TranslationalObstacle& operator=(const TranslationalObstacle& o);
  TranslationalObstacle& operator=(TranslationalObstacle&&) noexcept;
  ~TranslationalObstacle();

 private:
  std::unique_ptr<detail::ObstacleState> s_;  // proximity/obstacle_state.hpp
};

}  // namespace minksum
