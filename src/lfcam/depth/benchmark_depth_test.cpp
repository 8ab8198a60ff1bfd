// The depth estimate on a scene of the HCI 4D Light Field Benchmark (../shared/data/hci-antinous,
// when present), scored as the benchmark scores it: BadPix(0.07) and MSE x 100 over the centre
// view less a 15-pixel border (docs/depth.md, "On the field's benchmark").
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/depth/disparity_map.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::benchmark_depth_test {
namespace {

namespace fs = std::filesystem;

TEST(DepthOnTheBenchmark, AntinousScoresWhatDocsDepthSays) {
  const fs::path hci = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/hci-antinous";
  if (!fs::is_directory(hci)) GTEST_SKIP() << hci << " is not here (../shared/data)";
  const ImportedGrid grid = ScanGridFolder(hci, false);
  const LightField lf = ImportRectifiedViews(hci, grid, ResolveRectifiedGeometry(grid, {}));
  const auto start = std::chrono::steady_clock::now();
  const DepthMap map = EstimateDepth(lf, 4, 4, {});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const cv::Mat d = DisparityOf(lf, map);
  // OpenCV reads the PFM upright (its top row first); the map's rows count up.
  const cv::Mat truth = cv::imread((hci / "gt_disp_lowres.pfm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(truth.size(), cv::Size(512, 512));
  const int border = 15;
  int n = 0, bad = 0;
  double squared = 0;
  for (int y = border; y < 512 - border; ++y)
    for (int x = border; x < 512 - border; ++x) {
      const double e = d.at<float>(511 - y, x) - truth.at<float>(y, x);
      ++n;
      bad += !(std::abs(e) <= 0.07);
      squared += std::isfinite(e) ? e * e : 100.0;
    }
  const double badpix = 100.0 * bad / n, mse100 = 100.0 * squared / n;
  std::cout << fmt::format(
      "[depth benchmark] antinous: BadPix0.07 {:.2f}%, MSEx100 {:.2f}, {:.1f} s\n", badpix, mse100,
      seconds);
  // Floors a little above what was measured (docs/depth.md: 3.15% and 4.9; with the colour and
  // gradient terms counting alike, as at wide baselines, 5.28% and 6.4, which both floors fail;
  // without the slant prior then 5.38%, without the wider plane fit 5.55%, without the local
  // planes 6.32%).
  EXPECT_LE(badpix, 3.25);
  EXPECT_LE(mse100, 5.2);
}

}  // namespace
}  // namespace lfcam::benchmark_depth_test
