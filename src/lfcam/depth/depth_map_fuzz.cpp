// libFuzzer target: reading a depth map (depth/depth_map.h): the PNG's text chunks walked, the
// lfcam-depth metadata parsed, the 16-bit image decoded. Whatever it accepts must re-encode.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "lfcam/core/error.h"
#include "lfcam/depth/depth_map.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("LFCAM_MEMORY_LIMIT", "256M", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const lfcam::DepthMap map = lfcam::DecodeDepthPng(std::span(data, size), "fuzz");
    if (!map.range.valid() || map.depth.type() != CV_32FC1) std::abort();
    for (int l = 0; l < map.n_t(); ++l)
      for (int k = 0; k < map.n_s(); ++k) {
        const float d = map.depth.at<float>(l, k);
        if (!std::isnan(d) &&
            !(d >= float(map.range.near_mm) * 0.999f && d <= float(map.range.far_mm) * 1.001f))
          std::abort();
      }
    (void)lfcam::EncodeDepthPng(map);
  } catch (const lfcam::Error&) {
  }
  return 0;
}
