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

// out[i] within 4.7e-6 of SrgbDecodeTable()[in[i]] (0.015 of a level once encoded again),
// computed rather than looked up (render/sample_rows-inl.h's DecodeSrgb): a vector gather a
// lane costs several times the polynomial's arithmetic. For values that are filtered and
// encoded again (the quadrilinear limit's strided prefilter).
void DecodeSrgbValuesComputed(const std::uint8_t* in, std::size_t n, float* out);

// out[i] = LinearToSrgb8With(LinearToSrgb8EncodeTable(), in[i]) for i < n (NaN and below 0 to
// 0, 1 and above to 255).
void EncodeSrgbValues(const float* in, std::size_t n, std::uint8_t* out);

}  // namespace lfcam
