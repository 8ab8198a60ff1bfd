#include "lfcam/capture/recording_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"

namespace lfcam {

namespace {

// The frames camera c is missing from.
std::vector<std::int64_t> MissingFrames(const FrameAlignment& a, std::size_t c) {
  std::vector<std::int64_t> out;
  for (std::size_t k = 0; k < a.frames.size(); ++k)
    if (a.frames[k].frame_of_camera[c] < 0 && a.frames[k].group == a.camera_group[c])
      out.push_back(std::int64_t(k));
  return out;
}

}  // namespace

std::string FrameRanges(const std::vector<std::int64_t>& frames) {
  std::string out;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    if (!out.empty()) out += ", ";
    out += j == i ? fmt::format("{}", frames[i]) : fmt::format("{}-{}", frames[i], frames[j]);
    i = j + 1;
  }
  return out;
}

RecordingReport MakeRecordingReport(const CaptureManifest& m, const std::string& name,
                                    const AlignmentOptions& options) {
  const Shot* shot = nullptr;
  for (const Shot& s : m.shots)
    if (s.kind == ShotKind::kVideo && (name.empty() || s.name == name)) shot = &s;
  if (!shot)
    throw Error(name.empty() ? std::string("the session holds no recording")
                             : fmt::format("the session has no recording '{}'", name));
  RecordingReport r;
  r.shot = shot->name;
  r.video = *shot->video;
  r.alignment = AlignFrames(*shot, m.rows, m.cols, options);
  r.spread = SummarizeSpread(r.alignment);
  return r;
}

nlohmann::json RecordingReportToJson(const RecordingReport& r) {
  const FrameAlignment& a = r.alignment;
  nlohmann::json frames = nlohmann::json::array();
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    const LightFieldFrame& f = a.frames[k];
    nlohmann::json missing = nlohmann::json::array();
    for (std::size_t c = 0; c < f.frame_of_camera.size(); ++c)
      if (f.frame_of_camera[c] < 0 && a.camera_group[c] == f.group)
        missing.push_back({int(c) / a.cols, int(c) % a.cols});
    frames.push_back(
        {{"frame", k},
         {"group", f.group},
         {"time_ns", f.time_ns},
         {"cameras", f.cameras},
         {"spread_us", f.spread_ns ? nlohmann::json(double(*f.spread_ns) / 1e3) : nlohmann::json()},
         {"missing", missing}});
  }
  nlohmann::json cameras = nlohmann::json::array();
  for (std::size_t c = 0; c < a.cameras.size(); ++c) {
    const CameraSync& s = a.cameras[c];
    nlohmann::json j = {
        {"row", s.row},
        {"col", s.col},
        {"recorded", s.recorded},
        {"dropped", s.dropped},
        {"missing", s.missing},
        {"duplicates", s.duplicates},
        {"outside", s.outside},
        {"left_out", s.left_out},
        {"median_offset_us",
         s.median_offset_us ? nlohmann::json(*s.median_offset_us) : nlohmann::json()},
        {"fps", s.fps ? nlohmann::json(*s.fps) : nlohmann::json()},
        {"missing_frames", MissingFrames(a, c)}};
    if (!s.problem.empty()) j["problem"] = s.problem;
    cameras.push_back(std::move(j));
  }
  std::int64_t missing = 0, duplicates = 0;
  for (const CameraSync& s : a.cameras) {
    missing += s.missing;
    duplicates += s.duplicates;
  }
  return {{"shot", r.shot},
          {"fps", r.video.fps},
          {"seconds", r.video.seconds},
          {"sync", r.video.sync},
          {"groups", a.groups},
          {"size", {r.video.width, r.video.height}},
          {"frames", a.frames.size()},
          {"tau0_unix_ns", a.tau0_ns},
          {"spread_us",
           {{"frames", r.spread.frames},
            {"median", r.spread.median_us},
            {"p95", r.spread.p95_us},
            {"max", r.spread.max_us}}},
          {"camera_frames_missing", missing},
          {"camera_frames_duplicated", duplicates},
          {"problems", a.problems},
          {"per_frame", frames},
          {"per_camera", cameras}};
}

std::string RecordingReportText(const RecordingReport& r) {
  const FrameAlignment& a = r.alignment;
  std::int64_t recorded = 0, dropped = 0, missing = 0, duplicates = 0, outside = 0;
  for (const CameraSync& s : a.cameras) {
    recorded += s.recorded;
    dropped += s.dropped;
    missing += s.missing;
    duplicates += s.duplicates;
    outside += s.outside;
  }
  std::string out = fmt::format(
      "recording {}: {}x{} cameras, {:g} fps for {:g} s at {}x{}, sync {}{}: {} light field "
      "frames\n",
      r.shot, a.rows, a.cols, r.video.fps, r.video.seconds, r.video.width, r.video.height,
      r.video.sync,
      a.groups > 1 ? fmt::format(", staggered in {} groups ({:g} light field frames a second, "
                                 "each of one group)",
                                 a.groups, a.groups * r.video.fps)
                   : "",
      a.frames.size());
  if (r.spread.frames > 0)
    out += fmt::format(
        "spread (latest minus earliest exposure start, by the nodes' clocks): median {:.1f} us, "
        "95% {:.1f} us, max {:.1f} us over {} frames\n",
        r.spread.median_us, r.spread.p95_us, r.spread.max_us, r.spread.frames);
  out += fmt::format(
      "camera frames: {} recorded, {} dropped by their cameras; {} missing from light field "
      "frames (build fills them from the nearest cameras), {} duplicated, {} outside the "
      "recording\n",
      recorded, dropped, missing, duplicates, outside);
  for (std::size_t c = 0; c < a.cameras.size(); ++c) {
    const CameraSync& s = a.cameras[c];
    if (s.missing == 0 && s.duplicates == 0 && s.problem.empty()) continue;
    out += fmt::format("  camera ({}, {}):", s.row, s.col);
    if (!s.problem.empty()) out += " " + s.problem + ";";
    if (s.missing > 0 && s.missing < std::int64_t(a.frames.size()))
      out += fmt::format(" missing from frame {}", FrameRanges(MissingFrames(a, c)));
    else if (s.missing > 0)
      out += " missing from every frame";
    if (s.duplicates > 0) out += fmt::format(" ({} duplicated frames left out)", s.duplicates);
    out += "\n";
  }
  return out;
}

