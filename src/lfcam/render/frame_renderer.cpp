#include "lfcam/render/frame_renderer.h"

#include <fmt/format.h>
#include <tbb/info.h>

#include "lfcam/core/error.h"
#include "lfcam/render/prefilter_cache.h"
#include "lfcam/render/simd_kernels.h"

namespace lfcam {
namespace {

std::string CpuDescription() {
  return fmt::format("cpu ({} cores, {})", tbb::info::default_concurrency(), KernelTargetName());
}

std::string GlDescription(const GlRenderer& gl) {
  return fmt::format("gl on {} (OpenGL {})", gl.device().renderer, gl.device().version);
}

}  // namespace

std::string ToString(Backend backend) {
  switch (backend) {
    case Backend::kCpu:
      return "cpu";
    case Backend::kGl:
      return "gl";
    case Backend::kAuto:
      return "auto";
  }
  return "?";
}

Backend BackendFromString(const std::string& name) {
  if (name == "cpu") return Backend::kCpu;
  if (name == "gl") return Backend::kGl;
  if (name == "auto") return Backend::kAuto;
  throw Error(fmt::format("unknown backend '{}' (expected cpu, gl or auto)", name));
}

FrameRenderer::FrameRenderer(Backend backend, bool in_current_context) {
  if (backend == Backend::kCpu) {
    description_ = CpuDescription();
    return;
  }
  const auto open = [&] {
    return in_current_context ? std::make_unique<GlRenderer>(GlContext::AdoptCurrent())
                              : std::make_unique<GlRenderer>();
  };
  if (backend == Backend::kGl) {
    gl_ = open();
    description_ = GlDescription(*gl_);
    return;
  }
  try {
    auto gl = open();
    if (!gl->device().software) {
      gl_ = std::move(gl);
      description_ = GlDescription(*gl_) + ": auto found a hardware GPU";
      return;
    }
    description_ =
        CpuDescription() + ": auto found only a software GL (" + gl->device().renderer + ")";
  } catch (const Error& e) {
    description_ = CpuDescription() + ": auto found no GL 4.3 context";
  }
}

GlRenderOptions GlOptions(const FrameRenderOptions& options) {
  GlRenderOptions o;
  o.integrator = options.integrator;
  o.interpolation = options.interpolation;
  o.workgroup_x = options.workgroup_x;
  o.workgroup_y = options.workgroup_y;
  o.depth = options.depth;
  o.antialias = options.antialias;
  o.depth_blend = options.depth_blend;
  return o;
}

RenderResult FrameRenderer::Render(const LightField& lf, const VirtualCamera& camera,
                                   const FrameRenderOptions& options) const {
  if (gl_) return gl_->Render(lf, camera, GlOptions(options));
  CpuRenderOptions o;
  o.integrator = options.integrator;
  o.interpolation = options.interpolation;
  o.threads = options.threads;
  o.reference = options.reference;
  o.progress = options.progress;
  o.depth = options.depth;
  o.antialias = options.antialias;
  o.depth_blend = options.depth_blend;
  o.prefilter_cache = prefilter_cache_.get();
  o.prefilter_memory = prefilter_memory_.get();
  return RenderLightFieldCpu(lf, camera, o);
}

void FrameRenderer::KeepPrefilteredViews() {
  if (!prefilter_cache_) prefilter_cache_ = std::make_unique<PrefilterCache>();
}

}  // namespace lfcam
