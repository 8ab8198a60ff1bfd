#include "lfcam/core/image_header.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

std::uint32_t BigEndian32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}
std::uint16_t BigEndian16(const std::uint8_t* p) { return std::uint16_t(p[0] << 8 | p[1]); }

constexpr std::array<std::uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};

ImageHeader ProbePng(std::span<const std::uint8_t> b) {
  // Signature, then the IHDR chunk: length 13, "IHDR", width, height, depth, colour type, ...
  if (b.size() < 33) throw Error("truncated PNG header");
  if (BigEndian32(&b[8]) != 13 || !std::equal(b.begin() + 12, b.begin() + 16, "IHDR"))
    throw Error("malformed PNG: the first chunk is not IHDR");
  const std::uint32_t w = BigEndian32(&b[16]), h = BigEndian32(&b[20]);
  if (w == 0 || h == 0 || w > 0x7fffffffu || h > 0x7fffffffu)
    throw Error(fmt::format("malformed PNG: size {}x{}", w, h));
  const int depth = b[24], colour = b[25];
  int channels = 0;
  switch (colour) {
    case 0:
      channels = 1;
      break;
    case 2:
      channels = 3;
      break;
    case 3:
      channels = 3;
      break;  // palette, decoded to RGB
    case 4:
      channels = 2;
      break;
    case 6:
      channels = 4;
      break;
    default:
      throw Error(fmt::format("malformed PNG: colour type {}", colour));
  }
  if (depth != 1 && depth != 2 && depth != 4 && depth != 8 && depth != 16)
    throw Error(fmt::format("malformed PNG: bit depth {}", depth));
  return {"PNG", int(w), int(h), channels, depth == 16 ? 16 : 8};
}

bool IsStartOfFrame(std::uint8_t marker) {
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

ImageHeader ProbeJpeg(std::span<const std::uint8_t> b) {
  std::size_t pos = 2;
  while (true) {
    if (pos >= b.size()) throw Error("truncated JPEG: no frame header");
    if (b[pos] != 0xFF) throw Error(fmt::format("malformed JPEG: no marker at byte {}", pos));
    while (pos < b.size() && b[pos] == 0xFF) ++pos;  // fill bytes
    if (pos >= b.size()) throw Error("truncated JPEG: no frame header");
    const std::uint8_t marker = b[pos++];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    if (marker == 0xD9 || marker == 0xDA)
      throw Error("malformed JPEG: image data before the frame header");
    if (pos + 2 > b.size()) throw Error("truncated JPEG header");
    const std::size_t length = BigEndian16(&b[pos]);
    if (length < 2) throw Error(fmt::format("malformed JPEG: segment length {}", length));
    if (IsStartOfFrame(marker)) {
      if (length < 8 || pos + 8 > b.size()) throw Error("truncated JPEG frame header");
      const int bits = b[pos + 2], h = BigEndian16(&b[pos + 3]), w = BigEndian16(&b[pos + 5]),
                components = b[pos + 7];
      if (w == 0 || h == 0)
        throw Error(fmt::format("JPEG size {}x{} is not supported (zero side)", w, h));
      if (components != 1 && components != 3 && components != 4)
        throw Error(fmt::format("malformed JPEG: {} components", components));
      return {"JPEG", w, h, components == 1 ? 1 : 3, bits > 8 ? 16 : 8};
    }
    pos += length;
  }
}

}  // namespace

ImageHeader ProbeImageHeader(std::span<const std::uint8_t> bytes) {
  if (bytes.size() >= 8 && std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin()))
    return ProbePng(bytes);
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF)
    return ProbeJpeg(bytes);
  throw Error("not a PNG or JPEG image");
}

}  // namespace lfcam
