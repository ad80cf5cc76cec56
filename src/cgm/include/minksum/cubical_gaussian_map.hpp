// minksum — the Cubical Gaussian Map (Fogel and Halperin 2006, §2) and the Minkowski sum as
// an overlay of six pairs of planar maps (Fogel and Halperin 2006, §3).
//
// The Gaussian map of a convex polytope P sends every facet to its outer
// normal, every edge to the great arc between the normals of its two facets
// and every vertex to the spherical region of the directions it maximises.
// The CGM projects this map centrally onto the six faces of the cube
// [-1,1]^3: six planar maps, each a DCEL of the unit square [-1,1]^2.
//
// Planar maps (Fogel and Halperin 2006, Table 1).  Map k lies in the cube face below, with
// the 2D axes X, Y taken from the 3D coordinates listed; in every map
// X × Y is the outer normal of the cube face, so counter-clockwise in 2D is
// counter-clockwise seen from outside the cube.
//
//    id  plane    X  Y   corner 0 (-1,-1)  1 (-1,1)  2 (1,-1)  3 (1,1) -> next
//    0   x = -1   z  y   (1,0)             (2,2)     (5,0)     (4,2)
//    1   y = -1   x  z   (2,0)             (0,2)     (3,0)     (5,2)
//    2   z = -1   y  x   (0,0)             (1,2)     (4,0)     (3,2)
//    3   x = +1   y  z   (2,1)             (1,3)     (4,1)     (5,3)
//    4   y = +1   z  x   (0,1)             (2,3)     (5,1)     (3,3)
//    5   z = +1   x  y   (1,1)             (0,3)     (3,1)     (4,3)
//
// The corner columns give, for each corner of each map, the (map, corner)
// that follows it in the cyclic chain of the three copies of that cube
// corner, clockwise seen from outside the cube.  Corner ids are
// lexicographic in (X, Y).  (The chains are computed from the geometry in
// cgm/build.cpp and the test suite checks them against this table.)
//
// Every map starts as the artificial unit square (four corner vertices, four
// sides).  A facet normal n becomes a vertex at the exact central projection
// n / |n_k| on every map whose closed square contains it (one map, two on a
// cube edge, three on a cube corner); a polytope edge becomes a chain of at
// most three segments (a segment may lie on a cube edge: it then belongs to
// both maps); a polytope vertex becomes up to five faces.  Coordinates are
// exact rationals; no decision uses a tolerance.
//
// Attributes (Fogel and Halperin 2006, §2):
//   * vertex: 2D point; location (corner / edge / interior of the cube face);
//     `real` (a facet maps to it) with the facet index and its plane
//     coefficients; the polytope edge whose arc passes through it for the
//     artificial vertices where an arc crosses a cube edge; `link` to the
//     copy of the same point on the next map of its cyclic chain (pairs on
//     cube edges, clockwise triplets on cube corners), none in the interior;
//   * halfedge: origin, twin, next, prev, face (on its left), `real` (a
//     polytope edge maps to it) with the polytope halfedge whose arc it is a
//     piece of (the face on its left is the dual of that halfedge's target);
//     `operands` (bit 0: the arc is an edge of the first operand, bit 1: of
//     the second; set for maps of a Minkowski sum, both bits on overlapping
//     edges);
//   * face: one halfedge of its boundary cycle (counter-clockwise for the
//     bounded faces, clockwise for the single unbounded face outside the
//     square) and the primal vertex it is the dual of;
//   * per map: the four corner vertices and the halfedges along each side of
//     the square in counter-clockwise order (the fast boundary traversal).
//
// Invariants (checked by check_invariants()): per map V - E + F = 2 counting
// the unbounded face; every real halfedge of a bounded face names that face's
// primal vertex as the target of its primal halfedge; the boundary cycle of the unbounded face is the square
// (corner vertices at (±1, ±1)); every link chain is a cycle of length 2
// (cube edge) or 3 (cube corner) through copies of the same 3D point.
#pragma once

#include <minksum/sum_result.hpp>
#include <minksum/polytope.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace minksum {

enum class CgmLocation : std::uint8_t { corner, edge, interior };
const char* cgm_location_name(CgmLocation l);

