#include "lfcam/calib/array_fit.h"

#include <gtest/gtest.h>

#include <random>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// A tilted, rotated, shifted 10x10 grid of 28 mm, each centre moved a little off its cell.
struct TrueArray {
  ArrayPlane array;
  std::vector<GridCamera> cameras;
};

TrueArray MakeTrueArray(double theta, double jitter_mm, unsigned seed) {
  TrueArray t;
  ArrayPlane& a = t.array;
  a.rows = a.cols = 10;
  a.pitch_mm = 28;
  const Mat3 tilt = Eigen::AngleAxisd(0.05, Vec3(1, 2, 0).normalized()).toRotationMatrix();
  // Rotate within the plane by theta, then tilt the plane.
  a.u_ca = tilt * Vec3(std::cos(theta), std::sin(theta), 0);
  a.v_ca = tilt * Vec3(-std::sin(theta), std::cos(theta), 0);
  a.n_ca = a.u_ca.cross(a.v_ca);
  const Vec3 center(310, 260, 3600);
  a.p_ca = center - 0.5 * a.width_mm() * a.u_ca - 0.5 * a.height_mm() * a.v_ca;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, jitter_mm);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 10; ++c) {
      const Vec3 jitter(noise(rng), noise(rng), noise(rng));
      t.cameras.push_back({r, c, a.camera_center(r, c) + jitter});
    }
  return t;
}

TEST(ArrayFit, RecoversAnExactGrid) {
  const TrueArray t = MakeTrueArray(0.03, 0.0, 1);
  const ArrayFit fit = FitArray(t.cameras, 10, 10, 28, Vec3(300, 275, 0));
  EXPECT_NEAR((fit.array.p_ca - t.array.p_ca).norm(), 0, 1e-9);
  EXPECT_NEAR((fit.array.u_ca - t.array.u_ca).norm(), 0, 1e-12);
  EXPECT_NEAR((fit.array.v_ca - t.array.v_ca).norm(), 0, 1e-12);
  EXPECT_NEAR((fit.array.n_ca - t.array.n_ca).norm(), 0, 1e-12);
  EXPECT_NEAR(fit.grid_rms_mm, 0, 1e-9);
  EXPECT_NEAR(fit.plane_rms_mm, 0, 1e-5);  // rounding in the covariance of 3.6 m coordinates
  EXPECT_NEAR(fit.theta_newton, fit.theta_closed, 1e-12);
  EXPECT_GE(fit.newton_iterations, 1);
}

TEST(ArrayFit, NewtonAgreesWithTheClosedFormAndNormalFacesAway) {
  for (const double theta : {-0.3, -0.01, 0.0, 0.2, 0.7}) {
    const TrueArray t = MakeTrueArray(theta, 1.0, 7);
    const ArrayFit fit = FitArray(t.cameras, 10, 10, 28, Vec3(300, 275, 0));
    EXPECT_NEAR(fit.theta_newton, fit.theta_closed, 1e-10) << theta;
    EXPECT_GT(fit.array.n_ca.dot(t.array.n_ca), 0.999) << theta;
    // 100 centres jittered by 1 mm: the grid is found to well under a millimetre.
    EXPECT_LT((fit.array.center() - t.array.center()).norm(), 0.4) << theta;
    EXPECT_NEAR(fit.grid_rms_mm, std::sqrt(2.0), 0.4) << theta;
    EXPECT_EQ(fit.ideal_centers.size(), 100u);
  }
  // Seen from the other side, the normal flips to stay away from the scene.
  const TrueArray t = MakeTrueArray(0.1, 0.0, 3);
  const ArrayFit fit = FitArray(t.cameras, 10, 10, 28, Vec3(300, 275, 9000));
  EXPECT_LT(fit.array.n_ca.dot(t.array.n_ca), -0.999);
}

TEST(ArrayFit, RefusesCentresOnALineOrTooFew) {
  std::vector<GridCamera> line;
  for (int c = 0; c < 10; ++c) line.push_back({0, c, Vec3(28.0 * c, 0, 3600)});
  EXPECT_THROW(FitArray(line, 1, 10, 28, Vec3::Zero()), Error);
  line.resize(2);
  EXPECT_THROW(FitArray(line, 1, 10, 28, Vec3::Zero()), Error);
}

// A grid numbered as lfcam numbers it, seen in a board frame turned by `degrees` (and mirrored):
// aligned, half a turn (a board hung the other way up), a quarter turn or mirrored.
TEST(ArrayFit, TellsHowTheGridRunsAgainstTheBoard) {
  auto grid = [](double degrees, bool mirrored, int rows, int cols) {
    const double a = degrees * M_PI / 180;
    std::vector<GridCamera> cameras;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double x = 28.0 * c + 0.3 * ((r * 7 + c * 3) % 5 - 2);
        const double y = (mirrored ? -28.0 : 28.0) * r;
        cameras.push_back({r, c,
                           Vec3(300 + std::cos(a) * x - std::sin(a) * y,
                                275 + std::sin(a) * x + std::cos(a) * y, 3600)});
      }
    return GridAgainstBoard(cameras);
  };
  EXPECT_EQ(grid(0, false, 10, 10).turn, GridTurn::kAligned);
  EXPECT_EQ(grid(30, false, 10, 10).turn, GridTurn::kAligned);
  EXPECT_EQ(grid(180, false, 10, 10).turn, GridTurn::kHalfTurn);
  EXPECT_NEAR(std::abs(grid(180, false, 10, 10).angle_deg), 180, 1);
  EXPECT_EQ(grid(-170, false, 3, 3).turn, GridTurn::kHalfTurn);
  EXPECT_EQ(grid(90, false, 10, 10).turn, GridTurn::kQuarterTurn);
  EXPECT_EQ(grid(0, true, 10, 10).turn, GridTurn::kMirrored);
  // A single row or column still has a direction; a single camera has none.
  EXPECT_EQ(grid(180, false, 1, 5).turn, GridTurn::kHalfTurn);
  EXPECT_EQ(grid(180, false, 5, 1).turn, GridTurn::kHalfTurn);
  EXPECT_EQ(grid(180, false, 1, 1).turn, GridTurn::kAligned);
}

}  // namespace
}  // namespace lfcam
