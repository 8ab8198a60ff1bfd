// The outlier test vectorised across a row's samples with Highway's dynamic dispatch (as
// depth/local_planes.cpp): this file is compiled once per instruction set (foreach_target.h
// includes it again for each), and HWY_DYNAMIC_DISPATCH picks the best the machine supports.
// Each lane is one sample; the neighbourhood is taken offset by offset, so every load is a
// contiguous run of planar maps, padded so that no lane needs a bounds check.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/depth/weighted_median.cpp"
#include "lfcam/depth/weighted_median.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#ifndef LFCAM_DEPTH_WEIGHTED_MEDIAN_ONCE
#define LFCAM_DEPTH_WEIGHTED_MEDIAN_ONCE
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/depth/colour_weights.h"
#include "lfcam/depth/dark_limb.h"
#include "lfcam/depth/padded_label_maps.h"

namespace lfcam::weighted_median {

// What the kernel gives each sample: the neighbourhood's weight, and the weights of its labels
// below label − threshold and above label + threshold.
constexpr int kSums = 3;

}  // namespace lfcam::weighted_median
#endif  // LFCAM_DEPTH_WEIGHTED_MEDIAN_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;

// The sums over the neighbourhoods of samples [x0, x0 + lanes) of row y, into `sums` (kSums runs
// of `lanes` floats: all, below, above).
void OutlierSumsT(const PaddedLabelMaps& m, const ColourWeights& colour, float threshold, int y,
                  int x0, float* sums) {
  const DF d;
  const int r = m.radius;
  const std::size_t centre = m.At(y, x0);
  const VF own = hn::LoadU(d, m.label.data() + centre);
  const VF low = hn::Sub(own, hn::Set(d, threshold)), high = hn::Add(own, hn::Set(d, threshold));
  const VF red0 = hn::LoadU(d, m.red.data() + centre);
  const VF green0 = hn::LoadU(d, m.green.data() + centre);
  const VF blue0 = hn::LoadU(d, m.blue.data() + centre);
  const DI di;
  const float* colour_weight = colour.weight.data();
  const auto last = hn::Set(di, colour.last);
  VF all = hn::Zero(d), below = all, above = all;
  for (int yy = std::max(0, y - r); yy <= std::min(m.height - 1, y + r); ++yy)
    for (int dx = -r; dx <= r; ++dx) {
      const std::size_t at = m.At(yy, x0 + dx);
      const VF l = hn::LoadU(d, m.label.data() + at);
      const VF dr = hn::Sub(hn::LoadU(d, m.red.data() + at), red0);
      const VF dg = hn::Sub(hn::LoadU(d, m.green.data() + at), green0);
      const VF db = hn::Sub(hn::LoadU(d, m.blue.data() + at), blue0);
      const VF d2 = hn::MulAdd(dr, dr, hn::MulAdd(dg, dg, hn::Mul(db, db)));
      const VF w = hn::GatherIndex(d, colour_weight, hn::Min(hn::ConvertTo(di, d2), last));
      all = hn::Add(all, hn::IfThenElseZero(hn::Eq(l, l), w));  // NaN: the padding, unknowns
      below = hn::Add(below, hn::IfThenElseZero(hn::Lt(l, low), w));
      above = hn::Add(above, hn::IfThenElseZero(hn::Gt(l, high), w));
    }
  const std::size_t lanes = hn::Lanes(d);
  hn::StoreU(all, d, sums);
  hn::StoreU(below, d, sums + lanes);
  hn::StoreU(above, d, sums + 2 * lanes);
}

