// The CPU's plane sweep (SweepViews::Sweep: planes in groups, a band of rows at a time, counts
// from the views' rectangles) against the cost volume's definition evaluated directly, sample by
// sample, from the same reads: every view read with Keys' weights at its shift, each term
// truncated and weighted, averaged over each half-array and its window (the frame's edge
// repeated), the cheapest half-array that enough views see.
#include "lfcam/depth/cost_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/depth/bilinear_read.h"
#include "lfcam/depth/depth_test_scene.h"
#include "lfcam/depth/sweep_reads.h"

namespace lfcam {
namespace {

// An engine that evaluates the definition directly: slow, plain, and independent of the CPU
// sweep's order of work.
class DefinitionEngine : public CostVolumeEngine {
 public:
  CostVolume Sweep(const ShiftedSweep& sweep) override {
    constexpr int kChannels = ShiftedSweep::kChannels, kHalves = ShiftedSweep::kHalves;
    const int sub_arrays = sweep.sub_array_count;
    const int w = sweep.width, h = sweep.height, n = sweep.labels;
    const int views = int(sweep.views.size()), r = sweep.window_radius;
    const std::size_t plane = std::size_t(w) * h;
    CostVolume volume;
    volume.width = w;
    volume.height = h;
    volume.labels = n;
    volume.cost.resize(plane * std::size_t(n));
    std::vector<double> sum(plane * std::size_t(sub_arrays)),
        count(plane * std::size_t(sub_arrays));
    for (int i = 0; i < n; ++i) {
      std::fill(sum.begin(), sum.end(), 0.0);
      std::fill(count.begin(), count.end(), 0.0);
      for (int v = 0; v < views; ++v) {
        const ShiftedSweep::Read& read = sweep.reads[std::size_t(i) * views + v];
        scaled_ += read.scaled;
        for (int y = read.y_lo; y <= read.y_hi; ++y)
          for (int x = read.x_lo; x <= read.x_hi; ++x) {
            // The taps' first sample and weights: the shift's, or a scaled view's own at (x, y).
            int x0 = x + read.x0 - 1, y0 = y + read.y0 - 1;
            std::array<float, 4> wx = read.wx, wy = read.wy;
            if (read.scaled) {
              const double tx = read.ax * x + read.bx, ty = read.ay * y + read.by;
              x0 = int(std::floor(tx)) - 1;
              y0 = int(std::floor(ty)) - 1;
              wx = sweep::ReadWeights(tx - std::floor(tx), sweep.read_sigma);
              wy = sweep::ReadWeights(ty - std::floor(ty), sweep.read_sigma);
            }
            double value[kChannels] = {};
            for (int c = 0; c < kChannels; ++c) {
              for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) {
                  const int sy = std::clamp(y0 + j, 0, h - 1);
                  const int sx = std::clamp(x0 + k, 0, w - 1);
                  value[c] += double(wy[std::size_t(j)]) * wx[std::size_t(k)] *
                              sweep.views[std::size_t(v)][c * plane + std::size_t(sy) * w + sx];
                }
              value[c] /= sweep.packed_unit[std::size_t(c)];
            }
            const auto ref = [&](int c) {
              return double(sweep.reference[c * plane + std::size_t(y) * w + x]);
            };
            const double color = (std::abs(value[0] - ref(0)) + std::abs(value[1] - ref(1)) +
                                  std::abs(value[2] - ref(2))) /
                                 3.0;
            const double gradient = std::abs(value[3] - ref(3)) + std::abs(value[4] - ref(4));
            const double cost =
                sweep.color_weight * std::min<double>(color, sweep.color_cap) +
                sweep.gradient_weight * std::min<double>(gradient, sweep.gradient_cap);
            for (int g = 0; g < sub_arrays; ++g)
              if (sweep.sub_arrays[std::size_t(v)] >> g & 1) {
                sum[std::size_t(g) * plane + std::size_t(y) * w + x] += cost;
                count[std::size_t(g) * plane + std::size_t(y) * w + x] += 1.0;
              }
          }
      }
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          double best = INFINITY;
          double s[ShiftedSweep::kSubArrays] = {}, c[ShiftedSweep::kSubArrays] = {};
          bool quarter = false;
          for (int g = 0; g < sub_arrays; ++g) {
            for (int dy = -r; dy <= r; ++dy)
              for (int dx = -r; dx <= r; ++dx) {
                const std::size_t at = std::size_t(g) * plane +
                                       std::size_t(std::clamp(y + dy, 0, h - 1)) * w +
                                       std::size_t(std::clamp(x + dx, 0, w - 1));
                s[g] += sum[at];
                c[g] += count[at];
              }
            const double weight = g < kHalves ? 1.0 : sweep.quarter_weight;
            if (c[g] > sweep.min_count && weight * s[g] / c[g] < best) {
              best = weight * s[g] / c[g];
              quarter = g >= kHalves;
            }
          }
          // Where no half-array counts: the pairs of opposite half-arrays.
          if (!std::isfinite(best)) {
            for (int g = 0; g < kHalves / 2; ++g) {
              const double pair_count = c[g] + c[g + kHalves / 2];
              if (pair_count > sweep.pair_min_count)
                best = std::min(best, (s[g] + s[g + kHalves / 2]) / pair_count);
            }
            paired_ += std::isfinite(best);
          }
          uncounted_ += !std::isfinite(best);
          quarters_ += std::isfinite(best) && quarter;
          sub_array_count_ = sub_arrays;
          volume.at(x, y)[i] = std::isfinite(best)
                                   ? std::uint16_t(std::lround(best * CostVolume::kCostUnit))
                                   : sweep.most;
        }
    }
    return volume;
  }
  void RanOnCpu(const std::string& why) override { FAIL() << "not a shifted sweep: " << why; }
  int uncounted() const { return uncounted_; }
  int paired() const { return paired_; }
  int quarters() const { return quarters_; }  // costs a quarter-array gave
  int sub_array_count() const { return sub_array_count_; }
  int scaled() const { return scaled_; }  // the reads of views scaled as well as shifted

