#include "lfcam/calib/lightfield_video_build.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <future>
#include <memory>

#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/lightfield_video_file.h"

namespace lfcam {

std::pair<int, int> DefaultVideoStSamples(int width) {
  const double scale = double(width) / 2592.0;
  return {std::max(1, int(std::lround(1248 * scale))), std::max(1, int(std::lround(1152 * scale)))};
}

VideoBuildReport BuildLightFieldVideo(const std::filesystem::path& dir,
                                      const CaptureManifest& manifest, const CalibrationFile& cal,
                                      const std::string& shot_name,
                                      const std::filesystem::path& out,
                                      const VideoBuildOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const Shot* found = nullptr;
  for (const Shot& s : manifest.shots)
    if (s.name == shot_name) found = &s;
  if (!found)
    throw Error(fmt::format("{}: the session has no shot named '{}'",
                            (dir / kManifestName).string(), shot_name));
  if (found->kind != ShotKind::kVideo || !found->video)
    throw Error(fmt::format("shot '{}' is not a recording (build it as a still)", shot_name));
  if (manifest.rows != cal.rows || manifest.cols != cal.cols)
    throw Error(fmt::format("the calibration is for a {}x{} array, the session has {}x{}", cal.rows,
                            cal.cols, manifest.rows, manifest.cols));
  const VideoShot& video = *found->video;
  const CalibrationFile scaled = ScaledCalibration(cal, video.width, video.height);

  // The streams in the session (the cameras still on their nodes are missing), checked against
  // what the manifest says of their frames.
  Shot here = *found;
  here.pending.clear();
  std::vector<std::unique_ptr<InputFile>> streams(std::size_t(cal.rows * cal.cols));
  for (const ShotImage& image : here.images) {
    auto stream = std::make_unique<InputFile>(dir / image.file);
    if (!image.frames.empty() &&
        stream->size() < image.frames.back().offset + image.frames.back().size)
      throw Error(
          fmt::format("{} ({}): the stream has {} bytes, its frames end at byte {}: "
                      "truncated, or the manifest is wrong",
                      stream->name(), CameraLabel(image.row, image.col), stream->size(),
                      image.frames.back().offset + image.frames.back().size));
    streams[std::size_t(image.row * cal.cols + image.col)] = std::move(stream);
  }
  const FrameAlignment alignment = AlignFrames(here, cal.rows, cal.cols, o.alignment);
  const auto total = std::int64_t(alignment.frames.size());
  const std::int64_t first = std::clamp<std::int64_t>(o.first_frame, 0, total);
  const std::int64_t count =
      o.frame_count < 0 ? total - first : std::min(o.frame_count, total - first);
  if (count <= 0)
    throw Error(fmt::format("recording '{}' has {} light field frames: none from frame {}",
                            shot_name, total, o.first_frame));

  VideoBuildReport report;
  report.spread = SummarizeSpread(alignment);
  report.problems = alignment.problems;
  nlohmann::json per_camera = nlohmann::json::array();
  for (const CameraSync& s : alignment.cameras) {
    nlohmann::json j = {{"row", s.row},           {"col", s.col},
                        {"recorded", s.recorded}, {"dropped", s.dropped},
                        {"missing", s.missing},   {"duplicates", s.duplicates}};
    if (!s.problem.empty()) j["problem"] = s.problem;
    per_camera.push_back(std::move(j));
  }
  LightFieldVideoHeader header;
  header.fps = video.fps * alignment.groups;  // staggered: the groups' frames interleaved
  header.frames_planned = count;
  header.start_unix_ns = alignment.frames[std::size_t(first)].time_ns;
  header.metadata = {{"source", "built"},
                     {"recording", shot_name},
                     {"session", manifest.source},
                     {"first_frame", first},
                     {"video_mode", {video.width, video.height}},
                     {"sync", video.sync},
                     {"groups", alignment.groups},
                     {"camera_fps", video.fps},
                     {"sync_report",
                      {{"spread_us",
                        {{"median", report.spread.median_us},
                         {"p95", report.spread.p95_us},
                         {"max", report.spread.max_us},
                         {"frames", report.spread.frames}}},
                       {"problems", alignment.problems},
                       {"cameras", per_camera}}},
                     {"calibration", cal.summary}};

  BuildOptions build = o.build;
  build.allow_missing = true;
  LightFieldVideoWriter writer(out, header);
  // Frame k is compressed and written while frame k + 1 is built: the two stages share the
  // cores, and neither waits on the other's serial parts.
  std::vector<ViewMap> maps;  // each camera's, made with the first frame
  std::future<void> writing;
  const auto finish_writing = [&] {
    if (writing.valid()) writing.get();
  };
  for (std::int64_t k = first; k < first + count; ++k) {
    const LightFieldFrame& frame = alignment.frames[std::size_t(k)];
    std::vector<CameraImage> images;
    for (const ShotImage& image : here.images) {
      const std::size_t c = std::size_t(image.row * cal.cols + image.col);
      const int i = frame.frame_of_camera[c];
      if (i < 0) continue;
      const FrameTime& f = image.frames[std::size_t(i)];
      const InputFile* stream = streams[c].get();
      images.push_back({image.row, image.col,
                        fmt::format("{} frame {} (sequence {})", stream->name(), i, f.sequence),
                        [stream, f] {
                          std::vector<std::uint8_t> bytes(f.size);
                          stream->read_exactly(bytes.data(), bytes.size(), f.offset);
                          return bytes;
                        }});
    }
    BuildReport frame_report;
    LightField lf = BuildLightFieldFromImages(
        scaled, images, fmt::format("in light field frame {}", k), build, &frame_report, &maps);
    report.filled_views += std::int64_t(frame_report.filled.size());
    lf.metadata()["recording"] = shot_name;
    lf.metadata()["frame"] = k;
    lf.metadata()["time_unix_ns"] = frame.time_ns;
    lf.metadata()["spread_us"] =
        frame.spread_ns ? nlohmann::json(double(*frame.spread_ns) / 1e3) : nlohmann::json();
    lf.metadata()["session"] = manifest.source;
    if (alignment.groups > 1) {
      // Staggered: the frame holds one group's cameras; the others' views are filled.
      nlohmann::json held = nlohmann::json::array();
      for (std::size_t c = 0; c < frame.frame_of_camera.size(); ++c)
        if (frame.frame_of_camera[c] >= 0) held.push_back({int(c) / cal.cols, int(c) % cal.cols});
      lf.metadata()["group"] = frame.group;
      lf.metadata()["groups"] = alignment.groups;
      lf.metadata()["cameras_held"] = std::move(held);
    }
    finish_writing();
    writing = std::async(std::launch::async,
                         [&writer, &o, &report,
                          info = VideoFrameInfo{k - first, frame.time_ns, frame.spread_ns, 0, 0},
                          built = std::make_shared<LightField>(std::move(lf))] {
                           writer.Append(*built, info, o.write);
                           ++report.frames;
                           if (o.frame_done) o.frame_done();
                         });
  }
  finish_writing();
  writer.Finish();
  report.bytes = writer.bytes();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace lfcam
