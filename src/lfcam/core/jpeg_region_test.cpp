#include "lfcam/core/jpeg_region.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/libjpeg_errors.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

// A smooth colourful 640x480 test image, JPEG-encoded at quality 95.
std::vector<std::uint8_t> TestJpeg(cv::Mat* rgb_out) {
  cv::Mat rgb(480, 640, CV_8UC3);
  for (int y = 0; y < rgb.rows; ++y)
    for (int x = 0; x < rgb.cols; ++x)
      rgb.at<cv::Vec3b>(y, x) =
          cv::Vec3b(std::uint8_t(x * 255 / 639), std::uint8_t(y * 255 / 479),
                    ((x / 5 + y / 5) % 2) ? 220 : 30);  // sharp: shows any offset
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, 95});
  *rgb_out = rgb;
  return bytes;
}

// OpenCV's decode of the whole image at 1/reduction size, R, G, B.
cv::Mat OpenCvDecode(const std::vector<std::uint8_t>& bytes, int reduction) {
  const int flags = reduction == 1   ? cv::IMREAD_COLOR
                    : reduction == 2 ? cv::IMREAD_REDUCED_COLOR_2
                    : reduction == 4 ? cv::IMREAD_REDUCED_COLOR_4
                                     : cv::IMREAD_REDUCED_COLOR_8;
  cv::Mat whole = cv::imdecode(bytes, flags);
  cv::cvtColor(whole, whole, cv::COLOR_BGR2RGB);
  return whole;
}

// Two decodes of the same pixels agree: on average to 0.1 levels, everywhere to 2.
void ExpectSamePixels(const cv::Mat& expected, const cv::Mat& got) {
  cv::Mat difference;
  cv::absdiff(expected, got, difference);
  // An offset of one pixel would differ by up to 190 on the 5-pixel checker.
  const cv::Scalar mean = cv::mean(difference);
  EXPECT_LT(mean[0] + mean[1] + mean[2], 0.1) << mean;
  cv::Mat grey;
  cv::transform(difference, grey, cv::Matx13f(1, 1, 1));
  double worst = 0;
  cv::Point at;
  cv::minMaxLoc(grey, nullptr, &worst, nullptr, &at);
  EXPECT_LE(worst, 2.0) << "at " << at;
}

TEST(JpegRegion, DecodesTheRegionAsAWholeDecodeWould) {
  cv::Mat rgb;
  const auto bytes = TestJpeg(&rgb);
  for (const ChromaUpsampling chroma : {ChromaUpsampling::kInterpolated, ChromaUpsampling::kGuided})
    for (const int reduction : {1, 2, 4, 8}) {
      SCOPED_TRACE(ToString(chroma) + " at 1/" + std::to_string(reduction));
      const cv::Size scaled((640 + reduction - 1) / reduction, (480 + reduction - 1) / reduction);
      // An odd first row: a region starts on a chroma sample whatever is asked.
      const cv::Rect wanted(scaled.width / 3, scaled.height / 4 + 1, scaled.width / 3,
                            scaled.height / 2);
      const JpegRegion r = DecodeJpegRegion(bytes, "test.jpg", reduction, wanted, chroma);
      EXPECT_EQ(r.scaled, scaled);
      const cv::Rect got(r.origin, r.rgb.size());
      EXPECT_EQ(got & wanted, wanted);  // it covers the region
      // The same pixels as the whole image decoded: by OpenCV when libjpeg interpolates the
      // chroma (and at reduced sizes, where the chroma has the output's resolution already).
      const cv::Mat whole =
          chroma == ChromaUpsampling::kGuided && reduction == 1
              ? DecodeJpegRegion(bytes, "test.jpg", 1, cv::Rect(0, 0, 640, 480), chroma).rgb
              : OpenCvDecode(bytes, reduction);
      ExpectSamePixels(whole(wanted), r.rgb(cv::Rect(wanted.tl() - r.origin, wanted.size())));
    }
}

TEST(JpegRegion, GuidedChromaIsCloserToTheOriginalThanInterpolated) {
  cv::Mat rgb;
  const auto bytes = TestJpeg(&rgb);
  const cv::Rect all(0, 0, 640, 480);
  const cv::Mat guided = DecodeJpegRegion(bytes, "t.jpg", 1, all, ChromaUpsampling::kGuided).rgb;
  const cv::Mat interpolated =
      DecodeJpegRegion(bytes, "t.jpg", 1, all, ChromaUpsampling::kInterpolated).rgb;
  ASSERT_EQ(guided.size(), rgb.size());
  // The blue checker of 5-pixel squares is a colour edge every 5 pixels: 4:2:0 chroma holds it
  // at half resolution. Measured: interpolated 18.8 dB, guided 28.2 dB.
  EXPECT_GT(cv::PSNR(guided, rgb), cv::PSNR(interpolated, rgb) + 8.0);
  // The luma is untouched: the same as libjpeg's, to rounding.
  cv::Mat y_guided, y_interpolated;
  cv::cvtColor(guided, y_guided, cv::COLOR_RGB2GRAY);
  cv::cvtColor(interpolated, y_interpolated, cv::COLOR_RGB2GRAY);
  EXPECT_GT(cv::PSNR(y_guided, y_interpolated), 40.0);
}

