// The progress line of long commands (see progress.hpp).
#include "progress.hpp"

#include <minksum/sum_result.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <system_error>
#include <unistd.h>

namespace minksum::cli {

std::string progress_line(const std::string& label, const std::string& phase, double fraction, double seconds) {
  std::string line = label + ": " + (phase.empty() ? std::string("computing") : phase);
  char buf[64];
  if (fraction >= 0 && !std::isnan(fraction)) {
    int percent = static_cast<int>(std::floor(std::min(fraction, 1.0) * 100));
    std::snprintf(buf, sizeof buf, " %d%%", percent);
    line += buf;
  }
  std::snprintf(buf, sizeof buf, " (%.1f s)", seconds);
  line += buf;
  return line;
}

ProgressTicker::ProgressTicker(std::string label, std::chrono::milliseconds delay, std::chrono::milliseconds period)
    : label_(std::move(label)), delay_(delay), period_(period), start_(std::chrono::steady_clock::now()) {
  if (!::isatty(STDERR_FILENO)) return;
  try {
    thread_ = std::thread([this] { loop(); });
  } catch (const std::system_error&) {
    // No thread, no progress line: the computation itself is unaffected.
  }
}

ProgressTicker::~ProgressTicker() { stop(); }

SumOptions ProgressTicker::sum_options() {
  SumOptions o;
  o.progress = [this](const char* phase, double fraction) {
    fraction_.store(fraction, std::memory_order_relaxed);
    phase_.store(phase, std::memory_order_release);
  };
  return o;
}

void ProgressTicker::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ProgressTicker::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_until(lock, start_ + delay_, [this] { return stopping_; })) return;  // fast: nothing drawn
  do {
    lock.unlock();  // no lock held while writing: stop() never waits on the terminal
    const char* phase = phase_.load(std::memory_order_acquire);
    const double fraction = fraction_.load(std::memory_order_relaxed);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    // "\r" back to column 0, the text, then clear what a longer previous line left.
    const std::string text = "\r" + progress_line(label_, phase ? phase : "", fraction, seconds) + "\033[K";
    std::fputs(text.c_str(), stderr);
    std::fflush(stderr);
    lock.lock();
  } while (!wake_.wait_for(lock, period_, [this] { return stopping_; }));
  lock.unlock();
  std::fputs("\r\033[K", stderr);  // erase the line: what follows starts on a clean line
  std::fflush(stderr);
}

}  // namespace minksum::cli
