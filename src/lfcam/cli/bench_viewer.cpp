#include "lfcam/cli/bench_viewer.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "lfcam/render/benchmark_tables.h"
#include "lfcam/render/gl_renderer.h"
#include "lfcam/viewer/view_navigation.h"

namespace lfcam::cli {
namespace {

// One frame as the viewer renders it: on GL into the output texture (no read-back), on the CPU
// the image it draws. The wall-clock time, and the GPU's (negative on the CPU).
std::pair<double, double> ViewerFrame(const LightField& lf, const VirtualCameraParams& params,
                                      const FrameRenderer& renderer,
                                      const FrameRenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const VirtualCamera camera(params);
  double gpu_ms = -1;
  if (renderer.uses_gl())
    gpu_ms = renderer.gl()->RenderToTexture(lf, camera, GlOptions(options));
  else
    renderer.Render(lf, camera, options);
  return {
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
      gpu_ms};
}

}  // namespace

void BenchViewer(const LightField& lf, const ViewerBenchOptions& options,
                 const FrameRenderer& renderer, const FrameRenderOptions& render) {
  FrameRenderOptions o = render;
  o.integrator = options.integrator;
  VirtualCameraParams start = StartingView(lf, options.width, options.height);
  start.aperture_mm = options.aperture_mm;
  const Vec3 forward = (start.look_at - start.eye).normalized();
  const Vec3 right = forward.cross(start.up).normalized(), up = right.cross(forward);
  fmt::print("renderer: {}; viewer {}x{}, {}, d_l {} mm\n", renderer.description(), options.width,
             options.height, ToString(options.integrator), options.aperture_mm);
  fmt::print("{:<44} {:>7} {:>9} {:>9} {:>8} {:>10}\n", "eye moving every frame", "frames",
             "wall ms", "GPU ms", "wall/GPU", "frames/s");
  struct Path {
    const char* name;
    double forward_mm;  // the eye's distance in front of the opening view's
  };
  for (const Path& path : {Path{"across the array's plane (40 mm circle)", 0.0},
                           Path{"500 mm in front of it (40 mm circle)", 500.0}}) {
    std::vector<double> wall, gpu;
    double spent_ms = 0;
    // Frame -1: the warm-up (uploads, programs).
    for (int i = -1; i < kMaxViewerFrames; ++i) {
      if (i >= options.min_frames && spent_ms >= 1000.0 * options.min_seconds) break;
      const double angle = 2 * std::numbers::pi * std::max(i, 0) / 60.0;
      VirtualCameraParams p = start;
      const Vec3 move =
          path.forward_mm * forward + 40.0 * (std::cos(angle) * right + std::sin(angle) * up);
      p.eye += move;
      p.look_at += move;
      const auto [wall_ms, gpu_ms] = ViewerFrame(lf, p, renderer, o);
      if (i < 0) continue;
      spent_ms += wall_ms;
      wall.push_back(wall_ms);
      gpu.push_back(gpu_ms);
    }
    const double w = Median(wall), g = Median(gpu);
    fmt::print("{:<44} {:>7} {:>9.2f} {:>9} {:>8} {:>10.1f}\n", path.name, wall.size(), w,
               g >= 0 ? fmt::format("{:.2f}", g) : std::string("-"),
               g > 0 ? fmt::format("{:.2f}", w / g) : std::string("-"), 1000.0 / w);
  }
  fmt::print("wall ms: a frame's median wall-clock, {}; the viewer then draws it to its window\n",
             renderer.uses_gl()
                 ? "from its set-up to the GPU's last pass finished (the frame stays on the GPU, "
                   "in the renderer's output texture, as the viewer's)"
                 : "the CPU renderer's whole frame");
}

}  // namespace lfcam::cli
