#pragma once
// A virtual camera that changes over the frames of a video (`lfcam render --video`): either a
// path through saved views (the viewer's F12 files), interpolated, or the flags' camera with
// some of its parameters swept from one value to another (`--focus-distance 3400:5200`).
//
// A path of K views spends an equal share of the frames on each of its K - 1 legs. The eye and
// the point looked at follow a Catmull-Rom spline through the views (it passes through every
// view, with no corner at one; its end tangents are the first and last legs'), the up vector is
// blended and normalised, and the lens (focal length, focus distance, aperture, lens rate, the
// principal offset) is interpolated linearly within each leg. A sweep is linear from A to B.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// What a sweep changes, each from .first (the first frame) to .second (the last).
struct CameraSweep {
  std::optional<std::pair<Vec3, Vec3>> eye, look_at;
  std::optional<std::pair<double, double>> focal_length_mm, focus_distance_mm, aperture_mm;
  bool empty() const {
    return !eye && !look_at && !focal_length_mm && !focus_distance_mm && !aperture_mm;
  }
};

class CameraPath {
 public:
  // The same camera in every frame.
  static CameraPath Fixed(const VirtualCameraParams& camera);
  // `base` with the sweep's parameters replaced along the way.
  static CameraPath Sweep(const VirtualCameraParams& base, const CameraSweep& sweep);
  // Through `views` in order (at least two). Their frame sizes and breathing must agree:
  // otherwise lfcam::Error naming `names[i]` (the file each came from) and the field.
  static CameraPath ThroughViews(const std::vector<VirtualCameraParams>& views,
                                 const std::vector<std::string>& names);

  // The camera at u in [0, 1] (0: the first frame, 1: the last); u is clamped.
  VirtualCameraParams At(double u) const;
  // The camera of frame k of `frames` (k / (frames - 1); a single frame is u = 0).
  VirtualCameraParams AtFrame(int k, int frames) const;
  bool is_fixed() const { return keys_.size() == 1 && sweep_.empty(); }

 private:
  std::vector<VirtualCameraParams> keys_;
  CameraSweep sweep_;
};

}  // namespace lfcam
