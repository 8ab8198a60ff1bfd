// The depth estimate on a scene of the HCI 4D Light Field Benchmark (../shared/data/hci-antinous,
// when present), and on simulated scenes of the benchmark's kinds (the `paper` scene, slopes,
// thin occluders) whose truth is registered to their views, scored as the benchmark scores it:
// BadPix(0.07) and MSE x 100 over the centre view less a 15-pixel border (docs/depth.md, "On the
// field's benchmark", "A seventh round" and "Scenes of the benchmark's kinds").
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "lfcam/depth/depth_map.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/depth/depth_test_scene.h"
#include "lfcam/depth/disparity_map.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/rectified_import.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/shapes.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::benchmark_depth_test {
namespace {

namespace fs = std::filesystem;

TEST(DepthOnTheBenchmark, AntinousScoresWhatDocsDepthSays) {
  const fs::path hci = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/hci-antinous";
  if (!fs::is_directory(hci)) GTEST_SKIP() << hci << " is not here (../shared/data)";
  const ImportedGrid grid = ScanGridFolder(hci, false);
  const LightField lf = ImportRectifiedViews(hci, grid, ResolveRectifiedGeometry(grid, {}));
  const auto start = std::chrono::steady_clock::now();
  const DepthMap map = EstimateDepth(lf, 4, 4, {});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const cv::Mat d = DisparityOf(lf, map);
  // OpenCV reads the PFM upright (its top row first); the map's rows count up.
  const cv::Mat truth = cv::imread((hci / "gt_disp_lowres.pfm").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(truth.size(), cv::Size(512, 512));
  const int border = 15;
  int n = 0, bad = 0;
  double squared = 0;
  for (int y = border; y < 512 - border; ++y)
    for (int x = border; x < 512 - border; ++x) {
      const double e = d.at<float>(511 - y, x) - truth.at<float>(y, x);
      ++n;
      bad += !(std::abs(e) <= 0.07);
      squared += std::isfinite(e) ? e * e : 100.0;
    }
  const double badpix = 100.0 * bad / n, mse100 = 100.0 * squared / n;
  std::cout << fmt::format(
      "[depth benchmark] antinous: BadPix0.07 {:.2f}%, MSEx100 {:.2f}, {:.1f} s\n", badpix, mse100,
      seconds);
  // Floors a little above what was measured; the MSE floor is issue 22's target (docs/depth.md:
  // 2.73% and 1.47 here, 2.73% and 1.473 through `lfcam import`, with the sweep's planes on one
  // lattice from the zero-disparity plane; 2.73% and 1.46, and 1.481, with its planes spread
  // evenly over the range found; 2.78% and 1.47 when each side of
  // the visibility step's window was only its samples within the edge's threshold of the side's
  // label; 2.80% and 1.49 when the visibility step took the window's farthest label for the far
  // depth, not the far side's plane; 2.74% and 1.51 when it also read each side of its window at
  // the judged depth, not at the samples' own, which the MSE floor fails; 2.75% and 1.75 when the
  // visibility step judged the near side at its own depth alone, which the MSE floor fails; 2.75%
  // and 1.78 when it also moved samples the far side did not reach; when the clean-up replaced
  // samples the sweep was sure of as well, 2.83% and 2.62, which the MSE floor fails; when the
  // clean-up moved the statue's dark limb onto the wall and the visibility step took only
  // half-sample jumps, 2.84% and 2.85, which the MSE floor fails; with the visibility step's cost
  // over the whole window at its silhouettes, 2.91% and 3.06; with its window and passes of wide
  // baselines 2.91% and 3.12; without the step 2.97% and 3.83; without the quarter-arrays as well
  // 3.05% and 4.82; with the colour and gradient terms counting alike, as at wide baselines, 5.28%
  // and 6.4, which both floors fail; without the slant prior then 5.38%, without the wider plane
  // fit 5.55%, without the local planes 6.32%).
  EXPECT_LE(badpix, 2.9);
  EXPECT_LE(mse100, 1.5);
}

// The same views imported in assumed units (no parameters.cfg: the cameras' spacing 1 unit) and
// in millimetres (a parameters.cfg's optics: 100 mm on a 35 mm sensor, 90 mm apart, focused at
// 4.25 m) give the same disparity map: the depth range is found in each, a little apart in the
// views' samples, and the sweep's planes lie on one lattice from the zero-disparity plane whatever
// the range (docs/depth.md, "The planes on one lattice"): 3 samples more than 0.07 px apart (what
// is left follows the ranges found, which decide the gradient term's share). Before, with the
// planes spread evenly over each range, 220.
TEST(DepthOnTheBenchmark, TheSameMapWhateverUnitsTheRigIsImportedIn) {
  const fs::path hci = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/hci-antinous";
  if (!fs::is_directory(hci)) GTEST_SKIP() << hci << " is not here (../shared/data)";
  const ImportedGrid grid = ScanGridFolder(hci, false);
  ImportOptions metric;
  metric.focal_px = 100.0 * 512 / 35;
  metric.pitch_mm = 90.0;
  metric.st_distance_mm = 4250.0;
  const RectifiedGeometry in_mm = ResolveRectifiedGeometry(grid, metric);
  const RectifiedGeometry in_units = ResolveRectifiedGeometry(grid, {});
  ASSERT_TRUE(in_mm.metric);
  ASSERT_FALSE(in_units.metric);
  const auto disparity = [&](const RectifiedGeometry& geometry) {
    const LightField lf = ImportRectifiedViews(hci, grid, geometry);
    return DisparityOf(lf, EstimateDepth(lf, 4, 4, {}));
  };
  const cv::Mat a = disparity(in_units), b = disparity(in_mm);
  ASSERT_EQ(a.size(), b.size());
  int apart = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x)
      apart += !(std::abs(a.at<float>(y, x) - b.at<float>(y, x)) <= 0.07);
  std::cout << fmt::format(
      "[depth benchmark] antinous in units and in mm: {} samples more than 0.07 px apart\n", apart);
  EXPECT_LE(apart, 20);
}

// The `paper` scene through a 9 x 9 rig of the benchmark's kind, cameras `pitch_mm` apart (views
// of 416 x 384 samples, each the mean of 3 x 3 rays, so that silhouettes have mixed pixels), the
// truth the simulator's, registered to the views by construction; each view's bytes scaled by
// 1 - falloff * (its squared grid distance from the centre) / 32 (a plenoptic camera's outer
// views are darker). Scored on the centre view less a 15-sample border.
struct SimulatedScore {
  double badpix = 0, mse100 = 0;
  double silhouettes100 = 0;  // MSE x 100 of samples within 3 of another object, over the view
  double moved_row100 = 0;    // MSE x 100 of the truth against itself moved one row
  std::vector<std::pair<int, int>> views_too_dark;  // the views the estimate left out
};

// The rig's light field and the centre view's truth, simulated once a process for each scene and
// pitch (two tests read the same rig: the simulation is most of a test's time).
struct SimulatedRig {
  LightField lf;
  DepthTruth truth;
};

const SimulatedRig& SimulateRig(Scene scene, double pitch_mm) {
  static std::map<std::string, SimulatedRig> rigs;
  const std::string key = fmt::format("{}@{}", scene.name, pitch_mm);
  if (const auto found = rigs.find(key); found != rigs.end()) return found->second;
  scene.rig.array.pitch_mm = pitch_mm;
  SimulateLightFieldOptions o;
  o.rows = o.cols = 9;
  o.n_s = 416;
  o.n_t = 384;
  o.supersampling = 3;
  LightField lf = SimulateLightField(scene, o);
  DepthTruth truth = GroundTruthDepth(scene, lf, 4, 4);
  return rigs.emplace(key, SimulatedRig{std::move(lf), std::move(truth)}).first->second;
}

// `view_gain`, when given, scales view (r, c)'s bytes in place of the falloff; `estimator`, when
// given, makes the centre view's map in place of EstimateDepth with `options`.
SimulatedScore ScoreSimulatedRig(const Scene& scene, double pitch_mm, double falloff = 0.0,
                                 double noise = 0.0, const PlaneSweepOptions& options = {},
                                 const std::function<double(int, int)>& view_gain = {},
                                 const std::function<DepthMap(const LightField&)>& estimator = {}) {
  const SimulatedRig& rig = SimulateRig(scene, pitch_mm);
  const LightFieldDims& o = rig.lf.dims();
  // A copy of its samples, which the brightness and the noise then change.
  LightField lf(o, rig.lf.sample_type(), rig.lf.slab());
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c)
      std::memcpy(lf.mutable_view_data(r, c), rig.lf.view_data(r, c), o.samples_per_view() * 3);
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) {
      const double gain = view_gain
                              ? view_gain(r, c)
                              : 1.0 - falloff * ((r - 4) * (r - 4) + (c - 4) * (c - 4)) / 32.0;
      std::uint8_t* p = lf.mutable_view_data(r, c);
      for (std::size_t i = 0; i < std::size_t(o.n_s) * o.n_t * 3; ++i)
        p[i] = cv::saturate_cast<std::uint8_t>(p[i] * gain);
      if (noise > 0) {  // each view's own noise, the same from run to run
        cv::RNG rng(std::uint64_t(1000 + 9 * r + c));
        cv::Mat n(o.n_t, o.n_s * 3, CV_32F);
        rng.fill(n, cv::RNG::NORMAL, 0.0, noise);
        for (std::size_t i = 0; i < std::size_t(o.n_s) * o.n_t * 3; ++i)
          p[i] = cv::saturate_cast<std::uint8_t>(p[i] + n.ptr<float>()[i]);
      }
    }
  const DepthTruth& truth = rig.truth;
  const DepthMap estimate = estimator ? estimator(lf) : EstimateDepth(lf, 4, 4, options);
  const cv::Mat t = DisparityOf(lf, truth.map), d = DisparityOf(lf, estimate);
  if (const char* dir = std::getenv("LFCAM_FIDELITY_OUT")) {  // the maps, to look at
    // One set of files a rig and its views' falloff and noise: the first map the process makes of
    // them (run in the suite's order, the estimate as shipped; the tests' variants come after).
    static std::set<std::string> written;
    std::string name = fmt::format("benchmark_like_{}_{}mm_falloff{}_noise{}", scene.name, pitch_mm,
                                   falloff, noise);
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    if (written.insert(name).second) {
      WriteDepthFiles(fs::path(dir) / (name + "_estimate.png"), estimate);
      DepthMap same_range = truth.map;
      same_range.range = estimate.range;
      WriteDepthFiles(fs::path(dir) / (name + "_truth.png"), same_range);
      // And both disparities as the benchmark's PFMs, for bench/hci_score.py (--silhouettes).
      WriteDisparityPfm(fs::path(dir) / (name + "_estimate.pfm"), d);
      WriteDisparityPfm(fs::path(dir) / (name + "_truth.pfm"), t);
    }
  }
  const int border = 15, edge_reach = 3;
  // [0]: away from depth edges; [1]: within 3 samples of another object (the silhouettes).
  double squared[2] = {0, 0}, moved_row = 0;
  int n[2] = {0, 0}, bad = 0;
  for (int l = border; l < t.rows - border; ++l)
    for (int k = border; k < t.cols - border; ++k) {
      const int object = truth.object.at<int>(l, k);
      bool edge = false;
      for (int a = -edge_reach; a <= edge_reach && !edge; ++a)
        for (int b = -edge_reach; b <= edge_reach && !edge; ++b)
          edge = truth.object.at<int>(l + a, k + b) != object;
      const double e = d.at<float>(l, k) - t.at<float>(l, k);
      squared[edge] += std::isfinite(e) ? e * e : 100.0;
      ++n[edge];
      bad += !(std::abs(e) <= 0.07);
      const double m = t.at<float>(l + 1, k) - t.at<float>(l, k);
      moved_row += m * m;
    }
  const int total = n[0] + n[1];
  SimulatedScore s{100.0 * bad / total, 100.0 * (squared[0] + squared[1]) / total,
                   100.0 * squared[1] / total, 100.0 * moved_row / total, estimate.views_too_dark};
  std::cout << fmt::format(
      "[depth benchmark] {} scene, 9 x 9 rig {} mm apart, brightness falloff {}, noise {}: "
      "BadPix0.07 {:.2f}%, MSEx100 {:.3f} (silhouettes {:.3f}; the truth moved one row scores "
      "{:.3f})\n",
      scene.name, pitch_mm, falloff, noise, s.badpix, s.mse100, s.silhouettes100, s.moved_row100);
  return s;
}

