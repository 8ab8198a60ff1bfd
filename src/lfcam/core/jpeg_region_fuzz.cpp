// libFuzzer target: decoding part of a JPEG with libjpeg-turbo (core/jpeg_region.h), the path
// `lfcam build` reads every camera image through. The first two bytes pick the reduction, the
// chroma upsampling and the region; the rest is the file.
#include <cstdint>
#include <span>

#include "lfcam/core/error.h"
#include "lfcam/core/jpeg_region.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const int reduction = 1 << (data[0] & 3);
  const auto chroma =
      data[0] & 4 ? lfcam::ChromaUpsampling::kInterpolated : lfcam::ChromaUpsampling::kGuided;
  const int corner = data[1];
  const cv::Rect region(corner, corner / 2, 64 + corner, 48 + corner);
  try {
    const lfcam::JpegRegion r =
        lfcam::DecodeJpegRegion(std::span(data + 2, size - 2), "fuzz", reduction, region, chroma);
    if (!r.rgb.empty() && r.rgb.type() != CV_8UC3) __builtin_trap();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
