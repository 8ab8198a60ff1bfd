#include "lfcam/render/lens_sampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam {

Vec2 SampleUniformDiskConcentric(const Vec2& u) {
  const Vec2 offset = 2.0 * u - Vec2(1.0, 1.0);
  if (offset.x() == 0 && offset.y() == 0) return Vec2::Zero();
  constexpr double kPiOver4 = std::numbers::pi / 4, kPiOver2 = std::numbers::pi / 2;
  double r, theta;
  if (std::abs(offset.x()) > std::abs(offset.y())) {
    r = offset.x();
    theta = kPiOver4 * (offset.y() / offset.x());
  } else {
    r = offset.y();
    theta = kPiOver2 - kPiOver4 * (offset.x() / offset.y());
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

int LensSampleCount(double lens_rate, double aperture_mm) {
  const double radius = aperture_mm / 2.0;
  const double n = std::round(lens_rate * radius * radius / 210.0);  // in double: never wraps
  if (!(n <= kMaxLensSamples))
    throw Error(
        fmt::format("lens sampling rate {} with a {} mm aperture asks for {:.4g} lens "
                    "samples a pixel, more than the limit of {}",
                    lens_rate, aperture_mm, n, kMaxLensSamples));
  return std::max(1, int(n));
}

Vec2 Hammersley(int i, int n) {
  std::uint32_t bits = std::uint32_t(i);
  bits = (bits << 16) | (bits >> 16);
  bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
  bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
  bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
  bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
  // Shifted by half a stratum in y so that n = 1 gives the centre and the set is symmetric.
  const double y = bits * 2.3283064365386963e-10 + 0.5 / n;
  return {(i + 0.5) / n, y - std::floor(y)};
}

std::vector<Vec2> UnitDiskSamples(int n) {
  std::vector<Vec2> samples;
  samples.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) samples.push_back(SampleUniformDiskConcentric(Hammersley(i, n)));
  return samples;
}

}  // namespace lfcam
