#pragma once
// Semi-global matching (Hirschmüller 2008): a cost volume's costs aggregated along straight
// paths through every sample, each path adding a small penalty P1 where the label moves by one
// from one sample to the next and a large one P2 where it jumps. Textureless regions then take
// the labels their surroundings agree on, and a surface's label changes slowly across it.
//
// Four paths (left, right, up, down), not Hirschmüller's eight: on the HCI benchmark's
// `antinous` the diagonal paths double the bad pixels on its steeply slanted floor (2.0% of the
// view bad there with four paths, 4.1% with eight; docs/depth.md), and halve the time.
#include "lfcam/depth/cost_volume.h"

namespace lfcam {

struct SemiGlobalOptions {
  int p1 = 16;   // a one-label step's penalty, in CostVolume units
  int p2 = 160;  // a jump's penalty where the guide is flat
  // Across an edge of the guide (grey levels g apart) a jump costs P2 / (1 + g / edge_grey):
  // depth edges are where colour edges are.
  double edge_grey = 8.0;
};

// The sum over the paths (same layout as the volume), led by `guide` (the reference view, 8-bit
// grey, the volume's size). The volume's costs must be at most 16000 so that the sum fits 16
// bits.
// `expected_step` (optional, CV_32FC2 of the volume's size): the label change expected per
// sample along +x and +y (a surface's slant); a path then pays P1 / P2 for departing from it
// rather than from the same label (Scharstein, Taniai and Sinha 2017).
CostVolume AggregateSemiGlobal(const CostVolume& volume, const cv::Mat& guide,
                               const SemiGlobalOptions& options,
                               const cv::Mat& expected_step = cv::Mat());

}  // namespace lfcam
