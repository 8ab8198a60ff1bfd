#include "lfcam/render/lightfield_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace lfcam {
namespace {

// A multilinear function of (col, row, k, l): quadrilinear interpolation must be exact on it.
Eigen::Vector3f Multilinear(double c, double r, double k, double l) {
  const double a = 0.1 + 0.05 * c + 0.02 * r + 0.001 * k + 0.0007 * l;
  const double b = 0.2 + 0.01 * c * r + 0.0001 * k * l;
  const double d = 0.3 + 0.0001 * c * k + 0.00005 * r * l * c;
  return Eigen::Vector3f(float(a), float(b), float(d));
}

// A rows x cols array 1 m in front of a 200 x 100 mm st window.
Slab TestSlab(int rows, int cols) {
  Slab slab;
  slab.uv.rows = rows;
  slab.uv.cols = cols;
  slab.uv.p_ca = Vec3(0, 0, 1000);
  slab.st = ViewWindow{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 200, 100};
  return slab;
}

LightField MakeMultilinearLightField() {
  LightField lf({4, 5, 40, 30}, SampleType::kLinearF16, TestSlab(4, 5));
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c)
      for (int l = 0; l < 30; ++l)
        for (int k = 0; k < 40; ++k) lf.set_linear_rgb(r, c, k, l, Multilinear(c, r, k, l));
  return lf;
}

TEST(LightFieldSampler, QuadrilinearIsExactOnMultilinearData) {
  const LightField lf = MakeMultilinearLightField();
  const LightFieldSampler sampler(lf);
  for (double c : {0.0, 0.3, 1.5, 3.99})
    for (double r : {0.0, 1.25, 2.7})
      for (double k : {0.0, 7.5, 38.2})
        for (double l : {0.0, 11.1, 28.9}) {
          // Sample centres sit at (i + 0.5) / n in window coordinates.
          const double u = (c + 0.5) / 5, v = (r + 0.5) / 4;
          const double s = (k + 0.5) / 40, t = (l + 0.5) / 30;
          float rgb[3];
          sampler.Fetch(u, v, s, t, rgb);
          const Eigen::Vector3f expected = Multilinear(c, r, k, l);
          for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(rgb[ch], expected[ch], 2e-3);  // f16 storage
        }
}

// Keys' cubic reproduces a quadratic exactly (away from the view's edges, where the edge
// sample repeats), where a bilinear read of the same quadratic is off by up to a quarter of its
// second difference between samples: the sharper read the depth lookup uses at the views' own
// resolution.
TEST(LightFieldSampler, CubicReadsAreExactOnAQuadratic) {
  LightField lf = MakeMultilinearLightField();  // view (0, 1) made a quadratic below
  // 0.1 .. 0.32 over the samples read: f16 holds it to 1.2e-4.
  const auto quadratic = [](double k, double l) {
    return 0.1 + 0.002 * (k - 20) * (k - 20) + 0.001 * l;
  };
  for (int l = 0; l < 30; ++l)
    for (int k = 0; k < 40; ++k)
      lf.set_linear_rgb(0, 1, k, l, Eigen::Vector3f::Constant(float(quadratic(k, l))));
  const LightFieldSampler sampler(lf);
  double worst_cubic = 0, worst_bilinear = 0;
  for (double k : {10.5, 16.5, 20.5, 27.5})  // halfway: bilinear is off by 0.002 / 4 there
    for (double l : {4.0, 15.3, 22.7}) {
      float cubic[3] = {0, 0, 0}, bilinear[3] = {0, 0, 0};
      EXPECT_EQ(sampler.AccumulateAtCubic(0, 1, k, l, 1.0f, cubic), 1.0f);
      sampler.AccumulateAt(0, 1, k, l, 1.0f, bilinear);
      worst_cubic = std::max(worst_cubic, std::abs(cubic[0] - quadratic(k, l)));
      worst_bilinear = std::max(worst_bilinear, std::abs(bilinear[0] - quadratic(k, l)));
    }
  EXPECT_LT(worst_cubic, 2.5e-4);
  EXPECT_GT(worst_bilinear, 4e-4);
  // At a sample the cubic read is the sample itself.
  float at[3] = {0, 0, 0};
  sampler.AccumulateAtCubic(0, 1, 7.0, 9.0, 2.0f, at);
  EXPECT_NEAR(at[1], 2.0 * quadratic(7, 9), 2e-3);
}

