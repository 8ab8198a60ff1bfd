// lfcam's PNG and JPEG codec against OpenCV's (an independent reader and writer over the same
// file formats): the same pixels from the same files, whatever their kind.
#include "lfcam/core/image_codec.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam::image_codec_test {
namespace {

std::vector<std::uint8_t> OpenCvEncode(const std::string& ext, const cv::Mat& m,
                                       const std::vector<int>& params = {}) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, m, bytes, params));
  return bytes;
}

cv::Mat OpenCvDecode(const std::vector<std::uint8_t>& bytes, int flags) {
  return cv::imdecode(
      cv::Mat(1, int(bytes.size()), CV_8UC1, const_cast<std::uint8_t*>(bytes.data())), flags);
}

// A PNG of the kinds OpenCV does not write (palette with transparency, grey with alpha,
// 1-bit grey, interlaced), written with libpng here.
std::vector<std::uint8_t> LibpngEncode(int width, int height, int depth, int colour,
                                       bool interlaced,
                                       const std::vector<std::uint8_t>& packed_rows,
                                       const std::vector<png_color>& palette = {},
                                       const std::vector<png_byte>& transparency = {}) {
  std::vector<std::uint8_t> bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(
      png, &bytes,
      [](png_structp p, png_bytep data, png_size_t n) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(p));
        out->insert(out->end(), data, data + n);
      },
      nullptr);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), depth, colour,
               interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  if (!transparency.empty())
    png_set_tRNS(png, info, transparency.data(), int(transparency.size()), nullptr);
  png_write_info(png, info);
  const std::size_t stride = packed_rows.size() / std::size_t(height);
  std::vector<png_bytep> rows;
  for (int y = 0; y < height; ++y)
    rows.push_back(const_cast<png_bytep>(packed_rows.data()) + std::size_t(y) * stride);
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

void ExpectSame(const cv::Mat& ours, const cv::Mat& theirs, const std::string& what) {
  ASSERT_FALSE(ours.empty()) << what;
  ASSERT_EQ(ours.type(), theirs.type()) << what;
  ASSERT_EQ(ours.size(), theirs.size()) << what;
  EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0) << what;
}

// Every mode against OpenCV's flags for it.
void ExpectDecodesAsOpenCv(const std::vector<std::uint8_t>& bytes, bool png,
                           const std::string& what) {
  const struct {
    ImageDecodeMode mode;
    int flags;
    const char* name;
  } modes[] = {{ImageDecodeMode::kUnchanged, cv::IMREAD_UNCHANGED, "unchanged"},
               {ImageDecodeMode::kGray8, cv::IMREAD_GRAYSCALE, "grey"},
               {ImageDecodeMode::kColour8, cv::IMREAD_COLOR, "colour"}};
  for (const auto& m : modes) {
    std::string error;
    const cv::Mat ours =
        png ? DecodePngBytes(bytes, m.mode, 1, error) : DecodeJpegBytes(bytes, m.mode, 1, error);
    EXPECT_EQ(error, "") << what;
    ExpectSame(ours, OpenCvDecode(bytes, m.flags), what + ", " + m.name);
  }
  const int reduced[] = {cv::IMREAD_REDUCED_COLOR_2, cv::IMREAD_REDUCED_COLOR_4,
                         cv::IMREAD_REDUCED_COLOR_8};
  for (int k = 0; k < 3; ++k) {
    std::string error;
    const int reduction = 2 << k;
    const cv::Mat ours = png ? DecodePngBytes(bytes, ImageDecodeMode::kColour8, reduction, error)
                             : DecodeJpegBytes(bytes, ImageDecodeMode::kColour8, reduction, error);
    ExpectSame(ours, OpenCvDecode(bytes, reduced[k]),
               what + ", colour at 1/" + std::to_string(reduction));
  }
}

cv::Mat Picture(int width, int height, int type) {
  cv::Mat m(height, width, type);
  cv::RNG rng(width * 31 + height);
  rng.fill(m, cv::RNG::UNIFORM, 0, type == CV_16UC1 ? 65536 : 256);
  cv::GaussianBlur(m, m, cv::Size(0, 0), 1.5);  // JPEG-like content, not pure noise
  return m;
}

TEST(ImageCodec, DecodesWhatOpenCvWritesAsOpenCvDoes) {
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3}) {
    const cv::Mat m = Picture(67, 45, type);
    ExpectDecodesAsOpenCv(OpenCvEncode(".png", m), true, "PNG of type " + std::to_string(type));
  }
  for (const int type : {CV_8UC1, CV_8UC3}) {
    for (const int quality : {50, 95}) {
      const cv::Mat m = Picture(83, 61, type);
      ExpectDecodesAsOpenCv(OpenCvEncode(".jpg", m, {cv::IMWRITE_JPEG_QUALITY, quality}), false,
                            "JPEG of type " + std::to_string(type));
    }
  }
}