// Cameras 5 mm apart: disparities -1.55 to +0.69 px between neighbours. Here the benchmark's
// targets hold, silhouettes included (docs/depth.md, "A seventh round"): what antinous'
// silhouettes lose is their truth's registration.
TEST(DepthOnABenchmarkLikeScene, MeetsTheTargetsWhereTheTruthIsRegistered) {
  const SimulatedScore s = ScoreSimulatedRig(MakePaperScene(), 5.0);
  // Measured 2.87%, 0.385 and 0.33 against 1.66 (2.84%, 0.374 and 0.32 when the clean-up replaced
  // samples the sweep was sure of too; 2.89%, 0.415 and 0.36 with the visibility
  // step's cost over the whole window at the silhouettes; 2.80%, 0.555 and 0.50 without the
  // quarter-arrays; 3.05% and 0.57 with planes 0.25 samples apart;
  // 4.66% and 0.60 when these sharp views were read through Keys' cubic; before the range took
  // in faint surfaces: 34.7%, the back wall all at the range's far end).
  EXPECT_LE(s.badpix, 5.0);
  EXPECT_LE(s.mse100, 1.5);
  EXPECT_LE(s.silhouettes100, 0.5 * s.moved_row100);
}

// Cameras 8 mm apart: the checkerboard (a third of the view; sharp edges between flat squares,
// each sample the mean of 3 x 3 rays) lies -1.71 px between neighbours, and read through Keys'
// cubic it matched best where its farthest views shift by whole samples: 0.09 px off (up to
// 0.28), 62% of it bad, the view 25.96% bad. Views this sharp are read through a Gaussian
// (docs/depth.md, "Sharp views"): measured 6.83% and MSE x 100 0.75 (6.79% and 0.63 when the
// clean-up replaced samples the sweep was sure of too; 7.44% and 1.03 before the visibility
// step's small steps; 6.97% and 1.01 without the
// quarter-arrays, which match some squares of the flat checkerboard at a false depth; 7.42% with
// planes 0.25 samples apart; MSE x 100 1.95 with Keys' reads).
TEST(DepthOnABenchmarkLikeScene, ReadsViewsSharperThanTheirSamplingWithoutThePull) {
  const SimulatedScore s = ScoreSimulatedRig(MakePaperScene(), 8.0);
  EXPECT_LE(s.badpix, 10.0);
  EXPECT_LE(s.mse100, 1.3);
}

