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

// One axis's bilinear read for the pixels of a tile along it (its columns or its rows), for one
// line origin: the samples read and their weights, and where the line meets the domain.
struct TileMap {
  std::vector<std::int32_t> i0, i1;
  std::vector<float> w0, w1, inside;
  int lo = 0, hi = 0;  // every sample read lies in [lo, hi]
  void Resize(std::size_t n) {
    i0.resize(n);
    i1.resize(n);
    w0.resize(n);
    w1.resize(n);
    inside.resize(n);
  }
};

// The map of origin `o` over `count` pixels along one axis, where p_o's functions are
// n_at0 + n_step t and x_at0 + x_step t at the pixel t; `padded` entries (the rest read the
// first sample with no weight).
void ComputeMap(const OriginConstants& o, double n_at0, double n_step, double x_at0, double x_step,
                int count, int padded, int samples, TileMap& m) {
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
}

// out[i] = in[i0[i] - lo] w0[i] + in[i1[i] - lo] w1[i] for the padded row. `in` is
// readable for Lanes() values past its last sample. Where a chunk's taps span fewer samples
// than a vector holds (a frame that magnifies the views), they are permuted out of one load
// instead of gathered.
void ResampleRow(const TileMap& k, const float* in, float* out, int padded) {
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
    hn::StoreU(hn::MulAdd(tap0, hn::LoadU(d, k.w0.data() + i),
                          hn::Mul(tap1, hn::LoadU(d, k.w1.data() + i))),
               d, out + i);
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
// whether they meet the sampled domain.
struct Hit {
  VF k, l;
  hn::Mask<DF> inside;
};
Hit Project(const OriginConstants& o, const RowFunctions& row, const VF& pixel, int n_s, int n_t) {
  const DF d;
  const VF den =
      hn::Sub(hn::MulAdd(hn::Set(d, row.dn), pixel, hn::Set(d, row.n0)), hn::Set(d, o.n_o));
  const VF lambda = hn::Div(hn::Set(d, o.num), den);
  const VF x = hn::MulAdd(hn::Set(d, row.dx), pixel, hn::Set(d, row.x0));
  const VF y = hn::MulAdd(hn::Set(d, row.dy), pixel, hn::Set(d, row.y0));
  const VF k = hn::MulAdd(lambda, hn::Sub(x, hn::Set(d, o.x_o)), hn::Set(d, o.x0));
  const VF l = hn::MulAdd(lambda, hn::Sub(y, hn::Set(d, o.y_o)), hn::Set(d, o.y0));
  const VF lo = hn::Set(d, -0.5f);
  const auto in_k = hn::And(hn::Ge(k, lo), hn::Le(k, hn::Set(d, float(n_s) - 0.5f)));
  const auto in_l = hn::And(hn::Ge(l, lo), hn::Le(l, hn::Set(d, float(n_t) - 0.5f)));
  return {k, l, hn::And(in_k, in_l)};
}

// The st coordinates (double) of origin o's line through pixel (i, j)'s point in focus.
void Coordinates(const OriginConstants& o, const PlaneAffines& a, double i, double j, double* k,
                 double* l) {
  const double lambda = o.num / (a.n.at(i, j) - o.n_o);
  *k = o.x0 + lambda * (a.x.at(i, j) - o.x_o);
  *l = o.y0 + lambda * (a.y.at(i, j) - o.y_o);
}

// acc += weight * the term's view read along the lines from its `read` origin, where the lines
// from its `mask` origin meet the domain, for pixel rows [j0, j1); the mask's hits are added
// to `hits` when `count_hits`. `band_mask`, when given, is the mask's hits already (0 or 1 per
// pixel of the band: the cameras integrator's eye, the same for every term).
void AddTerm(const SeparableFrame& f, const RaySetup& s, const SeparableTerm& t, int j0, int j1,
             std::size_t stride, float* const acc[3], float* hits, bool count_hits,
             const float* band_mask, Planes& decoded, Planes& resampled, TileMap& k_map) {
  const DF d;
  const DI di;
  const int lanes = int(hn::Lanes(d));
  const int padded = int(stride);
  const OriginConstants& read = f.origins[std::size_t(t.read)];
  const OriginConstants& mask = f.origins[std::size_t(t.mask)];
  // The sample rows the band reads: l is monotonic along both axes, so its extremes lie at the
  // band's corners.
  double l_min = 1e300, l_max = -1e300, l_first = 0, l_last = 0, unused = 0;
  const double i_mid = 0.5 * (f.width - 1);
  for (const double i : {0.0, double(f.width - 1)})
    for (const int j : {j0, j1 - 1}) {
      double k, l;
      Coordinates(read, f.st, i, j, &k, &l);
      l_min = std::min(l_min, l);
      l_max = std::max(l_max, l);
    }
  Coordinates(read, f.st, i_mid, j0, &unused, &l_first);
  Coordinates(read, f.st, i_mid, j1 - 1, &unused, &l_last);
  const int top = s.n_t - 1;
  const int l_lo = std::clamp(int(std::floor(std::clamp(l_min, 0.0, double(top)))), 0, top);
  const int l_hi = std::clamp(int(std::floor(std::clamp(l_max, 0.0, double(top)))) + 1, 0, top);
  // Each sample row is resampled along k as the band row that reads it needs it (the nearest
  // to where l crosses it): the rows that read it lie within 1 / |dl/dj| of there, and k drifts
  // with the row by at most SeparableFrame::map_error over that.
  resampled.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(padded));
  const std::uint8_t* view = s.samples + std::size_t(t.view) * std::size_t(s.view_bytes);
  for (int l = l_lo; l <= l_hi; ++l) {
    double j_l = 0.5 * (j0 + j1 - 1);
    if (std::abs(l_last - l_first) > 1e-12)
      j_l = std::clamp(j0 + (l - l_first) / (l_last - l_first) * (j1 - 1 - j0), double(j0),
                       double(j1 - 1));
    // Where k does not drift with the row (map_error 0), one map serves every sample row.
    if (l == l_lo || f.map_error > 0)
      ComputeMap(read, f.st.n.at(0, j_l), f.st.n.di, f.st.x.at(0, j_l), f.st.x.di, f.width, padded,
                 s.n_s, k_map);
    const int k_count = k_map.hi - k_map.lo + 1;
    decoded.Resize(1, std::size_t(k_count + lanes));
    const std::uint8_t* row = view + (std::size_t(l) * s.n_s + std::size_t(k_map.lo)) * 3;
    DecodeRow(s, row, k_count, decoded.channel(0, 0), decoded.channel(0, 1), decoded.channel(0, 2));
    for (int c = 0; c < 3; ++c)
      ResampleRow(k_map, decoded.channel(0, c), resampled.channel(std::size_t(l - l_lo), c),
                  padded);
  }
  // Each pixel blends the resampled rows around its own l.
  const VF one = hn::Set(d, 1.0f), zero = hn::Zero(d), l_top = hn::Set(d, float(top));
  const VF weight = hn::Set(d, t.weight), width = hn::Set(d, float(f.width));
  const double last = f.width - 1, middle = 0.5 * last;
  for (int j = j0; j < j1; ++j) {
    const std::size_t at = std::size_t(j - j0) * stride;
    // l along the row, through its values at both ends and the middle: a projective function
    // whose curvature over a row is tiny, so the quadratic is exact to third order.
    double l_a, l_m, l_b, k_a, k_b, unused_k;
    Coordinates(read, f.st, 0, j, &unused_k, &l_a);
    Coordinates(read, f.st, middle, j, &unused_k, &l_m);
    Coordinates(read, f.st, last, j, &unused_k, &l_b);
    double qa = l_a, qb = 0, qc = 0;
    if (last > 0) {
      qc = 2 * (l_a - 2 * l_m + l_b) / (last * last);
      qb = (l_b - l_a) / last - qc * last;
    }
    const auto row_base = [&](double l) {
      return std::clamp(int(std::floor(std::clamp(l, 0.0, double(top)))), 0, std::max(0, top - 1));
    };
    // The mask's lines meet the domain all along the row when they do at both ends (the domain
    // is convex and the row's lines meet the st-plane along a segment).
    bool all_inside = false;
    if (band_mask == nullptr) {
      double l_ma, l_mb;
      Coordinates(mask, f.st, 0, j, &k_a, &l_ma);
      Coordinates(mask, f.st, last, j, &k_b, &l_mb);
      const auto in = [&](double k, double l) {
        return k >= -0.5 && k <= s.n_s - 0.5 && l >= -0.5 && l <= s.n_t - 0.5;
      };
      all_inside = in(k_a, l_ma) && in(k_b, l_mb);
    }
    const int base = row_base(l_a);
    if (base == row_base(l_b) && (all_inside || band_mask != nullptr)) {
      // One pair of sample rows for the whole row, each pixel with its own weights.
      const float* r0[3] = {resampled.channel(std::size_t(base - l_lo), 0),
                            resampled.channel(std::size_t(base - l_lo), 1),
                            resampled.channel(std::size_t(base - l_lo), 2)};
      const std::size_t next = std::size_t(std::min(base + 1, l_hi) - l_lo);
      const float* r1[3] = {resampled.channel(next, 0), resampled.channel(next, 1),
                            resampled.channel(next, 2)};
      const VF va = hn::Set(d, float(qa)), vb = hn::Set(d, float(qb)), vc = hn::Set(d, float(qc));
      const VF vbase = hn::Set(d, float(base));
      for (int i = 0; i < padded; i += lanes) {
        const VF pixel = hn::Iota(d, float(i));
        const auto real = hn::Lt(pixel, width);
        VF w = hn::IfThenElseZero(real, weight);
        if (band_mask != nullptr) w = hn::Mul(w, hn::LoadU(d, band_mask + at + i));
        if (count_hits)
          hn::StoreU(hn::Add(hn::LoadU(d, hits + at + i), hn::IfThenElseZero(real, one)), d,
                     hits + at + i);
        const VF l = hn::MulAdd(hn::MulAdd(vc, pixel, vb), pixel, va);
        const VF w1 = hn::Sub(hn::Min(hn::Max(l, zero), l_top), vbase);
        const VF a0 = hn::Mul(w, hn::Sub(one, w1)), a1 = hn::Mul(w, w1);
        for (int c = 0; c < 3; ++c) {
          const VF v = hn::MulAdd(a0, hn::LoadU(d, r0[c] + i), hn::LoadU(d, acc[c] + at + i));
          hn::StoreU(hn::MulAdd(a1, hn::LoadU(d, r1[c] + i), v), d, acc[c] + at + i);
        }
      }
      continue;
    }
    // Near the domain's edge, or where l crosses a sample row along the row: each pixel's own
    // projection, and a tent over three sample rows.
    const RowFunctions row(f.st, j);
    for (int i = 0; i < padded; i += lanes) {
      const VF pixel = hn::Iota(d, float(i));
      const Hit r = Project(read, row, pixel, s.n_s, s.n_t);
      VF w = hn::IfThenElseZero(hn::Lt(pixel, width), weight);
      if (band_mask != nullptr) {
        w = hn::Mul(w, hn::LoadU(d, band_mask + at + i));
      } else {
        const auto inside =
            t.mask == t.read ? r.inside : Project(mask, row, pixel, s.n_s, s.n_t).inside;
        w = hn::IfThenElseZero(inside, w);
        if (count_hits)
          hn::StoreU(hn::Add(hn::LoadU(d, hits + at + i), hn::IfThenElseZero(hn::Gt(w, zero), one)),
                     d, hits + at + i);
      }
      if (hn::AllFalse(d, hn::Gt(w, zero))) continue;
      const VF lc = hn::Min(hn::Max(r.l, zero), l_top);
      const int low =
          std::clamp(hn::GetLane(hn::MinOfLanes(di, hn::ConvertTo(di, lc))), l_lo, l_hi);
      const VF offset = hn::Sub(lc, hn::Set(d, float(low)));
      // The tent weights of rows low, low + 1, low + 2.
      const VF c0 = hn::Max(zero, hn::Sub(one, hn::Abs(offset)));
      const VF c1 = hn::Max(zero, hn::Sub(one, hn::Abs(hn::Sub(offset, one))));
      const VF c2 = hn::Max(zero, hn::Sub(one, hn::Abs(hn::Sub(offset, hn::Set(d, 2.0f)))));
      const std::size_t r0 = std::size_t(low - l_lo);
      const std::size_t r1 = std::size_t(std::min(low + 1, l_hi) - l_lo);
      const std::size_t r2 = std::size_t(std::min(low + 2, l_hi) - l_lo);
      for (int c = 0; c < 3; ++c) {
        VF v = hn::Mul(c0, hn::LoadU(d, resampled.channel(r0, c) + i));
        v = hn::MulAdd(c1, hn::LoadU(d, resampled.channel(r1, c) + i), v);
        v = hn::MulAdd(c2, hn::LoadU(d, resampled.channel(r2, c) + i), v);
        hn::StoreU(hn::MulAdd(w, v, hn::LoadU(d, acc[c] + at + i)), d, acc[c] + at + i);
      }
    }
  }
}

}  // namespace

