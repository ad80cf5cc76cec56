// A progress line on stderr for long computations (minksum sum).
#pragma once

#include <minksum/sum_result.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace minksum::cli {

// RAII ticker: while alive, and only when stderr is a terminal, a background
// thread waits until `delay` has passed, then rewrites one line on stderr
// every `period` from the last report of the sum given sum_options(), e.g.
//   "minksum sum: walk 42% (2.3 s)"   (phase with a known fraction)
//   "minksum sum: cgm (2.3 s)"        (fraction unknown)
//   "minksum sum: computing (2.3 s)"  (no phase reported)
// The destructor (normal exit or exception) wakes the thread at once, which
// erases the line it drew ("\r\033[K") before the caller prints anything
// else.  Nothing is ever printed when stderr is not a terminal or when the
// ticker dies before `delay`.
class ProgressTicker {
 public:
  explicit ProgressTicker(std::string label,
                          std::chrono::milliseconds delay = std::chrono::milliseconds(1000),
                          std::chrono::milliseconds period = std::chrono::milliseconds(200));
  ~ProgressTicker();
  ProgressTicker(const ProgressTicker&) = delete;
  ProgressTicker& operator=(const ProgressTicker&) = delete;

  // Options for the sum this ticker shows: their progress callback stores
  // the phase and fraction in the ticker's atomics, which its thread polls.
  // The ticker must outlive the sum.
  SumOptions sum_options();

  // Stop the thread and erase the line (idempotent; the destructor calls it).
  void stop();

 private:
  void loop();

  // The last report (written by the computing thread, read by the ticker's):
  // the phase (a string literal, nullptr before the first report) and its
  // fraction.
  std::atomic<const char*> phase_{nullptr};
  std::atomic<double> fraction_{-1.0};

  std::string label_;
  std::chrono::milliseconds delay_, period_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  // guarded by mutex_
  std::thread thread_;     // not joinable when stderr is not a terminal
};

// The text of one progress line (without "\r" or terminal escapes):
// "LABEL: PHASE[ NN%] (S.S s)"; an empty phase reads "computing".
std::string progress_line(const std::string& label, const std::string& phase, double fraction, double seconds);

}  // namespace minksum::cli
