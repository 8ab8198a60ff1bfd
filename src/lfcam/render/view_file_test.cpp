// The view file: what the viewer saves beside a screenshot and `render --camera` reads back.
#include "lfcam/render/view_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

TEST(ViewFile, RoundTripsEveryParameter) {
  const auto dir = testing::MakeScratchDir("lfcam_view_file");
  ViewSettings v;
  v.camera.width = 321;
  v.camera.height = 123;
  v.camera.eye = Vec3(1.5, -2.25, 3600.125);
  v.camera.look_at = Vec3(10, 20, -30);
  v.camera.up = Vec3(0.1, 1, 0);
  v.camera.focal_length_mm = 444.5;
  v.camera.focus_distance_mm = 3912.75;
  v.camera.aperture_mm = 96;
  v.camera.lens_rate = 9;
  v.camera.breathing = false;
  v.integrator = Integrator::kCameras;
  v.interpolation = Interpolation::kFocalPlane;
  v.light_field = "paper.lf";
  const std::string path = (dir / "v.json").string();
  WriteViewFile(path, v);
  const ViewSettings r = ReadViewFile(path);
  EXPECT_EQ(r.camera.width, 321);
  EXPECT_EQ(r.camera.height, 123);
  EXPECT_EQ(r.camera.eye, v.camera.eye);
  EXPECT_EQ(r.camera.look_at, v.camera.look_at);
  EXPECT_EQ(r.camera.up, v.camera.up);
  EXPECT_EQ(r.camera.focal_length_mm, 444.5);
  EXPECT_EQ(r.camera.focus_distance_mm, 3912.75);
  EXPECT_EQ(r.camera.aperture_mm, 96);
  EXPECT_EQ(r.camera.lens_rate, 9);
  EXPECT_FALSE(r.camera.breathing);
  EXPECT_EQ(r.integrator, Integrator::kCameras);
  EXPECT_EQ(r.interpolation, Interpolation::kFocalPlane);
  EXPECT_EQ(r.light_field, "paper.lf");
  std::filesystem::remove_all(dir);
}

TEST(ViewFile, NamesWhatIsWrong) {
  const auto message = [](const std::string& text) {
    return testing::ErrorOf([&] { ViewFromJson(nlohmann::json::parse(text), "v.json"); });
  };
  EXPECT_NE(message(R"({"format": "lfcam-calibration", "version": 1})").find("v.json"),
            std::string::npos);
  const std::string camera =
      R"("camera": {"width": 64, "height": 48, "eye": [0, 0, 0], "look_at": [0, 0, -1],
                    "up": [0, 1, 0], "focal_length_mm": 500, "focus_distance_mm": 4000,
                    "aperture_mm": 0, "lens_rate": 4, "breathing": true})";
  EXPECT_EQ(message(R"({"format": "lfcam-view", "version": 1, )" + camera + "}"), "");
  std::string bad = camera;
  bad.replace(bad.find("\"width\": 64"), 11, "\"width\": -4");
  EXPECT_NE(message(R"({"format": "lfcam-view", "version": 1, )" + bad + "}").find("width"),
            std::string::npos);
  bad = camera;
  bad.replace(bad.find("\"focus_distance_mm\": 4000"), 25, "\"focus_distance_mm\": 100");
  EXPECT_NE(message(R"({"format": "lfcam-view", "version": 1, )" + bad + "}").find("camera"),
            std::string::npos);
  EXPECT_NE(message(R"({"format": "lfcam-view", "version": 1, )" + camera +
                    R"(, "render": {"integrator": "magic", "interpolation": "quadrilinear"}})")
                .find("magic"),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