// Cameras 2 mm apart (a plenoptic camera's disparities: -0.62 to +0.25 px), the corner views 10%
// darker than the centre's: each view's brightness is made the reference's before matching
// (docs/depth.md, "An eighth round"). Measured 3.29% (3.11% when the clean-up replaced samples
// the sweep was sure of too; 3.57% before the visibility step; 4.09% with Keys' reads; without the
// equalising 8.53%, and 18.5% with it in the final sweep only: the range's coarse sweep, misled
// by the brightness, then cut off the nearest objects).
TEST(DepthOnABenchmarkLikeScene, IgnoresBrightnessThatChangesFromViewToView) {
  EXPECT_LE(ScoreSimulatedRig(MakePaperScene(), 2.0, 0.1).badpix, 5.0);
}

// Cameras 2 mm apart, the outer ring of views (4 grid steps from the centre) at 8% of their
// brightness and its four corners black, as a plenoptic camera's views at the main lens's edge.
// The dim views are made the reference's brightness (a gain of 12.5) and matched: measured
// 4.20% and MSE x 100 0.394 (4.00% and 0.291 when the clean-up replaced samples the sweep was
// sure of too; with the gain held to 2, as it was, 9.94%; the views inside the ring alone, reach 3,
// 10.37%). The black corners are left out as too dark to match (docs/depth.md, "Views too dark
// to match").
TEST(DepthOnABenchmarkLikeScene, MatchesDimViewsAndLeavesOutBlackOnes) {
  const auto gain = [](int r, int c) {
    if (std::max(std::abs(r - 4), std::abs(c - 4)) < 4) return 1.0;
    return std::abs(r - 4) + std::abs(c - 4) == 8 ? 0.0 : 0.08;
  };
  const SimulatedScore dark = ScoreSimulatedRig(MakePaperScene(), 2.0, 0.0, 0.0, {}, gain);
  std::vector<std::pair<int, int>> left_out = dark.views_too_dark;
  std::sort(left_out.begin(), left_out.end());
  EXPECT_EQ(left_out, (std::vector<std::pair<int, int>>{{0, 0}, {0, 8}, {8, 0}, {8, 8}}));
  EXPECT_LE(dark.badpix, 5.0);
  EXPECT_LE(dark.mse100, 0.4);
}

