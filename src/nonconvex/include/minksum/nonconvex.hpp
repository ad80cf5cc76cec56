// minksum — exact Minkowski sums of non-convex polyhedra (docs/nonconvex.md).
//
// A Solid is a closed polyhedral solid of any genus: a closed, consistently
// oriented, 2-manifold surface without self-intersection whose facets face
// outwards (positive volume).  validate_solid() checks all of it exactly and
// throws InputError(source, place, problem) for the first violation.
//
// minkowski_sum_nonconvex(A, B) computes the exact boundary of A ⊕ B by the
// boundary sweep (docs/nonconvex.md, "Method"):
//   1. A ⊕ B = (A + b) ∪ ⋃ (t ⊕ B_j) over the triangles t of the surface of
//      the non-convex operand A and the convex pieces B_j of B (B itself when
//      convex), b a point inside B; every piece t ⊕ B_j is summed by the walk,
//      in parallel;
//   2. only the facets of the pieces whose normal lies in the local normal
//      cone of A at the feature of t they come from can hold points of the
//      boundary: the others are culled (they still cut);
//   3. the union of the pieces is taken exactly over the remaining facets:
//      each is cut by the pieces that reach over its plane where they meet
//      it, the pieces left are merged into maximal faces, the parts of that
//      boundary inside A + b are dropped, and the boundary is returned as a
//      closed mesh.
// Hachenberger's method (both operands cut into convex pieces by CGAL's
// convex_decomposition_3, every pair summed, the same union) is kept as
// NonconvexMethod::decomposition.
// Every decision is an exact predicate; there is no tolerance anywhere.
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/polytope.hpp>
#include <minksum/sum_result.hpp>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace minksum {

// A validated closed solid.
struct Solid {
  // The surface as triangles, counter-clockwise seen from outside: exactly
  // equal input vertices welded, unused ones dropped, each planar polygon of
  // the input triangulated (ear clipping, exact).
  Mesh triangles;
  // For each triangle, the face of the input mesh it comes from.
  std::vector<Index> source_face;
  // Exact enclosed volume (> 0; its opposite for a complement).  The sums
  // do not read it: the first step of an opening or a closing, swept by the
  // second, is a Solid of volume 0 (not computed).
  Rational volume;
  // The input faces (after welding) and the number of vertices used.
  std::size_t faces = 0, vertices = 0;
  // The solid as a convex polytope when it is one (then sums with it take
  // the convex path); empty for a non-convex solid.
  std::optional<ConvexPolytope> convex;
  // True for the closure of the complement of a solid, an unbounded set that
  // erosion sweeps (A ⊖ B is the complement of Aᶜ ⊕ (−B)): `triangles` is
  // then the solid's surface reversed, facing into the solid.  validate_solid
  // and solid_of never make one.
  bool complement = false;
};

// Validate `mesh` as a closed solid.  Checks, in this order, each failure
// being an InputError naming `source`, the place and the problem: faces of
// at least three distinct vertices, every face exactly planar and a simple
// polygon, every edge shared by exactly two faces traversing it in opposite
// directions (closed, consistently oriented), every vertex a single fan of
// faces (2-manifold), no two faces intersecting other than in their shared
// edges and vertices (exact CGAL self-intersection test), every shell
// oriented as its nesting depth requires (outer boundaries and islands
// outwards, cavities inwards; one shell: positive volume).
Solid validate_solid(const Mesh& mesh, const std::string& source);

// The solid's faces as polygons again (Solid keeps its triangles): every face
// of the input (welded, as validated) one loop, counter-clockwise seen from
// outside, over the points of s.triangles.
Mesh solid_faces(const Solid& s);

// What `minksum stats` reports of a solid, from its faces (solid_faces): the
// counts, the shells (connected components of the surface; a cavity is
// one), the genus (the sum of the shells' genera, by Euler's formula: a
// torus has 1) and the exact bounding box.
struct SolidStats {
  std::size_t vertices = 0, edges = 0, facets = 0;
  std::size_t shells = 0;
  std::size_t genus = 0;
  Point3 min, max;
};
SolidStats solid_stats(const Mesh& faces);
// A convex polytope as a Solid (no validation needed).  Without
// `with_volume` its volume is left 0 (not computed), as the sums, which do
// not read it, ask.
Solid solid_of(const ConvexPolytope& p, bool with_volume = true);

// The exact convex decomposition of a solid (CGAL's convex_decomposition_3
// on its Nef polyhedron: cuts along the planes of the reflex edges, O(r^2)
// pieces for r reflex edges): convex polytopes with exact coordinates whose
// union is the solid and whose interiors are disjoint.  A convex solid gives
// itself.
std::vector<ConvexPolytope> convex_decomposition(const Solid& s);

