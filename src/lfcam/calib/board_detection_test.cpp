#include "lfcam/calib/board_detection.h"

#include <gtest/gtest.h>

#include <numbers>
#include <opencv2/imgproc.hpp>

#include "lfcam/sim/board_radiance.h"
#include "lfcam/sim/camera_module.h"
#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

// A module 900 mm in front of a board centred at `center` (mm, the camera looks along +z from
// z = 900), turned by `roll` about its normal and tilted about its y axis.
struct BoardPhoto {
  SimulatedModule module;
  BoardSpec board{10, 7, 30.0};
  Rigid3 world_from_board;
  cv::Mat gray;
};

BoardPhoto Photograph(double roll_degrees, double tilt_degrees,
                      const BoardSpec& board = {10, 7, 30.0},
                      const Vec3& center = Vec3(20, -10, 0)) {
  BoardPhoto p;
  p.board = board;
  p.module.intrinsics = NominalPiCamera(1296, 972);
  p.module.intrinsics.distortion = {0.1, -0.2, 0.0005, -0.0007, 0.06};
  p.module.world_from_camera = {
      WorldFromCameraRotation(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()), Vec3(0, 0, 900)};
  const double degree = std::numbers::pi / 180;
  const Mat3 r = (Eigen::AngleAxisd(roll_degrees * degree, Vec3::UnitZ()) *
                  Eigen::AngleAxisd(tilt_degrees * degree, Vec3::UnitY()))
                     .toRotationMatrix();
  const Vec3 half(0.5 * p.board.width_mm(), 0.5 * p.board.height_mm(), 0);
  p.world_from_board = {r, center - r * half};
  const Scene scene = MakePaperScene();
  ExposureOptions exposure;
  exposure.noise = false;
  const cv::Mat rgb = ExposeModule(p.module, ModuleRayDirections(p.module),
                                   BoardInFrontOf(p.board, p.world_from_board, scene), exposure);
  cv::cvtColor(rgb, p.gray, cv::COLOR_RGB2GRAY);
  return p;
}

// Checks the corners found against their true pixels; returns how many were found.
int ExpectCornersAtTheirTruePixels(const BoardPhoto& p, double tolerance_px,
                                   double mean_tolerance_px = 0.06) {
  const auto found = DetectBoard(p.gray, p.board);
  EXPECT_TRUE(found);
  if (!found) return 0;
  const auto points = p.board.corners();
  EXPECT_EQ(found->size(), points.size());
  const Rigid3 camera_from_board = p.module.world_from_camera.inverse() * p.world_from_board;
  double worst = 0, sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < points.size() && i < found->size(); ++i) {
    if (!CornerFound((*found)[i])) continue;
    const auto truth = p.module.intrinsics.Project(camera_from_board * points[i]);
    EXPECT_TRUE(truth);
    if (!truth) continue;
    const double error = (*truth - Vec2((*found)[i].x, (*found)[i].y)).norm();
    worst = std::max(worst, error);
    sum += error;
    ++count;
  }
  EXPECT_LT(worst, tolerance_px);
  EXPECT_LT(sum / std::max(1, count), mean_tolerance_px);
  return count;
}

TEST(BoardDetection, FindsEveryCornerWhereItIsAndInTheBoardsOrder) {
  // Upright, turned a little, upside down (OpenCV would number it from the other end) and
  // tilted: the corners come back at their true pixels, in the board's own order.
  for (const double roll : {0.0, 12.0, 180.0, -100.0}) {
    SCOPED_TRACE(roll);
    ExpectCornersAtTheirTruePixels(Photograph(roll, 20.0), 0.15);
  }
}

TEST(BoardDetection, ChArUcoCornersAreFoundAndIdentifiedWhereverTheBoardIs) {
  // A ChArUco corner is refined in a window that stays clear of the markers' edges (here 4 mm
  // from the corner, 5 px): smaller than a chessboard's, so a little less precise.
  const BoardSpec board = ParseBoardSpec("charuco:11x8@30/22");
  for (const double roll : {0.0, 180.0, -100.0}) {
    SCOPED_TRACE(roll);
    EXPECT_EQ(ExpectCornersAtTheirTruePixels(Photograph(roll, 20.0, board), 0.3, 0.12),
              board.corner_count());
  }
  // Partly out of view (a chessboard detector finds nothing here): the corners in view are
  // found, identified by their markers, at their true pixels; the others are NaN.
  const BoardPhoto edge = Photograph(8.0, 15.0, board, Vec3(-420, 150, 0));
  EXPECT_FALSE(DetectChessboard(edge.gray, BoardSpec{10, 7, 30.0}));
  const int partial = ExpectCornersAtTheirTruePixels(edge, 0.3, 0.12);
  EXPECT_GT(partial, 8);
  EXPECT_LT(partial, board.corner_count());
}

TEST(BoardDetection, ReportsABoardThatIsNotThere) {
  const BoardPhoto p = Photograph(0, 0);
  EXPECT_FALSE(DetectChessboard(p.gray, BoardSpec{9, 6, 30.0}));  // the wrong size
  EXPECT_FALSE(DetectChessboard(cv::Mat(480, 640, CV_8UC1, cv::Scalar(90)), p.board));
  // A chessboard has no markers; a ChArUco board of another dictionary has none of these.
  EXPECT_FALSE(DetectBoard(p.gray, ParseBoardSpec("charuco:11x8@30/22")));
  const BoardPhoto c = Photograph(0, 0, ParseBoardSpec("charuco:11x8@30/22"));
  EXPECT_FALSE(DetectBoard(c.gray, ParseBoardSpec("charuco:11x8@30/22:6x6_250")));
}

}  // namespace
}  // namespace lfcam
