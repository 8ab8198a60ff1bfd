#include "lfcam/depth/depth_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/test_support.h"
#include "lfcam/depth/depth_set.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

DepthMap Ramp(int row, int col, int n_s = 40, int n_t = 30) {
  DepthMap map;
  map.row = row;
  map.col = col;
  map.range = {3000, 7000};
  map.depth.create(n_t, n_s, CV_32FC1);
  map.confidence.create(n_t, n_s, CV_32FC1);
  for (int l = 0; l < n_t; ++l)
    for (int k = 0; k < n_s; ++k) {
      map.depth.at<float>(l, k) = float(3000 + 100 * k + 7 * l);
      map.confidence.at<float>(l, k) = float(l) / (n_t - 1);
    }
  map.depth.at<float>(2, 3) = NAN;  // unknown
  return map;
}

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(DepthMapFile, RoundTripsDepthRangeViewAndConfidence) {
  const fs::path dir = testing::MakeScratchDir("lfcam_depth_map");
  const DepthMap map = Ramp(2, 5);
  WriteDepthFiles(dir / "d.png", map);
  ASSERT_TRUE(fs::exists(dir / "d.confidence.png"));
  ASSERT_TRUE(fs::exists(dir / "d.preview.png"));
  DepthMap back = ReadDepthPng(dir / "d.png");
  ReadConfidencePng(dir / "d.confidence.png", back);
  EXPECT_EQ(back.row, 2);
  EXPECT_EQ(back.col, 5);
  EXPECT_DOUBLE_EQ(back.range.near_mm, 3000);
  EXPECT_DOUBLE_EQ(back.range.far_mm, 7000);
  ASSERT_EQ(back.depth.size(), map.depth.size());
  const double step = 4000.0 / 65534.0;  // one code
  for (int l = 0; l < map.n_t(); ++l)
    for (int k = 0; k < map.n_s(); ++k) {
      const float a = map.depth.at<float>(l, k), b = back.depth.at<float>(l, k);
      if (std::isnan(a)) {
        EXPECT_TRUE(std::isnan(b));
        continue;
      }
      ASSERT_NEAR(b, std::clamp(a, 3000.0f, 7000.0f), step) << k << "," << l;
      ASSERT_NEAR(back.confidence.at<float>(l, k), map.confidence.at<float>(l, k), 0.5 / 255);
    }
  // On disk the map is upright: the top row of the PNG is the highest st row.
  const cv::Mat raw = cv::imread((dir / "d.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  EXPECT_LT(raw.at<std::uint16_t>(0, 0), raw.at<std::uint16_t>(0, 1));             // deeper along k
  EXPECT_GT(raw.at<std::uint16_t>(0, 0), raw.at<std::uint16_t>(raw.rows - 1, 0));  // and up l
  // The preview is an RGB picture with a scale bar beside the map.
  const cv::Mat preview = DepthPreview(map);
  EXPECT_EQ(preview.type(), CV_8UC3);
  EXPECT_EQ(preview.rows, map.n_t());
  EXPECT_GT(preview.cols, map.n_s());
}

// The scale bar runs in inverse depth as the map's colours do, so that over a range of depths
// 40 times apart (a real scene's: 4 m to 164 m) each label sits beside its colour in the map.
TEST(DepthMapFile, TheScaleBarShowsEachLabelsDepthInTheMapsColour) {
  DepthMap map = Ramp(1, 1, 40, 41);
  map.range = {4100, 164100};
  const double q_near = 1.0 / map.range.near_mm, q_far = 1.0 / map.range.far_mm;
  // Row l of the map (drawn upside down: image row n_t - 1 - l) at the depth of the label a
  // fraction l / 40 of the way from near to far in 1/D.
  for (int l = 0; l < map.n_t(); ++l)
    for (int k = 0; k < map.n_s(); ++k)
      map.depth.at<float>(l, k) = float(1.0 / (q_near + (q_far - q_near) * l / 40.0));
  const cv::Mat preview = DepthPreview(map);
  // The bar: the first column right of the map whose colour is not the sheet's white.
  int bar = map.n_s();
  while (bar < preview.cols && preview.at<cv::Vec3b>(20, bar) == cv::Vec3b(255, 255, 255)) ++bar;
  ASSERT_LT(bar, preview.cols);
  for (int i = 0; i <= 4; ++i) {
    const int y = (map.n_t() - 1) * i / 4;       // the bar's row of label i
    const int map_row = map.n_t() - 1 - 10 * i;  // the map's image row at that label's depth
    const cv::Vec3b in_bar = preview.at<cv::Vec3b>(y, bar),
                    in_map = preview.at<cv::Vec3b>(map_row, 5);
    EXPECT_LE(cv::norm(cv::Vec3i(in_bar) - cv::Vec3i(in_map), cv::NORM_INF), 8)
        << "label " << i << ": bar " << in_bar << ", map " << in_map;
  }
}

// A light field imported without a metric scale (lengths in units of the cameras' spacing)
// gets a scale in those units, not in metres; the files say which.
TEST(DepthMapFile, LabelsItsScaleInTheLightFieldsLengthUnit) {
  DepthMap map = Ramp(1, 1);
  map.range = {48, 105};
  const cv::Mat metric = DepthPreview(map), units = DepthPreview(map, "units");
  const cv::Rect picture(0, 0, map.n_s(), map.n_t());
  EXPECT_EQ(cv::norm(metric(picture), units(picture), cv::NORM_INF), 0.0);  // the same map
  EXPECT_GT(units.cols, metric.cols);  // "105 units" is wider than "0.10 m"
  const fs::path dir = testing::MakeScratchDir("lfcam_depth_units");
  const LightFieldDims dims{3, 3, 40, 30};
  DepthSet set(dims);
  set.set(map);
  WriteDepthSet(dir / "set", set, "test.lf", "units");
  const auto text = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_NE(text(dir / "set" / "depth.json").find("\"length_unit\": \"units\""), std::string::npos);
  EXPECT_NE(text(dir / "set" / "depth_01_01.png").find("\"length_unit\":\"units\""),
            std::string::npos);
  const cv::Mat preview = cv::imread((dir / "set" / "preview.png").string());
  EXPECT_EQ(preview.cols, units.cols);
}

TEST(DepthMapFile, RefusesWhatIsNotADepthMapNamingTheFile) {
  const fs::path dir = testing::MakeScratchDir("lfcam_depth_bad");
  cv::imwrite((dir / "plain.png").string(), cv::Mat(8, 8, CV_16UC1, cv::Scalar(5)));
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthPng(dir / "plain.png"); }).find("plain.png"),
            std::string::npos);
  const std::string good = EncodeDepthPng(Ramp(0, 0));
  WriteBytes(dir / "cut.png", good.substr(0, good.size() / 2));
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthPng(dir / "cut.png"); }).find("cut.png"),
            std::string::npos);
  WriteBytes(dir / "missing.png", "");
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthPng(dir / "nothere.png"); }), "");
  // Metadata that lies about the range.
  std::string bad = good;
  const auto at = bad.find("\"far_mm\":7000");
  ASSERT_NE(at, std::string::npos);
  bad.replace(at, 13, "\"far_mm\":1000");  // same length: the CRC is now wrong, the text is read
  WriteBytes(dir / "range.png", bad);
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthPng(dir / "range.png"); }), "");
  DepthMap map = Ramp(0, 0);
  EXPECT_NE(testing::ErrorOf([&] { ReadConfidencePng(dir / "plain.png", map); }), "");
}

