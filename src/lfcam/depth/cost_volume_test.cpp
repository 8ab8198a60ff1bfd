// The CPU's plane sweep (SweepViews::Sweep: planes in groups, a band of rows at a time, counts
// from the views' rectangles) against the cost volume's definition evaluated directly, sample by
// sample, from the same reads: every view read with Keys' weights at its shift, each term
// truncated and weighted, averaged over each half-array and its window (the frame's edge
// repeated), the cheapest half-array that enough views see.
#include "lfcam/depth/cost_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "lfcam/depth/depth_test_scene.h"

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
        for (int y = read.y_lo; y <= read.y_hi; ++y)
          for (int x = read.x_lo; x <= read.x_hi; ++x) {
            double value[kChannels] = {};
            for (int c = 0; c < kChannels; ++c) {
              for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) {
                  const int sy = std::clamp(y + read.y0 - 1 + j, 0, h - 1);
                  const int sx = std::clamp(x + read.x0 - 1 + k, 0, w - 1);
                  value[c] += double(read.wy[std::size_t(j)]) * read.wx[std::size_t(k)] *
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

 private:
  int uncounted_ = 0, paired_ = 0, quarters_ = 0, sub_array_count_ = 0;
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
