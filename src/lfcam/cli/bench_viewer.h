#pragma once
// `lfcam bench viewer --lightfield FILE.lf`: the viewer's frames of a still light field without a
// window (the headless figure): the view the viewer opens on, at its default integrator (or
// --integrator) and --aperture, the eye moving every frame, first across the array's plane and
// then in front of it (the cameras integrator's weight table built again every frame). On the GL
// backend each frame is rendered as the viewer renders it, into the renderer's output texture
// without reading it back; the wall-clock per frame (set-up, dispatch, the GPU's work) beside the
// GPU's own time, and the frames a second that makes.
#include "lfcam/core/lightfield.h"
#include "lfcam/render/frame_renderer.h"

namespace lfcam::cli {

inline constexpr int kMaxViewerFrames = 600;

struct ViewerBenchOptions {
  int width = 1920, height = 1080;
  double aperture_mm = 256;
  Integrator integrator = Integrator::kCamerasQuadrilinear;
  // Frames a path, after a warm-up frame: at least `min_frames`, and more until `min_seconds`
  // are spent, at most kMaxViewerFrames. The eye goes round its circle once in 60 frames.
  int min_frames = 5;
  double min_seconds = 1.0;
};

void BenchViewer(const LightField& lf, const ViewerBenchOptions& options,
                 const FrameRenderer& renderer, const FrameRenderOptions& render);

}  // namespace lfcam::cli
