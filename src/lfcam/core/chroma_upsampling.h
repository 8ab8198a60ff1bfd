#pragma once
// JPEG keeps a picture's colour (the chroma, Cb and Cr) at a lower resolution than its brightness
// (the luma, Y): most encoders halve it both ways (4:2:0), the Raspberry Pi camera's and
// OpenCV's among them. A decoder interpolates the chroma back, so every colour edge comes out
// blurred over two pixels while the luma beside it is sharp. On a light field built from such
// images that blur is most of what separates its sharpest renders from those of a light field
// sampled directly (docs/fidelity.md, "The built light field against the truth").
//
// GuidedChromaToRgb brings the chroma back guided by the luma, which the file keeps whole:
//  1. locally, chroma is close to an affine function of luma (an edge between two colours is an
//     edge in both); the affine map of each 3 x 3 window of chroma samples is fitted to the luma
//     averaged the same way (the guided filter, regularised by `kChromaGuideEpsilon`), the maps
//     of the windows around each sample averaged, and applied to the full-resolution luma;
//  2. the result is corrected so that, averaged back over each chroma sample's pixels, it is the
//     chroma the file holds (back-projection, `kChromaBackProjections` rounds): nothing the
//     file recorded is contradicted, only what it left out is filled in.
// Where chroma is not a function of luma (two colours of one brightness) step 1 finds no slope
// and the result is the chroma interpolated, as a plain decoder would give it.
#include <opencv2/core.hpp>

namespace lfcam {

// The guided filter's regulariser, in 8-bit luma units squared: a window whose luma varies less
// than about this (noise) is given a flat chroma.
inline constexpr float kChromaGuideEpsilon = 16.0f;
inline constexpr int kChromaBackProjections = 3;

// Luma `y` (CV_8UC1, W x H) and chroma `cb`, `cr` (CV_8UC1, ceil(W / factor.width) x
// ceil(H / factor.height); each sample the average of its factor.width x factor.height luma
// pixels, as a JPEG encoder takes it; a factor of 1 or 2 each way) to R, G, B (CV_8UC3), through
// JFIF's full-range BT.601 conversion. A factor of 1 x 1 is the plain conversion.
cv::Mat GuidedChromaToRgb(const cv::Mat& y, const cv::Mat& cb, const cv::Mat& cr, cv::Size factor);

}  // namespace lfcam
