#include "lfcam/render/cpu_renderer.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/prefilter_cache.h"
#include "lfcam/render/prefilter_memory.h"
#include "lfcam/render/quadrilinear_limit.h"
#include "lfcam/render/ray_setup.h"
#include "lfcam/render/separable_frame.h"
#include "lfcam/render/separable_kernels.h"
#include "lfcam/render/simd_kernels.h"

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
  const DepthAwareSampler* depth = nullptr;  // Interpolation::kDepth
  const WindowTaper* taper = nullptr;        // the cameras integrator's fade at the windows
  bool antialias = false;                    // with it: rays over the pixel's area

  bool Sample(const Vec3& origin, const Vec3& direction, float rgb[3], const Vec3& p_o) const {
    if (depth) return depth->Sample(origin, direction, rgb);
    return sampler.Sample(origin, direction, rgb, interpolation, p_o);
  }
};

// The cameras integrator: every camera under the footprint, read along its own ray through p_o
// with its weight. A camera counts where its own line through p_o meets the sampled st domain
// (and, with views in their own windows, its view's window holds the point), as a lens sample
// counts where its line does: at the domain's edge the cameras that still see the point carry
// the pixel, their weights renormalised, and a pixel none of them sees misses. With a taper
// (the quadrilinear limit's) a camera counts by the share of its tent inside its window instead.
// Returns the cameras read.
int RenderPixelCameras(const Frame& frame, int i, int j, float* weights, float out[3]) {
  const VirtualCamera& camera = frame.camera;
  const Vec3 direction = camera.pixel_direction(i, j);
  const Vec3 p_o = camera.focus_point(direction);
  out[0] = out[1] = out[2] = 0.0f;
  float sum[3] = {0, 0, 0};
  int read = 0;
  float held = 0;  // the weights of the cameras that count
  const bool windows = frame.sampler.view_windows();
  const auto accumulate = [&](int row, int col, float w) {
    if (frame.taper) {
      const float a = frame.sampler.AccumulateFocusedTapered(row, col, p_o, w, *frame.taper, sum);
      if (!(a > 0)) return;
      held += a;
      ++read;
      return;
    }
    if (!frame.sampler.CameraLineMeetsStDomain(row, col, p_o)) return;
    const float a = frame.sampler.AccumulateFocused(row, col, p_o, w, sum);
    if (windows && !(a > 0)) return;  // its window misses the point
    held += a;
    ++read;
  };
  if (const auto& uniform = frame.cameras->uniform_weights(); !uniform.empty()) {
    for (const GridCameraWeight& c : uniform) accumulate(c.row, c.col, float(c.weight));
  } else {
    frame.cameras->Weights(frame.cameras->FootprintOf(i, j), weights);
    const int cols = frame.sampler.cols();
    for (int c = 0; c < frame.view_count; ++c)
      if (weights[c] > 0.0f) accumulate(c / cols, c % cols, weights[c]);
  }
  if (!(held > 0)) return 0;
  for (int k = 0; k < 3; ++k) out[k] = sum[k] / held;
  return read;
}

// The depth lookup's antialiased pixel: its rays spread over the pixel's area on the film as well
// as over the lens, as a sensor's pixel integrates (otherwise, as in the paper, every ray passes
// through the pixel's centre). A pinhole's pixel takes 2 x 2 film points; with an aperture, lens
// sample m takes film point m of the R2 sequence (Roberts 2018), uncorrelated with the lens
// pattern.
int RenderPixelDepth(const Frame& frame, int i, int j, float out[3]) {
  const VirtualCamera& camera = frame.camera;
  float sum[3] = {0, 0, 0}, rgb[3];
  int hits = 0;
  const auto add = [&](const Vec3& origin, const Vec3& direction) {
    if (!frame.depth->Sample(origin, direction, rgb)) return;
    for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
    ++hits;
  };
  if (camera.is_pinhole()) {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        add(camera.e_c(), camera.direction_through(i + 0.25 + 0.5 * b, j + 0.25 + 0.5 * a));
  } else {
    constexpr double kA1 = 0.7548776662466927, kA2 = 0.5698402909980532;  // 1/g, 1/g^2 (plastic)
    for (std::size_t m = 0; m < frame.lens_points.size(); ++m) {
      const double x = std::fmod(0.5 + kA1 * double(m), 1.0);
      const double y = std::fmod(0.5 + kA2 * double(m), 1.0);
      const Vec3 p_o = camera.focus_point(camera.direction_through(i + x, j + y));
      add(frame.lens_points[m], p_o - frame.lens_points[m]);
    }
  }
  const float inv = hits > 0 ? 1.0f / float(hits) : 0.0f;
  for (int c = 0; c < 3; ++c) out[c] = sum[c] * inv;
  return hits;
}