// The boundary of A ⊕ B and what computing it took.
struct NonconvexSum {
  // The boundary: polygons (exactly planar; facets of the union are maximal
  // planar regions, a facet with a hole is triangulated), counter-clockwise
  // seen from outside, exact coordinates.  Cavities are kept as inner
  // shells facing into the cavity.  Non-manifold contacts are kept as they
  // are: an edge where the solid touches itself belongs to four faces, a
  // vertex where it touches itself to several fans (docs/nonconvex.md).
  Mesh mesh;
  Rational volume;  // exact volume of A ⊕ B (0 when SumOptions::volume is false)
  // The boundary as a convex polytope when the last step built one (the
  // erosion, opening or closing of a convex A: the half-space intersection
  // and the convex path), its facets `mesh`'s faces: written as a convex
  // polytope is (writable_polytope); empty otherwise.
  std::optional<ConvexPolytope> convex;
  // The method (NonconvexMethod) and, for the boundary sweep, which operand's
  // surface was swept ('a' or 'b'; 0 for the decomposition).
  const char* method = "sweep";
  char swept = 0;
  Method pair_method = Method::walk;       // the method that summed the convex pieces
  // Sweep: the pieces P ⊕ O_j built from the Gaussian maps of P and O_j, P
  // a convex polygon of the swept surface (pair_method is then not used;
  // false with --method chms, the pairwise hull of each triangle's sums).
  bool pieces_from_maps = false;
  // Decomposition: the convex pieces of A and B.  Sweep: the convex
  // polygons of the swept operand's surface (its triangles, coplanar ones
  // merged; with --method chms its triangles) and the convex pieces of the
  // other.
  std::size_t pieces_a = 0, pieces_b = 0;
  std::size_t pairs = 0;                   // convex pieces summed (pieces_a * pieces_b)
  // Facets of those sums that can lie on the boundary (the union's input)
  // and facets culled as unable to (the sweep's normal-cone test; 0 for the
  // decomposition).
  std::size_t candidate_facets = 0, culled_facets = 0;
  std::size_t dropped_components = 0;      // parts of the sweep's boundary inside A + b, dropped
  // Over all pair sums; pair_vertices is counted by the decomposition only
  // (the sweep's pieces are built from their planes, without their vertices).
  std::size_t pair_vertices = 0, pair_facets = 0;
  std::size_t clips = 0;                   // facets cut by a pair sum that overlaps them (the union's work)
  std::size_t shells = 0;                  // boundary shells (outer ones and cavities)
  std::size_t non_manifold_edges = 0;      // edges of the boundary shared by more than two faces
  // "sum", or "erosion", "opening", "closing" (erode, opening, closing: the
  // counts and seconds are then those of all their steps together).
  const char* operation = "sum";
  // Seconds spent in each step.
  double seconds_decompose = 0, seconds_pairs = 0, seconds_union = 0, seconds_boundary = 0;
  double seconds() const { return seconds_decompose + seconds_pairs + seconds_union + seconds_boundary; }
};

// How A ⊕ B is computed (docs/nonconvex.md, "Method"); both give the same
// exact boundary.
enum class NonconvexMethod {
  // The boundary sweep: A ⊕ B = (A + b) ∪ ⋃ (t ⊕ B_j) over the triangles t
  // of A's surface and the convex pieces B_j of B (b inside B); only the
  // facets whose normal is in the local normal cone of A are candidates,
  // and the parts of the union's boundary inside A + b are dropped.  The
  // swept operand is the non-convex one (of two non-convex ones, the one with
  // more triangles; the other is decomposed).
  sweep,
  // Hachenberger's method: both operands cut into convex pieces (CGAL's
  // convex_decomposition_3), every pair summed, the union of the pair sums.
  decomposition,
};

// A ⊕ B for two solids (either or both non-convex).  `threads` (0: all
// hardware threads) sum the pieces with `method` (any method of
// <minksum/minkowski.hpp> for the decomposition's pairs of polytopes; the
// sweep's pieces t ⊕ B_j, a triangle and a polytope, by walk or chms, and
// by walk for the other methods); `options` reports progress (phases
// "decompose", "pairs", "union", "boundary"; fractions for pairs and union)
// and is checked for cancellation between steps.
NonconvexSum minkowski_sum_nonconvex(const Solid& a, const Solid& b, const SumOptions& options = {},
                                     unsigned threads = 0, Method method = Method::walk,
                                     NonconvexMethod how = NonconvexMethod::sweep);

