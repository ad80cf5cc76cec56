// Internal to src/nonconvex/: the boundary sweep's view of a solid's surface
// (sweep_pieces.cpp, docs/nonconvex.md "Method").
#pragma once

#include <minksum/nonconvex.hpp>
#include <minksum/predicates.hpp>

#include "kernel/plane.hpp"
#include "nonconvex/union.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace minksum::nonconvex_detail {

// Whether q lies in the interior of the closed surface made of `tris`
// (indices into `points`, counter-clockwise seen from outside; q must not
// lie on it): the parity of the crossings of an exact ray that meets no edge
// or vertex of the surface.  `normals`, when given, holds each triangle's
// (p1 - p0) x (p2 - p0) or a positive multiple of it; `approx`, when given, the nearest doubles of the
// points (the orientation tests then filter on them); `boxes`, when given,
// boxes (lo, hi) containing each triangle's exact points: the triangles
// whose boxes the ray's line provably misses are skipped.
bool strictly_inside(const Point3& q, const std::vector<Point3>& points, const std::vector<std::array<Index, 3>>& tris,
                     const std::vector<Point3>* normals = nullptr, const std::vector<Vec3d>* approx = nullptr,
                     const std::vector<std::array<double, 6>>* boxes = nullptr);

// The triangulated closed surface of a solid A (Solid::triangles), with what
// decides which facets of a piece t ⊕ C (t a triangle of A, C convex) can
// lie on the boundary of A ⊕ B.
class SurfaceCones {
 public:
  explicit SurfaceCones(const Mesh& triangles);

  // Whether a facet with outward normal u of t ⊕ C (any convex C) can hold
  // points of the boundary of A ⊕ B.  Such a point is a + c with a on t
  // and u in the local normal cone of A at a (A lies below the plane
  // through a normal to u near a).  With the face of t extreme in u:
  //   * t itself: u must be t's outward normal;
  //   * an edge of t: u in the edge's cone (convex edges: the arc between
  //     the normals of its two faces; flat and reflex edges: none) or in a
  //     cone of one of its two vertices;
  //   * a vertex v: u in v's cone, over-approximated by u . (w - v) <= 0
  //     for every neighbour w of v (exact for a convex vertex; a superset
  //     elsewhere, whose extra facets lie inside A + b and are dropped with
  //     the pockets of the sweep).
  // Exact: signs of dot products by the kernel's filtered dot_sign on the
  // exact points and their cached roundings (u given with a faithful
  // rounding of each coordinate, as to_double gives).
  bool candidate(Index t, const RoundedPoint3& u) const;
  // The same, given which of t's vertices are highest along u (at_top[k]
  // for the k-th vertex of the triangle).
  // `memo`, when given, remembers for each point v of the surface
  // (memo[v * stride], -1 before it is known) whether every neighbour of v
  // is at most as high as v along u, the vertex cone's test, which depends
  // on v and u only; concurrent callers may share it.
  bool candidate(Index t, const RoundedPoint3& u, const bool at_top[3], signed char* memo = nullptr,
                 std::size_t stride = 0) const;
  bool candidate(Index t, const Point3& u) const { const Vec3d a = to_double(u); return candidate(t, RoundedPoint3{u, a}); }

  // Whether t keeps a candidate facet with normal u of t ⊕ C (at_top as for
  // candidate) when other triangles build the same facet, the same polygon
  // on the same plane, which is then a candidate of theirs too: the facet
  // is kept by the first of them.
  //   * face_u(t) an edge e whose other triangle t' has its far vertex
  //     strictly below along u: t' has e at its top too, and builds the same
  //     facet (face_u(t') = e, so the same kind, plane and polygon) with the
  //     same candidate test (the edge's convexity, the arcs and the two
  //     vertex cones are the edge's, not the triangle's); the lower index
  //     keeps it;
  //   * face_u(t) a vertex v: every triangle at v whose two other vertices
  //     are strictly below builds f + v with the same test (v's cone); the
  //     lowest index keeps it;
  //   * face_u(t) = t: only t builds it.
  // Where an edge has other than two triangles, or its two triangles are not
  // each other's neighbours across it, t keeps the facet.
  bool keeps(Index t, const RoundedPoint3& u, const bool at_top[3]) const;

