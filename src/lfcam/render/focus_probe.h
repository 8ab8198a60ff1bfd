#pragma once
// Click to focus: the focus distance of whatever a pixel sees, estimated from the light field
// itself by a plane sweep. For each candidate focus distance d (the plane of focus at d along
// -n_c), a small patch of that plane around the pixel's central ray is read from every camera
// along the camera's own rays (the focal-plane read); where the plane meets the surface the
// cameras agree, so the spread of their colours is smallest. Candidates are swept coarse to fine
// (ratio 1.02, then 1.001) between `near_mm` and `far_mm`.
#include "lfcam/core/lightfield.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

struct FocusProbeOptions {
  double near_mm = 0;        // 0: just beyond the focal length
  double far_mm = 100000;    // 100 m
  int patch_radius = 4;      // the patch: (2r + 1)^2 points ...
  double patch_step_mm = 0;  // ... this far apart on the plane (0: 3 st samples' pitch)
};

struct FocusProbe {
  bool found = false;            // false: no camera sees the pixel's neighbourhood
  double focus_distance_mm = 0;  // d_o, along -n_c from the lens
  // How much the best candidate stands out: 1 - its cost over the median cost (0: a flat,
  // textureless patch, every depth alike; near 1: a clear match).
  double confidence = 0;
  int cameras = 0;  // cameras that saw the patch at the best distance
};

// The focus distance at film position (x, y) in pixels (bottom-left origin, as
// VirtualCamera::direction_through counts: pixel (i, j)'s centre is (i + 0.5, j + 0.5)).
FocusProbe ProbeFocusDistance(const LightField& lf, const VirtualCamera& camera, double x, double y,
                              const FocusProbeOptions& options = {});

}  // namespace lfcam
