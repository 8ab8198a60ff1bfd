#include "lfcam/share/video_render.h"

#include <fmt/format.h>

#include <chrono>
#include <future>
#include <optional>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"

namespace lfcam {
namespace {

double VideoSecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VirtualCamera FrameCamera(const CameraPath& path, int k, int frames) {
  try {
    return VirtualCamera(path.AtFrame(k, frames));
  } catch (const Error& e) {
    throw Error(fmt::format("video frame {} of {}: {}", k, frames, e.what()));
  }
}

}  // namespace

VideoRenderReport RenderVideo(const VideoRenderJob& job, const FrameRenderer& renderer,
                              const std::filesystem::path& out) {
  if (job.frames < 1) throw Error("a video needs at least one frame");
  const auto start = std::chrono::steady_clock::now();
  // Every frame's camera first: a path that fails half-way fails before any work.
  std::vector<VirtualCamera> cameras;
  cameras.reserve(std::size_t(job.frames));
  for (int k = 0; k < job.frames; ++k) cameras.push_back(FrameCamera(job.path, k, job.frames));
  std::optional<Mp4Writer> writer;
  VideoRenderReport report;
  if (job.encode) {
    writer.emplace(out, cameras[0].width(), cameras[0].height(), job.mp4);
    report.encoder = writer->encoder_name();
  }

  std::future<const LightField*> next_lf =
      std::async(std::launch::async, [&] { return &job.light_field(0); });
  std::future<double> encoding;  // seconds the previous frame took to encode
  for (int k = 0; k < job.frames; ++k) {
    const LightField& lf = *next_lf.get();
    if (k + 1 < job.frames)
      next_lf = std::async(std::launch::async, [&job, k] { return &job.light_field(k + 1); });
    const auto render_start = std::chrono::steady_clock::now();
    RenderResult result = renderer.Render(lf, cameras[std::size_t(k)], job.render);
    report.render_seconds += VideoSecondsSince(render_start);
    if (encoding.valid()) {
      report.encode_seconds += encoding.get();
      if (job.progress) job.progress(1);
    }
    encoding = std::async(std::launch::async, [&writer, image = std::move(result.image)] {
      const auto encode_start = std::chrono::steady_clock::now();
      const cv::Mat frame = LinearToSrgb8Image(image);
      if (writer) writer->Write(frame);
      return VideoSecondsSince(encode_start);
    });
  }
  report.encode_seconds += encoding.get();
  if (job.progress) job.progress(1);
  const auto finish_start = std::chrono::steady_clock::now();
  if (writer) writer->Finish();
  report.encode_seconds += VideoSecondsSince(finish_start);
  report.frames = job.frames;
  report.seconds = VideoSecondsSince(start);
  return report;
}

}  // namespace lfcam
