#include "lfcam/depth/sweep_reads.h"

#include <cmath>
#include <numbers>

#include "lfcam/core/keys_cubic.h"

namespace lfcam::sweep {

std::array<float, 4> ReadWeights(double f, double read_sigma) {
  if (read_sigma <= 0) return KeysCubicWeights(f);
  std::array<float, 4> w{};
  double total = 0;
  for (int i = 0; i < 4; ++i) {
    const double x = (i - 1) - f;
    const double taper =
        std::abs(x) < 2.0 ? std::pow(std::cos(std::numbers::pi * x / 4.0), 2) : 0.0;
    const double value = std::exp(-x * x / (2.0 * read_sigma * read_sigma)) * taper;
    w[std::size_t(i)] = float(value);
    total += value;
  }
  for (float& v : w) v = float(v / total);
  return w;
}

bool IsShift(const cv::Matx33d& m) {
  return std::abs(m(0, 0) - 1) < 1e-9 && std::abs(m(1, 1) - 1) < 1e-9 && std::abs(m(0, 1)) < 1e-9 &&
         std::abs(m(1, 0)) < 1e-9 && std::abs(m(2, 0)) < 1e-12 && std::abs(m(2, 1)) < 1e-12 &&
         std::abs(m(2, 2) - 1) < 1e-12;
}

bool IsScaledShift(const cv::Matx33d& m) {
  return m(0, 1) == 0 && m(1, 0) == 0 && m(2, 0) == 0 && m(2, 1) == 0 && m(2, 2) == 1 &&
         m(0, 0) > 0 && m(1, 1) > 0;
}

}  // namespace lfcam::sweep
