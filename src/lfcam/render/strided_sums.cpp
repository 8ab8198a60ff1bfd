// Highway's dynamic dispatch, as in simd_kernels.cpp: compiled once per instruction set.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/strided_sums.cpp"
#include "lfcam/render/strided_sums.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#ifndef LFCAM_RENDER_STRIDED_SUMS_ONCE
#define LFCAM_RENDER_STRIDED_SUMS_ONCE
#include <algorithm>
#include <cstdint>
#endif  // LFCAM_RENDER_STRIDED_SUMS_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;

void WeightedRowSumT(const float* const* rows, const float* weights, int count, std::size_t n,
                     float* out) {
  const DF d;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t j = 0;
  for (; j + lanes <= n; j += lanes) {
    auto sum = hn::Zero(d);
    for (int i = 0; i < count; ++i)
      sum = hn::MulAdd(hn::Set(d, weights[i]), hn::LoadU(d, rows[i] + j), sum);
    hn::StoreU(sum, d, out + j);
  }
  for (; j < n; ++j) {
    float sum = 0;
    for (int i = 0; i < count; ++i) sum += weights[i] * rows[i][j];
    out[j] = sum;
  }
}

void StridedTapSumT(const float* in, const float* weights, int count, int stride, std::size_t n,
                    float* out) {
  // Every sample's sum over a block of kept samples, with contiguous loads (a gather a lane
  // costs more than the stride's extra sums), then the kept ones picked out of it.
  const DF d;
  const std::size_t lanes = hn::Lanes(d);
  constexpr std::size_t kBlockSamples = 1024;
  HWY_ALIGN float every[3 * kBlockSamples];
  const std::size_t m = std::size_t(stride);
  const std::size_t block = (kBlockSamples - 1) / m + 1;  // kept samples a block
  for (std::size_t k0 = 0; k0 < n; k0 += block) {
    const std::size_t kept = std::min(block, n - k0);
    const std::size_t values = 3 * (m * (kept - 1) + 1);
    const float* from = in + 3 * m * k0;
    std::size_t j = 0;
    for (; j + lanes <= values; j += lanes) {
      auto sum = hn::Zero(d);
      for (int i = 0; i < count; ++i)
        sum = hn::MulAdd(hn::Set(d, weights[i]), hn::LoadU(d, from + j + 3 * i), sum);
      hn::Store(sum, d, every + j);
    }
    for (; j < values; ++j) {
      float sum = 0;
      for (int i = 0; i < count; ++i) sum += weights[i] * from[j + 3 * i];
      every[j] = sum;
    }
    for (std::size_t k = 0; k < kept; ++k)
      for (int c = 0; c < 3; ++c) out[3 * (k0 + k) + c] = every[3 * m * k + c];
  }
}

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(WeightedRowSumT);
HWY_EXPORT(StridedTapSumT);

void WeightedRowSum(const float* const* rows, const float* weights, int count, std::size_t n,
                    float* out) {
  HWY_DYNAMIC_DISPATCH(WeightedRowSumT)(rows, weights, count, n, out);
}

void StridedTapSum(const float* in, const float* weights, int count, int stride, std::size_t n,
                   float* out) {
  HWY_DYNAMIC_DISPATCH(StridedTapSumT)(in, weights, count, stride, n, out);
}

}  // namespace lfcam
#endif  // HWY_ONCE
