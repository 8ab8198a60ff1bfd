#pragma once
// The silhouettes re-decided by what each view can see (docs/depth.md, "Visibility at the
// silhouettes").
//
// The sweep's costs are over sub-arrays of views, never over exactly the views that see a point:
// beside a near object's silhouette a sample of the far surface behind is matched well at the
// near object's depth too, and the near object comes out larger than it is (a sample or two of
// "fattening" along its silhouettes). Given the map, each view's visibility is known: a point at
// depth D is hidden from a view where the map puts something nearer on that view's line through
// it. So each sample on the near side of a depth edge (a jump between neighbouring samples, not a
// slope) is judged between its own depth and the farthest one around it (or, with
// `far_side_plane`, the far side's plane continued under it), by their mean matching
// cost over the views that see the point at each (the map's own samples splatted into every
// view, nearest first: a z-buffer); it takes the far depth where that matches better. Its cost
// is over a 3 x 3 window, which at an edge straddles it: with `same_side_window` a depth is
// judged by the sample and those of its window whose label is that depth's (within the edge's
// threshold), not by the other side's samples read at a shift that is not theirs; with
// `side_at_own_depths`, by every sample on its side of the edge, each read at its own depth (a
// limb is slanted across the window). The near
// depth is the map's own to within a fraction of a sample, and at a limb, where the surface turns
// away and its shading changes from sample to sample, a read that far off costs more than the
// far side's smooth wall: so the near side counts at its best of its own depth and that depth
// moved a little each way (`near_search_samples`; the label stays the map's). Only
// towards the far side: the near side is seen by every view that sees its neighbours, so the
// sweep's own choice stands there; and only where the far side reaches the sample
// (ReachedByTheFarSide). A few passes, each over the samples next to those the last one moved.
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/depth/cost_volume.h"

namespace lfcam {

struct SilhouetteVisibilityOptions {
  int window = 3;  // a depth edge's two sides: the farthest label within, and the sample's own
  int passes = 3;  // at most: each with the map the last one left, until no sample moves
  double edge_samples = 0.5;       // a depth edge: its sides this far apart (nearest view's shift)
  double tolerance_samples = 0.3;  // nearer than this (nearest view's shift) hides a point
  double color_cap = 0.1;          // the colour cost's truncation (sRGB 0 .. 1)
  bool same_side_window = false;   // each depth's cost over its own side of the window only
  // With same_side_window: each of the side's other samples read at its own label (moved as
  // the hypothesis moves the side's), not at the sample's depth: a limb turning away from the
  // views is slanted across the window. A side is then every sample on that side of the edge,
  // not only those within the threshold of the side's label.
  bool side_at_own_depths = true;
  // The near side judged at its best of its own depth and that depth moved by up to
  // near_search_steps steps of near_search_samples (nearest view's shift) each way (at most 3;
  // 0: its own depth alone).
  double near_search_samples = 0.05;
  int near_search_steps = 2;
  // The far depth a sample is judged at, and takes: the plane through the far-side samples of its
  // 3 x 3 window, where they fit one (FarSidePlaneAt), not the farthest label of its window.
  bool far_side_plane = false;
};

// The far side's depth at sample (x, y) of `label` (CV_32F): the plane through the samples of its
// 3 x 3 window whose labels are over `beyond` (least squares, slopes held towards none where the
// samples do not fix them), at (x, y), if at least three such samples give one over `beyond`; no
// farther than `farthest` plus `edge`; else `farthest`. A slanted far surface (a floor, a ramp)
// runs on under the sample: its farthest label in the window lies a sample or two off and past
// it, the mean of its samples short of it.
float FarSidePlaneAt(const cv::Mat& label, int x, int y, float beyond, float farthest, float edge);

// A sum of matching costs that comes out the same whatever order they are added in. The views are
// taken in parallel, each thread summing the views it was given, and a floating-point sum's last
// bits depend on that order: a near tie between a sample's two depths then went either way from
// run to run (one sample of the full-size `paper` view in 1.4 million, by the threads' timing).
// Fixed point, kUnits a unit of cost: a cost here is at most the colour cap (0.1), summed over a
// few thousand views at most, far within the integers' range, and 2^-32 is below any meaning.
struct CostSum {
  static constexpr double kUnits = 4294967296.0;
  std::int64_t units = 0;
  void Add(double cost) { units += std::llround(cost * kUnits); }
  CostSum& operator+=(const CostSum& other) {
    units += other.units;
    return *this;
  }
  double value() const { return double(units) / kUnits; }
};

// Of the samples that would take a farther depth (`far`, CV_32F: that label, NaN where a sample
// keeps its own), those the far side reaches: a sample next to one whose label (CV_32F) is
// already at least that far less `edge` labels, or next to another reached sample that moves
// at least that far less `edge`. The rest keep their labels: a sample inside an object whose far
// depth matched better by chance, with its own object between it and the edge, would open a hole no
// view sees through (`hci-antinous`' statue, one sample in from its dark side). Returns CV_8U,
// 1 where reached.
cv::Mat ReachedByTheFarSide(const cv::Mat& label, const cv::Mat& far, float edge);

// Re-decides `label` (CV_32F, the planes of inverse depth q[i] as SweepViews::Sweep swept them;
// fractional) at its depth edges as above; `samples_per_label` is the nearest view's shift
// between neighbouring planes. Returns how many samples took the far side's label; 0, and
// nothing done, where a view is not read shifted.
int RefineSilhouettesByVisibility(const SweepViews& views, const std::vector<double>& q,
                                  double samples_per_label, cv::Mat& label,
                                  const SilhouetteVisibilityOptions& options = {});

}  // namespace lfcam
