#pragma once
// sRGB <-> linear light. Every average lfcam takes (supersampling, resampling, the lens
// integral) is taken in linear light; 8-bit values are sRGB-encoded.
#include <array>
#include <cstddef>
#include <cstdint>

namespace lfcam {

float SrgbToLinear(float encoded);  // both in [0, 1]
float LinearToSrgb(float linear);   // clamps to [0, 1]
std::uint8_t LinearToSrgb8(float linear);

// SrgbToLinear through a table of kSrgbFineSteps steps, interpolated linearly (within 4e-7 of
// it; the input clamped to [0, 1], NaN to 0): for bulk work on encoded values between the 8-bit
// codes (the depth lookup's cubic reads, render/lightfield_sampler.h).
inline constexpr int kSrgbFineSteps = 4096;
const std::array<float, kSrgbFineSteps + 1>& SrgbDecodeFineTable();
inline float SrgbToLinearFine(const std::array<float, kSrgbFineSteps + 1>& table, float encoded) {
  const float x = (encoded > 0.0f ? (encoded < 1.0f ? encoded : 1.0f) : 0.0f) * kSrgbFineSteps;
  const int i = static_cast<int>(x) < kSrgbFineSteps ? static_cast<int>(x) : kSrgbFineSteps - 1;
  const float f = x - static_cast<float>(i);
  return table[std::size_t(i)] + f * (table[std::size_t(i) + 1] - table[std::size_t(i)]);
}

// Decoding table for 8-bit sRGB: SrgbDecodeTable()[v] == SrgbToLinear(v / 255).
const std::array<float, 256>& SrgbDecodeTable();

// Encoding through a table of 2^16 steps of linear light: LinearToSrgb8 to within one code
// (exact except where the value lies within 1/131070 of a rounding boundary), for bulk work.
std::uint8_t LinearToSrgb8Table(float linear);

// The table behind LinearToSrgb8Table, for loops that encode many values with
// LinearToSrgb8With (the same result, without a call per value).
const std::array<std::uint8_t, 65536>& LinearToSrgb8EncodeTable();
inline std::uint8_t LinearToSrgb8With(const std::array<std::uint8_t, 65536>& table, float linear) {
  const float x = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;  // NaN -> 0
  return table[static_cast<std::size_t>(x * 65535.0f + 0.5f)];
}

// LinearToSrgb8 exactly, for bulk work (every image lfcam writes): the table's code, corrected
// against the 255 linear values where LinearToSrgb8 steps from one code to the next (found once,
// by bisection over the float values). About twenty times faster than LinearToSrgb8.
std::uint8_t LinearToSrgb8Exact(float linear);

}  // namespace lfcam
