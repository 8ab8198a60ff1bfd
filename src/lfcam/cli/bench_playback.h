#pragma once
// `lfcam bench playback --lightfield VIDEO.lfv`: the viewer's playback without a window (the
// headless figure): the video plays from frame 0 for a few seconds through the viewer's own
// decoder (viewer/video_playback.h) and frame scheduler (viewer/frame_scheduler.h) at the
// viewer's window size, and the frames drawn a second, their resolution and the frames skipped
// are printed.
#include <string>

#include "lfcam/render/frame_renderer.h"

namespace lfcam::cli {

struct PlaybackBenchOptions {
  std::string video;
  int width = 1280, height = 960;  // the viewer's default window
  double seconds = 5;
  Integrator integrator = Integrator::kCameras;
  double aperture_mm = 0;
  bool quiet = false;
};

void BenchPlayback(const PlaybackBenchOptions& options, const FrameRenderer& renderer,
                   const FrameRenderOptions& render);

}  // namespace lfcam::cli
