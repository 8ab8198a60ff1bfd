#include "lfcam/calib/photometry.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <mutex>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/input_file.h"

namespace lfcam {

namespace {

struct SquareView {
  Vec3 value;  // linear RGB, mean over a patch inside the square
  double rho2;
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The world board's squares as camera `c` saw them: nullopt where a square's patch is not
// wholly inside the image.
std::vector<std::optional<SquareView>> ObserveSquares(const cv::Mat& bgr, int reduction,
                                                      const CalibratedCamera& c,
                                                      const BoardSpec& board) {
  const auto& lut = SrgbDecodeTable();
  const CameraIntrinsics& k = c.intrinsics;
  const Rigid3 camera_from_world = c.world_from_camera.inverse();
  const double half_diagonal2 = 0.25 * (double(k.width) * k.width + double(k.height) * k.height);
  std::vector<std::optional<SquareView>> out;
  for (int j = 0; j <= board.rows; ++j)
    for (int i = 0; i <= board.cols; ++i) {
      const double x = (i + 0.5) * board.square_mm, y = (j + 0.5) * board.square_mm;
      const auto center = k.Project(camera_from_world * Vec3(x, y, 0));
      const auto side = k.Project(camera_from_world * Vec3(x + 0.5 * board.square_mm, y, 0));
      if (!center || !side) {
        out.emplace_back();
        continue;
      }
      // A patch of half the square's width, well clear of its edges, in the reduced image.
      const double half = 0.25 * (*side - *center).norm() / reduction;
      const double cx = (center->x() + 0.5) / reduction - 0.5;
      const double cy = (center->y() + 0.5) / reduction - 0.5;
      const int x0 = int(std::ceil(cx - half)), x1 = int(std::floor(cx + half));
      const int y0 = int(std::ceil(cy - half)), y1 = int(std::floor(cy + half));
      if (x1 < x0 || y1 < y0 || x0 < 0 || y0 < 0 || x1 >= bgr.cols || y1 >= bgr.rows) {
        out.emplace_back();
        continue;
      }
      Vec3 sum = Vec3::Zero();
      for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px) {
          const cv::Vec3b b = bgr.at<cv::Vec3b>(py, px);
          sum += Vec3(lut[b[2]], lut[b[1]], lut[b[0]]);
        }
      const double dx = center->x() - k.cx, dy = center->y() - k.cy;
      out.push_back(SquareView{sum / double((x1 - x0 + 1) * (y1 - y0 + 1)),
                               (dx * dx + dy * dy) / half_diagonal2});
    }
  return out;
}

}  // namespace

PhotometryEstimate EstimatePhotometry(const std::filesystem::path& dir,
                                      const CaptureManifest& manifest,
                                      const CalibrationFile& calibration, const BoardSpec& board,
                                      const std::function<void()>& image_done) {
  const auto world = manifest.shots_of(ShotKind::kWorld);
  if (world.size() != 1) throw Error("photometry: the session needs exactly one world shot");
  const std::size_t n = calibration.cameras.size();
  std::vector<std::vector<std::optional<SquareView>>> seen(n);
  int reduction = 1;
  while (reduction < 8 && std::max(calibration.width, calibration.height) / reduction > 1400)
    reduction *= 2;
  std::mutex mutex;
  const auto& images = world[0]->images;
  tbb::parallel_for(std::size_t(0), images.size(), [&](std::size_t index) {
    const ShotImage& image = images[index];
    const std::size_t i = std::size_t(image.row * calibration.cols + image.col);
    const CalibratedCamera& c = calibration.cameras[i];
    if (c.calibrated) {
      try {
        const auto path = dir / image.file;
        const auto bytes = ReadFileBytes(path, kMaxEncodedImageBytes, "image file");
        const cv::Mat bgr =
            DecodeImageBytes(bytes, path.string(), ImageDecodeMode::kColour8, reduction);
        if (bgr.type() == CV_8UC3) seen[i] = ObserveSquares(bgr, reduction, c, board);
      } catch (const Error&) {
        // An unreadable world image: calibration has reported it; this camera is not corrected.
      }
    }
    if (image_done) {
      std::lock_guard lock(mutex);
      image_done();
    }
  });

  const std::size_t squares = std::size_t(board.cols + 1) * std::size_t(board.rows + 1);
  PhotometryEstimate estimate;
  estimate.cameras.assign(n, std::nullopt);
  std::vector<PhotometricCorrection> model(n);
  std::vector<Vec3> radiance(squares, Vec3::Zero());
  for (int iteration = 0; iteration < 6; ++iteration) {
    // Each square's radiance: the median over the cameras, as currently corrected.
    int compared = 0;
    for (std::size_t q = 0; q < squares; ++q) {
      for (int ch = 0; ch < 3; ++ch) {
        std::vector<double> values;
        for (std::size_t i = 0; i < n; ++i)
          if (!seen[i].empty() && seen[i][q])
            values.push_back(seen[i][q]->value[ch] /
                             (model[i].gain[ch] * (1 + model[i].vignetting * seen[i][q]->rho2)));
        radiance[q][ch] = values.size() >= 2 ? Median(values) : 0.0;
        if (ch == 0 && values.size() >= 2) ++compared;
      }
    }
    estimate.squares = compared;
    // Each camera: vignetting from the sum of the channels, then a gain per channel.
    for (std::size_t i = 0; i < n; ++i) {
      if (seen[i].empty()) continue;
      Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
      Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
      double rho_max2 = 0;
      for (std::size_t q = 0; q < squares; ++q) {
        if (!seen[i][q] || radiance[q].sum() <= 0) continue;
        const double l = radiance[q].sum(), o = seen[i][q]->value.sum(), r2 = seen[i][q]->rho2;
        const Eigen::Vector2d a(l, l * r2);  // o = g l + (g v) l r2
        normal += a * a.transpose();
        rhs += a * o;
        rho_max2 = std::max(rho_max2, r2);
      }
      if (std::abs(normal.determinant()) < 1e-12 * normal.squaredNorm()) continue;
      const Eigen::Vector2d x = normal.ldlt().solve(rhs);
      PhotometricCorrection& m = model[i];
      m.vignetting = x(0) > 0 ? std::clamp(x(1) / x(0), -0.9, 0.5) : 0.0;
      m.rho_max = std::sqrt(rho_max2);
      for (int ch = 0; ch < 3; ++ch) {
        double num = 0, den = 0;
        for (std::size_t q = 0; q < squares; ++q) {
          if (!seen[i][q]) continue;
          const double predicted = radiance[q][ch] * (1 + m.vignetting * seen[i][q]->rho2);
          num += seen[i][q]->value[ch] * predicted;
          den += predicted * predicted;
        }
        if (den > 0) m.gain[ch] = num / den;
      }
    }
    // The array's median camera keeps its colour.
    for (int ch = 0; ch < 3; ++ch) {
      std::vector<double> gains;
      for (std::size_t i = 0; i < n; ++i)
        if (!seen[i].empty()) gains.push_back(model[i].gain[ch]);
      const double median = Median(gains);
      if (median > 0)
        for (auto& m : model) m.gain[ch] /= median;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!seen[i].empty() && model[i].gain.minCoeff() > 0) estimate.cameras[i] = model[i];
  return estimate;
}

void AddPhotometryToCalibration(nlohmann::json& calibration, const PhotometryEstimate& e) {
  auto& cameras = calibration.at("cameras");
  int corrected = 0;
  for (std::size_t i = 0; i < e.cameras.size() && i < cameras.size(); ++i)
    if (e.cameras[i]) {
      cameras[i]["photometry"] = PhotometryToJson(*e.cameras[i]);
      ++corrected;
    }
  calibration["photometry"] = {
      {"model",
       "gain[c] * (1 + vignetting * rho^2), rho from the principal point over the "
       "half-diagonal"},
      {"source", "world board squares, median over the cameras"},
      {"squares_compared", e.squares},
      {"cameras", corrected}};
}

}  // namespace lfcam