  // The pieces of the sweep are convex polygons of the surface, P ⊕ C
  // (docs/nonconvex.md, "Pieces"): each triangle its own polygon, until
  // merge_coplanar groups triangles.  A polygon's corners are surface
  // points, counter-clockwise seen from outside, strictly convex (no three
  // on a line), each of them a corner of the polygon's triangles and every
  // corner of those triangles one of them; its edges are edges of the
  // surface, edge k from corner k to corner k + 1 being edge
  // edge_index[k] of the polygon's triangle edge_triangle[k] (the same
  // direction).
  struct Polygon {
    std::vector<Index> corners;
    std::vector<Index> edge_triangle;
    std::vector<std::uint8_t> edge_index;
  };
  // The most corners of a merged polygon (the sweep's plane tags hold a corner's number).
  static constexpr std::size_t kMaxCorners = 64;
  // Groups the triangles into strictly convex polygons: starting from each
  // triangle not yet grouped, in order, the triangle across an edge of the
  // polygon joins it when the edge is flat, the two triangles pair up across
  // it and have the same outward normal, and the polygon stays strictly
  // convex (exact orientations in the common plane).  The union of the
  // pieces P ⊕ C is that of the triangles' pieces t ⊕ C (the sum
  // distributes over the union of the triangles, which is P), with fewer
  // pieces where the surface is flat.
  void merge_coplanar();
  std::size_t polygons() const { return polygons_.size(); }
  const Polygon& polygon(Index g) const { return polygons_[g]; }
  // The polygon holding triangle t.
  Index polygon_of(Index t) const { return polygon_of_[t]; }
  // candidate and keeps for a facet with outward normal u of P ⊕ C, P
  // polygon g, at_top[k] telling whether P's k-th corner is highest along u
  // (a corner, an edge or all of P).  The face of P extreme along u is a
  // corner, an edge or P itself, and so is it for the triangle of P that
  // holds it: candidate is the triangle's test on that face.  keeps:
  //   * face_u(P) = P: only P builds the facet;
  //   * an edge e: the polygon across e builds the same facet when its far
  //     side is strictly below along u (one corner off e tells, P being
  //     strictly convex); the lower number keeps it;
  //   * a corner v: every polygon at v whose two neighbours of v are
  //     strictly below builds f + v with the same test; the lowest number
  //     keeps it.
  // With each triangle its own polygon these are candidate and keeps above.
  bool polygon_candidate(Index g, const RoundedPoint3& u, const bool* at_top, signed char* memo = nullptr,
                         std::size_t stride = 0) const;
  bool polygon_candidate(Index g, const RoundedPoint3& u) const;
  bool polygon_keeps(Index g, const RoundedPoint3& u, const bool* at_top) const;

  // Whether q lies in the interior of the solid (q must not lie on its
  // surface): the parity of the crossings of an exact ray that meets no
  // edge or vertex of the surface.
  bool strictly_inside(const Point3& q) const;

  std::size_t triangles() const { return tri_.size(); }
  std::size_t points() const { return points_.size(); }
  const std::array<Index, 3>& triangle(Index t) const { return tri_[t]; }
  const Point3& point(Index v) const { return points_[v]; }
  // The point as integers over a common denominator (kernel/plane.hpp).
  const ScaledPoint& scaled(Index v) const { return scaled_[v]; }
  // The point with its nearest doubles, for the kernel's filtered predicates.
  RoundedPoint3 rounded(Index v) const { return at(v); }
  // The edges of the surface, each once, numbered in the order of the
  // triangles that first hold them: their ends, in the direction that
  // triangle runs the edge.
  std::size_t edges() const { return edge_ends_.size(); }
  const std::array<Index, 2>& edge_ends(std::size_t e) const { return edge_ends_[e]; }
  // Edge k = (c[k], c[k+1]) of triangle t: 2 e for edge e run from its first
  // end to its second, 2 e + 1 the other way.
  Index edge_of(Index t, int k) const { return edge_[t][k]; }
  // Triangle t's outward normal, the primitive integer multiple of
  // (p1 - p0) x (p2 - p0) (made in integers, smaller than the rational
  // product), and its nearest doubles.
  const Point3& normal(Index t) const { return normal_[t]; }
  const Vec3d& normal_approx(Index t) const { return normal_approx_[t]; }

