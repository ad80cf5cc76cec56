// Progress and cancellation of the Minkowski sums (SumOptions in
// minkowski.hpp): per call, no global state.  Sums running at once in
// several threads (some sharing an operand) each report to their own
// callback exactly what they report alone, on their own thread, with
// fractions that never decrease within a phase, and compute the same
// polytopes; a cancellation flag stops a sum at its next report point with
// Cancelled, whether it is set before the call, from the callback or from
// another thread.  `make tsan` runs this suite under ThreadSanitizer.
#include <minksum/catalog.hpp>
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/walk.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <functional>
#include <latch>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

ConvexPolytope cat(const std::string& s) { return catalog_polytope(s); }

struct Report {
  std::string phase;
  double fraction;
  friend bool operator==(const Report&, const Report&) = default;
};

// Records every report of one sum, and whether any came from another thread
// than the one that asked for the options.
class Recorder {
 public:
  SumOptions options() {
    owner_ = std::this_thread::get_id();
    SumOptions o;
    o.progress = [this](const char* phase, double fraction) {
      if (std::this_thread::get_id() != owner_) foreign_thread_ = true;
      reports_.push_back({phase, fraction});
    };
    return o;
  }
  const std::vector<Report>& reports() const { return reports_; }
  bool foreign_thread() const { return foreign_thread_; }

 private:
  std::thread::id owner_;
  std::vector<Report> reports_;
  bool foreign_thread_ = false;
};

// Within each phase, the known fractions lie in [0, 1] and never decrease.
void expect_monotone(const std::vector<Report>& reports, const std::string& label) {
  std::map<std::string, double> last;
  for (const Report& r : reports) {
    if (r.fraction < 0) continue;
    EXPECT_LE(r.fraction, 1.0) << label << ": " << r.phase;
    auto [it, first] = last.try_emplace(r.phase, r.fraction);
    if (!first) {
      EXPECT_GE(r.fraction, it->second) << label << ": phase " << r.phase << " went back";
      it->second = r.fraction;
    }
  }
}

std::vector<std::string> phases_of(const std::vector<Report>& reports) {
  std::vector<std::string> p;
  for (const Report& r : reports)
    if (p.empty() || p.back() != r.phase) p.push_back(r.phase);
  return p;
}

struct Job {
  std::string label;
  const ConvexPolytope* a;
  const ConvexPolytope* b;
  Method method;
  std::vector<std::string> phases;  // in order, each once
};

const std::vector<Method> kMethods = {Method::automatic, Method::walk, Method::chms, Method::cvms,
                                      Method::essdms,    Method::mssd, Method::cgm};

TEST(ProgressReports, EachSumAloneReportsItsPhasesInOrder) {
  const ConvexPolytope a = cat("sphere:2"), b = cat("dodecahedron");
  for (Method m : kMethods) {
    SCOPED_TRACE(method_name(m));
    Recorder rec;
    const SumResult r = minkowski_sum(a, b, m, rec.options());
    ASSERT_FALSE(rec.reports().empty());
    if (m == Method::walk || m == Method::automatic) {
      EXPECT_EQ(phases_of(rec.reports()), (std::vector<std::string>{"walk", "convert"}));
      EXPECT_EQ(rec.reports().front(), (Report{"walk", 0.0}));
    } else {
      EXPECT_EQ(phases_of(rec.reports()), std::vector<std::string>{method_name(m)});
      for (const Report& x : rec.reports()) EXPECT_LT(x.fraction, 0);
    }
    expect_monotone(rec.reports(), method_name(m));
    EXPECT_TRUE(same_polytope(r.polytope, minkowski_sum(a, b, m).polytope));
  }
}

TEST(ProgressReports, WalkReportsFractionsAsItGoes) {
  // 5120 facets per operand: reports at 0 and 4096 facets of each walk.
  Recorder rec;
  const WalkSum w = minkowski_walk(cat("sphere:5"), cat("sphere:5@rot:1"), rec.options());
  ASSERT_GT(w.num_facets(), 0);
  std::vector<double> f;
  for (const Report& r : rec.reports()) {
    EXPECT_EQ(r.phase, "walk");
    f.push_back(r.fraction);
  }
  ASSERT_EQ(f.size(), 6u);
  EXPECT_EQ(f.front(), 0.0);
  EXPECT_EQ(f.back(), 0.8);
  EXPECT_GT(f[2], 0.0);
  EXPECT_LT(f[2], 0.4);
  expect_monotone(rec.reports(), "walk");
}

