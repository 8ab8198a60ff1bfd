#include "lfcam/render/depth_aware_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/depth/depth_test_scene.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/oracle.h"

namespace lfcam {
namespace {

class DepthLookup : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(testing::TwoPlaneScene());
    lf_ = new LightField(testing::TwoPlaneLightField(*scene_));
    truth_ = new DepthSet(lf_->dims());
    for (int r = 0; r < lf_->dims().rows; ++r)
      for (int c = 0; c < lf_->dims().cols; ++c)
        truth_->set(GroundTruthDepth(*scene_, *lf_, r, c).map);
  }
  static void TearDownTestSuite() {
    delete truth_;
    delete lf_;
    delete scene_;
  }

  // A 96 x 96 view of the plate's edge from `eye` on the array's plane.
  static VirtualCamera Camera(const Vec3& eye, double aperture = 0, double focus = 4000) {
    VirtualCameraParams p;
    p.width = p.height = 96;
    p.eye = eye;
    p.look_at = Vec3(300, 275, 0);
    p.focal_length_mm = 500;
    p.focus_distance_mm = focus;
    p.aperture_mm = aperture;
    return VirtualCamera(p);
  }
  static double Psnr(const VirtualCamera& camera, Interpolation interpolation,
                     const DepthSet* depth = nullptr, bool antialias = false) {
    CpuRenderOptions o;
    o.interpolation = interpolation;
    o.depth = depth;
    o.antialias = antialias;
    const cv::Mat render = LinearToSrgb8Image(RenderLightFieldCpu(*lf_, camera, o).image);
    // 256 samples a pixel, with an aperture too (a quarter of the default: this runs under the
    // sanitizers); the three lookups are measured against the same oracle.
    OracleOptions oracle_options;
    oracle_options.samples_per_pixel = 256;
    const cv::Mat oracle = LinearToSrgb8Image(RenderSceneOracle(*scene_, camera, oracle_options));
    return CompareImages(render, oracle).psnr_db;
  }

  static Scene* scene_;
  static LightField* lf_;
  static DepthSet* truth_;
};
Scene* DepthLookup::scene_ = nullptr;
LightField* DepthLookup::lf_ = nullptr;
DepthSet* DepthLookup::truth_ = nullptr;

TEST_F(DepthLookup, PinholeBetweenCamerasIsAsCloseAsAtACameraWithoutGhosts) {
  const Vec3 between = 0.25 * (lf_->camera_center(3, 3) + lf_->camera_center(3, 4) +
                               lf_->camera_center(4, 3) + lf_->camera_center(4, 4));
  const double at_camera = Psnr(Camera(lf_->camera_center(3, 3)), Interpolation::kQuadrilinear);
  const double quadrilinear = Psnr(Camera(between), Interpolation::kQuadrilinear);
  const double focal_plane = Psnr(Camera(between, 0, 5000), Interpolation::kFocalPlane);
  const double depth = Psnr(Camera(between), Interpolation::kDepth, truth_);
  const double antialiased = Psnr(Camera(between), Interpolation::kDepth, truth_, true);
  std::cout << "[depth lookup] at a camera " << at_camera << " dB; between cameras: quadrilinear "
            << quadrilinear << ", focal-plane on the wall " << focal_plane << ", depth " << depth
            << ", depth antialiased " << antialiased << " dB\n";
  EXPECT_GE(depth, quadrilinear + 6.0);
  EXPECT_GE(depth, focal_plane + 3.0);
  // The plate's edge, sharp from the cameras that see it, steps from pixel to pixel where the
  // oracle's pixels blend; over the pixels' area it is as close as a view read at a camera.
  EXPECT_GE(depth, at_camera - 4.0);
  EXPECT_GE(antialiased, at_camera - 1.0);
}

TEST_F(DepthLookup, RefocusedThroughAnApertureBeatsBothLookups) {
  const Vec3 eye = lf_->slab().uv.center();
  for (const double focus : {3200.0, 5000.0}) {
    const VirtualCamera camera = Camera(eye, 96, focus);
    const double quadrilinear = Psnr(camera, Interpolation::kQuadrilinear);
    const double focal_plane = Psnr(camera, Interpolation::kFocalPlane);
    const double depth = Psnr(camera, Interpolation::kDepth, truth_);
    std::cout << "[depth lookup] d_o " << focus << ": quadrilinear " << quadrilinear
              << ", focal-plane " << focal_plane << ", depth " << depth << " dB\n";
    EXPECT_GE(depth, std::max(quadrilinear, focal_plane));
  }
}

// The rays a frame counts are the rays it cast: an antialiased pinhole pixel casts four (the
// command's "% of rays hit the slab" said 400% before).
TEST_F(DepthLookup, CountsTheRaysAnAntialiasedPixelCasts) {
  CpuRenderOptions o;
  o.interpolation = Interpolation::kDepth;
  o.depth = truth_;
  o.antialias = true;
  const VirtualCamera camera = Camera(lf_->slab().uv.center());
  const RenderResult r = RenderLightFieldCpu(*lf_, camera, o);
  const long long pixels = static_cast<long long>(camera.width()) * camera.height();
  EXPECT_EQ(r.rays, 4 * pixels);
  EXPECT_GT(r.rays_hit, 3 * pixels);
  EXPECT_LE(r.rays_hit, r.rays);
}

TEST_F(DepthLookup, NeedsDepthMapsAndTheLensSamplesIntegrator) {
  const VirtualCamera camera = Camera(lf_->slab().uv.center(), 64);
  CpuRenderOptions o;
  o.interpolation = Interpolation::kDepth;
  EXPECT_THROW(RenderLightFieldCpu(*lf_, camera, o), Error);
  o.depth = truth_;
  o.integrator = Integrator::kCameras;
  EXPECT_THROW(RenderLightFieldCpu(*lf_, camera, o), Error);
  const DepthSet other({7, 7, 120, 110});
  EXPECT_THROW(DepthAwareSampler(*lf_, other, LightFieldSampler(*lf_)), Error);
}

TEST_F(DepthLookup, ViewsNeededAreThoseAroundTheRays) {
  // A pinhole at camera (3, 3) reads it and its neighbours, not the grid's far corner.
  const std::vector<bool> at_camera = DepthViewsNeeded(*lf_, Camera(lf_->camera_center(3, 3)));
  EXPECT_TRUE(at_camera[3 * 7 + 3]);
  EXPECT_TRUE(at_camera[4 * 7 + 4]);
  EXPECT_FALSE(at_camera[0]);
  EXPECT_FALSE(at_camera[6 * 7 + 6]);
  // An aperture as wide as the array reads all of them.
  const std::vector<bool> wide = DepthViewsNeeded(*lf_, Camera(lf_->slab().uv.center(), 300));
  EXPECT_EQ(std::count(wide.begin(), wide.end(), true), 49);
}

}  // namespace
}  // namespace lfcam
