#include "lfcam/session/board.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

TEST(BoardSpec, ParsesInnerCornersAndSquare) {
  const BoardSpec b = ParseBoardSpec("10x7@30");
  EXPECT_EQ(b.cols, 10);
  EXPECT_EQ(b.rows, 7);
  EXPECT_DOUBLE_EQ(b.square_mm, 30.0);
  EXPECT_DOUBLE_EQ(b.width_mm(), 330.0);
  EXPECT_DOUBLE_EQ(b.height_mm(), 240.0);
  EXPECT_EQ(b.corner_count(), 70);
  EXPECT_EQ(ParseBoardSpec("11x10@25.5").square_mm, 25.5);
  EXPECT_EQ(ParseBoardSpec(b.spec()), b);
}

TEST(BoardSpec, RefusesWhatIsNotABoard) {
  for (const char* text : {"", "10x7", "10@30", "10x7@", "x7@30", "10x7@30mm", "10x7@-3",
                           "10x7@nan", "10x7@inf", "1x8@30", "300x7@30", "10 x7@30", "10x7@0"})
    EXPECT_THROW(ParseBoardSpec(text), Error) << text;
  // Both counts even (or both odd): the board looks the same turned by 180 degrees.
  const std::string message = testing::ErrorOf([] { ParseBoardSpec("10x8@30"); });
  EXPECT_NE(message.find("one count must be odd"), std::string::npos) << message;
  EXPECT_THROW(ParseBoardSpec("9x7@30"), Error);
}

TEST(BoardSpec, CornerOrderAndColours) {
  const BoardSpec b{4, 3, 10.0};
  const auto corners = b.corners();
  ASSERT_EQ(corners.size(), 12u);
  EXPECT_EQ(corners[0], Vec3(10, 10, 0));  // (i, j) = (0, 0)
  EXPECT_EQ(corners[1], Vec3(20, 10, 0));  // along x first
  EXPECT_EQ(corners[4], Vec3(10, 20, 0));  // then up a row
  EXPECT_EQ(corners[11], Vec3(40, 30, 0));
  EXPECT_TRUE(b.black_at(5, 5));  // the bottom-left square is black
  EXPECT_FALSE(b.black_at(15, 5));
  EXPECT_TRUE(b.black_at(15, 15));
  EXPECT_FALSE(b.black_at(45, 35));  // the top-right square: 4 + 3 odd, white
}

TEST(BoardSpec, JsonRoundTripAndBadFields) {
  const BoardSpec b = ParseBoardSpec("11x10@50");
  EXPECT_EQ(BoardFromJson(BoardToJson(b), "board"), b);
  nlohmann::json j = BoardToJson(b);
  j["type"] = "charuco";
  EXPECT_THROW(BoardFromJson(j, "board"), Error);
  j = BoardToJson(b);
  j["inner_corners"] = {11, 10.5};
  EXPECT_THROW(BoardFromJson(j, "board"), Error);
  j = BoardToJson(b);
  j["square_mm"] = -1;
  EXPECT_THROW(BoardFromJson(j, "board"), Error);
}

}  // namespace
}  // namespace lfcam
