// Welding points by their exact coordinates (internal to the library).
#pragma once

#include <minksum/point_list.hpp>
#include <minksum/polytope.hpp>

#include <vector>

namespace minksum {

// canon[v] = the first point u <= v (in list order) exactly equal to
// point v, for every used point v (every point when `used` is null, else
// those with (*used)[v] != 0); kNoIndex for the unused ones.  A point that
// equals no earlier used point is its own representative.  Points in the
// doubles and double-pairs forms are equal exactly when their bits are
// (zeros are stored unsigned), so they are compared by their bits in an
// open-addressing table; rationals by their exact value.
std::vector<Index> weld_exact(const PointList& points, const std::vector<char>* used = nullptr);

// The welded list: the representatives (canon[v] == v) in list order, and
// id[v] = the number in it of point v's representative (kNoIndex for the
// points weld_exact left unused).  Numbering by first appearance.
struct Welded {
  PointList points;
  std::vector<Index> id;
};
Welded welded(const PointList& points, const std::vector<Index>& canon);

}  // namespace minksum
