// The vectorised renderer against the scalar reference: the same model, the same sample
// positions, float rounding only. Every case runs on every instruction set Highway compiled
// that this machine can run (on an AVX-512 machine: AVX3, AVX2, SSE4, SSSE3 and the emulated
// baseline), so a kernel bug on any of them fails here.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "lfcam/core/instruction_sets_for_tests.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/render/simd_kernels.h"

namespace lfcam {
namespace {

using render_test::Cases;
using render_test::SmallPaperLightField;
using render_test::TurnedStPlaneLightField;

// A case's options for the scalar reference (one thread), and for the vectorised renderer (every
// core).
// `base`'s views and geometry, each sample's linear colour `colour(r, c, k, l)`, stored as `type`.
LightField WithSamples(const LightField& base, SampleType type,
                       const std::function<Eigen::Vector3f(int, int, int, int)>& colour) {
  LightField out(base.dims(), type, base.slab());
  out.set_measured_poses(base.measured_poses());
  const LightFieldDims& d = base.dims();
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c)
      for (int l = 0; l < d.n_t; ++l)
        for (int k = 0; k < d.n_s; ++k) out.set_linear_rgb(r, c, k, l, colour(r, c, k, l));
  return out;
}

CpuRenderOptions CaseOptions(const render_test::Case& c, bool reference) {
  CpuRenderOptions o;
  o.integrator = c.integrator;
  o.interpolation = c.interpolation;
  o.reference = reference;
  o.threads = reference ? 1 : 0;
  return o;
}

TEST(FastRenderer, AgreesWithTheScalarReferenceOnEveryInstructionSet) {
  const std::vector<std::int64_t> targets = testing::InstructionSetsThisMachineRuns();
  ASSERT_FALSE(targets.empty());
  std::cout << "instruction sets:";
  for (const std::int64_t t : targets) std::cout << " " << hwy::TargetName(t);
  std::cout << "\n";
  double worst = 0;
  // The quadrilinear limits render their filtered copies, with the fade at the views' edges
  // (render/window_taper.h), on the same paths.
  for (const render_test::Case& c : render_test::WithQuadrilinearLimits(Cases())) {
    const LightField& lf = c.turned ? TurnedStPlaneLightField() : SmallPaperLightField();
    const VirtualCamera camera(c.camera);
    const RenderResult reference = RenderLightFieldCpu(lf, camera, CaseOptions(c, true));
    ASSERT_EQ(reference.path.substr(0, 9), "reference") << c.name;
    ASSERT_GT(reference.rays_hit, 0) << c.name;
    const CpuRenderOptions fast_options = CaseOptions(c, false);
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      const RenderResult fast = RenderLightFieldCpu(lf, camera, fast_options);
      const std::string where = c.name + " on " + hwy::TargetName(target);
      const std::string path = c.path + " (" + hwy::TargetName(target) + ")";
      EXPECT_EQ(fast.path.substr(0, path.size()), path) << where;
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

// A camera turned up or down makes k drift with the pixel row, and the separable frame then
// resamples each sample row again every few rows (SeparableFrame::resample_every). On views of
// one-sample stripes across k, where any error in k shows at full contrast, its frames still
// agree with the scalar reference to within the tolerance's share of a level.
TEST(FastRenderer, FramesTurnedUpOrDownResampleTheirRowsOftenEnough) {
  const LightField& paper = SmallPaperLightField();
  const LightField stripes = WithSamples(paper, paper.sample_type(), [](int, int, int k, int) {
    return Eigen::Vector3f::Constant(k % 2 == 0 ? 1.0f : 0.0f);
  });
  int drifting = 0;
  for (const render_test::Case& c : Cases()) {
    if (c.integrator != Integrator::kCameras ||
        (c.name.rfind("turned up,", 0) != 0 &&
         c.name.rfind("aperture in front of the array, turned cameras", 0) != 0))
      continue;
    const VirtualCamera camera(c.camera);
    const RenderResult reference = RenderLightFieldCpu(stripes, camera, CaseOptions(c, true));
    const RenderResult fast = RenderLightFieldCpu(stripes, camera, CaseOptions(c, false));
    EXPECT_EQ(fast.path.substr(0, 9), "separable") << c.name;
    const cv::Mat both = (fast.hit_mask > 0) & (reference.hit_mask > 0);
    cv::Mat difference;
    cv::absdiff(fast.image, reference.image, difference);
    double worst = 0;
    cv::minMaxLoc(difference.reshape(1), nullptr, &worst, nullptr, nullptr,
                  cv::repeat(both, 1, 3).reshape(1));
    EXPECT_LE(worst, 1.0 / 255) << c.name;
    ++drifting;
  }
  EXPECT_EQ(drifting, 2);
}

// A light field of linear half floats (`--sample-type linear_f16`): the same samples, the row
// kernels convert them where they decode bytes; the kernels that gather single samples read only
// 8-bit words, and leave such frames to the reference.
TEST(FastRenderer, ReadsHalfFloatLightFieldsWithTheRowKernels) {
  const LightField& bytes = SmallPaperLightField();
  const LightField halves =
      WithSamples(bytes, SampleType::kLinearF16,
                  [&](int r, int c, int k, int l) { return bytes.linear_rgb(r, c, k, l); });
  const std::vector<std::int64_t> targets = testing::InstructionSetsThisMachineRuns();
  int row_frames = 0;
  for (const render_test::Case& c : Cases()) {
    if (c.turned) continue;
    const VirtualCamera camera(c.camera);
    const RenderResult reference = RenderLightFieldCpu(halves, camera, CaseOptions(c, true));
    // The 8-bit light field's frame: what the half floats hold is its samples, decoded.
    const RenderResult from_bytes = RenderLightFieldCpu(bytes, camera, CaseOptions(c, true));
    EXPECT_LE(cv::norm(reference.image, from_bytes.image, cv::NORM_INF), 1e-3) << c.name;
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      const RenderResult fast = RenderLightFieldCpu(halves, camera, CaseOptions(c, false));
      const std::string where = c.name + " on " + hwy::TargetName(target);
      if (c.path == "separable") {
        EXPECT_EQ(fast.path, "separable (" + std::string(hwy::TargetName(target)) + ")") << where;
        ++row_frames;
      } else {
        EXPECT_EQ(fast.path, "reference") << where;
      }
      EXPECT_LE(cv::norm(fast.image, reference.image, cv::NORM_INF), 1.0 / 255) << where;
      EXPECT_EQ(cv::countNonZero(fast.hit_mask != reference.hit_mask), 0) << where;
    }
    hwy::SetSupportedTargetsForTest(0);
  }
  EXPECT_GT(row_frames, 0);
}

}  // namespace
}  // namespace lfcam
