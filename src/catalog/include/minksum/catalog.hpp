// minksum — the built-in database of named polytopes (docs/catalog.md).
//
// A catalog spec is accepted anywhere a file path is.  Grammar:
//   spec     := base ( '@' transform )*
//   base     := NAME               a fixed solid: the 5 Platonic, 13 Archimedean
//                                  and 13 Catalan solids (tetra, cube, ...,
//                                  truncated-cube, ...; see catalog_entries())
//             | sphere:L           geodesic sphere, 1 <= L <= 9 (L = 1: icosahedron)
//             | dioctagonal:N      squashed pyramid with N facets, 4 <= N <= 100000
//             | random:N:SEED      exact hull of N random unit vectors, 4 <= N <= 10^6
//             | zonotope:N:SEED    N random generators in general position, 3 <= N <= 256
//             | zonotope:X,Y,Z:... 1..16 explicit generators
//             | box:X:Y:Z          axis-aligned box with sides X, Y, Z > 0
//             | ball:N             latitude/longitude ball, N bands, 2N meridians, 2 <= N <= 1000
//             | prism:N            prism over the regular N-gon (a cylinder), 3 <= N <= 100000
//             | tube | tube:H | lshape | ring:N | star:N | gear:N
//                                  non-convex solids (catalog_mesh only)
//             | point:X,Y,Z        lower-dimensional sets (docs/sweeps.md):
//             | segment:X,Y,Z:X,Y,Z  a point, a segment (distinct ends),
//             | polygon:N | square   a regular N-gon or the unit square at z=0
//   transform:= rot:SEED           a pseudo-random exact rational rotation
//             | rot:A,B,C,D        the rotation of the integer quaternion (A,B,C,D)
//             | scale:S | scale:X,Y,Z | translate:X,Y,Z | neg
// Counts and seeds are integers (a seed is 0 .. 2^64-1); lengths and
// coordinates are read exactly by parse_number ("1/3", "1e-12").  Transforms
// apply left to right.  A spec gives the same polytope (coordinates, vertex
// order, facet loops) on every run and platform.
// Every catalog polytope has exact coordinates and exactly planar facets;
// where a solid needs an irrational constant, the rational approximation used
// is documented in catalog_entries() and docs/catalog.md.
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/polytope.hpp>

#include <string>
#include <vector>

namespace minksum {

struct CatalogEntry {
  std::string syntax;       // e.g. "sphere:L"
  std::string description;  // one line, for --help and docs
};

// All names and parameterised forms of solids the catalog understands, and
// its transforms.
const std::vector<CatalogEntry>& catalog_entries();
// The lower-dimensional sets (point, segment, polygon, square): not solids,
// listed apart so that every name of catalog_entries() is a polytope.
const std::vector<CatalogEntry>& flat_catalog_entries();
// The non-convex solids of the catalog (catalog_mesh), the same way.
const std::vector<CatalogEntry>& nonconvex_catalog_entries();

// True if `spec` names the catalog: its base name (the text before the first
// ':' or '@') is a catalog name.  Parameters and transforms are not checked
// here: catalog_polytope() rejects a bad one with a UsageError saying what is
// allowed ("sphere:12" is a catalog spec, not a missing file).  Paths such as
// "foo.off" or "./cube" are never catalog specs.
bool is_catalog_spec(const std::string& spec);

// True if `spec`'s base name is one of the catalog's non-convex solids
// (nonconvex_catalog_entries: catalog_mesh gives them, catalog_polytope
// refuses them).  Parameters and transforms are not checked here.
bool is_nonconvex_catalog_spec(const std::string& spec);

// The catalog name closest to the base name of `spec` (within two edits, else
// a name that the text begins), or "" when none is close: the "did you mean"
// of error messages.
std::string closest_catalog_name(const std::string& spec);

// Build the polytope named by `spec`.  Throws UsageError for an unknown name
// or a bad/out-of-range parameter (message says which and the allowed range).
// Non-convex solids (tube, lshape, ring:N, star:N, gear:N) are refused with
// a NotConvexError: catalog_mesh() gives them.  A point, segment or polygon
// spec is refused here (UsageError saying so).
ConvexPolytope catalog_polytope(const std::string& spec);

// The mesh named by `spec`, not validated: a convex polytope's facets, or a
// non-convex solid's faces (polygons, counter-clockwise from outside), with
// the transforms applied.  Throws UsageError like catalog_polytope().
Mesh catalog_mesh(const std::string& spec);

// Apply the transforms `transforms` (the text after a file name's '@':
// "rot:1@neg", the syntax above) to `mesh` in order, for an operand
// "FILE@TRANSFORM@...".  Throws UsageError naming `spec` for a bad transform,
// before changing the mesh.
void apply_transforms(Mesh& mesh, const std::string& spec, const std::string& transforms);

// Build the convex set named by `spec`: a point, a segment or a polygon for
// those names (transforms applied to their points), else the polytope of
// catalog_polytope().
ConvexSet catalog_convex_set(const std::string& spec);

}  // namespace minksum