TEST(ProgressReports, ConcurrentSumsReportOnlyTheirOwnProgress) {
  // Operands shared between threads, as a caller's pool would share them.
  const ConvexPolytope s5 = cat("sphere:5"), s5r = cat("sphere:5@rot:1"), rnd = cat("random:3000:7");
  const ConvexPolytope s2 = cat("sphere:2"), dod = cat("dodecahedron"), tc = cat("truncated-cube");
  const std::vector<Job> jobs = {
      {"walk sphere:5 + sphere:5@rot:1", &s5, &s5r, Method::walk, {"walk", "convert"}},
      {"walk random:3000:7 + sphere:5", &rnd, &s5, Method::automatic, {"walk", "convert"}},
      {"cgm sphere:2 + dodecahedron", &s2, &dod, Method::cgm, {"cgm"}},
      {"cvms sphere:2 + truncated-cube", &s2, &tc, Method::cvms, {"cvms"}},
  };
  // Alone, one after the other: the reference reports and results.
  std::vector<std::vector<Report>> alone;
  std::vector<SumResult> alone_result;
  for (const Job& j : jobs) {
    Recorder rec;
    alone_result.push_back(minkowski_sum(*j.a, *j.b, j.method, rec.options()));
    alone.push_back(rec.reports());
    EXPECT_EQ(phases_of(rec.reports()), j.phases) << j.label;
    expect_monotone(rec.reports(), j.label);
  }
  EXPECT_GT(alone[0].size(), 4u) << "the walk should report fractions along the way";

  // At once, each in its own thread, released together; twice over.
  for (int round = 0; round < 2; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    std::vector<Recorder> recs(jobs.size());
    std::vector<SumResult> results(jobs.size());
    std::vector<std::string> errors(jobs.size());
    std::latch start(std::ptrdiff_t(jobs.size()));
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < jobs.size(); ++i)
      threads.emplace_back([&, i] {
        const SumOptions options = recs[i].options();
        start.arrive_and_wait();
        try {
          results[i] = minkowski_sum(*jobs[i].a, *jobs[i].b, jobs[i].method, options);
        } catch (const std::exception& e) {
          errors[i] = e.what();
        }
      });
    for (auto& t : threads) t.join();
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      SCOPED_TRACE(jobs[i].label);
      ASSERT_EQ(errors[i], "");
      EXPECT_FALSE(recs[i].foreign_thread()) << "a report reached the callback from another thread";
      EXPECT_EQ(recs[i].reports(), alone[i]);
      expect_monotone(recs[i].reports(), jobs[i].label);
      EXPECT_EQ(results[i].method, alone_result[i].method);
      EXPECT_EQ(results[i].vertex_origin, alone_result[i].vertex_origin);
      EXPECT_TRUE(same_polytope(results[i].polytope, alone_result[i].polytope));
    }
  }
}

TEST(ProgressReports, NoCallbackNoFlagIsTheDefault) {
  const SumOptions o;
  EXPECT_FALSE(o.progress);
  EXPECT_EQ(o.cancel, nullptr);
  EXPECT_NO_THROW(o.report("walk", 0.5));
}

// ---------------------------------------------------------------------------
// Cancellation.

static_assert(!std::is_base_of_v<UsageError, Cancelled> && !std::is_base_of_v<InputError, Cancelled>,
              "a cancelled sum is neither bad usage nor bad input");

