#include "lfcam/render/cpu_renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <functional>
#include <vector>

namespace lfcam {
namespace {

// Everything a pixel needs, set up once per frame.
struct Frame {
  const VirtualCamera& camera;
  const LightFieldSampler& sampler;
  std::vector<Vec3> lens_points;  // the same for every pixel
  Interpolation interpolation;
};

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

  RenderResult result;
  result.image = cv::Mat(camera.height(), camera.width(), CV_32FC3);
  result.hit_mask = cv::Mat(camera.height(), camera.width(), CV_8UC1);
  tbb::combinable<long long> hits_per_thread(0);
  const auto render_tile = [&](const tbb::blocked_range2d<int>& tile) {
    long long hits_here = 0;
    for (int j = tile.rows().begin(); j != tile.rows().end(); ++j) {
      const int row = camera.image_row(j);
      auto* out = result.image.ptr<cv::Vec3f>(row);
      auto* mask = result.hit_mask.ptr<std::uint8_t>(row);
      for (int i = tile.cols().begin(); i != tile.cols().end(); ++i) {
        const int hits = RenderPixel(frame, i, j, out[i].val);
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
  result.rays = static_cast<long long>(camera.width()) * camera.height() *
                static_cast<long long>(frame.lens_points.size());
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  return result;
}

}  // namespace lfcam
