#pragma once
// A float plane read bilinearly between its samples (the depth steps that read a view at the
// point a map says, one sample at a time).
#include <algorithm>
#include <opencv2/core.hpp>

namespace lfcam {

// Plane `m` (CV_32FC1) at (x, y) into `out`; false, and nothing written, outside the plane.
inline bool BilinearAt(const cv::Mat& m, double x, double y, float* out) {
  if (!(x >= 0 && y >= 0 && x <= m.cols - 1 && y <= m.rows - 1)) return false;
  const int x0 = std::min(int(x), m.cols - 2), y0 = std::min(int(y), m.rows - 2);
  const float fx = float(x - x0), fy = float(y - y0);
  const float* a = m.ptr<float>(y0) + x0;
  const float* b = m.ptr<float>(y0 + 1) + x0;
  *out = (a[0] * (1 - fx) + a[1] * fx) * (1 - fy) + (b[0] * (1 - fx) + b[1] * fx) * fy;
  return true;
}

}  // namespace lfcam
