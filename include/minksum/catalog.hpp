// minksum — the built-in database of named polytopes.
//
// A catalog spec is accepted anywhere a file path is.  Grammar:
//   spec     := base ( '@' transform )*
//   base     := tetra | cube | octahedron | dodecahedron | icosahedron
//             | truncated-cube | ... (see catalog_entries())
//             | sphere:L | dioctagonal:N | random:N:SEED | zonotope:N:SEED
//             | box:X:Y:Z
//   transform:= rot:SEED          a pseudo-random exact rational rotation
//             | rot:A,B,C,D       the rotation of the integer quaternion (A,B,C,D)
//             | ... (see catalog_entries())
// Every catalog polytope has exact coordinates and exactly planar facets;
// where a solid needs an irrational constant, the rational approximation used
// is documented in catalog_entries() and docs/catalog.md.
#pragma once

#include <minksum/polytope.hpp>

#include <string>
#include <vector>

namespace minksum {

struct CatalogEntry {
  std::string syntax;       // e.g. "sphere:L"
  std::string description;  // one line, for --help and docs
};

// All names and parameterised forms the catalog understands.
const std::vector<CatalogEntry>& catalog_entries();

// True if `spec` parses as a catalog spec (parameters not yet range-checked).
bool is_catalog_spec(const std::string& spec);

// Build the polytope named by `spec`.  Throws UsageError for an unknown name
// or a bad/out-of-range parameter (message says which and the allowed range).
ConvexPolytope catalog_polytope(const std::string& spec);

}  // namespace minksum
