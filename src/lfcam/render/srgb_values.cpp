// Highway's dynamic dispatch, as in simd_kernels.cpp: compiled once per instruction set.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/srgb_values.cpp"
#include "lfcam/render/srgb_values.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "lfcam/render/sample_rows-inl.h"

#ifndef LFCAM_RENDER_SRGB_VALUES_ONCE
#define LFCAM_RENDER_SRGB_VALUES_ONCE
#include <vector>

#include "lfcam/core/color.h"

namespace lfcam::srgb_values {

// The encoding table's codes widened to 32 bits: what a vector gather reads (256 KB, on the heap).
inline const std::int32_t* WideEncodeTable() {
  static const std::vector<std::int32_t> table(LinearToSrgb8EncodeTable().begin(),
                                               LinearToSrgb8EncodeTable().end());
  return table.data();
}

}  // namespace lfcam::srgb_values
#endif  // LFCAM_RENDER_SRGB_VALUES_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using D8 = hn::Rebind<std::uint8_t, DF>;

void DecodeSrgbValuesT(const std::uint8_t* in, std::size_t n, float* out) {
  const DF d;
  const DI di;
  const D8 d8;
  const float* table = SrgbDecodeTable().data();
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    hn::StoreU(hn::GatherIndex(d, table, hn::PromoteTo(di, hn::LoadU(d8, in + i))), d, out + i);
  for (; i < n; ++i) out[i] = table[in[i]];
}

void DecodeSrgbValuesComputedT(const std::uint8_t* in, std::size_t n, float* out) {
  const DF d;
  const DI di;
  const D8 d8;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    hn::StoreU(sample_rows::DecodeSrgb(hn::ConvertTo(d, hn::PromoteTo(di, hn::LoadU(d8, in + i)))),
               d, out + i);
  const float* table = SrgbDecodeTable().data();
  for (; i < n; ++i) out[i] = table[in[i]];
}

void EncodeSrgbValuesT(const float* in, std::size_t n, std::uint8_t* out) {
  const DF d;
  const DI di;
  const D8 d8;
  const std::int32_t* table = srgb_values::WideEncodeTable();
  const auto& codes = LinearToSrgb8EncodeTable();
  const std::size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f), scale = hn::Set(d, 65535.0f),
             half = hn::Set(d, 0.5f);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto v = hn::LoadU(d, in + i);
    // As LinearToSrgb8With: clamped to [0, 1], NaN to 0 (the comparison is false for it).
    const auto x = hn::IfThenElseZero(hn::Gt(v, zero), hn::Min(v, one));
    const auto index = hn::ConvertTo(di, hn::Add(hn::Mul(x, scale), half));
    hn::StoreU(hn::DemoteTo(d8, hn::GatherIndex(di, table, index)), d8, out + i);
  }
  for (; i < n; ++i) out[i] = LinearToSrgb8With(codes, in[i]);
}

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(DecodeSrgbValuesT);
HWY_EXPORT(DecodeSrgbValuesComputedT);
HWY_EXPORT(EncodeSrgbValuesT);

void DecodeSrgbValues(const std::uint8_t* in, std::size_t n, float* out) {
  HWY_DYNAMIC_DISPATCH(DecodeSrgbValuesT)(in, n, out);
}

void DecodeSrgbValuesComputed(const std::uint8_t* in, std::size_t n, float* out) {
  HWY_DYNAMIC_DISPATCH(DecodeSrgbValuesComputedT)(in, n, out);
}

void EncodeSrgbValues(const float* in, std::size_t n, std::uint8_t* out) {
  HWY_DYNAMIC_DISPATCH(EncodeSrgbValuesT)(in, n, out);
}

}  // namespace lfcam
#endif  // HWY_ONCE
