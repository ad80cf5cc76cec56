// The quaternion of the rot:SEED transform (the rotation itself: <minksum/transform.hpp>).
#include "catalog/catalog_internal.hpp"

namespace minksum::catalog_detail {

std::array<Integer, 4> random_quaternion(std::uint64_t seed) {
  SplitMix64 rng = make_rng(seed, kStreamRotation);
  for (;;) {
    std::int64_t q[4];
    std::int64_t norm2 = 0;
    for (auto& x : q) {
      x = rng.uniform_int(-100, 100);
      norm2 += x * x;
    }
    if (norm2 >= 50 * 50 && norm2 <= 100 * 100)
      return {Integer(static_cast<long>(q[0])), Integer(static_cast<long>(q[1])),
              Integer(static_cast<long>(q[2])), Integer(static_cast<long>(q[3]))};
  }
}

}  // namespace minksum::catalog_detail
