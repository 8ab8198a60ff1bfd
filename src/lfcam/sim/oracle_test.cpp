#include "lfcam/sim/oracle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"

namespace lfcam {
namespace {

VirtualCameraParams PaperCamera(double aperture) {
  VirtualCameraParams p;
  p.width = p.height = 64;
  p.eye = Vec3(300, 275, 3600);
  p.look_at = Vec3(300, 275, 0);
  p.focus_distance_mm = 3900;
  p.aperture_mm = aperture;
  return p;
}

// The oracle tests each ray against its block's objects alone (ObjectsTheRaysCanMeet); that is
// exact only if every object a ray of the block meets is among them.
TEST(Oracle, EachBlockKeepsEveryObjectItsRaysMeet) {
  const Scene scene = MakePaperScene();
  std::vector<VirtualCameraParams> cameras = {PaperCamera(0), PaperCamera(192)};
  VirtualCameraParams wide = PaperCamera(600);  // a lens wider than the array, focused near
  wide.focal_length_mm = 60;
  wide.focus_distance_mm = 900;
  wide.breathing = false;
  cameras.push_back(wide);
  VirtualCameraParams aslant = PaperCamera(150);  // off the axis, a shifted sensor
  aslant.eye = Vec3(-400, 900, 2500);
  aslant.look_at = Vec3(400, 100, -300);
  aslant.focus_distance_mm = 5200;
  aslant.principal_offset_px = Vec2(9.5, -6.0);
  cameras.push_back(aslant);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int rays_meeting = 0, left_out = 0;
  for (const VirtualCameraParams& p : cameras) {
    const VirtualCamera camera(p);
    constexpr int kBlock = 8;
    for (int j0 = 0; j0 < p.height; j0 += kBlock)
      for (int i0 = 0; i0 < p.width; i0 += kBlock) {
        const std::vector<int> kept =
            ObjectsTheRaysCanMeet(scene, camera, i0, j0, i0 + kBlock, j0 + kBlock);
        ASSERT_TRUE(std::is_sorted(kept.begin(), kept.end()));
        left_out += int(scene.objects.size() - kept.size());
        for (int ray = 0; ray < 300; ++ray) {
          const Vec3 direction =
              camera.direction_through(i0 + kBlock * unit(random), j0 + kBlock * unit(random));
          // A lens point anywhere on the disk, its rim included.
          const double angle = 2 * M_PI * unit(random), radius = ray % 10 == 0 ? 1.0 : unit(random);
          const Vec3 lens =
              camera.lens_point(Vec2(radius * std::cos(angle), radius * std::sin(angle)));
          const Vec3 p_o = camera.focus_point(direction);
          for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            SurfaceHit hit;
            if (!scene.objects[i].shape->Intersect({lens, p_o - lens}, 1e-9, HUGE_VAL, &hit))
              continue;
            ++rays_meeting;
            EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), int(i)))
                << "object " << i << " (" << scene.objects[i].name << ") met by a ray of block ("
                << i0 << ", " << j0 << ") but left out; camera at " << p.eye.transpose();
          }
        }
      }
  }
  EXPECT_GT(rays_meeting, 10000);
  EXPECT_GT(left_out, 100);  // the blocks leave objects out: the culling does something
}

TEST(Oracle, DefaultSampleCountIsConverged) {
  // The defaults (256 samples a pixel for a pinhole, 1024 with an aperture) must agree with 4x
  // as many to well above the PSNRs the fidelity tests measure (at most ~40 dB).
  const Scene scene = MakePaperScene();
  for (const auto& [aperture, more_samples, min_psnr] :
       {std::tuple{0.0, 1024, 40.0}, std::tuple{192.0, 4096, 46.0}}) {
    const VirtualCamera camera(PaperCamera(aperture));
    const cv::Mat standard = LinearToSrgb8Image(RenderSceneOracle(scene, camera));
    const cv::Mat more =
        LinearToSrgb8Image(RenderSceneOracle(scene, camera, {more_samples, 0, {}}));
    EXPECT_GT(CompareImages(standard, more).psnr_db, min_psnr) << "aperture " << aperture;
  }
}

TEST(Oracle, ApertureBlursOutOfFocusDetail) {
  const Scene scene = MakePaperScene();
  const cv::Mat pinhole = RenderSceneOracle(scene, VirtualCamera(PaperCamera(0)));
  const cv::Mat wide = RenderSceneOracle(scene, VirtualCamera(PaperCamera(192)));
  // The checkerboard at 5.2 m fills the top left corner: contrast drops with the aperture.
  cv::Mat mean_p, std_p, mean_w, std_w;
  cv::meanStdDev(pinhole(cv::Rect(0, 0, 16, 16)), mean_p, std_p);
  cv::meanStdDev(wide(cv::Rect(0, 0, 16, 16)), mean_w, std_w);
  EXPECT_LT(std_w.at<double>(0), 0.5 * std_p.at<double>(0));
  // ... while its mean radiance is preserved (a linear-light average).
  EXPECT_NEAR(mean_w.at<double>(0), mean_p.at<double>(0), 0.1 * mean_p.at<double>(0));
}

}  // namespace
}  // namespace lfcam
