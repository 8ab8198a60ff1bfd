#include "lfcam/calib/charuco.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <random>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

TEST(Charuco, SpecsParseInSquaresAndRoundTrip) {
  const BoardSpec b = ParseBoardSpec("charuco:11x8@30/22");
  EXPECT_TRUE(b.charuco());
  EXPECT_EQ(b.cols, 10);  // inner corners
  EXPECT_EQ(b.rows, 7);
  EXPECT_DOUBLE_EQ(b.square_mm, 30);
  EXPECT_DOUBLE_EQ(b.marker_mm, 22);
  EXPECT_EQ(b.dictionary, "5X5_100");
  EXPECT_EQ(b.width_mm(), 330);
  EXPECT_EQ(ParseBoardSpec(b.spec()), b);
  EXPECT_EQ(BoardFromJson(BoardToJson(b), "board"), b);
  EXPECT_EQ(BoardToJson(b)["squares"], nlohmann::json::array({11, 8}));
  // Both counts even is fine for ChArUco (the markers say which way up it is).
  EXPECT_EQ(ParseBoardSpec("charuco:6x6@40/30:4x4_50").dictionary, "4X4_50");
  for (const char* text : {"charuco:11x8@30", "charuco:11x8@30/", "charuco:11x8@30/29",
                           "charuco:11x8@30/5", "charuco:11x8@30/22:5X5_99", "charuco:2x8@30/22",
                           "charuco:11x8@30/22:", "charuco:", "charuco:21x21@30/22:4X4_100"})
    EXPECT_THROW(ParseBoardSpec(text), Error) << text;
  EXPECT_NE(testing::ErrorOf([] {
              ParseBoardSpec("charuco:21x21@30/22:4X4_100");
            }).find("need 220 markers; dictionary 4X4_100 has 100"),
            std::string::npos);
  nlohmann::json j = BoardToJson(b);
  j["dictionary"] = "ARUCO_ORIGINAL";
  EXPECT_THROW(BoardFromJson(j, "board"), Error);
}

TEST(Charuco, LayoutIsTheBoardOpenCvDraws) {
  // 4X4 markers of 6 mm in 12 mm squares: 1 mm cells, so at 4 px/mm every cell edge falls on
  // a pixel edge of OpenCV's drawing (whose top row is the board's top, largest y).
  const BoardSpec b = ParseBoardSpec("charuco:5x7@12/6:4x4_50");
  const CharucoLayout layout = MakeCharucoLayout(b);
  EXPECT_EQ(layout.markers.size(), 17u);
  const int k = 4;
  cv::Mat drawn;
  cv::aruco::CharucoBoard::create(5, 7, 12.f, 6.f,
                                  cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50))
      ->draw(cv::Size(int(b.width_mm()) * k, int(b.height_mm()) * k), drawn, 0, 1);
  int mismatched = 0;
  for (int r = 0; r < drawn.rows; ++r)
    for (int c = 0; c < drawn.cols; ++c) {
      const double x = (c + 0.5) / k, y = b.height_mm() - (r + 0.5) / k;
      const bool black = CharucoBlackAreaFraction(layout, x, x, y, y) > 0.5;
      mismatched += black != (drawn.at<uchar>(r, c) < 128);
    }
  EXPECT_LT(mismatched, drawn.rows * drawn.cols / 1000) << mismatched;
}

TEST(Charuco, BlackAreaIsTheExactShareUnderTheFootprint) {
  const BoardSpec b = ParseBoardSpec("charuco:11x8@30/22");
  const CharucoLayout layout = MakeCharucoLayout(b);
  auto brute = [&](double x0, double x1, double y0, double y1) {
    const int n = 300;
    double black = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = x0 + (i + 0.5) / n * (x1 - x0), y = y0 + (j + 0.5) / n * (y1 - y0);
        black += CharucoBlackAreaFraction(layout, x, x, y, y);
      }
    return black / (n * n);
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-30, 340), size(0.3, 25);
  for (int trial = 0; trial < 30; ++trial) {
    const double x0 = pos(rng), y0 = pos(rng) * 0.75, w = size(rng), h = size(rng);
    EXPECT_NEAR(CharucoBlackAreaFraction(layout, x0, x0 + w, y0, y0 + h),
                brute(x0, x0 + w, y0, y0 + h), 6e-3)
        << x0 << " " << y0 << " " << w << " " << h;
  }
  // Outside the squared area: the white margin.
  EXPECT_EQ(CharucoBlackAreaFraction(layout, -20, -10, 5, 10), 0.0);
  EXPECT_EQ(CharucoBlackAreaFraction(layout, -5, -5, 5, 5), 0.0);
}

}  // namespace
}  // namespace lfcam
