#include "lfcam/sim/simulate_lightfield.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "lfcam/core/color.h"
#include "lfcam/sim/shapes.h"

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

// Each ray is tested only against the objects whose projection from its camera can reach its
// sample (the boxes SimulateLightField finds for each view): the light field is, sample for
// sample, the one every ray tested against every object gives. Cameras off the board's axis, a
// domain wider than the board, objects before and behind the st-plane, and one beside the
// cameras themselves (not in front of them: every sample tests it).
TEST(SimulateLightField, LeavingOutObjectsARayCannotMeetChangesNoSample) {
  Scene scene = MakePaperScene();
  const Vec3 array_centre = scene.rig.array.center();
  Texture red;
  red.color_a = Vec3(0.8, 0.1, 0.1);
  scene.Add("ball before the board", std::make_shared<SphereShape>(Vec3(120, 420, 1800), 70), red);
  scene.Add("ball beside the cameras",
            std::make_shared<SphereShape>(array_centre + Vec3(160, 0, 0), 40), red);
  SimulateLightFieldOptions o;
  o.rows = 4;
  o.cols = 5;
  o.n_s = 72;
  o.n_t = 60;
  o.st_domain = {-0.3, -0.2, 1.2, 1.1};
  o.supersampling = 2;
  const LightField lf = SimulateLightField(scene, o);
  LightField every(lf.dims(), lf.sample_type(), lf.slab());
  const StSampling sampling = lf.st_sampling();
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.cols; ++c) {
      const Vec3 centre = lf.camera_center(r, c);
      for (int l = 0; l < o.n_t; ++l)
        for (int k = 0; k < o.n_s; ++k) {
          Vec3 sum = Vec3::Zero();
          for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
              const Vec3 at = sampling.Point(k - 0.5 + (b + 0.5) / 2, l - 0.5 + (a + 0.5) / 2);
              sum += scene.Radiance({centre, at - centre});
            }
          every.set_linear_rgb(r, c, k, l, (sum * 0.25).cast<float>());
        }
    }
  EXPECT_EQ(std::memcmp(lf.data(), every.data(), lf.total_bytes()), 0);
  // The ball before the board is in the views, so leaving it out where it cannot be was tested.
  int red_samples = 0;
  for (int l = 0; l < o.n_t; ++l)
    for (int k = 0; k < o.n_s; ++k) {
      const Eigen::Vector3f v = lf.linear_rgb(2, 2, k, l);
      red_samples += v[0] > 2 * v[1] + 0.05f;
    }
  EXPECT_GT(red_samples, 10);
}

}  // namespace
}  // namespace lfcam
