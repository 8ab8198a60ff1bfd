// `lfcam depth`, `render --interpolation depth --depth` and `simulate lightfield --depth-out` as a
// user runs them: the files, --json, and the refusals (exit 2 for usage, 1 for bad input, with
// nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;

class DepthCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeScratchDir("lfcam_depth_cli");
    const auto run = Lfcam(
        "simulate lightfield --grid 3x3 --st-res 64x56 --supersampling 1 "
        "--quiet --out " +
        P("p.lf") + " --depth-out " + P("truth"));
    ASSERT_EQ(run.status, 0) << run.output;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(DepthCli, WritesAMapItsConfidenceAndPreviewAndAFolderForRendering) {
  auto run = Lfcam("depth " + P("p.lf") + " --out " + P("d.png") + " --json --disparity-pfm " +
                   P("d.pfm"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["map"]["view"], nlohmann::json({1, 1}));
  EXPECT_EQ(j["disparity_pfm"], P("d.pfm"));
  EXPECT_TRUE(fs::exists(P("d.pfm")));
  EXPECT_EQ(j["map"]["n_s"], 64);
  EXPECT_TRUE(fs::exists(P("d.png")) && fs::exists(P("d.confidence.png")) &&
              fs::exists(P("d.preview.png")));
  run = Lfcam("depth " + P("p.lf") + " --all --quiet --out " + P("set"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(fs::exists(P("set/depth.json")) && fs::exists(P("set/depth_02_02.png")));
  // The set renders (through an aperture too), as do the simulator's true maps, and without
  // maps they are estimated.
  for (const std::string& maps : {" --depth " + P("set") + " --aperture 40 --antialias",
                                  " --depth " + P("truth"), std::string()}) {
    run = Lfcam("render " + P("p.lf") + " --size 48 --interpolation depth --quiet --out " +
                P("r.png") + maps);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("depth lookup"), std::string::npos) << run.output;
  }
}

// --backend gl: the cost volumes on the GPU (llvmpipe in CI), the same map as the CPU's, and
// what ran where said; auto takes only a hardware GPU.
TEST_F(DepthCli, SweepsOnTheGpuWithBackendGl) {
  auto run = Lfcam("depth " + P("p.lf") + " --out " + P("cpu.png") + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("depth " + P("p.lf") + " --out " + P("gl.png") + " --backend gl --json");
  if (run.status != 0 && run.output.find("--backend gl:") != std::string::npos) {
    if (testing::GlRequired()) FAIL() << "LFCAM_REQUIRE_GL=1 but:\n" << run.output;
    GTEST_SKIP() << "no GL 4.3 context: " << run.output;
  }
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["gpu"]["gpu_sweeps"], 2) << run.output;  // the range's coarse sweep and the map's
  EXPECT_EQ(j["gpu"]["cpu_sweeps"], 0) << run.output;
  EXPECT_FALSE(j["gpu"]["device"].get<std::string>().empty());
  // The GPU's time, and what it went to: uploading, the passes, reading back.
  const double upload = j["gpu"]["gpu_upload_seconds"], passes = j["gpu"]["gpu_pass_seconds"],
               readback = j["gpu"]["gpu_readback_seconds"], total = j["gpu"]["gpu_seconds"];
  EXPECT_GT(passes, 0.0) << run.output;
  EXPECT_GE(std::min(upload, readback), 0.0) << run.output;
  EXPECT_NEAR(upload + passes + readback, total, 1e-6 + 1e-3 * total) << run.output;
  const cv::Mat cpu = cv::imread(P("cpu.png"), cv::IMREAD_UNCHANGED);
  const cv::Mat gl = cv::imread(P("gl.png"), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(cpu.empty());
  ASSERT_EQ(cpu.size(), gl.size());
  cv::Mat differ;
  cv::compare(cpu, gl, differ, cv::CMP_NE);
  EXPECT_LE(cv::countNonZero(differ), int(cpu.total() / 100));
  // Every view: their estimates run side by side and their sweeps take the GPU in turn.
  run = Lfcam("depth " + P("p.lf") + " --all --quiet --out " + P("set") + " --backend gl --json");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(run.output)["gpu"]["gpu_sweeps"], 10) << run.output;
  run = Lfcam("depth " + P("p.lf") + " --out " + P("auto.png") + " --backend auto");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(run.output.find("cost volumes:") != std::string::npos ||
              run.output.find("on the CPU") != std::string::npos)
      << run.output;
}

TEST_F(DepthCli, ExportsPointsFromTheMapsForColmapAndNerf) {
  auto run = Lfcam("export " + P("p.lf") + " --format colmap --out " + P("colmap") + " --depth " +
                   P("truth"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("points from the depth maps of 9 views"), std::string::npos)
      << run.output;
  std::ifstream points(P("colmap/sparse/0/points3D.txt"));
  int lines = 0;
  for (std::string line; std::getline(points, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_GT(lines, 50);
  // And for NeRF a PLY that transforms.json names; not with plain PNG views; and the maps must
  // be this light field's.
  run =
      Lfcam("export " + P("p.lf") + " --format nerf --out " + P("nerf") + " --depth " + P("truth"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("sparse_pc.ply"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(P("nerf/sparse_pc.ply")));
  run = Lfcam("export " + P("p.lf") + " --format png-views --out " + P("views") + " --depth " +
              P("truth"));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("--depth"), std::string::npos) << run.output;
  run = Lfcam("simulate lightfield --grid 3x3 --st-res 32x28 --supersampling 1 --quiet --out " +
              P("small.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = Lfcam("export " + P("small.lf") + " --format colmap --out " + P("colmap2") + " --depth " +
              P("truth"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_FALSE(fs::exists(P("views")) || fs::exists(P("colmap2")));
}

TEST_F(DepthCli, RefusesBadFlagsAndBadMapsWritingNothing) {
  const auto refused = [&](const std::string& args, int status, const std::string& names) {
    const auto run = Lfcam(args);
    EXPECT_EQ(run.status, status) << args << "\n" << run.output;
    EXPECT_NE(run.output.find(names), std::string::npos) << args << "\n" << run.output;
  };
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --view 3,0", 2, "--view");
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --backend cuda", 2, "--backend");
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --view 1.5,0", 2, "--view");
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --depth-range 5000,3000", 2,
          "--depth-range");
  refused("depth " + P("p.lf") + " --out " + P("x.jpg"), 2, "--out");
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --all --view 1,1", 2, "--view");
  refused("depth " + P("p.lf") + " --all --out " + P("truth"), 2, "not an empty folder");
  refused("depth " + P("p.lf") + " --out " + P("x.png") + " --disparity-pfm " + P("x.png"), 2,
          "--disparity-pfm");
  refused("depth " + P("p.lf") + " --all --out " + P("set2") + " --disparity-pfm " + P("x.pfm"), 2,
          "not with --all");
  refused("render " + P("p.lf") + " --out " + P("r.png") + " --depth " + P("truth"), 2, "--depth");
  refused("render " + P("p.lf") + " --out " + P("r.png") +
              " --interpolation depth "
              "--integrator cameras",
          2, "lens-samples");
  refused("render " + P("p.lf") + " --out " + P("r.png") + " --interpolation depth --depth " +
              P("nothere"),
          1, "depth.json");
  // A damaged map is named; no image is written.
  std::ofstream(P("truth/depth_01_01.png"), std::ios::trunc) << "not a png";
  refused("render " + P("p.lf") + " --out " + P("r.png") + " --interpolation depth --depth " +
              P("truth"),
          1, "depth_01_01.png");
  EXPECT_FALSE(fs::exists(P("r.png")));
  EXPECT_FALSE(fs::exists(P("x.png")));
  EXPECT_FALSE(fs::exists(P("x.pfm")));
}

}  // namespace
}  // namespace lfcam
