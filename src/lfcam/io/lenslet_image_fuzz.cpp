// libFuzzer target: a lenslet image's block size found and the image split (io/lenslet_image.h)
// on images of any size and content. Whatever size it finds divides both sides and leaves blocks
// of 8 samples a side at least; the split gives N x N views whose samples are the image's.
#include <cstdint>
#include <cstdlib>
#include <opencv2/core.hpp>

#include "lfcam/core/error.h"
#include "lfcam/io/lenslet_image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const int w = 1 + data[0] % 255, h = 1 + data[1] % 255;
  cv::Mat image(h, w, CV_8UC3);
  const std::size_t pixels = size - 2;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        image.at<cv::Vec3b>(y, x)[c] =
            data[2 + (std::size_t(y * w + x) * 3 + std::size_t(c)) % pixels];
  const lfcam::LensletPeriod found = lfcam::DetectLensletPeriod(image);
  const int n = found.views_per_side;
  if (n != 0 && (w % n != 0 || h % n != 0 || w / n < 8 || h / n < 8 || n < 3 || n > 32))
    std::abort();
  const int split = n != 0 ? n : 3 + data[0] % 30;
  try {
    const auto views = lfcam::SplitLensletImage(image, split);
    if (views.size() != std::size_t(split) * std::size_t(split)) std::abort();
    const cv::Mat& last = views.back();
    if (last.cols != w / split || last.rows != h / split) std::abort();
    if (last.cols > 0 && last.rows > 0 &&
        last.at<cv::Vec3b>(0, 0) != image.at<cv::Vec3b>(split - 1, split - 1))
      std::abort();
  } catch (const lfcam::Error&) {
    if (w % split == 0 && h % split == 0) std::abort();  // refused only when blocks do not fit
  }
  return 0;
}
