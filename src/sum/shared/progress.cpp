// Progress of the running Minkowski sum (see minkowski.hpp): two atomics, so
// a display thread can poll them while a method runs.
#include <minksum/minkowski.hpp>

#include <atomic>

namespace minksum {

namespace {
std::atomic<const char*> g_phase{nullptr};
std::atomic<double> g_fraction{-1.0};
}  // namespace

void report_sum_progress(const char* phase, double fraction) {
  g_fraction.store(fraction, std::memory_order_relaxed);
  g_phase.store(phase, std::memory_order_release);
}

SumProgress sum_progress() {
  SumProgress p;
  const char* phase = g_phase.load(std::memory_order_acquire);
  if (phase) p.phase = phase;
  p.fraction = g_fraction.load(std::memory_order_relaxed);
  return p;
}

}  // namespace minksum
