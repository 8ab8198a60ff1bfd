#pragma once
// 8-bit sRGB codes to linear light and back over runs of values (interleaved channels alike),
// vectorised with Highway's dynamic dispatch: the same numbers as lfcam's tables, value for
// value (core/color.h), for the bulk conversions of whole views (the quadrilinear limit's
// prefilter, render/quadrilinear_limit.h).
#include <cstddef>
#include <cstdint>

namespace lfcam {

// out[i] = SrgbDecodeTable()[in[i]] for i < n.
void DecodeSrgbValues(const std::uint8_t* in, std::size_t n, float* out);

// out[i] = LinearToSrgb8With(LinearToSrgb8EncodeTable(), in[i]) for i < n (NaN and below 0 to
// 0, 1 and above to 255).
void EncodeSrgbValues(const float* in, std::size_t n, std::uint8_t* out);

}  // namespace lfcam