 private:
  int uncounted_ = 0, paired_ = 0, quarters_ = 0, sub_array_count_ = 0, scaled_ = 0;
};

// The window's radius and the views' reach.
class CostVolumeDefinition : public ::testing::TestWithParam<std::pair<int, int>> {};

// 220 rows (not a whole number of the sweep's bands), 9 planes (groups of unequal size), the
// reference off centre (views cut by the frame's edge), at window radii 0, 1 and 2 with the
// views 1 step around (the half-arrays alone: the quarter-arrays hold the same views), and at
// radius 1 with the views 2 steps around (the quarter-arrays too).
TEST_P(CostVolumeDefinition, TheSweepIsTheCostItsDefinitionGives) {
  const LightField lf = testing::TwoPlaneLightField(testing::TwoPlaneScene());
  CostVolumeOptions options;
  const auto [radius, reach] = GetParam();
  options.reach = reach;
  options.same_views_at_every_plane = true;
  options.window_radius = radius;
  const SweepViews views(lf, 1, 4, options);
  ASSERT_NE(views.height() % 8, 0);
  const std::vector<double> q = testing::SweepPlanes(9);
  const CostVolume swept = views.Sweep(q, 0.6);
  DefinitionEngine definition;
  const CostVolume direct = views.Sweep(q, 0.6, &definition);
  ASSERT_EQ(swept.cost.size(), direct.cost.size());
  int off = 0;
  for (std::size_t i = 0; i < swept.cost.size(); ++i) {
    const int d = std::abs(int(swept.cost[i]) - int(direct.cost[i]));
    ASSERT_LE(d, 1) << "sample " << i / q.size() << ", plane " << i % q.size();
    off += d != 0;
  }
  EXPECT_LT(double(off) / double(swept.cost.size()), 0.01);
  if (reach == 1) {
    EXPECT_EQ(definition.sub_array_count(), ShiftedSweep::kHalves);
    // Samples that no half-array counts, along the frame's edge, were met, and a pair of
    // opposite half-arrays counted at some of them.
    EXPECT_GT(definition.paired(), 0);
  } else {
    EXPECT_EQ(definition.sub_array_count(), ShiftedSweep::kSubArrays);
    EXPECT_GT(definition.quarters(), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(RadiusAndReach, CostVolumeDefinition,
                         ::testing::Values(std::pair{0, 1}, std::pair{1, 1}, std::pair{2, 1},
                                           std::pair{1, 2}));

// A calibrated array's cameras lie a millimetre or two off one plane, so each plane scales a
// view as well as shifting it: the CPU reads such views along each row in runs at one fraction
// (at most 1/256 of a sample from where each read belongs), the definition each sample at its
// own; the volumes agree to within what that moves a cost.
TEST(CostVolumeDefinitionOffPlane, ViewsScaledAsWellAsShiftedAreReadAsTheDefinitionGives) {
  const LightField lf = testing::TwoPlaneLightField(testing::TwoPlaneScene(), 2.0);
  CostVolumeOptions options;
  options.reach = 2;
  options.same_views_at_every_plane = true;
  options.window_radius = 1;
  const SweepViews views(lf, 3, 3, options);
  const std::vector<double> q = testing::SweepPlanes(9);
  const CostVolume swept = views.Sweep(q, 0.6);
  DefinitionEngine definition;
  const CostVolume direct = views.Sweep(q, 0.6, &definition);
  // Every view but those level with the reference is scaled (24 a plane).
  EXPECT_EQ(definition.scaled(), 24 * 9);
  ASSERT_EQ(swept.cost.size(), direct.cost.size());
  int off = 0, far_off = 0;
  for (std::size_t i = 0; i < swept.cost.size(); ++i) {
    const int d = std::abs(int(swept.cost[i]) - int(direct.cost[i]));
    off += d != 0;
    far_off += d > 4;
  }
  std::cout << "costs off the definition's: " << off << " of " << swept.cost.size()
            << ", by more than 4 units " << far_off << "\n";
  EXPECT_EQ(far_off, 0);
  EXPECT_LT(double(off) / double(swept.cost.size()), 0.05);  // (read in one run: 11%, and 4 far)
}

// An engine that keeps the reads it is given.
class RecordingEngine : public CostVolumeEngine {
 public:
  CostVolume Sweep(const ShiftedSweep& sweep) override {
    reads = sweep.reads;
    return {};
  }
  void RanOnCpu(const std::string& why) override { FAIL() << "not a shifted sweep: " << why; }
  std::vector<ShiftedSweep::Read> reads;
};

// What the silhouettes' visibility step and the occlusion order read (SweepViews::ReadShifts: a
// line in 1/D for each view's shift and scale) is where the sweep reads each view, to a
// hundredth of a sample, its cameras off one plane or not.
TEST(CostVolumeReadShifts, FollowTheSweepsReadsWithTheCamerasOffOnePlane) {
  // On one plane; off it; off it with the st-plane turned a thousandth of a radian from the
  // array's (a calibration's: each view bent a little too, still read as scaled).
  for (const auto& [off_plane_mm, turn_deg] :
       {std::pair{0.0, 0.0}, std::pair{2.0, 0.0}, std::pair{2.0, 0.06}}) {
    const LightField lf =
        testing::TwoPlaneLightField(testing::TwoPlaneScene(turn_deg), off_plane_mm);
    CostVolumeOptions options;
    options.reach = 2;
    const SweepViews views(lf, 3, 3, options);
    const std::vector<double> q = testing::SweepPlanes(5);
    RecordingEngine engine;
    views.Sweep(q, 0.5, &engine);
    const auto shifts = views.ReadShifts();
    ASSERT_TRUE(shifts.has_value()) << off_plane_mm;
    const int count = views.view_count();
    ASSERT_EQ(engine.reads.size(), q.size() * std::size_t(count));
    double worst = 0;
    int scaled = 0;
    for (std::size_t i = 0; i < q.size(); ++i)
      for (int v = 0; v < count; ++v) {
        const ShiftedSweep::Read& read = engine.reads[i * std::size_t(count) + std::size_t(v)];
        scaled += read.scaled;
        for (const double x : {0.0, 120.0, 239.0})
          for (const double y : {0.0, 219.0}) {
            const cv::Point2d at = (*shifts)[std::size_t(v)].At(x, y, q[i]);
            // The sweep's read: the shift's whole-sample offset and its fraction (the weights
            // are Keys' here: where their centre of mass lies), or a scaled view's own mapping.
            const double sx = read.scaled
                                  ? read.ax * x + read.bx
                                  : x + read.x0 + (read.wx[2] + 2 * read.wx[3] - read.wx[0]);
            const double sy = read.scaled
                                  ? read.ay * y + read.by
                                  : y + read.y0 + (read.wy[2] + 2 * read.wy[3] - read.wy[0]);
            worst = std::max({worst, std::abs(at.x - sx), std::abs(at.y - sy)});
          }
      }
    std::cout << "cameras " << off_plane_mm << " mm off one plane, the st-plane turned " << turn_deg
              << " degrees: the reads " << worst << " samples apart at most\n";
    EXPECT_EQ(scaled > 0, off_plane_mm > 0);
    // Shifts are lines in 1/D exactly; a scaled view's scale and shift are only to first order
    // in its camera's offset (the reads 60 samples apart at reach 2: a hundredth of a sample).
    EXPECT_LT(worst, off_plane_mm > 0 ? 0.02 : 1e-6);
  }
}

TEST(CostVolumeColour, TheViewsPackedColourReadsAsTheirFloatColour) {
  // The silhouettes' visibility step reads the views' own 16-bit planes where the sweep reads
  // them unblurred: every bilinear read the same float as from Colour(i)'s copy, bit for bit.
  const LightField lf = testing::TwoPlaneLightField(testing::TwoPlaneScene());
  CostVolumeOptions options;
  options.reach = 1;
  const SweepViews views(lf, 3, 3, options);
  ASSERT_GT(views.view_count(), 0);
  const float scale = float(1.0 / SweepViews::kPackedColour);
  cv::RNG rng(7);
  int reads = 0, differing = 0;
  double spread = 0;
  for (int i = 0; i < views.view_count(); ++i) {
    const std::array<cv::Mat, 3> colour = views.Colour(i), packed = views.PackedColour(i);
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_EQ(packed[c].type(), CV_16SC1);
      ASSERT_EQ(packed[c].size(), colour[c].size());
      double lo = 0, hi = 0;
      cv::minMaxLoc(colour[c], &lo, &hi);
      spread = std::max(spread, hi - lo);
    }
    const int cols = colour[0].cols, rows = colour[0].rows;
    for (int k = 0; k < 600; ++k) {
      // Anywhere on the planes, their last row and column too, and a little beyond (refused).
      const double x = rng.uniform(-0.5, cols - 0.5), y = rng.uniform(-0.5, rows - 0.5);
      float from_float[3] = {-1, -1, -1}, from_packed[3] = {-1, -1, -1};
      const bool inside = BilinearAt3<float>(colour, x, y, 1.0f, from_float);
      ASSERT_EQ(BilinearAt3<std::int16_t>(packed, x, y, scale, from_packed), inside);
      if (!inside) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        ++reads;
        differing += from_float[c] != from_packed[c];
      }
    }
  }
  EXPECT_GT(spread, 0.2);  // the views have texture: the reads tell values apart
  EXPECT_GT(reads, 1000);
  EXPECT_EQ(differing, 0) << "of " << reads;
}

// An engine that takes no sweep (as a GPU refuses one beyond its texture limits).
class RefusingEngine : public CostVolumeEngine {
 public:
  CostVolume Sweep(const ShiftedSweep&) override {
    ADD_FAILURE() << "a refused sweep was handed over";
    return {};
  }
  std::string Refuses(const ShiftedSweep& sweep) const override {
    return "too large for it: " + std::to_string(sweep.height) + " rows";
  }
  void RanOnCpu(const std::string& why) override { reasons.push_back(why); }
  std::vector<std::string> reasons;
};

TEST(CostVolumeEngineChoice, ASweepTheEngineRefusesRunsOnTheCpuAndItIsToldWhy) {
  const LightField lf = testing::TwoPlaneLightField(testing::TwoPlaneScene());
  CostVolumeOptions options;
  options.reach = 1;
  const SweepViews views(lf, 3, 3, options);
  const std::vector<double> q = testing::SweepPlanes(6);
  RefusingEngine engine;
  const CostVolume refused = views.Sweep(q, 0.5, &engine);
  EXPECT_EQ(refused.cost, views.Sweep(q, 0.5).cost);
  ASSERT_EQ(engine.reasons.size(), 1u);
  EXPECT_EQ(engine.reasons[0], "too large for it: " + std::to_string(views.height()) + " rows");
}

}  // namespace
}  // namespace lfcam
