#pragma once
// A depth map's labels and its reference view's colours laid out for a kernel vectorised across
// a row's samples (depth/local_planes.cpp, depth/weighted_median.cpp): planar float, each row
// padded by `radius` samples either side and to a whole number of vectors, so that any
// neighbour within `radius` of a run of samples is one contiguous load, with no bounds check.
// The padding's labels are NaN (no comparison passes: they take no part), its colours 0.
#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

namespace lfcam {

struct PaddedLabelMaps {
  int width = 0, height = 0, radius = 0;
  std::size_t stride = 0;  // floats a padded row
  std::vector<float> label, red, green, blue;
  // Where row y's sample x is: x + radius into the padded row.
  std::size_t At(int y, int x) const { return std::size_t(y) * stride + std::size_t(x + radius); }
};

// `label`: CV_32FC1; `guide_rgb8`: CV_8UC3 of the same size (checked by the caller); `lanes`:
// the kernel's vector length, in floats.
PaddedLabelMaps PadLabelMaps(const cv::Mat& label, const cv::Mat& guide_rgb8, int radius,
                             int lanes);

}  // namespace lfcam
