#include "lfcam/session/frame_alignment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lfcam/core/error.h"

namespace lfcam {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The frame rate a camera's frames show: the median of its frame-to-frame periods (dropped
// frames keep their numbers, so a gap of n counts as n periods), or nullopt with fewer than 3
// frames. The median, so that one frame delivered twice or late does not move it.
std::optional<double> FittedFps(const std::vector<FrameTime>& frames) {
  if (frames.size() < 3) return std::nullopt;
  std::vector<double> periods;
  for (std::size_t i = 1; i < frames.size(); ++i)
    periods.push_back(
        double(frames[i].wall_clock_ns - frames[i - 1].wall_clock_ns) /
        double(std::max<std::int64_t>(1, frames[i].sequence - frames[i - 1].sequence)));
  const double period = Median(periods);
  if (!(period > 0)) return std::nullopt;
  return 1e9 / period;
}

// A camera's phase on the frame grid (radians): the circular mean of its frames'.
double CameraPhase(const std::vector<FrameTime>& frames, std::int64_t start, double period) {
  double sx = 0, sy = 0;
  for (const FrameTime& f : frames) {
    const double phase =
        2 * std::numbers::pi * std::fmod(double(f.wall_clock_ns - start), period) / period;
    sx += std::cos(phase);
    sy += std::sin(phase);
  }
  return std::atan2(sy, sx);
}

double CircularDistance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 2 * std::numbers::pi);
  return std::min(d, 2 * std::numbers::pi - d);
}

}  // namespace

