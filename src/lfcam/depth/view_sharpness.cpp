#include "lfcam/depth/view_sharpness.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lfcam {

double NearNyquistShare(const cv::Mat& rgb8) {
  if (rgb8.cols < 16 || rgb8.rows < 16) return 0.0;
  cv::Mat grey;
  if (rgb8.channels() == 3)
    cv::cvtColor(rgb8, grey, cv::COLOR_RGB2GRAY);
  else
    grey = rgb8;
  const cv::Rect middle(rgb8.cols / 8, rgb8.rows / 8, rgb8.cols - rgb8.cols / 4,
                        rgb8.rows - rgb8.rows / 4);
  cv::Mat x, window, spectrum;
  grey(middle).convertTo(x, CV_32F);
  x -= cv::mean(x);
  cv::createHanningWindow(window, x.size(), CV_32F);
  cv::dft(x.mul(window), spectrum, cv::DFT_COMPLEX_OUTPUT);
  // A frequency index's distance from zero, in cycles a sample.
  const auto cycles = [](int i, int n) { return double(std::min(i, n - i)) / n; };
  double near_limit = 0, textured = 0;
  for (int r = 0; r < spectrum.rows; ++r) {
    const double fy = cycles(r, spectrum.rows);
    const cv::Vec2f* row = spectrum.ptr<cv::Vec2f>(r);
    for (int c = 0; c < spectrum.cols; ++c) {
      const double f = std::max(fy, cycles(c, spectrum.cols));
      if (f <= 0.02) continue;
      const double power = double(row[c][0]) * row[c][0] + double(row[c][1]) * row[c][1];
      textured += power;
      if (f >= 0.35) near_limit += power;
    }
  }
  return textured > 0 ? near_limit / textured : 0.0;
}

}  // namespace lfcam
