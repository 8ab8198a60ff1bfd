#include "lfcam/core/chroma_upsampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfcam/core/error.h"

// Only two passes touch full resolution: one applies the first affine maps and averages the
// result back to chroma resolution (for the back-projection), the other applies the final maps
// and converts to RGB. Everything else runs at chroma resolution, a quarter of the pixels.

namespace lfcam {
namespace {

// The mean over each 3 x 3 window (the image's edge repeated).
cv::Mat WindowMean(const cv::Mat& x) {
  cv::Mat out;
  cv::blur(x, out, cv::Size(3, 3), cv::Point(-1, -1), cv::BORDER_REPLICATE);
  return out;
}

// Where full-resolution index i lies between chroma samples along one axis subsampled by
// `factor`: bilinear between the samples' centres (at factor * j + (factor - 1) / 2), the edge
// sample repeated beyond the first and last centres.
struct AxisTaps {
  std::vector<int> lo, hi;
  std::vector<float> w;  // weight of hi

  AxisTaps(int full, int low, int factor) : lo(std::size_t(full)), hi(lo), w(lo.size()) {
    for (int i = 0; i < full; ++i) {
      const double x = (i + 0.5) / factor - 0.5;
      const int j = int(std::floor(x));
      lo[std::size_t(i)] = std::clamp(j, 0, low - 1);
      hi[std::size_t(i)] = std::clamp(j + 1, 0, low - 1);
      w[std::size_t(i)] = float(x - j);
    }
  }
};

// Four maps (CV_32FC4 at chroma resolution: Cb slope, Cr slope, Cb offset, Cr offset) read
// bilinearly at full resolution, a row at a time.
class MapRows {
 public:
  MapRows(const cv::Mat& maps, cv::Size full, cv::Size factor)
      : maps_(maps),
        rows_(full.height, maps.rows, factor.height),
        cols_(full.width, maps.cols, factor.width),
        between_(std::size_t(maps.cols)),
        row_(std::size_t(full.width)) {}

  const cv::Vec4f* Row(int y) {
    const std::size_t i = std::size_t(y);
    const cv::Vec4f* a = maps_.ptr<cv::Vec4f>(rows_.lo[i]);
    const cv::Vec4f* b = maps_.ptr<cv::Vec4f>(rows_.hi[i]);
    const float w = rows_.w[i];
    for (std::size_t x = 0; x < between_.size(); ++x) between_[x] = a[x] + w * (b[x] - a[x]);
    for (std::size_t x = 0; x < row_.size(); ++x) {
      const cv::Vec4f& lo = between_[std::size_t(cols_.lo[x])];
      const cv::Vec4f& hi = between_[std::size_t(cols_.hi[x])];
      row_[x] = lo + cols_.w[x] * (hi - lo);
    }
    return row_.data();
  }

