#include "lfcam/cli/backend_flags.h"

#include <tuple>

#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"

namespace lfcam::cli {

void BackendFlags::AddTo(CLI::App& command) {
  command
      .add_option("--backend", backend,
                  "cpu (the vectorised renderer on every core), gl (the OpenGL compute shader, "
                  "headless through EGL, on a GPU or Mesa's llvmpipe) or auto (gl on a hardware "
                  "GPU, else cpu; says which)")
      ->capture_default_str();
  command
      .add_option("--workgroup", workgroup, "gl: the compute shader's work group, WxH invocations")
      ->capture_default_str();
}

Backend BackendFlags::Validate(FrameRenderOptions& options) const {
  const Backend b = FlagValue("--backend", [&] { return BackendFromString(backend); });
  std::tie(options.workgroup_x, options.workgroup_y) = ParseSize("--workgroup", workgroup, 1024);
  if (options.reference && b != Backend::kCpu)
    throw UsageError("--reference: the scalar reference is the cpu backend's (--backend cpu)");
  return b;
}

std::unique_ptr<FrameRenderer> BackendFlags::Open(Backend backend) {
  try {
    return std::make_unique<FrameRenderer>(backend);
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw Error("--backend " + ToString(backend) + ": " + e.what());
  }
}

}  // namespace lfcam::cli
