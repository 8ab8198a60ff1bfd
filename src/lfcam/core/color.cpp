#include "lfcam/core/color.h"

#include <algorithm>
#include <cmath>
#include <cstring>

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

const std::array<float, kSrgbFineSteps + 1>& SrgbDecodeFineTable() {
  static const std::array<float, kSrgbFineSteps + 1> table = [] {
    std::array<float, kSrgbFineSteps + 1> t{};
    for (int i = 0; i <= kSrgbFineSteps; ++i)
      t[std::size_t(i)] = SrgbToLinear(static_cast<float>(i) / kSrgbFineSteps);
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

namespace {

// steps[c]: the smallest float in [0, 1] that LinearToSrgb8 encodes above c (c = 0 .. 254).
const std::array<float, 255>& EncodeSteps() {
  static const std::array<float, 255> steps = [] {
    std::array<float, 255> t{};
    const auto bits = [](float f) {
      std::uint32_t u;
      std::memcpy(&u, &f, sizeof u);
      return u;
    };
    const auto value = [](std::uint32_t u) {
      float f;
      std::memcpy(&f, &u, sizeof f);
      return f;
    };
    for (int c = 0; c < 255; ++c) {
      // Non-negative floats order as their bit patterns do.
      std::uint32_t lo = bits(0.0f), hi = bits(1.0f);  // LinearToSrgb8(lo) <= c < (hi)'s
      while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        if (LinearToSrgb8(value(mid)) > c)
          hi = mid;
        else
          lo = mid;
      }
      t[std::size_t(c)] = value(hi);
    }
    return t;
  }();
  return steps;
}

}  // namespace

std::uint8_t LinearToSrgb8Exact(float linear) {
  static const auto& table = LinearToSrgb8EncodeTable();
  static const auto& steps = EncodeSteps();
  const float x = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;  // NaN -> 0
  int c = table[static_cast<std::size_t>(x * 65535.0f + 0.5f)];
  while (c < 255 && x >= steps[std::size_t(c)]) ++c;
  while (c > 0 && x < steps[std::size_t(c - 1)]) --c;
  return static_cast<std::uint8_t>(c);
}

std::uint8_t LinearToSrgb8Table(float linear) {
  return LinearToSrgb8With(LinearToSrgb8EncodeTable(), linear);
}

}  // namespace lfcam
