#include "lfcam/core/image_header.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

std::vector<std::uint8_t> Encode(const cv::Mat& image, const std::string& ext) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes));
  return bytes;
}

void PutBigEndian32(std::uint8_t* p, std::uint32_t v) {
  p[0] = std::uint8_t(v >> 24);
  p[1] = std::uint8_t(v >> 16);
  p[2] = std::uint8_t(v >> 8);
  p[3] = std::uint8_t(v);
}

using testing::ErrorOf;

TEST(ImageHeader, ReadsPngAndJpegSizesWithoutDecoding) {
  const cv::Mat rgb(37, 53, CV_8UC3, cv::Scalar(10, 200, 30));
  const cv::Mat grey16(5, 7, CV_16UC1, cv::Scalar(40000));
  auto h = ProbeImageHeader(Encode(rgb, ".png"));
  EXPECT_EQ(h.format, "PNG");
  EXPECT_EQ(h.width, 53);
  EXPECT_EQ(h.height, 37);
  EXPECT_EQ(h.channels, 3);
  h = ProbeImageHeader(Encode(grey16, ".png"));
  EXPECT_EQ(h.channels, 1);
  EXPECT_EQ(h.bits_per_channel, 16);
  h = ProbeImageHeader(Encode(rgb, ".jpg"));
  EXPECT_EQ(h.format, "JPEG");
  EXPECT_EQ(h.width, 53);
  EXPECT_EQ(h.height, 37);
  EXPECT_NE(ErrorOf([] {
              ProbeImageHeader(std::vector<std::uint8_t>{'B', 'M', 0, 0});
            }).find("not a PNG or JPEG"),
            std::string::npos);
}

// A 1 kB PNG that claims 20000 x 20000 pixels: refused from the header, before any decoding.
TEST(ImageHeader, DecompressionBombsAreRefusedBeforeDecoding) {
  auto png = Encode(cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(0)), ".png");
  PutBigEndian32(&png[16], 20000);
  PutBigEndian32(&png[20], 20000);
  EXPECT_NE(ErrorOf([&] {
              DecodeImageBytes(png, "bomb.png");
            }).find("bomb.png: a 20000x20000 PNG image is larger than the limit of 16384"),
            std::string::npos);
  // Within the side limit but not within memory.
  PutBigEndian32(&png[16], 16000);
  PutBigEndian32(&png[20], 16000);
  std::string error;
  {
    const testing::ScopedEnv limit("LFCAM_MEMORY_LIMIT", "64M");
    error = ErrorOf([&] { DecodeImageBytes(png, "big.png"); });
  }
  EXPECT_NE(error.find("memory limit"), std::string::npos) << error;
  // Truncated headers are refused by the probe.
  EXPECT_NE(ErrorOf([&] {
              DecodeImageBytes(std::span(png.data(), 20), "cut.png");
            }).find("cut.png: truncated PNG header"),
            std::string::npos);
}

// The generator of corrupt images: random edits of real PNGs and JPEGs. Each decodes or is
// refused with lfcam::Error.
TEST(ImageHeader, RandomlyCorruptedImagesDecodeOrAreRefusedCleanly) {
  cv::Mat noise(24, 32, CV_8UC3);
  cv::randu(noise, 0, 255);
  std::mt19937 rng(11);
  int refused = 0;
  for (const char* ext : {".png", ".jpg"}) {
    const auto good = Encode(noise, ext);
    refused += testing::CountRefused(
        300,
        [&](int) {
          auto bad = good;
          const std::size_t at = rng() % bad.size();
          switch (rng() % 3) {
            case 0:
              bad[at] = std::uint8_t(rng());
              break;
            case 1:
              bad.resize(at + 1);
              break;
            default:
              bad[rng() % std::min<std::size_t>(bad.size(), 40)] ^= std::uint8_t(1 << (rng() % 8));
          }
          return bad;
        },
        [](const std::vector<std::uint8_t>& bad) { DecodeImageBytes(bad, "mutant"); });
  }
  EXPECT_GT(refused, 50);
}

}  // namespace
}  // namespace lfcam
