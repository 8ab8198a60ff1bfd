#include "lfcam/sim/oracle.h"

#include <gtest/gtest.h>

#include <tuple>

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