// A depth set (`lfcam depth --all`, the depth lookup's maps) on the 2-mm rig, where neighbouring
// views see the scene at most a few samples apart: its maps reach two views each way, since the
// nearest neighbours alone cannot tell the disparities apart to a tenth of a sample (the corner
// views 10% darker; measured: the set's centre map 11.70% and MSE x 100 0.511, the same map at
// reach 1 34.24% and 1.567 (11.19%, 0.434 and 33.93%, 1.458 when the clean-up replaced samples
// the sweep was sure of too), at reach 4, a single view's default, 3.24% and 0.261; docs/depth.md,
// "The set's reach at narrow baselines").
TEST(DepthOnABenchmarkLikeScene, ASetReachesTwoViewsAtNarrowBaselines) {
  const auto centre_of_a_set = [](const LightField& lf) {
    DepthSet set(lf.dims());
    EstimateDepthSet(lf, set, [](int r, int c) { return r == 4 && c == 4; }, {});
    return set.at(4, 4);
  };
  const SimulatedScore set =
      ScoreSimulatedRig(MakePaperScene(), 2.0, 0.1, 0.0, {}, {}, centre_of_a_set);
  PlaneSweepOptions one_step;
  one_step.reach = 1;
  const SimulatedScore reach1 = ScoreSimulatedRig(MakePaperScene(), 2.0, 0.1, 0.0, one_step);
  EXPECT_LE(set.badpix, 0.5 * reach1.badpix);
  EXPECT_LE(set.mse100, 0.5 * reach1.mse100);
}

