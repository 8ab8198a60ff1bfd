#pragma once
// Keys' cubic convolution kernel (Keys 1981) with a = -0.5: the interpolating cubic that
// reproduces a quadratic exactly and passes more of the band than OpenCV's a = -0.75, whose extra
// smoothing at half-sample positions pulls sub-sample matches towards whole and half samples.
// The plane sweep's sub-sample shifts (depth/cost_volume.h) and the depth lookup's reads at a
// frame's own resolution (render/lightfield_sampler.h) use it.
#include <array>

namespace lfcam {

// The weights of the samples at -1, 0, 1, 2 for a point at fraction f (0 <= f < 1) past sample 0.
inline std::array<float, 4> KeysCubicWeights(double f) {
  constexpr double a = -0.5;
  const auto near = [](double x) { return ((a + 2) * x - (a + 3)) * x * x + 1; };
  const auto far = [](double x) { return ((a * x - 5 * a) * x + 8 * a) * x - 4 * a; };
  return {float(far(1 + f)), float(near(f)), float(near(1 - f)), float(far(2 - f))};
}

}  // namespace lfcam
