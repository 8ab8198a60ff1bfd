// `lfcam export --format quilt` as a user runs it: the quilt's tiles are `lfcam render` of its
// views' saved cameras (within 1/255), in the displays' order; a video's quilts as an MP4; bad
// flags refused with nothing written.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/cli/share_test_support.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/share/mp4_test_support.h"
#include "lfcam/share/quilt.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;

class QuiltCli : public testing::SharingTest {
 protected:
  // The largest difference, in 8-bit steps, between two images.
  static double MaxDifference(const cv::Mat& a, const cv::Mat& b) {
    cv::Mat diff;
    cv::absdiff(a, b, diff);
    double max = 0;
    cv::minMaxLoc(diff.reshape(1), nullptr, &max);
    return max;
  }
};

TEST_F(QuiltCli, TilesAreTheRendersOfTheirViewsCamerasInTheDisplaysOrder) {
  for (const std::string preset : {"portrait", "go"}) {
    const std::string out = Path("quilt_" + preset);
    const auto run = Lfcam(fmt::format(
        "export {} --format quilt --preset {} --focal-length 300 --focus-distance 4300 --out {}",
        Input("still.lf"), preset, out));
    ASSERT_EQ(run.status, 0) << run.output;
    const QuiltLayout layout = LayoutQuilt(QuiltPresetNamed(preset));
    const fs::path file = fs::path(out) / ("still" + layout.suffix() + ".png");
    ASSERT_TRUE(fs::is_regular_file(file)) << run.output;
    const cv::Mat quilt = ReadImageSrgb8(file);
    ASSERT_EQ(quilt.size(), cv::Size(layout.width(), layout.height()));
    const auto info = nlohmann::json::parse(std::ifstream(fs::path(out) / "quilt.json"));
    EXPECT_EQ(info["columns"], layout.cols);
    EXPECT_EQ(info["zero_parallax_mm"], 4300.0);
    // View 0, a middle one and the last: each tile is the render of its saved camera.
    double previous_x = -1e9;
    for (const int k : {0, layout.views() / 2, layout.views() - 1}) {
      const std::string view = (fs::path(out) / fmt::format("cameras/view_{:02}.json", k)).string();
      const auto camera = nlohmann::json::parse(std::ifstream(view))["camera"];
      EXPECT_GT(camera["eye"][0].get<double>(), previous_x) << "left to right";
      previous_x = camera["eye"][0];
      const std::string png = Path(fmt::format("view_{}_{}.png", preset, k));
      const auto render = Lfcam(
          fmt::format("render {} --camera {} --out {} --quiet", Input("still.lf"), view, png));
      ASSERT_EQ(render.status, 0) << render.output;
      const cv::Mat tile = ToTile(ReadImageSrgb8(png), layout);
      EXPECT_LE(MaxDifference(quilt(QuiltTile(layout, k)), tile), 1.0) << preset << " view " << k;
    }
    // The tile order is the display's: view 0 sits bottom-left, not top-left.
    const cv::Mat view0 =
        ToTile(ReadImageSrgb8(Path(fmt::format("view_{}_0.png", preset))), layout);
    const cv::Rect top_left(0, 0, layout.tile_width, layout.tile_height);
    EXPECT_GT(MaxDifference(quilt(top_left), view0), 10.0);
  }
}

TEST_F(QuiltCli, AVideoBecomesAnMp4OfQuilts) {
  const std::string out = Path("quilt_video");
  const auto run =
      Lfcam(fmt::format("export {} --format quilt --preset go --focal-length 300 --out {} --quiet",
                        Input("moving.lfv"), out));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("3 frames at 2 fps"), std::string::npos) << run.output;
  const QuiltLayout layout = LayoutQuilt(QuiltPresetNamed("go"), /*even=*/true);
  const testing::DecodedMp4 video =
      testing::DecodeMp4((fs::path(out) / ("moving" + layout.suffix() + ".mp4")).string());
  ASSERT_EQ(video.frames.size(), 3u);
  EXPECT_NEAR(video.fps, 2.0, 1e-6);
  EXPECT_EQ(video.frames[0].size(), cv::Size(layout.width(), layout.height()));
  // Frame 2's centre view is the render of light field frame 2 through that view's camera.
  const int k = layout.views() / 2;
  const std::string view = (fs::path(out) / fmt::format("cameras/view_{:02}.json", k)).string();
  for (const int frame : {0, 2}) {
    const std::string png = Path(fmt::format("video_view_{}.png", frame));
    ASSERT_EQ(Lfcam(fmt::format("render {} --frame {} --camera {} --out {} --quiet",
                                Input("moving.lfv"), frame, view, png))
                  .status,
              0);
  }
  const cv::Mat tile = video.frames[2](QuiltTile(layout, k));
  EXPECT_GT(
      CompareImages(tile, ToTile(ReadImageSrgb8(Path("video_view_2.png")), layout)).psnr_db,
      CompareImages(tile, ToTile(ReadImageSrgb8(Path("video_view_0.png")), layout)).psnr_db + 2.0);
  // --frame N alone: one quilt of that frame, a PNG.
  const auto one = Lfcam(fmt::format("export {} --format quilt --frame 1 --out {} --quiet",
                                     Input("moving.lfv"), Path("quilt_frame1")));
  ASSERT_EQ(one.status, 0) << one.output;
  EXPECT_TRUE(fs::is_regular_file(fs::path(Path("quilt_frame1")) / "moving_qs8x6a0.75.png"));
}

TEST_F(QuiltCli, BadFlagsAreRefusedAndNothingIsWritten) {
  fs::create_directories(Path("full"));
  std::ofstream(Path("full/x")) << "x";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--format quilt --preset hologram --out " + Path("q1"), "--preset hologram"},
      {"--format quilt --size 512 --out " + Path("q1"), "--size"},
      {"--format quilt --out " + Path("full"), "not an empty folder"},
      {"--format quilt --focus-distance 10 --out " + Path("q1"), "--focus-distance"},
      {"--format png-views --preset go --out " + Path("q1"), "--preset: only with --format quilt"},
      {"--format png-views --aperture 20 --out " + Path("q1"), "--aperture: only with"},
      {"--format quilt --baseline -5 --out " + Path("q1"), "--baseline"},
  };
  for (const auto& [flags, expected] : cases) {
    const auto run = Lfcam(fmt::format("export {} {}", Input("still.lf"), flags));
    EXPECT_NE(run.status, 0) << flags << "\n" << run.output;
    EXPECT_NE(run.output.find(expected), std::string::npos) << flags << "\n" << run.output;
  }
  const auto frames = Lfcam(
      fmt::format("export {} --format quilt --frames 9 --out {}", Input("moving.lfv"), Path("q1")));
  EXPECT_EQ(frames.status, 2) << frames.output;
  EXPECT_NE(frames.output.find("has 3 frames from --frame 0"), std::string::npos) << frames.output;
  EXPECT_FALSE(fs::exists(Path("q1")));
  for (const auto& entry : fs::directory_iterator(*dir_))
    EXPECT_EQ(entry.path().filename().string().find(".partial-"), std::string::npos);
}

}  // namespace
}  // namespace lfcam
