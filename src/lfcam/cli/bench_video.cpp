#include "lfcam/cli/bench_video.h"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "lfcam/core/progress.h"
#include "lfcam/core/signal_cleanup.h"
#include "lfcam/share/video_render.h"

namespace lfcam::cli {

void BenchVideo(const LightField& lf, const FrameRenderer& renderer, Integrator integrator,
                Interpolation interpolation, int runs, bool quiet) {
  VirtualCameraParams camera;
  camera.width = camera.height = 1024;
  camera.eye = lf.slab().uv.center();
  camera.look_at = camera.eye - 1000.0 * lf.slab().uv.n_ca;
  camera.up = lf.slab().uv.v_ca;
  camera.focal_length_mm = 500;
  camera.aperture_mm = 192;
  CameraSweep sweep;
  sweep.focus_distance_mm = {{3400.0, 5200.0}};
  VideoRenderJob job;
  job.path = CameraPath::Sweep(camera, sweep);
  job.frames = 60;
  job.light_field = [&](int) -> const LightField& { return lf; };
  job.render.integrator = integrator;
  job.render.interpolation = interpolation;
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / fmt::format("lfcam-bench-video-{}.mp4", ::getpid());
  const TemporaryFileRegistration registration(out);
  fmt::print("renderer: {}; {} integrator, 60 frames of 1024^2 (Fig. 11 (a)'s sweep)\n",
             renderer.description(), ToString(integrator));
  std::vector<double> alone, encoded, encode_cpu;
  double bytes = 0;
  ProgressBar progress("timing", 2 * runs, ProgressWanted(quiet));
  for (int run = 0; run < runs; ++run) {
    job.encode = false;
    alone.push_back(RenderVideo(job, renderer, out).seconds);
    progress.advance(1);
    job.encode = true;
    const VideoRenderReport report = RenderVideo(job, renderer, out);
    encoded.push_back(report.seconds);
    encode_cpu.push_back(report.encode_seconds);
    bytes = double(std::filesystem::file_size(out));
    std::filesystem::remove(out);
    progress.advance(1);
  }
  progress.finish();
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double a = median(alone), e = median(encoded);
  fmt::print("{:>28} {:>8} {:>10}\n", "", "s", "ms a frame");
  fmt::print("{:>28} {:>8.2f} {:>10.1f}\n", "renders (sRGB, not encoded)", a, a / 60 * 1e3);
  fmt::print("{:>28} {:>8.2f} {:>10.1f}\n", "renders + H.264 (the file)", e, e / 60 * 1e3);
  fmt::print(
      "encoding adds {:+.1f}% (target: at most 10%); the encoder itself {:.1f} ms a frame "
      "on its thread; {:.2f} MB; medians of {} runs each, alternated\n",
      100.0 * (e - a) / a, median(encode_cpu) / 60 * 1e3, bytes / 1e6, runs);
}

}  // namespace lfcam::cli