TEST(DepthSetFolder, RoundTripsAndRefusesAnotherLightFieldsMaps) {
  const fs::path dir = testing::MakeScratchDir("lfcam_depth_set");
  const LightFieldDims dims{2, 3, 40, 30};
  DepthSet set(dims);
  set.set(Ramp(0, 0));
  set.set(Ramp(1, 2));
  EXPECT_EQ(set.count(), 2);
  EXPECT_THROW(set.set(Ramp(0, 1, 41, 30)), Error);  // wrong size
  EXPECT_THROW(set.set(Ramp(2, 0)), Error);          // outside the grid
  WriteDepthSet(dir / "set", set, "test.lf");
  Slab slab;
  slab.uv.rows = 2;
  slab.uv.cols = 3;
  const LightField lf(dims, SampleType::kSrgb8, slab);
  const DepthSet back = ReadDepthSet(dir / "set", lf);
  EXPECT_EQ(back.count(), 2);
  EXPECT_TRUE(back.has(1, 2));
  EXPECT_FALSE(back.has(0, 1));
  EXPECT_NEAR(back.at(1, 2).depth.at<float>(3, 4), 3000 + 400 + 21, 0.1);
  EXPECT_THROW(back.at(0, 1), Error);
  const LightField other({2, 3, 40, 31}, SampleType::kSrgb8, slab);
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthSet(dir / "set", other); }).find("depth.json"),
            std::string::npos);
  // A view file that escapes the folder is refused.
  WriteBytes(dir / "set" / "depth.json",
             R"({"format": "lfcam-depth-set", "version": 1, "rows": 2, "cols": 3, "n_s": 40,
                 "n_t": 30, "views": [{"row": 0, "col": 0, "file": "../x.png"}]})");
  EXPECT_NE(testing::ErrorOf([&] { ReadDepthSet(dir / "set", lf); }).find("plain name"),
            std::string::npos);
}

