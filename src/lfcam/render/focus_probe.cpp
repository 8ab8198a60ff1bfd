#include "lfcam/render/focus_probe.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lfcam/core/view_filling.h"
#include "lfcam/render/lightfield_sampler.h"

namespace lfcam {
namespace {

constexpr double kPatchStepInSamples = 3.0;

struct Cost {
  double value = std::numeric_limits<double>::infinity();
  int cameras = 0;
};

// The spread of the cameras' colours over the patch on the plane of focus at distance d: the
// variance across cameras, summed over the patch's points and channels, per point. Cameras
// whose lines to a point leave the sampled st domain (or their own window) are left out of that
// point, and so are those not `photographed` (filled from their neighbours: core/view_filling.h).
Cost PatchCost(const LightField& lf, const LightFieldSampler& sampler,
               const std::vector<bool>& photographed, const VirtualCamera& camera,
               const Vec3& direction, double d, const FocusProbeOptions& o, double step_mm) {
  const int rows = lf.dims().rows, cols = lf.dims().cols;
  const Vec3 centre = camera.e_c() + d * direction;
  const Vec3& n_ca = lf.slab().uv.n_ca;
  double total = 0;
  int points = 0, cameras_seen = 0;
  for (int b = -o.patch_radius; b <= o.patch_radius; ++b)
    for (int a = -o.patch_radius; a <= o.patch_radius; ++a) {
      const Vec3 p = centre + (a * step_mm) * camera.u_c() + (b * step_mm) * camera.v_c();
      double sum[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
      int n = 0;
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
          if (!photographed[std::size_t(r * cols + c)]) continue;
          const Vec3 origin = lf.camera_center(r, c);
          // The camera sees p only in front of it (toward the scene) and inside the domain.
          if (n_ca.dot(p - origin) >= 0 || !sampler.MeetsStDomain(origin, p - origin)) continue;
          float rgb[3] = {0, 0, 0};
          if (!(sampler.AccumulateFocused(r, c, p, 1.0f, rgb) > 0)) continue;  // outside its window
          for (int k = 0; k < 3; ++k) {
            sum[k] += rgb[k];
            squares[k] += double(rgb[k]) * rgb[k];
          }
          ++n;
        }
      if (n < 2) continue;
      double variance = 0;
      for (int k = 0; k < 3; ++k) variance += squares[k] / n - (sum[k] / n) * (sum[k] / n);
      total += std::max(variance, 0.0);
      ++points;
      cameras_seen = std::max(cameras_seen, n);
    }
  // Half the patch at least, else this distance is not measured.
  const int side = 2 * o.patch_radius + 1;
  if (points * 2 < side * side) return {};
  return {total / points, cameras_seen};
}

// Costs at the given distances, in parallel.
std::vector<Cost> Sweep(const LightField& lf, const LightFieldSampler& sampler,
                        const std::vector<bool>& photographed, const VirtualCamera& camera,
                        const Vec3& direction, const std::vector<double>& distances,
                        const FocusProbeOptions& o, double step_mm) {
  std::vector<Cost> costs(distances.size());
  tbb::parallel_for(std::size_t(0), distances.size(), [&](std::size_t i) {
    costs[i] = PatchCost(lf, sampler, photographed, camera, direction, distances[i], o, step_mm);
  });
  return costs;
}

std::vector<double> Geometric(double lo, double hi, double ratio) {
  std::vector<double> d;
  for (double x = lo; x <= hi; x *= ratio) d.push_back(x);
  return d;
}

std::size_t Best(const std::vector<Cost>& costs) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < costs.size(); ++i)
    if (costs[i].value < costs[best].value) best = i;
  return best;
}

}  // namespace

FocusProbe ProbeFocusDistance(const LightField& lf, const VirtualCamera& camera, double x, double y,
                              const FocusProbeOptions& options) {
  FocusProbe probe;
  const LightFieldSampler sampler(lf);
  // The photographed views, unless every view was filled.
  std::vector<bool> photographed = PhotographedViews(lf);
  if (std::find(photographed.begin(), photographed.end(), true) == photographed.end())
    photographed.assign(photographed.size(), true);
  const Vec3 direction = camera.direction_through(x, y);
  const double near_mm =
      options.near_mm > 0 ? options.near_mm : 1.02 * camera.params().focal_length_mm;
  const double far_mm = std::max(options.far_mm, near_mm * 1.1);
  // The patch's spacing: a few st samples' pitch on the st-plane (where the views are
  // sharpest), so that the patch spans some texture.
  const double step_mm =
      options.patch_step_mm > 0
          ? options.patch_step_mm
          : kPatchStepInSamples * std::max(lf.st_sampling().ds_mm(), lf.st_sampling().dt_mm());

  const std::vector<double> coarse = Geometric(near_mm, far_mm, 1.02);
  const std::vector<Cost> coarse_costs =
      Sweep(lf, sampler, photographed, camera, direction, coarse, options, step_mm);
  const std::size_t best = Best(coarse_costs);
  if (!std::isfinite(coarse_costs[best].value)) return probe;
  const double lo = coarse[best] / (1.02 * 1.02), hi = coarse[best] * 1.02 * 1.02;
  const std::vector<double> fine = Geometric(std::max(lo, near_mm), std::min(hi, far_mm), 1.001);
  const std::vector<Cost> fine_costs =
      Sweep(lf, sampler, photographed, camera, direction, fine, options, step_mm);
  const std::size_t fine_best = Best(fine_costs);
  if (!std::isfinite(fine_costs[fine_best].value)) return probe;

  std::vector<double> finite;
  for (const Cost& c : coarse_costs)
    if (std::isfinite(c.value)) finite.push_back(c.value);
  std::nth_element(finite.begin(), finite.begin() + std::ptrdiff_t(finite.size() / 2),
                   finite.end());
  const double median = finite[finite.size() / 2];
  probe.found = true;
  probe.focus_distance_mm = fine[fine_best];
  probe.cameras = fine_costs[fine_best].cameras;
  probe.confidence =
      median > 0 ? std::clamp(1.0 - fine_costs[fine_best].value / median, 0.0, 1.0) : 0.0;
  return probe;
}

}  // namespace lfcam