// Noisy views (Gaussian noise of 8 levels in every view): Keys' cubic reads pass a sample's noise
// whole at whole-sample shifts and 0.41 of its variance halfway between samples, so the planes at
// which the farthest views fall halfway matched better by that alone, and the estimate came in
// terraces a quarter of a pixel apart. Noisy views are now read through a Gaussian (docs/depth.md,
// "Noisy views"): measured 14.10% and 1.18, against 31.93% and 2.59 with Keys' reads. Their
// silhouettes are judged by visibility over the whole cost window, not each depth by its own
// side of it: that lost here (1.24), and at noise of 1.5 and 3 levels (0.548 -> 0.590, 0.620 ->
// 0.671; docs/depth.md, "Visibility at the silhouettes").
TEST(DepthOnABenchmarkLikeScene, HoldsUpOnNoisyViews) {
  const SimulatedScore s = ScoreSimulatedRig(MakePaperScene(), 5.0, 0.0, 8.0);
  EXPECT_LE(s.badpix, 18.0);
  EXPECT_LE(s.mse100, 1.2);
}

Texture Faint(Texture t, double contrast, double scale) {
  const Vec3 mid = 0.5 * (t.color_a + t.color_b);
  t.color_a = mid + contrast * (t.color_a - mid);
  t.color_b = mid + contrast * (t.color_b - mid);
  t.scale_mm *= scale;
  return t;
}

Scene Fainter(Scene scene, double contrast, double scale) {
  for (auto& o : scene.objects) o.texture = Faint(o.texture, contrast, scale);
  scene.name += fmt::format(" (contrast {}, features x{})", contrast, scale);
  return scene;
}

// The occluders' texture: noise from deep red to pale yellow, features of `scale_mm`.
Texture RedToYellow(double scale_mm, unsigned seed) {
  return Texture{Pattern::kNoise, {0.6, 0.1, 0.05}, {0.95, 0.9, 0.3}, scale_mm, seed};
}

