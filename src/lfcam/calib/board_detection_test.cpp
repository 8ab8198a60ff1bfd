#include "lfcam/calib/board_detection.h"

#include <gtest/gtest.h>

#include <numbers>
#include <opencv2/imgproc.hpp>

#include "lfcam/sim/board_radiance.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

// A module 900 mm in front of a 10x7 board, which is turned by `roll` about its normal.
struct BoardPhoto {
  SimulatedModule module;
  BoardSpec board{10, 7, 30.0};
  Rigid3 world_from_board;
  cv::Mat gray;
};

BoardPhoto Photograph(double roll_degrees, double tilt_degrees) {
  BoardPhoto p;
  p.module.intrinsics = NominalPiCamera(1296, 972);
  p.module.intrinsics.distortion = {0.1, -0.2, 0.0005, -0.0007, 0.06};
  p.module.world_from_camera = {
      WorldFromCameraRotation(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()), Vec3(0, 0, 900)};
  const double degree = std::numbers::pi / 180;
  const Mat3 r = (Eigen::AngleAxisd(roll_degrees * degree, Vec3::UnitZ()) *
                  Eigen::AngleAxisd(tilt_degrees * degree, Vec3::UnitY()))
                     .toRotationMatrix();
  const Vec3 half(0.5 * p.board.width_mm(), 0.5 * p.board.height_mm(), 0);
  p.world_from_board = {r, Vec3(20, -10, 0) - r * half};
  const Scene scene = MakePaperScene();
  ExposureOptions exposure;
  exposure.noise = false;
  const cv::Mat rgb = ExposeModule(p.module, ModuleRayDirections(p.module),
                                   BoardInFrontOf(p.board, p.world_from_board, scene), exposure);
  cv::cvtColor(rgb, p.gray, cv::COLOR_RGB2GRAY);
  return p;
}

void ExpectCornersAtTheirTruePixels(const BoardPhoto& p, double tolerance_px) {
  const auto found = DetectChessboard(p.gray, p.board);
  ASSERT_TRUE(found);
  const auto points = p.board.corners();
  ASSERT_EQ(found->size(), points.size());
  const Rigid3 camera_from_board = p.module.world_from_camera.inverse() * p.world_from_board;
  double worst = 0, sum = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto truth = p.module.intrinsics.Project(camera_from_board * points[i]);
    ASSERT_TRUE(truth);
    const double error = (*truth - Vec2((*found)[i].x, (*found)[i].y)).norm();
    worst = std::max(worst, error);
    sum += error;
  }
  EXPECT_LT(worst, tolerance_px);
  EXPECT_LT(sum / double(points.size()), 0.06);
}

TEST(BoardDetection, FindsEveryCornerWhereItIsAndInTheBoardsOrder) {
  // Upright, turned a little, upside down (OpenCV would number it from the other end) and
  // tilted: the corners come back at their true pixels, in the board's own order.
  for (const double roll : {0.0, 12.0, 180.0, -100.0}) {
    SCOPED_TRACE(roll);
    ExpectCornersAtTheirTruePixels(Photograph(roll, 20.0), 0.15);
  }
}

TEST(BoardDetection, ReportsABoardThatIsNotThere) {
  const BoardPhoto p = Photograph(0, 0);
  EXPECT_FALSE(DetectChessboard(p.gray, BoardSpec{9, 6, 30.0}));  // the wrong size
  EXPECT_FALSE(DetectChessboard(cv::Mat(480, 640, CV_8UC1, cv::Scalar(90)), p.board));
}

}  // namespace
}  // namespace lfcam
