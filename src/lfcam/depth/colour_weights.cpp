// Highway's dynamic dispatch, as depth/local_planes.cpp: compiled once per instruction set, so
// that the table holds the exponential of the instruction set the kernels that read it run.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/depth/colour_weights.cpp"
#include "lfcam/depth/colour_weights.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>
// After highway.h, once per instruction set:
#include <hwy/contrib/math/math-inl.h>

#ifndef LFCAM_DEPTH_COLOUR_WEIGHTS_ONCE
#define LFCAM_DEPTH_COLOUR_WEIGHTS_ONCE
#include <cstddef>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam::colour_weights {

constexpr int kLargestSquaredDistance = 3 * 255 * 255;

}  // namespace lfcam::colour_weights
#endif  // LFCAM_DEPTH_COLOUR_WEIGHTS_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;

// out[n] = exp(n · scale) for n < count (a whole number of vectors: `out` has room).
void ExpOfSquaredDistancesT(float scale, std::size_t count, float* out) {
  const DF d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t n = 0; n < count; n += lanes)
    hn::StoreU(hn::Exp(d, hn::Mul(hn::Iota(d, float(n)), hn::Set(d, scale))), d, out + n);
}

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(ExpOfSquaredDistancesT);

ColourWeights MakeColourWeights(float scale) {
  if (!(scale < 0)) throw Error("MakeColourWeights: the colour scale must be negative");
  constexpr std::size_t kCount = colour_weights::kLargestSquaredDistance + 1;
  ColourWeights table;
  table.weight.resize(kCount + 64);  // room for the last vector, whatever its width
  HWY_DYNAMIC_DISPATCH(ExpOfSquaredDistancesT)(scale, kCount, table.weight.data());
  table.weight.resize(kCount);
  // Where every larger distance weighs 0, the table ends at the first of them.
  int last = int(kCount) - 1;
  if (table.weight[std::size_t(last)] == 0.0f)
    while (last > 0 && table.weight[std::size_t(last - 1)] == 0.0f) --last;
  table.weight.resize(std::size_t(last) + 1);
  table.last = last;
  return table;
}

}  // namespace lfcam
#endif  // HWY_ONCE
