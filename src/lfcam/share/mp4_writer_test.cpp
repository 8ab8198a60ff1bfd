#include "lfcam/share/mp4_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/image_metrics.h"
#include "lfcam/core/test_support.h"
#include "lfcam/share/mp4_test_support.h"

namespace lfcam {
namespace {

// A frame that changes with k: a gradient, a moving disc and fine stripes.
cv::Mat TestFrame(int k, int width, int height) {
  cv::Mat rgb(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      rgb.at<cv::Vec3b>(y, x) =
          cv::Vec3b(std::uint8_t(255 * x / width), std::uint8_t(255 * y / height),
                    std::uint8_t((x / 8 + y / 8) % 2 ? 200 : 60));
  cv::circle(rgb, {20 + 6 * k, height / 2}, 14, cv::Scalar(250, 240, 30), cv::FILLED);
  return rgb;
}

TEST(Mp4Writer, FramesComeBackAtTheirRateSizeAndColours) {
  const auto dir = testing::MakeScratchDir("mp4_writer");
  const auto path = dir / "clip.mp4";
  const int width = 160, height = 96, count = 12;
  Mp4Options options;
  options.fps = 24;
  {
    Mp4Writer writer(path, width, height, options);
    EXPECT_FALSE(std::filesystem::exists(path)) << "the file appears only when finished";
    for (int k = 0; k < count; ++k) writer.Write(TestFrame(k, width, height));
    writer.Finish();
    EXPECT_EQ(writer.frames(), count);
  }
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1) << "no temporary left";
  const testing::DecodedMp4 video = testing::DecodeMp4(path.string());
  EXPECT_EQ(video.codec, "h264");
  EXPECT_NEAR(video.fps, 24.0, 1e-6);
  EXPECT_EQ(video.colorspace, AVCOL_SPC_BT709);
  EXPECT_EQ(video.range, AVCOL_RANGE_MPEG);
  ASSERT_EQ(int(video.frames.size()), count);
  for (int k = 0; k < count; ++k) {
    ASSERT_EQ(video.frames[k].size(), cv::Size(width, height));
    // 4:2:0 halves the chroma of the 8-pixel checks' edges; the rest is the encoder's loss.
    EXPECT_GT(CompareImages(video.frames[k], TestFrame(k, width, height)).psnr_db, 30.0) << k;
  }
  // Each decoded frame is its own source frame, not a neighbour's (the disc moves 6 px a frame).
  EXPECT_GT(CompareImages(video.frames[5], TestFrame(5, width, height)).psnr_db,
            CompareImages(video.frames[5], TestFrame(6, width, height)).psnr_db + 3.0);
}

TEST(Mp4Writer, AnUnfinishedWriterLeavesNothing) {
  const auto dir = testing::MakeScratchDir("mp4_writer");
  {
    Mp4Writer writer(dir / "clip.mp4", 64, 64, {});
    writer.Write(TestFrame(0, 64, 64));
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(Mp4Writer, RefusesOddSizesWrongFramesAndBadOptions) {
  const auto dir = testing::MakeScratchDir("mp4_writer");
  EXPECT_NE(testing::ErrorOf([&] { Mp4Writer(dir / "a.mp4", 63, 64, {}); }).find("even width"),
            std::string::npos);
  Mp4Options options;
  options.fps = 0;
  EXPECT_NE(testing::ErrorOf([&] { RequireMp4Frame(64, 64, options); }).find("frames a second"),
            std::string::npos);
  options = {};
  options.crf = 60;
  EXPECT_NE(testing::ErrorOf([&] { RequireMp4Frame(64, 64, options); }).find("crf 60"),
            std::string::npos);
  Mp4Writer writer(dir / "b.mp4", 64, 64, {});
  EXPECT_NE(testing::ErrorOf([&] { writer.Write(TestFrame(0, 32, 64)); }).find("frame 0 is 32x64"),
            std::string::npos);
  EXPECT_NE(testing::ErrorOf([&] { writer.Finish(); }).find("at least one frame"),
            std::string::npos);
  EXPECT_NE(testing::ErrorOf([&] { Mp4Writer(dir / "no" / "c.mp4", 64, 64, {}); }).find("no/c.mp4"),
            std::string::npos);
}

}  // namespace
}  // namespace lfcam
