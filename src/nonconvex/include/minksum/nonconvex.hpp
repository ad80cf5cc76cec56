// minksum — exact Minkowski sums of non-convex polyhedra (docs/nonconvex.md).
//
// A Solid is a closed polyhedral solid of any genus: a closed, consistently
// oriented, 2-manifold surface without self-intersection whose facets face
// outwards (positive volume).  validate_solid() checks all of it exactly and
// throws InputError(source, place, problem) for the first violation.
//
// minkowski_sum_nonconvex(A, B) computes the exact boundary of A ⊕ B in three
// steps:
//   1. each non-convex operand is cut into convex pieces (CGAL's
//      convex_decomposition_3 on an exact Nef polyhedron: cuts along the
//      planes of the reflex edges); a convex operand is its own single piece;
//   2. every pair of pieces is summed by the walk (<minksum/walk.hpp>), in
//      parallel over the pairs;
//   3. the union of the convex pair sums is taken exactly: each facet of a
//      pair sum is cut by the pair sums that reach over its plane where they
//      meet it, the pieces left are merged into maximal faces, and the
//      boundary is returned as a closed mesh.
// Every decision is an exact predicate; there is no tolerance anywhere.
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/polytope.hpp>
#include <minksum/sum_result.hpp>

#include <cstddef>
#include <optional>
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
  // Exact enclosed volume (> 0).
  Rational volume;
  // The input faces (after welding) and the number of vertices used.
  std::size_t faces = 0, vertices = 0;
  // The solid as a convex polytope when it is one (then sums with it take
  // the convex path); empty for a non-convex solid.
  std::optional<ConvexPolytope> convex;
};

// Validate `mesh` as a closed solid.  Checks, in this order, each failure
// being an InputError naming `source`, the place and the problem: faces of
// at least three distinct vertices, every face exactly planar and a simple
// polygon, every edge shared by exactly two faces traversing it in opposite
// directions (closed, consistently oriented), every vertex a single fan of
// faces (2-manifold), no two faces intersecting other than in their shared
// edges and vertices (exact CGAL self-intersection test), positive volume
// (facets outward).
Solid validate_solid(const Mesh& mesh, const std::string& source);
// A convex polytope as a Solid (no validation needed).
Solid solid_of(const ConvexPolytope& p);

// The exact convex decomposition of a solid: convex polytopes with exact
// coordinates whose union is the solid and whose interiors are disjoint.  A
// convex solid gives itself.
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
  Rational volume;  // exact volume of A ⊕ B
  std::size_t pieces_a = 0, pieces_b = 0;  // convex pieces of A and B
  std::size_t pairs = 0;                   // pair sums computed (pieces_a * pieces_b)
  std::size_t pair_vertices = 0, pair_facets = 0;  // over all pair sums
  std::size_t clips = 0;                   // facets cut by a pair sum that overlaps them (the union's work)
  std::size_t shells = 0;                  // boundary shells (outer ones and cavities)
  std::size_t non_manifold_edges = 0;      // edges of the boundary shared by more than two faces
  // Seconds spent in each step.
  double seconds_decompose = 0, seconds_pairs = 0, seconds_union = 0, seconds_boundary = 0;
  double seconds() const { return seconds_decompose + seconds_pairs + seconds_union + seconds_boundary; }
};

// A ⊕ B for two solids (either or both non-convex).  `threads` (0: all
// hardware threads) sum the pairs of pieces with `method` (any method of
// <minksum/minkowski.hpp>; all give the same exact pair sums); `options`
// reports progress (phases "decompose", "pairs", "union", "boundary";
// fractions for pairs and union) and is checked for cancellation between
// steps.
NonconvexSum minkowski_sum_nonconvex(const Solid& a, const Solid& b, const SumOptions& options = {},
                                     unsigned threads = 0, Method method = Method::walk);

// The reference: A ⊕ B by CGAL's minkowski_sum_3 on the solids' Nef
// polyhedra (Hachenberger's implementation: its own decomposition, pair sums
// and union), its boundary as NonconvexSum::mesh is.  Slow; the oracle of the
// tests and the competitor of bench/nonconvex.  `seconds`, when given,
// receives the time of minkowski_sum_3 alone.
Mesh reference_minkowski_sum(const Solid& a, const Solid& b, double* seconds = nullptr);

// The faces of `mesh` (simple planar polygons, as a NonconvexSum's) cut into
// triangles by exact ear clipping, same orientation, same points; for formats
// that hold triangles only.  Throws InputError(source, face, ...) for a face
// that is not a simple polygon.
Mesh triangulate(const Mesh& mesh, const std::string& source);

// Exact signed volume enclosed by a closed mesh whose faces are planar
// polygons (sum of the signed tetrahedra of the fan of each face).
Rational mesh_volume(const Mesh& mesh);

}  // namespace minksum
