// Views in their own st windows (format version 4) against the same samples on a shared grid:
// every renderer (the scalar reference, the vectorised kernels, the GL shader) reads a view in
// its own window, so where every view holds a point the frames are the shared grid's; where
// only some do, the blend is renormalised over those (no black, no smeared edge), and a point
// none holds misses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/gl_renderer.h"
#include "lfcam/render/lightfield_sampler.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/scene.h"

namespace lfcam::view_windows_test {
namespace {

constexpr int kMargin = 6;  // each view loses this many samples on every side, moved by up to it

StOffset OffsetOf(int r, int c) {
  return {(3 * r + 5 * c) % (2 * kMargin + 1) - kMargin, (7 * r + c) % (2 * kMargin + 1) - kMargin};
}

// `shared` with each view in its own window: view (r, c) keeps n - 2 m samples each way, those of
// `shared` from m + OffsetOf(r, c); the reference grid is shared's moved in by m.
LightField Windowed(const LightField& shared) {
  LightFieldDims dims = shared.dims();
  dims.n_s -= 2 * kMargin;
  dims.n_t -= 2 * kMargin;
  Slab slab = shared.slab();
  const StDomain& d = shared.slab().st_domain;
  const double ds = d.s_extent() / shared.dims().n_s, dt = d.t_extent() / shared.dims().n_t;
  slab.st_domain = {d.s0 + kMargin * ds, d.t0 + kMargin * dt, d.s1 - kMargin * ds,
                    d.t1 - kMargin * dt};
  LightField out(dims, SampleType::kSrgb8, slab);
  out.set_measured_poses(shared.measured_poses());
  std::vector<StOffset> offsets;
  for (int r = 0; r < dims.rows; ++r)
    for (int c = 0; c < dims.cols; ++c) {
      const StOffset o = OffsetOf(r, c);
      offsets.push_back(o);
      for (int l = 0; l < dims.n_t; ++l)
        std::copy_n(shared.view_data(r, c) +
                        (std::size_t(l + kMargin + o.l) * shared.dims().n_s + kMargin + o.k) * 3,
                    std::size_t(dims.n_s) * 3,
                    out.mutable_view_data(r, c) + std::size_t(l) * dims.n_s * 3);
    }
  out.set_st_offsets(offsets);
  return out;
}

const LightField& WindowedPaperLightField() {
  static const LightField lf = Windowed(render_test::SmallPaperLightField());
  return lf;
}

// Which pixels every view holds: the pixel's central line meets the st-plane at least `slack`
// samples inside the windows' common part (shared's grid).
cv::Mat HeldByEveryView(const LightField& shared, const VirtualCamera& camera, double slack) {
  const LightFieldSampler sampler(shared);
  const int n_s = shared.dims().n_s, n_t = shared.dims().n_t;
  cv::Mat mask(camera.height(), camera.width(), CV_8UC1, cv::Scalar(0));
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i) {
      double k, l;
      if (!sampler.StSampleAt(camera.e_c(), camera.focus_point(camera.pixel_direction(i, j)), k, l))
        continue;
      const double lo = 2 * kMargin + slack;
      if (k >= lo && k <= n_s - 1 - lo && l >= lo && l <= n_t - 1 - lo)
        mask.at<uchar>(camera.image_row(j), i) = 255;  // j counts from the bottom
    }
  return mask;
}

double MaxDifference(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  double largest = 0;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x)
      if (mask.at<uchar>(y, x)) {
        const cv::Vec3f d = difference.at<cv::Vec3f>(y, x);
        largest = std::max<double>(largest, std::max({d[0], d[1], d[2]}));
      }
  return largest;
}

RenderResult Cpu(const LightField& lf, const render_test::Case& c, bool reference) {
  CpuRenderOptions o;
  o.integrator = c.integrator;
  o.interpolation = c.interpolation;
  o.reference = reference;
  return RenderLightFieldCpu(lf, VirtualCamera(c.camera), o);
}

TEST(ViewWindows, EveryCpuPathReadsEachViewInItsOwnWindow) {
  const LightField& shared = render_test::SmallPaperLightField();
  const LightField& windowed = WindowedPaperLightField();
  ASSERT_TRUE(windowed.has_view_windows());
  int compared = 0, separable = 0;
  for (const render_test::Case& c : render_test::Cases()) {
    if (c.turned) continue;
    const VirtualCamera camera(c.camera);
    // Lens rays spread around the central line's point by the aperture's image on the plane.
    const cv::Mat held = HeldByEveryView(shared, camera, 4);
    if (cv::countNonZero(held) < 50) continue;
    ++compared;
    for (const bool reference : {true, false}) {
      const RenderResult a = Cpu(shared, c, reference), b = Cpu(windowed, c, reference);
      const std::string where = c.name + (reference ? " (reference)" : " (" + b.path + ")");
      EXPECT_LT(MaxDifference(a.image, b.image, held), 2e-4) << where;
      if (!reference && b.path.rfind("separable", 0) == 0) ++separable;
    }
  }
  EXPECT_GE(compared, 8);
  // Frames whose reads all stay inside their views' windows keep the separable path.
  EXPECT_GT(separable, 0);
}