Scene SlopesScene() {
  Scene scene = testing::WallScene("slopes");
  auto turned_y = [](double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return Vec3(std::cos(a), 0.0, -std::sin(a));
  };
  auto turned_x = [](double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return Vec3(0.0, std::cos(a), -std::sin(a));
  };
  scene.Add(
      "ramp y50",
      std::make_shared<RectangleShape>(Vec3(170, 390, -300), turned_y(50), Vec3::UnitY(), 110, 80),
      RedToYellow(10, 9));
  scene.Add(
      "ramp x45",
      std::make_shared<RectangleShape>(Vec3(430, 390, 200), Vec3::UnitX(), turned_x(45), 100, 90),
      Texture{Pattern::kNoise, {0.1, 0.5, 0.1}, {0.8, 0.9, 0.7}, 12, 5});
  scene.Add("ball", std::make_shared<SphereShape>(Vec3(290, 150, -200), 110.0),
            Texture{Pattern::kNoise, {0.5, 0.4, 0.3}, {0.95, 0.85, 0.8}, 15, 7});
  scene.Add(
      "ramp y-65",
      std::make_shared<RectangleShape>(Vec3(470, 150, -700), turned_y(-65), Vec3::UnitY(), 150, 90),
      Texture{Pattern::kNoise, {0.3, 0.3, 0.6}, {0.9, 0.9, 0.95}, 14, 11});
  return scene;
}

Scene SlatsScene() {
  Scene scene = testing::WallScene("slats");
  for (int i = 0; i < 9; ++i)
    scene.Add(fmt::format("slat {}", i),
              std::make_shared<RectangleShape>(Vec3(80 + 55 * i, 275, 150), Vec3::UnitX(),
                                               Vec3::UnitY(), 2.0 + i, 200),
              RedToYellow(6, 9u + i));
  return scene;
}

// Slanted planes (turned 45 to 65 degrees) and a ball in front of a wall, their textures faint (15%
// of their contrast) and three times as coarse: the benchmark's slopes, where only the local planes
// and the slant prior keep the estimate off terraces (docs/depth.md, "Scenes of the benchmark's
// kinds"). Measured 0.96% and 0.245 (0.99% and 0.247 when each side of the visibility step's window
// was only its samples within the edge's threshold of the side's label; 0.90% and 0.238 before the
// visibility step read each side of its window at the samples' own depths and took the far side's
// plane, which gain on the benchmark-like scenes and lose here; with the mean of the far side's
// samples in place of its plane 1.11% and 0.260, which the floors fail; 0.88% and 0.232 when the
// clean-up replaced samples the sweep was sure of too; 1.11% and 0.259 when the visibility step
// took only jumps of half a sample for depth edges, "Small steps"; 1.34% and 0.41 with its cost
// over the whole window at the silhouettes; without the fit and the prior: 2.25%).
TEST(DepthOnABenchmarkLikeScene, HoldsOnFaintSlopes) {
  const SimulatedScore s = ScoreSimulatedRig(Fainter(SlopesScene(), 0.15, 3.0), 5.0);
  EXPECT_LE(s.badpix, 1.05);
  EXPECT_LE(s.mse100, 0.255);
}

// Nine upright slats 4 to 20 mm wide (3 to 14 samples) 3.45 m from the cameras, in front of a wall
// at 5 m: thin occluders, whose silhouettes must stay within about a sample of the truth's.
// Measured 0.27%, MSE x 100 0.334, the silhouettes 0.321 against 0.145 for the truth moved one
// row: a sample of the wall beside a slat in about one row of six along its edges is taken for the
// slat, since the clean-up leaves the samples the sweep was sure of (docs/depth.md, "The clean-up
// where the sweep was sure": 0.06%, 0.077 and 0.064 when it replaced those too, which thinned
// `hci-antinous`' statue; without any clean-up 0.24%, 0.299; without it in 2026-11: 3.12% and
// 3.77, the slats fattened by several samples).
TEST(DepthOnABenchmarkLikeScene, KeepsThinOccludersInPlace) {
  const SimulatedScore s = ScoreSimulatedRig(SlatsScene(), 5.0);
  EXPECT_LE(s.badpix, 0.4);
  EXPECT_LE(s.mse100, 0.4);
  EXPECT_LE(s.silhouettes100, 2.6 * s.moved_row100);
}

