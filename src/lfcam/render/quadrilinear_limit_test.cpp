#include "lfcam/render/quadrilinear_limit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "lfcam/core/error.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"
#include "lfcam/sim/test_paper_lightfield.h"

namespace lfcam {
namespace {

TEST(QuadrilinearLimit, TapsCarryTheTentsSpreadForTheBilinearReadToFinish) {
  EXPECT_EQ(PrefilterTaps(0.0), std::vector<float>{1.0f});
  for (const double h : {0.3, 1.0, 1.41, 2.5, 7.25, 30.0}) {
    SCOPED_TRACE(h);
    const std::vector<float> taps = PrefilterTaps(h);
    ASSERT_EQ(taps.size() % 2, 1u);
    const int n = int(taps.size()) / 2;
    double total = 0, variance = 0;
    for (int d = -n; d <= n; ++d) {
      const float t = taps[std::size_t(d + n)];
      EXPECT_GE(t, 0.0f);
      EXPECT_FLOAT_EQ(t, taps[std::size_t(n - d)]);
      total += t;
      variance += t * d * d;
    }
    EXPECT_NEAR(total, 1.0, 1e-6);
    // With the bilinear read's tent_1 after them, the spread of tent_1 * tent_h: the taps carry
    // tent_h's variance, h^2 / 6.
    EXPECT_NEAR(variance, h * h / 6, 1e-5 * (1 + h * h));
    // Reaching no farther than the tent does.
    EXPECT_LE(n, int(std::ceil(h)) + 1);
    // For a copy kept every m samples, whose bilinear read is a tent of half-width m, the
    // rest of the variance: the stride chosen leaves the taps a tent twice its width (m of 4
    // and more) or 1.45 times it (2 and 3), and no wider stride would.
    const int m = PrefilterStride(h, 1000);
    const std::vector<float> strided = PrefilterTaps(h, m);
    const int reach = int(strided.size()) / 2;
    double spread = 0;
    for (int d = -reach; d <= reach; ++d) spread += strided[std::size_t(d + reach)] * d * d;
    EXPECT_NEAR(spread, (h * h + 1 - m * m) / 6, 1e-5 * (1 + h * h));
    const auto width = [&](int stride) {
      return std::sqrt(std::max(0.0, h * h + 1 - stride * stride));
    };
    if (m > 1) {
      EXPECT_GE(width(m), (m <= 3 ? 1.45 : 2.0) * m);
    }
    EXPECT_LT(width(m + 1), (m + 1 <= 3 ? 1.45 : 2.0) * (m + 1));
  }
  EXPECT_EQ(PrefilterStride(30.0, 1000), 13);
  EXPECT_EQ(PrefilterStride(30.0, 100), 6);  // 16 samples or more kept
}

RenderResult Render(const LightField& lf, const VirtualCameraParams& p, Integrator integrator,
                    Interpolation interpolation, double lens_rate = 4) {
  VirtualCameraParams q = p;
  q.lens_rate = lens_rate;
  CpuRenderOptions o;
  o.integrator = integrator;
  o.interpolation = interpolation;
  return RenderLightFieldCpu(lf, VirtualCamera(q), o);
}

// PSNR of two linear renders against a peak of 1, over the pixels both hit: at the st domain's
// edges the integrators count a pixel as hit differently (the lens samples ray by ray, the
// cameras integrators by the pixel's central line).
double LinearPsnr(const RenderResult& a, const RenderResult& b, bool most_hit = true) {
  const cv::Mat both = a.hit_mask & b.hit_mask;
  double sum = 0;
  int n = 0;
  for (int y = 0; y < both.rows; ++y)
    for (int x = 0; x < both.cols; ++x) {
      if (!both.at<std::uint8_t>(y, x)) continue;
      const cv::Vec3f d = a.image.at<cv::Vec3f>(y, x) - b.image.at<cv::Vec3f>(y, x);
      sum += d.dot(d);
      n += 3;
    }
  if (most_hit) {
    EXPECT_GT(n, int(both.total()));  // most pixels hit in both
  }
  return 10.0 * std::log10(1.0 / std::max(sum / std::max(n, 1), 1e-30));
}

// Puts view (r, c) of `lf` in a window of its own, `offset(r, c)` samples from the reference grid.
template <typename Offset>
void SetViewWindows(LightField& lf, Offset&& offset) {
  std::vector<StOffset> offsets;
  for (int r = 0; r < lf.dims().rows; ++r)
    for (int c = 0; c < lf.dims().cols; ++c) offsets.push_back(offset(r, c));
  lf.set_st_offsets(std::move(offsets));
}

struct LimitCase {
  render_test::ConvergenceCamera camera;
  double floor_db;  // what the limit must reach against gamma 256
};

// The paper's estimator (lens samples, quadrilinear lookup) converges to the quadrilinear limit
// as the lens sampling rate grows, for focus on both sides of the st-plane, an eye in front of
// the array, no breathing, and a turned camera (whose plane of focus is not parallel to the
// st-plane: one filter for the frame, taken at its centre); where the focal-plane limit shows
// the copies one camera apart, the quadrilinear limit is the estimator's smooth blur.
TEST(QuadrilinearLimit, IsTheLimitOfLensSamplesWithTheQuadrilinearLookup) {
  const LightField lf = testing::SharedPaperLightField();
  for (const LimitCase& c : {
           LimitCase{{"near focus", {300, 275, 3600}, {300, 275, 0}, 500, 3400, 192, true}, 40},
           LimitCase{{"far focus", {300, 275, 3600}, {300, 275, 0}, 500, 5200, 192, true}, 40},
           LimitCase{
               {"in front, no breathing", {250, 300, 3000}, {250, 300, 0}, 300, 4700, 96, false},
               38},
           LimitCase{{"turned 2.8 degrees", {300, 275, 3600}, {450, 200, 0}, 500, 4700, 192, true},
                     35},
       }) {
    SCOPED_TRACE(c.camera.name);
    const VirtualCameraParams p = c.camera.Params(48);
    const RenderResult limit =
        Render(lf, p, Integrator::kCamerasQuadrilinear, Interpolation::kQuadrilinear);
    const RenderResult at_64 =
        Render(lf, p, Integrator::kLensSamples, Interpolation::kQuadrilinear, 64);
    const RenderResult at_256 =
        Render(lf, p, Integrator::kLensSamples, Interpolation::kQuadrilinear, 256);
    const double psnr_64 = LinearPsnr(at_64, limit), psnr_256 = LinearPsnr(at_256, limit);
    const double focal_plane =
        LinearPsnr(at_256, Render(lf, p, Integrator::kCameras, Interpolation::kFocalPlane));
    std::cout << "[" << c.camera.name << "] lens samples against the quadrilinear limit: gamma 64 "
              << psnr_64 << " dB, gamma 256 " << psnr_256 << " dB; the focal-plane limit "
              << focal_plane << " dB\n";
    EXPECT_GT(psnr_256, psnr_64 - 0.05);
    EXPECT_GT(psnr_256, c.floor_db);
    EXPECT_GT(psnr_256, focal_plane + 3.0);
  }
}

// Where a strongly defocused frame reaches past the views' edges (the sampled domain's, or each
// view's own window), the lens samples drop their rays one by one as they leave, and a camera's
// share of the blend fades; the limit counts each camera by the share of its tent inside its
// window (render/window_taper.h), so it fades alike. Counting the camera wholly or not at all,
// as the focal-plane reads do, steps the blend from row to row and column to column: bands.
// Over the pixels the lens samples hit with half their rays or more, within 12 pixels of the
// frame's edges: 48.0–53.6 dB (45.8–51.8 with the hard edges); the whole frame 46.2–51.4 dB
// (46.0–50.4). Larger frames show more (docs/fidelity.md).
TEST(QuadrilinearLimit, ACameraFadesOutAsItsTentLeavesItsWindowAsTheLensSamplesDo) {
  LightField lf = testing::SharedPaperLightField();
  for (const bool windows : {false, true}) {
    if (windows) SetViewWindows(lf, [](int r, int c) { return StOffset{3 * c - 14, 2 * r - 9}; });
    for (const render_test::ConvergenceCamera& c : {
             render_test::ConvergenceCamera{
                 "wide, far focus", {300, 275, 3600}, {300, 275, 0}, 250, 9000, 256, true},
             render_test::ConvergenceCamera{
                 "wide, near focus", {250, 250, 3600}, {250, 250, 0}, 250, 2000, 192, true},
         }) {
      SCOPED_TRACE(std::string(c.name) + (windows ? ", views in windows" : ""));
      const VirtualCameraParams p = c.Params(72);
      const RenderResult limit =
          Render(lf, p, Integrator::kCamerasQuadrilinear, Interpolation::kQuadrilinear);
      const RenderResult lens =
          Render(lf, p, Integrator::kLensSamples, Interpolation::kQuadrilinear, 64);
      // The frame reaches past the edges: some lens samples miss.
      ASSERT_LT(lens.rays_hit, lens.rays);
      const long long per_pixel = lens.rays / (long long)lens.counts.total();
      RenderResult compared = lens;
      compared.hit_mask = lens.counts >= int(per_pixel / 2);
      cv::Mat edges = compared.hit_mask.clone();
      edges(cv::Rect(12, 12, edges.cols - 24, edges.rows - 24)).setTo(0);
      const double psnr = LinearPsnr(compared, limit);
      compared.hit_mask = edges;
      const double at_edges = LinearPsnr(compared, limit, false);
      std::cout << "[" << c.name << (windows ? ", windows" : "")
                << "] lens samples against the limit " << psnr << " dB, at the frame's edges "
                << at_edges << " dB\n";
      EXPECT_GT(psnr, 45.0);
      EXPECT_GT(at_edges, 47.5);
    }
  }
}

// The taper's windows are the light field's views', one each: any other count is refused.
TEST(QuadrilinearLimit, ATaperForAnotherLightFieldIsRefused) {
  const LightField& lf = render_test::SmallPaperLightField();
  WindowTaper taper;
  taper.h_k = taper.h_l = 2;
  taper.windows.assign(lf.dims().view_count() - 1, {-0.5f, -0.5f, 10.5f, 10.5f});
  CpuRenderOptions o;
  o.integrator = Integrator::kCameras;
  o.window_taper = &taper;
  VirtualCameraParams p;
  p.width = p.height = 8;
  p.aperture_mm = 50;
  EXPECT_THROW(RenderLightFieldCpu(lf, VirtualCamera(p), o), Error);
}

// The CPU renderer keeps the filtered views every m samples where the tent is wide enough
// (PrefilterStride), reading the copy bilinearly between its samples: its frames are the frames
// of the whole filtered copy to within the decimation's aliasing, for views that share the
// light field's window and for views in windows of their own (offsets that are not multiples of
// the stride: each view's copy starts up to m - 1 samples before its window).
TEST(QuadrilinearLimit, AStridedCopyRendersAsTheWholeCopyDoes) {
  LightField lf = testing::SharedPaperLightField();
  const auto whole_copy = [](const LightField& source, const VirtualCamera& camera) {
    const StPrefilter f = QuadrilinearLimitPrefilter(source, camera);
    LightField copy = PrefilteredCopy(source, 1, 1);
    const LightFieldDims& d = source.dims();
    PrefilterViews(source, f, std::vector<cv::Rect>(d.view_count(), cv::Rect(0, 0, d.n_s, d.n_t)),
                   &copy);
    CpuRenderOptions o;
    o.integrator = Integrator::kCameras;
    o.interpolation = Interpolation::kFocalPlane;
    return RenderLightFieldCpu(copy, camera, o);
  };
  int even = 0, odd = 0;
  for (const bool windows : {false, true}) {
    if (windows)
      SetViewWindows(lf, [](int r, int c) { return StOffset{(c % 5) - 2, (r % 4) - 1}; });
    for (const render_test::ConvergenceCamera& c : {
             render_test::ConvergenceCamera{
                 "far focus", {300, 275, 3600}, {300, 275, 0}, 500, 9000, 192, true},
             render_test::ConvergenceCamera{
                 "farther focus", {300, 275, 3600}, {300, 275, 0}, 500, 12000, 128, true},
             render_test::ConvergenceCamera{
                 "near focus", {300, 275, 3600}, {300, 275, 0}, 300, 2000, 256, true},
             render_test::ConvergenceCamera{
                 "in front", {250, 300, 2500}, {250, 300, 0}, 300, 7000, 96, false},
         }) {
      SCOPED_TRACE(std::string(c.name) + (windows ? ", views in windows" : ""));
      const VirtualCamera camera(c.Params(96));
      const StPrefilter f = QuadrilinearLimitPrefilter(lf, camera);
      const int m = PrefilterStride(f.h_s, lf.dims().n_s);
      const RenderResult ours =
          Render(lf, c.Params(96), Integrator::kCamerasQuadrilinear, Interpolation::kQuadrilinear);
      const double psnr = LinearPsnr(ours, whole_copy(lf, camera));
      std::cout << "[" << c.name << (windows ? ", windows" : "") << "] tent " << f.h_s
                << " samples, kept every " << m << ": " << psnr << " dB from the whole copy\n";
      (m % 2 == 0 ? even : odd) += m > 1;
      EXPECT_GT(psnr, 50.0);
    }
  }
  EXPECT_GE(even, 2);  // both kinds of stride: copy samples on their cells' centres and beside
  EXPECT_GE(odd, 2);
}

// Each view's strided copy covers the view's own window, and its samples stand on the view's
// own samples: with no filter left for the taps (h^2 + 1 <= m^2), copy sample k is the view's
// sample m (k + O) + (m - 1) / 2 - o, rounded down (its edge repeated beyond it), for odd and
// even strides and offsets of either sign.
TEST(QuadrilinearLimit, EachViewsStridedCopyStandsOnItsOwnSamplesAndCoversItsWindow) {
  LightField lf = render_test::SmallPaperLightField();
  const LightFieldDims& d = lf.dims();
  std::vector<StOffset> offsets;
  for (int v = 0; v < int(d.view_count()); ++v) offsets.push_back({v % 7 - 3, v % 5 - 4});
  lf.set_st_offsets(offsets);
  for (const int m : {2, 3, 4, 5}) {
    SCOPED_TRACE(m);
    StPrefilter f;
    f.h_s = f.h_t = 1.0;
    f.stride_s = f.stride_t = m;
    ASSERT_EQ(PrefilterTaps(f.h_s, m), std::vector<float>{1.0f});
    LightField copy = PrefilteredCopy(lf, m, m);
    ASSERT_LE(copy.dims().n_s, (d.n_s + 2 * m) / m);
    const cv::Rect everything(0, 0, copy.dims().n_s, copy.dims().n_t);
    PrefilterViews(lf, f, std::vector<cv::Rect>(d.view_count(), everything), &copy);
    for (int v = 0; v < int(d.view_count()); ++v) {
      const int r = v / d.cols, c = v % d.cols;
      const StSampling own = lf.st_sampling(r, c), kept = copy.st_sampling(r, c);
      EXPECT_LE(kept.domain.s0, own.domain.s0 + 1e-12);
      EXPECT_LE(kept.domain.t0, own.domain.t0 + 1e-12);
      EXPECT_GE(kept.domain.s1, own.domain.s1 - 1e-12);
      EXPECT_GE(kept.domain.t1, own.domain.t1 - 1e-12);
      for (int l = 0; l < copy.dims().n_t; l += 3)
        for (int k = 0; k < copy.dims().n_s; ++k) {
          const double at_k = own.k_of(kept.s_of(k)), at_l = own.l_of(kept.t_of(l));
          ASSERT_NEAR(at_k, std::round(at_k), 1e-9);
          ASSERT_NEAR(at_l, std::round(at_l), 1e-9);
          const int vk = std::clamp(int(std::round(at_k)), 0, d.n_s - 1);
          const int vl = std::clamp(int(std::round(at_l)), 0, d.n_t - 1);
          ASSERT_EQ(copy.linear_rgb(r, c, k, l), lf.linear_rgb(r, c, vk, vl))
              << "view " << v << ", copy sample " << k << ", " << l;
        }
    }
  }
}

TEST(QuadrilinearLimit, APinholeOrFocusOnTheStPlaneIsTheFocalPlaneLookup) {
  VirtualCameraParams p;
  p.width = p.height = 32;
  p.eye = Vec3(300, 275, 3600);  // the array's centre, looking along its normal
  p.look_at = Vec3(300, 275, 0);
  p.focal_length_mm = 500;
  p.aperture_mm = 0;
  const LightField& lf = render_test::GridPaperLightField();
  EXPECT_EQ(
      cv::norm(Render(lf, p, Integrator::kCamerasQuadrilinear, Interpolation::kQuadrilinear).image,
               Render(lf, p, Integrator::kCameras, Interpolation::kFocalPlane).image, cv::NORM_INF),
      0.0);
  // The st-plane is the world board's plane, z = 0; the array 3.6 m from it.
  p.aperture_mm = 192;
  p.focus_distance_mm = 3600;
  const StPrefilter f =
      QuadrilinearLimitPrefilter(render_test::GridPaperLightField(), VirtualCamera(p));
  EXPECT_NEAR(f.k, 0.0, 1e-9);
  p.focus_distance_mm = 7200;  // twice as far: k = 1/2
  EXPECT_NEAR(QuadrilinearLimitPrefilter(render_test::GridPaperLightField(), VirtualCamera(p)).k,
              0.5, 1e-9);
}

// Filtering a region gives the samples the whole view filtered gives there: the filter reads the
// view's real samples around the region and repeats the view's own edge only beyond it, for
// regions in the middle, along each edge and at the corners, in 8-bit and half-float views.
TEST(QuadrilinearLimit, AFilteredRegionIsTheWholeFilteredViewThere) {
  const LightField& bytes = render_test::SmallPaperLightField();
  const LightFieldDims& d = bytes.dims();
  LightField halves(d, SampleType::kLinearF16, bytes.slab());
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c)
      for (int l = 0; l < d.n_t; ++l)
        for (int k = 0; k < d.n_s; ++k)
          halves.set_linear_rgb(r, c, k, l, bytes.linear_rgb(r, c, k, l));
  StPrefilter filter;
  filter.h_s = 4.3;  // 9 taps along s
  filter.h_t = 2.2;  // 5 along t
  const cv::Rect whole(0, 0, d.n_s, d.n_t);
  const cv::Rect cuts[] = {{30, 20, 17, 25}, {0, 10, 12, 30}, {70, 5, 26, 9},
                           {40, 0, 9, 3},    {0, 0, 5, 6},    {90, 80, 6, 8},
                           {2, 84, 93, 4},   {1, 1, 94, 86},  {95, 87, 1, 1}};
  for (const LightField* lf : {&bytes, static_cast<const LightField*>(&halves)}) {
    const std::vector<cv::Rect> everything(d.view_count(), whole);
    LightField reference = PrefilteredCopy(*lf, 1, 1);
    PrefilterViews(*lf, filter, everything, &reference);
    std::vector<cv::Rect> regions(d.view_count());
    for (std::size_t v = 0; v < regions.size(); ++v) regions[v] = cuts[v % std::size(cuts)];
    LightField cut = PrefilteredCopy(*lf, 1, 1);
    PrefilterViews(*lf, filter, regions, &cut);
    int compared = 0;
    for (int v = 0; v < int(d.view_count()); ++v) {
      const cv::Rect& region = regions[std::size_t(v)];
      for (int l = region.y; l < region.br().y; ++l)
        for (int k = region.x; k < region.br().x; ++k, ++compared) {
          ASSERT_EQ(cut.linear_rgb(v / d.cols, v % d.cols, k, l),
                    reference.linear_rgb(v / d.cols, v % d.cols, k, l))
              << ToString(lf->sample_type()) << " view " << v << " sample " << k << ", " << l;
        }
      // Outside its region a view is left black.
      const int k = region.x > 0 ? 0 : d.n_s - 1, l = region.y > 0 ? 0 : d.n_t - 1;
      if (!region.contains({k, l})) {
        EXPECT_EQ(cut.linear_rgb(v / d.cols, v % d.cols, k, l), Eigen::Vector3f::Zero());
      }
    }
    EXPECT_GT(compared, 10000);
  }
}

}  // namespace
}  // namespace lfcam
