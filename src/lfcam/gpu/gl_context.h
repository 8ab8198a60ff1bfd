#pragma once
// A headless OpenGL 4.3+ core context through EGL: no window, no X server. The GL renderer
// (render/gl_renderer.h) computes in it; the viewer will share its shaders.
//
// The display is chosen among EGL's devices (EGL_EXT_device_enumeration): a hardware GPU first,
// Mesa's software rasteriser (llvmpipe) last; where the driver enumerates no devices, Mesa's
// surfaceless platform, then the default display. The context is made current on the thread
// that creates it; call MakeCurrent() before using it on another.
#include <memory>
#include <string>

namespace lfcam {

struct GlDeviceInfo {
  std::string renderer;   // GL_RENDERER, for example "NVIDIA H100 80GB HBM3/PCIe/SSE2"
  std::string vendor;     // GL_VENDOR
  std::string version;    // GL_VERSION
  bool software = false;  // a CPU rasteriser (llvmpipe, softpipe, swrast)
};

class GlContext {
 public:
  // Throws lfcam::Error naming what is missing (no EGL, no display, no GL 4.3 core context)
  // when none can be made. With `prefer_hardware` false the software rasteriser is taken first
  // when there is one.
  static std::unique_ptr<GlContext> Create(bool prefer_hardware = true);
  // The context current on this thread, made by someone else (the viewer's window): used, never
  // destroyed or switched. Throws lfcam::Error when none is current or it is older than 4.3.
  static std::unique_ptr<GlContext> AdoptCurrent();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void MakeCurrent() const;
  const GlDeviceInfo& device() const { return device_; }

 private:
  GlContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  bool owned_ = true;
  GlDeviceInfo device_;
};

}  // namespace lfcam
