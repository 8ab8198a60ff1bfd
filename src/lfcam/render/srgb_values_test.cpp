// The vectorised sRGB conversions against the tables they stand for, value for value, on every
// instruction set Highway compiled that this machine runs.
#include "lfcam/render/srgb_values.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "lfcam/core/color.h"
#include "lfcam/core/instruction_sets_for_tests.h"

namespace lfcam {
namespace {

TEST(SrgbValues, DecodeAndEncodeAsTheTablesDoOnEveryInstructionSet) {
  // Every code, in runs that end mid-vector (the scalar tails) and start anywhere.
  std::vector<std::uint8_t> codes;
  for (int repeat = 0; repeat < 3; ++repeat)
    for (int v = 0; v < 256; ++v) codes.push_back(std::uint8_t((v * 37 + repeat) % 256));
  // Linear values where the encoding table's index steps (a half-step each side, and the floats
  // next to them), everything beyond [0, 1], NaN, and random values.
  std::vector<float> linear;
  for (int i = 0; i < 65536; i += 7) {
    const float edge = (float(i) + 0.5f) / 65535.0f;
    linear.push_back(edge);
    linear.push_back(std::nextafter(edge, 0.0f));
    linear.push_back(std::nextafter(edge, 2.0f));
  }
  for (const float v :
       {-1.0f, -0.0f, 0.0f, 1.0f, 1.5f, 1e30f, -std::numeric_limits<float>::infinity(),
        std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(), 1e-30f})
    linear.push_back(v);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
  for (int i = 0; i < 20000; ++i) linear.push_back(unit(rng));
  const auto& decode = SrgbDecodeTable();
  const auto& encode = LinearToSrgb8EncodeTable();
  for (const std::int64_t target : testing::InstructionSetsThisMachineRuns()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    for (const std::size_t start : {std::size_t(0), std::size_t(3), std::size_t(17)}) {
      const std::size_t n = codes.size() - start - 5;
      std::vector<float> decoded(n + 1, -7.0f);
      DecodeSrgbValues(codes.data() + start, n, decoded.data());
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(decoded[i], decode[codes[start + i]]) << "code " << int(codes[start + i]);
      EXPECT_EQ(decoded[n], -7.0f);  // nothing written past the run
      // Computed, not looked up: within 4.7e-6 of the table, so within 0.02 of a level of the
      // code once encoded exactly again.
      std::fill(decoded.begin(), decoded.end(), -7.0f);
      DecodeSrgbValuesComputed(codes.data() + start, n, decoded.data());
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_NEAR(decoded[i], decode[codes[start + i]], 4.7e-6)
            << "code " << int(codes[start + i]);
        ASSERT_NEAR(255.0 * LinearToSrgb(decoded[i]), codes[start + i], 0.02)
            << "code " << int(codes[start + i]);
      }
      EXPECT_EQ(decoded[n], -7.0f);
      const std::size_t m = linear.size() - start - 3;
      std::vector<std::uint8_t> encoded(m + 1, 77);
      EncodeSrgbValues(linear.data() + start, m, encoded.data());
      int differ = 0;
      for (std::size_t i = 0; i < m; ++i)
        differ += encoded[i] != LinearToSrgb8With(encode, linear[start + i]);
      EXPECT_EQ(differ, 0);
      EXPECT_EQ(encoded[m], 77);
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace lfcam
