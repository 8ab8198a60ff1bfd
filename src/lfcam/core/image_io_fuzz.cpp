// libFuzzer target: image header probing and decoding (PNG, JPEG), the path every image input
// takes (compare, montage, and later the camera captures).
#include <cstdint>
#include <cstdlib>
#include <span>

#include "lfcam/core/error.h"
#include "lfcam/core/image_header.h"
#include "lfcam/core/image_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("LFCAM_MEMORY_LIMIT", "256M", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  try {
    const lfcam::ImageHeader header = lfcam::ProbeImageHeader(bytes);
    if (header.width < 1 || header.height < 1) std::abort();
    const cv::Mat image = lfcam::DecodeImageBytes(bytes, "fuzz");
    if (image.cols != header.width || image.rows != header.height) std::abort();
  } catch (const lfcam::Error&) {
  }
  return 0;
}
