#pragma once
// What the simulator knows about depth: for a view of a simulated light field, the depth of the
// first surface along each st sample's central ray and the object it belongs to
// (`lfcam simulate lightfield --depth-out DIR`, and the depth fidelity measurements).
#include <opencv2/core.hpp>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_map.h"
#include "lfcam/sim/scene.h"

namespace lfcam {

struct DepthTruth {
  DepthMap map;    // confidence 1 where a surface was hit; depth NaN where the ray hit nothing
  cv::Mat object;  // CV_32SC1, same layout: the index of the object in scene.objects, or -1
};

// The range is the depths found, widened to whole centimetres.
DepthTruth GroundTruthDepth(const Scene& scene, const LightField& lf, int row, int col);

}  // namespace lfcam
