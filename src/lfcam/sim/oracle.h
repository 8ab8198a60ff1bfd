#pragma once
// The ground-truth renderer: the scene itself (not a light field) through the same virtual
// camera, integrated over each pixel's footprint and the lens with many samples. Every light
// field rendering is measured against it.
#include <opencv2/core.hpp>
#include <vector>

#include "lfcam/core/progress.h"
#include "lfcam/render/virtual_camera.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

struct OracleOptions {
  int samples_per_pixel = 0;  // 0: 256 for a pinhole, 1024 with an aperture (converged:
                              // oracle_test.cpp)
  int threads = 0;            // 0: all cores
  ProgressCallback progress;  // told the pixels done (may be empty)
};

// The samples a pixel the oracle takes with these options.
int OracleSamplesPerPixel(const VirtualCamera& camera, const OracleOptions& options);

// The objects (indices into scene.objects, ascending) that a ray through the film rectangle
// [x0, x1] x [y0, y1] (pixel units, bottom-left origin, as VirtualCamera::direction_through) and
// any point of the lens can meet: every object whose bounding sphere the bundle of those rays
// can reach. The oracle tests each ray against its block's objects alone (the same radiance, bit
// for bit: Scene::Radiance with candidates).
std::vector<int> ObjectsTheRaysCanMeet(const Scene& scene, const VirtualCamera& camera, double x0,
                                       double y0, double x1, double y1);

// Linear RGB (CV_32FC3, row 0 at the top).
cv::Mat RenderSceneOracle(const Scene& scene, const VirtualCamera& camera,
                          const OracleOptions& options = {});

}  // namespace lfcam