// Pockets of a faint wall (10% of its texture's contrast) between parts of one occluder 3.45 m
// away: four U shapes of bars 14 mm wide, their gaps 8 to 40 mm (6 to 28 samples), and four
// pairs of balls 60 mm across, 2 to 12 mm apart (a wedge of wall between them). Seen past the
// occluder's parts on two or three sides, such a pocket is seen whole by no half-array.
Scene PocketsScene() {
  Scene scene = testing::WallScene("pockets");
  scene.objects.front().texture = Faint(scene.objects.front().texture, 0.1, 1.0);
  const double gaps[] = {8, 16, 24, 40};
  for (int i = 0; i < 4; ++i) {
    const Texture texture = RedToYellow(6, 20u + i);
    const double g = gaps[i], x = 90 + 130 * i, y = 170, t = 14, height = 110;
    const auto bar = [&](const std::string& name, double cx, double cy, double w, double h) {
      scene.Add(fmt::format("u {} {}", i, name),
                std::make_shared<RectangleShape>(Vec3(cx, cy, 150), Vec3::UnitX(), Vec3::UnitY(),
                                                 w / 2, h / 2),
                texture);
    };
    bar("left", x - g / 2 - t / 2, y, t, height);
    bar("right", x + g / 2 + t / 2, y, t, height);
    bar("base", x, y - height / 2 + t / 2, g + 2 * t, t);
    scene.Add(fmt::format("ball {} a", i),
              std::make_shared<SphereShape>(Vec3(x - 31, 390, 100), 30.0), texture);
    scene.Add(fmt::format("ball {} b", i),
              std::make_shared<SphereShape>(Vec3(x + 31 + g / 4, 390, 100), 30.0), texture);
  }
  return scene;
}

// Where the wall is faint, a sample of it next to the occluder matches the occluder's depth as
// well as its own (at that depth every view sees the same faint wall beside the occluder's edge),
// and where the occluder is on two or three sides, semi-global matching's paths carry the
// occluder's depth in. The quarter-arrays see into the wider pockets' corners (docs/depth.md,
// "Quarter-arrays"); the visibility of each view, known once there is a map, opens the narrow
// gaps and the wedges between the balls further ("Visibility at the silhouettes"). Measured
// 0.47% and MSE x 100 0.59 (0.63% and 0.58 when the clean-up replaced samples the sweep was sure
// of too; with the step's cost over the whole window, each side's samples read
// at the other's depth too, 1.38% and 1.47; with its window and passes of wide baselines, 3 and
// 3, 2.04% and 2.23; without the step 2.59% and 2.88; without the quarter-arrays as well 2.77%
// and 2.97).
TEST(DepthOnABenchmarkLikeScene, FillsFewPocketsOfAFaintWall) {
  const SimulatedScore s = ScoreSimulatedRig(PocketsScene(), 5.0);
  EXPECT_LE(s.badpix, 1.8);
  EXPECT_LE(s.mse100, 1.8);
  PlaneSweepOptions without;
  without.silhouette_visibility = false;
  const SimulatedScore before = ScoreSimulatedRig(PocketsScene(), 5.0, 0.0, 0.0, without);
  EXPECT_LT(s.mse100, 0.3 * before.mse100);
  EXPECT_LT(s.badpix, before.badpix - 1.5);
}