// The average radiance over the rays of pixel (i, j) that hit the slab; returns their number.
int RenderPixel(const Frame& frame, int i, int j, float out[3]) {
  if (frame.depth && frame.antialias) return RenderPixelDepth(frame, i, j, out);
  const VirtualCamera& camera = frame.camera;
  const Vec3 direction = camera.pixel_direction(i, j);
  // p_o: where the central ray meets the plane of focus; every lens ray passes through it.
  const Vec3 p_o = camera.focus_point(direction);
  float sum[3] = {0, 0, 0}, rgb[3];
  int hits = 0;
  if (camera.is_pinhole()) {
    hits = frame.Sample(camera.e_c(), direction, sum, p_o) ? 1 : 0;
  } else {
    for (const Vec3& lens : frame.lens_points) {
      if (!frame.Sample(lens, p_o - lens, rgb, p_o)) continue;
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

// Runs `work` on the options' thread count (all cores when 0).
template <typename F>
void RunWithThreads(int threads, const F& work) {
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(work);
  } else {
    work();
  }
}

// Each pixel of `tile`, row by row: pixel(i, j, rgb) writes pixel (i, j)'s colour and returns the
// rays (or cameras) that hit it, which the hit mask and the counts take. Returns their sum.
template <typename Pixel>
long long FillTile(const VirtualCamera& camera, const tbb::blocked_range2d<int>& tile,
                   RenderResult& result, Pixel&& pixel) {
  long long hit = 0;
  for (int j = tile.rows().begin(); j != tile.rows().end(); ++j) {
    const int row = camera.image_row(j);
    auto* out = result.image.ptr<cv::Vec3f>(row);
    auto* mask = result.hit_mask.ptr<std::uint8_t>(row);
    auto* counts = result.counts.ptr<std::int32_t>(row);
    for (int i = tile.cols().begin(); i != tile.cols().end(); ++i) {
      const int hits = pixel(i, j, out[i].val);
      mask[i] = hits > 0 ? 255 : 0;
      counts[i] = hits;
      hit += hits;
    }
  }
  return hit;
}

// A tile of pixels through an aperture, lens sample by lens sample: pixel by pixel, the tile's
// rays for one lens point leave from the same point towards neighbouring points in focus, so
// consecutive rays read the same cameras near the same samples (the views and the depth maps
// stay in cache). Each pixel's rays are summed in RenderPixel's order: the same result to the
// bit. Returns the rays that hit.
long long RenderTileLensOuter(const Frame& frame, const tbb::blocked_range2d<int>& tile,
                              RenderResult& result) {
  const VirtualCamera& camera = frame.camera;
  const int width = int(tile.cols().size());
  const std::size_t n = tile.rows().size() * tile.cols().size();
  std::vector<Vec3> p_o(n);
  std::vector<float> sum(3 * n, 0.0f);
  std::vector<int> hits(n, 0);
  for (int j = tile.rows().begin(); j != tile.rows().end(); ++j)
    for (int i = tile.cols().begin(); i != tile.cols().end(); ++i)
      p_o[std::size_t((j - tile.rows().begin()) * width + (i - tile.cols().begin()))] =
          camera.focus_point(camera.pixel_direction(i, j));
  float rgb[3];
  for (const Vec3& lens : frame.lens_points)
    for (std::size_t at = 0; at < n; ++at) {
      if (!frame.Sample(lens, p_o[at] - lens, rgb, p_o[at])) continue;
      float* out = &sum[3 * at];
      out[0] += rgb[0];
      out[1] += rgb[1];
      out[2] += rgb[2];
      ++hits[at];
    }
  return FillTile(camera, tile, result, [&](int i, int j, float rgb_out[3]) {
    const std::size_t at =
        std::size_t((j - tile.rows().begin()) * width + (i - tile.cols().begin()));
    const float inv = hits[at] > 0 ? 1.0f / float(hits[at]) : 0.0f;
    for (int c = 0; c < 3; ++c) rgb_out[c] = sum[3 * at + c] * inv;
    return hits[at];
  });
}

RenderResult NewResult(const VirtualCamera& camera) {
  RenderResult result;
  result.image = cv::Mat(camera.height(), camera.width(), CV_32FC3);
  result.hit_mask = cv::Mat(camera.height(), camera.width(), CV_8UC1);
  result.counts = cv::Mat(camera.height(), camera.width(), CV_32SC1);
  return result;
}

// `prebuilt`, when given, is the cameras integrator's frame for this camera and the light
// field's slab and grid (the quadrilinear limit's, made for its prefilter).
RenderResult RenderReference(const LightField& lf, const VirtualCamera& camera,
                             const CpuRenderOptions& options,
                             const CameraIntegratorFrame* prebuilt = nullptr) {
  const LightFieldSampler sampler(lf);
  Frame frame{camera, sampler, {}, options.interpolation};
  for (const Vec2& disk : camera.lens_samples())
    frame.lens_points.push_back(camera.lens_point(disk));
  std::optional<CameraIntegratorFrame> cameras;
  std::optional<DepthAwareSampler> depth;
  if (options.interpolation == Interpolation::kDepth) {
    if (options.integrator != Integrator::kLensSamples)
      throw Error(
          "the depth lookup reads each lens sample's own scene point: it goes with the "
          "lens-samples integrator, not the cameras integrator");
    if (!options.depth) throw Error("the depth lookup needs the views' depth maps");
    depth.emplace(lf, *options.depth, sampler);
    depth->set_cubic_reads(DepthLookupReadsCubic(camera, sampler));
    depth->set_blend(options.depth_blend);
    frame.depth = &*depth;
    frame.antialias = options.antialias;
  }
  if (options.integrator == Integrator::kCameras) {
    // A pinhole's limit is the focal-plane lookup itself.
    frame.interpolation = Interpolation::kFocalPlane;
    if (!camera.is_pinhole()) {
      frame.cameras = prebuilt ? prebuilt : &cameras.emplace(lf, camera);
      frame.view_count = lf.dims().rows * lf.dims().cols;
      frame.taper = options.window_taper;
    }
  }

  RenderResult result = NewResult(camera);
  tbb::combinable<long long> hits_per_thread(0);
  // Through an aperture (not the cameras integrator, nor the antialiased depth lookup's own
  // film points) a tile is rendered lens point by lens point.
  const bool lens_outer =
      !frame.cameras && !camera.is_pinhole() && !(frame.depth && frame.antialias);
  const auto render_tile = [&](const tbb::blocked_range2d<int>& tile) {
    long long hits_here = 0;
    std::vector<float> weights(std::size_t(frame.view_count));
    if (lens_outer) {
      hits_here = RenderTileLensOuter(frame, tile, result);
    } else {
      hits_here = FillTile(camera, tile, result, [&](int i, int j, float rgb_out[3]) {
        return frame.cameras ? RenderPixelCameras(frame, i, j, weights.data(), rgb_out)
                             : RenderPixel(frame, i, j, rgb_out);
      });
    }
    hits_per_thread.local() += hits_here;
    if (options.progress)
      options.progress(std::int64_t(tile.rows().size()) * std::int64_t(tile.cols().size()));
  };
  RunWithThreads(options.threads, [&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, camera.height(), 16, 0, camera.width(), 16),
                      render_tile);
  });
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  result.path = frame.depth ? "reference (depth lookup)" : "reference";
  // An antialiased pinhole pixel of the depth lookup casts its 2 x 2 film points
  // (RenderPixelDepth); otherwise a pixel casts one ray a lens sample.
  const long long rays_per_pixel = frame.depth && frame.antialias && camera.is_pinhole()
                                       ? 4
                                       : static_cast<long long>(frame.lens_points.size());
  result.rays = frame.cameras
                    ? result.rays_hit
                    : static_cast<long long>(camera.width()) * camera.height() * rays_per_pixel;
  return result;
}

