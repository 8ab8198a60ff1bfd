#include "lfcam/render/lens_sample_accumulator.h"

#include "lfcam/core/error.h"

namespace lfcam {

void LensSampleAccumulator::Reset(int width, int height) {
  sum_ = cv::Mat::zeros(height, width, CV_32FC3);
  counts_ = cv::Mat::zeros(height, width, CV_32SC1);
  rays_ = rays_hit_ = 0;
  parts_ = 0;
}

void LensSampleAccumulator::Add(const RenderResult& part) {
  if (part.image.size() != sum_.size() || part.counts.size() != sum_.size())
    throw Error("LensSampleAccumulator: a part of another size");
  for (int y = 0; y < sum_.rows; ++y) {
    const auto* image = part.image.ptr<cv::Vec3f>(y);
    const auto* n = part.counts.ptr<std::int32_t>(y);
    auto* sum = sum_.ptr<cv::Vec3f>(y);
    auto* counts = counts_.ptr<std::int32_t>(y);
    for (int x = 0; x < sum_.cols; ++x) {
      sum[x] += image[x] * float(n[x]);
      counts[x] += n[x];
    }
  }
  rays_ += part.rays;
  rays_hit_ += part.rays_hit;
  ++parts_;
}

RenderResult LensSampleAccumulator::Frame() const {
  RenderResult frame;
  frame.image = cv::Mat(sum_.size(), CV_32FC3);
  frame.hit_mask = cv::Mat(sum_.size(), CV_8UC1);
  frame.counts = counts_.clone();
  for (int y = 0; y < sum_.rows; ++y) {
    const auto* sum = sum_.ptr<cv::Vec3f>(y);
    const auto* counts = counts_.ptr<std::int32_t>(y);
    auto* image = frame.image.ptr<cv::Vec3f>(y);
    auto* mask = frame.hit_mask.ptr<std::uint8_t>(y);
    for (int x = 0; x < sum_.cols; ++x) {
      image[x] = counts[x] > 0 ? sum[x] * (1.0f / float(counts[x])) : cv::Vec3f(0, 0, 0);
      mask[x] = counts[x] > 0 ? 255 : 0;
    }
  }
  frame.rays = rays_;
  frame.rays_hit = rays_hit_;
  frame.path = "accumulated";
  return frame;
}

}  // namespace lfcam
