// The table's row weights blended node by node against the scalar sum written out, to the last
// bit, on every instruction set Highway compiled that this machine runs.
#include "lfcam/render/table_node_blend.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "lfcam/core/instruction_sets_for_tests.h"

namespace lfcam {
namespace {

TEST(TableNodeBlend, IsTheScalarSumToTheLastBitOnEveryInstructionSet) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  constexpr int kWidth = 77, kCameras = 6;
  constexpr std::size_t kStride = 80;  // a row's weights, as a caller pads them
  // Runs of 1 to 40 pixels, ending anywhere within a vector.
  const std::vector<int> run_begin = {0, 1, 5, 21, 22, 40, 63, kWidth};
  const int runs = int(run_begin.size()) - 1;
  // Camera 0 written over every run, 1 over the middle runs, 2 over one, 3 not at all, 4 over
  // runs whose nodes weigh nothing (zeros written), 5 over the last run alone.
  const std::vector<int> first_run = {0, 2, 4, -1, 1, runs - 1};
  const std::vector<int> last_run = {runs - 1, 5, 4, -1, 2, runs - 1};
  for (const int nodes : {4, 8}) {
    SCOPED_TRACE(nodes);
    std::vector<float> coefficients(std::size_t(nodes) * kWidth + kTableNodeRowPadding);
    for (float& c : coefficients) c = unit(rng);
    std::vector<float> values(std::size_t(kCameras) * std::size_t(runs) * std::size_t(nodes));
    for (float& v : values) v = unit(rng) < 0.3f ? 0.0f : unit(rng) * 1e-3f;
    for (int r = 1; r <= 2; ++r)
      for (int n = 0; n < nodes; ++n)
        values[(std::size_t(4) * std::size_t(runs) + std::size_t(r)) * std::size_t(nodes) +
               std::size_t(n)] = 0.0f;
    TableNodeRow row;
    row.cameras = kCameras;
    row.runs = runs;
    row.nodes = nodes;
    row.run_begin = run_begin.data();
    row.first_run = first_run.data();
    row.last_run = last_run.data();
    row.values = values.data();
    row.coefficients = coefficients.data();
    row.coefficient_stride = kWidth;
    for (const std::int64_t target : testing::InstructionSetsThisMachineRuns()) {
      hwy::SetSupportedTargetsForTest(target);
      SCOPED_TRACE(hwy::TargetName(target));
      constexpr float kUnwritten = -7.0f;
      std::vector<float> weights(kCameras * kStride, kUnwritten);
      BlendTableNodes(row, weights.data(), kStride);
      for (int c = 0; c < kCameras; ++c)
        for (int i = 0; i < int(kStride); ++i) {
          const float got = weights[std::size_t(c) * kStride + std::size_t(i)];
          int r = 0;
          while (i < kWidth && run_begin[std::size_t(r) + 1] <= i) ++r;
          if (i >= kWidth || first_run[std::size_t(c)] < 0 || r < first_run[std::size_t(c)] ||
              r > last_run[std::size_t(c)]) {
            ASSERT_EQ(got, kUnwritten) << "camera " << c << " pixel " << i;
            continue;
          }
          float sum = 0.0f;
          for (int n = 0; n < nodes; ++n) {
            const float product =
                values[(std::size_t(c) * std::size_t(runs) + std::size_t(r)) * std::size_t(nodes) +
                       std::size_t(n)] *
                coefficients[std::size_t(n) * kWidth + std::size_t(i)];
            sum += product;
          }
          ASSERT_EQ(got, sum) << "camera " << c << " pixel " << i << " run " << r;
          if (c == 4) {
            EXPECT_EQ(got, 0.0f);
          }
        }
    }
    hwy::SetSupportedTargetsForTest(0);
  }
}

}  // namespace
}  // namespace lfcam
