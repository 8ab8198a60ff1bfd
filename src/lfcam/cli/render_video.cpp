#include "lfcam/cli/render_video.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <mutex>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/parse.h"
#include "lfcam/cli/render_flags.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/core/progress.h"
#include "lfcam/share/video_render.h"

namespace lfcam::cli {
namespace {

constexpr int kStillVideoFrames = 60;
constexpr double kStillVideoFps = 30.0;

bool EndsWithMp4(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".mp4";
}

// The light field of each output frame: a still's one light field, or a video's frames read
// ahead into two slots (the one rendering, the next).
class FrameSource {
 public:
  FrameSource(const std::string& path, const LightFieldVideo& video, LightField first,
              int first_frame)
      : path_(path), video_(video), first_frame_(first_frame) {
    slots_[0] = std::move(first);
  }
  const LightField& At(int k) {
    if (!video_.is_video() || k == 0) return slots_[0];
    LightField& slot = slots_[std::size_t(k % 2)];
    slot = video_.ReadFrame(std::size_t(first_frame_ + k));
    return slot;
  }

 private:
  std::string path_;
  const LightFieldVideo& video_;
  int first_frame_;
  std::array<LightField, 2> slots_;
};

}  // namespace

CLI::Option* VideoFlags::AddTo(CLI::App& c) {
  auto* video = c.add_option(
      "--video", out,
      "Write an H.264 video (.mp4, docs/sharing.md) instead of an image: the camera along --path, "
      "or with ranges A:B swept (--focus-distance 3400:5200, --aperture, --focal-length, --eye, "
      "--look-at), of a still light field or across a light field video's frames");
  options_.push_back(
      c.add_option("--path", path,
                   "With --video: saved views (the viewer's F12 JSON files), comma-separated, in "
                   "order: the eye and the point looked at pass through each (a Catmull-Rom "
                   "spline), the lens is interpolated between them; camera flags given override "
                   "every view")
          ->delimiter(','));
  options_.push_back(c.add_option("--frames", frames,
                                  fmt::format("With --video: frames in the video (default: {} for "
                                              "a still light field; a light field video's frames "
                                              "from --frame on)",
                                              kStillVideoFrames))
                         ->check(CLI::Range(1, 1000000)));
  options_.push_back(
      c.add_option("--fps", fps,
                   "With --video: frames a second (default: the light field video's rate, or 30)")
          ->check(CLI::Range(0.01, 1000.0)));
  options_.push_back(c.add_option("--crf", crf,
                                  "With --video: x264's quality, 0 (lossless) to 51 (18 looks "
                                  "like the frames to most eyes)")
                         ->capture_default_str()
                         ->check(CLI::Range(0, 51)));
  options_.push_back(
      c.add_option("--preset", preset, "With --video: x264's speed preset (slower: smaller files)")
          ->capture_default_str()
          ->check(CLI::IsMember({"ultrafast", "superfast", "veryfast", "faster", "fast", "medium",
                                 "slow", "slower", "veryslow"})));
  return video;
}

void VideoFlags::RequireNoVideoFlags() const {
  for (const CLI::Option* option : options_)
    if (option->count() > 0)
      throw UsageError(fmt::format("{}: goes with --video OUT.mp4", option->get_name()));
}

std::optional<ViewSettings> VideoFlags::FirstView() const {
  if (path.empty()) return std::nullopt;
  return FlagValue("--path", [&] { return ReadViewFile(path.front()); });
}

void RenderVideoCommand(const VideoRenderInput& input, const VideoFlags& video,
                        const CameraFlags& camera, FrameRenderOptions options, Backend backend) {
  // The flags, the output and the path's views are checked before the light field is read.
  if (!EndsWithMp4(video.out))
    throw UsageError(fmt::format("--video {}: the file must end in .mp4", video.out));
  RequireWritableOutput(video.out, "--video");
  std::error_code ec;
  if (std::filesystem::equivalent(input.lightfield, video.out, ec))
    throw UsageError(fmt::format("--video {}: is the input light field", video.out));
  const CameraSweep sweep = camera.sweep();
  if (!video.path.empty()) {
    if (!camera.view_file.empty()) throw UsageError("--camera: not with --path (its views)");
    if (!sweep.empty()) throw UsageError("--path: not with a range A:B swept");
    if (video.path.size() < 2)
      throw UsageError(
          fmt::format("--path {}: a path needs two views or more (one view is --camera {})",
                      video.path[0], video.path[0]));
    for (const std::string& file : video.path) camera.WithView(file).Validate();
  }

  const LightFieldVideo source(input.lightfield);
  if (std::size_t(input.first_frame) >= source.frame_count())
    throw UsageError(fmt::format("--frame {}: {} has {} frame{}", input.first_frame,
                                 input.lightfield, source.frame_count(),
                                 source.frame_count() == 1 ? "" : "s"));
  const int available = int(source.frame_count()) - input.first_frame;
  int frames = video.frames;
  if (source.is_video()) {
    if (frames == 0) frames = available;
    if (frames > available)
      throw UsageError(fmt::format("--frames {}: {} has {} frames from --frame {}", frames,
                                   input.lightfield, available, input.first_frame));
  } else {
    if (frames == 0) frames = kStillVideoFrames;
    if (video.path.empty() && sweep.empty())
      throw UsageError(
          "--video of a still light field: nothing changes; give --path V1.json,V2.json or a "
          "range A:B (--focus-distance 3400:5200, --aperture, --focal-length, --eye, --look-at)");
  }
  Mp4Options mp4;
  mp4.fps = video.fps > 0 ? video.fps : source.is_video() ? source.header().fps : kStillVideoFps;
  mp4.crf = video.crf;
  mp4.preset = video.preset;

  LightField first = source.ReadFrame(std::size_t(input.first_frame));
  CameraPath path = CameraPath::Fixed(camera.MakeCamera(first).params());
  if (!video.path.empty()) {
    std::vector<VirtualCameraParams> keys;
    for (const std::string& file : video.path)
      keys.push_back(camera.WithView(file).MakeCamera(first).params());
    path = FlagValue("--path", [&] { return CameraPath::ThroughViews(keys, video.path); });
  } else if (!sweep.empty()) {
    path = CameraPath::Sweep(path.At(0), sweep);
  }
  const VirtualCameraParams start = path.At(0);
  // A size the video cannot have is a usage error (it says so); FFmpeg missing is not.
  RequireMp4Frame(start.width, start.height, mp4);

  DepthSet depth;
  if (options.interpolation == Interpolation::kDepth) {
    if (source.is_video() && frames > 1)
      throw UsageError(
          "--interpolation depth: depth maps belong to one light field frame; render a "
          "video's frames with --integrator cameras-quadrilinear, or one frame with --frame N");
    if (input.depth.empty()) {
      std::vector<VirtualCamera> cameras;
      for (int k = 0; k < frames; ++k) cameras.emplace_back(path.AtFrame(k, frames));
      depth = EstimateDepthForFrames(first, cameras, input.lightfield, input.quiet);
    } else {
      depth = ReadDepthSet(input.depth, first, DepthsForRendering());
    }
    options.depth = &depth;
    options.antialias = input.antialias;
  }

  const std::unique_ptr<FrameRenderer> renderer = BackendFlags::Open(backend);
  FrameSource frame_source(input.lightfield, source, std::move(first), input.first_frame);
  VideoRenderJob job;
  job.path = path;
  job.frames = frames;
  job.light_field = [&](int k) -> const LightField& { return frame_source.At(k); };
  job.render = options;
  job.mp4 = mp4;
  ProgressBar progress("rendering video", frames, ProgressWanted(input.quiet));
  job.progress = progress.callback();
  const VideoRenderReport report = RenderVideo(job, *renderer, video.out);
  progress.finish();
  fmt::print(
      "wrote {}: {} frames of {}x{} at {:g} fps ({:.2f} s), H.264 ({} crf {}, {}), {:.2f} MB; "
      "{:.1f} s ({:.1f} s rendering, {:.1f} s encoding alongside; {})\n",
      video.out, report.frames, start.width, start.height, mp4.fps, report.frames / mp4.fps,
      report.encoder, mp4.crf, mp4.preset, double(std::filesystem::file_size(video.out)) / 1e6,
      report.seconds, report.render_seconds, report.encode_seconds, renderer->description());
}

}  // namespace lfcam::cli
