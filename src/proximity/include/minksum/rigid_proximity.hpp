// minksum — exact collision, separation distance and penetration depth of
// two convex polytopes each under its own pose (rotation and translation),
// without building P ⊕ (−Q).  Collision is described here; distance and
// depth below, at their functions.
//
// P is placed by x ↦ R_P x + t_P and Q by x ↦ R_Q x + t_Q.  A rotation is an
// integer quaternion (the exact rational matrix of transform.hpp, as
// "@rot:A,B,C,D") or a 3×3 matrix of doubles taken exactly as given: the
// answer is exact for that matrix (which need not be exactly orthogonal; it
// must have a positive determinant, so that it maps a convex polytope onto a
// convex polytope with the same faces).
//
// The status follows the translation queries' convention (proximity.hpp):
// separate (no common point), touching (common points, interiors disjoint),
// penetrating (the interiors meet).  The search runs on doubles — GJK on the
// Minkowski difference D of the placed bodies, each support found by hill
// climbing on the body's vertex graph from the previous witness — and the
// answer is certified exactly (docs/proximity.md "Rigid motion"):
//   * separate: a direction n (doubles, taken exactly), a vertex p of P and a
//     vertex q of Q such that p is a maximum of n · x over placed P and q a
//     minimum over placed Q (no neighbour in the vertex graph is further,
//     exact signs) and n · (q' − p') > 0 (exact sign);
//   * penetrating: four pairs (p_k, q_k) whose differences, points of D,
//     span a tetrahedron that holds the origin strictly inside (exact
//     signs);
//   * touching, and separate where the doubles cannot certify a plane (the
//     gap within rounding): the features the search ends on (a facet of
//     one placed body, or an edge of each) give a plane with an exact
//     rational normal N; exact climbs find max N·x over placed P and min
//     over placed Q.  Below: separate.  Equal: the bodies meet only in
//     their faces in that plane, so touching when those faces meet (a
//     vertex of one in the other, or two edges crossing; exact signs) and
//     separate otherwise (certificate feature_plane);
//   * penetrating within rounding (no candidate plane separates or
//     touches): a tetrahedron over the face of D nearest the origin along
//     a candidate's exact normal, with the vertex of D lowest along it,
//     holding the origin strictly (exact signs; certificate simplex);
//   * anything else — poses the double search and the feature plane leave
//     undecided — is decided in exact arithmetic: M = R_P P ⊕ (−R_Q Q) is
//     built exactly and asked for t_Q − t_P (the cost of building M).
// Every sign is an exact sign (placed_predicates.hpp: interval filter, then
// rationals; the feature plane and the tetrahedron's exact stage evaluate on
// the points of one PlacedFrame, integers when the matrices and the vertices
// are doubles, whatever the translations).
#pragma once

#include <minksum/placed_predicates.hpp>
#include <minksum/polytope.hpp>
#include <minksum/proximity.hpp>
#include <minksum/transform.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

namespace minksum {

// A rigid placement x ↦ R x + t (see the top of this header).
class RigidPose {
 public:
  RigidPose() = default;  // the identity
  explicit RigidPose(PlacedMap map) : map_(std::move(map)) {}
  static RigidPose translation(const Point3& t);
  // The rotation of the non-zero integer quaternion q, then t.
  static RigidPose quaternion(const Quaternion& q, const Point3& t);
  static RigidPose quaternion(const Quaternion& q, const Vec3d& t);  // t's doubles taken exactly
  // Machine-integer components (no GMP number made for those of at most
  // 2^25); its own name, so that quaternion({1, 2, 3, 4}, t) stays unambiguous.
  static RigidPose quaternion64(const std::array<std::int64_t, 4>& q, const Vec3d& t);
  // A row-major matrix of doubles, taken exactly, then t.  Throws
  // UsageError for a non-finite entry or a determinant ≤ 0.
  static RigidPose matrix(const std::array<double, 9>& r, const Point3& t);
  static RigidPose matrix(const std::array<double, 9>& r, const Vec3d& t);
  const PlacedMap& map() const { return map_; }

 private:
  PlacedMap map_;
};

// A convex polytope prepared for queries under rigid motion: its vertex
// graph, its vertices as doubles and their interval enclosures, and where
// the searches' climbs start for each direction (about one seed vertex per
// vertex; docs/proximity.md "Search").  Built once; copies share it, and
// every pose and every thread reads it without synchronisation.
class RigidBody {
 public:
  explicit RigidBody(ConvexPolytope p);
  const ConvexPolytope& polytope() const;
  struct Data;
  const Data& data() const { return *d_; }

