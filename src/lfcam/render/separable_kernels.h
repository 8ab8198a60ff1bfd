#pragma once
// The vectorised kernels of the separable frame (render/separable_frame.h): a band of output
// rows as a weighted sum of resized views. For each term, the sample rows the band needs are
// decoded once through the sRGB table, resampled along the row with the term's column map, and
// blended into the band's rows with its row map.
#include <cstdint>

#include "lfcam/render/ray_setup.h"
#include "lfcam/render/separable_frame.h"

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

}  // namespace lfcam