 private:
  bool below_all_neighbours(Index v, const RoundedPoint3& u, Index level = ~Index(0)) const;
  bool below_all_neighbours(Index v, const RoundedPoint3& u, Index level, signed char* memo, std::size_t stride) const;
  RoundedPoint3 at(Index v) const { return RoundedPoint3{points_[v], approx_[v]}; }

  std::vector<Point3> points_;
  std::vector<Vec3d> approx_;                      // nearest doubles of points_
  std::vector<ScaledPoint> scaled_;                // points_ over common denominators
  std::vector<Vec3d> normal_approx_;               // of normal_
  std::vector<std::array<double, 6>> box_;         // per triangle, (lo, hi) containing its exact points (widen_box)
  std::vector<std::array<Index, 3>> tri_;
  std::vector<Point3> normal_;                     // primitive integer multiple of (p1 - p0) x (p2 - p0)
  std::vector<std::array<Index, 3>> opposite_;     // edge k = (c[k], c[k+1]): the far vertex of the face across it
  std::vector<std::array<signed char, 3>> kind_;   // edge k: -1 convex, 0 flat, +1 reflex
  std::vector<std::vector<Index>> neighbours_;     // per vertex
  std::vector<std::vector<Index>> incident_;       // per vertex, its triangles, ascending
  std::vector<std::array<Index, 3>> across_;       // edge k: the triangle across it, when the two pair up; else kNoTriangle
  std::vector<std::array<Index, 3>> edge_;         // edge k: edge_of
  std::vector<std::array<Index, 2>> edge_ends_;    // per edge
  std::vector<Polygon> polygons_;                  // the pieces' polygons (merge_coplanar)
  std::vector<Index> polygon_of_;                  // per triangle
  std::vector<std::vector<Index>> polygons_at_;    // per point, the polygons holding it, ascending (merged only)
  bool merged_ = false;                            // else polygon g is triangle g, polygons_at_ is incident_
  static constexpr Index kNoTriangle = ~Index(0);
};

// The convex operand B of the pieces P ⊕ B, prepared once for every
// polygon P of the swept surface (triangle_sum.cpp, docs/nonconvex.md
// "Pieces"): its facets' planes and normals, its edges with the far vertex of
// each adjacent facet, its exact bounding box.
class SweptPolytope final : public PlaneBuilder {
 public:
  // `surface`, when given, is the surface of the non-convex solid O that B
  // is a convex piece of (B ⊆ O): a facet of P ⊕ B is then also culled
  // unless its face of B can hold a point o of O's surface with the
  // facet's normal u in O's local normal cone at o (on_surface).
  explicit SweptPolytope(const ConvexPolytope& b, const SurfaceCones* surface = nullptr);
  // The canonical plane k of a piece, from its tag and code (triangle_sum.cpp):
  // facet k of B moved to the corner of P at its top, P plus a vertex of B,
  // or an edge of P plus an edge of B.
  Plane build(const Piece& piece, Index k) const override;
  // Whether plane k of a piece holds p_m + b_v, the label m << 32 | v
  // (surface point m, vertex v of B), by construction: m the top corner and
  // v on the facet (A), v the plane's vertex of B and m a corner (B), m an
  // end of the plane's edge of P and v an end of its edge of B (C).
  bool contains(const Piece& piece, Index k, std::uint64_t label) const override;