class CubicalGaussianMap {
 public:
  struct VertexRef {
    int map = -1;
    Index vertex = kNoIndex;
    friend bool operator==(const VertexRef&, const VertexRef&) = default;
  };
  struct Vertex {
    Rational x, y;  // 2D coordinates in the map's axes
    CgmLocation location = CgmLocation::interior;
    bool real = false;                // a facet maps here
    Index facet = kNoIndex;           // that facet (of the source polytope)
    Plane plane;                      // its plane (meaningful when real)
    Index arc_edge = kNoIndex;        // artificial vertex on the arc of this polytope edge
    VertexRef link;                   // next copy in the cyclic chain
    Index halfedge = kNoIndex;        // one outgoing halfedge
  };
  struct Halfedge {
    Index origin = kNoIndex, twin = kNoIndex, next = kNoIndex, prev = kNoIndex, face = kNoIndex;
    bool real = false;
    Index primal = kNoIndex;  // polytope halfedge (real halfedges only)
    std::uint8_t operands = 0;
  };
  struct Face {
    Index halfedge = kNoIndex;
    bool unbounded = false;
    Index vertex = kNoIndex;  // primal vertex (bounded faces)
  };
  struct PlanarMap {
    int id = 0;
    std::vector<Vertex> vertices;
    std::vector<Halfedge> halfedges;
    std::vector<Face> faces;
    std::array<Index, 4> corner{};                 // corner vertex ids (lexicographic)
    std::array<std::vector<Index>, 4> side;        // inner halfedges along side s, CCW:
                                                   // 0: Y=-1, 1: X=1, 2: Y=1, 3: X=-1
    Index num_real_vertices() const;
    Index num_real_edges() const;
  };

  CubicalGaussianMap() = default;

  static CubicalGaussianMap from_polytope(const ConvexPolytope& p);
  // The polytope back: one facet per distinct real vertex, its corners the
  // primal vertices of the faces around all its copies.  Exact.
  ConvexPolytope to_polytope() const;

  const PlanarMap& map(int id) const { return maps_[id]; }
  const std::vector<Point3>& primal_points() const { return points_; }
  Index num_facets() const { return num_facets_; }

  // Cube-face geometry of map k: dominant axis, its sign, the 2D axes.
  static int axis(int k) { return k % 3; }
  static int sign(int k) { return k < 3 ? -1 : 1; }
  static int axis_x(int k);
  static int axis_y(int k);
  // The 3D point of the cube surface at (x, y) on map k.
  static Point3 lift(int k, const Rational& x, const Rational& y);
  Point3 lift(int k, Index v) const { return lift(k, maps_[k].vertices[v].x, maps_[k].vertices[v].y); }

  // Copies of vertex v of map k along its chain (itself first).
  std::vector<VertexRef> chain(int k, Index v) const;

  // Empty string when every invariant listed above holds, else the first failure.
  std::string check_invariants() const;

  // Mark every real halfedge with the operand(s) its primal edge comes from,
  // for the CGM of s = a ⊕ b built by minkowski_sum_cgm (vertex_origin of s).
  void set_operands(const std::vector<std::pair<Index, Index>>& vertex_origin, const ConvexPolytope& s);

  // Table-2-style counts of one map: vertices, halfedges, faces (the
  // unbounded face included, as in a DCEL).
  struct Counts {
    Index vertices = 0, halfedges = 0, faces = 0;
  };
  Counts counts(int k) const;

  // The unfolded CGM as SVG: the six squares in a cross, each named by its
  // map id and plane, real edges solid (coloured by operand when set: the
  // first operand P red, the second Q blue, both purple), artificial edges
  // dashed, real vertices dotted (the dots shrink where they crowd: at most
  // a third of the distance between the two closest on a map; where they
  // are closer than 7.5 units, a zoom inset magnifies the map around its
  // closest pair); `title` and `subtitle` above, a legend of the colours
  // below the left arm of the cross.
  std::string to_svg(const std::string& title = "Cubical Gaussian Map", const std::string& subtitle = "") const;

 private:
  friend struct CgmBuilder;
  std::array<PlanarMap, 6> maps_;
  std::vector<Point3> points_;  // primal vertices
  std::vector<Index> primal_target_;  // target vertex of each primal halfedge
  Index num_facets_ = 0;
};

// The sum by overlaying the six pairs of planar maps of the two CGMs.
// Counters name the overlay cases met (see docs/cgm.md).  Reports phase
// "cgm" to options before each pair of maps and before the assembly
// (SumOptions, sum_result.hpp).
SumResult minkowski_sum_cgm(const CubicalGaussianMap& a, const CubicalGaussianMap& b, const ConvexPolytope& pa,
                            const ConvexPolytope& pb, const SumOptions& options = {});
// The Cubical Gaussian Map method (Fogel and Halperin 2006, §2-3): builds the two CGMs, then
// the overlay above.  minkowski_sum(a, b, Method::cgm) calls it.
SumResult minkowski_sum_cgm(const ConvexPolytope& a, const ConvexPolytope& b, const SumOptions& options = {});

}  // namespace minksum
