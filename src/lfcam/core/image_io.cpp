#include "lfcam/core/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_codec.h"
#include "lfcam/core/image_header.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/limits.h"

namespace lfcam {
namespace {

cv::Mat ReadRaw(const std::filesystem::path& path) {
  const auto bytes = ReadFileBytes(path, kMaxEncodedImageBytes, "image file");
  return DecodeImageBytes(bytes, path.string());
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

// Every chunk of a PNG lies inside the bytes, up to IEND: libpng allocates what a chunk claims
// before it finds that the bytes are not there (a 2-byte change made it ask for 1.9 GB).
void CheckPngChunks(std::span<const std::uint8_t> b, const std::string& name) {
  std::size_t at = 8;  // after the signature
  while (at + 12 <= b.size()) {
    const std::uint32_t length = std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 |
                                 std::uint32_t(b[at + 2]) << 8 | b[at + 3];
    if (length > b.size() - at - 12)
      throw Error(
          fmt::format("{}: truncated or corrupt PNG: the chunk at byte {} claims {} bytes, "
                      "{} remain",
                      name, at, length, b.size() - at - 12));
    if (std::equal(b.begin() + std::ptrdiff_t(at + 4), b.begin() + std::ptrdiff_t(at + 8), "IEND"))
      return;
    at += 12 + std::size_t(length);
  }
  throw Error(fmt::format("{}: truncated PNG: it ends before its IEND chunk", name));
}

}  // namespace

cv::Mat DecodeImageBytes(std::span<const std::uint8_t> bytes, const std::string& name,
                         ImageDecodeMode mode, int reduction) {
  ImageHeader header;
  try {
    header = ProbeImageHeader(bytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", name, e.what()));
  }
  if (header.width > kMaxImageSide || header.height > kMaxImageSide)
    throw Error(fmt::format("{}: a {}x{} {} image is larger than the limit of {} pixels a side",
                            name, header.width, header.height, header.format, kMaxImageSide));
  if (header.format == "PNG") CheckPngChunks(bytes, name);
  // The decoded image, its 8-bit RGB copy and a linear float copy.
  const double pixels = double(header.width) * header.height;
  RequireMemory(pixels * (header.channels * header.bits_per_channel / 8.0 + 3 + 12),
                fmt::format("{}: decoding a {}x{} image", name, header.width, header.height));
  if (reduction != 1 && reduction != 2 && reduction != 4 && reduction != 8)
    throw Error(fmt::format("{}: internal: a reduction of {}", name, reduction));
  std::string reason;
  const cv::Mat m = header.format == "PNG" ? DecodePngBytes(bytes, mode, reduction, reason)
                                           : DecodeJpegBytes(bytes, mode, reduction, reason);
  if (m.empty())
    throw Error(fmt::format("{}: not a readable {} image (corrupt or truncated: {})", name,
                            header.format, reason));
  const int expected_w = (header.width + reduction - 1) / reduction;
  const int expected_h = (header.height + reduction - 1) / reduction;
  if (std::abs(m.cols - expected_w) > (reduction > 1) ||
      std::abs(m.rows - expected_h) > (reduction > 1))
    throw Error(fmt::format("{}: decoded to {}x{}, but its header says {}x{}{}", name, m.cols,
                            m.rows, header.width, header.height,
                            reduction > 1 ? fmt::format(" (at 1/{} size)", reduction) : ""));
  return m;
}

ImageHeader ProbeImageFile(const std::filesystem::path& path) {
  InputFile in(path);
  std::vector<std::uint8_t> bytes(std::size_t(std::min<std::uint64_t>(in.size(), 1 << 18)));
  in.read_exactly(bytes.data(), bytes.size(), 0);
  try {
    return ProbeImageHeader(bytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", path.string(), e.what()));
  }
}

cv::Mat ReadImageGray8(const std::filesystem::path& path) {
  const auto bytes = ReadFileBytes(path, kMaxEncodedImageBytes, "image file");
  return DecodeImageBytes(bytes, path.string(), ImageDecodeMode::kGray8);
}

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
  cv::parallel_for_(cv::Range(0, out.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const float* in = linear_rgb.ptr<float>(y);
      std::uint8_t* o = out.ptr<std::uint8_t>(y);
      for (int x = 0; x < out.cols * 3; ++x) o[x] = LinearToSrgb8Exact(in[x]);
    }
  });
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

namespace {

// ".png" (also for a path with no extension) or ".jpg"; anything else is refused.
std::string ImageExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext.empty() || ext == ".png") return ".png";
  if (ext == ".jpg" || ext == ".jpeg") return ".jpg";
  throw UsageError(fmt::format("{}: cannot write an image with extension '{}' (use .png or .jpg)",
                               path.string(), path.extension().string()));
}

std::vector<std::uint8_t> EncodeImage(const std::filesystem::path& path, const cv::Mat& rgb,
                                      int jpeg_quality = 95) {
  cv::Mat srgb = rgb.type() == CV_32FC3 ? LinearToSrgb8Image(rgb) : rgb;
  if (srgb.type() != CV_8UC3)
    throw Error(fmt::format("{}: internal: bad image type", path.string()));
  cv::Mat bgr;
  cv::cvtColor(srgb, bgr, cv::COLOR_RGB2BGR);
  try {
    return ImageExtension(path) == ".jpg" ? EncodeJpegBytes(bgr, jpeg_quality)
                                          : EncodePngBytes(bgr);
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw Error(fmt::format("{}: the image could not be encoded: {}", path.string(), e.what()));
  }
}

}  // namespace

void RequireImageOutput(const std::filesystem::path& path, const std::string& flag) {
  try {
    ImageExtension(path);
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("{} {}", flag, e.what()));
  }
  RequireWritableOutput(path, flag);
}

void WriteImage(const std::filesystem::path& path, const cv::Mat& rgb) {
  WriteFileAtomically(path, EncodeImage(path, rgb));
}

std::vector<std::uint8_t> EncodeJpeg(const cv::Mat& rgb, int quality) {
  return EncodeImage("image.jpg", rgb, quality);
}

void WriteImages(const std::vector<std::pair<std::filesystem::path, cv::Mat>>& images) {
  std::vector<std::unique_ptr<AtomicFileWriter>> writers;
  for (const auto& [path, rgb] : images) {
    const auto bytes = EncodeImage(path, rgb);
    writers.push_back(std::make_unique<AtomicFileWriter>(path));
    writers.back()->write(bytes);
  }
  CommitAll(writers);
}

}  // namespace lfcam
