#include "lfcam/cli/bench_playback.h"

#include <fmt/core.h>

#include <thread>

#include "lfcam/viewer/frame_scheduler.h"
#include "lfcam/viewer/video_playback.h"
#include "lfcam/viewer/view_navigation.h"

namespace lfcam::cli {

void BenchPlayback(const PlaybackBenchOptions& options, const FrameRenderer& renderer,
                   const FrameRenderOptions& render) {
  using Clock = VideoPlayback::Clock;
  VideoPlayback playback(options.video);
  ViewSettings view;
  view.camera = StartingView(*playback.current(), options.width, options.height);
  view.camera.aperture_mm = options.aperture_mm;
  view.integrator = options.integrator;
  const double period_ms = 1000.0 / playback.fps();
  // As the viewer plays: the frame budget is the frame period (its default, 40 ms, at most).
  FrameScheduler scheduler(playback.current(), renderer, render, std::min(40.0, period_ms));
  scheduler.SetLightField(playback.current(), playback.current_index());
  fmt::print("renderer: {}; {} at {} fps, {} frames; viewer {}x{}, {}{}\n", renderer.description(),
             options.video, playback.fps(), playback.frames(), options.width, options.height,
             ToString(options.integrator),
             options.aperture_mm > 0 ? fmt::format(", d_l {} mm", options.aperture_mm) : "");
  // Warm up at rest (the first full frame's cost sets the scale while playing).
  while (!scheduler.converged(view)) {
    scheduler.Update(view, false);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const Clock::time_point start = Clock::now();
  playback.Play(start);
  std::int64_t drawn = 0, last = scheduler.shown_index();
  double scale_sum = 0;
  while (Clock::now() - start < std::chrono::duration<double>(options.seconds)) {
    if (playback.Tick()) scheduler.SetLightField(playback.current(), playback.current_index());
    scheduler.Update(view, true);
    if (scheduler.shown_index() != last) {
      last = scheduler.shown_index();
      ++drawn;
      scale_sum += scheduler.shown_scale();
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const auto passed = std::int64_t(seconds * playback.fps());
  fmt::print(
      "kept {:.1f} of {:g} frames a second over {:.1f} s, at {:.0f}% resolution on average: {} of "
      "the {} frames the clock passed drawn ({} never decoded in time); decoding {:.1f} ms a "
      "frame\n",
      double(drawn) / seconds, playback.fps(), seconds, drawn ? 100.0 * scale_sum / drawn : 0.0,
      drawn, passed, playback.skipped(), playback.decode_ms());
}

}  // namespace lfcam::cli