// An 8-bit view is interpolated in its sRGB encoding and the result decoded. On a view whose
// codes are a quadratic (which Keys' cubic reproduces exactly), a read between samples is the
// decoded quadratic. Beside an edge from code 20 to 200, it is Keys' cubic of the codes: the
// cubic through the decoded samples would overshoot below black on the dark side (where the
// encoding is steepest, so the error is largest once encoded) and lie far brighter at the edge.
TEST(LightFieldSampler, CubicReadsOfAn8BitViewInterpolateItsEncoding) {
  LightField lf({1, 2, 40, 30}, SampleType::kSrgb8, TestSlab(1, 2));
  const auto quadratic = [](double k, double l) { return 30 + (k - 20) * (k - 20) + 2 * l; };
  const auto edge = [](int k) { return k < 20 ? 20 : 200; };
  for (int l = 0; l < 30; ++l)
    for (int k = 0; k < 40; ++k) {
      const std::size_t o = (std::size_t(l) * 40 + std::size_t(k)) * 3;
      for (int ch = 0; ch < 3; ++ch) {
        lf.mutable_view_data(0, 0)[o + ch] = std::uint8_t(edge(k));
        if (k >= 8 && k < 32) lf.mutable_view_data(0, 1)[o + ch] = std::uint8_t(quadratic(k, l));
      }
    }
  const LightFieldSampler sampler(lf);
  const auto decoded = [](double code) { return double(SrgbToLinear(float(code / 255))); };
  double worst = 0;
  for (double k : {12.5, 16.5, 20.5, 23.5, 27.5})
    for (double l : {4.0, 15.5, 22.25}) {
      float read[3] = {0, 0, 0};
      EXPECT_EQ(sampler.AccumulateAtCubic(0, 1, k, l, 1.0f, read), 1.0f);
      worst = std::max(worst, std::abs(read[1] - decoded(quadratic(k, l))));
    }
  EXPECT_LT(worst, 2e-6);  // the fine decoding table's error
  // Beside the edge, halfway between samples: Keys' weights -1/16, 9/16, 9/16, -1/16.
  for (const auto& [k, codes] : {std::pair{18.5, 20 * 17 / 16.0 - 200 / 16.0},  // 8.75
                                 {19.5, 110.0}}) {
    float read[3] = {0, 0, 0};
    sampler.AccumulateAtCubic(0, 0, k, 10.0, 1.0f, read);
    EXPECT_NEAR(read[0], decoded(codes), 2e-6) << k;
  }
  float dark[3] = {0, 0, 0};
  sampler.AccumulateAtCubic(0, 0, 18.5, 10.0, 1.0f, dark);
  EXPECT_GT(dark[0], 0.0f);  // through the decoded samples: 17/16 x 0.0070 - 0.578 / 16 < 0
  EXPECT_LT(17 / 16.0 * decoded(20) - decoded(200) / 16, -0.02);
  // At a sample the read is the sample's own decoded code.
  float at[3] = {0, 0, 0};
  sampler.AccumulateAtCubic(0, 1, 14.0, 9.0, 2.0f, at);
  EXPECT_FLOAT_EQ(at[0], 2.0f * SrgbDecodeTable()[std::size_t(quadratic(14, 9))]);
}

TEST(LightFieldSampler, LinesThroughTheSlabFetchTheRightSample) {
  const LightField lf = MakeMultilinearLightField();
  const LightFieldSampler sampler(lf);
  // The line from camera (2, 3)'s centre through st sample (k, l) = (10, 20)'s centre.
  const Vec3 from = lf.slab().uv.camera_center(2, 3);
  const Vec3 to = lf.slab().st.point_at(lf.s_of(10), lf.t_of(20));
  float rgb[3];
  ASSERT_TRUE(sampler.Sample(from, to - from, rgb));
  const Eigen::Vector3f expected = lf.linear_rgb(2, 3, 10, 20);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(rgb[ch], expected[ch], 1e-6);
  // Misses outside the PRP window and outside the st domain.
  EXPECT_FALSE(sampler.Sample(Vec3(-10, 50, 1000), Vec3(0, 0, -1), rgb));
  EXPECT_FALSE(sampler.Sample(Vec3(100, 50, 1000), Vec3(0.5, 0, -1), rgb));
}

TEST(LightFieldSampler, ALinesProjectionIsWhereEachOfItsPointsMeetsTheStPlane) {
  const LightField lf = MakeMultilinearLightField();
  const LightFieldSampler sampler(lf);
  const Vec3 from = lf.slab().uv.camera_center(1, 2);
  // A ray from in front of the array, aimed down and across the slab, at x = 1 / q along it.
  const Vec3 a(30, -20, 900), b(0.02, 0.015, -1.0);
  const auto line = sampler.ProjectLine(from, a, b);
  for (const double q : {1.0 / 200, 1.0 / 1500, 1.0 / 4000, 1.0 / 90000}) {
    double k, l, k_expected, l_expected;
    ASSERT_TRUE(line.AtReciprocal(q, k, l));
    ASSERT_TRUE(sampler.StSampleAt(from, a + (1.0 / q) * b, k_expected, l_expected));
    EXPECT_NEAR(k, k_expected, 1e-9 * (1 + std::abs(k_expected))) << q;
    EXPECT_NEAR(l, l_expected, 1e-9 * (1 + std::abs(l_expected))) << q;
  }
  // A line through `from` parallel to the st-plane meets it nowhere.
  const auto parallel = sampler.ProjectLine(from, from, Vec3(1, 0, 0));
  double k, l;
  EXPECT_FALSE(parallel.AtReciprocal(0.5, k, l));
}

TEST(LightFieldSampler, ClampsToTheOutermostSamplesInsideTheWindows) {
  const LightField lf = MakeMultilinearLightField();
  const LightFieldSampler sampler(lf);
  float edge[3], corner[3];
  sampler.Fetch(0.0, 0.0, 0.0, 0.0, edge);  // window corner, half a sample outside the centres
  sampler.Fetch(0.1, 0.125, 0.5 / 40, 0.5 / 30, corner);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(edge[ch], corner[ch], 1e-6);
}

}  // namespace
}  // namespace lfcam
