#pragma once
// A view's colour planes read bilinearly between their samples (the depth steps that read a view
// at the point a map says, one sample at a time).
#include <algorithm>
#include <array>
#include <opencv2/core.hpp>

namespace lfcam {

// Three planes of one size (a view's colours: T float, or a fixed point such as std::int16_t) at
// (x, y), each sample times `scale`, into out[0..2], the place and its weights found once; false,
// and nothing written, outside the planes.
template <typename T>
inline bool BilinearAt3(const std::array<cv::Mat, 3>& m, double x, double y, float scale,
                        float* out) {
  const int cols = m[0].cols, rows = m[0].rows;
  if (!(x >= 0 && y >= 0 && x <= cols - 1 && y <= rows - 1)) return false;
  const int x0 = std::min(int(x), cols - 2), y0 = std::min(int(y), rows - 2);
  const float fx = float(x - x0), fy = float(y - y0);
  for (std::size_t c = 0; c < 3; ++c) {
    const T* a = m[c].ptr<T>(y0) + x0;
    const T* b = m[c].ptr<T>(y0 + 1) + x0;
    const float a0 = float(a[0]) * scale, a1 = float(a[1]) * scale, b0 = float(b[0]) * scale,
                b1 = float(b[1]) * scale;
    out[c] = (a0 * (1 - fx) + a1 * fx) * (1 - fy) + (b0 * (1 - fx) + b1 * fx) * fy;
  }
  return true;
}

}  // namespace lfcam
