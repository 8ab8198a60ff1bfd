// A plenoptic photograph as one lenslet image (ESLF): split into its views pixel for pixel, its
// block size found from the main lens's vignetting of every microlens, and imported as the same
// views in a folder are.
#include "lfcam/io/lenslet_image.h"

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"

namespace lfcam::lenslet_image_test {
namespace {

namespace fs = std::filesystem;

// n x n views of w x h noise (BGR), each darkened by its distance from the grid's centre as a
// main lens vignettes a plenoptic camera's outer views when `vignetted`; and the lenslet image
// interleaving them.
struct Lenslet {
  std::vector<cv::Mat> views;
  cv::Mat image;
};
Lenslet MakeLenslet(int n, int w, int h, bool vignetted) {
  Lenslet l;
  cv::RNG rng(5);
  cv::Mat scene(h, w + n, CV_8UC3);
  rng.fill(scene, cv::RNG::UNIFORM, 40, 220);
  l.image.create(h * n, w * n, CV_8UC3);
  const double c = 0.5 * (n - 1);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      cv::Mat view = scene(cv::Rect(b, 0, w, h)).clone();  // a little parallax
      if (vignetted) view *= std::max(0.0, 1.0 - std::hypot(a - c, b - c) / (c + 1.5));
      for (int i = 0; i < h; ++i)
        for (int j = 0; j < w; ++j)
          l.image.at<cv::Vec3b>(a + n * i, b + n * j) = view.at<cv::Vec3b>(i, j);
      l.views.push_back(view);
    }
  return l;
}

TEST(LensletImage, SplitsIntoItsViewsPixelForPixel) {
  const Lenslet l = MakeLenslet(7, 20, 12, false);
  const std::vector<cv::Mat> views = SplitLensletImage(l.image, 7);
  ASSERT_EQ(views.size(), 49u);
  for (std::size_t i = 0; i < views.size(); ++i)
    EXPECT_EQ(cv::norm(views[i], l.views[i], cv::NORM_INF), 0.0) << "view " << i;
  EXPECT_THROW(SplitLensletImage(l.image, 6), Error);
}

TEST(LensletImage, FindsItsBlockSizeFromTheVignetting) {
  // 7 x 7 blocks: found as 7, not 14 or 21 (which repeat the pattern) nor a size that mixes it.
  const LensletPeriod found = DetectLensletPeriod(MakeLenslet(7, 24, 18, true).image);
  EXPECT_EQ(found.views_per_side, 7) << found.strength;
  EXPECT_GT(found.strength, 0.3);
  EXPECT_EQ(DetectLensletPeriod(MakeLenslet(14, 12, 10, true).image).views_per_side, 14);
  // Without vignetting (views as bright as one another) nothing stands out: said, not guessed.
  EXPECT_EQ(DetectLensletPeriod(MakeLenslet(7, 24, 18, false).image).views_per_side, 0);
}

// `lfcam import FILE`: the light field is the one the same views in a folder give, sample for
// sample, with where the views came from said and recorded; an image whose block size is not
// found, or not given rightly, is refused naming it, and no temporary folder is left behind.
TEST(LensletImage, ImportsAsTheSameViewsInAFolderDo) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_lenslet_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "views");
  const int n = 5;
  const Lenslet l = MakeLenslet(n, 40, 32, true);
  ASSERT_TRUE(cv::imwrite((dir / "photo_eslf.png").string(), l.image));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      ASSERT_TRUE(
          cv::imwrite((dir / "views" / fmt::format("v_{:02d}_{:02d}.png", a + 1, b + 1)).string(),
                      l.views[std::size_t(a * n + b)]));
  const std::string flags = "--keep-axes --keep-dark-views --json --quiet";
  auto run = testing::Lfcam(fmt::format("import {} --out {} {}", (dir / "photo_eslf.png").string(),
                                        (dir / "l.lf").string(), flags));
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json summary = nlohmann::json::parse(run.output);
  EXPECT_EQ(summary["lenslet"]["views_per_side"], n);
  EXPECT_EQ(summary["lenslet"]["views_per_side_given"], false);
  EXPECT_NE(
      summary["notes"][0].get<std::string>().find("read as a lenslet image: 5 x 5 views of 40x32"),
      std::string::npos)
      << summary["notes"];
  run = testing::Lfcam(fmt::format("import {} --out {} {}", (dir / "views").string(),
                                   (dir / "f.lf").string(), flags));
  ASSERT_EQ(run.status, 0) << run.output;
  const LightField from_image = ReadLightField(dir / "l.lf"),
                   from_folder = ReadLightField(dir / "f.lf");
  ASSERT_EQ(from_image.dims().rows, n);
  ASSERT_EQ(from_image.view_bytes(), from_folder.view_bytes());
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      EXPECT_TRUE(std::equal(from_image.view_data(r, c),
                             from_image.view_data(r, c) + from_image.view_bytes(),
                             from_folder.view_data(r, c)))
          << "view " << r << ", " << c;
  EXPECT_EQ(from_image.metadata()["import"]["folder"], (dir / "photo_eslf.png").string());
  EXPECT_EQ(from_image.metadata()["import"]["lenslet"]["views_per_side"], n);
  // Refused: a block size that does not divide it, and one that cannot be found.
  run = testing::Lfcam(fmt::format("import {} --lenslet 3 --out {}",
                                   (dir / "photo_eslf.png").string(), (dir / "x.lf").string()));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("--lenslet 3: its 200x160 pixels are not blocks of 3x3"),
            std::string::npos)
      << run.output;
  run = testing::Lfcam(fmt::format("import {} --lenslet 5 --out {}", (dir / "views").string(),
                                   (dir / "x.lf").string()));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--lenslet: " + (dir / "views").string() + " is not one image"),
            std::string::npos)
      << run.output;
  ASSERT_TRUE(cv::imwrite((dir / "flat.png").string(), MakeLenslet(n, 40, 32, false).image));
  run = testing::Lfcam(
      fmt::format("import {} --out {}", (dir / "flat.png").string(), (dir / "x.lf").string()));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("not a lenslet image? --lenslet N"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "x.lf"));
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_EQ(
        entry.path().filename().string().rfind(fmt::format("lfcam_lenslet_{}_", ::getpid()), 0),
        std::string::npos)
        << entry.path();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam::lenslet_image_test
