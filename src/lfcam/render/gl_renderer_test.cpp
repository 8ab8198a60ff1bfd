// The GL renderer against the CPU renderer: the same model, so the same frames up to float
// rounding and the texture unit's fixed-point filter. Runs on whatever GL 4.3 EGL offers (in
// CI, Mesa's llvmpipe); without one the tests say so and skip, unless LFCAM_REQUIRE_GL=1
// (scripts/test.sh sets it, having installed Mesa), where that is a failure.
#include "lfcam/render/gl_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/test_support.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/scene.h"

namespace lfcam {
namespace {

using render_test::Case;
using render_test::SmallPaperLightField;
using render_test::TurnedStPlaneLightField;
using render_test::WithQuadrilinearLimits;

// The renderer every test shares (a context and an uploaded light field), or null with the
// reason in `why`.
GlRenderer* SharedRenderer(std::string* why) {
  static std::string failure;
  static const std::unique_ptr<GlRenderer> renderer = []() -> std::unique_ptr<GlRenderer> {
    try {
      auto gl = std::make_unique<GlRenderer>();
      std::cout << "GL device: " << gl->device().renderer << ", OpenGL " << gl->device().version
                << "\n";
      return gl;
    } catch (const Error& e) {
      failure = e.what();
      return nullptr;
    }
  }();
  *why = failure;
  return renderer.get();
}

#define LFCAM_GL_OR_SKIP(gl)                                               \
  std::string why_no_gl;                                                   \
  GlRenderer* gl = SharedRenderer(&why_no_gl);                             \
  if (gl == nullptr) {                                                     \
    if (testing::GlRequired())                                             \
      FAIL() << "LFCAM_REQUIRE_GL=1 but no GL 4.3 context: " << why_no_gl; \
    GTEST_SKIP() << "no GL 4.3 context could be made: " << why_no_gl;      \
  }

// Random valid cameras over the small light field: eyes on, in front of and behind the array's
// plane, turned and rolled, pinholes and apertures, breathing on and off.
std::vector<Case> RandomCases(int count, unsigned seed) {
  const LightField& lf = SmallPaperLightField();
  const Vec3 centre = lf.slab().uv.center();
  std::mt19937 rng(seed);
  const auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  std::vector<Case> cases;
  for (int n = 0; n < count; ++n) {
    VirtualCameraParams p;
    p.width = int(uniform(33, 97));
    p.height = int(uniform(29, 81));
    const double height = n % 3 == 0 ? 0.0 : uniform(-400, 900);
    p.eye = centre + Vec3(uniform(-60, 60), uniform(-50, 50), height);
    p.look_at = n % 2 == 0 ? Vec3(p.eye - Vec3(0, 0, 1000))
                           : Vec3(centre + Vec3(uniform(-400, 400), uniform(-300, 300), -3500));
    if (n % 4 == 3) p.up = Vec3(std::sin(0.5), std::cos(0.5), 0);
    p.focal_length_mm = uniform(120, 420);
    p.focus_distance_mm = uniform(3300, 5200);
    p.aperture_mm = n % 5 == 0 ? 0.0 : uniform(20, 150);
    p.lens_rate = uniform(1, 3);
    p.breathing = n % 2 == 1;
    const int kind = n % 3;
    const Integrator integrator = kind == 2 ? Integrator::kCameras : Integrator::kLensSamples;
    const Interpolation interpolation =
        kind == 0 ? Interpolation::kQuadrilinear : Interpolation::kFocalPlane;
    cases.push_back({"random camera " + std::to_string(n) + " " + ToString(integrator) + " " +
                         ToString(interpolation),
                     p, integrator, interpolation, "", n % 4 == 1});
  }
  return cases;
}

struct Agreement {
  double mean_abs = 0, psnr = 0, max_abs = 0, mask_mismatch = 0;
};

// Over the pixels both renderers hit: the mean and largest absolute difference (linear light,
// 0..1) and the PSNR; and the share of pixels whose hit masks differ.
Agreement Compare(const RenderResult& gl, const RenderResult& cpu) {
  Agreement a;
  const cv::Mat both = gl.hit_mask & cpu.hit_mask;
  const int pixels = std::max(1, cv::countNonZero(both));
  cv::Mat difference;
  cv::absdiff(gl.image, cpu.image, difference);
  const cv::Scalar sum = cv::sum(difference.setTo(cv::Scalar::all(0), ~both));
  a.mean_abs = (sum[0] + sum[1] + sum[2]) / (3.0 * pixels);
  double squares = 0;
  for (int y = 0; y < difference.rows; ++y)
    for (int x = 0; x < difference.cols; ++x) {
      const cv::Vec3f d = difference.at<cv::Vec3f>(y, x);
      squares += d.dot(d);
      a.max_abs = std::max<double>(a.max_abs, std::max({d[0], d[1], d[2]}));
    }
  const double mse = squares / (3.0 * pixels);
  a.psnr = mse > 0 ? 10 * std::log10(1.0 / mse) : 99.0;
  a.mask_mismatch = double(cv::countNonZero(gl.hit_mask != cpu.hit_mask)) / gl.hit_mask.total();
  return a;
}

void ExpectAgreement(GlRenderer& gl, const std::vector<Case>& all_cases, Agreement& worst) {
  for (const Case& c : WithQuadrilinearLimits(all_cases)) {
    const LightField& lf = c.turned ? TurnedStPlaneLightField() : SmallPaperLightField();
    const VirtualCamera camera(c.camera);
    CpuRenderOptions cpu_options;
    cpu_options.integrator = c.integrator;
    cpu_options.interpolation = c.interpolation;
    const RenderResult cpu = RenderLightFieldCpu(lf, camera, cpu_options);
    GlRenderOptions gl_options;
    gl_options.integrator = c.integrator;
    gl_options.interpolation = c.interpolation;
    const RenderResult frame = gl.Render(lf, camera, gl_options);
    ASSERT_GT(cpu.rays_hit, 0) << c.name;
    // Both say when they prefiltered the views.
    EXPECT_EQ(frame.path.find("views prefiltered") != std::string::npos,
              cpu.path.find("views prefiltered") != std::string::npos)
        << c.name << ": " << frame.path << " against " << cpu.path;
    const Agreement a = Compare(frame, cpu);
    EXPECT_LT(a.mean_abs, 1.0 / 255) << c.name;
    EXPECT_GT(a.psnr, 45.0) << c.name;
    // No pixel far off either: a wrong weight or tap shows in a few pixels long before the mean.
    EXPECT_LT(a.max_abs, 2.0 / 255) << c.name;
    EXPECT_LT(a.mask_mismatch, 0.01) << c.name;
    // Rays and cameras read agree up to the pixels along the domain's edges.
    EXPECT_NEAR(double(frame.rays_hit), double(cpu.rays_hit), 0.01 * double(cpu.rays_hit))
        << c.name;
    EXPECT_EQ(frame.rays > 0, cpu.rays > 0) << c.name;
    EXPECT_GE(frame.gpu_ms, 0.0) << c.name;
    worst.mean_abs = std::max(worst.mean_abs, a.mean_abs);
    worst.max_abs = std::max(worst.max_abs, a.max_abs);
    worst.mask_mismatch = std::max(worst.mask_mismatch, a.mask_mismatch);
    worst.psnr = worst.psnr == 0 ? a.psnr : std::min(worst.psnr, a.psnr);
  }
}

TEST(GlRenderer, AgreesWithTheCpuRendererOnEveryPath) {
  LFCAM_GL_OR_SKIP(gl);
  Agreement worst;
  ExpectAgreement(*gl, render_test::Cases(), worst);
  ExpectAgreement(*gl, RandomCases(24, 2026), worst);
  std::cout << "worst over every case: mean |difference| " << worst.mean_abs * 255
            << " / 255, largest " << worst.max_abs * 255 << " / 255, PSNR " << worst.psnr
            << " dB, hit masks differing on " << 100 * worst.mask_mismatch << "% of pixels\n";
}

// The depth lookup: every camera of the agreement cases with lens samples, through the views'
// true depth maps, with and without antialiasing, on the small light field (cameras off the
// ideal grid) and on its turned st-plane.
TEST(GlRenderer, DepthLookupAgreesWithTheCpuRenderer) {
  LFCAM_GL_OR_SKIP(gl);
  const Scene scene = MakePaperScene();
  const auto truth_of = [&](const LightField& lf) {
    DepthSet set(lf.dims());
    for (int r = 0; r < lf.dims().rows; ++r)
      for (int c = 0; c < lf.dims().cols; ++c) set.set(GroundTruthDepth(scene, lf, r, c).map);
    return set;
  };
  const DepthSet straight = truth_of(SmallPaperLightField());
  const DepthSet turned = truth_of(TurnedStPlaneLightField());
  double worst_mean = 0, worst_far = 0;
  int cases = 0;
  for (const Case& c : render_test::Cases()) {
    if (c.integrator != Integrator::kLensSamples || c.interpolation != Interpolation::kFocalPlane)
      continue;
    for (const bool antialias : {false, true}) {
      const LightField& lf = c.turned ? TurnedStPlaneLightField() : SmallPaperLightField();
      const VirtualCamera camera(c.camera);
      CpuRenderOptions cpu_options;
      cpu_options.interpolation = Interpolation::kDepth;
      cpu_options.depth = c.turned ? &turned : &straight;
      cpu_options.antialias = antialias;
      const RenderResult cpu = RenderLightFieldCpu(lf, camera, cpu_options);
      GlRenderOptions gl_options;
      gl_options.interpolation = Interpolation::kDepth;
      gl_options.depth = cpu_options.depth;
      gl_options.antialias = antialias;
      const RenderResult frame = gl->Render(lf, camera, gl_options);
      const std::string name = c.name + (antialias ? ", antialiased" : "");
      ASSERT_GT(cpu.rays_hit, 0) << name;
      EXPECT_NE(frame.path.find("depth lookup"), std::string::npos) << frame.path;
      const Agreement a = Compare(frame, cpu);
      // The march runs in float on the GPU and in double on the CPU: at a depth edge a ray can
      // stop on the other side (a few pixels of a frame); elsewhere the two agree as the other
      // lookups do.
      cv::Mat difference;
      cv::absdiff(frame.image, cpu.image, difference);
      cv::Mat largest;
      cv::reduce(difference.reshape(1, int(difference.total())), largest, 1, cv::REDUCE_MAX);
      const double far = double(cv::countNonZero(largest > 2.0 / 255)) / double(largest.total());
      EXPECT_LT(a.mean_abs, 1.0 / 255) << name;
      EXPECT_GT(a.psnr, 40.0) << name;
      EXPECT_LT(far, 0.01) << name;
      EXPECT_LT(a.mask_mismatch, 0.01) << name;
      EXPECT_EQ(frame.rays, cpu.rays) << name;
      EXPECT_NEAR(double(frame.rays_hit), double(cpu.rays_hit), 0.01 * double(cpu.rays_hit))
          << name;
      worst_mean = std::max(worst_mean, a.mean_abs);
      worst_far = std::max(worst_far, far);
      ++cases;
    }
  }
  // Frames at the views' own sampling or finer, where both read the views with Keys' cubic (an
  // 8-bit view's codes interpolated and then decoded): pinholes between the cameras.
  const LightField& small = SmallPaperLightField();
  ASSERT_EQ(small.sample_type(), SampleType::kSrgb8);
  for (const auto& [row, col] : {std::pair{2, 3}, {3, 1}}) {
    const LightField& lf = small;
    VirtualCameraParams p;
    p.width = p.height = 320;
    p.eye = 0.5 * (lf.camera_center(row, col) + lf.camera_center(row + 1, col + 1));
    p.look_at = p.eye - Vec3(0, 0, 1000);
    const VirtualCamera camera(p);
    ASSERT_TRUE(DepthLookupReadsCubic(camera, LightFieldSampler(lf)));
    // Both blends (render/depth_aware_sampler.h), and each backend's two differ: the GL
    // renderer is told which.
    RenderResult frames[2];
    for (const DepthBlend blend : {DepthBlend::kAgreeing, DepthBlend::kFourCameras}) {
      CpuRenderOptions cpu_options;
      cpu_options.interpolation = Interpolation::kDepth;
      cpu_options.depth = &straight;
      cpu_options.depth_blend = blend;
      const RenderResult cpu = RenderLightFieldCpu(lf, camera, cpu_options);
      GlRenderOptions gl_options;
      gl_options.interpolation = Interpolation::kDepth;
      gl_options.depth = &straight;
      gl_options.depth_blend = blend;
      RenderResult frame = gl->Render(lf, camera, gl_options);
      const Agreement a = Compare(frame, cpu);
      EXPECT_LT(a.mean_abs, 1.0 / 255) << row << ", " << col << ", " << ToString(blend);
      EXPECT_GT(a.psnr, 40.0) << row << ", " << col << ", " << ToString(blend);
      worst_mean = std::max(worst_mean, a.mean_abs);
      frames[blend == DepthBlend::kAgreeing ? 0 : 1] = std::move(frame);
      ++cases;
    }
    cv::Mat blend_difference;
    cv::absdiff(frames[0].image, frames[1].image, blend_difference);
    EXPECT_GT(cv::mean(blend_difference.reshape(1))[0], 0.05 / 255) << row << ", " << col;
  }
  EXPECT_GE(cases, 20);
  std::cout << cases << " depth-lookup frames: worst mean |difference| " << worst_mean * 255
            << " / 255, at most " << 100 * worst_far << "% of pixels more than 2/255 off\n";
  // Without the maps, or with another integrator: the CPU's refusals.
  GlRenderOptions missing;
  missing.interpolation = Interpolation::kDepth;
  const VirtualCamera camera(render_test::Cases().front().camera);
  EXPECT_THROW(gl->Render(SmallPaperLightField(), camera, missing), Error);
  missing.depth = &straight;
  missing.integrator = Integrator::kCameras;
  EXPECT_THROW(gl->Render(SmallPaperLightField(), camera, missing), Error);
}

TEST(GlRenderer, RefusesViewsLargerThanTheDeviceWithItsLimit) {
  LFCAM_GL_OR_SKIP(gl);
  const LightField& small = SmallPaperLightField();
  LightFieldDims dims = small.dims();
  dims.n_s = gl->limits().max_texture_size + 1;
  dims.n_t = 2;
  const LightField wide(dims, SampleType::kSrgb8, small.slab());
  VirtualCameraParams p;
  p.width = p.height = 8;
  p.eye = small.slab().uv.center();
  p.look_at = p.eye - Vec3(0, 0, 1000);
  try {
    gl->Render(wide, VirtualCamera(p), {});
    FAIL() << "rendered a light field wider than the largest texture";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(std::to_string(dims.n_s)), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(gl->limits().max_texture_size)), std::string::npos)
        << message;
  }
  // The renderer still works afterwards.
  EXPECT_GT(gl->Render(small, VirtualCamera(p), {}).rays_hit, 0);
}

