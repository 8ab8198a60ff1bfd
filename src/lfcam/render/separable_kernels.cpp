// Highway's dynamic dispatch, as in simd_kernels.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/separable_kernels.cpp"
#include "lfcam/render/separable_kernels.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <vector>

#include "lfcam/render/simd_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;

// Planar RGB rows.
struct Planes {
  std::vector<float> data;
  std::size_t stride = 0;
  void Resize(std::size_t rows, std::size_t length) {
    stride = length;
    if (data.size() < rows * 3 * length) data.resize(rows * 3 * length);
  }
  float* channel(std::size_t row, int c) {
    return data.data() + (row * 3 + std::size_t(c)) * stride;
  }
};

// Decodes `count` samples of one st row (RGB bytes from `bytes`) into linear planes: the bytes
// are loaded in order (the prefetcher streams them) and decoded through the table.
void DecodeRow(const RaySetup& s, const std::uint8_t* bytes, int count, float* r, float* g,
               float* b) {
  const DF d;
  const DI di;
  const hn::Rebind<std::uint8_t, DF> d8;
  const int lanes = int(hn::Lanes(d));
  std::uint8_t tail[3 * HWY_MAX_BYTES / 4] = {};
  for (int k = 0; k < count; k += lanes) {
    const std::uint8_t* at = bytes + std::size_t(k) * 3;
    if (k + lanes > count) {  // the last samples: never read past the row
      std::copy_n(at, std::size_t(count - k) * 3, tail);
      at = tail;
    }
    hn::Vec<decltype(d8)> v0, v1, v2;
    hn::LoadInterleaved3(d8, at, v0, v1, v2);
    hn::StoreU(hn::GatherIndex(d, s.decode, hn::PromoteTo(di, v0)), d, r + k);
    hn::StoreU(hn::GatherIndex(d, s.decode, hn::PromoteTo(di, v1)), d, g + k);
    hn::StoreU(hn::GatherIndex(d, s.decode, hn::PromoteTo(di, v2)), d, b + k);
  }
}

// out[i] = (in[i0[i] - lo] w0[i] + in[i1[i] - lo] w1[i]) mask[i] for the padded row. `in` is
// readable for Lanes() values past its last sample. Where a chunk's taps span fewer samples
// than a vector holds (a frame that magnifies the views), they are permuted out of one load
// instead of gathered.
void ResampleRow(const AxisMap& k, const std::vector<float>& mask, const float* in, float* out,
                 int padded) {
  const DF d;
  const DI di;
  const int lanes = int(hn::Lanes(d));
  for (int i = 0; i < padded; i += lanes) {
    const VI a = hn::LoadU(di, k.i0.data() + i), b = hn::LoadU(di, k.i1.data() + i);
    const int lo = hn::GetLane(hn::MinOfLanes(di, a));
    const int hi = hn::GetLane(hn::MaxOfLanes(di, b));
    VF tap0, tap1;
    if (hi - lo < lanes) {
      const VF window = hn::LoadU(d, in + (lo - k.lo));
      const VI base = hn::Set(di, lo);
      tap0 = hn::TableLookupLanes(window, hn::IndicesFromVec(d, hn::Sub(a, base)));
      tap1 = hn::TableLookupLanes(window, hn::IndicesFromVec(d, hn::Sub(b, base)));
    } else {
      const VI base = hn::Set(di, k.lo);
      tap0 = hn::GatherIndex(d, in, hn::Sub(a, base));
      tap1 = hn::GatherIndex(d, in, hn::Sub(b, base));
    }
    const VF v = hn::MulAdd(tap0, hn::LoadU(d, k.w0.data() + i),
                            hn::Mul(tap1, hn::LoadU(d, k.w1.data() + i)));
    hn::StoreU(hn::Mul(v, hn::LoadU(d, mask.data() + i)), d, out + i);
  }
}

// acc[i] += a x0[i] + b x1[i].
void BlendRows(float a, const float* x0, float b, const float* x1, float* acc, int padded) {
  const DF d;
  const VF va = hn::Set(d, a), vb = hn::Set(d, b);
  for (int i = 0; i < padded; i += int(hn::Lanes(d))) {
    const VF sum = hn::MulAdd(va, hn::LoadU(d, x0 + i), hn::LoadU(d, acc + i));
    hn::StoreU(hn::MulAdd(vb, hn::LoadU(d, x1 + i), sum), d, acc + i);
  }
}

}  // namespace

