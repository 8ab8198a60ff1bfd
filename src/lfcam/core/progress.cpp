#include "lfcam/core/progress.h"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>

namespace lfcam {

bool ProgressWanted(bool quiet) { return !quiet && ::isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(std::string label, std::int64_t total, bool enabled)
    : label_(std::move(label)),
      total_(std::max<std::int64_t>(1, total)),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::finish() {
  std::lock_guard lock(draw_mutex_);
  if (enabled_ && drawn_) {
    fmt::print(stderr, "\r\033[K");
    std::fflush(stderr);
  }
  enabled_ = false;
}

void ProgressBar::advance(std::int64_t n) {
  const std::int64_t done = done_.fetch_add(n) + n;
  const auto now = std::chrono::steady_clock::now();
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !enabled_ || now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw(done);
}

ProgressCallback ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](std::int64_t n) { advance(n); };
}

void ProgressBar::draw(std::int64_t done) {
  constexpr int kWidth = 30;
  const double fraction = std::clamp(double(done) / double(total_), 0.0, 1.0);
  const int filled = int(fraction * kWidth);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  fmt::print(stderr, "\r\033[K{} {:3.0f}% [{}{}] {:.1f} s", label_, 100 * fraction,
             std::string(std::size_t(filled), '='), std::string(std::size_t(kWidth - filled), ' '),
             seconds);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace lfcam
