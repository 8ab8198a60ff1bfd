#pragma once
// Depth from the light field itself: a plane sweep (docs/depth.md says why this method and what
// decided each step).
//
// For one view (the reference), planes parallel to the array's plane are swept at depths D,
// uniformly in 1/D (the parameter a light field's disparity is linear in), finely: 0.3 of a
// sample of the farthest view's shift a step. Each plane's matching cost against every view
// within `reach` grid steps, occlusion-aware (depth/cost_volume.h), is aggregated by semi-global
// matching (depth/semi_global.h), the cheapest plane per sample is refined to a fraction of a
// step (a parabola through three aggregated costs), outliers (a sample far from the
// weighted median of its neighbours of the same colour; at narrow baselines on clean views only
// where the sweep was unsure of its match) take that median, and each sample then
// takes the plane through its neighbours' labels (depth/local_planes.h); a sample of little
// confidence, the plane through a neighbourhood twice as wide. Then semi-global matching is run
// again with the fitted planes' slant as what its paths expect, and the steps after it. Last,
// the samples beside the silhouettes are re-decided by what each view can see there
// (depth/silhouette_visibility.h).
//
// Confidence: how far the chosen plane's own matching cost lies below the sample's mean cost
// over all planes (1 - best / mean, against a floor): near 1 for a clear minimum, 0 where the
// views agree at every depth (no texture: there the depth is semi-global matching's fill from
// the surroundings) or where the minimum is on the first or last plane; in the map returned, a
// quarter of that within 2 samples of a depth edge, whose place is known to a sample or two only
// (docs/depth.md, "Confidence at depth edges").
#include <functional>
#include <optional>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_map.h"
#include "lfcam/depth/depth_set.h"

namespace lfcam {

class CostVolumeEngine;

struct PlaneSweepOptions {
  std::optional<DepthRange> range;  // the depths swept; default: EstimateDepthRange
  // Views up to this many grid steps away in rows and in columns; 0: 4 for one view, 1 for
  // every view of a set (EstimateDepthSet: a hundred views' maps in about a minute, not ten).
  int reach = 0;
  // Plane spacing: the farthest view's shift per step, in samples (0.3: docs/depth.md, "The
  // planes' spacing and phase").
  double step_samples = 0.3;
  double truncation = 0.1;  // the colour and the gradient terms' caps (sRGB units, 0 .. 1)
  int window_radius = 1;    // the matching window's radius in samples (a box)
  int smoothness_p1 = 16;   // semi-global matching's penalties (depth/semi_global.h)
  int smoothness_p2 = 160;
  bool refine_edges = true;      // the weighted-median outlier clean-up
  int refine_radius = 0;         // its radius in samples; 0: from the view's size
  bool keep_dark_limbs = true;   // ... which, at narrow baselines, leaves dark limbs on their
                                 // objects (depth/dark_limb.h)
  bool fit_local_planes = true;  // then each sample on the plane through its neighbours' labels
                                 // (depth/local_planes.h)
  // Then, at reach 2 or more, semi-global matching again expecting the fitted planes' slant, kept
  // where the first pass was confident (docs/depth.md; not at reach 1, `--all`'s default,
  // where it costs a third more time for a tenth of a point).
  bool slant_prior = true;
  // Last, the samples beside the silhouettes re-decided by what each view can see
  // (depth/silhouette_visibility.h).
  bool silhouette_visibility = true;
  // Views built more finely than their cameras recorded are blurred to the cameras' scale before
  // matching (CostVolumeOptions::blur_to_cameras).
  bool blur_to_cameras = true;
  // Where given, the cost volumes are computed by it (depth/gl_cost_volume.h: on the GPU); the
  // rest of the estimate stays on the CPU.
  CostVolumeEngine* engine = nullptr;
};

// The depth map of view (row, col). Throws lfcam::Error when the light field has a single view
// or the range is invalid.
DepthMap EstimateDepth(const LightField& lf, int row, int col, const PlaneSweepOptions& options);

// Whether neighbouring views of (row, col) see the range's scene (its found part, without the
// margin) at most 8 samples apart from its nearest to its farthest: a plenoptic camera, a dense
// grid. There the views' brightness is made alike, and a depth set reaches two views each way
// (docs/depth.md, "An eighth round", "The set's reach at narrow baselines").
bool SeesTheSceneNarrowly(const LightField& lf, int row, int col, const DepthRange& range);

// The reach of a depth set's maps where the views see the scene narrowly apart
// (SeesTheSceneNarrowly); elsewhere 1.
inline constexpr int kNarrowSetReach = 2;

// Fills in the views of a depth set (depth/depth_set.h) for which `needed(row, col)` is true and
// that have no map yet, by EstimateDepth over one range (estimated once, from the central view,
// when `range` is empty), in parallel, each map at `options.reach` or, where that is 0, at 1 or
// kNarrowSetReach. `progress` is told each view as it is done.
void EstimateDepthSet(const LightField& lf, DepthSet& set,
                      const std::function<bool(int row, int col)>& needed,
                      const PlaneSweepOptions& options,
                      const std::function<void(int done, int total)>& progress = {});

// The depth range worth sweeping, from a coarse sweep of view (row, col) at a quarter of its
// resolution over 0.5 to 20 times the st-plane's distance: the 1st to 99th percentile of its
// confident depths, and any depth that 2% of its samples choose with a unique (if shallow)
// minimum (`found_near_mm` .. `found_far_mm`), widened by a margin of two of the coarse sweep's
// natural planes (a coarse sample of the farthest view apart): the same range in the views' own
// samples whatever units the light field is in.
DepthRange EstimateDepthRange(const LightField& lf, int row, int col,
                              const PlaneSweepOptions& options = {});

// The depth D (mm) of a world point: its distance from the array's plane along -n_ca.
inline double DepthOf(const Slab& slab, const Vec3& p) {
  return slab.uv.n_ca.dot(slab.uv.p_ca - p);
}

}  // namespace lfcam
