#pragma once
// Building a light field video from a calibrated recording (issue 24): the recording's cameras'
// frames grouped into light field frames by their times (session/frame_alignment.h), and each
// light field frame built as a still is (calib/lightfield_build.h) from that frame's images, with
// the stills' calibration scaled to the video's sensor mode (one calibration serves the whole
// recording: the rig is rigid). A camera frame that is missing (dropped, or its node stopped) or
// cannot be decoded is filled from the nearest cameras, as a missing still is, and recorded in
// the frame's metadata. Frames are written as they are built (core/lightfield_video_file.h), so
// the file can be read while the build runs.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/calib/lightfield_build.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/session/frame_alignment.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct VideoBuildOptions {
  BuildOptions build;  // st sampling, resampling, windows (shot and allow_missing are not used)
  LightFieldWriteOptions write{Compression::kZstd, 1};
  AlignmentOptions alignment;
  std::int64_t first_frame = 0;
  std::int64_t frame_count = -1;  // -1: to the end
  std::function<void()> frame_done;
};

struct VideoBuildReport {
  std::int64_t frames = 0;
  double seconds = 0;
  std::uint64_t bytes = 0;        // the file's
  std::int64_t filled_views = 0;  // camera frames filled, over all frames
  SpreadSummary spread;
  std::vector<std::string> problems;  // the alignment's: cameras whose clock or rate is off
};

// The st samples per view a build of a video `width` pixels wide uses by default: the stills'
// default, 1248 x 1152 for the Pi v1.3's 2592-pixel-wide images (the paper's), scaled by the
// width (312 x 288 for 648 x 486 video, 624 x 576 for 1296 x 972).
std::pair<int, int> DefaultVideoStSamples(int width);

// Builds video shot `shot` of the session into `out`. Throws lfcam::Error for a shot that is not
// a recording, a calibration that does not match the grid or cannot be scaled to the video's
// mode, a stream missing or shorter than its frames say (the camera named), or no frame to build.
VideoBuildReport BuildLightFieldVideo(const std::filesystem::path& session_dir,
                                      const CaptureManifest& manifest,
                                      const CalibrationFile& calibration, const std::string& shot,
                                      const std::filesystem::path& out,
                                      const VideoBuildOptions& options);

}  // namespace lfcam