// Copies pixel row j (bottom-up) from planar kernel output into the result; returns the rays
// that hit (or cameras read) along it.
long long StoreRow(const VirtualCamera& camera, int j, const float* r, const float* g,
                   const float* b, const std::int32_t* count, RenderResult& result) {
  const int row = camera.image_row(j);
  auto* out = result.image.ptr<cv::Vec3f>(row);
  auto* mask = result.hit_mask.ptr<std::uint8_t>(row);
  auto* counts = result.counts.ptr<std::int32_t>(row);
  InterleaveRow(r, g, b, camera.width(), &out[0][0]);
  const int width = camera.width();
  std::copy_n(count, width, counts);
  // Separate loops, each of which the compiler vectorises.
  for (int i = 0; i < width; ++i) mask[i] = count[i] > 0 ? 255 : 0;
  std::int64_t hits = 0;
  for (int i = 0; i < width; ++i) hits += count[i];
  return hits;
}

// A row's buffers for the vectorised kernels, one set per task.
struct RowBuffers {
  std::vector<float> r, g, b;
  std::vector<std::int32_t> count;
  std::vector<float> pixel_weights;  // [camera][pixel], the cameras integrator off-plane
  std::vector<int> cameras;          // those with a weight somewhere in the row
  explicit RowBuffers(int padded) : r(padded), g(padded), b(padded), count(padded) {}
  RowOutput output() { return {r.data(), g.data(), b.data(), count.data()}; }
};

