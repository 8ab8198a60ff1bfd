#pragma once
// The renderer flags shared by `render`, `bench` and `view`: --backend, --workgroup (and the
// CPU's --threads and --reference where the command has them).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "lfcam/render/frame_renderer.h"

namespace lfcam::cli {

struct BackendFlags {
  std::string backend = "cpu";  // the commands' default (view: auto)
  std::string workgroup = "16x8";

  void AddTo(CLI::App& command);
  // --backend and --workgroup checked (UsageError naming the flag), into `options`.
  Backend Validate(FrameRenderOptions& options) const;
  // Opens the backend; no GL context for --backend gl is an Error naming the flag.
  static std::unique_ptr<FrameRenderer> Open(Backend backend);
};

}  // namespace lfcam::cli
