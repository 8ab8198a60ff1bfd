#pragma once
// Light field frames from a recording (issue 24; ../shared/DESIGN.md, "Light field video"): the
// cameras' frames grouped by their wall-clock times. Light field frame k stands at time
// tau_k = tau_0 + k / fps on the array's wall clock; from each camera it takes the frame nearest
// tau_k within half a frame period. A camera with no frame there is missing from light field
// frame k (a dropped frame, a node that stopped); one with two is duplicated (the farther one is
// left out). The frame's spread is the latest minus the earliest wall-clock time it holds: its
// sync error as the clocks say, reported, never hidden. tau_0 is the start asked plus the phase
// the frames share (the cameras' phases' circular median). A staggered recording
// (VideoShot::groups = N, each camera's group in its capture record) has N light field frames a
// period, 1 / (N fps) apart, frame k holding the cameras of group k mod N.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/session/session.h"

namespace lfcam {

struct AlignmentOptions {
  // A camera whose frames lie farther than this from the array's times, on median, has a
  // clock or a sync that is off: named, and its frames still used where they fall.
  double max_camera_offset_ms = 1.0;
  // A camera whose frame period differs from the array's by more than this fraction records at
  // another rate: named, and left out of every light field frame.
  double max_period_error = 0.005;
};

struct LightFieldFrame {
  std::int64_t time_ns = 0;  // tau_k
  int group = 0;             // staggered: the group of cameras it holds (k mod groups)
  // Per camera (row-major over the grid), the index of its frame in ShotImage::frames, or -1.
  std::vector<int> frame_of_camera;
  // Per camera, its frame's wall-clock time minus tau_k (0 where it has none).
  std::vector<std::int64_t> offset_ns;
  std::optional<std::int64_t> spread_ns;  // nullopt with fewer than two cameras
  int cameras = 0;                        // present
};

struct CameraSync {
  int row = 0, col = 0;
  std::int64_t recorded = 0;    // frames the camera delivered
  std::int64_t dropped = 0;     // gaps in its sequence numbers
  std::int64_t missing = 0;     // light field frames of its group it has no frame in
  std::int64_t duplicates = 0;  // frames of it that fell in a slot another of its frames took
  std::int64_t outside = 0;     // frames before the first or after the last light field frame
  std::optional<double> median_offset_us;  // its frames' wall-clock times minus tau_k
  std::optional<double> fps;               // fitted to its frames' times
  bool left_out = false;                   // its rate differs: in no light field frame
  std::string problem;                     // what is wrong with it, or empty
};

struct FrameAlignment {
  int rows = 0, cols = 0;
  double fps = 0;  // each camera's; the light field frames come groups * fps a second
  int groups = 1;  // staggered recordings: the groups of cameras, each in every groups-th frame
  std::vector<int> camera_group;  // per camera (row-major), from its capture record's "group"
  std::int64_t tau0_ns = 0;
  std::vector<LightFieldFrame> frames;
  std::vector<CameraSync> cameras;    // row-major over the grid
  std::vector<std::string> problems;  // every camera's, and the array's
};

// Aligns the cameras of a video shot of a `rows` x `cols` grid (cameras not in the shot, or with
// no frames, are missing from every frame). Throws lfcam::Error for a shot that is not video.
FrameAlignment AlignFrames(const Shot& shot, int rows, int cols,
                           const AlignmentOptions& options = {});

// Summary numbers of the spreads (microseconds) over the frames with two cameras or more.
struct SpreadSummary {
  int frames = 0;
  double median_us = 0, p95_us = 0, max_us = 0;
};
SpreadSummary SummarizeSpread(const FrameAlignment& alignment);

}  // namespace lfcam
