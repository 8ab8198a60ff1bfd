#include "lfcam/render/aperture_weights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace lfcam {
namespace {

// Camera `i`'s weight at x along one axis of an n-camera grid (see the header).
double AxisWeight(double x, int i, int n) {
  if (x < -0.5 || x > n - 0.5) return 0.0;
  if (n == 1) return 1.0;
  if ((i == 0 && x <= 0.0) || (i == n - 1 && x >= n - 1)) return 1.0;
  return std::max(0.0, 1.0 - std::abs(x - i));
}

// Where AxisWeight(., i, n) has a kink or a jump; it is linear between them.
std::array<double, 7> AxisKinks(int i, int n) {
  std::array<double, 7> k = {-0.5, n - 0.5, i - 1.0, double(i), i + 1.0, 0.0, n - 1.0};
  for (double& x : k) x = std::clamp(x, -0.5, n - 0.5);
  std::sort(k.begin(), k.end());
  return k;
}

// The integral of AxisWeight(., i, n) from -infinity to y, in closed form: the weight's rising
// half (1 over the window's outer half-sample for the first camera, else the tent's t over
// [i - 1, i]) and its falling half (1 over the outer half-sample for the last camera, else
// 1 - t over [i, i + 1]).
double AxisCumulative(double y, int i, int n) {
  double rising, falling;
  if (i == 0) {
    rising = std::clamp(y + 0.5, 0.0, 0.5);
  } else {
    const double t = std::clamp(y - (i - 1), 0.0, 1.0);
    rising = 0.5 * t * t;
  }
  if (i == n - 1) {
    falling = std::clamp(y - i, 0.0, 0.5);
  } else {
    const double t = std::clamp(y - i, 0.0, 1.0);
    falling = t - 0.5 * t * t;
  }
  return rising + falling;
}

// Gauss-Legendre, 8 points on [-1, 1].
constexpr std::array<double, 4> kNodes = {0.1834346424956498, 0.5255324099163290,
                                          0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kWeights = {0.3626837833783620, 0.3137066458778873,
                                            0.2223810344533745, 0.1012285362903763};

}  // namespace

double DiskCameraIntegral(double radius, double cx, double cy, int col, int row, int cols,
                          int rows) {
  if (!(radius > 0.0)) return 0.0;
  const auto x_kinks = AxisKinks(col, cols), y_kinks = AxisKinks(row, rows);
  // The disk swept along x: x = cx + R sin(theta), half-height R cos(theta). The integrand is
  // smooth in theta between the thetas where x crosses a kink of the x weight or cy +- R cos
  // crosses a kink of the y weight.
  std::vector<double> cuts = {-0.5 * std::numbers::pi, 0.5 * std::numbers::pi};
  for (const double k : x_kinks)
    if (std::abs(k - cx) < radius) cuts.push_back(std::asin((k - cx) / radius));
  for (const double k : y_kinks)
    if (std::abs(k - cy) < radius) {
      const double theta = std::acos(std::abs(k - cy) / radius);
      cuts.push_back(theta);
      cuts.push_back(-theta);
    }
  std::sort(cuts.begin(), cuts.end());
  auto integrand = [&](double theta) {
    const double x = cx + radius * std::sin(theta), h = radius * std::cos(theta);
    const double wx = AxisWeight(x, col, cols);
    if (wx == 0.0) return 0.0;
    const double wy = AxisCumulative(cy + h, row, rows) - AxisCumulative(cy - h, row, rows);
    return wx * wy * h;  // dx = R cos(theta) dtheta = h dtheta
  };
  double sum = 0.0;
  for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
    const double mid = 0.5 * (cuts[p] + cuts[p + 1]), half = 0.5 * (cuts[p + 1] - cuts[p]);
    if (half <= 0.0) continue;
    double piece = 0.0;
    for (std::size_t q = 0; q < kNodes.size(); ++q)
      piece +=
          kWeights[q] * (integrand(mid - half * kNodes[q]) + integrand(mid + half * kNodes[q]));
    sum += half * piece;
  }
  return sum;
}