TEST(Cancellation, FlagSetBeforeTheCallStopsEveryMethodAtItsStart) {
  const ConvexPolytope a = cat("sphere:2"), b = cat("cube");
  std::atomic<bool> cancel{true};
  int calls = 0;
  SumOptions o;
  o.cancel = &cancel;
  o.progress = [&](const char*, double) { ++calls; };
  for (Method m : kMethods) EXPECT_THROW(minkowski_sum(a, b, m, o), Cancelled) << method_name(m);
  EXPECT_THROW(minkowski_sum_walk(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_walk(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_sum_chms(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_sum_cvms(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_sum_essdms(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_sum_mssd(a, b, o), Cancelled);
  EXPECT_THROW(minkowski_sum_cgm(a, b, o), Cancelled);
  const CubicalGaussianMap ga = CubicalGaussianMap::from_polytope(a), gb = CubicalGaussianMap::from_polytope(b);
  EXPECT_THROW(minkowski_sum_cgm(ga, gb, a, b, o), Cancelled);
  EXPECT_EQ(calls, 0) << "the flag is checked before the callback";

  // Cleared, the same options compute the sum.
  cancel = false;
  for (Method m : kMethods)
    EXPECT_TRUE(same_polytope(minkowski_sum(a, b, m, o).polytope, minkowski_sum_chms(a, b).polytope)) << method_name(m);
  EXPECT_GT(calls, 0);
}

// The callback sets the flag at its k-th call: the next report point throws,
// before any further call, for every k short of the last report.
void expect_stops_at_next_report(const ConvexPolytope& a, const ConvexPolytope& b, Method m) {
  SCOPED_TRACE(method_name(m));
  int total = 0;
  SumOptions count;
  count.progress = [&](const char*, double) { ++total; };
  minkowski_sum(a, b, m, count);
  ASSERT_GE(total, 2) << "a start report and at least one more";
  for (int stop_after = 1; stop_after < total; ++stop_after) {
    std::atomic<bool> cancel{false};
    int calls = 0;
    SumOptions o;
    o.cancel = &cancel;
    o.progress = [&](const char*, double) {
      if (++calls == stop_after) cancel = true;
    };
    EXPECT_THROW(minkowski_sum(a, b, m, o), Cancelled) << "stop after " << stop_after;
    EXPECT_EQ(calls, stop_after);
  }
}

TEST(Cancellation, FlagSetByTheCallbackStopsAtTheNextReport) {
  // walk on operands large enough for reports along its walks.
  const ConvexPolytope a = cat("sphere:5"), b = cat("sphere:5@rot:1");
  expect_stops_at_next_report(a, b, Method::walk);
  expect_stops_at_next_report(a, b, Method::automatic);
  const ConvexPolytope c = cat("sphere:2"), d = cat("truncated-cube");
  for (Method m : {Method::chms, Method::cvms, Method::essdms, Method::mssd, Method::cgm})
    expect_stops_at_next_report(c, d, m);
}

TEST(Cancellation, FlagSetFromAnotherThreadStopsTheSum) {
  const ConvexPolytope a = cat("sphere:5"), b = cat("sphere:5@rot:1");
  std::atomic<bool> cancel{false};
  std::mutex mutex;
  std::condition_variable cv;
  bool started = false, flag_set = false;
  int calls = 0;
  bool cancelled = false;
  std::string other_error;
  SumOptions o;
  o.cancel = &cancel;
  o.progress = [&](const char*, double) {
    ++calls;
    if (calls != 1) return;
    // First report: tell the main thread, and wait until it has set the flag.
    std::unique_lock<std::mutex> lock(mutex);
    started = true;
    cv.notify_all();
    cv.wait(lock, [&] { return flag_set; });
  };
  std::thread worker([&] {
    try {
      minkowski_sum(a, b, Method::walk, o);
    } catch (const Cancelled&) {
      cancelled = true;
    } catch (const std::exception& e) {
      other_error = e.what();
    }
  });
  {
    std::unique_lock<std::mutex> lock(mutex);
    cv.wait(lock, [&] { return started; });
    cancel.store(true);
    flag_set = true;
  }
  cv.notify_all();
  worker.join();
  EXPECT_TRUE(cancelled);
  EXPECT_EQ(other_error, "");
  EXPECT_EQ(calls, 1) << "the report after the flag was set threw";

  // A sum cancelled in one thread leaves nothing behind for the next one.
  cancel = false;
  SumOptions again_options;
  again_options.cancel = &cancel;
  const SumResult again = minkowski_sum(a, b, Method::walk, again_options);
  EXPECT_TRUE(same_polytope(again.polytope, minkowski_sum(a, b, Method::walk).polytope));
}

TEST(Cancellation, CancelledSaysWhatHappened) {
  const Cancelled c;
  EXPECT_NE(std::string(c.what()).find("cancelled"), std::string::npos);
}

}  // namespace
