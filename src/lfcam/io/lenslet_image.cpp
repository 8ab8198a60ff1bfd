#include "lfcam/io/lenslet_image.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_codec.h"

namespace lfcam {
namespace {

// The mean brightness of each of the n x n positions within the image's blocks: its standard
// deviation over its mean.
double PositionContrast(const cv::Mat& rgb8, int n) {
  std::vector<double> sum(std::size_t(n) * std::size_t(n), 0.0);
  for (int y = 0; y < rgb8.rows; ++y) {
    const cv::Vec3b* row = rgb8.ptr<cv::Vec3b>(y);
    double* cell = &sum[std::size_t(y % n) * std::size_t(n)];
    for (int x = 0; x < rgb8.cols; ++x)
      cell[x % n] += double(row[x][0]) + double(row[x][1]) + double(row[x][2]);
  }
  double mean = 0, square = 0;
  for (double s : sum) mean += s;
  mean /= double(sum.size());
  if (!(mean > 0)) return 0;
  for (double s : sum) square += (s - mean) * (s - mean);
  return std::sqrt(square / double(sum.size())) / mean;
}

}  // namespace

LensletPeriod DetectLensletPeriod(const cv::Mat& rgb8) {
  CV_Assert(rgb8.type() == CV_8UC3);
  std::vector<std::pair<int, double>> tried;
  double strongest = 0;
  for (int n = 3; n <= 32; ++n)
    if (rgb8.cols % n == 0 && rgb8.rows % n == 0 && rgb8.cols / n >= 8 && rgb8.rows / n >= 8) {
      tried.emplace_back(n, PositionContrast(rgb8, n));
      strongest = std::max(strongest, tried.back().second);
    }
  LensletPeriod found;
  found.strength = strongest;
  if (strongest < kLensletStrength) return found;
  for (const auto& [n, strength] : tried)
    if (strength >= 0.9 * strongest) {
      found.views_per_side = n;
      found.strength = strength;
      break;
    }
  return found;
}

std::vector<cv::Mat> SplitLensletImage(const cv::Mat& image, int n) {
  if (n < 1 || image.cols % n != 0 || image.rows % n != 0)
    throw Error(fmt::format("a lenslet image of {}x{} pixels is not made of blocks of {}x{}",
                            image.cols, image.rows, n, n));
  const int w = image.cols / n, h = image.rows / n;
  const std::size_t bytes = image.elemSize();
  std::vector<cv::Mat> views;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      cv::Mat view(h, w, image.type());
      for (int i = 0; i < h; ++i) {
        const std::uint8_t* in = image.ptr<std::uint8_t>(a + n * i) + std::size_t(b) * bytes;
        std::uint8_t* out = view.ptr<std::uint8_t>(i);
        for (int j = 0; j < w; ++j)
          std::copy_n(in + std::size_t(j) * std::size_t(n) * bytes, bytes,
                      out + std::size_t(j) * bytes);
      }
      views.push_back(std::move(view));
    }
  return views;
}

void WriteLensletViews(const cv::Mat& rgb8, int n, const std::filesystem::path& folder) {
  const std::vector<cv::Mat> views = SplitLensletImage(rgb8, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      cv::Mat bgr;
      cv::cvtColor(views[std::size_t(a * n + b)], bgr, cv::COLOR_RGB2BGR);
      const auto path = folder / fmt::format("view_{:02d}_{:02d}.png", a + 1, b + 1);
      WriteFileAtomically(path, EncodePngBytes(bgr));
    }
}

}  // namespace lfcam
