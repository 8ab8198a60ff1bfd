#include "lfcam/session/session.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

CaptureManifest Example() {
  CaptureManifest m;
  m.rows = 2;
  m.cols = 3;
  m.sensor_width = 640;
  m.sensor_height = 480;
  m.intrinsics_board = ParseBoardSpec("10x7@30");
  m.world_board = ParseBoardSpec("11x10@50");
  Shot shot{ShotKind::kIntrinsics, "shot_00", {}};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c)
      shot.images.push_back({r, c, "calib/intrinsics/shot_00/" + CameraFileName(r, c)});
  m.shots.push_back(shot);
  m.shots.push_back({ShotKind::kWorld, "world", {{0, 0, "calib/world/cam_00_00.jpg"}}});
  return m;
}

TEST(CaptureSession, ManifestRoundTrip) {
  const CaptureManifest m = Example();
  const CaptureManifest back = ManifestFromJson(ManifestToJson(m), "manifest");
  EXPECT_EQ(back.rows, 2);
  EXPECT_EQ(back.cols, 3);
  EXPECT_EQ(back.sensor_width, 640);
  EXPECT_EQ(*back.intrinsics_board, *m.intrinsics_board);
  ASSERT_EQ(back.shots.size(), 2u);
  EXPECT_EQ(back.shots_of(ShotKind::kWorld).size(), 1u);
  EXPECT_EQ(back.shots[0].images[4].file, "calib/intrinsics/shot_00/cam_01_01.jpg");
  EXPECT_EQ(CameraFileName(3, 12), "cam_03_12.jpg");
}

TEST(CaptureSession, RefusesNamesOutsideTheSessionAndBadEntries) {
  auto with_file = [](const std::string& file) {
    nlohmann::json j = ManifestToJson(Example());
    j["shots"][1]["images"][0]["file"] = file;
    return j;
  };
  for (const char* bad :
       {"../x.jpg", "/etc/passwd", "a/../../b.jpg", "", "a//b.jpg", "./a.jpg", "a\\b.jpg"})
    EXPECT_THROW(ManifestFromJson(with_file(bad), "m"), Error) << bad;
  nlohmann::json j = ManifestToJson(Example());
  j["shots"][0]["images"][1]["col"] = 0;  // camera (0, 0) twice
  EXPECT_NE(testing::ErrorOf([&] { ManifestFromJson(j, "m"); }).find("appears twice"),
            std::string::npos);
  j = ManifestToJson(Example());
  j["shots"][0]["images"][1]["row"] = 5;  // outside the 2x3 grid
  EXPECT_THROW(ManifestFromJson(j, "m"), Error);
  j = ManifestToJson(Example());
  j["shots"][0]["kind"] = "flat";
  EXPECT_THROW(ManifestFromJson(j, "m"), Error);
  j = ManifestToJson(Example());
  j["version"] = 99;
  EXPECT_THROW(ManifestFromJson(j, "m"), Error);
  j = ManifestToJson(Example());
  j["boards"]["world"]["inner_corners"] = {10, 10};
  EXPECT_THROW(ManifestFromJson(j, "m"), Error);
}

TEST(CaptureSession, ReadManifestNamesTheFile) {
  const auto dir = testing::MakeScratchDir("session");
  EXPECT_NE(testing::ErrorOf([&] { ReadManifest(dir / "none"); }).find("none"), std::string::npos);
  std::ofstream(dir / kManifestName) << "{\"format\": \"lfcam-capture\", \"version\": 1";
  EXPECT_NE(testing::ErrorOf([&] { ReadManifest(dir); }).find("manifest.json"), std::string::npos);
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

TEST(CaptureSession, WithoutAManifestTheLayoutIsTheManifest) {
  const auto dir = testing::MakeScratchDir("layout");
  const cv::Mat image(30, 40, CV_8UC3, cv::Scalar(10, 20, 30));
  for (const char* folder :
       {"calib/intrinsics/shot_00", "calib/intrinsics/shot_01", "calib/world", "scene"})
    std::filesystem::create_directories(dir / folder);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      cv::imwrite((dir / "calib/intrinsics/shot_00" / CameraFileName(r, c)).string(), image);
      cv::imwrite((dir / "scene" / CameraFileName(r, c)).string(), image);
    }
  cv::imwrite((dir / "calib/intrinsics/shot_01/cam_01_02.jpg").string(), image);
  cv::imwrite((dir / "calib/world/cam_00_00.jpg").string(), image);
  std::ofstream(dir / "scene/notes.txt") << "not an image";
  const CaptureManifest m = ReadManifest(dir);
  EXPECT_EQ(m.rows, 2);
  EXPECT_EQ(m.cols, 3);
  EXPECT_EQ(m.sensor_width, 40);
  EXPECT_EQ(m.sensor_height, 30);
  ASSERT_EQ(m.shots_of(ShotKind::kIntrinsics).size(), 2u);
  EXPECT_EQ(m.shots_of(ShotKind::kIntrinsics)[1]->images.size(), 1u);
  EXPECT_EQ(m.shots_of(ShotKind::kScene)[0]->images.size(), 6u);
  EXPECT_FALSE(m.intrinsics_board);
  const auto empty = testing::MakeScratchDir("layout-empty");
  EXPECT_NE(testing::ErrorOf([&] { ReadManifest(empty); }).find("capture layout"),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
