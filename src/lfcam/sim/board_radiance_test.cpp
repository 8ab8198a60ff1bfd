#include "lfcam/sim/board_radiance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "lfcam/sim/scene.h"
#include "lfcam/sim/shapes.h"

namespace lfcam {
namespace {

double BruteForceBlack(const BoardSpec& b, double x0, double x1, double y0, double y1) {
  const int n = 400;
  int black = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (i + 0.5) / n * (x1 - x0), y = y0 + (j + 0.5) / n * (y1 - y0);
      const bool inside = x >= 0 && y >= 0 && x < b.width_mm() && y < b.height_mm();
      black += inside && b.black_at(x, y);
    }
  return double(black) / (n * n);
}

TEST(BoardRadiance, BlackAreaIsTheExactShareUnderTheFootprint) {
  const BoardSpec b{10, 7, 30.0};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-40, 360), size(0.5, 70);
  for (int trial = 0; trial < 40; ++trial) {
    const double x0 = pos(rng), y0 = pos(rng) * 0.7, w = size(rng), h = size(rng);
    EXPECT_NEAR(BlackAreaFraction(b, x0, x0 + w, y0, y0 + h),
                BruteForceBlack(b, x0, x0 + w, y0, y0 + h), 4e-3)
        << x0 << " " << y0 << " " << w << " " << h;
  }
  // Straddling a corner symmetrically: half black.
  EXPECT_NEAR(BlackAreaFraction(b, 25, 35, 25, 35), 0.5, 1e-12);
  // Inside one square.
  EXPECT_NEAR(BlackAreaFraction(b, 1, 2, 1, 2), 1.0, 1e-12);
  EXPECT_NEAR(BlackAreaFraction(b, 31, 32, 1, 2), 0.0, 1e-12);
  // Outside the squared area: the white margin.
  EXPECT_NEAR(BlackAreaFraction(b, -20, -10, 5, 10), 0.0, 1e-12);
}

// A 320 x 240 module with a wide lens's distortion, 1 m from the world origin, looking down -z.
SimulatedModule DistortedModule() {
  SimulatedModule m;
  m.intrinsics = NominalPiCamera(320, 240);
  m.intrinsics.distortion = {0.1, -0.2, 0.0005, -0.0007, 0.06};
  m.world_from_camera = {WorldFromCameraRotation(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()),
                         Vec3(0, 0, 1000)};
  return m;
}

// A board turned by `tilt` degrees about y and `roll` about z, its centre at `center`.
Rigid3 BoardPose(const BoardSpec& b, double tilt, double roll, const Vec3& center) {
  const double degree = std::numbers::pi / 180;
  const Mat3 r = (Eigen::AngleAxisd(roll * degree, Vec3::UnitZ()) *
                  Eigen::AngleAxisd(tilt * degree, Vec3::UnitY()))
                     .toRotationMatrix();
  return {r, center - r * Vec3(0.5 * b.width_mm(), 0.5 * b.height_mm(), 0)};
}

TEST(BoardRadiance, FootprintRunsHoldEveryPixelTheBoardChanges) {
  const SimulatedModule module = DistortedModule();
  const cv::Mat directions = ModuleRayDirections(module);
  const Scene scene = MakePaperScene();
  const cv::Mat behind = RenderRadiance(module, directions, SceneRadiance(scene, 1));
  const BoardSpec board{10, 7, 30.0};
  struct BoardCase {
    const char* what;
    Rigid3 pose;
    double min_share, max_share;  // of the image's pixels inside the runs
  };
  const BoardCase cases[] = {
      {"head-on, in the middle", BoardPose(board, 0, 0, Vec3(0, 0, 0)), 0.05, 0.6},
      {"tilted and rolled, off-centre", BoardPose(board, 35, 20, Vec3(150, -80, 100)), 0.05, 0.7},
      {"partly out of view", BoardPose(board, -20, 5, Vec3(480, 250, 0)), 0.01, 0.5},
      {"filling the view", BoardPose(board, 0, 0, Vec3(0, 0, 700)), 0.99, 1.0},
      {"behind the camera", BoardPose(board, 0, 0, Vec3(0, 0, 1500)), 0.0, 0.0},
  };
  for (const BoardCase& c : cases) {
    const PixelRadiance radiance = BoardInFrontOf(board, c.pose, scene);
    const PixelRuns runs = BoardFootprintRuns(board, c.pose, module, directions);
    ASSERT_EQ(int(runs.size()), module.intrinsics.height) << c.what;
    const cv::Mat everywhere = RenderRadiance(module, directions, radiance, &behind);
    const cv::Mat in_runs = RenderRadiance(module, directions, radiance, &behind, &runs);
    // Not one pixel differs: every pixel outside the runs is exactly what stands behind.
    EXPECT_EQ(cv::norm(everywhere, in_runs, cv::NORM_INF), 0.0) << c.what;
    double inside = 0;
    for (const cv::Vec2i& run : runs) inside += std::max(0, run[1] - run[0]);
    const double share = inside / double(module.intrinsics.width * module.intrinsics.height);
    EXPECT_GE(share, c.min_share) << c.what;
    EXPECT_LE(share, c.max_share) << c.what;
  }
}

