#include "lfcam/render/cpu_renderer.h"

#include <fmt/format.h>
#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <functional>
#include <optional>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/render/camera_integrator.h"

namespace lfcam {
namespace {

// Everything a pixel needs, set up once per frame.
struct Frame {
  const VirtualCamera& camera;
  const LightFieldSampler& sampler;
  std::vector<Vec3> lens_points;  // the same for every pixel
  Interpolation interpolation;
  const CameraIntegratorFrame* cameras = nullptr;  // the cameras integrator, with an aperture
  int view_count = 0;
};

// The cameras integrator: every camera under the footprint, read along its own ray through p_o
// with its weight. Returns the cameras read.
int RenderPixelCameras(const Frame& frame, int i, int j, float* weights, float out[3]) {
  const VirtualCamera& camera = frame.camera;
  const Vec3 direction = camera.pixel_direction(i, j);
  const Vec3 p_o = camera.focus_point(direction);
  out[0] = out[1] = out[2] = 0.0f;
  // The lens samples' lines through p_o that leave the sampled st domain miss; here the pixel's
  // central line decides for the whole pixel (the same away from the domain's edges).
  if (!frame.sampler.MeetsStDomain(camera.e_c(), direction)) return 0;
  float sum[3] = {0, 0, 0};
  int read = 0;
  if (const auto& uniform = frame.cameras->uniform_weights(); !uniform.empty()) {
    for (const GridCameraWeight& c : uniform)
      frame.sampler.AccumulateFocused(c.row, c.col, p_o, float(c.weight), sum);
    for (int k = 0; k < 3; ++k) out[k] = sum[k];
    return int(uniform.size());
  }
  frame.cameras->Weights(frame.cameras->FootprintOf(i, j), weights);
  const int cols = frame.sampler.cols();
  for (int c = 0; c < frame.view_count; ++c) {
    if (!(weights[c] > 0.0f)) continue;
    frame.sampler.AccumulateFocused(c / cols, c % cols, p_o, weights[c], sum);
    ++read;
  }
  for (int k = 0; k < 3; ++k) out[k] = sum[k];
  return read;
}

// The average radiance over the rays of pixel (i, j) that hit the slab; returns their number.
int RenderPixel(const Frame& frame, int i, int j, float out[3]) {
  const VirtualCamera& camera = frame.camera;
  const Vec3 direction = camera.pixel_direction(i, j);
  // p_o: where the central ray meets the plane of focus; every lens ray passes through it.
  const Vec3 p_o = camera.focus_point(direction);
  float sum[3] = {0, 0, 0}, rgb[3];
  int hits = 0;
  if (camera.is_pinhole()) {
    hits = frame.sampler.Sample(camera.e_c(), direction, sum, frame.interpolation, p_o) ? 1 : 0;
  } else {
    for (const Vec3& lens : frame.lens_points) {
      if (!frame.sampler.Sample(lens, p_o - lens, rgb, frame.interpolation, p_o)) continue;
      sum[0] += rgb[0];
      sum[1] += rgb[1];
      sum[2] += rgb[2];
      ++hits;
    }
  }
  const float inv = hits > 0 ? 1.0f / float(hits) : 0.0f;
  for (int c = 0; c < 3; ++c) out[c] = sum[c] * inv;
  return hits;
}

}  // namespace

RenderResult RenderLightFieldCpu(const LightField& lf, const VirtualCamera& camera,
                                 const CpuRenderOptions& options) {
  const LightFieldSampler sampler(lf);
  Frame frame{camera, sampler, {}, options.interpolation};
  for (const Vec2& disk : camera.lens_samples())
    frame.lens_points.push_back(camera.lens_point(disk));
  std::optional<CameraIntegratorFrame> cameras;
  if (options.integrator == Integrator::kCameras) {
    // A pinhole's limit is the focal-plane lookup itself.
    frame.interpolation = Interpolation::kFocalPlane;
    if (!camera.is_pinhole()) {
      cameras.emplace(lf, camera);
      frame.cameras = &*cameras;
      frame.view_count = lf.dims().rows * lf.dims().cols;
    }
  }

  RenderResult result;
  result.image = cv::Mat(camera.height(), camera.width(), CV_32FC3);
  result.hit_mask = cv::Mat(camera.height(), camera.width(), CV_8UC1);
  tbb::combinable<long long> hits_per_thread(0);
  const auto render_tile = [&](const tbb::blocked_range2d<int>& tile) {
    long long hits_here = 0;
    std::vector<float> weights(std::size_t(frame.view_count));
    for (int j = tile.rows().begin(); j != tile.rows().end(); ++j) {
      const int row = camera.image_row(j);
      auto* out = result.image.ptr<cv::Vec3f>(row);
      auto* mask = result.hit_mask.ptr<std::uint8_t>(row);
      for (int i = tile.cols().begin(); i != tile.cols().end(); ++i) {
        const int hits = frame.cameras ? RenderPixelCameras(frame, i, j, weights.data(), out[i].val)
                                       : RenderPixel(frame, i, j, out[i].val);
        mask[i] = hits > 0 ? 255 : 0;
        hits_here += hits;
      }
    }
    hits_per_thread.local() += hits_here;
    if (options.progress)
      options.progress(std::int64_t(tile.rows().size()) * std::int64_t(tile.cols().size()));
  };
  const auto render = [&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, camera.height(), 16, 0, camera.width(), 16),
                      render_tile);
  };
  if (options.threads > 0) {
    tbb::task_arena arena(options.threads);
    arena.execute(render);
  } else {
    render();
  }
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  result.rays = frame.cameras ? result.rays_hit
                              : static_cast<long long>(camera.width()) * camera.height() *
                                    static_cast<long long>(frame.lens_points.size());
  return result;
}

std::string ToString(Integrator integrator) {
  return integrator == Integrator::kLensSamples ? "lens-samples" : "cameras";
}

Integrator IntegratorFromString(const std::string& name) {
  if (name == "lens-samples") return Integrator::kLensSamples;
  if (name == "cameras") return Integrator::kCameras;
  throw Error(fmt::format("unknown integrator '{}' (expected lens-samples or cameras)", name));
}

}  // namespace lfcam
