// parallel_for (<minksum/parallel.hpp>): every job once, the thread count as
// documented, the first failure in index order rethrown, sums on several
// threads equal to the same sums on one, and the pool: threads reused, loops
// from two threads at once, a forked child.
#include <gtest/gtest.h>

#include <minksum/catalog.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/parallel.hpp>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

using namespace minksum;

TEST(Parallel, EveryJobExactlyOnce) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<std::atomic<int>> count(1000);
    parallel_for(count.size(), threads, [&](std::size_t i) { ++count[i]; });
    for (std::size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i].load(), 1) << "threads " << threads << " job " << i;
  }
  parallel_for(0, 4, [](std::size_t) { FAIL() << "no job to run"; });
}

TEST(Parallel, ThreadCount) {
  EXPECT_EQ(parallel_threads(4, 2), 2u);  // never more threads than jobs
  EXPECT_EQ(parallel_threads(4, 0), 1u);
  EXPECT_EQ(parallel_threads(3, 100), 3u);
  EXPECT_EQ(parallel_threads(0, 1000), std::max(1u, std::thread::hardware_concurrency()));
  // One thread: the jobs run on the calling thread.
  const auto self = std::this_thread::get_id();
  parallel_for(5, 1, [&](std::size_t) { EXPECT_EQ(std::this_thread::get_id(), self); });
  // Several: on that many distinct threads (each job waits until all have started one).
  std::mutex m;
  std::set<std::thread::id> ids;
  std::atomic<int> started{0};
  parallel_for(3, 3, [&](std::size_t) {
    {
      std::lock_guard<std::mutex> lock(m);
      ids.insert(std::this_thread::get_id());
    }
    ++started;
    while (started.load() < 3) std::this_thread::yield();
  });
  EXPECT_EQ(ids.size(), 3u);
}

TEST(Parallel, FirstFailureInIndexOrderIsRethrown) {
  for (unsigned threads : {1u, 2u, 4u}) {
    try {
      parallel_for(200, threads, [](std::size_t i) {
        if (i == 37 || i == 150) throw std::runtime_error("job " + std::to_string(i));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "job 37") << "threads " << threads;
    }
  }
}

TEST(Parallel, SumsOnTwoThreadsEqualSumsOnOne) {
  const char* specs[] = {"cube", "sphere:2@rot:3", "random:80:4", "truncated-cube"};
  std::vector<std::pair<ConvexPolytope, ConvexPolytope>> pairs;
  for (const char* a : specs)
    for (const char* b : specs) pairs.emplace_back(catalog_polytope(a), catalog_polytope(b));
  auto run = [&](unsigned threads) {
    std::vector<std::vector<Point3>> out(pairs.size());
    parallel_for(pairs.size(), threads, [&](std::size_t i) {
      out[i] = minkowski_sum(pairs[i].first, pairs[i].second).polytope.coordinates().to_points();
    });
    return out;
  };
  EXPECT_EQ(run(1), run(2));
}

// A parallel_for inside a job runs its jobs on that job's thread, in order.
TEST(Parallel, NestedLoopRunsOnTheJobsThread) {
  std::atomic<int> inner_elsewhere{0}, out_of_order{0};
  parallel_for(4, 2, [&](std::size_t) {
    const std::thread::id me = std::this_thread::get_id();
    std::size_t next = 0;
    parallel_for(8, 4, [&](std::size_t j) {  // (jobs long enough for other threads to take some)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      if (std::this_thread::get_id() != me) ++inner_elsewhere;
      if (j != next++) ++out_of_order;
    });
  });
  EXPECT_EQ(inner_elsewhere.load(), 0);
  EXPECT_EQ(out_of_order.load(), 0);
  // Outside any job, the loop starts its threads again: two jobs that each
  // wait for the other to start finish only on two threads.
  std::atomic<int> started{0};
  std::atomic<int> met{0};
  parallel_for(2, 2, [&](std::size_t) {
    ++started;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (started.load() < 2 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (started.load() == 2) ++met;
  });
  EXPECT_EQ(met.load(), 2);
}

// The threads are started once and reused: twenty loops that each need a
// helper (two jobs waiting for each other) run on a few kernel threads, at
// most as many as the largest loop of this process asked for (seven), where
// threads started per loop would be twenty distinct ones.
TEST(Parallel, PoolThreadsAreReused) {
  std::mutex m;
  std::set<pid_t> helpers;
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> started{0};
    parallel_for(2, 2, [&](std::size_t) {
      ++started;
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (started.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
      std::lock_guard<std::mutex> lock(m);
      if (gettid() != getpid()) helpers.insert(gettid());
    });
    ASSERT_EQ(started.load(), 2);
  }
  EXPECT_GE(helpers.size(), 1u);
  EXPECT_LE(helpers.size(), 7u);
}

// Two threads of an application running loops at the same time: one uses
// the pool, the other its own threads; every job of each runs once.
TEST(Parallel, ConcurrentLoopsFromTwoThreads) {
  std::vector<std::atomic<int>> a(20000), b(20000);
  auto loops = [](std::vector<std::atomic<int>>& count) {
    for (std::size_t round = 0; round < 200; ++round)
      parallel_for(100, 2, [&](std::size_t i) { ++count[round * 100 + i]; });
  };
  std::thread other([&] { loops(b); });
  loops(a);
  other.join();
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].load(), 1) << i;
    ASSERT_EQ(b[i].load(), 1) << i;
  }
}

// A child process forked after the pool has started has none of its
// threads: its loops start a pool of their own and finish.
TEST(Parallel, ForkedChildRunsItsLoops) {
  std::atomic<int> warm{0};
  parallel_for(4, 2, [&](std::size_t) { ++warm; });
  ASSERT_EQ(warm.load(), 4);
  const pid_t child = fork();
  ASSERT_NE(child, -1);
  if (child == 0) {
    std::vector<std::atomic<int>> count(1000);
    std::atomic<int> started{0};
    parallel_for(2, 2, [&](std::size_t) {  // needs two threads to finish
      ++started;
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (started.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    });
    parallel_for(count.size(), 2, [&](std::size_t i) { ++count[i]; });
    bool ok = started.load() == 2;
    for (auto& c : count) ok = ok && c.load() == 1;
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}
