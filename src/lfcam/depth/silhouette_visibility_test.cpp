// The silhouettes re-decided by visibility (depth/silhouette_visibility.h): its views' costs
// summed alike whatever order the threads take the views in. Its effect on the maps is measured
// where the estimator's is (DepthOnABenchmarkLikeScene.*, docs/depth.md, "Visibility at the
// silhouettes"). A refinement of a small scene in arenas of 1 to 7 threads gave the same map with
// floating-point sums too (the near ties are rare: one sample of a full-size view in 1.4
// million), so the sums themselves are what is tested.
#include "lfcam/depth/silhouette_visibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace lfcam {
namespace {

// Costs as the views give them, summed in every order a parallel loop might take them in: split
// among threads at any points, each thread's own views in any order, the threads' sums added.
TEST(CostSums, AreTheSameWhateverTheOrderTheCostsComeIn) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> cost(0.0, 0.1);
  std::vector<double> costs(80);
  for (double& c : costs) c = cost(random);
  long double exact = 0;
  for (const double c : costs) exact += c;
  CostSum first;
  double first_double = 0;
  int doubles_differ = 0;
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::shuffle(order.begin(), order.end(), random);
    const std::size_t split = std::uniform_int_distribution<std::size_t>(0, costs.size())(random);
    CostSum threads[2];
    double doubles[2] = {0, 0};
    for (std::size_t i = 0; i < order.size(); ++i) {
      threads[i < split ? 0 : 1].Add(costs[order[i]]);
      doubles[i < split ? 0 : 1] += costs[order[i]];
    }
    CostSum total = threads[trial % 2];
    total += threads[1 - trial % 2];
    const double total_double = doubles[trial % 2] + doubles[1 - trial % 2];
    if (trial == 0) {
      first = total;
      first_double = total_double;
    }
    EXPECT_EQ(total.units, first.units) << "order " << trial;
    doubles_differ += total_double != first_double;
    EXPECT_NEAR(total.value(), double(exact), 1e-8);
  }
  // What the fixed point is for: the same costs summed as doubles differ in their last bits.
  EXPECT_GT(doubles_differ, 0);
}

}  // namespace
}  // namespace lfcam
