#pragma once
// The size of a PNG or JPEG image, read from its header without decoding anything, so that a
// small file that would decode to a huge image (a "decompression bomb") is refused first.
#include <cstdint>
#include <span>
#include <string>

namespace lfcam {

struct ImageHeader {
  std::string format;  // "PNG" or "JPEG"
  int width = 0, height = 0;
  int channels = 0;  // as decoded: 1 (grey), 2 (grey + alpha), 3, 4
  int bits_per_channel = 0;
};

// Throws lfcam::Error (without a file name: callers add it) when the bytes are neither a PNG
// nor a JPEG, or their header is malformed.
ImageHeader ProbeImageHeader(std::span<const std::uint8_t> bytes);

}  // namespace lfcam
