#pragma once
// How the plane sweep reads its views, shared by the two halves of depth/cost_volume.h: the views
// prepared (depth/sweep_views.cpp) and swept (depth/cost_volume.cpp).
#include <array>
#include <opencv2/core.hpp>

#include "lfcam/depth/cost_volume.h"

namespace lfcam::sweep {

// The channels compared: R, G, B (sRGB, 0 .. 1), the grey level's x and y gradients.
inline constexpr int kChannels = 5;
inline constexpr int kHalves = 8;      // half-arrays, their directions 45 degrees apart
inline constexpr int kSubArrays = 16;  // and quarter-arrays in the same directions (cost_volume.h)
static_assert(kChannels == ShiftedSweep::kChannels && kHalves == ShiftedSweep::kHalves &&
              kSubArrays == ShiftedSweep::kSubArrays);
// The packed channels' units: sRGB levels exactly (0 .. 255); gradients (at most 1 in size) in
// steps of 1/8192, finer than an 8-bit grey level's gradient (1/2040).
inline constexpr std::array<float, kChannels> kPacked = {255.0f, 255.0f, 255.0f, 8192.0f, 8192.0f};
static_assert(kPacked[0] == SweepViews::kPackedColour && kPacked[1] == SweepViews::kPackedColour &&
              kPacked[2] == SweepViews::kPackedColour);

// The weights of a read at fraction f of a sample (taps at -1 - f, -f, 1 - f, 2 - f): Keys'
// cubic, or with `read_sigma` > 0 a Gaussian of that many samples tapered to zero at 2 samples
// (cos^2), normalised. Keys' kernel passes a sample's noise whole at f = 0 and 0.64 of its
// variance at f = 0.5 (0.41 in two dimensions), so on noisy views the planes at which the
// farther views fall between samples match better by that alone; the Gaussian passes nearly the
// same share at every fraction (docs/depth.md, "Noisy views").
std::array<float, 4> ReadWeights(double f, double read_sigma);

// Whether the homography m is a shift (to within rounding).
bool IsShift(const cv::Matx33d& m);
// Whether it is a scale and a shift along each axis, both scales positive (SweepViews::Homography
// makes such a view's exactly so: a camera nearer to or farther from the st-plane than the
// reference's); a shift is one.
bool IsScaledShift(const cv::Matx33d& m);

}  // namespace lfcam::sweep
