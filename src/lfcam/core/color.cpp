#include "lfcam/core/color.h"

#include <algorithm>
#include <cmath>

namespace lfcam {

float SrgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float LinearToSrgb(float linear) {
  // NaN (a corrupt sample, a 0/0) encodes as black, +inf as white: never an undefined cast.
  const float x = linear > 0.0f ? std::min(linear, 1.0f) : 0.0f;
  if (x <= 0.0031308f) return 12.92f * x;
  return 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t LinearToSrgb8(float linear) {
  return static_cast<std::uint8_t>(std::lround(LinearToSrgb(linear) * 255.0f));
}

const std::array<float, 256>& SrgbDecodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[v] = SrgbToLinear(static_cast<float>(v) / 255.0f);
    return t;
  }();
  return table;
}

const std::array<std::uint8_t, 65536>& LinearToSrgb8EncodeTable() {
  static const std::array<std::uint8_t, 65536> table = [] {
    std::array<std::uint8_t, 65536> t{};
    for (int i = 0; i < 65536; ++i) t[std::size_t(i)] = LinearToSrgb8(float(i) / 65535.0f);
    return t;
  }();
  return table;
}

std::uint8_t LinearToSrgb8Table(float linear) {
  return LinearToSrgb8With(LinearToSrgb8EncodeTable(), linear);
}

}  // namespace lfcam
