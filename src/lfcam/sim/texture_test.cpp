#include "lfcam/sim/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace lfcam {
namespace {

// The noise as first written (std::floor, each corner hashed on its own): the simulator's
// scenes, and every figure measured on them, rest on these exact values.
std::uint32_t HashAsDefined(std::int64_t x, std::int64_t y, std::uint32_t seed) {
  std::uint64_t h = std::uint64_t(x) * 0x9E3779B97F4A7C15ull ^
                    std::uint64_t(y) * 0xC2B2AE3D27D4EB4Full ^ (std::uint64_t(seed) << 32);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return std::uint32_t(h);
}

double NoiseAsDefined(const Vec2& p, unsigned seed) {
  double sum = 0, amplitude = 0.5, norm = 0;
  Vec2 q = p;
  for (int octave = 0; octave < 4; ++octave) {
    const unsigned s = seed + unsigned(octave) * 101u;
    const double fx = std::floor(q.x()), fy = std::floor(q.y());
    const auto x = std::int64_t(fx), y = std::int64_t(fy);
    const auto smooth = [](double t) { return t * t * (3 - 2 * t); };
    const double tx = smooth(q.x() - fx), ty = smooth(q.y() - fy);
    const auto lattice = [&](std::int64_t i, std::int64_t j) {
      return HashAsDefined(i, j, s) * (1.0 / 4294967295.0);
    };
    const double a = lattice(x, y), b = lattice(x + 1, y);
    const double c = lattice(x, y + 1), d = lattice(x + 1, y + 1);
    sum += amplitude * ((a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty);
    norm += amplitude;
    amplitude *= 0.5;
    q *= 2.03;
  }
  return sum / norm;
}

TEST(FractalNoise, IsItsDefinitionToTheLastBit) {
  // Whole and half numbers of both signs, signed zeros, values just either side of an integer,
  // and a spread of points far from the origin: where a floor computed another way could differ.
  const double specials[] = {
      0.0,  -0.0, 1.0,    -1.0,    0.5,    -0.5,    2.999999999999,
      -3.0, -3.5, 1e-300, -1e-300, 123.25, -987.75, std::nextafter(-7.0, 0.0),
      1e9,  -1e9, 4.5e12, -4.5e12};
  int compared = 0;
  for (double x : specials)
    for (double y : specials) {
      for (unsigned seed : {0u, 1u, 77u, 0xFFFFFFFFu}) {
        EXPECT_EQ(FractalNoise(Vec2(x, y), seed), NoiseAsDefined(Vec2(x, y), seed))
            << "at (" << x << ", " << y << "), seed " << seed;
        ++compared;
      }
    }
  for (int i = 0; i < 20000; ++i) {
    const Vec2 p(std::sin(i * 12.9898) * 4000.0, std::cos(i * 78.233) * 4000.0);
    ASSERT_EQ(FractalNoise(p, 5u), NoiseAsDefined(p, 5u))
        << "at (" << p.x() << ", " << p.y() << ")";
    ++compared;
  }
  EXPECT_GT(compared, 20000);
  // And it is noise: in [0, 1] and not constant.
  EXPECT_NE(FractalNoise(Vec2(0.3, 0.7), 1), FractalNoise(Vec2(5.3, 0.7), 1));
  EXPECT_GE(FractalNoise(Vec2(-12.5, 3.25), 9), 0.0);
  EXPECT_LE(FractalNoise(Vec2(-12.5, 3.25), 9), 1.0);
}

}  // namespace
}  // namespace lfcam