TEST(DepthSetFolder, ReadsTheDepthsAloneForRenderersAndNamesTheFirstBadFileWhateverTheThreads) {
  const fs::path dir = testing::MakeScratchDir("lfcam_depth_set_read");
  const LightFieldDims dims{3, 4, 40, 30};
  DepthSet set(dims);
  for (int r = 0; r < dims.rows; ++r)
    for (int c = 0; c < dims.cols; ++c) set.set(Ramp(r, c));
  WriteDepthSet(dir / "set", set, "test.lf");
  Slab slab;
  slab.uv.rows = dims.rows;
  slab.uv.cols = dims.cols;
  const LightField lf(dims, SampleType::kSrgb8, slab);
  const DepthSet both = ReadDepthSet(dir / "set", lf);
  const DepthSet depths = ReadDepthSet(dir / "set", lf, DepthsForRendering());
  ASSERT_EQ(both.count(), 12);
  ASSERT_EQ(depths.count(), 12);
  for (int r = 0; r < dims.rows; ++r)
    for (int c = 0; c < dims.cols; ++c) {
      const DepthMap& a = both.at(r, c);
      const DepthMap& b = depths.at(r, c);
      ASSERT_TRUE(a.depth.isContinuous() && b.depth.isContinuous());
      EXPECT_EQ(std::memcmp(a.depth.data, b.depth.data, a.depth.total() * sizeof(float)), 0)
          << r << ", " << c;  // the same bits, the unknown sample's NaN too
      EXPECT_TRUE(std::isnan(b.depth.at<float>(2, 3)));
      EXPECT_NEAR(b.depth.at<float>(29, 30), 3000 + 3000 + 7 * 29, 0.1);
      ASSERT_FALSE(a.confidence.empty());
      EXPECT_NEAR(a.confidence.at<float>(29, 0), 1.0, 1.0 / 255);
      EXPECT_TRUE(b.confidence.empty());  // not read
    }
  // Two views' files broken: the error names the first in depth.json's order, every time.
  const std::string cut = EncodeDepthPng(Ramp(2, 3));
  WriteBytes(dir / "set" / DepthFileName(2, 3), cut.substr(0, cut.size() / 2));
  WriteBytes(dir / "set" / DepthFileName(1, 1), EncodeDepthPng(Ramp(0, 2)));  // another view's
  for (int i = 0; i < 5; ++i) {
    const std::string error = testing::ErrorOf([&] { ReadDepthSet(dir / "set", lf); });
    EXPECT_NE(error.find(DepthFileName(1, 1)), std::string::npos) << error;
    EXPECT_NE(error.find("holds view (0, 2), the index says (1, 1)"), std::string::npos) << error;
  }
  // A frame's views alone: the others' files are not opened.
  std::vector<bool> views(12, false);
  views[0] = views[2] = views[6] = true;  // (0, 0), (0, 2), (1, 2)
  const DepthSet some = ReadDepthSet(dir / "set", lf, DepthsForRendering(views));
  EXPECT_EQ(some.count(), 3);
  EXPECT_TRUE(some.has(1, 2));
  EXPECT_FALSE(some.has(1, 1));
  views[5] = true;  // (1, 1), the broken one
  EXPECT_NE(testing::ErrorOf([&] {
              ReadDepthSet(dir / "set", lf, DepthsForRendering(views));
            }).find(DepthFileName(1, 1)),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
