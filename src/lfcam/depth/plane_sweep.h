#pragma once
// Depth from the light field itself: a plane sweep (docs/depth.md says why this method).
//
// For one view (the reference), planes parallel to the array's plane are swept at depths D,
// uniformly in 1/D (the parameter a light field's disparity is linear in). For each plane,
// every other view on the reference's row and column (up to `reach` cameras each way) is
// warped onto the reference's st samples through that plane (a homography: exact for any
// slab, whatever the st-plane's tilt) and compared with it: absolute colour difference,
// truncated. Occlusion: a point hidden from the cameras on one side of the reference is seen
// from the other, so the cost keeps the better side along each axis (left or right, below or
// above) and averages the two axes. Each plane's cost is filtered edge-aware (a guided filter
// led by the reference view: cost-volume filtering, Rhemann et al. 2011), the best plane per
// sample is refined to a fraction of a step (a parabola through three costs), and the map is
// cleaned at depth edges by a weighted median led by the reference view that fills
// low-confidence samples from confident neighbours of the same colour.
//
// Confidence: how far the best cost lies below the sample's mean cost over all planes
// (1 - best / mean): near 1 for a clear minimum, 0 where the views agree at every depth
// (no texture).
#include <optional>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_map.h"

namespace lfcam {

struct PlaneSweepOptions {
  std::optional<DepthRange> range;  // the depths swept; default: EstimateDepthRange
  int reach = 4;                    // cameras used each way along the view's row and column
  double step_samples = 1.0;  // plane spacing: the farthest camera's shift per step, in samples
  double truncation = 0.1;    // the per-view cost's cap (sRGB units, 0 .. 1)
  int filter_radius = 0;      // guided filter radius in samples; 0: from the view's size
  bool refine_edges = true;   // the weighted-median clean-up
  int refine_radius = 0;      // its radius in samples; 0: from the view's size
};

// The depth map of view (row, col). Throws lfcam::Error when the light field has a single view
// or the range is invalid.
DepthMap EstimateDepth(const LightField& lf, int row, int col, const PlaneSweepOptions& options);

// The depth range worth sweeping, from a coarse sweep of view (row, col) at a quarter of its
// resolution over 0.5 to 20 times the st-plane's distance: the 1st to 99th percentile of its
// confident depths, widened by a margin.
DepthRange EstimateDepthRange(const LightField& lf, int row, int col,
                              const PlaneSweepOptions& options = {});

// The depth D (mm) of a world point: its distance from the array's plane along -n_ca.
inline double DepthOf(const Slab& slab, const Vec3& p) {
  return slab.uv.n_ca.dot(slab.uv.p_ca - p);
}

}  // namespace lfcam
