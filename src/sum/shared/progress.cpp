// Report points of the Minkowski-sum methods (SumOptions, minkowski.hpp):
// the caller's cancellation flag, then the caller's progress callback.
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

namespace minksum {

void SumOptions::report(const char* phase, double fraction) const {
  // Relaxed: the flag publishes nothing but itself.
  if (cancel && cancel->load(std::memory_order_relaxed)) throw Cancelled();
  if (progress) progress(phase, fraction);
}

}  // namespace minksum
