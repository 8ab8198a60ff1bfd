#include "lfcam/calib/intrinsics_calibration.h"

#include <fmt/format.h>

#include <opencv2/calib3d.hpp>

#include "lfcam/calib/board_detection.h"
#include "lfcam/calib/bundle_adjustment.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// The board points and image points of the corners found in one view (all of a chessboard's,
// those of a partial ChArUco view).
struct ViewPoints {
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
};

ViewPoints FoundPoints(const BoardSpec& board, const std::vector<cv::Point2f>& corners) {
  const auto points = board.corners();
  if (corners.size() != points.size())
    throw Error(fmt::format("a view has {} corners; board {} has {}", corners.size(), board.spec(),
                            points.size()));
  ViewPoints v;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (CornerFound(corners[i])) {
      v.object.emplace_back(float(points[i].x()), float(points[i].y()), 0.f);
      v.image.push_back(corners[i]);
    }
  return v;
}

Rigid3 FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat r64, t64;
  rvec.convertTo(r64, CV_64F);
  tvec.convertTo(t64, CV_64F);
  return {RotationFromAngleAxis(Vec3(r64.at<double>(0), r64.at<double>(1), r64.at<double>(2))),
          Vec3(t64.at<double>(0), t64.at<double>(1), t64.at<double>(2))};
}

cv::Mat DistortionMat(const Distortion& d) {
  const auto c = d.opencv();
  return (cv::Mat_<double>(1, 5) << c[0], c[1], c[2], c[3], c[4]);
}

cv::Mat KMat(const CameraIntrinsics& k) {
  return (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

}  // namespace

SingleCameraCalibration CalibrateSingleCamera(const std::vector<std::vector<cv::Point2f>>& views,
                                              const BoardSpec& board, int width, int height) {
  if (views.size() < 3)
    throw Error(
        fmt::format("intrinsics need the board in at least 3 views, found in {}", views.size()));
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> images;
  for (const auto& view : views) {
    ViewPoints v = FoundPoints(board, view);
    objects.push_back(std::move(v.object));
    images.push_back(std::move(v.image));
  }
  cv::Mat K, dist;
  std::vector<cv::Mat> rvecs, tvecs;
  const double rms = cv::calibrateCamera(
      objects, images, cv::Size(width, height), K, dist, rvecs, tvecs, 0,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
  SingleCameraCalibration out;
  out.rms_px = rms;
  CameraIntrinsics& c = out.intrinsics;
  c.width = width;
  c.height = height;
  c.fx = K.at<double>(0, 0);
  c.fy = K.at<double>(1, 1);
  c.cx = K.at<double>(0, 2);
  c.cy = K.at<double>(1, 2);
  c.distortion = {dist.at<double>(0), dist.at<double>(1), dist.at<double>(2), dist.at<double>(3),
                  dist.at<double>(4)};
  const auto points = board.corners();
  for (std::size_t i = 0; i < views.size(); ++i) {
    out.camera_from_board.push_back(FromRvecTvec(rvecs[i], tvecs[i]));
    out.view_rms_px.push_back(ReprojectionRms(c, out.camera_from_board.back(), points, views[i]));
  }
  return out;
}

Rigid3 BoardPose(const CameraIntrinsics& intrinsics, const BoardSpec& board,
                 const std::vector<cv::Point2f>& corners) {
  const ViewPoints v = FoundPoints(board, corners);
  if (v.image.size() < 4)
    throw Error(fmt::format("the board's pose needs at least 4 corners, found {}", v.image.size()));
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(v.object, v.image, KMat(intrinsics), DistortionMat(intrinsics.distortion), rvec,
                    tvec, false, cv::SOLVEPNP_ITERATIVE))
    throw Error("the board's pose could not be found (solvePnP failed)");
  return FromRvecTvec(rvec, tvec);
}

}  // namespace lfcam
