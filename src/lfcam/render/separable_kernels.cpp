// Highway's dynamic dispatch, as in simd_kernels.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/render/separable_kernels.cpp"
#include "lfcam/render/separable_kernels.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <vector>

#include "lfcam/render/sample_rows-inl.h"
#include "lfcam/render/simd_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

using namespace sample_rows;  // NOLINT: the shared helpers of this instruction set

// acc += weight * the term's view read along the lines from its `read` origin, where the lines
// from its `mask` origin meet the domain, for pixel rows [j0, j1); the mask's hits are counted
// in `hits` when `count_hits`, and the weight in `held` when given (the cameras integrator
// renormalises by it): per pixel, or once for a row in `row_hits` and `row_held` (one for each
// row of the band) where every pixel of the row counts, so that the blend's common path stores
// nothing but its colour. With a taper (RaySetup::taper, the cameras integrator's) the term counts
// by the share of its tent inside its view's window, at the read's own coordinates.
//
// With per-pixel weights (`per_pixel`, SeparableFrame::pixel_weights) the term weighs each pixel
// by its own weight. Where its reads are whole along a row it counts nothing and marks itself in
// `per_pixel.whole` (the row's weights and cameras, summed once, are then the row's counts);
// elsewhere it counts per pixel, as above, and marks the row in `per_pixel.partial`.
struct PixelWeights {
  const float* weights = nullptr;  // [row of the band][view][pixel]
  // [row of the band][view][2]: the pixels [begin, end) that hold its weights, whole vectors
  // (a footprint that sweeps across the array along the row weighs each camera over a part);
  // empty where the view weighs no pixel of the row.
  const int* spans = nullptr;
  std::size_t views = 0;
  char* whole = nullptr;    // [row of the band][view]: read whole along the row
  char* partial = nullptr;  // [row of the band]: some view was not
};
void AddTerm(const SeparableFrame& f, const RaySetup& s, const SeparableTerm& t, int j0, int j1,
             std::size_t stride, float* const sums[3], float* hits, bool count_hits, float* held,
             float* row_hits, float* row_held, const PixelWeights& per_pixel, Planes& decoded,
             Planes& band_decoded, Planes& resampled, TileMap& k_map,
             std::vector<int>& resampled_for) {
  // The rows' pointers held here, where no store through them can change them (read through
  // `sums` they were loaded again at every store).
  float* const acc[3] = {sums[0], sums[1], sums[2]};
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
  // At most the last row but one, as the rows' base below is, so that the pair of rows a row
  // blends (base, base + 1) is always among those resampled, even where the band's reads all lie
  // beyond the view's last row (a lens sample through another view's window).
  const int l_lo =
      std::clamp(int(std::floor(std::clamp(l_min, 0.0, double(top)))), 0, std::max(0, top - 1));
  const int l_hi = std::clamp(int(std::floor(std::clamp(l_max, 0.0, double(top)))) + 1, 0, top);
  // Each sample row is resampled along k as the band row that reads it needs it (the nearest
  // to where l crosses it): the rows that read it lie within 1 / |dl/dj| of there, and k drifts
  // with the row by at most SeparableFrame::map_error over that.
  resampled.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(padded));
  // k drifting with the pixel row (SeparableFrame::resample_every): each sample row decoded once
  // for the band, over the samples the band's first and last rows' maps reach (with a sample
  // of margin), and resampled for each group of rows that reads it, when one first does.
  const int every = f.resample_every;
  int band_k_lo = 0, band_k_hi = -1, map_group = -1;
  if (every > 0) {
    for (const int j : {j0, j1 - 1}) {
      ComputeMap(read, f.st.n.at(0, j), f.st.n.di, f.st.x.at(0, j), f.st.x.di, f.width, padded,
                 s.n_s, k_map);
      band_k_lo = j == j0 ? k_map.lo : std::min(band_k_lo, k_map.lo);
      band_k_hi = j == j0 ? k_map.hi : std::max(band_k_hi, k_map.hi);
    }
    band_k_lo = std::max(0, band_k_lo - 1);
    band_k_hi = std::min(s.n_s - 1, band_k_hi + 1);
    const int count = band_k_hi - band_k_lo + 1;
    band_decoded.Resize(std::size_t(l_hi - l_lo + 1), std::size_t(count + lanes));
    for (int l = l_lo; l <= l_hi; ++l) {
      const std::size_t at = std::size_t(l - l_lo);
      ReadSampleRow(s, t.view, l, band_k_lo, count, l < l_hi, band_decoded.channel(at, 0),
                    band_decoded.channel(at, 1), band_decoded.channel(at, 2));
    }
    resampled_for.assign(std::size_t(l_hi - l_lo + 1), -1);
  }
  // Sample row l resampled for pixel row j's group, unless it is already.
  const auto ensure = [&](int l, int j) {
    if (every == 0) return;
    const int group = (j - j0) / every;
    int& made = resampled_for[std::size_t(l - l_lo)];
    if (made == group) return;
    if (map_group != group) {
      const int first = j0 + group * every, last = std::min(first + every, j1) - 1;
      const double j_c = 0.5 * (first + last);
      ComputeMap(read, f.st.n.at(0, j_c), f.st.n.di, f.st.x.at(0, j_c), f.st.x.di, f.width, padded,
                 s.n_s, k_map);
      map_group = group;
    }
    const std::size_t at = std::size_t(l - l_lo);
    const float* in[3];
    if (k_map.lo >= band_k_lo && k_map.hi <= band_k_hi) {
      for (int c = 0; c < 3; ++c) in[c] = band_decoded.channel(at, c) + (k_map.lo - band_k_lo);
    } else {  // beyond the band's decoded samples (float rounding): this row's own
      const int k_count = k_map.hi - k_map.lo + 1;
      decoded.Resize(1, std::size_t(k_count + lanes));
      ReadSampleRow(s, t.view, l, k_map.lo, k_count, false, decoded.channel(0, 0),
                    decoded.channel(0, 1), decoded.channel(0, 2));
      for (int c = 0; c < 3; ++c) in[c] = decoded.channel(0, c);
    }
    float* const out[3] = {resampled.channel(at, 0), resampled.channel(at, 1),
                           resampled.channel(at, 2)};
    ResampleRow(k_map, in, out, padded);
    made = group;
  };
  for (int l = l_lo; every == 0 && l <= l_hi; ++l) {
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
    ReadSampleRow(s, t.view, l, k_map.lo, k_count, l < l_hi, decoded.channel(0, 0),
                  decoded.channel(0, 1), decoded.channel(0, 2));
    const float* const in[3] = {decoded.channel(0, 0), decoded.channel(0, 1),
                                decoded.channel(0, 2)};
    const std::size_t at = std::size_t(l - l_lo);
    float* const out[3] = {resampled.channel(at, 0), resampled.channel(at, 1),
                           resampled.channel(at, 2)};
    ResampleRow(k_map, in, out, padded);
  }
  // Each pixel blends the resampled rows around its own l.
  const VF one = hn::Set(d, 1.0f), zero = hn::Zero(d), l_top = hn::Set(d, float(top));
  const VF weight = hn::Set(d, t.weight), width = hn::Set(d, float(f.width));
  const double last = f.width - 1, middle = 0.5 * last;
  for (int j = j0; j < j1; ++j) {
    const std::size_t at = std::size_t(j - j0) * stride;
    const float* own = nullptr;  // this term's weight for each pixel of the row
    int i_begin = 0, i_end = padded;
    if (per_pixel.weights != nullptr) {
      const std::size_t slot = std::size_t(j - j0) * per_pixel.views + std::size_t(t.view);
      i_begin = per_pixel.spans[2 * slot];
      i_end = per_pixel.spans[2 * slot + 1];
      if (i_begin >= i_end) continue;  // no pixel of the row weighs it
      own = per_pixel.weights + slot * stride;
    }
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
    // With a taper, the read's own lines at their whole share along the row.
    double l_ma, l_mb;
    Coordinates(s.taper ? read : mask, f.st, 0, j, &k_a, &l_ma);
    Coordinates(s.taper ? read : mask, f.st, last, j, &k_b, &l_mb);
    const auto in = [&](double k, double l) {
      return k >= s.domain[0] && k <= s.domain[2] && l >= s.domain[1] && l <= s.domain[3];
    };
    const bool all_inside =
        s.taper ? WholeShareAlong(s, t.view, k_a, l_ma, k_b, l_mb) : in(k_a, l_ma) && in(k_b, l_mb);
    const int base = row_base(l_a);
    if (base == row_base(l_b) && all_inside) {
      ensure(base, j);
      ensure(std::min(base + 1, l_hi), j);
      // One pair of sample rows for the whole row, each pixel with its own weights.
      const float* r0[3] = {resampled.channel(std::size_t(base - l_lo), 0),
                            resampled.channel(std::size_t(base - l_lo), 1),
                            resampled.channel(std::size_t(base - l_lo), 2)};
      const std::size_t next = std::size_t(std::min(base + 1, l_hi) - l_lo);
      const float* r1[3] = {resampled.channel(next, 0), resampled.channel(next, 1),
                            resampled.channel(next, 2)};
      const VF va = hn::Set(d, float(qa)), vb = hn::Set(d, float(qb)), vc = hn::Set(d, float(qc));
      const VF vbase = hn::Set(d, float(base));
      // Every pixel of the row counts: once for the row (with per-pixel weights, at the end).
      if (own != nullptr) {
        per_pixel.whole[std::size_t(j - j0) * per_pixel.views + std::size_t(t.view)] = 1;
      } else {
        if (count_hits) row_hits[j - j0] += 1.0f;
        if (held != nullptr) row_held[j - j0] += t.weight;
      }
      // The loop for each kind of weight on its own: the blend is most of a frame whose views
      // are magnified, and a choice made in it cost a uniform frame 10-15%.
      const auto blend = [&](auto weight_at) {
        for (int i = i_begin; i < i_end; i += lanes) {
          const VF pixel = hn::Iota(d, float(i));
          const VF w = hn::IfThenElseZero(hn::Lt(pixel, width), weight_at(i));
          const VF l = hn::MulAdd(hn::MulAdd(vc, pixel, vb), pixel, va);
          const VF w1 = hn::Sub(hn::Min(hn::Max(l, zero), l_top), vbase);
          const VF a0 = hn::Mul(w, hn::Sub(one, w1)), a1 = hn::Mul(w, w1);
          for (int c = 0; c < 3; ++c) {
            const VF v = hn::MulAdd(a0, hn::LoadU(d, r0[c] + i), hn::LoadU(d, acc[c] + at + i));
            hn::StoreU(hn::MulAdd(a1, hn::LoadU(d, r1[c] + i), v), d, acc[c] + at + i);
          }
        }
      };
      if (own != nullptr)
        blend([&](int i) { return hn::LoadU(d, own + i); });
      else
        blend([&](int) { return weight; });
      continue;
    }
    // Near the domain's edge, or where l crosses a sample row along the row: each pixel's own
    // projection, and a tent over the sample rows around its own l.
    if (own != nullptr) per_pixel.partial[j - j0] = 1;
    const RowFunctions row(f.st, j);
    for (int i = i_begin; i < i_end; i += lanes) {
      const VF pixel = hn::Iota(d, float(i));
      const Hit r = Project(read, row, pixel, s.n_s, s.n_t);
      const VF whole =
          hn::IfThenElseZero(hn::Lt(pixel, width), own != nullptr ? hn::LoadU(d, own + i) : weight);
      VF w;
      if (s.taper) {
        w = hn::Mul(whole, WindowShare(s, t.view, r.k, r.l));
      } else {
        const auto inside =
            t.mask == t.read ? r.inside : Project(mask, row, pixel, s.domain).inside;
        w = hn::IfThenElseZero(inside, whole);
      }
      const auto counted = hn::Gt(w, zero);
      if (count_hits)
        hn::StoreU(hn::Add(hn::LoadU(d, hits + at + i), hn::IfThenElseZero(counted, one)), d,
                   hits + at + i);
      if (held != nullptr) hn::StoreU(hn::Add(hn::LoadU(d, held + at + i), w), d, held + at + i);
      if (hn::AllFalse(d, hn::Gt(w, zero))) continue;
      const VF lc = hn::Min(hn::Max(r.l, zero), l_top);
      // The sample rows the weighed lanes' tents reach: two or three where l changes slowly
      // along the row, more where it changes fast (a camera turned about the vertical).
      const auto weighed = hn::Gt(w, zero);
      const VI rows_of = hn::ConvertTo(di, lc);
      const int low = std::clamp(
          hn::GetLane(hn::MinOfLanes(
              di, hn::IfThenElse(hn::RebindMask(di, weighed), rows_of, hn::Set(di, l_hi)))),
          l_lo, l_hi);
      const int high = std::clamp(
          hn::GetLane(hn::MaxOfLanes(
              di, hn::IfThenElse(hn::RebindMask(di, weighed), rows_of, hn::Set(di, l_lo)))) +
              1,
          low, l_hi);
      VF v[3] = {zero, zero, zero};
      // (Made ready in a loop of their own: a call in the blend's loop cost frames whose rows
      // are resampled once a band 7%.)
      for (int sample_row = low; every > 0 && sample_row <= high; ++sample_row)
        ensure(sample_row, j);
      for (int sample_row = low; sample_row <= high; ++sample_row) {
        const VF tent =
            hn::Max(zero, hn::Sub(one, hn::Abs(hn::Sub(lc, hn::Set(d, float(sample_row))))));
        const std::size_t row_at = std::size_t(sample_row - l_lo);
        for (int c = 0; c < 3; ++c)
          v[c] = hn::MulAdd(tent, hn::LoadU(d, resampled.channel(row_at, c) + i), v[c]);
      }
      for (int c = 0; c < 3; ++c) {
        hn::StoreU(hn::MulAdd(w, v[c], hn::LoadU(d, acc[c] + at + i)), d, acc[c] + at + i);
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
  // hits: the lens samples that hit, or the cameras counted; held: the cameras integrator's
  // counted weights (each camera counts where its own line through p_o meets the domain).
  const bool cameras = f.eye >= 0;
  const std::size_t rows = std::size_t(j1 - j0);
  // Each followed by its per-row part (AddTerm's row_hits, row_held).
  std::vector<float> hits(band + rows, 0.0f), held(cameras ? band + rows : 0, 0.0f);
  float* const row_hits = hits.data() + band;
  float* const row_held = cameras ? held.data() + band : nullptr;
  // Per-pixel weights: every row's, each pixel's sum over the views and the views weighing it
  // (its counts where every view's reads are whole along the row: not summed again then, nor
  // taken apart again, where a few views' tiny weights would lose their digits).
  PixelWeights pixel;
  std::vector<float> row_sums, row_counts;
  std::vector<char> whole, partial;
  std::vector<int> row_cameras, spans;
  std::vector<std::pair<int, int>> row_spans;
  if (f.pixel_weights != nullptr) {
    pixel.views = std::size_t(s.rows) * std::size_t(s.cols);
    // A few MB a band, kept by each thread from band to band (only the listed views' spans are
    // written, and read).
    thread_local std::vector<float> weights;
    if (weights.size() < rows * pixel.views * stride) weights.resize(rows * pixel.views * stride);
    spans.assign(2 * rows * pixel.views, 0);
    whole.assign(rows * pixel.views, 0);
    partial.assign(rows, 0);
    row_sums.assign(band, 0.0f);
    row_counts.assign(band, 0.0f);
    for (int j = j0; j < j1; ++j) {
      const std::size_t row = std::size_t(j - j0);
      float* row_weights = weights.data() + row * pixel.views * stride;
      f.pixel_weights->RowWeights(j, f.width, stride, row_weights, &row_cameras, &row_spans);
      const int lanes = int(hn::Lanes(d));
      for (std::size_t n = 0; n < row_cameras.size(); ++n) {
        const std::size_t slot = row * pixel.views + std::size_t(row_cameras[n]);
        // The written pixels, widened to whole vectors with zeros.
        const auto [begin, end] = row_spans[n];
        const int vector_begin = begin / lanes * lanes;
        const int vector_end = std::min(padded, (end + lanes - 1) / lanes * lanes);
        float* w = row_weights + std::size_t(row_cameras[n]) * stride;
        std::fill(w + vector_begin, w + begin, 0.0f);
        std::fill(w + end, w + vector_end, 0.0f);
        spans[2 * slot] = vector_begin;
        spans[2 * slot + 1] = vector_end;
        float* sum = row_sums.data() + row * stride;
        float* count = row_counts.data() + row * stride;
        for (int i = begin; i < end; ++i) {
          sum[i] += w[i];
          count[i] += w[i] > 0.0f ? 1.0f : 0.0f;
        }
      }
    }
    pixel = {weights.data(), spans.data(), pixel.views, whole.data(), partial.data()};
  }
  Planes decoded, band_decoded, resampled;
  TileMap k_map;
  std::vector<int> resampled_for;
  int counted_mask = -1;
  for (const SeparableTerm& t : f.terms) {
    // Lens samples: each one's hits are counted once (its terms come together).
    const bool count_hits = cameras || t.mask != counted_mask;
    AddTerm(f, s, t, j0, j1, stride, acc, hits.data(), count_hits, cameras ? held.data() : nullptr,
            row_hits, row_held, pixel, decoded, band_decoded, resampled, k_map, resampled_for);
    if (count_hits) counted_mask = t.mask;
  }
  if (f.pixel_weights != nullptr)
    for (std::size_t row = 0; row < rows; ++row) {
      float* sum = held.data() + row * stride;
      float* count = hits.data() + row * stride;
      if (!partial[row]) {  // every view whole along the row
        std::copy_n(row_sums.data() + row * stride, stride, sum);
        std::copy_n(row_counts.data() + row * stride, stride, count);
        continue;
      }
      // The views read whole, added to what the others counted pixel by pixel.
      for (std::size_t view = 0; view < pixel.views; ++view) {
        const std::size_t slot = row * pixel.views + view;
        if (!whole[slot]) continue;
        const float* w = pixel.weights + slot * stride;
        for (int i = spans[2 * slot]; i < spans[2 * slot + 1]; ++i) {
          sum[i] += w[i];
          count[i] += w[i] > 0.0f ? 1.0f : 0.0f;
        }
      }
    }
  const DI di;
  const VF width = hn::Set(d, float(f.width)), zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  for (int j = j0; j < j1; ++j) {
    const std::size_t at = std::size_t(j - j0) * stride;
    const float* count = hits.data() + at;
    const float* weights = cameras ? held.data() + at : nullptr;
    // What counted at every pixel of the row, added at the row's real pixels.
    const VF row_count = hn::Set(d, row_hits[std::size_t(j - j0)]);
    const VF row_weight = hn::Set(d, cameras ? row_held[std::size_t(j - j0)] : 0.0f);
    for (int i = 0; i < padded; i += int(hn::Lanes(d))) {
      const auto real = hn::Lt(hn::Iota(d, float(i)), width);
      VF n = hn::Add(hn::LoadU(d, count + i), hn::IfThenElseZero(real, row_count));
      // Lens samples: the mean over those that hit; cameras: the counted weights renormalised.
      const VF divisor =
          cameras ? hn::Add(hn::LoadU(d, weights + i), hn::IfThenElseZero(real, row_weight)) : n;
      const auto any = hn::Gt(divisor, zero);
      const VF inv = hn::IfThenElseZero(any, hn::Div(one, divisor));
      for (float* channel : acc)
        hn::StoreU(hn::Mul(hn::LoadU(d, channel + at + i), inv), d, channel + at + i);
      if (cameras) n = hn::IfThenElseZero(any, n);
      hn::StoreU(hn::ConvertTo(di, n), di, out.count + at + std::size_t(i));
    }
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
