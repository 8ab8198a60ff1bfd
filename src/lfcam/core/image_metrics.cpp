#include "lfcam/core/image_metrics.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

cv::Mat Luma(const cv::Mat& rgb8) {
  cv::Mat f;
  rgb8.convertTo(f, CV_32FC3);
  cv::Mat y;
  cv::transform(f, y, cv::Matx13f(0.299f, 0.587f, 0.114f));
  return y;
}

cv::Mat SsimMap(const cv::Mat& a, const cv::Mat& b) {
  constexpr double c1 = (0.01 * 255) * (0.01 * 255);
  constexpr double c2 = (0.03 * 255) * (0.03 * 255);
  auto blur = [](const cv::Mat& m) {
    cv::Mat out;
    cv::GaussianBlur(m, out, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return out;
  };
  const cv::Mat mu_a = blur(a), mu_b = blur(b);
  const cv::Mat mu_aa = mu_a.mul(mu_a), mu_bb = mu_b.mul(mu_b), mu_ab = mu_a.mul(mu_b);
  const cv::Mat s_aa = blur(a.mul(a)) - mu_aa;
  const cv::Mat s_bb = blur(b.mul(b)) - mu_bb;
  const cv::Mat s_ab = blur(a.mul(b)) - mu_ab;
  cv::Mat num = (2 * mu_ab + c1).mul(2 * s_ab + c2);
  cv::Mat den = (mu_aa + mu_bb + c1).mul(s_aa + s_bb + c2);
  cv::Mat ssim;
  cv::divide(num, den, ssim);
  return ssim;
}

}  // namespace

ImageComparison CompareImages(const cv::Mat& a_srgb8, const cv::Mat& b_srgb8, const cv::Mat& mask) {
  if (a_srgb8.size() != b_srgb8.size())
    throw Error(fmt::format("images differ in size: {}x{} vs {}x{}", a_srgb8.cols, a_srgb8.rows,
                            b_srgb8.cols, b_srgb8.rows));
  CV_Assert(a_srgb8.type() == CV_8UC3 && b_srgb8.type() == CV_8UC3);
  cv::Mat used = mask.empty() ? cv::Mat(a_srgb8.size(), CV_8UC1, cv::Scalar(255)) : mask;
  if (used.size() != a_srgb8.size())
    throw Error(fmt::format("mask is {}x{}, images are {}x{}", used.cols, used.rows, a_srgb8.cols,
                            a_srgb8.rows));
  ImageComparison r;
  r.pixels = cv::countNonZero(used);
  if (r.pixels == 0) throw Error("mask selects no pixels");

  double sq = 0, abs_sum = 0;
  for (int y = 0; y < a_srgb8.rows; ++y) {
    const auto* pa = a_srgb8.ptr<std::uint8_t>(y);
    const auto* pb = b_srgb8.ptr<std::uint8_t>(y);
    const auto* pm = used.ptr<std::uint8_t>(y);
    for (int x = 0; x < a_srgb8.cols; ++x) {
      if (!pm[x]) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = double(pa[3 * x + c]) - double(pb[3 * x + c]);
        sq += d * d;
        abs_sum += std::abs(d);
      }
    }
  }
  const double mse = sq / (3.0 * double(r.pixels));
  r.mean_abs_error = abs_sum / (3.0 * double(r.pixels));
  r.psnr_db =
      mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
  r.ssim = cv::mean(SsimMap(Luma(a_srgb8), Luma(b_srgb8)), used)[0];
  return r;
}

}  // namespace lfcam