  // P ⊕ B for polygon g of `cones`' surface (SurfaceCones::polygon: a
  // triangle, or coplanar triangles merged), built from the Gaussian maps
  // of P and B without constructing its vertices: every facet's lazy plane
  // (the candidates' held exactly), the vertex loops of the facets that
  // SurfaceCones::polygon_candidate keeps with their points' labels, and
  // its box.
  Piece sum(const SurfaceCones& cones, Index g) const;
  // Makes, for every point v of `cones`' surface and facet f of B, the
  // doubles of the lazy plane f + v (what sum computes for each polygon
  // at v, each point being shared by several polygons), in parallel;
  // sum then reads them.  Memory: 9 bytes per pair.  Also, when there are
  // at most 2^24 of them, the sign along each facet normal of B of every
  // edge of the surface, which sum needs for both polygons at the edge
  // (1 byte each).
  void prepare(const SurfaceCones& cones, unsigned threads);
  // Frees what prepare made (sum then computes it again).
  void release();
  std::size_t facets() const { return facets_.size(); }
  // on_surface for facet f of B and its normal (true without a surface).
  bool facet_on_surface(Index f) const { return !surface_ || facet_on_surface_[f]; }

 private:
  struct Facet {
    Point3 normal;        // (a, b, c) of the canonical plane
    Vec3d normal_approx;  // nearest doubles
    Integer primitive_integer[3];  // (a, b, c) / gcd(a, b, c)
    long scale;                    // lazy_plane_scale of the primitive normal
    double primitive_approx[3];    // their doubles, scaled by 2^-scale (towards zero)
    bool primitive_usable;         // each usable in the filter
    Integer offset_num, offset_den;  // d / gcd(a, b, c) in lowest terms: primitive . x = offset on the facet
    std::vector<Index> loop;
  };
  struct Edge {
    Index v0, v1;  // the edge's ends
    Index w0, w1;  // a vertex of each adjacent facet off the edge
    Index f0, f1;  // those facets (f0 holds w0)
    Integer direction[3];  // a positive multiple of v1 - v0, primitive
  };
  // Whether the face of B extreme along u, which holds vertex x of B, can
  // hold a point o of O's surface with u in O's local normal cone at o.
  // Such an o lies on a triangle t' of O that lies below the plane through
  // x normal to u (O does near o, and t' is planar) with o in face_u(t'),
  // and SurfaceCones::candidate(t', u) holds: the test keeps every such
  // face (a superset; t' ranges over the triangles whose box meets B's).
  bool on_surface(Index x, const RoundedPoint3& u) const;
  // The vertices of B highest along sign · n_t, n_t the normal of p0 p1 p2
  // (three corners of a polygon, counter-clockwise; na: n_t's nearest
  // doubles), ascending.
  void extreme_face(const RoundedPoint3 p[3], const Vec3d& na, int sign, std::vector<Index>& face) const;
  static void offset_along(const Facet& f, const ScaledPoint& q, Integer work[3]);
  static void lazy_doubles(const Facet& f, const Integer work[3], double& d, bool& filtered);
  static Plane canonical_from_offset(const Facet& f, Integer work[3]);
  RoundedPoint3 at(Index v) const { return RoundedPoint3{points_[v], approx_[v]}; }

  std::vector<Point3> points_;
  std::vector<ScaledPoint> scaled_;  // points_ as integers over a common denominator
  std::vector<Vec3d> approx_;
  std::vector<Facet> facets_;
  std::vector<Edge> edges_;
  std::vector<std::vector<Index>> neighbours_;  // per vertex of B
  Point3 lo_, hi_;  // exact bounding box
  DirectionIndex directions_;  // approximate unit facet normals (Piece::directions)
  const SurfaceCones* surface_ = nullptr;  // O's, when B is a piece of a non-convex O
  std::vector<Index> touching_;            // O's triangles whose exact box meets B's
  std::vector<char> facet_on_surface_;     // on_surface for each facet of B
  const SurfaceCones* prepared_ = nullptr;  // the surface the table is for (prepare)
  std::vector<double> offset_d_;           // [v * facets + f]: the offset's double of f + v
  std::vector<char> offset_ok_;            // and whether the filter may use it
  std::vector<signed char> rise_;          // [e * facets + f]: sign n_f . (q - p) for edge e from p to q (or empty)
  mutable std::vector<signed char> below_;  // [v * facets + f]: SurfaceCones::candidate's memo for n_f (or empty)
};

}  // namespace minksum::nonconvex_detail
