#pragma once
// A disparity map's labels refined as local planes: each sample takes the value at its own
// position of the plane (label = a + b·dx + c·dy) fitted, by weighted least squares, to its
// neighbours within `radius` samples that look like it (a Gaussian in colour distance in the
// reference view), lie near it (a Gaussian in distance) and near its label (within
// `max_label_gap`: the other side of a depth edge does not count), weighted by their
// confidence.
//
// Why (docs/depth.md): the sweep's labels come from a plane index chosen per sample, whose
// small-step penalty in semi-global matching favours surfaces parallel to the array; on a
// slanted or curved smooth surface they scatter by a plane or two about the surface and step
// where the surface does not. A plane through the neighbourhood's labels follows the slant
// and averages the scatter away; on the HCI benchmark's `antinous` it takes BadPix0.07 from
// 6.32% to about 5.6%.
#include <opencv2/core.hpp>

namespace lfcam {

struct LocalPlaneOptions {
  int radius = 5;                // the neighbourhood, in samples (a square)
  double sigma_space = 3.0;      // the distance weight's Gaussian, in samples
  double sigma_colour = 0.06;    // the colour weight's, in sRGB units (0 .. 1) over R, G, B
  double max_label_gap = 7.0;    // neighbours farther from the sample's own label do not count
  double min_confidence = 0.05;  // a neighbour's confidence counts at least this much
  // Only samples less confident than this are refitted (the others keep their labels).
  double refit_below_confidence = 2.0;
  // Where refitting may happen at all (CV_8UC1 of the labels' size, non-zero where it may), for
  // a caller that keeps only part of the result; empty: everywhere.
  cv::Mat refit_only;
};

// `label`: CV_32FC1 continuous labels (linear in disparity); `guide_rgb8`: the reference view,
// CV_8UC3 of the same size; `confidence`: CV_32FC1 in [0, 1] of the same size. Returns the
// refined labels; `slopes`, when given, gets each refitted sample's plane slope (label change
// per sample along x and y, CV_32FC2; made, zero, when it is not a map of that size and type).
cv::Mat FitLocalPlanes(const cv::Mat& label, const cv::Mat& guide_rgb8, const cv::Mat& confidence,
                       const LocalPlaneOptions& options = {}, cv::Mat* slopes = nullptr);

}  // namespace lfcam
