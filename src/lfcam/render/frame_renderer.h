#pragma once
// One front over the two backends (`--backend cpu|gl|auto`): `lfcam render`, `lfcam bench` and
// the viewer render through it. `auto` takes the GL renderer when EGL offers a hardware GPU and
// the CPU renderer otherwise (Mesa's llvmpipe runs the shader on the CPU too, slower than the
// CPU renderer itself), and says which and why.
#include <memory>
#include <string>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/gl_renderer.h"
#include "lfcam/render/prefilter_cache.h"
#include "lfcam/render/prefilter_memory.h"

namespace lfcam {

enum class Backend { kCpu, kGl, kAuto };
std::string ToString(Backend backend);
Backend BackendFromString(const std::string& name);  // throws lfcam::Error

struct FrameRenderOptions {
  Integrator integrator = Integrator::kLensSamples;
  Interpolation interpolation = Interpolation::kQuadrilinear;
  int threads = 0;                                 // CPU: 0 = all cores
  bool reference = false;                          // CPU: the scalar reference
  int workgroup_x = 16, workgroup_y = 8;           // GL
  ProgressCallback progress;                       // CPU only
  const DepthSet* depth = nullptr;                 // Interpolation::kDepth
  bool antialias = false;                          // with it (CpuRenderOptions::antialias)
  DepthBlend depth_blend = DepthBlend::kAgreeing;  // with it: the cameras blended
};

// The GL renderer's share of the options.
GlRenderOptions GlOptions(const FrameRenderOptions& options);

class FrameRenderer {
 public:
  // Opens the backend; kGl throws lfcam::Error when no GL 4.3 context can be made. With
  // `in_current_context` the GL renderer uses the context current on this thread (the viewer's
  // window) instead of making its own.
  explicit FrameRenderer(Backend backend, bool in_current_context = false);
  bool uses_gl() const { return gl_ != nullptr; }
  GlRenderer* gl() const { return gl_.get(); }
  // What renders, for people: "gl on NVIDIA H100 80GB HBM3/PCIe/SSE2 (OpenGL 4.6.0 NVIDIA
  // 580.159.04)" or "cpu (2 cores, AVX3)", and with auto, why.
  const std::string& description() const { return description_; }

  RenderResult Render(const LightField& lf, const VirtualCamera& camera,
                      const FrameRenderOptions& options) const;

  // On the CPU, keep the quadrilinear limit's filtered views from frame to frame, as the GL
  // renderer keeps them (render/prefilter_cache.h): for a renderer that draws many frames of one
  // light field (the viewer). A frame at a focus already filtered then costs its render alone.
  void KeepPrefilteredViews();

 private:
  std::unique_ptr<GlRenderer> gl_;
  std::unique_ptr<PrefilterCache> prefilter_cache_;
  // Without the cache, the filtered copy's memory (render/prefilter_memory.h).
  std::unique_ptr<PrefilterMemory> prefilter_memory_ = std::make_unique<PrefilterMemory>();
  std::string description_;
};

}  // namespace lfcam