 private:
  std::shared_ptr<const Data> d_;
};

// How an answer was proved.
enum class RigidCertificate : std::uint8_t {
  separating_plane,  // separate: the plane of `normal` between the supports p and q
  simplex,           // penetrating: a tetrahedron of D holding the origin strictly
  exact,             // built M exactly (touching, or undecided by the search)
  closest_points,    // separate, with its distance: closest points whose difference's plane supports both bodies
  nearest_facet,     // penetrating, with its depth: a star of triangles of D around the origin, the nearest plane supporting D
  exit_facet,        // penetrating, with a directional depth: the triangle of D the ray leaves by, its plane supporting D
  feature_plane,     // separate or touching: the exact plane of a facet of one body or an edge of each supports both;
                     // touching when their faces in it meet
};
// "separating_plane", "simplex", "exact", "closest_points", "nearest_facet",
// "exit_facet", "feature_plane".
const char* rigid_certificate_name(RigidCertificate c);

struct RigidCollision {
  ContactStatus status = ContactStatus::separate;
  RigidCertificate certificate = RigidCertificate::exact;
  // separating_plane: the direction n (taken exactly) and vertices p of P
  // and q of Q with n·x' < n·q' for every vertex x of placed P and n·y' >
  // n·p' for every vertex y of placed Q (p and q: where the search's climbs
  // ended, at or within rounding of the maximum and the minimum along n;
  // docs/proximity.md, "Certificates").  feature_plane: n the nearest doubles of the plane's exact
  // normal N, p and q with N·p' = max over placed P = min over placed Q
  // (touching) or < it (separate).  Otherwise n is zero and p, q the last
  // support pair of the search.
  Vec3d normal;
  Index p = kNoIndex, q = kNoIndex;
};

// The witnesses a query starts from and leaves for the next one: the last
// support vertices of P and Q and the last search direction (zero: none),
// and, after collide answered penetrating by a tetrahedron, its four pairs
// of vertices (tp[k], tq[k]), which the next collide checks first: on a
// coherent trajectory the same tetrahedron of D usually still holds the
// origin.  A coherent sequence of poses passed with the same RigidWarmStart
// costs a few support steps per query.  Every field is a guess that the
// query certifies or drops.
struct RigidWarmStart {
  Index p = 0, q = 0;
  Vec3d direction;
  bool tetrahedron = false;
  std::array<Index, 4> tp{}, tq{};
};

// Counters of the calling thread since it started: queries (collide and
// distance) and how they were proved, GJK iterations, support-climb steps.
struct RigidStats {
  std::uint64_t queries = 0, separating_plane = 0, simplex = 0, exact = 0, closest_points = 0, nearest_facet = 0,
                exit_facet = 0, feature_plane = 0;
  std::uint64_t iterations = 0, climb_steps = 0;
  std::uint64_t warm_tetrahedra = 0;  // collide answers proved by the warm start's tetrahedron (counted in simplex too)
  std::uint64_t inward_tetrahedra = 0;  // ... by a tetrahedron over the face of D nearest the origin (simplex too)
  std::uint64_t epa_continuations = 0;  // depth: vertices of D added beyond a nearest face the exact climbs refuted
};
RigidStats rigid_stats();

// Collision of placed P and placed Q.  `warm` (optional) is read and updated.
RigidCollision collide(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                       RigidWarmStart* warm = nullptr);

// The same for N poses: poses_p and poses_q each hold N poses or a single one
// (the same pose for every query); out must hold N answers.  The poses are
// split into runs of consecutive poses over `threads` threads (0: one per
// hardware thread, 1: the calling thread), each run warm-started from its
// previous pose, so a trajectory stays coherent within a run.  Throws
// UsageError for mismatched sizes.
void collide(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
             std::span<const RigidPose> poses_q, std::span<RigidCollision> out, unsigned threads = 0);

// Poses made on demand, for a batch over poses held in another form (arrays
// of numbers): source(i, body, scratch) gives pose i of P (body 0) or of Q
// (body 1), either a pose the source keeps or `scratch` once built there.
// The batches below call it just before answering pose i, on the thread
// that answers it (so from several threads at once), and answer exactly as
// the span batches do on the same poses, without a vector of N poses.  An
// exception it throws is rethrown by the batch (the first in pose order).
using RigidPoseSource = std::function<const RigidPose&(std::size_t i, int body, RigidPose& scratch)>;
void collide(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses, std::span<RigidCollision> out,
             unsigned threads = 0);

// The exact values of a distance answer.
struct RigidDistanceExact {
  Rational squared_distance;  // dist(P', Q')², 0 unless separate
  Point3 point_p, point_q;    // closest points of placed P and placed Q (equal unless separate)
};

// Separation distance of placed P and placed Q, with closest points.
//
// The search is GJK run to convergence in doubles; its last simplex gives k
// (1 to 3) pairs (p_j, q_j) of vertices of P and Q whose differences d_j =
// p_j' − q_j' (placed points) are points of D = P' ⊕ (−Q').  The answer is
// certified (certificate closest_points) when, in exact signs
// (placed_predicates.hpp, PlacedSimplexPoint):
//   * the point v of the affine hull of the d_j nearest the origin is
//     v = Σ λ_j d_j with every λ_j ≥ 0 (so v ∈ D, x = Σ λ_j p_j' ∈ P',
//     y = Σ λ_j q_j' ∈ Q', v = x − y) and v ≠ 0;
//   * p_0 is a maximum of −v · z over placed P and q_0 a minimum over
//     placed Q (no neighbour in the vertex graph further, exact signs).
// Then |v| = dist(P', Q') (the plane normal to v through x supports P', the
// one through y supports Q', and they are |v| apart) and x, y are closest
// points.  Penetrating answers are certified as by collide (simplex),
// touching ones by collide's feature plane (certificate feature_plane: the
// distance is 0 and the common point of the faces in the plane is both
// closest points); what the search leaves undecided is answered on
// M = R_P P ⊕ (−R_Q Q) built exactly (certificate exact).
struct RigidDistance {
  ContactStatus status = ContactStatus::separate;
  RigidCertificate certificate = RigidCertificate::exact;
  // lower ≤ dist(P', Q') ≤ upper, certified (0 unless separate), and a
  // double within them (the search's).  The exact value: exact_values().
  double distance = 0, lower = 0, upper = 0;
  // The k pairs of vertices (indices of P and of Q as given) behind the
  // answer: closest_points, the 1 to 3 pairs of the closest points (x = Σ
  // λ_j p_j', y = Σ λ_j q_j'); simplex, the 4 pairs of the tetrahedron
  // holding the origin; exact and feature_plane, none (k = 0).
  int k = 0;
  std::array<Index, 4> p{kNoIndex, kNoIndex, kNoIndex, kNoIndex}, q{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
  // The closest points of placed P and placed Q (a common point when they
  // meet), doubles near the exact ones.
  Vec3d point_p, point_q;
  // exact and feature_plane: the exact values, found while answering.
  std::shared_ptr<const RigidDistanceExact> exact;
};

RigidDistance distance(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                       RigidWarmStart* warm = nullptr);

// The same for N poses, as the batch collide above.
void distance(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
              std::span<const RigidPose> poses_q, std::span<RigidDistance> out, unsigned threads = 0);
void distance(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses, std::span<RigidDistance> out,
              unsigned threads = 0);

// The exact squared distance and closest points of an answer of distance()
// for the same bodies and poses: rational arithmetic on its certified pairs
// (closest_points: the λ_j solved exactly; simplex: the origin's barycentric
// coordinates in the tetrahedron give a common point), or the values kept
// from M (exact).  Throws UsageError when the answer's indices do not fit
// the bodies.
RigidDistanceExact exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                const RigidPose& pose_q, const RigidDistance& d);

// The exact values of a penetration-depth answer.
struct RigidDepthExact {
  Rational squared_depth;  // 0 unless penetrating
  Point3 direction;        // the shortest translation of P that brings the bodies out of overlap (0 unless penetrating)
};

// Penetration depth of placed P and placed Q: dist(0, ∂D) for D = P′ ⊕
// (−Q′) when the origin is inside D, and the shortest translation of P
// that ends the overlap.
//
// The search is GJK (a tetrahedron of D holding the origin), then EPA
// (G. van den Bergen, "Proximity queries and penetration depth computation
// on 3D game objects", Game Developers Conference 2001) in doubles: a closed
// surface of triangles with vertices in D, grown towards ∂D.  The answer is
// certified (nearest_facet) when, in exact signs (PlacedTriangle):
//   * the triangles form a closed, consistently oriented surface of genus 0
//     (every directed edge has its reverse once, V − E + F = 2) and the
//     origin lies strictly inside every triangle's plane: then the cones
//     from the origin over the triangles tile space (the radial projection
//     is a covering of the sphere by a sphere, hence one sheet), so every
//     ray from the origin leaves their union through one triangle;
//   * the plane of one triangle F is no further from the origin than any
//     other's: the ball of radius r = dist(0, plane F) lies in the union,
//     which lies in D (its vertices are points of D), so depth ≥ r;
//   * F's plane supports D: for one of F's pairs (p_a, q_a), p_a maximises
//     n · x over placed P and q_a minimises it over placed Q (no neighbour
//     further): then D lies on one side of F's plane, so depth ≤ r.
// Answers that are not penetrating are collide's (depth 0); anything the
// search leaves undecided is answered on M built exactly (exact).
struct RigidDepth {
  ContactStatus status = ContactStatus::separate;
  RigidCertificate certificate = RigidCertificate::exact;
  // lower ≤ depth ≤ upper, certified (0 unless penetrating), and a double
  // within them.  The exact value: exact_values().
  double depth = 0, lower = 0, upper = 0;
  // nearest_facet: the three pairs of vertices (of P and of Q as given)
  // whose differences span F; otherwise kNoIndex.
  std::array<Index, 3> p{kNoIndex, kNoIndex, kNoIndex}, q{kNoIndex, kNoIndex, kNoIndex};
  // Doubles near the shortest translation of P out of overlap.
  Vec3d direction;
  // exact: the exact values, found while answering (on M).
  std::shared_ptr<const RigidDepthExact> exact;
};

RigidDepth penetration_depth(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                             RigidWarmStart* warm = nullptr);
void penetration_depth(const RigidBody& p, std::span<const RigidPose> poses_p, const RigidBody& q,
                       std::span<const RigidPose> poses_q, std::span<RigidDepth> out, unsigned threads = 0);
void penetration_depth(const RigidBody& p, const RigidBody& q, const RigidPoseSource& poses,
                       std::span<RigidDepth> out, unsigned threads = 0);
// The exact squared depth and translation of an answer of
// penetration_depth() for the same bodies and poses.
RigidDepthExact exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                             const RigidDepth& d);
// The same on M built exactly (a reference).
RigidDepthExact depth_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q);

