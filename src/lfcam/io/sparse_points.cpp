#include "lfcam/io/sparse_points.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "lfcam/core/color.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/io/lightfield_export.h"

namespace lfcam {
namespace {

// Where world point p falls in view camera v: OpenCV's pixel (x right, y down, (0, 0) the centre
// of the top-left sample); false when behind the camera.
bool ProjectInto(const ViewCamera& v, const Vec3& p, double* u, double* w) {
  const Vec3 q = v.world_from_camera.rotation.transpose() * (p - v.world_from_camera.translation);
  if (!(q.z() > 0)) return false;
  *u = v.cx + v.fx * q.x() / q.z();
  *w = v.cy + v.fy * q.y() / q.z();
  return true;
}

}  // namespace

SparsePoints PointsFromDepth(const LightField& lf, const DepthSet& depth,
                             const SparsePointOptions& options) {
  const LightFieldDims& d = lf.dims();
  const Slab& slab = lf.slab();
  const int stride =
      options.stride > 0
          ? options.stride
          : std::max(1, int(std::lround(std::sqrt(double(d.samples_per_view()) / 5000.0))));
  std::vector<ViewCamera> cameras;
  // The views a point may come from or be seen in: those with a map that were photographed
  // (a view filled from its neighbours is no photograph, and is not exported as one).
  std::vector<bool> seeing = PhotographedViews(lf);
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      cameras.push_back(ViewAsCamera(lf, r, c));
      if (!depth.has(r, c)) seeing[std::size_t(r * d.cols + c)] = false;
    }
  std::vector<int> with_map;
  for (int view = 0; view < int(d.view_count()); ++view)
    if (seeing[std::size_t(view)]) with_map.push_back(view);
  // Views nearest the grid's centre first: they see most of what the others see.
  const double mid_r = 0.5 * (d.rows - 1), mid_c = 0.5 * (d.cols - 1);
  std::stable_sort(with_map.begin(), with_map.end(), [&](int a, int b) {
    auto distance = [&](int i) { return std::hypot(i / d.cols - mid_r, i % d.cols - mid_c); };
    return distance(a) < distance(b);
  });
  // A point's cell: a stride of the central view's samples across, 1% in depth.
  const ViewCamera& centre = cameras[std::size_t(d.rows / 2 * d.cols + d.cols / 2)];
  auto cell_of = [&](const Vec3& p, double depth_mm, std::uint64_t* key) {
    double u, w;
    if (!ProjectInto(centre, p, &u, &w)) return false;
    const auto i = std::int64_t(std::floor(u / stride)) & 0x1FFFFF;
    const auto j = std::int64_t(std::floor(w / stride)) & 0x1FFFFF;
    const auto m = std::int64_t(std::floor(std::log(depth_mm) / std::log1p(0.01))) & 0x3FFFFF;
    *key = std::uint64_t(i) | std::uint64_t(j) << 21 | std::uint64_t(m) << 42;
    return true;
  };

  SparsePoints out;
  out.observations.resize(d.view_count());
  std::unordered_set<std::uint64_t> made;
  for (const int view : with_map) {
    const int r = view / d.cols, c = view % d.cols;
    const DepthMap& map = depth.at(r, c);
    const Vec3 eye = lf.camera_center(r, c);
    const double eye_depth = DepthOf(slab, eye);
    const StSampling sampling = lf.st_sampling(r, c);  // the view's own window
    for (int l = stride / 2; l < d.n_t; l += stride)
      for (int k = stride / 2; k < d.n_s; k += stride) {
        const float depth_mm = map.depth.at<float>(l, k);
        if (!std::isfinite(depth_mm) || depth_mm <= 0) continue;
        if (!map.confidence.empty() && map.confidence.at<float>(l, k) < options.min_confidence)
          continue;
        // Along the ray from the camera through the sample, depth changes linearly.
        const Vec3 on_st = sampling.Point(k, l);
        const double st_depth = DepthOf(slab, on_st);
        if (!(std::abs(st_depth - eye_depth) > 1e-9)) continue;
        const Vec3 p = eye + (depth_mm - eye_depth) / (st_depth - eye_depth) * (on_st - eye);
        std::uint64_t key = 0;
        if (cell_of(p, depth_mm, &key) && !made.insert(key).second) continue;

        SparsePoint point;
        point.position_mm = p;
        const Eigen::Vector3f rgb = lf.linear_rgb(r, c, k, l);
        point.rgb = {LinearToSrgb8(rgb.x()), LinearToSrgb8(rgb.y()), LinearToSrgb8(rgb.z())};
        const int index = int(out.points.size());
        for (int other = 0; other < int(d.view_count()); ++other) {
          if (!seeing[std::size_t(other)]) continue;
          double u, w;
          if (!ProjectInto(cameras[std::size_t(other)], p, &u, &w)) continue;
          // The view it came from sees it by construction; another sees it where the four
          // samples around its projection all agree on its depth (not across an edge or along
          // a surface seen edge-on, where the nearest sample says little about the ray).
          if (other != view) {
            const cv::Mat& seen = depth.at(other / d.cols, other % d.cols).depth;
            const int k0 = int(std::floor(u)), top0 = int(std::floor(w));
            if (k0 < 0 || k0 + 1 >= d.n_s || top0 < 0 || top0 + 1 >= d.n_t) continue;
            bool agree = true;
            for (int dy = 0; dy < 2 && agree; ++dy)
              for (int dx = 0; dx < 2 && agree; ++dx) {
                const float there = seen.at<float>(d.n_t - 1 - (top0 + dy), k0 + dx);
                agree = std::abs(there - depth_mm) <= options.agreement * depth_mm;
              }
            if (!agree) continue;
          }
          auto& list = out.observations[std::size_t(other)];
          point.track.emplace_back(other, int(list.size()));
          list.push_back({u + 0.5, w + 0.5, index});
        }
        out.points.push_back(std::move(point));
      }
  }
  return out;
}

}  // namespace lfcam
