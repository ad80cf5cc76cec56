// minksum — independent jobs on a pool of threads (<minksum/parallel.hpp>).
#include <minksum/parallel.hpp>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace minksum {

namespace {
// True on a thread while it runs a job of parallel_for.
thread_local bool t_in_job = false;
}  // namespace

unsigned parallel_threads(unsigned threads, std::size_t n) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, n)));
}

void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& job) {
  const unsigned t = t_in_job ? 1 : parallel_threads(threads, n);
  if (t == 1) {
    for (std::size_t i = 0; i < n; ++i) job(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> stop{n};  // no job at or after this index starts
  std::mutex m;
  std::size_t failed_at = n;
  std::exception_ptr failure;
  auto work = [&] {
    const bool was_in_job = t_in_job;
    t_in_job = true;
    struct Restore {
      bool value;
      ~Restore() { t_in_job = value; }
    } restore{was_in_job};
    for (;;) {
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= n || i >= stop.load(std::memory_order_relaxed)) return;
      try {
        job(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
          std::size_t s = stop.load();
          while (i < s && !stop.compare_exchange_weak(s, i)) {
          }
        }
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(t - 1);
  try {
    for (unsigned k = 1; k < t; ++k) pool.emplace_back(work);
  } catch (...) {  // no more threads: the ones started and this one share the jobs
  }
  work();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace minksum
