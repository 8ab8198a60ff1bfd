#pragma once
// Images in memory are cv::Mat CV_32FC3 in linear light, channels R, G, B, row 0 at the top
// (as PNG stores them). Files are sRGB-encoded PNGs, written atomically.
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/core/image_codec.h"
#include "lfcam/core/image_header.h"

namespace lfcam {

// Encoded image files larger than this are refused before they are read.
inline constexpr std::uint64_t kMaxEncodedImageBytes = std::uint64_t(1) << 30;

// Decodes a PNG or JPEG held in memory (OpenCV's channel order, any depth) after checking its
// header: at most kMaxImageSide a side and within the memory limit. `name` is for messages.
// `mode` and `reduction` (1, 2, 4 or 8) as core/image_codec.h takes them.
cv::Mat DecodeImageBytes(std::span<const std::uint8_t> bytes, const std::string& name,
                         ImageDecodeMode mode = ImageDecodeMode::kUnchanged, int reduction = 1);

// The size, channels and depth of the PNG or JPEG at `path`, from its header alone (its first
// 256 KB read). Throws lfcam::Error naming the file.
ImageHeader ProbeImageFile(const std::filesystem::path& path);

// Reads an 8- or 16-bit PNG/JPEG as linear RGB float. Throws lfcam::Error naming the file.
cv::Mat ReadImageLinear(const std::filesystem::path& path);
// Reads an image as 8-bit grey (CV_8UC1), decoded straight to grey where the codec can.
cv::Mat ReadImageGray8(const std::filesystem::path& path);
// Reads an image as 8-bit sRGB, channels R, G, B (CV_8UC3).
cv::Mat ReadImageSrgb8(const std::filesystem::path& path);
// Reads a mask (any channels; nonzero = inside) as CV_8UC1 of 0/255.
cv::Mat ReadMask(const std::filesystem::path& path);

cv::Mat LinearToSrgb8Image(const cv::Mat& linear_rgb);  // CV_32FC3 -> CV_8UC3
cv::Mat Srgb8ToLinearImage(const cv::Mat& srgb8_rgb);   // CV_8UC3 -> CV_32FC3

// Writes an sRGB 8-bit RGB image (CV_8UC3) or a linear float one (CV_32FC3, encoded first).
// The extension picks the encoding: .png (or none) or .jpg/.jpeg; others throw UsageError.
void WriteImage(const std::filesystem::path& path, const cv::Mat& rgb);
// A JPEG of an 8-bit sRGB RGB image (CV_8UC3; CV_32FC3 linear is converted) at `quality`
// (1..100; WriteImage's .jpg is quality 95).
std::vector<std::uint8_t> EncodeJpeg(const cv::Mat& rgb, int quality);
// Several images, all or none (core/atomic_file.h: CommitAll).
void WriteImages(const std::vector<std::pair<std::filesystem::path, cv::Mat>>& images);
// Checks before any work that `path` can take an image: a known extension and a writable place.
// Throws lfcam::UsageError naming `flag`.
void RequireImageOutput(const std::filesystem::path& path, const std::string& flag);

}  // namespace lfcam
