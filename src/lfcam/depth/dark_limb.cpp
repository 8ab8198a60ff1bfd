#include "lfcam/depth/dark_limb.h"

#include <algorithm>
#include <cmath>

namespace lfcam {

bool IsDarkLimb(const cv::Mat& guide_rgb8, const cv::Mat& label, int x, int y, float farther,
                float threshold, const DarkLimbOptions& options) {
  if (!(options.levels > 0)) return false;
  const auto grey = [&](int yy, int xx) {
    const cv::Vec3b& c = guide_rgb8.at<cv::Vec3b>(yy, xx);
    return (double(c[0]) + c[1] + c[2]) / 3.0;
  };
  const float own = label.at<float>(y, x);
  const double limit = grey(y, x) + options.levels;
  const int r = std::max(1, options.radius);
  double own_side = 0;
  int own_count = 0, farther_count = 0;
  for (int yy = std::max(0, y - r); yy <= std::min(label.rows - 1, y + r); ++yy)
    for (int xx = std::max(0, x - r); xx <= std::min(label.cols - 1, x + r); ++xx) {
      if (yy == y && xx == x) continue;
      const float l = label.at<float>(yy, xx);
      if (std::abs(l - farther) <= threshold) {  // false for NaN labels
        if (grey(yy, xx) < limit) return false;  // the farther side is as dark somewhere
        ++farther_count;
      } else if (std::abs(l - own) <= threshold) {
        own_side += grey(yy, xx);
        ++own_count;
      }
    }
  return farther_count > 0 && own_count > 0 && own_side / own_count >= limit;
}

}  // namespace lfcam
