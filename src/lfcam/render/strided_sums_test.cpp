// The strided prefilter's vectorised sums against the sums written out, on every instruction set
// Highway compiled that this machine runs.
#include "lfcam/render/strided_sums.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "lfcam/core/instruction_sets_for_tests.h"

namespace lfcam {
namespace {

TEST(StridedSums, AreTheSumsWrittenOutOnEveryInstructionSet) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> values(40000);
  for (float& v : values) v = unit(rng);
  for (const std::int64_t target : testing::InstructionSetsThisMachineRuns()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    for (const int count : {1, 3, 8, 13}) {
      std::vector<float> weights(static_cast<std::size_t>(count));
      for (float& w : weights) w = unit(rng);
      // Rows of lengths that end mid-vector, each row somewhere else in `values`.
      for (const std::size_t n :
           {std::size_t(1), std::size_t(7), std::size_t(100), std::size_t(1111)}) {
        std::vector<const float*> rows;
        for (int i = 0; i < count; ++i)
          rows.push_back(values.data() + 997 * std::size_t(i) + n % 5);
        std::vector<float> out(n + 1, -7.0f);
        WeightedRowSum(rows.data(), weights.data(), count, n, out.data());
        for (std::size_t j = 0; j < n; ++j) {
          float sum = 0;
          for (int i = 0; i < count; ++i) sum += weights[std::size_t(i)] * rows[std::size_t(i)][j];
          ASSERT_NEAR(out[j], sum, 1e-5f)
              << "row value " << j << " of " << n << ", " << count << " rows";
        }
        EXPECT_EQ(out[n], -7.0f);  // nothing written past the row
      }
      // Kept every `stride` samples of three channels, over more than one of its blocks.
      for (const int stride : {1, 3, 7, 31})
        for (const std::size_t n :
             {std::size_t(1), std::size_t(5), std::size_t(200), std::size_t(401)}) {
          if (3 * (std::size_t(stride) * (n - 1) + std::size_t(count)) > values.size()) continue;
          std::vector<float> out(3 * n + 1, -7.0f);
          StridedTapSum(values.data() + 2, weights.data(), count, stride, n, out.data());
          for (std::size_t k = 0; k < n; ++k)
            for (int c = 0; c < 3; ++c) {
              float sum = 0;
              for (int i = 0; i < count; ++i)
                sum += weights[std::size_t(i)] *
                       values[2 + 3 * (std::size_t(stride) * k + std::size_t(i)) + std::size_t(c)];
              ASSERT_NEAR(out[3 * k + std::size_t(c)], sum, 1e-5f)
                  << "kept sample " << k << " channel " << c << ", stride " << stride;
            }
          EXPECT_EQ(out[3 * n], -7.0f);
        }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace lfcam
