#include "lfcam/render/camera_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam {
namespace {

// The render in linear light (float: the comparisons below go beyond 8 bits).
cv::Mat Render(const VirtualCameraParams& p, Integrator integrator, double lens_rate = 4) {
  VirtualCameraParams q = p;
  q.lens_rate = lens_rate;
  CpuRenderOptions o;
  o.integrator = integrator;
  o.interpolation = Interpolation::kFocalPlane;
  return RenderLightFieldCpu(render_test::GridPaperLightField(), VirtualCamera(q), o).image;
}

// PSNR of two linear images against a peak of 1.
double LinearPsnr(const cv::Mat& a, const cv::Mat& b) {
  const double mse = cv::norm(a, b, cv::NORM_L2SQR) / double(a.total() * a.channels());
  return 10.0 * std::log10(1.0 / std::max(mse, 1e-30));
}

// The lens-sample estimator with the focal-plane lookup converges to the cameras integrator as
// the lens sampling rate grows: eyes on, behind and in front of the array, a camera turned
// away from the array's normal (its footprint taken as the disk of the same area), breathing
// on and off.
TEST(CameraIntegrator, IsTheLimitOfLensSamplesWithTheFocalPlaneLookup) {
  for (const render_test::ConvergenceCamera& c : {
           render_test::ConvergenceCamera{
               "on the array", {300, 275, 3600}, {300, 275, 0}, 500, 3900, 192, true},
           render_test::ConvergenceCamera{
               "behind", {300, 275, 4600}, {300, 275, 0}, 400, 4700, 192, true},
           render_test::ConvergenceCamera{
               "in front, no breathing", {250, 300, 3000}, {250, 300, 0}, 300, 3400, 96, false},
           render_test::ConvergenceCamera{
               "turned 2.8 degrees", {300, 275, 3600}, {450, 200, 0}, 500, 4000, 192, true},
       }) {
    SCOPED_TRACE(c.name);
    const VirtualCameraParams p = c.Params(24);
    const cv::Mat limit = Render(p, Integrator::kCameras);
    const double at_64 = LinearPsnr(Render(p, Integrator::kLensSamples, 64), limit);
    const double at_256 = LinearPsnr(Render(p, Integrator::kLensSamples, 256), limit);
    std::cout << "[" << c.name << "] lens samples against the limit: gamma 64 " << at_64
              << " dB, gamma 256 " << at_256 << " dB\n";
    // Measured (float, against a peak of 1): 81 -> 92, 82 -> 85, 69 -> 79, 83 -> 88 dB.
    EXPECT_GT(at_256, at_64);
    EXPECT_GT(at_256, 60.0);
  }
}

// Where the st domain's edge crosses the frame, the lens samples reach past the pixels whose
// central line meets it: a camera counts where its own line through p_o meets the domain, so the
// cameras integrator renders the pixels the lens samples reach, with the blend the lens samples
// converge to there (before issue 23 it left every pixel whose central line missed black). Eyes
// on, in front of and behind the array.
TEST(CameraIntegrator, RendersTheEdgePixelsTheLensSamplesReach) {
  for (const render_test::ConvergenceCamera& c : {
           render_test::ConvergenceCamera{
               "on the array", {300, 275, 3600}, {300, 275, 0}, 70, 2500, 150, true},
           render_test::ConvergenceCamera{
               "in front", {250, 300, 3000}, {250, 300, 0}, 60, 2000, 120, true},
           render_test::ConvergenceCamera{
               "behind, turned", {300, 275, 4300}, {600, 400, 0}, 90, 2500, 150, false},
       }) {
    SCOPED_TRACE(c.name);
    VirtualCameraParams p = c.Params(48);
    const auto render = [&](Integrator integrator, double rate) {
      p.lens_rate = rate;
      CpuRenderOptions o;
      o.integrator = integrator;
      o.interpolation = Interpolation::kFocalPlane;
      return RenderLightFieldCpu(render_test::GridPaperLightField(), VirtualCamera(p), o);
    };
    const RenderResult cameras = render(Integrator::kCameras, 4);
    const RenderResult lens = render(Integrator::kLensSamples, 64);
    const int n_ls = int(VirtualCamera(p).lens_samples().size());
    // The frame's edge band: pixels some lens samples reach and others miss.
    int band = 0, reached = 0, half_reached = 0, rendered_of_half = 0, stray = 0;
    double squares = 0;
    int compared = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) {
        const int hits = lens.counts.at<std::int32_t>(y, x);
        const bool rendered = cameras.counts.at<std::int32_t>(y, x) > 0;
        if (hits > 0 && hits < n_ls) ++band;
        if (hits > 0) ++reached;
        if (4 * hits >= n_ls) {
          ++half_reached;
          rendered_of_half += rendered;
          if (rendered) {
            const cv::Vec3f d = cameras.image.at<cv::Vec3f>(y, x) - lens.image.at<cv::Vec3f>(y, x);
            squares += d.dot(d) / 3;
            ++compared;
          }
        }
        if (rendered && hits == 0) ++stray;
      }
    const double psnr = 10 * std::log10(1.0 / std::max(squares / std::max(compared, 1), 1e-30));
    std::cout << "[" << c.name << "] " << band << " edge pixels; of the " << half_reached
              << " that a quarter of the lens samples reach the cameras integrator renders "
              << rendered_of_half << ", " << stray << " that none reach; " << psnr
              << " dB against gamma 64 there\n";
    ASSERT_GT(band, 48) << "the domain's edge should cross the frame";
    EXPECT_EQ(rendered_of_half, half_reached);
    // A camera's line is not one of the 64-gamma lens samples': at the band's outer rim a pixel
    // may be rendered that none of them reaches.
    EXPECT_LE(stray, band / 50);
    EXPECT_GT(psnr, 35.0);
  }
}

