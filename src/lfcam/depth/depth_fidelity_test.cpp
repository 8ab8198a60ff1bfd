// Depth from the light field against the simulator's truth (docs/fidelity.md, "Depth"): the
// reduced `paper` light field, the plane sweep's map of a view against GroundTruthDepth, per
// object: the share of samples within 1% of the true depth and the mean absolute error.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>

#include "lfcam/core/image_io.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/test_paper_lightfield.h"

namespace lfcam {
namespace {

struct ObjectScore {
  int samples = 0, within = 0;
  double abs_error = 0;
  double share() const { return samples ? double(within) / samples : 0.0; }
  double mean_error() const { return samples ? abs_error / samples : 0.0; }
};

// Per object (by name), and "all"; samples whose truth is unknown are left out.
std::map<std::string, ObjectScore> Score(const Scene& scene, const DepthTruth& truth,
                                         const DepthMap& estimate) {
  std::map<std::string, ObjectScore> scores;
  for (int l = 0; l < truth.map.n_t(); ++l)
    for (int k = 0; k < truth.map.n_s(); ++k) {
      const float t = truth.map.depth.at<float>(l, k), e = estimate.depth.at<float>(l, k);
      const int object = truth.object.at<int>(l, k);
      if (!std::isfinite(t) || object < 0) continue;
      const double error = std::isfinite(e) ? std::abs(double(e) - t) : double(t);
      for (const std::string& name : {scene.objects[object].name, std::string("all")}) {
        ObjectScore& s = scores[name];
        ++s.samples;
        s.within += error <= 0.01 * t;
        s.abs_error += error;
      }
    }
  return scores;
}

TEST(DepthFidelity, PlaneSweepFindsThePaperScenesDepths) {
  const Scene scene = MakePaperScene();
  const LightField lf = testing::SharedPaperLightField();
  const int row = 4, col = 4;
  const DepthTruth truth = GroundTruthDepth(scene, lf, row, col);
  const DepthMap estimate = EstimateDepth(lf, row, col, {});
  auto scores = Score(scene, truth, estimate);
  for (const auto& [name, s] : scores)
    std::cout << fmt::format(
        "[depth fidelity] {}: {} samples, {:.1f}% within 1%, mean error "
        "{:.1f} mm\n",
        name, s.samples, 100.0 * s.share(), s.mean_error());
  // Floors about 5 points under what was measured (docs/fidelity.md): every textured object is
  // found to 1% almost everywhere, the checkerboard's and the print's uniform patches included.
  EXPECT_GE(scores["all"].share(), 0.91);
  EXPECT_GE(scores["globe"].share(), 0.93);
  EXPECT_GE(scores["fan"].share(), 0.94);
  EXPECT_GE(scores["marker cone"].share(), 0.90);
  EXPECT_GE(scores["back wall"].share(), 0.94);
  EXPECT_GE(scores["checkerboard"].share(), 0.93);
  EXPECT_GE(scores["coffee maker"].share(), 0.93);
  EXPECT_LE(scores["all"].mean_error(), 50.0);
  // The table, seen at a grazing angle, is where the slant prior shows (82.8% without it, 84.3%
  // with it; docs/depth.md): this floor is just under what was measured.
  EXPECT_GE(scores["table"].share(), 0.835);
  // The range does not reach the checkerboard's false match (1.85 m: a shift of one period
  // between neighbours) whatever the map's own reach: the nearest object is 3.4 m away.
  PlaneSweepOptions narrow;
  narrow.reach = 2;
  EXPECT_GT(EstimateDepthRange(lf, row, col, narrow).near_mm, 2800.0);
  if (const char* dir = std::getenv("LFCAM_FIDELITY_OUT")) {
    WriteDepthFiles(std::filesystem::path(dir) / "depth_estimate.png", estimate);
    DepthMap t = truth.map;
    t.range = estimate.range;
    WriteDepthFiles(std::filesystem::path(dir) / "depth_truth.png", t);
  }
}

}  // namespace
}  // namespace lfcam
