#pragma once
// `render`'s flags beyond the camera's: the integrator and the lookup, the depth maps the depth
// lookup reads, the CPU's threads and reference renderer. Shared by `lfcam render` and the
// Python module's lfcam.render (cli/keyword_arguments.h), so both take the same defaults,
// limits and messages.
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/camera_flags.h"
#include "lfcam/cli/keyword_arguments.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/view_file.h"

namespace lfcam::cli {

struct RenderOptionFlags {
  std::string integrator = "lens-samples", interpolation = "quadrilinear";
  std::string depth;                     // --depth DIR: the views' depth maps (`lfcam depth --all`)
  std::string depth_blend = "agreeing";  // --depth-blend
  int threads = 0;
  bool reference = false, antialias = false;

  void AddTo(CLI::App& command);
  // The options the flags say, over a saved view's integrator and lookup where the flags do not
  // say them (`view`: --camera's or a path's first). Throws UsageError naming the flag.
  FrameRenderOptions Resolve(const std::optional<ViewSettings>& view) const;
  // --depth and --antialias go with --interpolation depth, which goes with lens samples.
  void CheckDepthFlags(const FrameRenderOptions& options) const;

 private:
  CLI::Option* integrator_option_ = nullptr;
  CLI::Option* interpolation_option_ = nullptr;
  CLI::Option* depth_blend_option_ = nullptr;
};

// What a caller of render asks for with keyword arguments (the Python module's lfcam.render).
struct RenderRequest {
  std::unique_ptr<CLI::App> parser;  // the flags keep pointers into it: kept with them
  CameraFlags camera;
  RenderOptionFlags render;
  BackendFlags backend;
  FrameRenderOptions options;  // resolved from the flags
  Backend chosen_backend = Backend::kCpu;
};

// The keywords through `lfcam render`'s own flags (cli/keyword_arguments.h). Throws UsageError
// with the keyword's name. Heap-held: the flags' parser keeps pointers into it.
std::unique_ptr<RenderRequest> ParseRenderKeywords(const std::vector<KeywordArgument>& arguments);

// The depth maps every view the cameras read needs, estimated; unless `quiet`, with a progress
// bar and a line on stderr saying how to keep them (`input`: the light field's file).
DepthSet EstimateDepthForFrames(const LightField& lf, const std::vector<VirtualCamera>& cameras,
                                const std::string& input, bool quiet);

}  // namespace lfcam::cli