TEST(ImageCodec, DecodesPalettesGreyWithAlphaFewBitsAndInterlacingAsOpenCvDoes) {
  const int w = 21, h = 13;
  cv::RNG rng(5);
  // Palette of 4 colours, the first two partly transparent; interlaced and not.
  std::vector<png_color> palette = {{255, 0, 0}, {0, 200, 30}, {10, 20, 250}, {128, 128, 128}};
  std::vector<std::uint8_t> indices(std::size_t(w * h));
  for (auto& i : indices) i = std::uint8_t(rng.uniform(0, 4));
  for (const bool interlaced : {false, true}) {
    ExpectDecodesAsOpenCv(
        LibpngEncode(w, h, 8, PNG_COLOR_TYPE_PALETTE, interlaced, indices, palette, {0, 128}), true,
        "palette with transparency");
    ExpectDecodesAsOpenCv(
        LibpngEncode(w, h, 8, PNG_COLOR_TYPE_PALETTE, interlaced, indices, palette), true,
        "palette");
  }
  // Grey with alpha, 8 bits.
  std::vector<std::uint8_t> grey_alpha(std::size_t(w * h * 2));
  for (auto& v : grey_alpha) v = std::uint8_t(rng.uniform(0, 256));
  ExpectDecodesAsOpenCv(LibpngEncode(w, h, 8, PNG_COLOR_TYPE_GRAY_ALPHA, false, grey_alpha), true,
                        "grey with alpha");
  // 1-bit grey: a row of 21 samples is 3 bytes.
  std::vector<std::uint8_t> bits(std::size_t(3 * h));
  for (auto& v : bits) v = std::uint8_t(rng.uniform(0, 256));
  ExpectDecodesAsOpenCv(LibpngEncode(w, h, 1, PNG_COLOR_TYPE_GRAY, true, bits), true,
                        "1-bit grey, interlaced");
}

TEST(ImageCodec, WritesWhatOpenCvReadsBack) {
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1}) {
    const cv::Mat m = Picture(50, 37, type);
    const auto png = EncodePngBytes(m);
    ExpectSame(OpenCvDecode(png, cv::IMREAD_UNCHANGED), m, "PNG of type " + std::to_string(type));
  }
  for (const int type : {CV_8UC1, CV_8UC3}) {
    const cv::Mat m = Picture(64, 48, type);
    // The same encoder and settings as OpenCV's: the same pixels back.
    const auto ours = EncodeJpegBytes(m, 90);
    const auto theirs = OpenCvEncode(".jpg", m, {cv::IMWRITE_JPEG_QUALITY, 90});
    ExpectSame(OpenCvDecode(ours, cv::IMREAD_UNCHANGED), OpenCvDecode(theirs, cv::IMREAD_UNCHANGED),
               "JPEG of type " + std::to_string(type));
    EXPECT_LT(
        cv::norm(OpenCvDecode(ours, cv::IMREAD_UNCHANGED), m, cv::NORM_L1) / double(m.total()),
        8.0 * m.channels());  // near the picture (blurred noise: hard for JPEG)
  }
  EXPECT_THROW(EncodePngBytes(cv::Mat(4, 4, CV_32FC1)), Error);
  EXPECT_THROW(EncodeJpegBytes(cv::Mat(4, 4, CV_16UC1), 90), Error);
  EXPECT_THROW(EncodePngBytes(cv::Mat()), Error);
}

TEST(ImageCodec, RefusesDamagedFilesWithTheReason) {
  const cv::Mat m = Picture(400, 300, CV_8UC3);  // large enough that half is in the image data
  const auto png = OpenCvEncode(".png", m);
  const auto jpeg = OpenCvEncode(".jpg", m);
  std::string error;
  // Cut short.
  EXPECT_TRUE(
      DecodePngBytes(std::span(png.data(), png.size() / 2), ImageDecodeMode::kUnchanged, 1, error)
          .empty());
  EXPECT_NE(error, "");
  EXPECT_TRUE(
      DecodeJpegBytes(std::span(jpeg.data(), jpeg.size() / 2), ImageDecodeMode::kColour8, 1, error)
          .empty());
  EXPECT_NE(error.find("ends before"), std::string::npos) << error;
  // Not the format at all.
  const std::vector<std::uint8_t> junk(100, 0x5a);
  EXPECT_TRUE(DecodePngBytes(junk, ImageDecodeMode::kUnchanged, 1, error).empty());
  EXPECT_NE(error, "");
  EXPECT_TRUE(DecodeJpegBytes(junk, ImageDecodeMode::kUnchanged, 1, error).empty());
  EXPECT_NE(error, "");
  // A PNG whose image data is corrupt (its CRC no longer matches).
  auto bad = png;
  bad[bad.size() / 2] ^= 0xff;
  EXPECT_TRUE(DecodePngBytes(bad, ImageDecodeMode::kUnchanged, 1, error).empty());
  EXPECT_NE(error, "");
}

}  // namespace
}  // namespace lfcam::image_codec_test
