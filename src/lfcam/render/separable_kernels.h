#pragma once
// The vectorised kernels of the separable frame (render/separable_frame.h): a band of output
// rows as a weighted sum of resized views. For each term, the sample rows the band needs are
// decoded once through the sRGB table, resampled along the row with the term's column map, and
// blended into the band's rows with its row map.
#include <cstdint>

#include "lfcam/render/ray_setup.h"
#include "lfcam/render/separable_frame.h"
#include "lfcam/render/simd_kernels.h"

namespace lfcam {

// Pixel rows [j0, j1) (bottom-up). Each output array holds (j1 - j0) rows of
// PaddedRowWidth(frame.width) values, row j at (j - j0) * padded.
struct BandOutput {
  float* r;
  float* g;
  float* b;
  std::int32_t* count;  // rays that hit (lens samples) or cameras read (cameras)
};
void RenderSeparableBand(const SeparableFrame& frame, const RaySetup& source, int j0, int j1,
                         const BandOutput& out);

// The most sample rows one camera's reads may span along a pixel row for
// RenderRowCamerasResampled (a camera turned against the array spans more).
inline constexpr int kMaxResampledRows = 4;

// Pixel row j of the cameras integrator (the same arguments as RenderRowCameras in
// simd_kernels.h), camera by camera with the separable frame's machinery: the few sample rows a
// camera's reads span along the pixel row are decoded once and resampled along k, then each
// pixel blends them around its own l with its own weight. Returns false, having written
// nothing, when some camera's reads span more than kMaxResampledRows sample rows.
bool RenderRowCamerasResampled(const RaySetup& setup, const GridCameraWeight* uniform,
                               int uniform_count, const float* pixel_weights, const int* cameras,
                               int camera_count, int j, const RowOutput& out);

}  // namespace lfcam
