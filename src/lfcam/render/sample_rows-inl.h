// The vectorised helpers both kernel files share (Highway's per-target inline header: included
// once per instruction set by each kernel file, inside its target's namespace): decoding sample
// rows (8-bit sRGB, or converting linear half floats), a row of bilinear reads along k, and the
// lines from an origin through a pixel row's points in focus.
#if defined(LFCAM_RENDER_SAMPLE_ROWS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef LFCAM_RENDER_SAMPLE_ROWS_INL_H_
#undef LFCAM_RENDER_SAMPLE_ROWS_INL_H_
#else
#define LFCAM_RENDER_SAMPLE_ROWS_INL_H_
#endif

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lfcam/render/ray_setup.h"

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace sample_rows {

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

// An 8-bit sRGB level (0 .. 255, as a float) in linear light, computed rather than looked up: a
// table lookup is a gather, which costs several times the arithmetic. Levels up to 10 are
// linear (x / 12.92); above, ((x + 0.055) / 1.055)^2.4 is a degree-7 polynomial in
// t = (level - 133) / 122, fitted (Chebyshev least squares) at the 245 levels it serves: within
// 4.7e-6 of the table everywhere, 0.015 of an 8-bit level once encoded again.
inline VF DecodeSrgb(const VF level) {
  const DF d;
  const VF t = hn::Mul(hn::Sub(level, hn::Set(d, 133.0f)), hn::Set(d, 1.0f / 122.0f));
  VF p = hn::Set(d, 3.006680926773697e-4f);
  p = hn::MulAdd(p, t, hn::Set(d, -5.813003517687321e-4f));
  p = hn::MulAdd(p, t, hn::Set(d, 8.660047315061092e-4f));
  p = hn::MulAdd(p, t, hn::Set(d, -3.5838973708450794e-3f));
  p = hn::MulAdd(p, t, hn::Set(d, 3.005448542535305e-2f));
  p = hn::MulAdd(p, t, hn::Set(d, 0.27129051089286804f));
  p = hn::MulAdd(p, t, hn::Set(d, 0.46710440516471863f));
  p = hn::MulAdd(p, t, hn::Set(d, 0.23455147445201874f));
  const VF linear = hn::Mul(level, hn::Set(d, float(1.0 / (255.0 * 12.92))));
  return hn::IfThenElse(hn::Lt(level, hn::Set(d, 10.5f)), linear, p);
}

// Decodes `count` samples of one st row (RGB bytes from `bytes`) into linear planes: the bytes
// are loaded in order and decoded by DecodeSrgb. `next`, when given, is the row to be decoded
// next (as many bytes): it is fetched into the cache meanwhile, since a frame reads short runs
// of many rows, each too short for the hardware's prefetcher to ramp up.
inline void DecodeRow(const std::uint8_t* bytes, int count, float* r, float* g, float* b,
                      const std::uint8_t* next = nullptr) {
  const DF d;
  const DI di;
  const hn::Rebind<std::uint8_t, DF> d8;
  const int lanes = int(hn::Lanes(d));
  std::uint8_t tail[3 * HWY_MAX_BYTES / 4] = {};
  for (int k = 0; k < count; k += lanes) {
    const std::uint8_t* at = bytes + std::size_t(k) * 3;
    if (next != nullptr) hwy::Prefetch(next + std::size_t(k) * 3);
    if (k + lanes > count) {  // the last samples: never read past the row
      std::copy_n(at, std::size_t(count - k) * 3, tail);
      at = tail;
    }
    hn::Vec<decltype(d8)> v0, v1, v2;
    hn::LoadInterleaved3(d8, at, v0, v1, v2);
    hn::StoreU(DecodeSrgb(hn::ConvertTo(d, hn::PromoteTo(di, v0))), d, r + k);
    hn::StoreU(DecodeSrgb(hn::ConvertTo(d, hn::PromoteTo(di, v1))), d, g + k);
    hn::StoreU(DecodeSrgb(hn::ConvertTo(d, hn::PromoteTo(di, v2))), d, b + k);
  }
}

// Converts `count` samples of one st row of a linear half-float light field (RGB, three IEEE
// binary16 values a sample, `halves`) into linear planes: one conversion a value (F16C where
// the instruction set has it), no decoding. `next` as in DecodeRow.
inline void ConvertHalfRow(const std::uint16_t* halves, int count, float* r, float* g, float* b,
                           const std::uint16_t* next = nullptr) {
  const DF d;
  const hn::Rebind<std::uint16_t, DF> d16;
  const hn::Rebind<hwy::float16_t, DF> dh;
  const int lanes = int(hn::Lanes(d));
  std::uint16_t tail[3 * HWY_MAX_BYTES / 4] = {};
  for (int k = 0; k < count; k += lanes) {
    const std::uint16_t* at = halves + std::size_t(k) * 3;
    if (next != nullptr) {  // twice the bytes of DecodeRow's step: two cache lines
      hwy::Prefetch(next + std::size_t(k) * 3);
      hwy::Prefetch(next + std::size_t(k) * 3 + 32);
    }
    if (k + lanes > count) {  // the last samples: never read past the row
      std::copy_n(at, std::size_t(count - k) * 3, tail);
      at = tail;
    }
    hn::Vec<decltype(d16)> v0, v1, v2;
    hn::LoadInterleaved3(d16, at, v0, v1, v2);
    hn::StoreU(hn::PromoteTo(d, hn::BitCast(dh, v0)), d, r + k);
    hn::StoreU(hn::PromoteTo(d, hn::BitCast(dh, v1)), d, g + k);
    hn::StoreU(hn::PromoteTo(d, hn::BitCast(dh, v2)), d, b + k);
  }
}

// Sample row `l` of view `view` (0-based, row-major) from sample `k0`, `count` samples, into
// linear planes, whatever the light field stores (RaySetup::half_floats); the next row is
// prefetched meanwhile when `prefetch_next`.
inline void ReadSampleRow(const RaySetup& s, int view, int l, int k0, int count, bool prefetch_next,
                          float* r, float* g, float* b) {
  const std::size_t first =
      std::size_t(view) * std::size_t(s.view_bytes) +
      (std::size_t(l) * std::size_t(s.n_s) + std::size_t(k0)) * std::size_t(s.sample_bytes);
  const std::size_t row_bytes = std::size_t(s.n_s) * std::size_t(s.sample_bytes);
  const std::uint8_t* row = s.samples + first;
  const std::uint8_t* next = prefetch_next ? row + row_bytes : nullptr;
  if (s.half_floats)
    ConvertHalfRow(reinterpret_cast<const std::uint16_t*>(row), count, r, g, b,
                   reinterpret_cast<const std::uint16_t*>(next));
  else
    DecodeRow(row, count, r, g, b, next);
}

// One axis's bilinear read for the pixels of a tile along it (its columns or its rows), for one
// line origin: the samples read and their weights, and where the line meets the domain.
struct TileMap {
  std::vector<std::int32_t> i0, i1;
  std::vector<float> w0, w1, inside;
  int lo = 0, hi = 0;  // every sample read lies in [lo, hi]
  // Per vector of pixels (a chunk): the first sample of the window its taps lie in when they
  // span fewer samples than a vector holds (a frame that magnifies the views: they are permuted
  // out of one load), else kGather; and i0, i1 less that window's start.
  static constexpr std::int32_t kGather = -1;
  std::vector<std::int32_t> window, p0, p1;
  void Resize(std::size_t n) {
    i0.resize(n);
    i1.resize(n);
    w0.resize(n);
    w1.resize(n);
    inside.resize(n);
    p0.resize(n);
    p1.resize(n);
  }
};

// The map of origin `o` over `count` pixels along one axis, where p_o's functions are
// n_at0 + n_step t and x_at0 + x_step t at the pixel t; `padded` entries (the rest read the
// first sample with no weight).
inline void ComputeMap(const OriginConstants& o, double n_at0, double n_step, double x_at0,
                       double x_step, int count, int padded, int samples, TileMap& m) {
  const DF d;
  const DI di;
  m.Resize(std::size_t(padded));
  const VF num = hn::Set(d, o.num), n_o = hn::Set(d, o.n_o), x_o = hn::Set(d, o.x_o),
           x0 = hn::Set(d, o.x0);
  const VF n0 = hn::Set(d, float(n_at0)), dn = hn::Set(d, float(n_step));
  const VF xa0 = hn::Set(d, float(x_at0)), dx = hn::Set(d, float(x_step));
  const VF lo = hn::Set(d, -0.5f), hi = hn::Set(d, float(samples) - 0.5f), one = hn::Set(d, 1.0f);
  const VF top = hn::Set(d, float(samples - 1));
  for (int t = 0; t < padded; t += int(hn::Lanes(d))) {
    const VF pos = hn::Iota(d, float(t));
    const VF den = hn::Sub(hn::MulAdd(dn, pos, n0), n_o);
    const VF x = hn::MulAdd(hn::Div(num, den), hn::Sub(hn::MulAdd(dx, pos, xa0), x_o), x0);
    const auto real = hn::And(hn::Lt(pos, hn::Set(d, float(count))), hn::Eq(x, x));
    const auto in = hn::And(real, hn::And(hn::Ge(x, lo), hn::Le(x, hi)));
    // AxisLerp: clamped to [0, samples - 1], split into i0, i1 and w1.
    const VF xc = hn::Min(hn::Max(hn::IfThenElseZero(real, x), hn::Zero(d)), top);
    const VI i0 = hn::Max(hn::Min(hn::ConvertTo(di, xc), hn::Set(di, samples - 2)), hn::Zero(di));
    const VI i1 = hn::Min(hn::Add(i0, hn::Set(di, 1)), hn::Set(di, samples - 1));
    const VF w1 = hn::IfThenElseZero(real, hn::Sub(xc, hn::ConvertTo(d, i0)));
    hn::StoreU(i0, di, m.i0.data() + t);
    hn::StoreU(i1, di, m.i1.data() + t);
    hn::StoreU(hn::IfThenElseZero(real, hn::Sub(one, w1)), d, m.w0.data() + t);
    hn::StoreU(w1, d, m.w1.data() + t);
    hn::StoreU(hn::IfThenElseZero(in, one), d, m.inside.data() + t);
  }
  // The map is monotonic: its extremes lie at its ends.
  const std::size_t end = std::size_t(std::max(count, 1) - 1);
  m.lo = std::min(m.i0[0], m.i0[end]);
  m.hi = std::max(m.i1[0], m.i1[end]);
  for (int t = count; t < padded; ++t) m.i0[std::size_t(t)] = m.i1[std::size_t(t)] = m.lo;
  const int lanes = int(hn::Lanes(d));
  m.window.resize(std::size_t(padded / lanes));
  for (int t = 0; t < padded; t += lanes) {
    const auto first = m.i0.begin() + t, last = m.i0.begin() + t + lanes;
    const int lo_t = *std::min_element(first, last);
    const int hi_t = *std::max_element(m.i1.begin() + t, m.i1.begin() + t + lanes);
    const bool permute = hi_t - lo_t < lanes;
    m.window[std::size_t(t / lanes)] = permute ? lo_t : TileMap::kGather;
    for (int u = t; u < t + lanes; ++u) {
      m.p0[std::size_t(u)] = m.i0[std::size_t(u)] - (permute ? lo_t : m.lo);
      m.p1[std::size_t(u)] = m.i1[std::size_t(u)] - (permute ? lo_t : m.lo);
    }
  }
}

// out[c][i] = in[c][i0[i] - lo] w0[i] + in[c][i1[i] - lo] w1[i] for the padded row, for the
// three channels c. Each `in` is readable for Lanes() values past its last sample.
inline void ResampleRow(const TileMap& k, const float* const in[3], float* const out[3],
                        int padded) {
  const DF d;
  const DI di;
  const int lanes = int(hn::Lanes(d));
  for (int i = 0; i < padded; i += lanes) {
    const VI a = hn::LoadU(di, k.p0.data() + i), b = hn::LoadU(di, k.p1.data() + i);
    const VF w0 = hn::LoadU(d, k.w0.data() + i), w1 = hn::LoadU(d, k.w1.data() + i);
    const std::int32_t window = k.window[std::size_t(i / lanes)];
    if (window != TileMap::kGather) {
      const auto ia = hn::IndicesFromVec(d, a), ib = hn::IndicesFromVec(d, b);
      for (int c = 0; c < 3; ++c) {
        const VF v = hn::LoadU(d, in[c] + (window - k.lo));
        hn::StoreU(
            hn::MulAdd(hn::TableLookupLanes(v, ia), w0, hn::Mul(hn::TableLookupLanes(v, ib), w1)),
            d, out[c] + i);
      }
    } else {
      for (int c = 0; c < 3; ++c)
        hn::StoreU(
            hn::MulAdd(hn::GatherIndex(d, in[c], a), w0, hn::Mul(hn::GatherIndex(d, in[c], b), w1)),
            d, out[c] + i);
    }
  }
}

// p_o's functions along pixel row j: value(i) = at0 + step i.
struct RowFunctions {
  float n0, dn, x0, dx, y0, dy;
  RowFunctions(const PlaneAffines& a, double j)
      : n0(float(a.n.at(0, j))),
        dn(float(a.n.di)),
        x0(float(a.x.at(0, j))),
        dx(float(a.x.di)),
        y0(float(a.y.at(0, j))),
        dy(float(a.y.di)) {}
};

// Where the lines from origin `o` through the chunk's points in focus meet the st-plane, and
// whether they meet `bounds` (lo k, lo l, hi k, hi l: the sampled domain, RaySetup::domain).
struct Hit {
  VF k, l;
  hn::Mask<DF> inside;
};
inline Hit Project(const OriginConstants& o, const RowFunctions& row, const VF& pixel,
                   const float bounds[4]) {
  const DF d;
  const VF den =
      hn::Sub(hn::MulAdd(hn::Set(d, row.dn), pixel, hn::Set(d, row.n0)), hn::Set(d, o.n_o));
  const VF lambda = hn::Div(hn::Set(d, o.num), den);
  const VF x = hn::MulAdd(hn::Set(d, row.dx), pixel, hn::Set(d, row.x0));
  const VF y = hn::MulAdd(hn::Set(d, row.dy), pixel, hn::Set(d, row.y0));
  const VF k = hn::MulAdd(lambda, hn::Sub(x, hn::Set(d, o.x_o)), hn::Set(d, o.x0));
  const VF l = hn::MulAdd(lambda, hn::Sub(y, hn::Set(d, o.y_o)), hn::Set(d, o.y0));
  const auto in_k = hn::And(hn::Ge(k, hn::Set(d, bounds[0])), hn::Le(k, hn::Set(d, bounds[2])));
  const auto in_l = hn::And(hn::Ge(l, hn::Set(d, bounds[1])), hn::Le(l, hn::Set(d, bounds[3])));
  return {k, l, hn::And(in_k, in_l)};
}
// ... and whether they meet [-0.5, n_s - 0.5] x [-0.5, n_t - 0.5] (one view's window, or the
// shared grid).
inline Hit Project(const OriginConstants& o, const RowFunctions& row, const VF& pixel, int n_s,
                   int n_t) {
  const float bounds[4] = {-0.5f, -0.5f, float(n_s) - 0.5f, float(n_t) - 0.5f};
  return Project(o, row, pixel, bounds);
}

// TentShareInside (render/window_taper.h) per lane: the share of a tent of half-width h centred
// at x inside [lo, hi]; with h 0 the hard edge (1 inside, ends included).
inline VF TentShare(const VF& x, float lo, float hi, float h) {
  const DF d;
  const VF one = hn::Set(d, 1.0f);
  if (!(h > 0)) {
    return hn::IfThenElseZero(hn::And(hn::Ge(x, hn::Set(d, lo)), hn::Le(x, hn::Set(d, hi))), one);
  }
  const VF inv = hn::Set(d, 1.0f / h), half = hn::Set(d, 0.5f);
  // The tent's distribution function at z half-widths from its centre.
  const auto below = [&](VF z) {
    z = hn::Min(hn::Max(z, hn::Neg(one)), one);
    return hn::NegMulAdd(hn::Mul(half, z), hn::Abs(z), hn::Add(half, z));
  };
  const VF share = hn::Add(below(hn::Mul(hn::Sub(hn::Set(d, hi), x), inv)),
                           below(hn::Mul(hn::Sub(x, hn::Set(d, lo)), inv)));
  return hn::Max(hn::Zero(d), hn::Sub(share, one));
}

// Camera `index`'s share of its tent inside its view's window at its own sample coordinates
// (k, l) (RaySetup::taper_window).
inline VF WindowShare(const RaySetup& s, int index, const VF& k, const VF& l) {
  const float* w = s.taper_window.data() + 4 * std::size_t(index);
  return hn::Mul(TentShare(k, w[0], w[2], s.taper_h[0]), TentShare(l, w[1], w[3], s.taper_h[1]));
}
// Whether the share is 1 all along a pixel row whose line runs from (k_a, l_a) to (k_b, l_b):
// both ends lie at least the tent's half-widths inside the window (it is convex).
inline bool WholeShareAlong(const RaySetup& s, int index, double k_a, double l_a, double k_b,
                            double l_b) {
  const float* w = s.taper_window.data() + 4 * std::size_t(index);
  const auto inside = [&](double k, double l) {
    return k >= w[0] + s.taper_h[0] && k <= w[2] - s.taper_h[0] && l >= w[1] + s.taper_h[1] &&
           l <= w[3] - s.taper_h[1];
  };
  return inside(k_a, l_a) && inside(k_b, l_b);
}

// The st coordinates (double) of origin o's line through pixel (i, j)'s point in focus.
inline void Coordinates(const OriginConstants& o, const PlaneAffines& a, double i, double j,
                        double* k, double* l) {
  const double lambda = o.num / (a.n.at(i, j) - o.n_o);
  *k = o.x0 + lambda * (a.x.at(i, j) - o.x_o);
  *l = o.y0 + lambda * (a.y.at(i, j) - o.y_o);
}

}  // namespace sample_rows
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#endif  // LFCAM_RENDER_SAMPLE_ROWS_INL_H_