cv::Mat RecordingReportPicture(const RecordingReport& r) {
  const FrameAlignment& a = r.alignment;
  const int width = 1000, left = 70, right = 20, plot_w = width - left - right;
  const int top_h = 220, gap = 60, rows_h = std::clamp(int(a.cameras.size()) * 3, 120, 400);
  const int height = 40 + top_h + gap + rows_h + 50;
  cv::Mat canvas(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Scalar ink(40, 40, 40), dim(150, 150, 150), line(200, 90, 30);
  const auto text = [&](const std::string& s, cv::Point at, double scale, const cv::Scalar& c) {
    cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, c, 1, cv::LINE_AA);
  };
  text(fmt::format("{}: {:g} fps, {:g} s, sync {}; spread median {:.1f} us, max {:.1f} us", r.shot,
                   r.video.fps, r.video.seconds, r.video.sync, r.spread.median_us, r.spread.max_us),
       {left, 24}, 0.55, ink);
  const std::size_t n = std::max<std::size_t>(a.frames.size(), 1);
  const auto x_of = [&](double k) { return left + int(std::lround(k / double(n) * plot_w)); };

  // The spread over time.
  const int y0 = 40, y1 = 40 + top_h;
  double top = 1;
  for (const LightFieldFrame& f : a.frames)
    if (f.spread_ns) top = std::max(top, double(*f.spread_ns) / 1e3);
  top *= 1.1;
  cv::rectangle(canvas, {left, y0}, {left + plot_w, y1}, dim);
  for (int t = 0; t <= 4; ++t) {
    const int y = y1 - (y1 - y0) * t / 4;
    text(fmt::format("{:.0f}", top * t / 4), {5, y + 4}, 0.4, ink);
    cv::line(canvas, {left, y}, {left + 4, y}, dim);
  }
  text("spread, us", {left + 8, y0 + 16}, 0.45, ink);
  std::vector<cv::Point> points;
  for (std::size_t k = 0; k < a.frames.size(); ++k)
    if (a.frames[k].spread_ns)
      points.push_back({x_of(double(k) + 0.5), y1 - int(std::lround(double(*a.frames[k].spread_ns) /
                                                                    1e3 / top * (y1 - y0)))});
  if (points.size() > 1) cv::polylines(canvas, points, false, line, 1, cv::LINE_AA);

  // Each camera's offset from the array's times: blue early, red late, black missing.
  const int r0 = y1 + gap, r1 = r0 + rows_h;
  double scale_us = 1;
  for (const LightFieldFrame& f : a.frames)
    for (std::size_t c = 0; c < a.cameras.size(); ++c)
      if (f.frame_of_camera[c] >= 0)
        scale_us = std::max(scale_us, std::abs(double(f.offset_ns[c]) / 1e3));
  text(fmt::format("a row per camera: its frames against the array's times (blue early, red "
                   "late, to {:.0f} us; black: missing{})",
                   scale_us, a.groups > 1 ? "; grey: another group's" : ""),
       {left, r0 - 10}, 0.45, ink);
  const double row_h = double(rows_h) / double(std::max<std::size_t>(a.cameras.size(), 1));
  for (std::size_t c = 0; c < a.cameras.size(); ++c) {
    const int ya = r0 + int(std::lround(double(c) * row_h)),
              yb = r0 + int(std::lround(double(c + 1) * row_h));
    for (std::size_t k = 0; k < a.frames.size(); ++k) {
      const int i = a.frames[k].frame_of_camera[c];
      cv::Scalar colour(0, 0, 0);
      if (a.frames[k].group != a.camera_group[c]) colour = cv::Scalar(225, 225, 225);
      if (i >= 0) {
        const double v = std::clamp(double(a.frames[k].offset_ns[c]) / 1e3 / scale_us, -1.0, 1.0);
        colour = v < 0 ? cv::Scalar(255, 255 * (1 + v), 255 * (1 + v))
                       : cv::Scalar(255 * (1 - v), 255 * (1 - v), 255);
      }
      cv::rectangle(canvas, {x_of(double(k)), ya},
                    {std::max(x_of(double(k + 1)) - 1, x_of(double(k))), std::max(yb - 1, ya)},
                    colour, cv::FILLED);
    }
  }
  cv::rectangle(canvas, {left, r0}, {left + plot_w, r1}, dim);
  text("cameras", {5, r0 + 14}, 0.4, ink);
  for (int t = 0; t <= 4; ++t) {
    const double k = double(n) * t / 4;
    text(fmt::format("{:.2f} s", k / r.video.fps), {x_of(k) - 20, r1 + 20}, 0.4, ink);
  }
  cv::cvtColor(canvas, canvas, cv::COLOR_BGR2RGB);
  return canvas;
}

}  // namespace lfcam
