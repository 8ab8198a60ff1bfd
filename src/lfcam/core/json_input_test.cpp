#include "lfcam/core/json_input.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

using testing::ErrorOf;

TEST(JsonInput, NestingDepthSkipsStringsAndEscapes) {
  EXPECT_EQ(JsonNestingDepth("1"), 0);
  EXPECT_EQ(JsonNestingDepth("[[{}]]"), 3);
  EXPECT_EQ(JsonNestingDepth(R"({"a": "[[[[", "b": [1]})"), 2);
  EXPECT_EQ(JsonNestingDepth(R"(["\"[[[", ["x"]])"), 2);
  EXPECT_EQ(JsonNestingDepth(R"(["\\", [[]]])"), 3);  // an escaped backslash ends the string
}

TEST(JsonInput, DeepOrHugeDocumentsAreRefusedBeforeParsing) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  EXPECT_NE(ErrorOf([&] { ParseJsonBounded(deep, "f.json"); }).find("f.json: JSON nests 200000"),
            std::string::npos);
  EXPECT_NO_THROW(ParseJsonBounded(std::string(64, '[') + std::string(64, ']'), "f"));
  EXPECT_THROW(ParseJsonBounded(std::string(65, '[') + std::string(65, ']'), "f"), Error);
  const std::string huge(kMaxJsonBytes + 1, ' ');
  EXPECT_NE(ErrorOf([&] { ParseJsonBounded(huge, "big.json"); }).find("larger than the limit"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseJsonBounded("{\"a\": ", "cut.json"); }).find("cut.json: malformed"),
            std::string::npos);
}

TEST(JsonInput, IntegersAreExactAndInRange) {
  const auto j = nlohmann::json::parse(
      R"({"ok": 12, "wrapped": 4294967306, "fraction": 10.7, "whole_float": 10.0, "neg": -1,
          "text": "10", "flag": true, "huge": 18446744073709551615, "null": null})");
  EXPECT_EQ(JsonInteger(j, "ok", 1, 100, "w"), 12);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "wrapped", 1, 65536, "w"); }).find("4294967306, outside"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "fraction", 1, 65536, "w"); }).find("whole number"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "whole_float", 1, 65536, "w"); }).find("whole number"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "neg", 1, 65536, "w"); }).find("-1, outside"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "text", 1, 65536, "w"); }).find("whole number"),
            std::string::npos);
  EXPECT_THROW(JsonInteger(j, "flag", 0, 1, "w"), Error);
  EXPECT_THROW(JsonInteger(j, "huge", 0, INT64_MAX, "w"), Error);
  EXPECT_EQ(JsonUnsigned(j, "huge", UINT64_MAX, "w"), UINT64_MAX);
  EXPECT_NE(ErrorOf([&] { JsonUnsigned(j, "neg", 10, "w"); }).find("negative"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { JsonInteger(j, "absent", 0, 1, "where"); }).find("where: missing field"),
            std::string::npos);
  EXPECT_THROW(JsonNumber(j, "null", "w"), Error);
  EXPECT_THROW(JsonString(j, "ok", "w"), Error);
  EXPECT_THROW(JsonVec3(j, "ok", "w"), Error);
  EXPECT_THROW(JsonField(nlohmann::json::array(), "x", "w"), Error);
}

// Regression (json_input_fuzz): a number beyond a double's range threw nlohmann's out_of_range
// instead of lfcam::Error.
TEST(JsonInput, NumbersOutOfRangeAreRefused) {
  EXPECT_NE(ErrorOf([] {
              ParseJsonBounded("[1468474473709e551615]", "n.json");
            }).find("n.json: JSON holds a number out of range"),
            std::string::npos);
  EXPECT_THROW(ParseJsonBounded("{\"a\": -1e400}", "n.json"), Error);
}

// Random documents built from JSON's own pieces: each parses or is refused with lfcam::Error.
TEST(JsonInput, RandomDocumentsParseOrAreRefusedCleanly) {
  const char* pieces[] = {"[", "]",  "{",  "}",    "\"",   "\\",    ":", ",",    "1",
                          "-", "e9", ".5", "true", "null", "\"k\"", " ", "\xff", "\"\\u00"};
  std::mt19937 rng(5);
  const int refused = testing::CountRefused(
      3000,
      [&](int) {
        std::string text;
        const int n = 1 + int(rng() % 200);
        for (int i = 0; i < n; ++i) text += pieces[rng() % std::size(pieces)];
        return text;
      },
      [](const std::string& text) { ParseJsonBounded(text, "random"); });
  EXPECT_GT(refused, 2000);
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

TEST(JsonInput, FormatAndVersionHeadersAreChecked) {
  EXPECT_EQ(JsonFormatVersion({{"format", "lfcam-x"}, {"version", 2}}, "lfcam-x", 3, "x", "f"), 2);
  EXPECT_THROW(JsonFormatVersion({{"format", "other"}, {"version", 1}}, "lfcam-x", 3, "x", "f"),
               Error);
  EXPECT_THROW(JsonFormatVersion({{"format", "lfcam-x"}, {"version", 4}}, "lfcam-x", 3, "x", "f"),
               Error);
  EXPECT_THROW(JsonFormatVersion({{"format", "lfcam-x"}, {"version", 0}}, "lfcam-x", 3, "x", "f"),
               Error);
  EXPECT_THROW(JsonFormatVersion(nlohmann::json::array(), "lfcam-x", 3, "x", "f"), Error);
}

}  // namespace
}  // namespace lfcam