// A 96 x 72 module 1 m in front of the plane z = 0, facing it square on.
SimulatedModule FacingModule() {
  SimulatedModule m;
  m.intrinsics = NominalPiCamera(96, 72);
  m.world_from_camera = {WorldFromCameraRotation(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()),
                         Vec3(0, 0, 1000)};
  return m;
}

// A white wall on the plane z = 0 whose vertical right edge stands at x = edge_mm, lit evenly.
Scene WallEndingAt(double edge_mm) {
  Texture white;
  white.color_a = Vec3(0.8, 0.8, 0.8);
  Scene scene;
  scene.ambient = 1.0;
  scene.Add("wall",
            std::make_shared<RectangleShape>(Vec3(edge_mm - 2000, 0, 0), Vec3::UnitX(),
                                             Vec3::UnitY(), 2000, 2000),
            white);
  return scene;
}

// A dark frame with a white wall whose vertical edge moves across one pixel in 16 steps: the
// edge's place in the image, read from each row's sum of coverage, must follow it. A regular
// 2 x 2 grid of rays a pixel (before 2026-12-06) rounds it to half a pixel, a staircase up to
// 0.25 px off, the same in every camera; rays drawn within the strata leave noise that the
// rows average out, and no staircase.
TEST(SceneRadiance, AnEdgesPlaceWithinAPixelIsRecordedNotRounded) {
  const SimulatedModule m = FacingModule();
  const cv::Mat directions = ModuleRayDirections(m);
  const double mm_per_px = 1000.0 / m.intrinsics.fx;
  auto edge_px = [&](double edge_mm) {
    const Scene scene = WallEndingAt(edge_mm);
    const cv::Mat lit = RenderRadiance(m, directions, SceneRadiance(scene, 2));
    // Each row: the covered share of every pixel, summed (the wall's width in pixels).
    const double left = lit.at<cv::Vec3f>(lit.rows / 2, 0)[1];
    const double right = lit.at<cv::Vec3f>(lit.rows / 2, lit.cols - 1)[1];
    const double wall = std::max(left, right), dark = std::min(left, right);
    double covered = 0;
    for (int y = 0; y < lit.rows; ++y)
      for (int x = 0; x < lit.cols; ++x)
        covered += (lit.at<cv::Vec3f>(y, x)[1] - dark) / (wall - dark);
    return covered / lit.rows;
  };
  const double start = edge_px(0.0);
  double worst = 0;
  for (int k = 1; k <= 16; ++k) {
    const double moved = k / 16.0;
    worst = std::max(worst, std::abs(std::abs(edge_px(moved * mm_per_px) - start) - moved));
  }
  EXPECT_LT(worst, 0.08) << "px: the edge's recorded place against its true one";
}

// The share of a pixel centred at x (pixels) that a step edge at e covers on its far side, once
// blurred by a Gaussian of sigma pixels: the integral over the pixel of the Gaussian's CDF,
// G(t) = t Phi(t) + phi(t) its antiderivative.
double BlurredEdgeShare(double x, double e, double sigma) {
  auto antiderivative = [](double t) {
    return t * 0.5 * std::erfc(-t / std::numbers::sqrt2) +
           std::exp(-0.5 * t * t) / std::sqrt(2 * std::numbers::pi);
  };
  return sigma * (antiderivative((x + 0.5 - e) / sigma) - antiderivative((x - 0.5 - e) / sigma));
}

// A lens of blur sigma spreads an edge as the pixel's box convolved with a Gaussian of sigma:
// the mean profile across a wall's edge, over every row, against that profile.
TEST(SceneRadiance, TheLensSpreadsAnEdgeByItsPointSpread) {
  SimulatedModule m = FacingModule();
  const cv::Mat directions = ModuleRayDirections(m);
  const double edge_mm = 3.3;
  const Scene scene = WallEndingAt(edge_mm);
  const auto edge =
      m.intrinsics.Project(m.world_from_camera.inverse() * Vec3(edge_mm, 0, 0)).value();
  for (const double sigma : {0.0, 0.3, 0.6, 1.2}) {
    m.lens_blur_px = sigma;
    const cv::Mat lit = RenderRadiance(m, directions, SceneRadiance(scene, 6));
    const float left = lit.at<cv::Vec3f>(0, 0)[1], right = lit.at<cv::Vec3f>(0, lit.cols - 1)[1];
    double worst = 0;
    for (int x = 0; x < lit.cols; ++x) {
      double share = 0;
      for (int y = 0; y < lit.rows; ++y)
        share += (lit.at<cv::Vec3f>(y, x)[1] - left) / (right - left);
      share /= lit.rows;
      const double expected = sigma > 0 ? BlurredEdgeShare(x, edge.x(), sigma)
                                        : std::clamp(x + 0.5 - edge.x(), 0.0, 1.0);
      worst = std::max(worst, std::abs(share - expected));
    }
    // (Measured 0.002-0.006; unblurred, the profiles differ by 0.02, 0.11 and 0.25.)
    EXPECT_LT(worst, 0.012) << "sigma " << sigma << " px: the mean profile against box * Gaussian";
  }
}

}  // namespace
}  // namespace lfcam