void RenderSeparableBandT(const SeparableFrame& f, const RaySetup& s, int j0, int j1,
                          const BandOutput& out) {
  const DF d;
  const int padded = PaddedRowWidth(f.width);
  const std::size_t stride = std::size_t(padded), band = std::size_t(j1 - j0) * stride;
  float* const acc[3] = {out.r, out.g, out.b};
  for (float* channel : acc) std::fill_n(channel, band, 0.0f);
  std::vector<float> hits(band, 0.0f);
  if (f.eye >= 0) {
    // The cameras integrator: the eye's central lines decide the domain, for every term.
    const OriginConstants& eye = f.origins[std::size_t(f.eye)];
    for (int j = j0; j < j1; ++j) {
      const RowFunctions row(f.st, j);
      float* mask = hits.data() + std::size_t(j - j0) * stride;
      for (int i = 0; i < padded; i += int(hn::Lanes(d))) {
        const VF pixel = hn::Iota(d, float(i));
        const auto inside = hn::And(Project(eye, row, pixel, s.n_s, s.n_t).inside,
                                    hn::Lt(pixel, hn::Set(d, float(f.width))));
        hn::StoreU(hn::IfThenElseZero(inside, hn::Set(d, 1.0f)), d, mask + i);
      }
    }
  }
  Planes decoded, resampled;
  TileMap k_map;
  int counted_mask = -1;
  for (const SeparableTerm& t : f.terms) {
    // Lens samples: each one's hits are counted once (its terms come together).
    const bool count_hits = f.eye < 0 && t.mask != counted_mask;
    AddTerm(f, s, t, j0, j1, stride, acc, hits.data(), count_hits,
            f.eye >= 0 ? hits.data() : nullptr, decoded, resampled, k_map);
    if (count_hits) counted_mask = t.mask;
  }
  for (int j = j0; j < j1; ++j) {
    const std::size_t at = std::size_t(j - j0) * stride;
    float* count = hits.data() + at;
    if (f.eye >= 0) {
      for (int i = 0; i < padded; ++i) count[i] *= float(f.reads_per_pixel);
    } else {
      for (int i = 0; i < padded; i += int(hn::Lanes(d))) {
        const VF n = hn::LoadU(d, count + i);
        const VF inv = hn::IfThenElseZero(hn::Gt(n, hn::Zero(d)), hn::Div(hn::Set(d, 1.0f), n));
        for (float* channel : acc)
          hn::StoreU(hn::Mul(hn::LoadU(d, channel + at + i), inv), d, channel + at + i);
      }
    }
    for (int i = 0; i < padded; ++i) out.count[at + std::size_t(i)] = std::int32_t(count[i]);
  }
}

