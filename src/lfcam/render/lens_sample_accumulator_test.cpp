// Rendering the lens samples a part at a time and accumulating gives the whole frame.
#include "lfcam/render/lens_sample_accumulator.h"

#include <gtest/gtest.h>

#include "lfcam/render/render_test_cases.h"

namespace lfcam {
namespace {

TEST(LensSampleAccumulator, PartsAddUpToTheWholeFrame) {
  const LightField& lf = render_test::SmallPaperLightField();
  int checked = 0;
  for (const render_test::Case& c : render_test::Cases()) {
    if (c.integrator != Integrator::kLensSamples || c.camera.aperture_mm <= 0 || c.turned) continue;
    const VirtualCamera camera(c.camera);
    CpuRenderOptions o;
    o.integrator = c.integrator;
    o.interpolation = c.interpolation;
    const RenderResult whole = RenderLightFieldCpu(lf, camera, o);
    const int n = int(camera.lens_samples().size());
    ASSERT_GT(n, 3) << c.name;
    LensSampleAccumulator acc;
    acc.Reset(camera.width(), camera.height());
    for (const auto& [begin, end] : {std::pair{0, 1}, std::pair{1, n / 2}, std::pair{n / 2, n}})
      acc.Add(RenderLightFieldCpu(lf, camera.WithLensSampleRange(begin, end), o));
    const RenderResult sum = acc.Frame();
    EXPECT_LE(cv::norm(sum.image, whole.image, cv::NORM_INF), 1e-5) << c.name;
    EXPECT_EQ(cv::countNonZero(sum.counts != whole.counts), 0) << c.name;
    EXPECT_EQ(sum.rays_hit, whole.rays_hit) << c.name;
    EXPECT_EQ(sum.rays, whole.rays) << c.name;
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

}  // namespace
}  // namespace lfcam
