// The silhouettes re-decided by visibility (depth/silhouette_visibility.h): its views' costs
// summed alike whatever order the threads take the views in. Its effect on the maps is measured
// where the estimator's is (DepthOnABenchmarkLikeScene.*, docs/depth.md, "Visibility at the
// silhouettes"). A refinement of a small scene in arenas of 1 to 7 threads gave the same map with
// floating-point sums too (the near ties are rare: one sample of a full-size view in 1.4
// million), so the sums themselves are what is tested; and which of the samples whose far depth
// matched better the far side reaches.
#include "lfcam/depth/silhouette_visibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
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

// A near square (label 10) on a far wall (label 50) of a 12 x 12 map. Samples that would move
// to the wall: a band two deep along the square's left edge, a sample alone in its middle, and a
// pair in it; and one on the right edge that would move farther than the wall beside it, by more
// than the edge's threshold.
TEST(SilhouetteVisibility, MovesOnlyTheSamplesTheFarSideReaches) {
  const float kNear = 10, kWall = 50, kEdge = 2;
  cv::Mat label(12, 12, CV_32F, cv::Scalar(kWall));
  label(cv::Rect(3, 3, 6, 6)).setTo(kNear);
  cv::Mat far(12, 12, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  far(cv::Rect(3, 3, 2, 6)).setTo(kWall);      // the band: columns 3 and 4
  far.at<float>(5, 6) = kWall;                 // alone, two samples in from the band
  far(cv::Rect(6, 7, 2, 1)).setTo(kWall - 1);  // the pair, within the threshold of the wall
  far.at<float>(4, 8) = kWall + 3 * kEdge;     // farther than the wall beside it
  const cv::Mat reached = ReachedByTheFarSide(label, far, kEdge);
  ASSERT_EQ(reached.type(), CV_8U);
  ASSERT_EQ(reached.size(), label.size());
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const bool band = x >= 3 && x <= 4 && y >= 3 && y <= 8;
      EXPECT_EQ(reached.at<unsigned char>(y, x) != 0, band) << "at x " << x << ", y " << y;
    }

  // The lone sample and the pair, once the band has moved (the next pass's map), are reached
  // through the samples between them and the wall only when those move too.
  far(cv::Rect(3, 3, 2, 6)).copyTo(label(cv::Rect(3, 3, 2, 6)));
  far.at<float>(5, 5) = kWall;
  far(cv::Rect(5, 7, 1, 1)).setTo(kWall + 1);  // farther than the pair: reaches it
  cv::Mat after(12, 12, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  for (const cv::Point at :
       {cv::Point(5, 5), cv::Point(6, 5), cv::Point(5, 7), cv::Point(6, 7), cv::Point(7, 7)})
    after.at<float>(at) = far.at<float>(at);
  const cv::Mat next = ReachedByTheFarSide(label, after, kEdge);
  EXPECT_EQ(cv::countNonZero(next), 5);
  for (const cv::Point at :
       {cv::Point(5, 5), cv::Point(6, 5), cv::Point(5, 7), cv::Point(6, 7), cv::Point(7, 7)})
    EXPECT_TRUE(next.at<unsigned char>(at)) << "at " << at;

  // A chain reaches only as far as each step's depth reaches the next's target (less the
  // threshold): a sample beyond one that moves to a much nearer depth is not reached through it.
  cv::Mat chain(12, 12, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  chain.at<float>(6, 5) = kWall;
  chain.at<float>(6, 6) = kWall - 3 * kEdge;
  chain.at<float>(6, 7) = kWall;
  const cv::Mat steps = ReachedByTheFarSide(label, chain, kEdge);
  EXPECT_TRUE(steps.at<unsigned char>(6, 5));
  EXPECT_TRUE(steps.at<unsigned char>(6, 6));
  EXPECT_FALSE(steps.at<unsigned char>(6, 7));
}

// The far side's depth under a sample on a near object's edge: the plane its far-side neighbours
// lie on, continued to the sample, where the window's farthest label (the caller's fallback) is a
// sample off and the far side's mean short of it.
TEST(SilhouetteVisibility, TakesTheFarSidesPlaneUnderAnEdgeSample) {
  const float kNear = 10, kEdge = 2, kBeyond = kNear + kEdge;
  // A straight edge between columns 4 and 5, the far side a floor rising 2 labels a row: the
  // sample's own row's far value, not its window's farthest (54) nor, with no slope across the
  // edge to read, anything but its column's.
  cv::Mat floor(12, 12, CV_32F, cv::Scalar(kNear));
  for (int y = 0; y < 12; ++y)
    for (int x = 5; x < 12; ++x) floor.at<float>(y, x) = 40.0f + 2.0f * float(y);
  EXPECT_NEAR(FarSidePlaneAt(floor, 4, 6, kBeyond, 54, kEdge), 52.0, 1e-4);
  // A diagonal edge (the near side where x + y <= 8), the far side a ramp rising 3 labels a
  // column: at (4, 4) its plane gives 52; the three far neighbours' mean is 54, their farthest 55.
  cv::Mat ramp(12, 12, CV_32F);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x)
      ramp.at<float>(y, x) = x + y <= 8 ? kNear : 40.0f + 3.0f * float(x);
  const float at_ramp = FarSidePlaneAt(ramp, 4, 4, kBeyond, 55, kEdge);
  EXPECT_GT(at_ramp, 52.0f - 0.5f);
  EXPECT_LT(at_ramp, 54.0f - 0.5f);
  // Fewer than three far neighbours (a near object's corner): the caller's farthest.
  cv::Mat corner(12, 12, CV_32F, cv::Scalar(kNear));
  corner.at<float>(5, 5) = 50;
  corner.at<float>(5, 6) = 50;
  EXPECT_EQ(FarSidePlaneAt(corner, 4, 4, kBeyond, 50, kEdge), 50.0f);
  // A plane that would put the sample on the near side: the farthest. The far side 13 + 30 (x +
  // y - 9) past the diagonal, its plane about 7 at (4, 4).
  cv::Mat towards_near(12, 12, CV_32F);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x)
      towards_near.at<float>(y, x) = x + y <= 8 ? kNear : 13.0f + 30.0f * float(x + y - 9);
  EXPECT_EQ(FarSidePlaneAt(towards_near, 4, 4, kBeyond, 43, kEdge), 43.0f);
  // One past the farthest label (50) by more than the edge's threshold: the farthest plus the
  // threshold. The far side 80 - 6 x past the diagonal, its plane about 54 at (4, 4).
  cv::Mat past_farthest(12, 12, CV_32F);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x)
      past_farthest.at<float>(y, x) = x + y <= 8 ? kNear : 80.0f - 6.0f * float(x);
  EXPECT_EQ(FarSidePlaneAt(past_farthest, 4, 4, kBeyond, 50, kEdge), 50.0f + kEdge);
}

}  // namespace
}  // namespace lfcam