// A light field video's frames: one light field after another of the same shape, each freed
// before the next is made (so an address may come back), the texture kept and its samples
// replaced. Each frame is its own, not the one before.
TEST(GlRenderer, SuccessiveLightFieldsOfOneShapeEachRenderTheirOwnSamples) {
  LFCAM_GL_OR_SKIP(gl);
  const LightField& small = SmallPaperLightField();
  VirtualCameraParams p;
  p.width = 48;
  p.height = 40;
  p.eye = small.slab().uv.center();
  p.look_at = p.eye - Vec3(0, 0, 1000);
  const VirtualCamera camera(p);
  const auto flat = [&](std::uint8_t value) {
    LightField lf(small.dims(), SampleType::kSrgb8, small.slab());
    std::fill_n(lf.mutable_view_data(0, 0), lf.total_bytes(), value);
    return lf;
  };
  for (const std::uint8_t value : {40, 200, 40, 120}) {
    const LightField frame = flat(value);
    EXPECT_NE(frame.samples_serial(), small.samples_serial());
    const RenderResult result = gl->Render(frame, camera, {});
    const cv::Scalar mean = cv::mean(LinearToSrgb8Image(result.image));
    EXPECT_NEAR(mean[0], value, 1.0) << "frame of " << int(value);
  }
  // A copy shares its samples (and their serial); the original renders as before.
  const LightField copy = small;
  EXPECT_EQ(copy.samples_serial(), small.samples_serial());
  EXPECT_GT(gl->Render(small, camera, {}).rays_hit, 0);
}

