#include "lfcam/render/cpu_renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <vector>

#include "lfcam/render/lightfield_sampler.h"

namespace lfcam {

RenderResult RenderLightFieldCpu(const LightField& lf, const VirtualCamera& camera,
                                 const CpuRenderOptions& options) {
  const LightFieldSampler sampler(lf);
  RenderResult result;
  result.image = cv::Mat(camera.height(), camera.width(), CV_32FC3);
  result.hit_mask = cv::Mat(camera.height(), camera.width(), CV_8UC1);

  // Lens points are the same for every pixel: compute them once per frame.
  std::vector<Vec3> lens_points;
  for (const Vec2& disk : camera.lens_samples()) lens_points.push_back(camera.lens_point(disk));
  const bool pinhole = camera.is_pinhole();
  const double d_o = camera.params().focus_distance_mm;
  tbb::combinable<long long> hits_per_thread(0);

  auto render = [&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, camera.height(), 16, 0, camera.width(), 16),
                      [&](const tbb::blocked_range2d<int>& r) {
                        long long hits_here = 0;
                        for (int j = r.rows().begin(); j != r.rows().end(); ++j) {
                          const int row = camera.image_row(j);
                          auto* out = result.image.ptr<cv::Vec3f>(row);
                          auto* mask = result.hit_mask.ptr<std::uint8_t>(row);
                          for (int i = r.cols().begin(); i != r.cols().end(); ++i) {
                            const Vec3 direction = camera.pixel_direction(i, j);
                            float sum[3] = {0, 0, 0}, rgb[3];
                            int hits = 0;
                            if (pinhole) {
                              hits = sampler.Sample(camera.e_c(), direction, sum) ? 1 : 0;
                            } else {
                              // Every lens sample sends a ray through p_o, the central ray's point
                              // of focus.
                              const Vec3 p_o = camera.e_c() + d_o * direction;
                              for (const Vec3& lens : lens_points) {
                                if (!sampler.Sample(lens, p_o - lens, rgb)) continue;
                                sum[0] += rgb[0];
                                sum[1] += rgb[1];
                                sum[2] += rgb[2];
                                ++hits;
                              }
                            }
                            const float inv = hits > 0 ? 1.0f / float(hits) : 0.0f;
                            out[i] = cv::Vec3f(sum[0] * inv, sum[1] * inv, sum[2] * inv);
                            mask[i] = hits > 0 ? 255 : 0;
                            hits_here += hits;
                          }
                        }
                        hits_per_thread.local() += hits_here;
                      });
  };
  if (options.threads > 0) {
    tbb::task_arena arena(options.threads);
    arena.execute(render);
  } else {
    render();
  }
  result.rays = static_cast<long long>(camera.width()) * camera.height() *
                static_cast<long long>(lens_points.size());
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  return result;
}

}  // namespace lfcam
