#pragma once
// The vectorised per-row kernels of the fast CPU renderer (Google Highway: compiled for every
// x86 and Arm instruction set Highway knows, the best one the machine has chosen at run time).
// A row of pixels is rendered in chunks of as many pixels as a vector holds: each pixel's ray
// coordinates come from the frame's projective set-up (ray_setup.h) in float, the samples are
// fetched as 8-bit words by gather and decoded through the sRGB table, and the taps are blended
// exactly as the scalar reference (lightfield_sampler.h) blends them.
#include <cstdint>
#include <string>

#include "lfcam/render/aperture_weights.h"
#include "lfcam/render/ray_setup.h"

namespace lfcam {

// Row buffers are padded to a multiple of this many pixels (at least the widest vector).
inline constexpr int kRowPadding = 64;
inline int PaddedRowWidth(int width) {
  return (width + kRowPadding - 1) / kRowPadding * kRowPadding;
}

// One row's output, planar, each PaddedRowWidth(width) long.
struct RowOutput {
  float* r;
  float* g;
  float* b;
  std::int32_t* count;  // rays that hit (lens samples) or cameras read (cameras)
};

// Pixel row j (bottom-up): the mean over the lens samples (setup.lens_uv/lens_st) of the
// quadrilinear or focal-plane lookup.
void RenderRowLensSamples(const RaySetup& setup, bool focal_plane, int j, const RowOutput& out);

// Pixel row j of the cameras integrator: either the same cameras and weights for every pixel
// (`uniform`, `uniform_count` of them), or per-pixel weights (`pixel_weights`: for each camera
// c in `cameras`, the weights of the row's pixels at pixel_weights[c * padded width + i]).
void RenderRowCameras(const RaySetup& setup, const GridCameraWeight* uniform, int uniform_count,
                      const float* pixel_weights, const int* cameras, int camera_count, int j,
                      const RowOutput& out);

// The most sample rows one camera's reads may span along a pixel row for
// RenderRowCamerasResampled (a camera turned against the array spans more). Each pixel blends
// only the rows its vector's tents reach, so the span costs the decode and resampling of its
// rows: beyond eight, the pixels' own reads cost less (docs/benchmarks.md, 2026-12-06).
inline constexpr int kMaxResampledRows = 8;

// Pixel row j of the cameras integrator, as RenderRowCameras, camera by camera with the
// separable frame's machinery (render/sample_rows-inl.h): the few sample rows a
// camera's reads span along the pixel row are decoded once and resampled along k, then each
// pixel blends them around its own l with its own weight. Returns false, having written
// nothing, when some camera's reads span more than kMaxResampledRows sample rows.
bool RenderRowCamerasResampled(const RaySetup& setup, const GridCameraWeight* uniform,
                               int uniform_count, const float* pixel_weights, const int* cameras,
                               int camera_count, int j, const RowOutput& out);

// rgb[3 i .. 3 i + 2] = r[i], g[i], b[i] for i < width: a planar row interleaved.
void InterleaveRow(const float* r, const float* g, const float* b, int width, float* rgb);

// The instruction set the kernels dispatch to on this machine (for example "AVX3").
std::string KernelTargetName();

}  // namespace lfcam
