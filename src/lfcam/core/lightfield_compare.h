#pragma once
// Comparing two light fields of the same shape view by view, as `lfcam compare` does images.
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/lightfield.h"

namespace lfcam {

struct LightFieldComparison {
  ImageComparison all;  // over every sample of every view (PSNR from the pooled error)
  double worst_view_psnr_db = 0;
  int worst_row = 0, worst_col = 0;
};

// Both light fields must be 8-bit sRGB with the same dimensions (throws lfcam::Error otherwise).
// The SSIM is the mean of the views'.
LightFieldComparison CompareLightFields(const LightField& a, const LightField& b);

}  // namespace lfcam
