#include "lfcam/sim/simulate_lightfield.h"

#include <gtest/gtest.h>

#include "lfcam/core/color.h"

namespace lfcam {
namespace {

TEST(SimulateLightField, EachSampleIsTheRayFromItsCameraThroughItsStPoint) {
  const Scene scene = MakePaperScene();
  SimulateLightFieldOptions o;
  o.rows = 4;
  o.cols = 3;
  o.n_s = 40;
  o.n_t = 30;
  o.st_domain = {-0.1, 0.0, 1.1, 1.0};
  o.supersampling = 1;
  o.sample_type = SampleType::kLinearF16;
  const LightField lf = SimulateLightField(scene, o);
  // The grid keeps the scene's pitch and centre.
  EXPECT_TRUE(lf.slab().uv.center().isApprox(scene.rig.array.center()));
  EXPECT_DOUBLE_EQ(lf.slab().uv.pitch_mm, 28);
  for (auto [r, c, k, l] :
       {std::array{0, 0, 0, 0}, {3, 2, 39, 29}, {1, 2, 17, 5}, {2, 0, 33, 21}}) {
    const Vec3 from = lf.slab().uv.camera_center(r, c);
    const Vec3 to = lf.slab().st.point_at(lf.s_of(k), lf.t_of(l));
    const Vec3 expected = scene.Radiance({from, to - from});
    const Eigen::Vector3f got = lf.linear_rgb(r, c, k, l);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], expected[ch], 2e-3 * (1 + expected[ch]));
  }
  EXPECT_EQ(lf.metadata()["scene"], "paper");
}

TEST(SimulateLightField, Srgb8IsTheEncodedAverageOverTheCell) {
  const Scene scene = MakePaperScene();
  SimulateLightFieldOptions o;
  o.rows = o.cols = 2;
  o.n_s = 16;
  o.n_t = 16;
  o.supersampling = 3;
  const LightField lf = SimulateLightField(scene, o);
  const int r = 1, c = 0, k = 9, l = 4;
  const Vec3 from = lf.slab().uv.camera_center(r, c);
  Vec3 sum = Vec3::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double s = lf.s_of(k - 0.5 + (b + 0.5) / 3), t = lf.t_of(l - 0.5 + (a + 0.5) / 3);
      sum += scene.Radiance({from, lf.slab().st.point_at(s, t) - from});
    }
  const std::uint8_t* p = lf.view_data(r, c) + (l * 16 + k) * 3;
  for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(p[ch], LinearToSrgb8(float(sum[ch] / 9)));
}

}  // namespace
}  // namespace lfcam