// `rgb` as a quality-95 JPEG whose luma is sampled h x v times as often as its chroma (OpenCV
// writes only 4:2:0; cameras also write 4:2:2 and 4:4:4), baseline or progressive.
std::vector<std::uint8_t> EncodeSampled(const cv::Mat& rgb, int h, int v, bool progressive) {
  jpeg_compress_struct cinfo;
  LibjpegErrors error;
  cinfo.err = error.install();
  if (setjmp(error.jump)) {
    jpeg_destroy_compress(&cinfo);
    ADD_FAILURE() << error.message;
    return {};
  }
  jpeg_create_compress(&cinfo);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&cinfo, &buffer, &size);
  cinfo.image_width = JDIMENSION(rgb.cols);
  cinfo.image_height = JDIMENSION(rgb.rows);
  cinfo.input_components = 3;
  cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 95, TRUE);
  cinfo.comp_info[0].h_samp_factor = h;
  cinfo.comp_info[0].v_samp_factor = v;
  if (progressive) jpeg_simple_progression(&cinfo);
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb.ptr<std::uint8_t>(int(cinfo.next_scanline)));
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  std::vector<std::uint8_t> bytes(buffer, buffer + size);
  std::free(buffer);
  return bytes;
}

TEST(JpegRegion, EveryChromaSamplingDecodesBaselineOrProgressive) {
  cv::Mat rgb;
  TestJpeg(&rgb);
  const cv::Rect all(0, 0, 640, 480);
  for (const bool progressive : {false, true})
    for (const cv::Size factor : {cv::Size(1, 1), cv::Size(2, 1), cv::Size(1, 2), cv::Size(2, 2)}) {
      SCOPED_TRACE(::testing::Message() << "luma sampled " << factor << " times the chroma"
                                        << (progressive ? ", progressive" : ""));
      const auto bytes = EncodeSampled(rgb, factor.width, factor.height, progressive);
      const cv::Mat guided =
          DecodeJpegRegion(bytes, "s.jpg", 1, all, ChromaUpsampling::kGuided).rgb;
      const cv::Mat interpolated =
          DecodeJpegRegion(bytes, "s.jpg", 1, all, ChromaUpsampling::kInterpolated).rgb;
      ASSERT_EQ(guided.size(), rgb.size());
      if (factor == cv::Size(1, 1)) {
        // Nothing to restore: libjpeg's own conversion, both ways.
        EXPECT_EQ(cv::norm(guided, interpolated, cv::NORM_INF), 0.0);
        continue;
      }
      // The blue checker's colour edges: guided beats interpolated whichever way the chroma was
      // halved (measured 7.3 to 9.3 dB).
      EXPECT_GT(cv::PSNR(guided, rgb), cv::PSNR(interpolated, rgb) + 4.0);
      // A region decodes as the whole image does, starting on an odd row and column.
      const cv::Rect wanted(201, 153, 211, 137);
      const JpegRegion r = DecodeJpegRegion(bytes, "s.jpg", 1, wanted, ChromaUpsampling::kGuided);
      ExpectSamePixels(guided(wanted), r.rgb(cv::Rect(wanted.tl() - r.origin, wanted.size())));
    }
}

TEST(JpegRegion, NamesTheChromaUpsamplings) {
  for (const ChromaUpsampling c : {ChromaUpsampling::kGuided, ChromaUpsampling::kInterpolated})
    EXPECT_EQ(ChromaUpsamplingFromString(ToString(c)), c);
  EXPECT_NE(testing::ErrorOf([] { ChromaUpsamplingFromString("fancy"); }).find("'fancy'"),
            std::string::npos);
}

TEST(JpegRegion, RefusesWhatIsNotAReadableJpeg) {
  cv::Mat rgb;
  auto bytes = TestJpeg(&rgb);
  EXPECT_THROW(DecodeJpegRegion(bytes, "x.jpg", 3, {0, 0, 10, 10}), Error);
  const std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0, 0, 0, 0};
  EXPECT_NE(testing::ErrorOf([&] {
              DecodeJpegRegion(png, "x.png", 1, {0, 0, 10, 10});
            }).find("not a JPEG"),
            std::string::npos);
  // Truncated: the rows that are missing would be grey, so it is an error.
  std::vector<std::uint8_t> truncated(bytes.begin(),
                                      bytes.begin() + std::ptrdiff_t(bytes.size() / 2));
  const std::string message = testing::ErrorOf([&] {
    DecodeJpegRegion(truncated, "cut.jpg", 1, {0, 400, 640, 80});
  });
  EXPECT_NE(message.find("cut.jpg"), std::string::npos) << message;
  // Garbage after a valid start.
  std::vector<std::uint8_t> garbage(bytes.begin(), bytes.begin() + 200);
  std::mt19937 rng(1);
  for (int i = 0; i < 5000; ++i) garbage.push_back(std::uint8_t(rng()));
  EXPECT_THROW(DecodeJpegRegion(garbage, "g.jpg", 1, {0, 0, 640, 480}), Error);
  // A region outside the image decodes to nothing.
  EXPECT_TRUE(DecodeJpegRegion(bytes, "x.jpg", 1, {700, 500, 10, 10}).rgb.empty());
}

}  // namespace
}  // namespace lfcam
