#pragma once
// PNG and JPEG to and from memory with libpng and libjpeg-turbo directly. lfcam reads and writes
// no other image formats, and OpenCV's codec module (imgcodecs) links GDAL, GDCM and OpenEXR:
// about 120 libraries that every start of `lfcam` and `lfcam-node` loaded for nothing
// (docs/benchmarks.md, "Start-up"). Channels in OpenCV's order (B, G, R, A), as cv::imdecode
// gave them, so that callers read the same pixels. core/image_io.h checks a file's header and
// size before it comes here.
#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

namespace lfcam {

enum class ImageDecodeMode {
  kUnchanged,  // as stored: 1 (grey), 3 (B, G, R) or 4 (B, G, R, A) channels, 8 or 16 bits
  kGray8,      // one 8-bit channel
  kColour8,    // B, G, R, 8 bits
};

// `reduction` 1, 2, 4 or 8: a JPEG is decoded at that scale (its DCT scaling, sizes rounded up),
// a PNG decoded whole and resized (sizes rounded down), as OpenCV's IMREAD_REDUCED_* did.
// Returns an empty Mat and the library's reason in `error` for data it cannot decode, including
// a JPEG that ends before its image does. EXIF orientation is not applied (as
// core/jpeg_region.h, which builds light fields from the same camera files).
cv::Mat DecodePngBytes(std::span<const std::uint8_t> bytes, ImageDecodeMode mode, int reduction,
                       std::string& error);
cv::Mat DecodeJpegBytes(std::span<const std::uint8_t> bytes, ImageDecodeMode mode, int reduction,
                        std::string& error);

// A PNG of CV_8UC1, CV_8UC3 (B, G, R), CV_8UC4 (B, G, R, A) or CV_16UC1 (fast settings: the
// sub filter, zlib level 1, run-length strategy). Throws lfcam::Error for another type.
std::vector<std::uint8_t> EncodePngBytes(const cv::Mat& image);
// A baseline JPEG of CV_8UC1 or CV_8UC3 (B, G, R) at `quality` (1..100), 4:2:0 chroma.
std::vector<std::uint8_t> EncodeJpegBytes(const cv::Mat& image, int quality);

}  // namespace lfcam
