#pragma once
// Image quality measures used by `lfcam compare` and the fidelity tests.
#include <opencv2/core.hpp>

namespace lfcam {

struct ImageComparison {
  double psnr_db = 0;         // over R, G, B of the 8-bit sRGB values; +inf when identical
  double ssim = 0;            // Wang et al. 2004 on luma (Rec. 601), 11x11 Gaussian, sigma 1.5
  double mean_abs_error = 0;  // per channel, 8-bit units
  long pixels = 0;            // pixels compared (inside the mask)
};

// Compares two 8-bit sRGB RGB images of the same size, over `mask` (CV_8UC1, nonzero = used)
// when it is not empty. Throws lfcam::Error when the sizes differ or the mask is empty.
ImageComparison CompareImages(const cv::Mat& a_srgb8, const cv::Mat& b_srgb8,
                              const cv::Mat& mask = {});

}  // namespace lfcam