FrameAlignment AlignFrames(const Shot& shot, int rows, int cols, const AlignmentOptions& o) {
  if (shot.kind != ShotKind::kVideo || !shot.video)
    throw Error(fmt::format("shot '{}' is not a recording", shot.name));
  const VideoShot& v = *shot.video;
  FrameAlignment a;
  a.rows = rows;
  a.cols = cols;
  a.fps = v.fps;
  const double period = 1e9 / v.fps;
  const int groups = std::max(1, v.groups);
  a.groups = groups;
  const std::size_t n = std::size_t(rows) * std::size_t(cols);
  std::vector<const ShotImage*> camera(n, nullptr);
  a.camera_group.assign(n, 0);
  for (const auto* list : {&shot.images, &shot.pending})
    for (const ShotImage& image : *list) {
      if (image.row < 0 || image.col < 0 || image.row >= rows || image.col >= cols) continue;
      const std::size_t c = std::size_t(image.row * cols + image.col);
      // Staggered: the camera's group (its frames start group / (groups * fps) later).
      if (image.capture.is_object() && image.capture.contains("group") &&
          image.capture["group"].is_number_integer())
        a.camera_group[c] = int(
            std::clamp<std::int64_t>(image.capture["group"].get<std::int64_t>(), 0, groups - 1));
      if (!image.frames.empty()) camera[c] = &image;
    }
  // Where camera c's frames stand on the array's grid: its group's offset.
  const auto group_offset = [&](std::size_t c) {
    return double(a.camera_group[c]) * period / groups;
  };

  // Cameras at another rate are left out of everything; the phase the others share is the
  // camera phase nearest all of theirs (a circular median: one camera off does not move it).
  a.cameras.resize(n);
  std::vector<double> phases;
  for (std::size_t c = 0; c < n; ++c) {
    CameraSync& s = a.cameras[c];
    s.row = int(c) / cols;
    s.col = int(c) % cols;
    if (!camera[c]) continue;
    s.fps = FittedFps(camera[c]->frames);
    if (s.fps && std::abs(*s.fps / v.fps - 1) > o.max_period_error) {
      s.left_out = true;
      s.problem = fmt::format("records at {:.3f} fps, the array at {:g}: left out", *s.fps, v.fps);
      continue;
    }
    phases.push_back(
        CameraPhase(camera[c]->frames, v.start_unix_ns + std::llround(group_offset(c)), period));
  }
  double phase = 0, best = std::numeric_limits<double>::infinity();
  for (const double p : phases) {
    double sum = 0;
    for (const double q : phases) sum += CircularDistance(p, q);
    if (sum < best) best = sum, phase = p;
  }
  const double shift = phase / (2 * std::numbers::pi) * period;
  a.tau0_ns = v.start_unix_ns + std::llround(shift);
  const auto count = std::int64_t(std::ceil(v.seconds * v.fps - 1e-9)) * groups;
  // One slot per camera and frame: a bound on what a manifest can make it allocate (100
  // cameras for 2 hours at 60 fps).
  if (double(count) * double(n) > 5e7)
    throw Error(
        fmt::format("recording '{}': {} frames of {} cameras is more than this host "
                    "aligns at once (5e7 camera frames)",
                    shot.name, count, n));
  a.frames.resize(std::size_t(std::max<std::int64_t>(count, 0)));
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    a.frames[k].time_ns = a.tau0_ns + std::llround(double(k) * period / groups);
    a.frames[k].group = int(k % std::size_t(groups));
    a.frames[k].frame_of_camera.assign(n, -1);
    a.frames[k].offset_ns.assign(n, 0);
  }

  for (std::size_t c = 0; c < n; ++c) {
    CameraSync& s = a.cameras[c];
    const ShotImage* image = camera[c];
    if (!image) {
      s.problem = "no frames";
      continue;
    }
    const std::vector<FrameTime>& frames = image->frames;
    s.recorded = std::int64_t(frames.size());
    for (std::size_t i = 1; i < frames.size(); ++i)
      s.dropped += frames[i].sequence - frames[i - 1].sequence - 1;
    if (s.left_out) continue;
    std::vector<double> offsets;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      // Its slot on its group's grid, and the light field frame that slot is.
      const double along = (double(frames[i].wall_clock_ns - a.tau0_ns) - group_offset(c)) / period;
      const auto k = std::int64_t(std::floor(along + 0.5)) * groups + a.camera_group[c];
      if (k < 0 || k >= std::int64_t(a.frames.size())) {
        ++s.outside;
        continue;
      }
      LightFieldFrame& frame = a.frames[std::size_t(k)];
      const double offset = double(frames[i].wall_clock_ns - frame.time_ns);
      int& chosen = frame.frame_of_camera[c];
      if (chosen >= 0) {
        ++s.duplicates;
        // The nearer of the two stays.
        if (std::abs(offset) >=
            std::abs(double(frames[std::size_t(chosen)].wall_clock_ns - frame.time_ns)))
          continue;
        offsets.pop_back();
      }
      chosen = int(i);
      frame.offset_ns[c] = frames[i].wall_clock_ns - frame.time_ns;
      offsets.push_back(offset);
    }
    if (!offsets.empty()) s.median_offset_us = Median(offsets) / 1e3;
    if (s.median_offset_us && std::abs(*s.median_offset_us) > o.max_camera_offset_ms * 1e3)
      s.problem = fmt::format(
          "its frames lie {:+.3f} ms from the array's on median (more than {:g} ms): its clock or "
          "its sync is off",
          *s.median_offset_us / 1e3, o.max_camera_offset_ms);
  }

  for (LightFieldFrame& frame : a.frames) {
    std::int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (std::size_t c = 0; c < n; ++c) {
      if (a.camera_group[c] != frame.group) continue;  // staggered: another group's frame
      const int i = frame.frame_of_camera[c];
      if (i < 0) {
        ++a.cameras[c].missing;
        continue;
      }
      const std::int64_t t = camera[c]->frames[std::size_t(i)].wall_clock_ns;
      lo = std::min(lo, t);
      hi = std::max(hi, t);
      ++frame.cameras;
    }
    if (frame.cameras >= 2) frame.spread_ns = hi - lo;
  }
  // Cameras with no frames, or left out, were counted missing in all their frames above.
  for (const CameraSync& s : a.cameras)
    if (!s.problem.empty())
      a.problems.push_back(fmt::format("camera ({}, {}): {}", s.row, s.col, s.problem));
  return a;
}

SpreadSummary SummarizeSpread(const FrameAlignment& a) {
  std::vector<double> spreads;
  for (const LightFieldFrame& f : a.frames)
    if (f.spread_ns) spreads.push_back(double(*f.spread_ns) / 1e3);
  SpreadSummary s;
  s.frames = int(spreads.size());
  if (spreads.empty()) return s;
  std::sort(spreads.begin(), spreads.end());
  s.median_us = spreads[spreads.size() / 2];
  s.p95_us = spreads[std::min(spreads.size() - 1, std::size_t(0.95 * double(spreads.size())))];
  s.max_us = spreads.back();
  return s;
}

}  // namespace lfcam
