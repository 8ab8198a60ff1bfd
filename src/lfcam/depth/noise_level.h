#pragma once
// How noisy a photograph is: its sensor noise's standard deviation in 8-bit levels. Immerkær's
// estimate (1996: the mean absolute response to a difference of two Laplacians, which cancels
// planes and ramps) taken over the flattest part of the image only (the samples with the smallest
// Sobel gradients, after Tai and Yang 2008), so that texture does not count as noise; each colour
// channel apart, then their mean. Measured (docs/depth.md, "Noisy views"): a clean render 0.4,
// the same with Gaussian noise of 1.5, 2.5 and 5 levels added 1.6, 2.6 and 5.0.
#include <opencv2/core.hpp>

namespace lfcam {

// `rgb8`: CV_8UC3 (or CV_8UC1). `flattest_share`: the share of the samples that counts. 0 for an
// image smaller than 3 x 3.
double NoiseLevel(const cv::Mat& rgb8, double flattest_share = 0.3);

}  // namespace lfcam