void RenderSeparableBandT(const SeparableFrame& f, const RaySetup& s, int j0, int j1,
                          const BandOutput& out) {
  const DF d;
  const int padded = PaddedRowWidth(f.width);
  const std::size_t band = std::size_t(j1 - j0) * std::size_t(padded);
  std::fill_n(out.r, band, 0.0f);
  std::fill_n(out.g, band, 0.0f);
  std::fill_n(out.b, band, 0.0f);
  std::vector<float> hits(band, 0.0f);

  Planes decoded, resampled;
  float* acc[3] = {out.r, out.g, out.b};
  for (const SeparableTerm& t : f.terms) {
    const SeparableOrigin& read = f.origins[std::size_t(t.read)];
    const SeparableOrigin& mask = f.origins[std::size_t(t.mask)];
    // The sample rows this band reads, where the mask's lines hit.
    int l_lo = s.n_t, l_hi = -1;
    for (int j = j0; j < j1; ++j) {
      if (mask.l.inside[std::size_t(j)] == 0.0f) continue;
      l_lo = std::min(l_lo, read.l.i0[std::size_t(j)]);
      l_hi = std::max(l_hi, read.l.i1[std::size_t(j)]);
    }
    if (l_hi < l_lo) continue;
    const int k_count = read.k.hi - read.k.lo + 1;
    decoded.Resize(1, std::size_t(k_count + int(hn::Lanes(d))));
    resampled.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(padded));
    const std::uint8_t* view = s.samples + std::size_t(t.view) * std::size_t(s.view_bytes);
    for (int l = l_lo; l <= l_hi; ++l) {
      const std::uint8_t* row = view + (std::size_t(l) * s.n_s + std::size_t(read.k.lo)) * 3;
      DecodeRow(s, row, k_count, decoded.channel(0, 0), decoded.channel(0, 1),
                decoded.channel(0, 2));
      for (int c = 0; c < 3; ++c)
        ResampleRow(read.k, mask.k.inside, decoded.channel(0, c),
                    resampled.channel(std::size_t(l - l_lo), c), padded);
    }
    for (int j = j0; j < j1; ++j) {
      const std::size_t js = std::size_t(j);
      if (mask.l.inside[js] == 0.0f) continue;
      const std::size_t r0 = std::size_t(read.l.i0[js] - l_lo),
                        r1 = std::size_t(read.l.i1[js] - l_lo);
      const std::size_t at = std::size_t(j - j0) * std::size_t(padded);
      for (int c = 0; c < 3; ++c)
        BlendRows(t.weight * read.l.w0[js], resampled.channel(r0, c), t.weight * read.l.w1[js],
                  resampled.channel(r1, c), acc[c] + at, padded);
    }
  }

  // Normalise: lens samples by the rays that hit, the cameras integrator by the eye's domain.
  for (int j = j0; j < j1; ++j) {
    const std::size_t at = std::size_t(j - j0) * std::size_t(padded);
    float* count = hits.data() + at;
    if (f.eye >= 0) {
      const SeparableOrigin& eye = f.origins[std::size_t(f.eye)];
      const float row = eye.l.inside[std::size_t(j)] * float(f.reads_per_pixel);
      for (int i = 0; i < padded; ++i) count[i] = row * eye.k.inside[std::size_t(i)];
    } else {
      for (const int o : f.hit_origins) {
        const SeparableOrigin& lens = f.origins[std::size_t(o)];
        if (lens.l.inside[std::size_t(j)] == 0.0f) continue;
        BlendRows(1.0f, lens.k.inside.data(), 0.0f, lens.k.inside.data(), count, padded);
      }
      for (int i = 0; i < padded; i += int(hn::Lanes(d))) {
        const VF n = hn::LoadU(d, count + i);
        const auto any = hn::Gt(n, hn::Zero(d));
        const VF inv = hn::IfThenElseZero(any, hn::Div(hn::Set(d, 1.0f), n));
        for (float* channel : acc)
          hn::StoreU(hn::Mul(hn::LoadU(d, channel + at + i), inv), d, channel + at + i);
      }
    }
    for (int i = 0; i < padded; ++i) out.count[at + std::size_t(i)] = std::int32_t(count[i]);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(RenderSeparableBandT);

void RenderSeparableBand(const SeparableFrame& frame, const RaySetup& source, int j0, int j1,
                         const BandOutput& out) {
  HWY_DYNAMIC_DISPATCH(RenderSeparableBandT)(frame, source, j0, j1, out);
}

}  // namespace lfcam
#endif
