// Internal to src/nonconvex/: an order of work by position, for locality.
#pragma once

#include <minksum/kernel.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace minksum::nonconvex_detail {

// The indices of `at` in the Morton order of the points within their
// bounding box (21 bits a coordinate; a coordinate that is not finite counts
// as the box's low end), ties by index.  Points near each other in space are
// mostly near each other in this order: work done in it finds its data in
// the cache.  It decides the time only, never a result.
inline std::vector<std::size_t> morton_order(const std::vector<Vec3d>& at) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const Vec3d& p : at)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  std::vector<std::pair<std::uint64_t, std::size_t>> code(at.size());
  for (std::size_t k = 0; k < at.size(); ++k) {
    std::uint32_t cell[3];
    for (int i = 0; i < 3; ++i) {
      const double span = hi[i] - lo[i];
      double t = span > 0 && std::isfinite(span) ? (at[k][i] - lo[i]) / span : 0.0;
      if (!(t > 0)) t = 0;  // (also NaN)
      if (t > 1) t = 1;
      cell[i] = std::uint32_t(t * 2097151.0);
    }
    std::uint64_t c = 0;
    for (int b = 20; b >= 0; --b)
      for (int i = 0; i < 3; ++i) c = (c << 1) | ((cell[i] >> b) & 1u);
    code[k] = {c, k};
  }
  std::sort(code.begin(), code.end());
  std::vector<std::size_t> order(at.size());
  for (std::size_t k = 0; k < at.size(); ++k) order[k] = code[k].second;
  return order;
}

}  // namespace minksum::nonconvex_detail
