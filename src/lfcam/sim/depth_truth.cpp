#include "lfcam/sim/depth_truth.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "lfcam/depth/plane_sweep.h"

namespace lfcam {

DepthTruth GroundTruthDepth(const Scene& scene, const LightField& lf, int row, int col) {
  const auto& d = lf.dims();
  DepthTruth truth;
  truth.map.row = row;
  truth.map.col = col;
  truth.map.depth.create(d.n_t, d.n_s, CV_32FC1);
  truth.map.confidence.create(d.n_t, d.n_s, CV_32FC1);
  truth.object.create(d.n_t, d.n_s, CV_32SC1);
  const Vec3 center = lf.camera_center(row, col);
  const StSampling sampling = lf.st_sampling(row, col);  // the view's own window
  tbb::parallel_for(0, d.n_t, [&](int l) {
    for (int k = 0; k < d.n_s; ++k) {
      const Ray ray{center, sampling.Point(k, l) - center};
      const Scene::Hit hit = scene.FirstHit(ray);
      const bool found = std::isfinite(hit.t);
      truth.map.depth.at<float>(l, k) = found ? float(DepthOf(lf.slab(), ray.at(hit.t))) : NAN;
      truth.map.confidence.at<float>(l, k) = found ? 1.0f : 0.0f;
      truth.object.at<int>(l, k) = hit.object;
    }
  });
  double lo = INFINITY, hi = -INFINITY;
  for (int l = 0; l < d.n_t; ++l)
    for (int k = 0; k < d.n_s; ++k) {
      const float v = truth.map.depth.at<float>(l, k);
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, double(v));
      hi = std::max(hi, double(v));
    }
  if (!(lo < hi)) lo = hi = 1000.0;  // nothing hit, or one flat plane: any valid range
  truth.map.range = {std::max(1.0, std::floor(lo / 10.0) * 10.0),
                     std::ceil(hi / 10.0) * 10.0 + 10.0};
  return truth;
}

}  // namespace lfcam
