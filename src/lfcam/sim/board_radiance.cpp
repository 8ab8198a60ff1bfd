#include "lfcam/sim/board_radiance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>

#include "lfcam/calib/charuco.h"
#include "lfcam/sim/splitmix.h"

namespace lfcam {
namespace {

// The integral from 0 to x of the square wave that is +1 on even squares and -1 on odd ones:
// a triangle wave of period 2 squares.
double SquareWaveIntegral(double x, double square) {
  const double u = x / square;
  const double m = u - 2.0 * std::floor(u / 2.0);  // in [0, 2)
  return square * (1.0 - std::abs(m - 1.0));
}

// Where in each of a pixel's n x n strata its ray falls: uniform in the stratum, drawn from the
// pixel's own centre ray (its origin and direction), so a pixel sees the same at every shot of
// its module and the draw needs no state shared between threads. At the strata's centres instead
// (a regular grid), a step edge's share of the pixel takes one of n + 1 values, the edge's place
// within the pixel is rounded to 1/n of it the same way in every camera, and two cameras'
// images matched by absolute differences (the depth sweep) agree best at a whole pixel's shift:
// the paper scene's checkered wall, 6.92 px between neighbouring cameras of 1296 x 972, matched
// at 7.00 px, and its depth 1.1% too near (docs/benchmarks.md, "Depth of a built light field").
class StratumJitter {
 public:
  explicit StratumJitter(const Ray& ray) {
    for (const double v : {ray.origin.x(), ray.origin.y(), ray.origin.z(), ray.direction.x(),
                           ray.direction.y(), ray.direction.z()}) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      state_ = SplitMixFinalise(state_ ^ bits);
    }
  }
  // Uniform in [0, 1).
  double Next() { return double(SplitMixNext(state_) >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_ = kSplitMixGamma;
};

// Where a pixel's footprint seen through the lens puts a given share of its weight, along one
// axis: the quantiles of one pixel's box (-0.5 .. 0.5) convolved with a Gaussian of sigma pixels,
// tabulated. The footprint is the same along either axis and separable, so a point drawn at the
// quantiles (u, v) of a stratum's uniform draw samples the blurred footprint as the strata sample
// the box: an edge falls in one stratum, not among random offsets (which would add noise the
// lens does not make). Sigma 0: the box's own quantiles, u - 0.5.
class LensFootprintQuantiles {
 public:
  explicit LensFootprintQuantiles(double sigma) : sigma_(sigma) {
    // The share of the footprint left of x: the integral over the box of the Gaussian's CDF, with
    // G(t) = t Phi(t) + phi(t) its antiderivative.
    const auto share_left_of = [sigma](double x) {
      const auto antiderivative = [](double t) {
        return t * 0.5 * std::erfc(-t / std::numbers::sqrt2) +
               std::exp(-0.5 * t * t) / std::sqrt(2 * std::numbers::pi);
      };
      return sigma * (antiderivative((x + 0.5) / sigma) - antiderivative((x - 0.5) / sigma));
    };
    const double reach = 0.5 + 5 * sigma;  // beyond it, less than 3e-7 of the weight
    quantiles_[0] = -reach;
    quantiles_[kSteps] = reach;
    for (int k = 1; k < kSteps; ++k) {
      double lo = -reach, hi = reach;
      for (int i = 0; i < 48; ++i) {
        const double mid = 0.5 * (lo + hi);
        (share_left_of(mid) < double(k) / kSteps ? lo : hi) = mid;
      }
      quantiles_[std::size_t(k)] = 0.5 * (lo + hi);
    }
  }
  double sigma() const { return sigma_; }
  // The offset from the pixel's centre (pixels) below which a share u in [0, 1) of the weight lies.
  double At(double u) const {
    const double at = u * kSteps;
    const int k = std::min(kSteps - 1, int(at));
    const double f = at - k;
    return (1 - f) * quantiles_[std::size_t(k)] + f * quantiles_[std::size_t(k) + 1];
  }

 private:
  static constexpr int kSteps = 1024;
  double sigma_;
  std::array<double, kSteps + 1> quantiles_{};
};

// The table for sigma, kept per thread while sigma stays the same (a module's pixels share it).
const LensFootprintQuantiles& FootprintQuantilesFor(double sigma) {
  thread_local std::unique_ptr<LensFootprintQuantiles> table;
  if (!table || table->sigma() != sigma) table = std::make_unique<LensFootprintQuantiles>(sigma);
  return *table;
}

}  // namespace

double BlackAreaFraction(const BoardSpec& board, double x0, double x1, double y0, double y1) {
  const double area = (x1 - x0) * (y1 - y0);
  if (!(area > 0)) return board.black_at(0.5 * (x0 + x1), 0.5 * (y0 + y1)) ? 1.0 : 0.0;
  // Only the squared area has squares; clip the rectangle to it.
  const double cx0 = std::max(x0, 0.0), cx1 = std::min(x1, board.width_mm());
  const double cy0 = std::max(y0, 0.0), cy1 = std::min(y1, board.height_mm());
  if (cx1 <= cx0 || cy1 <= cy0) return 0.0;
  const double s = board.square_mm;
  // Black is where the two square waves agree: (1 + q(x) q(y)) / 2.
  const double checker = (SquareWaveIntegral(cx1, s) - SquareWaveIntegral(cx0, s)) *
                         (SquareWaveIntegral(cy1, s) - SquareWaveIntegral(cy0, s));
  return 0.5 * ((cx1 - cx0) * (cy1 - cy0) + checker) / area;
}

PixelRadiance BoardInFrontOf(const BoardSpec& board, const Rigid3& world_from_board,
                             const Scene& scene, const BoardAppearance& look) {
  const Rigid3 board_from_world = world_from_board.inverse();
  const double margin = look.margin_squares * board.square_mm;
  std::shared_ptr<const CharucoLayout> charuco;
  if (board.charuco()) charuco = std::make_shared<const CharucoLayout>(MakeCharucoLayout(board));
  return [=, &scene](const Ray& ray, const PixelFootprint& footprint, const Vec3* behind) -> Vec3 {
    auto background = [&] { return behind ? *behind : scene.Radiance(ray); };
    // Everything in board coordinates: the board is the plane z = 0.
    const Vec3 o = board_from_world * ray.origin;
    const Mat3& r = board_from_world.rotation;
    auto hit = [&](const Vec3& world_direction, Vec2* at) {
      const Vec3 d = r * world_direction;
      if (std::abs(d.z()) < 1e-12) return false;
      const double t = -o.z() / d.z();
      if (!(t > 0)) return false;
      *at = Vec2(o.x() + t * d.x(), o.y() + t * d.y());
      return true;
    };
    Vec2 center, right, down;
    if (!hit(ray.direction, &center) || !hit(ray.direction + footprint.dx, &right) ||
        !hit(ray.direction + footprint.dy, &down))
      return background();
    // The footprint's extent along the board's axes, with the pixel's area, widened by the lens's
    // blur to the box of the same variance: a box 2h wide has variance h^2 / 3, and the blur adds
    // (2h sigma)^2 in the same units.
    const Vec2 ju = right - center, jv = down - center;
    const double widen = std::sqrt(1.0 + 12.0 * footprint.blur_px * footprint.blur_px);
    const double hx = 0.5 * widen * std::sqrt(ju.x() * ju.x() + jv.x() * jv.x());
    const double hy = 0.5 * widen * std::sqrt(ju.y() * ju.y() + jv.y() * jv.y());
    const double x0 = center.x() - hx, x1 = center.x() + hx;
    const double y0 = center.y() - hy, y1 = center.y() + hy;
    const double bx0 = -margin, bx1 = board.width_mm() + margin;
    const double by0 = -margin, by1 = board.height_mm() + margin;
    const double ox = std::max(0.0, std::min(x1, bx1) - std::max(x0, bx0));
    const double oy = std::max(0.0, std::min(y1, by1) - std::max(y0, by0));
    const double on_board = std::min(1.0, ox * oy / std::max(1e-300, (x1 - x0) * (y1 - y0)));
    if (on_board <= 0) return background();
    const double black = charuco ? CharucoBlackAreaFraction(*charuco, x0, x1, y0, y1)
                                 : BlackAreaFraction(board, x0, x1, y0, y1);
    const double value = look.black * black + look.white * (on_board - black);
    Vec3 out = Vec3::Constant(value);
    if (on_board < 1) out += (1 - on_board) * background();
    return out;
  };
}

PixelRuns BoardFootprintRuns(const BoardSpec& board, const Rigid3& world_from_board,
                             const SimulatedModule& module, const cv::Mat& directions,
                             const BoardAppearance& look) {
  const int width = directions.cols, height = directions.rows;
  const Rigid3 board_from_world = world_from_board.inverse();
  const Vec3 o = board_from_world * module.world_from_camera.translation;
  const Mat3& r = board_from_world.rotation;
  // Where the ray through a pixel's centre meets the board's plane (z = 0), if in front.
  auto hit = [&](int x, int y, Vec2* at) {
    const cv::Vec3f w = directions.at<cv::Vec3f>(y, x);
    const Vec3 d = r * Vec3(w[0], w[1], w[2]);
    if (std::abs(d.z()) < 1e-12) return false;
    const double t = -o.z() / d.z();
    if (!(t > 0)) return false;
    *at = Vec2(o.x() + t * d.x(), o.y() + t * d.y());
    return true;
  };
  const double margin = look.margin_squares * board.square_mm;
  const double bx0 = -margin, bx1 = board.width_mm() + margin;
  const double by0 = -margin, by1 = board.height_mm() + margin;
  constexpr int kStep = 8;
  PixelRuns runs(std::size_t(height), cv::Vec2i(0, 0));
  tbb::parallel_for(0, height, [&](int y) {
    const int y_next = y + 1 < height ? y + 1 : y - 1;
    int begin = width, end = 0;
    int a = 0;
    Vec2 ha = Vec2::Zero(), va = Vec2::Zero();
    bool a_ok = hit(a, y, &ha) && hit(a, y_next, &va);
    while (a < width - 1) {
      const int b = std::min(a + kStep, width - 1);
      Vec2 hb = Vec2::Zero(), vb = Vec2::Zero();
      const bool b_ok = hit(b, y, &hb) && hit(b, y_next, &vb);
      // Where the board's plane is behind the camera at one end only, its horizon crosses the
      // stretch: kept. Behind at both ends, the board is out of sight there.
      bool keep = a_ok != b_ok;
      if (a_ok && b_ok) {
        // The pixels from a to b lie along the chord from ha to hb; their footprints reach no
        // farther than a pixel's step along the row and down the column.
        const double grow = (hb - ha).norm() + (va - ha).norm() + (vb - hb).norm();
        keep = std::min(ha.x(), hb.x()) - grow < bx1 && std::max(ha.x(), hb.x()) + grow > bx0 &&
               std::min(ha.y(), hb.y()) - grow < by1 && std::max(ha.y(), hb.y()) + grow > by0;
      }
      if (keep) {
        begin = std::min(begin, a);
        end = std::max(end, b + 1);
      }
      a = b;
      ha = hb;
      va = vb;
      a_ok = b_ok;
    }
    if (width == 1) begin = 0, end = 1;
    runs[std::size_t(y)] = begin < end ? cv::Vec2i(begin, end) : cv::Vec2i(0, 0);
  });
  return runs;
}

PixelRadiance SceneRadiance(const Scene& scene, int n) {
  return [&scene, n](const Ray& ray, const PixelFootprint& footprint, const Vec3*) -> Vec3 {
    if (n <= 1) return scene.Radiance(ray);
    StratumJitter jitter(ray);
    const LensFootprintQuantiles* lens =
        footprint.blur_px > 0 ? &FootprintQuantilesFor(footprint.blur_px) : nullptr;
    Vec3 sum = Vec3::Zero();
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double u = (b + jitter.Next()) / n, v = (a + jitter.Next()) / n;
        const double fx = lens ? lens->At(u) : u - 0.5, fy = lens ? lens->At(v) : v - 0.5;
        sum += scene.Radiance({ray.origin, ray.direction + fx * footprint.dx + fy * footprint.dy});
      }
    return sum / double(n * n);
  };
}

}  // namespace lfcam
