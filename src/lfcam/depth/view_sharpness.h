#pragma once
// How much of a view's texture lies near its sampling limit: the share of its spectral power
// (grey levels, the middle three quarters of the frame, Hann-windowed, the mean left out) at
// frequencies of 0.35 to 0.5 cycles a sample along x or y, of all its power above 0.02 cycles a
// sample. A view whose edges are sharper than its sampling (a render antialiased only by a box
// over its pixel, a synthetic texture) has much there; optics' blur and a good antialiasing
// filter leave little. Keys' cubic blurs such content by an amount that depends on a read's
// fraction of a sample, so the sweep's planes at which views fall on whole samples match better
// by that alone (docs/depth.md, "Sharp views"). Measured there: `hci-antinous`' centre view
// 0.0055, `lytro-2067`'s 0.0087, `shop-center-9x9`'s JPEG photographs 0.015, the `paper`
// scene's views (3 x 3 rays a sample) 0.040.
#include <opencv2/core.hpp>

namespace lfcam {

// `rgb8`: CV_8UC3 (or CV_8UC1). 0 for an image smaller than 16 x 16 or without texture.
double NearNyquistShare(const cv::Mat& rgb8);

}  // namespace lfcam