// Erosion, opening and closing of a solid A (convex or not, any genus, any
// number of shells) by a convex polytope B (docs/nonconvex.md, "Erosion,
// opening, closing"), exactly, as NonconvexSum's boundary (closed, outward,
// exact coordinates, several parts as several shells of one solid):
//   erode(A, B)   = A ⊖ B = {x : x + B ⊆ A}, regularised (the closure of
//                   its interior), computed as the complement of
//                   Aᶜ ⊕ (−B) by the boundary sweep of Aᶜ's surface;
//   opening(A, B) = (A ⊖ B) ⊕ B, the union of the translates of B inside A
//                   (rounds A's convex edges and corners);
//   closing(A, B) = (A ⊕ B) ⊖ B (fills its concave ones).
// An empty result (B fits nowhere inside A) is an empty mesh with volume 0,
// not an error.  threads, method and options as minkowski_sum_nonconvex's
// (progress reports the phases of each step in turn).  Throws
// std::invalid_argument when B is not convex.
NonconvexSum erode(const Solid& a, const Solid& b, const SumOptions& options = {}, unsigned threads = 0,
                   Method method = Method::walk);
NonconvexSum opening(const Solid& a, const Solid& b, const SumOptions& options = {}, unsigned threads = 0,
                     Method method = Method::walk);
NonconvexSum closing(const Solid& a, const Solid& b, const SumOptions& options = {}, unsigned threads = 0,
                     Method method = Method::walk);

// The reference: A ⊕ B by CGAL's minkowski_sum_3 on the solids' Nef
// polyhedra (Hachenberger's implementation: its own decomposition, pair sums
// and union), its boundary as NonconvexSum::mesh is.  Slow; the oracle of the
// tests and the competitor of bench/nonconvex.  `seconds`, when given,
// receives the time of minkowski_sum_3 alone.
Mesh reference_minkowski_sum(const Solid& a, const Solid& b, double* seconds = nullptr);

// The reference erosion: A ⊖ B for a convex B by CGAL's Nef polyhedra,
// through complements: A minus minkowski_sum_3(K − A, −B) for a box K
// around A ⊕ B, regularised; its boundary as NonconvexSum::mesh is (empty
// when the erosion is).  Slow; the oracle of the tests and the competitor
// of bench/nonconvex.  `seconds` receives the time of minkowski_sum_3 and
// the difference.
Mesh reference_erosion(const Solid& a, const Solid& b, double* seconds = nullptr);

// The faces of `mesh` (simple planar polygons, as a NonconvexSum's) cut into
// triangles by exact ear clipping, same orientation, same points; for formats
// that hold triangles only.  Throws InputError(source, face, ...) for a face
// that is not a simple polygon.
Mesh triangulate(const Mesh& mesh, const std::string& source);

// A solid boundary in the numbers of a file format: every coordinate a double
// (or a 32-bit float), the surface a valid solid (validate_solid passes).
struct RoundedSolid {
  // Triangles; the exact mesh itself when nothing was rounded and the
  // surface does not touch itself (else the surface cut apart where it
  // does, even when rounded_coordinates is 0).
  Mesh mesh;
  std::size_t rounded_coordinates = 0;  // coordinates that were not doubles (floats)
  double max_displacement = 0;          // the largest distance a point moved (rounded up to a double)
  double grid = 0;                      // 0: no point snapped to a grid; else the coarsest grid points were snapped to
};

// round_solid could not represent the solid: a coordinate beyond the range of
// the format's numbers, a solid below it (every coordinate rounds to zero, or
// every face degenerates), or no valid rounding up to a grid of 2^-20 of the
// largest coordinate.
class RoundingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `exact` (a NonconvexSum's mesh: planar polygons, a closed solid, possibly
// touching itself along edges or at vertices) with every coordinate that is
// not a double (with `floats`, a 32-bit float) rounded, as a valid solid
// (docs/nonconvex.md, "Output"): the faces cut into triangles exactly; where
// the surface touches itself, cut apart, each part's copy of the contact
// moved a few spacings into that part; the coordinates rounded to the
// nearest, points that round together merged, the triangles that became
// degenerate removed (the surface kept closed).  When that is not a valid
// solid, it is repaired locally and re-tested exactly, round after round:
// triangles that rounding made meet across a gap are pushed apart into the
// solid, points of different parts merged into one are pushed apart along
// their exact offsets, and the points of any other offending triangles are
// snapped together to a coarser grid; failing that (problems multiplying),
// the same on every point first snapped to a grid of 2^e, e from the
// format's spacing at the largest coordinate up to 2^-20 of it.  The result
// passes validate_solid.  Throws RoundingError.
RoundedSolid round_solid(const Mesh& exact, bool floats, const std::string& name);

// Exact signed volume enclosed by a closed mesh whose faces are planar
// polygons (sum of the signed tetrahedra of the fan of each face).
Rational mesh_volume(const Mesh& mesh);

}  // namespace minksum
