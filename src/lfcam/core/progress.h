#pragma once
// A progress bar on stderr for long-running work ("rendering  42% [=====     ] 3.1 s"), drawn
// only when stderr is a terminal and the user did not ask for quiet, redrawn at most ten times
// a second, safe to advance from many threads.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

namespace lfcam {

// What a long-running library function reports: how many more units of work are done.
using ProgressCallback = std::function<void(std::int64_t done_now)>;

// True when progress should be drawn: stderr is a terminal and `quiet` is not set.
bool ProgressWanted(bool quiet);

class ProgressBar {
 public:
  ProgressBar(std::string label, std::int64_t total, bool enabled);
  ~ProgressBar();  // finish()
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void advance(std::int64_t n);
  // Clears the bar's line (so that what is printed next starts on a clean one); later calls to
  // advance() draw nothing.
  void finish();
  // A callback for library functions (empty when the bar is disabled, so they skip the work).
  ProgressCallback callback();

 private:
  void draw(std::int64_t done);

  std::string label_;
  std::int64_t total_;
  bool enabled_;
  std::atomic<std::int64_t> done_{0};
  std::mutex draw_mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace lfcam