// The cameras integrator's per-pixel weights for row j (a footprint per pixel), camera-major.
void FillPixelWeights(const CameraIntegratorFrame& frame, int views, int width, int j,
                      RowBuffers& buffers) {
  const int padded = PaddedRowWidth(width);
  // Cleared once, then only where the previous row wrote.
  if (buffers.pixel_weights.size() != std::size_t(views) * padded) {
    buffers.pixel_weights.assign(std::size_t(views) * padded, 0.0f);
  } else {
    for (const int c : buffers.cameras)
      std::fill_n(buffers.pixel_weights.begin() + std::ptrdiff_t(c) * padded, padded, 0.0f);
  }
  frame.RowWeights(j, width, std::size_t(padded), buffers.pixel_weights.data(), &buffers.cameras);
}

// The separable frame: bands of rows, each a weighted sum of resized views.
RenderResult RenderSeparable(const LightField& lf, const VirtualCamera& camera,
                             const SeparableFrame& frame, const CpuRenderOptions& options) {
  RaySetup setup(lf, camera, false);
  if (options.window_taper && frame.eye >= 0) setup.SetTaper(*options.window_taper);
  const int width = camera.width(), padded = PaddedRowWidth(width);
  RenderResult result = NewResult(camera);
  tbb::combinable<long long> hits_per_thread(0);
  const auto render_band = [&](const tbb::blocked_range<int>& band) {
    const int j0 = band.begin(), j1 = band.end();
    const std::size_t n = std::size_t(j1 - j0) * std::size_t(padded);
    std::vector<float> r(n), g(n), b(n);
    std::vector<std::int32_t> count(n);
    RenderSeparableBand(frame, setup, j0, j1, {r.data(), g.data(), b.data(), count.data()});
    long long hits_here = 0;
    for (int j = j0; j < j1; ++j) {
      const std::size_t at = std::size_t(j - j0) * std::size_t(padded);
      hits_here += StoreRow(camera, j, r.data() + at, g.data() + at, b.data() + at,
                            count.data() + at, result);
    }
    hits_per_thread.local() += hits_here;
    if (options.progress) options.progress(std::int64_t(j1 - j0) * width);
  };
  RunWithThreads(options.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height(), frame.band_rows), render_band);
  });
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  result.path = fmt::format("separable ({})", KernelTargetName());
  result.rays = frame.eye >= 0 ? result.rays_hit
                               : static_cast<long long>(width) * camera.height() *
                                     static_cast<long long>(camera.lens_samples().size());
  return result;
}

