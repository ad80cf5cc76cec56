// Report points of the Minkowski-sum methods (SumOptions, sum_result.hpp):
// the caller's cancellation flag, then the caller's progress callback.
#include <minksum/error.hpp>
#include <minksum/sum_result.hpp>

namespace minksum {

void SumOptions::report(const char* phase, double fraction) const {
  // Relaxed: the flag publishes nothing but itself.
  if (cancel && cancel->load(std::memory_order_relaxed)) throw Cancelled();
  if (progress) progress(phase, fraction);
}

}  // namespace minksum
