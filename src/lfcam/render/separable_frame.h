#pragma once
// The separable frame: the common case where a frame is a weighted sum of resized views.
//
// When the eye is on the array's plane and the camera looks along the array's normal (the
// paper's Tables 1 and 2, and most renders), the pieces of every pixel's estimate do not vary
// from pixel to pixel: each lens sample lies on the uv-plane, so its rays meet the uv-plane at
// the lens sample itself and read the same four cameras with the same weights everywhere, and
// the cameras integrator's footprint is the lens itself. What varies is only where each camera
// is read on the st-plane, and with the plane of focus parallel to the st-plane and the axes
// aligned, the sample column k depends on the pixel column alone and the sample row l on the
// pixel row alone, both affinely. Every term of the estimate is then a view resized by a
// bilinear filter whose taps are separable: each needed sample row is decoded once, resampled
// along the row, and blended into the output rows, with no per-pixel gathers from the whole
// light field (render/separable_kernels.cpp).
//
// The maps are computed per pixel column and row in double precision, exactly as the scalar
// reference computes each ray; the result agrees with it up to float rounding.
#include <cstdint>
#include <optional>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// One axis's bilinear read for every pixel along it (columns or rows), for one line origin.
struct AxisMap {
  std::vector<std::int32_t> i0, i1;  // the two samples read (i1 = i0 or i0 + 1)
  std::vector<float> w0, w1;         // their weights, zero where the line leaves the domain
  std::vector<float> inside;         // 1 where the line meets the sampled domain along this axis
  int lo = 0, hi = 0;                // every sample read lies in [lo, hi]
};

// The lines from one origin (a lens sample, a camera centre, the eye) through every pixel's
// point in focus, mapped on the st-plane.
struct SeparableOrigin {
  AxisMap k;  // over the pixel columns i (padded to PaddedRowWidth with zero weights)
  AxisMap l;  // over the pixel rows j (bottom-up)
};

// view * weight, read along the lines from origin `read`, counted where the lines from origin
// `mask` meet the st domain.
struct SeparableTerm {
  int view = 0;  // row-major camera index
  int read = 0, mask = 0;
  float weight = 0;
};

struct SeparableFrame {
  std::vector<SeparableOrigin> origins;
  std::vector<SeparableTerm> terms;
  // Lens samples: the pixel is the mean over these origins (each a lens sample whose rays meet
  // the array window) of their terms, counted where each meets the st domain. The cameras
  // integrator: empty, and every term is masked by the eye (origin `eye`).
  std::vector<int> hit_origins;
  int eye = -1;
  int reads_per_pixel = 0;  // the cameras integrator: cameras read where the eye's line hits
  int width = 0, height = 0;
};

// The separable form of the frame, or nothing when the frame is not separable (an eye off the
// array's plane, a turned camera, a tilted st-plane) or the light field cannot be read by the
// fast kernels.
std::optional<SeparableFrame> MakeSeparableFrame(const LightField& lf, const VirtualCamera& camera,
                                                 const CpuRenderOptions& options);

}  // namespace lfcam
