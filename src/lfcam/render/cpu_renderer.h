#pragma once
// The CPU light field renderer: the paper's virtual camera (§6) over a light field,
// multithreaded with oneTBB. Two implementations of one model: the scalar reference (one
// pixel at a time, every ray intersected in double precision: the readable definition the
// other paths are tested against) and the fast path (whole rows at a time from the frame's
// projective ray set-up, vectorised with Highway: render/simd_kernels.h).
#include <opencv2/core.hpp>
#include <string>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/lightfield_sampler.h"
#include "lfcam/render/virtual_camera.h"
#include "lfcam/render/window_taper.h"

namespace lfcam {

class PrefilterCache;
class PrefilterMemory;

// How a pixel integrates over the aperture.
enum class Integrator {
  kLensSamples,  // the paper's: the average over n_ls lens samples (with either lookup)
  kCameras,      // the limit of lens samples with the focal-plane lookup (camera_integrator.h)
  // The limit of lens samples with the quadrilinear lookup (the paper's own estimator): the
  // cameras integrator over views prefiltered by the hat scaled by k (quadrilinear_limit.h).
  kCamerasQuadrilinear,
};
std::string ToString(Integrator integrator);
Integrator IntegratorFromString(const std::string& name);  // throws lfcam::Error

struct CpuRenderOptions {
  int threads = 0;  // 0: all cores; 1: the paper's single-threaded CPU column
  Interpolation interpolation = Interpolation::kQuadrilinear;  // the paper's (lens samples)
  ProgressCallback progress;  // told the pixels done, tile by tile (may be empty)
  Integrator integrator = Integrator::kLensSamples;
  // The scalar reference instead of the vectorised kernels (which also stand back for it where
  // they cannot read the light field: see RowKernelsSupport and FastKernelsSupport).
  bool reference = false;
  // The views' depth maps, for Interpolation::kDepth (which the scalar path renders, on every
  // core): a map for every camera the frame reads (DepthViewsNeeded).
  const DepthSet* depth = nullptr;
  // With the depth lookup: spread each pixel's rays over its area on the film (a sensor pixel's
  // box filter) instead of through its centre (the paper's pixel).
  bool antialias = false;
  // With the depth lookup: which cameras are blended (render/depth_aware_sampler.h).
  DepthBlend depth_blend = DepthBlend::kAgreeing;
  // The quadrilinear limit's filtered copy kept from frame to frame (render/prefilter_cache.h;
  // the viewer's), or none: each frame filters what it reads.
  PrefilterCache* prefilter_cache = nullptr;
  // Without it, the memory the filtered copy is made in kept from frame to frame
  // (render/prefilter_memory.h), or none: each frame's copy in fresh pages.
  PrefilterMemory* prefilter_memory = nullptr;
  // The cameras integrator: each camera counted by the share of its tent inside its view's
  // window (render/window_taper.h) rather than wholly or not at all. The quadrilinear limit sets
  // it for its filtered copy; none: the hard edges of the focal-plane reads.
  const WindowTaper* window_taper = nullptr;
};

struct RenderResult {
  cv::Mat image;           // linear RGB, CV_32FC3, row 0 at the top
  cv::Mat hit_mask;        // CV_8UC1: 255 where at least one ray hit the slab
  cv::Mat counts;          // CV_32SC1: the rays that hit (cameras integrator: cameras read)
  long long rays = 0;      // rays cast (cameras integrator: camera reads)
  long long rays_hit = 0;  // rays that met both windows (cameras integrator: camera reads)
  // How it was rendered: "reference", or the vectorised kernels as "separable" (whole views
  // resized: render/separable_frame.h) or "rows" (per-pixel rays), with the instruction set,
  // for example "separable (AVX3)".
  std::string path;
  double gpu_ms = -1;  // the GL renderer: the compute pass's time from a GL timer query
};

RenderResult RenderLightFieldCpu(const LightField& lf, const VirtualCamera& camera,
                                 const CpuRenderOptions& options = {});

}  // namespace lfcam