// Directional penetration depth along d (exact, not normalised): the
// smallest α ≥ 0 such that placed P translated by α·d no longer overlaps
// the interior of placed Q — the exit parameter of the ray {−α d} from the
// origin out of D.  The search grows the tetrahedron of collide towards the
// face the ray crosses (EPA's insertions); the answer is certified
// (exit_facet) by a triangle T of D with, in exact signs: the origin
// strictly inside its plane, n · (−d) > 0, the ray's point on the plane
// inside T (three edge signs ≥ 0, so it is a point of D), and T's plane
// supporting D (climbs as for depth).  Then points of the ray before it are
// interior to D (the origin is) and points after it are beyond a
// supporting plane: α is the ray's parameter there, exactly.
struct RigidDirectionalDepth {
  ContactStatus status = ContactStatus::separate;
  RigidCertificate certificate = RigidCertificate::exact;
  double t = 0, lower = 0, upper = 0;  // α, certified enclosure (0 unless penetrating)
  std::array<Index, 3> p{kNoIndex, kNoIndex, kNoIndex}, q{kNoIndex, kNoIndex, kNoIndex};  // exit_facet: T's pairs
  std::shared_ptr<const Rational> exact;  // exact: α, found on M
};
RigidDirectionalDepth directional_depth(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                        const RigidPose& pose_q, const Point3& d, RigidWarmStart* warm = nullptr);
// α exactly, for an answer of directional_depth() with the same inputs.
Rational exact_values(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q,
                      const Point3& d, const RigidDirectionalDepth& r);
// α on M built exactly (a reference).
Rational directional_depth_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                 const RigidPose& pose_q, const Point3& d);

// The exact answer by building M = R_P P ⊕ (−R_Q Q) (the fall-back above,
// on its own: an independent check of the search; O(cost of the sum)).
ContactStatus collide_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q, const RigidPose& pose_q);
RigidDistanceExact distance_exact(const RigidBody& p, const RigidPose& pose_p, const RigidBody& q,
                                  const RigidPose& pose_q);

// The polytope R P (the linear part of the pose only), exactly.
ConvexPolytope placed_linear(const ConvexPolytope& p, const PlacedMap& map);

}  // namespace minksum