// `prebuilt` as for RenderReference.
RenderResult RenderFast(const LightField& lf, const VirtualCamera& camera,
                        const CpuRenderOptions& options, const CameraIntegratorFrame* prebuilt) {
  const bool lens_samples = options.integrator == Integrator::kLensSamples || camera.is_pinhole();
  // The cameras integrator's weights, worked out once for whichever path renders the frame.
  std::optional<CameraIntegratorFrame> own;
  const CameraIntegratorFrame* cameras = prebuilt;
  if (!lens_samples && cameras == nullptr) cameras = &own.emplace(lf, camera);
  if (const auto separable = MakeSeparableFrame(lf, camera, options, cameras))
    return RenderSeparable(lf, camera, *separable, options);
  if (!FastKernelsSupport(lf)) return RenderReference(lf, camera, options, cameras);
  // A pinhole's limit under the cameras integrator is the focal-plane lookup itself.
  const bool focal_plane = options.integrator == Integrator::kCameras ||
                           options.interpolation == Interpolation::kFocalPlane;
  RaySetup setup(lf, camera, lens_samples);
  if (!lens_samples && options.window_taper) setup.SetTaper(*options.window_taper);
  const int views = lf.dims().rows * lf.dims().cols;
  const int width = camera.width(), padded = PaddedRowWidth(width);

  RenderResult result = NewResult(camera);
  tbb::combinable<long long> hits_per_thread(0);
  const auto render_rows = [&](const tbb::blocked_range<int>& rows) {
    RowBuffers buffers(padded);
    long long hits_here = 0;
    for (int j = rows.begin(); j != rows.end(); ++j) {
      if (lens_samples) {
        RenderRowLensSamples(setup, focal_plane, j, buffers.output());
      } else {
        // The cameras integrator where the frame is not separable (a turned camera, views in
        // windows their reads leave): camera by camera through its few sample rows when they
        // are few, else by gathers pixel by pixel.
        // Either one weight list for every pixel, or per-pixel weights for the listed cameras.
        const auto& uniform = cameras->uniform_weights();
        if (uniform.empty()) FillPixelWeights(*cameras, views, width, j, buffers);
        const int uniform_count = int(uniform.size());
        const int camera_count = uniform.empty() ? int(buffers.cameras.size()) : 0;
        const float* weights = uniform.empty() ? buffers.pixel_weights.data() : nullptr;
        const int* listed = uniform.empty() ? buffers.cameras.data() : nullptr;
        if (!RenderRowCamerasResampled(setup, uniform.data(), uniform_count, weights, listed,
                                       camera_count, j, buffers.output()))
          RenderRowCameras(setup, uniform.data(), uniform_count, weights, listed, camera_count, j,
                           buffers.output());
      }
      hits_here += StoreRow(camera, j, buffers.r.data(), buffers.g.data(), buffers.b.data(),
                            buffers.count.data(), result);
    }
    hits_per_thread.local() += hits_here;
    if (options.progress) options.progress(std::int64_t(rows.size()) * width);
  };
  RunWithThreads(options.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height(), 4), render_rows);
  });
  result.rays_hit = hits_per_thread.combine(std::plus<>());
  result.path = fmt::format("rows ({})", KernelTargetName());
  result.rays = lens_samples ? static_cast<long long>(width) * camera.height() *
                                   static_cast<long long>(setup.lens_uv.size())
                             : result.rays_hit;
  return result;
}