// The quadrilinear limit's cameras fade as their tents leave their own windows (render/
// window_taper.h): the vectorised paths (the separable frame, whose terms then take the per-pixel
// share, and the rows) weigh each camera as the scalar reference does.
TEST(ViewWindows, TheQuadrilinearLimitFadesAtEachViewsWindowAlikeOnEveryCpuPath) {
  const LightField& windowed = WindowedPaperLightField();
  int separable = 0, rows = 0;
  for (render_test::Case c : render_test::Cases()) {
    if (c.turned || c.integrator != Integrator::kCameras || c.camera.aperture_mm <= 0) continue;
    c.integrator = Integrator::kCamerasQuadrilinear;
    c.interpolation = Interpolation::kQuadrilinear;
    const RenderResult a = Cpu(windowed, c, true), b = Cpu(windowed, c, false);
    const std::string where = c.name + " (" + b.path + ")";
    EXPECT_LE(cv::norm(a.image, b.image, cv::NORM_INF), 1.0 / 255) << where;
    EXPECT_EQ(cv::countNonZero(a.hit_mask != b.hit_mask), 0) << where;
    (b.path.rfind("separable", 0) == 0 ? separable : rows) += 1;
  }
  EXPECT_GT(separable, 0);
  EXPECT_GT(rows, 0);
}

// Near the union's edge only some views hold a point: their blend, renormalised, is close to the
// shared grid's (the same scene through fewer cameras), never darkened toward black or smeared
// from a window's edge; outside every window nothing is read.
TEST(ViewWindows, APointSomeViewsMissIsTheBlendOfThoseThatHoldIt) {
  const LightField& shared = render_test::SmallPaperLightField();
  const LightField& windowed = WindowedPaperLightField();
  const Vec3 centre = shared.slab().uv.center();
  VirtualCameraParams p;
  p.width = 96;
  p.height = 80;
  p.eye = centre;
  p.look_at = centre - Vec3(0, 0, 4000);
  p.focal_length_mm = 45;  // wide: past the union's edges
  p.focus_distance_mm = 3600;
  const VirtualCamera camera(p);
  const cv::Mat held = HeldByEveryView(shared, camera, 1);
  for (const bool reference : {true, false}) {
    CpuRenderOptions o;
    o.reference = reference;
    const RenderResult a = RenderLightFieldCpu(shared, camera, o);
    const RenderResult b = RenderLightFieldCpu(windowed, camera, o);
    // The windows' union is shared's grid less (margin - |offset|) on each side: the pixels the
    // windowed field hits but not every view holds.
    const cv::Mat some = b.hit_mask & ~held;
    ASSERT_GT(cv::countNonZero(some), 100);
    EXPECT_LT(cv::countNonZero(b.hit_mask), cv::countNonZero(a.hit_mask));  // the union is smaller
    cv::Mat difference;
    cv::absdiff(a.image, b.image, difference);
    const cv::Scalar mean = cv::mean(difference, some);
    EXPECT_LT((mean[0] + mean[1] + mean[2]) / 3, 0.02) << (reference ? "reference" : b.path);
    // The pixels there are as bright as the shared grid's: nothing black mixed in.
    const cv::Scalar bright_a = cv::mean(a.image, some), bright_b = cv::mean(b.image, some);
    EXPECT_NEAR(bright_b[1], bright_a[1], 0.02 * bright_a[1] + 1e-3);
  }
}

TEST(ViewWindows, TheGlRendererReadsEachViewInItsOwnWindow) {
  std::unique_ptr<GlRenderer> gl;
  try {
    gl = std::make_unique<GlRenderer>();
  } catch (const Error& e) {
    if (testing::GlRequired()) FAIL() << "LFCAM_REQUIRE_GL=1 but no GL 4.3 context: " << e.what();
    GTEST_SKIP() << "no GL 4.3 context could be made: " << e.what();
  }
  const LightField& windowed = WindowedPaperLightField();
  // The views' true depth maps, each in its view's own window, for the depth lookup.
  const Scene scene = MakePaperScene();
  DepthSet truth(windowed.dims());
  for (int r = 0; r < windowed.dims().rows; ++r)
    for (int c = 0; c < windowed.dims().cols; ++c)
      truth.set(GroundTruthDepth(scene, windowed, r, c).map);
  // Every case; and the cameras integrator's also as its quadrilinear limit, the focal-plane
  // lookup's also as the depth lookup.
  std::vector<render_test::Case> cases;
  for (const render_test::Case& c : render_test::Cases()) {
    if (c.turned) continue;
    cases.push_back(c);
    render_test::Case other = c;
    if (c.integrator == Integrator::kCameras) {
      other.integrator = Integrator::kCamerasQuadrilinear;
      other.interpolation = Interpolation::kQuadrilinear;
      cases.push_back(other);
    } else if (c.interpolation == Interpolation::kFocalPlane) {
      other.interpolation = Interpolation::kDepth;
      cases.push_back(other);
    }
  }
  for (const render_test::Case& c : cases) {
    const VirtualCamera camera(c.camera);
    CpuRenderOptions cpu_options;
    cpu_options.integrator = c.integrator;
    cpu_options.interpolation = c.interpolation;
    if (c.interpolation == Interpolation::kDepth) cpu_options.depth = &truth;
    const RenderResult cpu = RenderLightFieldCpu(windowed, camera, cpu_options);
    GlRenderOptions o;
    o.integrator = c.integrator;
    o.interpolation = c.interpolation;
    o.depth = cpu_options.depth;
    const RenderResult frame = gl->Render(windowed, camera, o);
    const cv::Mat both = frame.hit_mask & cpu.hit_mask;
    ASSERT_GT(cv::countNonZero(both), 0) << c.name;
    EXPECT_LT(MaxDifference(frame.image, cpu.image, both), 3.0 / 255) << c.name;
    EXPECT_LT(double(cv::countNonZero(frame.hit_mask != cpu.hit_mask)) / double(both.total()), 0.01)
        << c.name;
  }
}

}  // namespace
}  // namespace lfcam::view_windows_test
