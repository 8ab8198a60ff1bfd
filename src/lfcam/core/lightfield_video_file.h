#pragma once
// The .lfv light field video file (docs/format.md): L(u, v, s, t, tau), one calibrated light field
// over time. A preamble and a JSON header (the recording: frame rate, start, sync report,
// metadata), then the frames in order, each a frame record (its number, time, sync spread, size
// and its own checksum) followed by a complete .lf light field (core/lightfield_file.h: its
// views zstd-compressed, each with its checksum). A frame is whole on disk before the preamble
// counts it, so the file can be read while it is still being written (a long recording builds
// for minutes); readers find the frames by walking their records, and read any one alone.
// Everything that reads video reads a still .lf too, as a video of one frame.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lfcam/core/input_file.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/core/lightfield_file.h"

namespace lfcam {

inline constexpr std::uint32_t kLightFieldVideoVersion = 1;

struct VideoFrameInfo {
  std::int64_t index = 0;                 // the light field frame's number k
  std::int64_t time_ns = 0;               // its time tau_k (Unix ns, the array's wall clock)
  std::optional<std::int64_t> spread_ns;  // its sync spread (none: fewer than two cameras)
  std::uint64_t offset = 0, bytes = 0;    // where its .lf lies in the file
};

struct LightFieldVideoHeader {
  double fps = 30;
  std::int64_t frames_planned = 0;
  std::int64_t start_unix_ns = 0;                      // tau_0
  nlohmann::json metadata = nlohmann::json::object();  // the recording, its sync report, the build
};

// Writes a video frame by frame. The file is created at `path` (an existing file is replaced)
// and readable from the first frame on; Finish marks it complete. A writer destroyed before
// Finish (an error, an interruption) removes the file: nothing half-written stays.
class LightFieldVideoWriter {
 public:
  LightFieldVideoWriter(const std::filesystem::path& path, const LightFieldVideoHeader& header);
  ~LightFieldVideoWriter();
  LightFieldVideoWriter(const LightFieldVideoWriter&) = delete;
  LightFieldVideoWriter& operator=(const LightFieldVideoWriter&) = delete;

  // Appends frame `info.index` (the next in order). Throws lfcam::Error.
  void Append(const LightField& frame, const VideoFrameInfo& info,
              const LightFieldWriteOptions& options = {Compression::kZstd, 1});
  std::int64_t frames() const { return frames_; }
  std::uint64_t bytes() const { return position_; }
  void Finish();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t position_ = 0;
  std::int64_t frames_ = 0;
  bool finished_ = false;
};

// Reads a .lfv video, or a .lf light field as a video of one frame. Throws lfcam::Error naming
// the file and the frame for anything that does not hold together.
class LightFieldVideo {
 public:
  explicit LightFieldVideo(const std::filesystem::path& path);

  bool is_video() const { return video_; }  // false: a still .lf
  const LightFieldVideoHeader& header() const { return header_; }
  // The whole frames found (more may come while the file is written: Refresh).
  std::size_t frame_count() const { return frames_.size(); }
  bool complete() const { return complete_; }
  const VideoFrameInfo& frame(std::size_t k) const;
  LightField ReadFrame(std::size_t k, const LightFieldReadOptions& options = {}) const;
  LightFieldHeader FrameHeader(std::size_t k) const;
  // Looks again for frames a writer has appended since.
  void Refresh();
  std::uint64_t file_bytes() const;

 private:
  std::filesystem::path path_;
  std::unique_ptr<InputFile> file_;
  bool video_ = false, complete_ = true;
  LightFieldVideoHeader header_;
  std::uint64_t first_frame_ = 0;
  std::vector<VideoFrameInfo> frames_;
};

// Frame `frame` of a video, or the light field of a still .lf (frame 0; memory-mapped as
// ReadLightField maps it). Throws lfcam::Error naming the file and the frame.
LightField ReadLightFieldFrame(const std::filesystem::path& path, std::size_t frame = 0,
                               const LightFieldReadOptions& options = {});

// Whether the file starts as a light field video does (cheap; false for anything else).
bool IsLightFieldVideo(const std::filesystem::path& path);

}  // namespace lfcam
