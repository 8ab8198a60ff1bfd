#pragma once
// `lfcam export FILE --format quilt --out DIR`: a Looking Glass quilt (share/quilt.h) of a still
// light field as a PNG, or of a light field video as an H.264 MP4 of quilts, named
// STEM_qs{cols}x{rows}a{aspect}.png|.mp4, with quilt.json (the display, the layout, the
// baseline and the plane of zero parallax) and each view's camera as a saved view
// (cameras/view_KK.json, for `lfcam render --camera`). The folder appears whole or not at all.
#include <filesystem>
#include <functional>
#include <string>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/progress.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/share/quilt.h"

namespace lfcam {

struct QuiltExportJob {
  QuiltPreset preset;
  VirtualCameraParams centre;  // the middle camera (its focus distance: zero parallax)
  double baseline_mm = 0;
  FrameRenderOptions render;
  std::string stem = "lightfield";
  bool video = false;  // an MP4 of `frames` quilts at `fps`
  int frames = 1;
  double fps = 30;
  // The light field of frame k (called in order).
  std::function<const LightField&(int k)> light_field;
  ProgressCallback progress;  // one unit a view rendered
};

struct QuiltExportReport {
  std::filesystem::path file;  // the quilt, inside the folder
  QuiltLayout layout;
  int frames = 0;
};

QuiltExportReport ExportQuilt(const QuiltExportJob& job, const FrameRenderer& renderer,
                              const std::filesystem::path& out_dir);

}  // namespace lfcam
