#include "lfcam/core/image_io.h"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/color.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

cv::Mat ReadRaw(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path))
    throw Error(fmt::format("{}: no such image file", path.string()));
  cv::Mat m = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (m.empty()) throw Error(fmt::format("{}: not a readable image (corrupt?)", path.string()));
  return m;
}

cv::Mat ToRgb(const cv::Mat& m) {
  cv::Mat rgb;
  switch (m.channels()) {
    case 1:
      cv::cvtColor(m, rgb, cv::COLOR_GRAY2RGB);
      break;
    case 3:
      cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB);
      break;
    case 4:
      cv::cvtColor(m, rgb, cv::COLOR_BGRA2RGB);
      break;
    default:
      throw Error(fmt::format("images with {} channels are not supported", m.channels()));
  }
  return rgb;
}

}  // namespace

cv::Mat ReadImageSrgb8(const std::filesystem::path& path) {
  cv::Mat m = ReadRaw(path);
  if (m.depth() == CV_16U) m.convertTo(m, CV_8U, 1.0 / 257.0);
  if (m.depth() != CV_8U)
    throw Error(fmt::format("{}: only 8- and 16-bit images are supported", path.string()));
  try {
    return ToRgb(m);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", path.string(), e.what()));
  }
}

cv::Mat ReadImageLinear(const std::filesystem::path& path) {
  return Srgb8ToLinearImage(ReadImageSrgb8(path));
}

cv::Mat ReadMask(const std::filesystem::path& path) {
  cv::Mat m = ReadRaw(path);
  if (m.channels() > 1) {
    std::vector<cv::Mat> planes;
    cv::split(m, planes);
    m = planes[0];
  }
  cv::Mat mask;
  cv::compare(m, 0, mask, cv::CMP_GT);
  return mask;
}

cv::Mat LinearToSrgb8Image(const cv::Mat& linear_rgb) {
  CV_Assert(linear_rgb.type() == CV_32FC3);
  cv::Mat out(linear_rgb.size(), CV_8UC3);
  for (int y = 0; y < out.rows; ++y) {
    const float* in = linear_rgb.ptr<float>(y);
    std::uint8_t* o = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < out.cols * 3; ++x) o[x] = LinearToSrgb8(in[x]);
  }
  return out;
}

cv::Mat Srgb8ToLinearImage(const cv::Mat& srgb8_rgb) {
  CV_Assert(srgb8_rgb.type() == CV_8UC3);
  const auto& lut = SrgbDecodeTable();
  cv::Mat out(srgb8_rgb.size(), CV_32FC3);
  for (int y = 0; y < out.rows; ++y) {
    const std::uint8_t* in = srgb8_rgb.ptr<std::uint8_t>(y);
    float* o = out.ptr<float>(y);
    for (int x = 0; x < out.cols * 3; ++x) o[x] = lut[in[x]];
  }
  return out;
}

void WriteImage(const std::filesystem::path& path, const cv::Mat& rgb) {
  cv::Mat srgb = rgb.type() == CV_32FC3 ? LinearToSrgb8Image(rgb) : rgb;
  if (srgb.type() != CV_8UC3)
    throw Error(fmt::format("{}: internal: bad image type", path.string()));
  cv::Mat bgr;
  cv::cvtColor(srgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> bytes;
  const std::string ext = path.extension().string().empty() ? ".png" : path.extension().string();
  bool ok = false;
  try {
    ok = cv::imencode(ext, bgr, bytes);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok)
    throw Error(fmt::format("{}: cannot encode an image with extension '{}'", path.string(), ext));
  WriteFileAtomically(path, bytes);
}

}  // namespace lfcam
