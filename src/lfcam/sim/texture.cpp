#include "lfcam/sim/texture.h"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace lfcam {
namespace {

constexpr std::uint64_t kHashX = 0x9E3779B97F4A7C15ull, kHashY = 0xC2B2AE3D27D4EB4Full;

// The hash's finaliser: every bit of the key moves every bit of the result.
std::uint32_t Finalise(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return std::uint32_t(h);
}

std::uint32_t Hash(std::int64_t x, std::int64_t y, std::uint32_t seed) {
  return Finalise(std::uint64_t(x) * kHashX ^ std::uint64_t(y) * kHashY ^
                  (std::uint64_t(seed) << 32));
}

double Lattice(std::uint32_t hash) {
  // A multiply, not a division (a quarter of the simulator's time went to the noise, much of it
  // to the divider): the same value to within one ulp.
  constexpr double kInverseMax = 1.0 / 4294967295.0;
  return hash * kInverseMax;
}

// floor(x) as an integer: std::floor is a call into libm on x86-64's baseline instruction set
// (no rounding instruction), and the noise takes eight a sample. The same for every |x| < 2^63.
std::int64_t FloorToInt(double x) {
  const auto truncated = std::int64_t(x);
  return truncated - (double(truncated) > x);
}

double ValueNoise(const Vec2& p, unsigned seed) {
  const std::int64_t x = FloorToInt(p.x()), y = FloorToInt(p.y());
  auto smooth = [](double t) { return t * t * (3 - 2 * t); };
  const double tx = smooth(p.x() - double(x)), ty = smooth(p.y() - double(y));
  // Hash() at the cell's four corners, its products shared: (x + 1) kHashX = x kHashX + kHashX.
  const std::uint64_t x0 = std::uint64_t(x) * kHashX, x1 = x0 + kHashX;
  const std::uint64_t y0 = std::uint64_t(y) * kHashY ^ (std::uint64_t(seed) << 32),
                      y1 = (std::uint64_t(y) * kHashY + kHashY) ^ (std::uint64_t(seed) << 32);
  const double a = Lattice(Finalise(x0 ^ y0)), b = Lattice(Finalise(x1 ^ y0));
  const double c = Lattice(Finalise(x0 ^ y1)), d = Lattice(Finalise(x1 ^ y1));
  return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty;
}

int FloorMod(std::int64_t a, int m) { return int(((a % m) + m) % m); }

// A 5x7 dot-matrix "glyph" per cell, words separated by blank cells, lines by a blank row.
bool TextInk(const Vec2& uv, double glyph_h, unsigned seed) {
  const double cell_w = glyph_h * 6.0 / 7.0, line_h = glyph_h * 1.6;
  const auto col = std::int64_t(std::floor(uv.x() / cell_w));
  const auto line = std::int64_t(std::floor(uv.y() / line_h));
  const double in_x = (uv.x() - col * cell_w) / cell_w * 6.0;  // 0..6, dots at 0..5
  const double in_y = (uv.y() - line * line_h) / glyph_h * 7.0;
  if (in_x >= 5.0 || in_y >= 7.0) return false;
  if (Hash(col / 7, line, seed) % 5 == 0) return false;  // a short empty stretch
  if (FloorMod(col, 7) == 6) return false;               // the space between words
  const std::uint64_t bits =
      std::uint64_t(Hash(col, line, seed + 17)) << 32 | Hash(col, line, seed + 29);
  const int dot = int(in_y) * 5 + int(in_x);  // 0..34
  return (bits >> dot) & 1u;
}

}  // namespace

double FractalNoise(const Vec2& p, unsigned seed) {
  double sum = 0, amplitude = 0.5, norm = 0;
  Vec2 q = p;
  for (int octave = 0; octave < 4; ++octave) {
    sum += amplitude * ValueNoise(q, seed + unsigned(octave) * 101u);
    norm += amplitude;
    amplitude *= 0.5;
    q *= 2.03;
  }
  return sum / norm;
}

Vec3 Texture::Evaluate(const Vec2& uv) const {
  switch (pattern) {
    case Pattern::kConstant:
      return color_a;
    case Pattern::kChecker: {
      const auto i = std::int64_t(std::floor(uv.x() / scale_mm));
      const auto j = std::int64_t(std::floor(uv.y() / scale_mm));
      return ((i + j) & 1) ? color_b : color_a;
    }
    case Pattern::kStripes: {
      const double phase = uv.y() / scale_mm - std::floor(uv.y() / scale_mm);
      return phase < 0.5 ? color_a : color_b;
    }
    case Pattern::kNoise: {
      const double n = FractalNoise(uv / scale_mm, seed);
      return color_a + (color_b - color_a) * n;
    }
    case Pattern::kText:
      return TextInk(uv, scale_mm, seed) ? color_b : color_a;
    case Pattern::kBlotchGrid: {
      const double grid = scale_mm * 4;
      const double gx = std::abs(std::remainder(uv.x(), grid));
      const double gy = std::abs(std::remainder(uv.y(), grid));
      if (gx < 0.6 || gy < 0.6) return Vec3(0.9, 0.9, 0.85);
      const double n = FractalNoise(uv / scale_mm, seed);
      return n > 0.55 ? color_b : color_a;
    }
    case Pattern::kRadial: {
      const double r = uv.norm();
      const double angle = std::atan2(uv.y(), uv.x());
      const double blade = std::sin(5 * angle + r / (2 * scale_mm));
      if (std::abs(std::remainder(r, scale_mm * 2)) < 0.7) return Vec3(0.05, 0.05, 0.05);
      return blade > 0.2 ? color_a : color_b;
    }
  }
  return color_a;
}

}  // namespace lfcam