std::vector<GridCameraWeight> DiskCameraWeights(double radius, double cx, double cy, int cols,
                                                int rows) {
  const double reach = std::max(0.0, radius) + 1.0;
  const int c0 = std::max(0, int(std::floor(cx - reach))),
            c1 = std::min(cols - 1, int(std::ceil(cx + reach)));
  const int r0 = std::max(0, int(std::floor(cy - reach))),
            r1 = std::min(rows - 1, int(std::ceil(cy + reach)));
  if (c0 > c1 || r0 > r1) return {};
  const int box_cols = c1 - c0 + 1;
  std::vector<double> box(std::size_t(box_cols) * std::size_t(r1 - r0 + 1), 0.0);
  if (radius > 0.0) {
    // Every camera's DiskCameraIntegral in one sweep of the disk: the thetas are cut at every
    // camera's kinks (the grid's lines, and the window's edges), so each piece is smooth for
    // every camera, and each node's sine and cosine serve them all. A node's x meets at most two
    // cameras' weights along x; its chord, the rows it spans.
    std::vector<double> cuts = {-0.5 * std::numbers::pi, 0.5 * std::numbers::pi};
    const auto grid_lines = [](int n, const auto& add) {
      add(-0.5);
      add(n - 0.5);
      for (int k = 0; k < n; ++k) add(double(k));
    };
    grid_lines(cols, [&](double k) {
      if (std::abs(k - cx) < radius) cuts.push_back(std::asin((k - cx) / radius));
    });
    grid_lines(rows, [&](double k) {
      if (std::abs(k - cy) < radius) {
        const double theta = std::acos(std::abs(k - cy) / radius);
        cuts.push_back(theta);
        cuts.push_back(-theta);
      }
    });
    std::sort(cuts.begin(), cuts.end());
    const auto add_node = [&](double theta, double weight) {
      const double x = cx + radius * std::sin(theta), h = radius * std::cos(theta);
      const int x_floor = int(std::floor(x));
      double wx[2];
      int columns[2], n_columns = 0;
      for (int c = std::max(c0, x_floor); c <= std::min(c1, x_floor + 1); ++c) {
        const double w = AxisWeight(x, c, cols);
        if (w != 0.0) {
          wx[n_columns] = w;
          columns[n_columns++] = c;
        }
      }
      if (n_columns == 0) return;
      const int lo = std::max(r0, int(std::floor(cy - h)) - 1),
                hi = std::min(r1, int(std::ceil(cy + h)) + 1);
      for (int r = lo; r <= hi; ++r) {
        const double wy = AxisCumulative(cy + h, r, rows) - AxisCumulative(cy - h, r, rows);
        if (wy == 0.0) continue;
        double* at = box.data() + std::size_t(r - r0) * std::size_t(box_cols);
        for (int n = 0; n < n_columns; ++n) at[columns[n] - c0] += weight * wx[n] * wy * h;
      }
    };
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
      const double mid = 0.5 * (cuts[p] + cuts[p + 1]), half = 0.5 * (cuts[p + 1] - cuts[p]);
      if (half <= 0.0) continue;
      for (std::size_t q = 0; q < kNodes.size(); ++q) {
        add_node(mid - half * kNodes[q], half * kWeights[q]);
        add_node(mid + half * kNodes[q], half * kWeights[q]);
      }
    }
  } else {
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        box[std::size_t(r - r0) * std::size_t(box_cols) + std::size_t(c - c0)] =
            AxisWeight(cx, c, cols) * AxisWeight(cy, r, rows);
  }
  std::vector<GridCameraWeight> out;
  double total = 0.0;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      const double w = box[std::size_t(r - r0) * std::size_t(box_cols) + std::size_t(c - c0)];
      if (w > 0.0) {
        out.push_back({c, r, w});
        total += w;
      }
    }
  if (!(total > 0.0)) return {};
  for (auto& w : out) w.weight /= total;
  return out;
}

}  // namespace lfcam
