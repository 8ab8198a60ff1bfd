#pragma once
// `lfcam render FILE --video OUT.mp4`: the flags that make a video of a light field (a camera
// path through saved views, or the camera flags' ranges swept; the frames of a light field
// video) and the command's work (share/video_render.h).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/cli/camera_flags.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/view_file.h"

namespace lfcam::cli {

struct VideoFlags {
  std::string out;                // --video
  std::vector<std::string> path;  // --path V1.json,V2.json,...
  int frames = 0;                 // --frames (0: the default)
  double fps = 0;                 // --fps (0: the video's rate, or 30)
  int crf = 18;
  std::string preset = "veryfast";

  // Adds the flags; returns --video's option.
  CLI::Option* AddTo(CLI::App& command);
  // Throws UsageError when a video flag is given without --video.
  void RequireNoVideoFlags() const;
  // The first view of --path, read (none without --path). Throws UsageError naming the file.
  std::optional<ViewSettings> FirstView() const;

 private:
  std::vector<CLI::Option*> options_;
};

struct VideoRenderInput {
  std::string lightfield;
  int first_frame = 0;
  std::string depth;  // --depth DIR
  bool antialias = false, quiet = false;
};

void RenderVideoCommand(const VideoRenderInput& input, const VideoFlags& video,
                        const CameraFlags& camera, FrameRenderOptions options, Backend backend);

}  // namespace lfcam::cli
