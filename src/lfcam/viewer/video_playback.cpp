#include "lfcam/viewer/video_playback.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lfcam/core/error.h"

namespace lfcam {

VideoPlayback::VideoPlayback(const std::filesystem::path& path, std::int64_t first, int ahead)
    : video_(path), ahead_(std::max(1, ahead)) {
  if (first < 0 || first >= frames())
    throw Error(
        fmt::format("{}: there is no frame {} ({} frames)", path.string(), first, frames()));
  current_ = std::make_shared<const LightField>(video_.ReadFrame(std::size_t(first)));
  current_index_ = playhead_ = play_start_index_ = wanted_from_ = first;
  decoded_[first] = current_;
  if (frames() > 1) decoder_ = std::thread([this] { DecodeLoop(); });
}

VideoPlayback::~VideoPlayback() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  if (decoder_.joinable()) decoder_.join();
}

bool VideoPlayback::Wanted(std::int64_t k) const {
  const std::int64_t n = frames();
  for (std::int64_t i = 0; i <= ahead_; ++i) {
    std::int64_t j = wanted_from_ + i;
    if (j >= n) {
      if (!wanted_loop_) break;
      j %= n;
    }
    if (j == k) return true;
  }
  return false;
}

void VideoPlayback::DecodeLoop() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    // The first frame from the playhead on that is not decoded yet.
    std::int64_t next = -1;
    const std::int64_t n = frames();
    for (std::int64_t i = 0; i <= ahead_ && next < 0; ++i) {
      std::int64_t j = wanted_from_ + i;
      if (j >= n) {
        if (!wanted_loop_) break;
        j %= n;
      }
      if (!decoded_.count(j)) next = j;
    }
    if (next < 0 || !error_.empty()) {
      changed_.wait(lock);
      continue;
    }
    lock.unlock();
    std::shared_ptr<const LightField> frame;
    std::string failure;
    const auto start = Clock::now();
    try {
      frame = std::make_shared<const LightField>(video_.ReadFrame(std::size_t(next)));
    } catch (const std::exception& e) {
      failure = e.what();
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    lock.lock();
    if (!failure.empty()) {
      error_ = failure;
    } else {
      decoded_[next] = std::move(frame);
      ++decoded_count_;
      decode_ms_total_ += ms;
    }
    // Frames behind the playhead and not wanted ahead are let go (the one shown is held by
    // current_ anyway).
    for (auto it = decoded_.begin(); it != decoded_.end();)
      it = Wanted(it->first) ? std::next(it) : decoded_.erase(it);
    changed_.notify_all();
  }
}

void VideoPlayback::SetPlayhead(std::int64_t k) {
  playhead_ = k;
  {
    const std::lock_guard lock(mutex_);
    wanted_from_ = k;
    wanted_loop_ = loop_;
  }
  changed_.notify_all();
}

bool VideoPlayback::Tick(Clock::time_point now) {
  const std::int64_t n = frames();
  if (playing_ && n > 1) {
    const double elapsed = std::chrono::duration<double>(now - play_start_).count();
    std::int64_t k = play_start_index_ + std::int64_t(std::floor(elapsed * fps()));
    if (k >= n) {
      if (loop_) {
        k %= n;
      } else {
        k = n - 1;
        playing_ = false;
      }
    }
    if (k != playhead_) SetPlayhead(k);
  }
  // The newest decoded frame at or before the playhead (at the playhead itself when ready).
  std::shared_ptr<const LightField> frame;
  std::int64_t index = current_index_;
  {
    const std::lock_guard lock(mutex_);
    const auto at = decoded_.find(playhead_);
    if (at != decoded_.end()) {
      frame = at->second;
      index = playhead_;
    } else if (playing_) {
      for (const auto& [k, f] : decoded_)
        if (k <= playhead_ && k > index) {
          frame = f;
          index = k;
        }
    }
  }
  if (!frame || index == current_index_) return false;
  if (playing_) {
    const std::int64_t step = (index - current_index_ + n) % n;
    if (step > 1) skipped_ += step - 1;
  }
  current_ = std::move(frame);
  current_index_ = index;
  return true;
}

void VideoPlayback::Play(Clock::time_point now) {
  if (frames() <= 1) return;
  if (!loop_ && playhead_ >= frames() - 1) SetPlayhead(0);  // from the start again
  playing_ = true;
  play_start_ = now;
  play_start_index_ = playhead_;
  skipped_ = 0;
}

void VideoPlayback::Pause() { playing_ = false; }

void VideoPlayback::Toggle(Clock::time_point now) {
  if (playing_)
    Pause();
  else
    Play(now);
}

void VideoPlayback::Seek(std::int64_t k, Clock::time_point now) {
  k = std::clamp<std::int64_t>(k, 0, frames() - 1);
  SetPlayhead(k);
  play_start_ = now;
  play_start_index_ = k;
  // Wait for it (a scrub shows the frame asked for, not a neighbour).
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return decoded_.count(k) > 0 || !error_.empty() || stop_; });
}

void VideoPlayback::Step(std::int64_t k) {
  Pause();
  const std::int64_t n = frames();
  std::int64_t target = playhead_ + k;
  target = loop_ ? ((target % n) + n) % n : std::clamp<std::int64_t>(target, 0, n - 1);
  Seek(target);
}

bool VideoPlayback::ready(std::int64_t k) const {
  const std::lock_guard lock(mutex_);
  return decoded_.count(k) > 0;
}

double VideoPlayback::decode_ms() const {
  const std::lock_guard lock(mutex_);
  return decoded_count_ > 0 ? decode_ms_total_ / double(decoded_count_) : 0.0;
}

std::string VideoPlayback::error() const {
  const std::lock_guard lock(mutex_);
  return error_;
}

}  // namespace lfcam
