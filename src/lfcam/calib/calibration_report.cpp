#include "lfcam/calib/calibration_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace lfcam {
namespace {

const cv::Scalar kText(235, 235, 235);
const cv::Scalar kDim(150, 150, 150);

struct Panel {
  std::string title, unit;
  double scale_floor;  // the scale reaches at least this: a good array stays dark
  std::function<double(const CameraCalibration&)> value;
};

void DrawPanel(cv::Mat& canvas, cv::Rect area, const ArrayCalibration& a, const Panel& panel) {
  const int cell = std::max(8, std::min((area.width - 20) / a.cols, (area.height - 90) / a.rows));
  const cv::Point origin(area.x + (area.width - cell * a.cols) / 2, area.y + 40);
  cv::putText(canvas, panel.title, {area.x + 10, area.y + 26}, cv::FONT_HERSHEY_SIMPLEX, 0.6, kText,
              1, cv::LINE_AA);
  double lo = 1e300, hi = -1e300;
  std::vector<const CameraCalibration*> calibrated;
  for (const auto& c : a.cameras)
    if (c.calibrated) {
      lo = std::min(lo, panel.value(c));
      hi = std::max(hi, panel.value(c));
      calibrated.push_back(&c);
    }
  if (calibrated.empty()) hi = 0;
  const double worst = hi;
  // From zero to at least the floor: a uniformly good array looks uniformly dark, a bad camera
  // stands out bright.
  lo = 0;
  hi = std::max(hi, panel.scale_floor);
  const double span = hi > lo ? hi - lo : 1.0;
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i) = std::uint8_t(i);
  cv::Mat colors;
  cv::applyColorMap(ramp, colors, cv::COLORMAP_VIRIDIS);  // BGR
  auto color_of = [&](double v) {
    const auto b = colors.at<cv::Vec3b>(std::clamp(int((v - lo) / span * 255.0), 0, 255));
    return cv::Scalar(b[2], b[1], b[0]);  // the canvas is RGB
  };
  for (const auto& c : a.cameras) {
    // Row 0 at the bottom, column 0 at the left: the array seen from behind.
    const cv::Rect r(origin.x + c.col * cell, origin.y + (a.rows - 1 - c.row) * cell, cell - 2,
                     cell - 2);
    if (c.calibrated) {
      cv::rectangle(canvas, r, color_of(panel.value(c)), cv::FILLED);
    } else {
      cv::rectangle(canvas, r, cv::Scalar(70, 70, 70), cv::FILLED);
      cv::line(canvas, r.tl(), r.br(), cv::Scalar(230, 60, 60), 2, cv::LINE_AA);
      cv::line(canvas, {r.x, r.y + r.height}, {r.x + r.width, r.y}, cv::Scalar(230, 60, 60), 2,
               cv::LINE_AA);
    }
  }
  // The three worst, labelled in their cells and listed below.
  std::sort(calibrated.begin(), calibrated.end(),
            [&](auto* x, auto* y) { return panel.value(*x) > panel.value(*y); });
  const int bottom = origin.y + a.rows * cell;
  cv::putText(
      canvas,
      fmt::format("scale 0 .. {:.3g} {} (dark to bright); worst {:.3g}", hi, panel.unit, worst),
      {area.x + 10, bottom + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kDim, 1, cv::LINE_AA);
  for (std::size_t i = 0; i < std::min<std::size_t>(3, calibrated.size()); ++i) {
    const auto& c = *calibrated[i];
    const cv::Point center(origin.x + c.col * cell + cell / 2 - 5,
                           origin.y + (a.rows - 1 - c.row) * cell + cell / 2 + 5);
    cv::putText(canvas, std::to_string(i + 1), center, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(255, 80, 80), 2, cv::LINE_AA);
    cv::putText(canvas,
                fmt::format("{}. camera ({}, {}): {:.3g} {}", i + 1, c.row, c.col, panel.value(c),
                            panel.unit),
                {area.x + 10, bottom + 40 + int(i) * 18}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kText, 1,
                cv::LINE_AA);
  }
}

}  // namespace

cv::Mat DrawCalibrationReport(const ArrayCalibration& a) {
  const int panel_w = 420, panel_h = 520;
  cv::Mat canvas(panel_h + 50, 2 * panel_w, CV_8UC3, cv::Scalar(24, 24, 28));
  const auto& ba = a.bundle_adjustment;
  cv::putText(
      canvas,
      fmt::format("{} of {} cameras calibrated, reprojection RMS {:.3f} px, grid fit {:.2f} mm RMS",
                  a.calibrated_count(), a.cameras.size(), ba.final_rms_px, a.fit.grid_rms_mm),
      {10, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.55, kText, 1, cv::LINE_AA);
  DrawPanel(canvas, {0, 40, panel_w, panel_h}, a,
            {"reprojection error", "px", 0.5, [](const CameraCalibration& c) { return c.rms_px; }});
  DrawPanel(canvas, {panel_w, 40, panel_w, panel_h}, a,
            {"distance from the ideal grid", "mm", 2.0,
             [](const CameraCalibration& c) { return c.distance_to_ideal_mm; }});
  return canvas;
}

}  // namespace lfcam
