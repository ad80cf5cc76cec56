// minksum — independent jobs on a pool of threads (<minksum/parallel.hpp>).
//
// The threads are started once, on the first parallel_for that needs them,
// and then wait for work: a loop of a few milliseconds (validating a mesh
// of some thousands of facets, formatting a file) must not pay for starting
// and joining threads each time.  One loop at a time uses the pool; a loop
// started while another holds it (two threads of the application calling
// minksum at once) starts its own threads, as if there were no pool.
//
// Protocol.  The caller publishes its loop (under the pool's mutex), wakes
// the workers and takes jobs itself.  A worker joins the loop only while it
// is open and fewer workers than the caller asked for have joined; it takes
// jobs until none is left, then leaves.  When the caller runs out of jobs it
// closes the loop and waits for the workers that joined to leave: it never
// waits for a worker that has not joined, so a worker that is slow to wake
// (or absent: in a child process after fork, the pool's threads do not
// exist) costs nothing but its share of the jobs, which the caller does.
#include <minksum/parallel.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace minksum {

namespace {
// True on a thread while it runs a job of parallel_for.
thread_local bool t_in_job = false;

// One loop: the jobs, the next index to hand out, where to stop, and the
// first failure in index order.
struct Loop {
  std::size_t n = 0;
  const std::function<void(std::size_t)>* job = nullptr;
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> stop{0};  // no job at or after this index starts
  std::mutex m;
  std::size_t failed_at = 0;
  std::exception_ptr failure;

  Loop(std::size_t jobs, const std::function<void(std::size_t)>& j) : n(jobs), job(&j), stop(jobs), failed_at(jobs) {}

  // Takes jobs until none is left.
  void work() {
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
        (*job)(i);
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
  }
};

// The pool: workers waiting for a loop.  Never destroyed (its threads wait
// on it until the process ends), made anew in a child process after fork.
class Pool {
 public:
  // Runs `loop` on the calling thread and up to `helpers` pool threads;
  // false (nothing run) when another loop holds the pool.
  bool run(Loop& loop, unsigned helpers) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(m_);
      while (threads_ < helpers) {
        try {
          std::thread(&Pool::worker, this, generation_).detach();  // (joins the loop below)
        } catch (...) {  // no more threads: the ones there share the jobs
          break;
        }
        ++threads_;
      }
      loop_ = &loop;
      wanted_ = helpers;
      joined_ = 0;
      active_ = 0;
      ++generation_;
    }
    wake_.notify_all();
    loop.work();
    std::unique_lock<std::mutex> lock(m_);
    loop_ = nullptr;  // closed: no worker joins any more
    left_.wait(lock, [&] { return active_ == 0; });
    return true;
  }

 private:
  // `seen`: the last generation before the thread started.
  void worker(std::uint64_t seen) {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (!loop_ || joined_ >= wanted_) continue;
      Loop* loop = loop_;
      ++joined_;
      ++active_;
      lock.unlock();
      loop->work();
      lock.lock();
      if (--active_ == 0) left_.notify_all();
    }
  }

  std::mutex busy_;  // held by the loop using the pool
  std::mutex m_;
  std::condition_variable wake_, left_;
  unsigned threads_ = 0;
  Loop* loop_ = nullptr;
  unsigned wanted_ = 0, joined_ = 0, active_ = 0;
  std::uint64_t generation_ = 0;
};

Pool& pool() {
  static std::mutex m;
  static Pool* p = nullptr;
  static pid_t owner = 0;
  std::lock_guard<std::mutex> lock(m);
  if (!p || owner != getpid()) {  // (after fork, the parent's threads are not here)
    p = new Pool;
    owner = getpid();
  }
  return *p;
}
}  // namespace

unsigned hardware_threads() {
  // (std::thread::hardware_concurrency reads /sys on every call in a static
  // glibc: once is enough.)
  static const unsigned n = std::max(1u, std::thread::hardware_concurrency());
  return n;
}

namespace {
std::atomic<std::size_t> g_parallel_items{kParallelItems};
}  // namespace

std::size_t parallel_items() { return g_parallel_items.load(std::memory_order_relaxed); }

void set_parallel_items(std::size_t items) {
  g_parallel_items.store(std::max<std::size_t>(1, items), std::memory_order_relaxed);
}

unsigned parallel_threads(unsigned threads, std::size_t n) {
  if (threads == 0) threads = hardware_threads();
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, n)));
}

void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& job) {
  const unsigned t = t_in_job ? 1 : parallel_threads(threads, n);
  if (t == 1) {
    for (std::size_t i = 0; i < n; ++i) job(i);
    return;
  }
  Loop loop(n, job);
  if (!pool().run(loop, t - 1)) {
    // The pool is in use by another loop: threads of this loop's own.
    std::vector<std::thread> own;
    own.reserve(t - 1);
    try {
      for (unsigned k = 1; k < t; ++k) own.emplace_back([&loop] { loop.work(); });
    } catch (...) {  // no more threads: the ones started and this one share the jobs
    }
    loop.work();
    for (auto& th : own) th.join();
  }
  if (loop.failure) std::rethrow_exception(loop.failure);
}

}  // namespace minksum