bool RenderRowCamerasResampledT(const RaySetup& s, const GridCameraWeight* uniform,
                                int uniform_count, const float* pixel_weights, const int* cameras,
                                int camera_count, int j, const RowOutput& out) {
  const DF d;
  const DI di;
  const int lanes = int(hn::Lanes(d));
  const int padded = PaddedRowWidth(s.width);
  const int count = uniform_count > 0 ? uniform_count : camera_count;
  const auto camera_at = [&](int n) {
    return uniform_count > 0 ? uniform[n].row * s.cols + uniform[n].col : cameras[n];
  };
  // Each camera's sample rows along the pixel row (l is monotonic along it: its ends decide).
  const double last = s.width - 1;
  std::vector<int> first_row(static_cast<std::size_t>(count)), last_row(first_row.size());
  const int top = s.n_t - 1;
  for (int n = 0; n < count; ++n) {
    const OriginConstants c = s.camera_st(camera_at(n));
    double k, l_a, l_b;
    Coordinates(c, s.st, 0, j, &k, &l_a);
    Coordinates(c, s.st, last, j, &k, &l_b);
    const auto row_of = [&](double l) {
      return std::isfinite(l) ? std::clamp(int(std::floor(std::clamp(l, 0.0, double(top)))), 0, top)
                              : -1;
    };
    const int a = row_of(std::min(l_a, l_b)), b = row_of(std::max(l_a, l_b));
    if (a < 0 || b < 0 || b + 1 - a >= kMaxResampledRows) return false;
    first_row[std::size_t(n)] = a;
    last_row[std::size_t(n)] = std::min(b + 1, top);
  }

  std::fill_n(out.r, padded, 0.0f);
  std::fill_n(out.g, padded, 0.0f);
  std::fill_n(out.b, padded, 0.0f);
  // The pixel's central line decides whether it meets the sampled st domain.
  const RowFunctions row(s.st, j);
  std::vector<float> domain(static_cast<std::size_t>(padded)), reads(domain.size(), 0.0f);
  for (int i = 0; i < padded; i += lanes) {
    const VF pixel = hn::Iota(d, float(i));
    const auto inside = hn::And(Project(s.eye_st, row, pixel, s.n_s, s.n_t).inside,
                                hn::Lt(pixel, hn::Set(d, float(s.width))));
    hn::StoreU(hn::IfThenElseZero(inside, hn::Set(d, 1.0f)), d, domain.data() + i);
  }
  Planes decoded, resampled;
  TileMap k_map;
  float* const acc[3] = {out.r, out.g, out.b};
  const VF one = hn::Set(d, 1.0f), zero = hn::Zero(d), l_top = hn::Set(d, float(top));
  for (int n = 0; n < count; ++n) {
    const int view_index = camera_at(n);
    const OriginConstants c = s.camera_st(view_index);
    const float* weights =
        uniform_count > 0 ? nullptr : pixel_weights + std::size_t(view_index) * padded;
    const VF uniform_weight = hn::Set(d, uniform_count > 0 ? float(uniform[n].weight) : 0.0f);
    const int l_lo = first_row[std::size_t(n)], l_hi = last_row[std::size_t(n)];
    ComputeMap(c, s.st.n.at(0, j), s.st.n.di, s.st.x.at(0, j), s.st.x.di, s.width, padded, s.n_s,
               k_map);
    const int k_count = k_map.hi - k_map.lo + 1;
    decoded.Resize(1, std::size_t(k_count + lanes));
    resampled.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(padded));
    const std::uint8_t* view = s.samples + std::size_t(view_index) * std::size_t(s.view_bytes);
    for (int l = l_lo; l <= l_hi; ++l) {
      DecodeRow(s, view + (std::size_t(l) * s.n_s + std::size_t(k_map.lo)) * 3, k_count,
                decoded.channel(0, 0), decoded.channel(0, 1), decoded.channel(0, 2));
      for (int ch = 0; ch < 3; ++ch)
        ResampleRow(k_map, decoded.channel(0, ch), resampled.channel(std::size_t(l - l_lo), ch),
                    padded);
    }
    for (int i = 0; i < padded; i += lanes) {
      VF w = weights ? hn::LoadU(d, weights + i) : uniform_weight;
      w = hn::Mul(w, hn::LoadU(d, domain.data() + i));
      const auto read = hn::Gt(w, zero);
      if (hn::AllFalse(d, read)) continue;
      hn::StoreU(hn::Add(hn::LoadU(d, reads.data() + i), hn::IfThenElseZero(read, one)), d,
                 reads.data() + i);
      // A tent over the sample rows around each pixel's own l.
      const VF lc =
          hn::Min(hn::Max(Project(c, row, hn::Iota(d, float(i)), s.n_s, s.n_t).l, zero), l_top);
      VF sum[3] = {zero, zero, zero};
      for (int l = l_lo; l <= l_hi; ++l) {
        const VF tent = hn::Max(zero, hn::Sub(one, hn::Abs(hn::Sub(lc, hn::Set(d, float(l))))));
        for (int ch = 0; ch < 3; ++ch)
          sum[ch] = hn::MulAdd(tent, hn::LoadU(d, resampled.channel(std::size_t(l - l_lo), ch) + i),
                               sum[ch]);
      }
      for (int ch = 0; ch < 3; ++ch)
        hn::StoreU(hn::MulAdd(w, sum[ch], hn::LoadU(d, acc[ch] + i)), d, acc[ch] + i);
    }
  }
  for (int i = 0; i < padded; ++i) out.count[i] = std::int32_t(reads[std::size_t(i)]);
  (void)di;
  return true;
}

}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {

HWY_EXPORT(RenderSeparableBandT);
HWY_EXPORT(RenderRowCamerasResampledT);

void RenderSeparableBand(const SeparableFrame& frame, const RaySetup& source, int j0, int j1,
                         const BandOutput& out) {
  HWY_DYNAMIC_DISPATCH(RenderSeparableBandT)(frame, source, j0, j1, out);
}

bool RenderRowCamerasResampled(const RaySetup& setup, const GridCameraWeight* uniform,
                               int uniform_count, const float* pixel_weights, const int* cameras,
                               int camera_count, int j, const RowOutput& out) {
  return HWY_DYNAMIC_DISPATCH(RenderRowCamerasResampledT)(
      setup, uniform, uniform_count, pixel_weights, cameras, camera_count, j, out);
}

}  // namespace lfcam
#endif
