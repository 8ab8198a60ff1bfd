#pragma once
// The GL light field renderer (`lfcam render --backend gl`): the CPU renderer's model, one
// compute-shader invocation a pixel (render/shaders/render_frame.comp), headless through EGL.
// The per-frame set-up of the virtual camera is the CPU renderer's (render/ray_setup.h, and the
// cameras integrator's weights from render/camera_integrator.h), computed once in C++; the
// shader does per-pixel work only.
//
// The light field lives on the GPU as one sRGB texture array, a layer a view, so the hardware
// decodes to linear light and filters within a view (the filter's weights are fixed point on
// most GPUs: 8 bits of a sample on NVIDIA's, hence a difference from the CPU renderer of a few
// thousandths of the contrast between neighbouring samples; render/gl_renderer_test.cpp bounds
// it). It is uploaded once and kept while the same light field is rendered.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/gpu/gl_context.h"
#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/quadrilinear_limit.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

struct GlRenderOptions {
  Integrator integrator = Integrator::kLensSamples;
  Interpolation interpolation = Interpolation::kQuadrilinear;
  int workgroup_x = 16, workgroup_y = 8;  // the compute shader's local size
  const DepthSet* depth = nullptr;        // Interpolation::kDepth: the views' depth maps
  bool antialias = false;                 // with it: rays over each pixel's area (as the CPU's)
  DepthBlend depth_blend = DepthBlend::kAgreeing;  // with it: the cameras blended
};

// The device's limits that decide what it can render.
struct GlLimits {
  int max_texture_size = 0, max_array_layers = 0;
  long long max_storage_block_bytes = 0;
  int max_workgroup_invocations = 0;
  long long dedicated_memory_kb = -1;  // where the driver says (NVIDIA), else -1
};

class GlRenderer {
 public:
  // Makes a GL 4.3 context (gpu/gl_context.h); throws lfcam::Error when there is none.
  explicit GlRenderer(bool prefer_hardware = true);
  // In a context made elsewhere (GlContext::AdoptCurrent: the viewer's window).
  explicit GlRenderer(std::unique_ptr<GlContext> context);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  const GlDeviceInfo& device() const { return context_->device(); }
  const GlLimits& limits() const { return limits_; }

  // Renders a frame into the renderer's output texture (RGBA32F, row 0 at the bottom: alpha
  // holds the rays that hit or the cameras read) without reading it back, and returns the GPU
  // time of the compute pass in milliseconds (a GL timer query; on a software GL, whose timer
  // queries do not see compute work, the wall-clock time from the dispatch to glFinish). Throws
  // lfcam::Error when the light field or the frame exceeds the device's limits, naming the limit.
  double RenderToTexture(const LightField& lf, const VirtualCamera& camera,
                         const GlRenderOptions& options);
  unsigned output_texture() const { return output_; }

  // Renders and reads the frame back as the CPU renderer returns it; `gpu_ms` is set.
  RenderResult Render(const LightField& lf, const VirtualCamera& camera,
                      const GlRenderOptions& options);

 private:
  void Upload(const LightField& lf);
  // Throws naming `what` when the driver says the GPU has less memory than `bytes` (NVIDIA's).
  void RequireGpuMemory(double bytes, const std::string& what) const;
  // A texture array of the light field's shape (n_s x n_t, a layer a view) in `format`, with
  // `filter` and clamped edges; throws naming `what` and its `bytes` when it does not fit.
  unsigned NewTextureArray(unsigned format, const LightFieldDims& d, int filter, double bytes,
                           const std::string& what);
  unsigned Program(int mode, bool view_windows, const GlRenderOptions& options);
  void EnsureOutput(int width, int height);
  // The depth lookup's frame (render/shaders/render_depth.comp): the depth maps uploaded as a
  // texture array (kept while the same set is rendered), then one invocation a pixel; the GPU
  // time as RenderToTexture's.
  double RenderDepth(const LightField& lf, const VirtualCamera& camera,
                     const GlRenderOptions& options);
  void UploadDepth(const DepthSet& depth);
  // Runs the bound program over the frame and times it (a timer query, or on a software GL the
  // wall-clock time to glFinish).
  double Dispatch(const VirtualCamera& camera, const GlRenderOptions& options);
  // Runs `passes` (GL commands) under the timer, waits for them, checks GL's errors naming
  // `what`, and returns their GPU milliseconds (a software GL's wall-clock).
  double Timed(const std::string& what, const std::function<void()>& passes);
  // The cameras integrator's weight table for a frame whose footprints differ (the eye off the
  // array's plane, a turned camera), built on the GPU into the weight-table buffer
  // (render/shaders/camera_weight_table.comp): the footprints' range found there and read back,
  // the layout CameraIntegratorFrame's, the entries and their normalisation computed there. Its
  // layout (levels without weights; empty when no pixel reaches the array), and its wall-clock
  // time in `ms`.
  std::vector<CameraIntegratorFrame::Level> BuildWeightTable(const LightField& lf,
                                                             const VirtualCamera& camera,
                                                             double* ms);
  // The quadrilinear limit's views: the views `read` of the uploaded light field filtered by the
  // prefilter's taps on the GPU (render/shaders/prefilter_views.comp), kept while the same
  // filter serves the next frame; the texture, and the pass's time in `ms` (0 when kept).
  unsigned Prefilter(const LightField& lf, const StPrefilter& prefilter,
                     const std::vector<bool>& read, double* ms);

  std::unique_ptr<GlContext> context_;
  GlLimits limits_;
  unsigned views_ = 0;  // the light field's texture array
  // The same storage seen as GL_RGB8, its sRGB codes read undecoded (8-bit light fields only):
  // the depth lookup's cubic reads interpolate the encoding (render/lightfield_sampler.h).
  unsigned views_encoded_ = 0;
  const void* uploaded_ = nullptr;  // whose samples it holds (address and buffer serial)
  std::uint64_t uploaded_serial_ = 0;
  LightFieldDims uploaded_dims_{};
  bool uploaded_srgb8_ = false;
  unsigned output_ = 0;  // the frame, RGBA32F
  int output_width_ = 0, output_height_ = 0;
  unsigned buffers_[6] = {0, 0, 0, 0, 0, 0};  // the shader's storage buffers
  unsigned timer_ = 0;
  std::map<std::string, unsigned> programs_;  // by mode, view windows and work group size
  long long last_lens_count_ = 0;
  std::string last_note_;          // what the last frame's path adds ("views prefiltered ...")
  unsigned filtered_[2] = {0, 0};  // the prefilter's passes: along s, then along t
  LightFieldDims filtered_dims_{};
  std::string filtered_key_;                // the light field, taps and views the second holds
  unsigned prefilter_buffers_[2] = {0, 0};  // taps, views
  unsigned range_buffer_ = 0;               // the weight table's range of footprints
  unsigned depth_maps_ = 0;                 // the depth lookup's maps, R32F, a layer a view
  const DepthSet* uploaded_depth_ = nullptr;
  LightFieldDims depth_dims_{};
};

}  // namespace lfcam
