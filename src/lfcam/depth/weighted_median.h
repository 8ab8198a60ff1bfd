#pragma once
// A depth map's outliers replaced by the joint weighted median of their neighbourhood: a sample
// whose label lies more than `threshold` from the median of the labels within `radius` samples
// (a square, clipped at the map's edges), each weighted by how much its colour in the reference
// view looks like the sample's own (exp(−‖Δrgb‖² / 2σ²), σ in 8-bit levels), takes that median.
// Only outliers: the median quantises, and a slanted surface's smooth labels would take steps.
//
// The median is the smallest label whose weight, with the weights of every smaller label, makes
// at least half of the neighbourhood's. It is exact (no quantisation of labels or colours), the
// same on every machine and thread, and safe to run on several maps at once. Most samples are
// not outliers, and whether one is needs only two sums (the weight of the labels below
// label − threshold, and of those above label + threshold), vectorised across a row with
// Highway; the median itself is sorted out only where one of them reaches half
// (docs/depth.md, "The clean-up").
//
// With `dark_limb_levels` > 0, a sample whose median lies farther (a larger label) keeps its own
// label where it is a dark limb (depth/dark_limb.h), judged within `dark_limb_radius` samples,
// its sides those within the threshold of its own label and of the median.
#include <opencv2/core.hpp>

namespace lfcam {

struct WeightedMedianOptions {
  int radius = 2;                 // the neighbourhood, in samples
  double sigma_levels = 25.5;     // the colour weight's Gaussian, in 8-bit levels over R, G, B
  double threshold = 2.0;         // a sample farther than this from its median is an outlier
  double dark_limb_levels = 0.0;  // 0: no sample is kept as a dark limb
  int dark_limb_radius = 3;       // the neighbourhood the limb is judged in, in samples
  // Where a sample may be replaced at all (CV_8UC1 of the labels' size, non-zero where it may);
  // empty: everywhere. The others keep their labels and still count in their neighbours' medians.
  cv::Mat replace_only;
};

// `label`: CV_32FC1 (NaN: unknown, takes no part and stays); `guide_rgb8`: CV_8UC3 of the same
// size. Replaces the outliers in place (where `replace_only` allows); returns how many it replaced.
int ReplaceOutliersByWeightedMedian(const cv::Mat& guide_rgb8, const WeightedMedianOptions& options,
                                    cv::Mat& label);

}  // namespace lfcam
