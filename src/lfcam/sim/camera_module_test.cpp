#include "lfcam/sim/camera_module.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

SimulatedModule PlainModule(int width, int height) {
  SimulatedModule m;
  m.intrinsics = NominalPiCamera(width, height);
  return m;
}

// The linear values a CV_8UC3 sRGB image encodes, channel `ch`.
std::vector<double> DecodedChannel(const cv::Mat& image, int ch) {
  std::vector<double> out;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      out.push_back(SrgbDecodeTable()[image.at<cv::Vec3b>(y, x)[ch]]);
  return out;
}

TEST(CameraModuleExposure, ShotAndReadNoiseHaveTheSpreadOfTheElectronsCounted) {
  const SimulatedModule module = PlainModule(400, 300);
  const double level = 0.25;
  const cv::Mat radiance(300, 400, CV_32FC3, cv::Scalar::all(level));
  ExposureOptions options;
  options.noise_seed = 7;
  const cv::Mat image = ExposeRadiance(module, radiance, options);
  // Poisson electrons plus read noise, and the 8-bit step's uniform error on top.
  const double electrons = level * options.full_well;
  const double noise =
      std::sqrt(electrons + options.read_noise * options.read_noise) / options.full_well;
  const double code_step = SrgbToLinear(float(LinearToSrgb8(float(level)) + 1) / 255.0f) -
                           SrgbToLinear(float(LinearToSrgb8(float(level))) / 255.0f);
  const double expected_sd = std::sqrt(noise * noise + code_step * code_step / 12);
  for (int ch = 0; ch < 3; ++ch) {
    const auto values = DecodedChannel(image, ch);
    double sum = 0, sum2 = 0;
    for (double v : values) sum += v, sum2 += v * v;
    const double mean = sum / double(values.size());
    const double sd = std::sqrt(sum2 / double(values.size()) - mean * mean);
    EXPECT_NEAR(mean, level, 0.003 * level) << "channel " << ch;
    EXPECT_NEAR(sd, expected_sd, 0.04 * expected_sd) << "channel " << ch;
  }
  // Rows are independent streams: no row repeats another.
  EXPECT_GT(cv::norm(image.row(10), image.row(11), cv::NORM_L1), 0.0);
  // The same seed gives the same image whatever the threads; another seed, another image.
  EXPECT_EQ(cv::norm(image, ExposeRadiance(module, radiance, options), cv::NORM_INF), 0.0);
  options.noise_seed = 8;
  EXPECT_GT(cv::norm(image, ExposeRadiance(module, radiance, options), cv::NORM_L1), 0.0);
}

TEST(CameraModuleExposure, GainAndVignettingScaleTheRadiance) {
  SimulatedModule module = PlainModule(201, 151);
  module.photometry.gain = Vec3(1.1, 0.9, 0.8);
  module.photometry.vignetting[0] = -0.3;
  module.photometry.vignetting[1] = -0.05;
  const double level = 0.4;
  const cv::Mat radiance(151, 201, CV_32FC3, cv::Scalar::all(level));
  ExposureOptions options;
  options.noise = false;
  const cv::Mat image = ExposeRadiance(module, radiance, options);
  // At the centre no falloff; in a corner (rho = 1) the whole of it.
  const cv::Vec3b centre = image.at<cv::Vec3b>(75, 100), corner = image.at<cv::Vec3b>(0, 0);
  for (int ch = 0; ch < 3; ++ch) {
    const double gain = module.photometry.gain[ch];
    EXPECT_NEAR(centre[ch], LinearToSrgb8(float(level * gain)), 1) << "channel " << ch;
    EXPECT_NEAR(corner[ch], LinearToSrgb8(float(level * gain * (1 - 0.3 - 0.05))), 1)
        << "channel " << ch;
  }
}

TEST(CameraModuleExposure, RefusesARadianceImageOfAnotherSize) {
  const SimulatedModule module = PlainModule(64, 48);
  EXPECT_THROW(ExposeRadiance(module, cv::Mat(48, 63, CV_32FC3, cv::Scalar::all(0)), {}), Error);
  EXPECT_THROW(ExposeRadiance(module, cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(0)), {}), Error);
}

}  // namespace
}  // namespace lfcam
