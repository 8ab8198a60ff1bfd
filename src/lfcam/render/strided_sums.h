#pragma once
// The two sums of the quadrilinear limit's strided prefilter (render/quadrilinear_limit.h),
// vectorised with Highway's dynamic dispatch: the taps' weighted sum of a view's rows, and the
// taps' sum along a row of three-channel samples kept every `stride` samples.
#include <cstddef>

namespace lfcam {

// out[j] = sum over i < count of weights[i] * rows[i][j], for j < n.
void WeightedRowSum(const float* const* rows, const float* weights, int count, std::size_t n,
                    float* out);

// Interleaved three-channel samples filtered along the row and kept every `stride`:
// out[3 k + c] = sum over i < count of weights[i] * in[3 (stride k + i) + c], for k < n and
// c < 3 (`in` holds 3 (stride (n - 1) + count) values).
void StridedTapSum(const float* in, const float* weights, int count, int stride, std::size_t n,
                   float* out);

}  // namespace lfcam
