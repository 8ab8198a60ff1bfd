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

// How chroma kept at a lower resolution than luma (4:2:0, 4:2:2) comes back at full size:
// guided by the luma (core/chroma_upsampling.h; at 1/1 size only, since a scaled decode has the
// chroma's resolution already), or interpolated by libjpeg as every decoder does.
enum class ChromaUpsampling { kGuided, kInterpolated };
ChromaUpsampling ChromaUpsamplingFromString(const std::string& name);  // throws lfcam::Error
std::string ToString(ChromaUpsampling chroma);

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
                            int reduction, cv::Rect region,
                            ChromaUpsampling chroma = ChromaUpsampling::kGuided);

// Whether `bytes` start like a JPEG (SOI marker).
bool LooksLikeJpeg(std::span<const std::uint8_t> bytes);

}  // namespace lfcam