// The vectorised kernels where they can render the frame, else the reference; `prebuilt` as for
// RenderReference.
RenderResult RenderEither(const LightField& lf, const VirtualCamera& camera,
                          const CpuRenderOptions& options,
                          const CameraIntegratorFrame* prebuilt = nullptr) {
  if (options.reference || !RowKernelsSupport(lf) || options.interpolation == Interpolation::kDepth)
    return RenderReference(lf, camera, options, prebuilt);
  return RenderFast(lf, camera, options, prebuilt);
}

}  // namespace

RenderResult RenderLightFieldCpu(const LightField& lf, const VirtualCamera& camera,
                                 const CpuRenderOptions& options) {
  if (options.window_taper &&
      options.window_taper->windows.size() != std::size_t(lf.dims().view_count()))
    throw Error(fmt::format("the window taper has {} views' windows for a light field of {} views",
                            options.window_taper->windows.size(), lf.dims().view_count()));
  if (options.integrator == Integrator::kCamerasQuadrilinear) {
    // The cameras integrator over views prefiltered by the hat scaled by k.
    if (options.interpolation == Interpolation::kDepth)
      throw Error(
          "the depth lookup reads each lens sample's own scene point: it goes with the "
          "lens-samples integrator, not the cameras integrators");
    CpuRenderOptions focal = options;
    focal.integrator = Integrator::kCameras;
    focal.interpolation = Interpolation::kFocalPlane;
    StPrefilter prefilter = QuadrilinearLimitPrefilter(lf, camera);
    if (camera.is_pinhole() || (prefilter.h_s < 1e-3 && prefilter.h_t < 1e-3))
      return RenderEither(lf, camera, focal);
    // The filtered copy keeps the samples the tent leaves distinct, so that its cost follows
    // the frame's footprint on the views, not the light field's sampling.
    prefilter.stride_s = PrefilterStride(prefilter.h_s, lf.dims().n_s);
    prefilter.stride_t = PrefilterStride(prefilter.h_t, lf.dims().n_t);
    // Only the views some pixel reads are filtered; the filtered copy has the same slab and
    // grid of cameras, so the cameras' weights serve its render too.
    const CameraIntegratorFrame cameras(lf, camera);
    LightField own;
    SampleBuffer memory;
    const LightField* filtered = &own;
    bool kept = false;
    if (options.prefilter_cache) {
      filtered = &options.prefilter_cache->Filtered(lf, prefilter, camera, cameras.CamerasRead());
      kept = options.prefilter_cache->last_filtered_samples() == 0;
    } else {
      // The last frame's memory where the copy fits in it, else none held while the new is
      // taken (as PrefilterCache does).
      if (options.prefilter_memory) memory = options.prefilter_memory->Take();
      if (memory.size() < PrefilteredCopyBytes(lf, prefilter.stride_s, prefilter.stride_t))
        memory = SampleBuffer();
      own = PrefilteredCopy(lf, prefilter.stride_s, prefilter.stride_t, memory);
      PrefilterViews(lf, prefilter, ViewRegionsRead(own, camera, cameras.CamerasRead()), &own);
    }
    // Each camera fades out as its tent leaves its view's window, as the lens samples do.
    const WindowTaper taper = QuadrilinearLimitTaper(lf, *filtered, prefilter);
    focal.window_taper = &taper;
    RenderResult result = RenderEither(*filtered, camera, focal, &cameras);
    // The memory back once the frame is done with it (not on an error: then it goes).
    if (options.prefilter_memory && !options.prefilter_cache)
      options.prefilter_memory->Give(memory.size() > 0 ? memory : own.samples());
    result.path =
        fmt::format("{}, views prefiltered ({:.2f} x {:.2f} samples, kept every {} x {}{})",
                    result.path, prefilter.h_s, prefilter.h_t, prefilter.stride_s,
                    prefilter.stride_t, kept ? ", from the last frame" : "");
    return result;
  }
  return RenderEither(lf, camera, options);
}

}  // namespace lfcam