TEST(CameraIntegrator, APinholeOrATinyApertureIsTheFocalPlaneLookup) {
  VirtualCameraParams p;
  p.width = p.height = 32;
  p.eye = Vec3(287, 262, 3600);
  p.look_at = Vec3(300, 275, 0);
  p.focus_distance_mm = 4200;
  const cv::Mat lookup = Render(p, Integrator::kLensSamples);
  EXPECT_EQ(cv::norm(Render(p, Integrator::kCameras), lookup, cv::NORM_INF), 0.0);
  // Half a millimetre: the hats averaged over a disk of 0.009 pitches (about half an 8-bit
  // level at most).
  p.aperture_mm = 0.5;
  EXPECT_LE(cv::norm(Render(p, Integrator::kCameras), lookup, cv::NORM_INF), 4e-3);
}

TEST(CameraIntegrator, FootprintsAreTheLensSeenThroughThePointInFocus) {
  // Eye on the array plane: every pixel's footprint is the lens itself, around the eye.
  VirtualCameraParams p;
  p.width = p.height = 16;
  p.eye = Vec3(300, 275, 3600);
  p.look_at = Vec3(300, 275, 0);
  p.aperture_mm = 112;  // radius 2 pitches
  const VirtualCamera camera_on(p);
  const CameraIntegratorFrame on(render_test::GridPaperLightField(), camera_on);
  EXPECT_TRUE(on.exact());
  for (const auto& [i, j] : {std::pair{0, 0}, std::pair{7, 9}, std::pair{15, 15}}) {
    const Footprint f = on.FootprintOf(i, j);
    ASSERT_TRUE(f.valid);
    EXPECT_NEAR(f.cx, 4.5, 1e-9);  // the array's centre, between cameras 4 and 5
    EXPECT_NEAR(f.cy, 4.5, 1e-9);
    EXPECT_NEAR(f.radius, 2.0, 1e-9);
  }
  // The same footprint for every pixel: one set of weights, no table.
  EXPECT_EQ(on.table_nodes(), 0u);
  double sum = 0;
  for (const auto& c : on.uniform_weights()) sum += c.weight;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  // The hats a disk of radius 2 around (4.5, 4.5) meets: cameras 2..7 each way, less the four
  // corners (their hats end 2.12 pitches from the centre).
  EXPECT_EQ(on.uniform_weights().size(), 32u);
  // 1000 mm behind the array, focused 4000 mm ahead: the lens shrinks by 3000 / 4000 on its way
  // to the array, and the footprint follows the pixel's point in focus a quarter of the way.
  p.eye = Vec3(300, 275, 4600);
  p.focus_distance_mm = 4000;
  const VirtualCamera camera_behind(p);
  const CameraIntegratorFrame behind(render_test::GridPaperLightField(), camera_behind);
  const Footprint f = behind.FootprintOf(8, 8);
  EXPECT_NEAR(f.radius, 2.0 * 0.75, 1e-9);
  // The weights sum to 1.
  std::vector<float> w(100);
  behind.Weights(f, w.data());
  double total = 0;
  for (float x : w) total += x;
  EXPECT_NEAR(total, 1.0, 1e-5);
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

// Eyes off the array's plane: behind it, in front of it, and turned from its normal.
std::vector<render_test::ConvergenceCamera> OffThePlane() {
  return {{"behind", {300, 275, 4100}, {300, 275, 0}, 444, 4000, 256, true},
          {"in front", {150, 120, 2900}, {150, 120, 0}, 300, 4000, 128, false},
          {"turned", {280, 275, 3600}, {300, 275, 2600}, 500, 3400, 192, true}};
}

// The footprint's closed form (its centre and the radius of the disk of the same area) against
// the lens disk projected point by point: lens points e + s u_c + t v_c carried through the pixel's
// point in focus p_o onto the array's plane, the centre their image at s = t = 0, the area the
// determinant of that map's differences over a micrometre of lens each way. Eyes behind the array,
// in front of it, turned, far off to the side, and a lens nearly edge-on to the array's plane.
TEST(CameraIntegrator, TheFootprintIsTheLensProjectedThroughThePointInFocus) {
  const LightField& lf = render_test::GridPaperLightField();
  const ArrayPlane& uv = lf.slab().uv;
  std::vector<render_test::ConvergenceCamera> cameras = OffThePlane();
  cameras.push_back({"off to the side", {-900, 600, 3000}, {450, 200, 0}, 300, 4700, 64, true});
  cameras.push_back({"nearly edge-on", {300, 275, 3700}, {300, 3000, 3300}, 400, 2500, 100, false});
  for (const render_test::ConvergenceCamera& c : cameras) {
    SCOPED_TRACE(c.name);
    VirtualCameraParams p = c.Params(0);
    p.width = 64;
    p.height = 48;
    const VirtualCamera camera(p);
    const CameraIntegratorFrame frame(lf, camera, /*tabulate=*/false);
    for (const auto& [i, j] : {std::pair{0, 0}, std::pair{63, 0}, std::pair{0, 47},
                               std::pair{63, 47}, std::pair{31, 20}, std::pair{5, 40}}) {
      const Vec3 p_o = camera.focus_point(camera.pixel_direction(i, j));
      // (u, v) in grid units of the line from p_o through x where it meets the array's plane.
      const auto on_array = [&](const Vec3& x) {
        const double lambda = uv.n_ca.dot(uv.p_ca - p_o) / uv.n_ca.dot(x - p_o);
        const Vec3 u = p_o + lambda * (x - p_o) - uv.p_ca;
        return Vec2(u.dot(uv.u_ca) / uv.pitch_mm - 0.5, u.dot(uv.v_ca) / uv.pitch_mm - 0.5);
      };
      const Vec2 centre = on_array(camera.e_c());
      const double step = 1e-3;  // mm of lens
      const Vec2 ds = (on_array(camera.e_c() + step * camera.u_c()) -
                       on_array(camera.e_c() - step * camera.u_c())) /
                      (2 * step);
      const Vec2 dt = (on_array(camera.e_c() + step * camera.v_c()) -
                       on_array(camera.e_c() - step * camera.v_c())) /
                      (2 * step);
      const double radius =
          0.5 * p.aperture_mm * std::sqrt(std::abs(ds.x() * dt.y() - ds.y() * dt.x()));
      const Footprint f = frame.FootprintOf(i, j);
      ASSERT_TRUE(f.valid) << i << ", " << j;
      EXPECT_NEAR(f.cx, centre.x(), 1e-9 * (1 + std::abs(centre.x()))) << i << ", " << j;
      EXPECT_NEAR(f.cy, centre.y(), 1e-9 * (1 + std::abs(centre.y()))) << i << ", " << j;
      EXPECT_NEAR(f.radius, radius, 1e-7 * radius) << i << ", " << j;
    }
  }
}

// A row's weights, pixels sharing a table cell weighted together camera by camera, are each
// pixel's own weights (Weights of its footprint) to the last bit, for an eye behind the array, in
// front of it and a turned view, one table level or several; and the cameras listed are those
// with a weight somewhere in the row.
TEST(CameraIntegrator, ARowsWeightsAreEachPixelsOwn) {
  const LightField& lf = render_test::GridPaperLightField();
  const int views = int(lf.dims().view_count());
  std::vector<render_test::ConvergenceCamera> off_the_plane = OffThePlane();
  off_the_plane.push_back(
      {"small aperture, turned", {300, 275, 3600}, {450, 200, 0}, 500, 4700, 20, true});
  for (const render_test::ConvergenceCamera& c : off_the_plane) {
    SCOPED_TRACE(c.name);
    VirtualCameraParams p = c.Params(0);
    p.width = 77;
    p.height = 9;
    const VirtualCamera camera(p);
    const CameraIntegratorFrame frame(lf, camera);
    ASSERT_TRUE(frame.needs_table());
    const std::size_t stride = 80;
    std::vector<float> row(std::size_t(views) * stride), one(static_cast<std::size_t>(views));
    std::vector<int> cameras;
    for (int j = 0; j < p.height; j += 4) {
      std::fill(row.begin(), row.end(), 0.0f);
      frame.RowWeights(j, p.width, stride, row.data(), &cameras);
      std::vector<int> expected;
      for (int v = 0; v < views; ++v)
        for (int i = 0; i < p.width; ++i)
          if (row[std::size_t(v) * stride + std::size_t(i)] != 0.0f) {
            expected.push_back(v);
            break;
          }
      for (int i = 0; i < p.width; ++i) {
        frame.Weights(frame.FootprintOf(i, j), one.data());
        for (int v = 0; v < views; ++v)
          ASSERT_EQ(row[std::size_t(v) * stride + std::size_t(i)], one[std::size_t(v)])
              << "pixel " << i << ", " << j << ", camera " << v;
      }
      EXPECT_EQ(cameras, expected) << "row " << j;
      EXPECT_FALSE(cameras.empty());
    }
  }
}

}  // namespace
}  // namespace lfcam
