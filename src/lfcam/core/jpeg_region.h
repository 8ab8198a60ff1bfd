#pragma once
// Decoding only the part of a JPEG that is needed, at 1, 1/2, 1/4 or 1/8 size, with
// libjpeg-turbo: rows above the region are skipped (jpeg_skip_scanlines), columns outside it
// are not decoded (jpeg_crop_scanline), and the DCT scaling does the downsizing. Building a light
// field reads only the view window's part of each camera image, a fifth or less of it.
#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>

namespace lfcam {

struct JpegRegion {
  cv::Mat rgb;       // CV_8UC3, R, G, B, the decoded region (at least the requested one)
  cv::Point origin;  // its top-left corner in the scaled image
  cv::Size scaled;   // the whole scaled image's size
};

// Decodes `region` (in pixels of the image scaled by 1/reduction; clipped to it) of a JPEG held
// in memory. The result covers a little more than the region (decoding starts on a block
// boundary, and a block more on each side so that chroma upsampling at its edges matches a
// whole decode). Throws lfcam::Error naming `name` for anything that is not a readable JPEG.
JpegRegion DecodeJpegRegion(std::span<const std::uint8_t> bytes, const std::string& name,
                            int reduction, cv::Rect region);

// Whether `bytes` start like a JPEG (SOI marker).
bool LooksLikeJpeg(std::span<const std::uint8_t> bytes);

}  // namespace lfcam
