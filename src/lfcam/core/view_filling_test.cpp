// Which views a light field records as filled from their neighbours: the build's and the
// import's lists, today's objects and older imports' labels, and entries of no use passed over.
#include "lfcam/core/view_filling.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace lfcam::view_filling_test {
namespace {

using Views = std::vector<std::pair<int, int>>;

LightField Grid3x4(nlohmann::json metadata) {
  Slab slab;
  slab.uv.rows = 3;
  slab.uv.cols = 4;
  slab.uv.p_ca = Vec3(0, 0, 3000);
  LightField lf({3, 4, 8, 6}, SampleType::kSrgb8, slab);
  lf.metadata() = std::move(metadata);
  return lf;
}

TEST(FilledViews, TheBuildsAndTheImportsListsInEitherForm) {
  EXPECT_EQ(FilledViews(Grid3x4({})), Views{});
  EXPECT_EQ(FilledViews(Grid3x4({{"filled_views", nlohmann::json::array()}})), Views{});
  // The build's list.
  EXPECT_EQ(FilledViews(Grid3x4(
                {{"filled_views", {{{"row", 1}, {"col", 2}, {"from", {{0, 2}, {2, 2}}}}}}})),
            (Views{{1, 2}}));
  // An import's, as objects (today) and as the labels older imports wrote.
  EXPECT_EQ(FilledViews(Grid3x4(
                {{"import", {{"filled_views", {{{"row", 0}, {"col", 3}, {"from", {{0, 2}}}}}}}}})),
            (Views{{0, 3}}));
  EXPECT_EQ(
      FilledViews(Grid3x4(
          {{"import",
            {{"filled_views",
              {FilledViewLabel(2, 0, {{1, 0}, {2, 1}}), FilledViewLabel(0, 0, {{0, 1}})}}}}})),
      (Views{{2, 0}, {0, 0}}));
  // Entries of another shape, or outside the grid, are passed over.
  EXPECT_EQ(FilledViews(Grid3x4({{"import",
                                  {{"filled_views",
                                    {"camera (9, 9) from (0, 0)",
                                     "not a label",
                                     7,
                                     {{"row", "1"}, {"col", 1}},
                                     {{"row", -1}, {"col", 0}},
                                     {{"row", 2}, {"col", 3}}}}}}})),
            (Views{{2, 3}}));
  EXPECT_EQ(FilledViews(Grid3x4({{"import", "imported"}, {"filled_views", "none"}})), Views{});
}

}  // namespace
}  // namespace lfcam::view_filling_test
