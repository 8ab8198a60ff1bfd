// The vectorised renderer against the scalar reference: the same model, the same sample
// positions, float rounding only. Every case runs on every instruction set Highway compiled
// that this machine can run (on an AVX-512 machine: AVX3, AVX2, SSE4, SSSE3 and the emulated
// baseline), so a kernel bug on any of them fails here.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <iostream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/render/simd_kernels.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam {
namespace {

using render_test::Cases;
using render_test::SmallPaperLightField;
using render_test::TurnedStPlaneLightField;

// The instruction sets compiled in that this machine runs.
std::vector<std::int64_t> Targets() {
  std::vector<std::int64_t> targets;
  for (std::int64_t t = 1; t != 0 && t <= HWY_TARGETS; t <<= 1)
    if ((HWY_TARGETS & t) && (hwy::SupportedTargets() & t)) targets.push_back(t);
  return targets;
}

TEST(FastRenderer, AgreesWithTheScalarReferenceOnEveryInstructionSet) {
  const std::vector<std::int64_t> targets = Targets();
  ASSERT_FALSE(targets.empty());
  std::cout << "instruction sets:";
  for (const std::int64_t t : targets) std::cout << " " << hwy::TargetName(t);
  std::cout << "\n";
  double worst = 0;
  for (const render_test::Case& c : Cases()) {
    const LightField& lf = c.turned ? TurnedStPlaneLightField() : SmallPaperLightField();
    const VirtualCamera camera(c.camera);
    CpuRenderOptions reference_options;
    reference_options.integrator = c.integrator;
    reference_options.interpolation = c.interpolation;
    reference_options.reference = true;
    reference_options.threads = 1;
    const RenderResult reference = RenderLightFieldCpu(lf, camera, reference_options);
    ASSERT_EQ(reference.path, "reference");
    ASSERT_GT(reference.rays_hit, 0) << c.name;
    CpuRenderOptions fast_options = reference_options;
    fast_options.reference = false;
    fast_options.threads = 0;
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      const RenderResult fast = RenderLightFieldCpu(lf, camera, fast_options);
      const std::string where = c.name + " on " + hwy::TargetName(target);
      EXPECT_EQ(fast.path, c.path + " (" + hwy::TargetName(target) + ")") << where;
      const double difference = cv::norm(fast.image, reference.image, cv::NORM_INF);
      worst = std::max(worst, difference);
      EXPECT_LE(difference, 1.0 / 255) << where;
      EXPECT_EQ(cv::countNonZero(fast.hit_mask != reference.hit_mask), 0) << where;
      // The rays, or the cameras read: the same, but for a camera whose line through p_o grazes
      // the domain's edge, which float (fast) and double (reference) may put on either side: at
      // most one in 10^4 reads.
      const double slack = std::max(1.0, 1e-4 * double(reference.rays_hit));
      EXPECT_NEAR(double(fast.rays), double(reference.rays), slack) << where;
      EXPECT_NEAR(double(fast.rays_hit), double(reference.rays_hit), slack) << where;
    }
    hwy::SetSupportedTargetsForTest(0);
  }
  std::cout << "largest difference from the reference: " << worst * 255 << " / 255\n";
}

TEST(FastRenderer, LeavesHalfFloatLightFieldsToTheReference) {
  SimulateLightFieldOptions o;
  o.rows = o.cols = 3;
  o.n_s = 24;
  o.n_t = 22;
  o.supersampling = 1;
  o.sample_type = SampleType::kLinearF16;
  const LightField lf = SimulateLightField(MakePaperScene(), o);
  VirtualCameraParams p;
  p.width = p.height = 16;
  p.eye = lf.slab().uv.center();
  p.look_at = p.eye - Vec3(0, 0, 1000);
  EXPECT_EQ(RenderLightFieldCpu(lf, VirtualCamera(p)).path, "reference");
}

}  // namespace
}  // namespace lfcam