int LanesT() { return int(hn::Lanes(DF())); }

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {
namespace {

HWY_EXPORT(OutlierSumsT);
HWY_EXPORT(LanesT);

struct Weighted {
  float label;
  int bucket;  // LabelBuckets::Of(label)
  double weight;
};

// The map's labels cut into kCount buckets in their order: a label's bucket is never before a
// smaller label's. A median is found as the bucket where the weights' running sum reaches half,
// then among that bucket's labels alone.
struct LabelBuckets {
  static constexpr int kCount = 256;
  float lo = 0, scale = 0;
  explicit LabelBuckets(const cv::Mat& label) {
    float low = std::numeric_limits<float>::infinity(), high = -low;
    for (int y = 0; y < label.rows; ++y)
      for (const float l : std::span(label.ptr<float>(y), std::size_t(label.cols)))
        if (!std::isnan(l)) low = std::min(low, l), high = std::max(high, l);
    if (low < high && std::isfinite(high - low))
      lo = low, scale = float(kCount / double(high - low));
  }
  int Of(float l) const {
    const float t = (l - lo) * scale;  // NaN only for an infinite label with scale 0
    return !(t >= 1) ? 0 : t >= kCount - 1 ? kCount - 1 : int(t);
  }
};

// The smallest label whose weight, with the weights of every smaller label, reaches `target`
// (average linear time: a selection that keeps only the side the answer lies on). `items` is
// reordered; its weights sum to at least `target` > 0.
float WeightedSelect(std::span<Weighted> items, double target) {
  auto begin = items.begin(), end = items.end();
  float largest = -std::numeric_limits<float>::infinity();
  for (const Weighted& i : items) largest = std::max(largest, i.label);
  while (end - begin > 1) {
    const float pivot = (begin + (end - begin) / 2)->label;
    const auto less =
        std::partition(begin, end, [&](const Weighted& i) { return i.label < pivot; });
    const auto equal =
        std::partition(less, end, [&](const Weighted& i) { return i.label == pivot; });
    double below = 0, at = 0;
    for (auto i = begin; i != less; ++i) below += i->weight;
    for (auto i = less; i != equal; ++i) at += i->weight;
    if (below >= target) {
      end = less;
    } else if (below + at >= target) {
      return pivot;
    } else {
      target -= below + at;
      begin = equal;
    }
  }
  return begin == end ? largest : begin->label;  // empty only by rounding: the largest label
}

}  // namespace

int ReplaceOutliersByWeightedMedian(const cv::Mat& guide_rgb8, const WeightedMedianOptions& options,
                                    cv::Mat& label) {
  if (label.type() != CV_32FC1 || guide_rgb8.type() != CV_8UC3 || guide_rgb8.size() != label.size())
    throw Error(
        "ReplaceOutliersByWeightedMedian: labels and guide must be float and RGB8 maps "
        "of one size");
  if (!(options.sigma_levels > 0) || !(options.threshold >= 0) || !(options.dark_limb_levels >= 0))
    throw Error(
        "ReplaceOutliersByWeightedMedian: the colour sigma must be positive, the threshold and "
        "the dark limbs' levels not negative");
  if (!options.replace_only.empty() &&
      (options.replace_only.type() != CV_8UC1 || options.replace_only.size() != label.size()))
    throw Error(
        "ReplaceOutliersByWeightedMedian: the replace mask must be an 8-bit map of the labels' "
        "size");
  const int w = label.cols, h = label.rows, r = std::max(0, options.radius);
  if (w == 0 || h == 0) return 0;
  const int lanes = HWY_DYNAMIC_DISPATCH(LanesT)();
  const PaddedLabelMaps m = PadLabelMaps(label, guide_rgb8, r, lanes);
  const double s = options.sigma_levels;
  const float colour_scale = float(-1.0 / (2 * s * s));
  const float threshold = float(options.threshold);

  // The median's weights, exp(n colour_scale) for every squared colour distance n that two 8-bit
  // colours can be apart (each the same double the exponential gives for that n), looked up: a
  // sample decided by its median weighs a whole neighbourhood.
  constexpr int kLargestSquaredDistance = 3 * 255 * 255;
  std::vector<double> colour_weight(std::size_t(kLargestSquaredDistance) + 1);
  tbb::parallel_for(tbb::blocked_range<int>(0, kLargestSquaredDistance + 1, 4096),
                    [&](const tbb::blocked_range<int>& n) {
                      for (int i = n.begin(); i != n.end(); ++i)
                        colour_weight[std::size_t(i)] = std::exp(double(i) * colour_scale);
                    });
  const double* const weight_of = colour_weight.data();
  const ColourWeights colour = MakeColourWeights(colour_scale);
  const LabelBuckets buckets(label);
  cv::Mat out = label.clone();
  std::atomic<int> replaced{0};
  struct Scratch {
    std::vector<Weighted> items, in_bucket;
    std::array<double, LabelBuckets::kCount> bucket_weight{};
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(0, h, [&](int y) {
    std::vector<float> sums(std::size_t(weighted_median::kSums * lanes));
    Scratch& local = scratch.local();
    // Written by index into room for a whole neighbourhood (a push's bounds check and stored end
    // were about a sixth of the median's time).
    const std::size_t window = std::size_t(2 * r + 1) * std::size_t(2 * r + 1);
    local.items.resize(window);
    local.in_bucket.resize(window);
    int count = 0;
    const std::uint8_t* const only =
        options.replace_only.empty() ? nullptr : options.replace_only.ptr<std::uint8_t>(y);
    for (int x0 = 0; x0 < w; x0 += lanes) {
      HWY_DYNAMIC_DISPATCH(OutlierSumsT)(m, colour, threshold, y, x0, sums.data());
      for (int i = 0; i < lanes && x0 + i < w; ++i) {
        const float all = sums[std::size_t(i)], below = sums[std::size_t(lanes + i)],
                    above = sums[std::size_t(2 * lanes + i)];
        if (!(below >= 0.5f * all || above > 0.5f * all)) continue;  // false for NaN labels
        // An outlier, or near enough to one that the median decides: the median itself.
        const int x = x0 + i;
        if (only && only[x] == 0) continue;
        const std::size_t centre = m.At(y, x);
        std::size_t n = 0;
        local.bucket_weight.fill(0.0);
        Weighted* const item_out = local.items.data();
        double* const bucket_weight = local.bucket_weight.data();
        double total = 0;
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
            const std::size_t at = m.At(yy, xx);
            const float l = m.label[at];
            if (std::isnan(l)) continue;
            const int dr = int(m.red[at] - m.red[centre]), dg = int(m.green[at] - m.green[centre]),
                      db = int(m.blue[at] - m.blue[centre]);
            const double weight = weight_of[dr * dr + dg * dg + db * db];
            const int bucket = buckets.Of(l);
            item_out[n++] = {l, bucket, weight};
            bucket_weight[bucket] += weight;
            total += weight;
          }
        if (!(total > 0)) continue;
        // The bucket where the running sum reaches half, then the median among its labels.
        const double half = 0.5 * total;
        double before = 0;
        int k = 0;
        while (k + 1 < LabelBuckets::kCount && before + bucket_weight[k] < half)
          before += bucket_weight[k++];
        const std::span<Weighted> items(local.items.data(), n);
        std::size_t in_k = 0;
        for (const Weighted& item : items)
          if (item.bucket == k) local.in_bucket[in_k++] = item;
        // No label there only by rounding (the sums fell short of half): the largest label.
        const float median =
            in_k == 0
                ? std::ranges::max(items, {}, [](const Weighted& item) { return item.label; }).label
                : WeightedSelect({local.in_bucket.data(), in_k}, half - before);
        if (options.dark_limb_levels > 0 && median > m.label[centre] + threshold &&
            IsDarkLimb(guide_rgb8, label, x, y, median, threshold,
                       {options.dark_limb_levels, options.dark_limb_radius}))
          continue;
        if (std::abs(median - m.label[centre]) > threshold) {
          out.at<float>(y, x) = median;
          ++count;
        }
      }
    }
    replaced += count;
  });
  label = out;
  return replaced;
}

}  // namespace lfcam
#endif  // HWY_ONCE
