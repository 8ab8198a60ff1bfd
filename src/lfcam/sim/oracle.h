#pragma once
// The ground-truth renderer: the scene itself (not a light field) through the same virtual
// camera, integrated over each pixel's footprint and the lens with many samples. Every light
// field rendering is measured against it.
#include <opencv2/core.hpp>

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

// Linear RGB (CV_32FC3, row 0 at the top).
cv::Mat RenderSceneOracle(const Scene& scene, const VirtualCamera& camera,
                          const OracleOptions& options = {});

}  // namespace lfcam
