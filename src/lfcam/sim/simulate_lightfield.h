#pragma once
// The light field an ideal array would capture (no lens distortion, no calibration error):
// view (row, col) is the scene seen from camera (row, col)'s centre through the st samples,
// each sample the average radiance over its st cell (supersampled, linear light).
#include <functional>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

struct SimulateLightFieldOptions {
  int rows = 10, cols = 10;  // the camera grid (pitch and array centre from the scene)
  int n_s = 1248, n_t = 1152;
  StDomain st_domain;
  int supersampling = 2;  // per axis, per st cell
  SampleType sample_type = SampleType::kSrgb8;
  // Where each camera really is (row-major, rows x cols entries), for the light field an actual
  // array with mounting errors captures; empty: the ideal grid. Recorded as measured poses.
  std::vector<Vec3> camera_centers;
  std::function<void(int views_done, int views_total)> progress;
};

// The scene's rig resized to a rows x cols grid around the same centre, same pitch.
ArrayPlane ResizeArray(const ArrayPlane& array, int rows, int cols);

LightField SimulateLightField(const Scene& scene, const SimulateLightFieldOptions& options);

}  // namespace lfcam