// Twelve marble balls 44 to 92 mm across, 3.4 to 3.5 m from the cameras, before a grey wall at
// 5 m, lit from the cameras' side with little ambient light: each ball's shading falls to its
// limb, whose outermost samples are darker than the wall behind them (as a statue's are on
// `hci-antinous`). The sweep alone keeps the limbs on the balls and fattens them onto the wall;
// the visibility step and the clean-up take the fattening back, and take some of the darkest
// limb samples with it (docs/depth.md, "Dark limbs", "Dark limbs kept" and "The clean-up where
// the sweep was sure", "Moves the far side reaches", "The near side at its best depth").
// Measured 0.45% and MSE x 100 0.556 (0.562 with the near side judged at its own depth alone; 0.53%
// and 0.666, which the MSE floor fails, when the visibility step also moved samples inside a
// ball that the wall's side did not reach; 0.81% and 0.994 when the clean-up replaced the samples
// the sweep was sure of too; 0.87% and 1.069 when it also moved every limb sample darker than
// the wall); without the two steps 1.89% and 2.35, all of it on the wall's side.
Scene LimbsScene() {
  Scene scene = testing::WallScene("limbs");
  scene.objects.front().texture =
      Texture{Pattern::kNoise, {0.12, 0.12, 0.11}, {0.3, 0.28, 0.25}, 20, 3};
  scene.light_direction = Vec3::UnitZ();
  scene.ambient = 0.05;
  const Texture marble{Pattern::kNoise, {0.55, 0.55, 0.5}, {0.9, 0.9, 0.85}, 8, 31};
  int i = 0;
  for (const double x : {110.0, 250.0, 390.0, 500.0})
    for (const double y : {130.0, 300.0, 440.0}) {
      const double radius = 22.0 + 6.0 * ((i * 7) % 5);
      scene.Add(fmt::format("ball {}", i),
                std::make_shared<SphereShape>(Vec3(x, y, 100.0 + 40.0 * (i % 3)), radius), marble);
      ++i;
    }
  return scene;
}

TEST(DepthOnABenchmarkLikeScene, KeepsMostOfDarkLimbs) {
  const SimulatedScore s = ScoreSimulatedRig(LimbsScene(), 5.0);
  EXPECT_LE(s.badpix, 0.5);
  EXPECT_LE(s.mse100, 0.64);
  PlaneSweepOptions without;
  without.refine_edges = false;
  without.silhouette_visibility = false;
  const SimulatedScore raw = ScoreSimulatedRig(LimbsScene(), 5.0, 0.0, 0.0, without);
  EXPECT_LT(s.mse100, 0.4 * raw.mse100);
}

// A mesh of upright and level wires 2 mm thick, 8 mm apart (1.4 and 5.6 samples), over 360 x
// 310 mm at 3.45 m, before the wall at 5 m: the benchmark's "boxes" has a crate of such mesh.
Scene MeshScene() {
  Scene scene = testing::WallScene("mesh");
  const double wire = 2, pitch = 10, x0 = 120, x1 = 480, y0 = 120, y1 = 430, z = 150;
  const Texture metal = RedToYellow(6, 9u);
  int i = 0;
  for (double x = x0; x <= x1; x += pitch, ++i)
    scene.Add(fmt::format("upright {}", i),
              std::make_shared<RectangleShape>(Vec3(x, 0.5 * (y0 + y1), z), Vec3::UnitX(),
                                               Vec3::UnitY(), wire / 2, (y1 - y0) / 2),
              metal);
  for (double y = y0; y <= y1; y += pitch, ++i)
    scene.Add(fmt::format("level {}", i),
              std::make_shared<RectangleShape>(Vec3(0.5 * (x0 + x1), y, z + 0.01), Vec3::UnitX(),
                                               Vec3::UnitY(), (x1 - x0) / 2, wire / 2),
              metal);
  return scene;
}

// Not handled (docs/depth.md, "A wire mesh in front of a wall"): the map gives the gaps, the wall
// seen through them, the wires' depth. Measured 28.0% and MSE x 100 33.1 (27.8% and 32.9 when
// the visibility step also moved samples the far side did not reach; 27.7% and 33.5 when
// the clean-up replaced samples the sweep was sure of too); the floors keep it
// from getting worse and the scene at hand for whatever handles it (a step that opened the gaps
// by each sample's cheapest views: 23.5%, at twice the error of the `paper` rig).
TEST(DepthOnABenchmarkLikeScene, AWireMeshIsNoWorseThanDocsDepthSays) {
  const SimulatedScore s = ScoreSimulatedRig(MeshScene(), 5.0);
  EXPECT_LE(s.badpix, 30.0);
  EXPECT_LE(s.mse100, 36.0);
}

}  // namespace
}  // namespace lfcam::benchmark_depth_test