 private:
  const cv::Mat& maps_;
  AxisTaps rows_, cols_;
  std::vector<cv::Vec4f> between_, row_;
};

// Each chroma sample's share of one of its pixels: 1 / (its pixels inside the image).
cv::Mat BlockWeights(cv::Size full, cv::Size low, cv::Size factor) {
  cv::Mat out(low, CV_32FC1);
  for (int j = 0; j < low.height; ++j)
    for (int i = 0; i < low.width; ++i) {
      const int rows = std::min(factor.height, full.height - j * factor.height);
      const int cols = std::min(factor.width, full.width - i * factor.width);
      out.at<float>(j, i) = 1.0f / float(rows * cols);
    }
  return out;
}

// The luma averaged over each chroma sample's pixels, as the encoder averaged the chroma.
cv::Mat LumaAtChroma(const cv::Mat& y, cv::Size low, cv::Size factor, const cv::Mat& weights) {
  cv::Mat out = cv::Mat::zeros(low, CV_32FC1);
  for (int row = 0; row < y.rows; ++row) {
    const std::uint8_t* in = y.ptr<std::uint8_t>(row);
    float* sum = out.ptr<float>(row / factor.height);
    for (int x = 0; x < y.cols; ++x) sum[x / factor.width] += float(in[x]);
  }
  return out.mul(weights);
}

// Step 1 at chroma resolution: each window's affine map from luma to chroma (the guided filter),
// then each sample's map, the mean of its windows' maps. CV_32FC4 (slopes, offsets).
cv::Mat GuidedMaps(const cv::Mat& luma_low1, const cv::Mat& chroma) {
  cv::Mat luma_low;
  cv::merge(std::vector<cv::Mat>{luma_low1, luma_low1}, luma_low);
  const cv::Mat mean_y = WindowMean(luma_low), mean_c = WindowMean(chroma);
  const cv::Mat covariance = WindowMean(luma_low.mul(chroma)) - mean_y.mul(mean_c);
  const cv::Mat variance = WindowMean(luma_low.mul(luma_low)) - mean_y.mul(mean_y);
  // (A scalar added to a two-channel matrix goes to its first channel only: add it to both.)
  const cv::Mat window_slope = covariance / (variance + cv::Scalar::all(kChromaGuideEpsilon));
  cv::Mat maps;
  cv::merge(
      std::vector<cv::Mat>{WindowMean(window_slope), WindowMean(mean_c - window_slope.mul(mean_y))},
      maps);
  return maps;
}

// Step 2. Back-projection is out += Up(chroma - Down(out)), repeated; Up (bilinear) and Down
// (the block mean) are linear, so each round's correction lies at chroma resolution: with
// r = chroma - Down(out), the next round's r is r - Down(Up(r)), and out gains Up(the sum of the
// r's), which goes into the offsets. Down(Up(.)) is, along an axis subsampled by 2, the filter
// [1/8, 3/4, 1/8] (the edge repeated): only the first Down sees full resolution.
void BackProject(const cv::Mat& y, const cv::Mat& chroma, cv::Size factor, const cv::Mat& weights,
                 cv::Mat* maps) {
  const cv::Size low = chroma.size();
  cv::Mat down = cv::Mat::zeros(low, CV_32FC2);
  MapRows rows(*maps, y.size(), factor);
  for (int row = 0; row < y.rows; ++row) {
    const std::uint8_t* l = y.ptr<std::uint8_t>(row);
    const cv::Vec4f* m = rows.Row(row);
    cv::Vec2f* sum = down.ptr<cv::Vec2f>(row / factor.height);
    for (int x = 0; x < y.cols; ++x) {
      const float v = float(l[x]);
      sum[x / factor.width] += cv::Vec2f(m[x][0] * v + m[x][2], m[x][1] * v + m[x][3]);
    }
  }
  cv::Mat weights2;
  cv::merge(std::vector<cv::Mat>{weights, weights}, weights2);
  cv::Mat residual = chroma - down.mul(weights2);
  const cv::Mat taps = (cv::Mat_<float>(1, 3) << 0.125f, 0.75f, 0.125f);
  const cv::Mat identity = (cv::Mat_<float>(1, 1) << 1.0f);
  cv::Mat offsets = cv::Mat::zeros(low, CV_32FC2);
  for (int round = 0; round < kChromaBackProjections; ++round) {
    offsets += residual;
    cv::Mat down_up;
    cv::sepFilter2D(residual, down_up, -1, factor.width == 2 ? taps : identity,
                    factor.height == 2 ? taps : identity, cv::Point(-1, -1), 0,
                    cv::BORDER_REPLICATE);
    residual -= down_up;
  }
  cv::Mat zeros = cv::Mat::zeros(low, CV_32FC2), added;
  cv::merge(std::vector<cv::Mat>{zeros, offsets}, added);
  *maps += added;
}

}  // namespace

cv::Mat GuidedChromaToRgb(const cv::Mat& y, const cv::Mat& cb, const cv::Mat& cr, cv::Size factor) {
  if (y.type() != CV_8UC1 || cb.type() != CV_8UC1 || cr.type() != CV_8UC1)
    throw Error("GuidedChromaToRgb: planes must be 8-bit, one channel");
  if (factor.width < 1 || factor.width > 2 || factor.height < 1 || factor.height > 2)
    throw Error(fmt::format("GuidedChromaToRgb: chroma subsampling {}x{} is not 1 or 2 each way",
                            factor.width, factor.height));
  const cv::Size low((y.cols + factor.width - 1) / factor.width,
                     (y.rows + factor.height - 1) / factor.height);
  if (cb.size() != low || cr.size() != low)
    throw Error(fmt::format(
        "GuidedChromaToRgb: chroma of {}x{} and {}x{} for luma of {}x{} subsampled {}x{}", cb.cols,
        cb.rows, cr.cols, cr.rows, y.cols, y.rows, factor.width, factor.height));
  cv::Mat rgb(y.size(), CV_8UC3);
  if (y.empty()) return rgb;

  cv::Mat chroma;
  cv::merge(std::vector<cv::Mat>{cb, cr}, chroma);
  chroma.convertTo(chroma, CV_32FC2);
  // Chroma at every pixel is slope * luma + offset (slope 0 without subsampling).
  cv::Mat maps;
  if (factor == cv::Size(1, 1)) {
    cv::merge(std::vector<cv::Mat>{cv::Mat::zeros(low, CV_32FC2), chroma}, maps);
  } else {
    const cv::Mat weights = BlockWeights(y.size(), low, factor);
    maps = GuidedMaps(LumaAtChroma(y, low, factor, weights), chroma);
    BackProject(y, chroma, factor, weights, &maps);
  }

  MapRows rows(maps, y.size(), factor);
  for (int row = 0; row < y.rows; ++row) {
    const std::uint8_t* l = y.ptr<std::uint8_t>(row);
    const cv::Vec4f* m = rows.Row(row);
    cv::Vec3b* out = rgb.ptr<cv::Vec3b>(row);
    for (int x = 0; x < y.cols; ++x) {
      const float v = float(l[x]);
      const float b = m[x][0] * v + m[x][2] - 128.0f, r = m[x][1] * v + m[x][3] - 128.0f;
      out[x] = cv::Vec3b(cv::saturate_cast<std::uint8_t>(v + 1.402f * r),
                         cv::saturate_cast<std::uint8_t>(v - 0.344136f * b - 0.714136f * r),
                         cv::saturate_cast<std::uint8_t>(v + 1.772f * b));
    }
  }
  return rgb;
}

}  // namespace lfcam
