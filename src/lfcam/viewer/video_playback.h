#pragma once
// Playing a light field video in the viewer: a playhead that follows the clock at the video's
// frame rate while playing (looping or stopping at the end), seeks and steps, and a decoder
// thread that reads the frames ahead of it (each frame's views decompressed in parallel) so that
// the frame the clock asks for is usually ready. When decoding falls behind, the playhead does
// not wait: the newest frame ready is shown and the frames skipped are counted. A still light
// field plays as a video of one frame.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/lightfield_video_file.h"

namespace lfcam {

class VideoPlayback {
 public:
  using Clock = std::chrono::steady_clock;

  // Opens the file and decodes `first` (throws lfcam::Error naming the file and frame).
  // `ahead`: how many frames past the playhead the decoder keeps ready.
  explicit VideoPlayback(const std::filesystem::path& path, std::int64_t first = 0, int ahead = 4);
  ~VideoPlayback();
  VideoPlayback(const VideoPlayback&) = delete;
  VideoPlayback& operator=(const VideoPlayback&) = delete;

  bool is_video() const { return video_.is_video(); }
  std::int64_t frames() const { return std::int64_t(video_.frame_count()); }
  double fps() const { return video_.header().fps; }

  // Moves the playhead to where the clock says (while playing) and takes the newest decoded
  // frame at or before it; true when the frame to show changed.
  bool Tick(Clock::time_point now = Clock::now());
  // The frame to show and its number.
  const std::shared_ptr<const LightField>& current() const { return current_; }
  std::int64_t current_index() const { return current_index_; }
  // Where the playhead is (the frame the clock asks for; current_index() lags when decoding
  // does).
  std::int64_t playhead() const { return playhead_; }

  bool playing() const { return playing_; }
  void Play(Clock::time_point now = Clock::now());
  void Pause();
  void Toggle(Clock::time_point now = Clock::now());
  bool loop() const { return loop_; }
  void set_loop(bool loop) { loop_ = loop; }
  // Jumps to frame k (clamped); playing continues from there. Waits for the frame to decode,
  // so that a paused seek shows it.
  void Seek(std::int64_t k, Clock::time_point now = Clock::now());
  // k frames on (or back); pauses.
  void Step(std::int64_t k);

  // Frames the playhead passed that were never shown, since the last Play().
  std::int64_t skipped() const { return skipped_; }
  // Whether frame k is decoded and held, ready to show.
  bool ready(std::int64_t k) const;
  // The mean time to decode a frame (ms), over those decoded so far.
  double decode_ms() const;
  // An error the decoder met (the frame named), or empty.
  std::string error() const;

 private:
  void DecodeLoop();
  // The frames the decoder should hold: the playhead and `ahead_` after it (wrapping when
  // looping).
  bool Wanted(std::int64_t k) const;
  void SetPlayhead(std::int64_t k);

  LightFieldVideo video_;
  int ahead_;
  std::shared_ptr<const LightField> current_;
  std::int64_t current_index_ = 0, playhead_ = 0, skipped_ = 0;
  bool playing_ = false, loop_ = true;
  Clock::time_point play_start_;
  std::int64_t play_start_index_ = 0;

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::int64_t, std::shared_ptr<const LightField>> decoded_;
  std::int64_t wanted_from_ = 0;  // the playhead, as the decoder sees it
  bool wanted_loop_ = true, stop_ = false;
  std::int64_t decoded_count_ = 0;
  double decode_ms_total_ = 0;
  std::string error_;
  std::thread decoder_;
};

}  // namespace lfcam