TEST(GlRenderer, RefusesAWorkGroupTheDeviceCannotRun) {
  LFCAM_GL_OR_SKIP(gl);
  VirtualCameraParams p;
  p.width = p.height = 8;
  p.eye = SmallPaperLightField().slab().uv.center();
  p.look_at = p.eye - Vec3(0, 0, 1000);
  GlRenderOptions o;
  o.workgroup_x = gl->limits().max_workgroup_invocations;
  o.workgroup_y = 2;
  EXPECT_THROW(gl->Render(SmallPaperLightField(), VirtualCamera(p), o), UsageError);
  o.workgroup_x = 8;
  o.workgroup_y = 4;
  EXPECT_GT(gl->Render(SmallPaperLightField(), VirtualCamera(p), o).rays_hit, 0);
}

TEST(FrameRenderer, NamesTheBackendItPicked) {
  EXPECT_EQ(BackendFromString("auto"), Backend::kAuto);
  EXPECT_THROW(BackendFromString("vulkan"), Error);
  const FrameRenderer cpu(Backend::kCpu);
  EXPECT_FALSE(cpu.uses_gl());
  EXPECT_EQ(cpu.description().rfind("cpu (", 0), 0u) << cpu.description();
  const FrameRenderer automatic(Backend::kAuto);
  // auto takes a GL context only on a hardware GPU, and says why either way.
  if (automatic.uses_gl()) {
    EXPECT_FALSE(automatic.gl()->device().software);
  }
  EXPECT_NE(automatic.description().find("auto"), std::string::npos) << automatic.description();
}

}  // namespace
}  // namespace lfcam
