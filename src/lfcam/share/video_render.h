#pragma once
// `lfcam render --video`: the frames of a camera path (render/camera_path.h) rendered from a
// still light field or from the frames of a light field video, encoded into an MP4 as they come
// (share/mp4_writer.h). Rendering, encoding and reading the next light field frame overlap:
// frame k is encoded, and light field frame k + 1 read, while frame k + 1 renders.
#include <filesystem>
#include <functional>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/progress.h"
#include "lfcam/render/camera_path.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/share/mp4_writer.h"

namespace lfcam {

struct VideoRenderJob {
  CameraPath path;
  int frames = 60;
  // The light field output frame k is rendered from. Called in order, k = 0 .. frames - 1, from
  // a worker thread; returning the same light field again costs nothing more.
  std::function<const LightField&(int k)> light_field;
  FrameRenderOptions render;
  Mp4Options mp4;
  ProgressCallback progress;  // one unit a frame written
  // False: every frame is rendered and converted to sRGB but nothing is encoded or written
  // (`lfcam bench video`: what the encoding adds).
  bool encode = true;
};

struct VideoRenderReport {
  int frames = 0;
  double seconds = 0;         // wall clock, start to the file in place
  double render_seconds = 0;  // the renders alone (their sum)
  double encode_seconds = 0;  // sRGB conversion and H.264 encoding (their sum, overlapped)
  std::string encoder;
};

// Renders and writes the video; the file appears only when all of it is written (`out` is not
// touched when job.encode is false). Throws
// lfcam::Error (a frame's camera that makes no sense is named with its frame number).
VideoRenderReport RenderVideo(const VideoRenderJob& job, const FrameRenderer& renderer,
                              const std::filesystem::path& out);

}  // namespace lfcam
