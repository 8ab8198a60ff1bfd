// End-to-end checks of the lfcam command: a small simulate -> info -> render -> compare run, and
// bad input (missing files, corrupt files, wrong flags) giving a clear message, a non-zero exit
// and nothing half-written.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/test_support.h"

namespace {

namespace fs = std::filesystem;

using lfcam::testing::CommandResult;
using lfcam::testing::Lfcam;

class Cli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One directory per process: ctest runs each suite in its own process, in parallel.
    dir_ =
        new fs::path(fs::temp_directory_path() / ("lfcam_cli_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const CommandResult run =
        Lfcam("simulate lightfield --scene paper --grid 4x4 --st-res 96x88 --quiet --out " +
              (*dir_ / "small.lf").string());
    ASSERT_EQ(run.status, 0) << run.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  static fs::path* dir_;
};
fs::path* Cli::dir_ = nullptr;

TEST_F(Cli, InfoDescribesTheSlabUnderThePapersNames) {
  const CommandResult run = Lfcam("info --json " + Path("small.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["rows"], 4);
  EXPECT_EQ(j["n_s"], 96);
  EXPECT_EQ(j["n_t"], 88);
  EXPECT_EQ(j["sample_type"], "srgb8");
  for (const char* key :
       {"p_ca", "u_ca", "v_ca", "n_ca", "rows", "cols", "pitch_mm", "view_window", "st_domain"})
    EXPECT_TRUE(j["slab"].contains(key)) << key;
  EXPECT_DOUBLE_EQ(j["slab"]["pitch_mm"].get<double>(), 28.0);
  EXPECT_DOUBLE_EQ(j["separation_mm"].get<double>(), 3600.0);
  EXPECT_EQ(j["metadata"]["scene"], "paper");
  const CommandResult text = Lfcam("info " + Path("small.lf"));
  EXPECT_NE(text.output.find("p_ca"), std::string::npos);
}

TEST_F(Cli, RenderAndOracleAgreeAndCompareReportsIt) {
  const std::string camera = " --size 48 --aperture 96 --focus-distance 3900 ";
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + camera + "--out " + Path("r.png")).status, 0);
  ASSERT_EQ(Lfcam("oracle --scene paper" + camera + "--samples 64 --out " + Path("o.png")).status,
            0);
  const CommandResult run = Lfcam("compare --json " + Path("r.png") + " " + Path("o.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(run.output);
  EXPECT_GT(j["psnr_db"].get<double>(), 20.0);
  EXPECT_GT(j["ssim"].get<double>(), 0.5);
  EXPECT_EQ(j["pixels"], 48 * 48);
  // The cameras integrator too, and it says how many cameras a pixel it read.
  const CommandResult cameras =
      Lfcam("render " + Path("small.lf") + camera + "--integrator cameras --out " + Path("c.png"));
  ASSERT_EQ(cameras.status, 0) << cameras.output;
  EXPECT_NE(cameras.output.find("cameras a pixel"), std::string::npos) << cameras.output;
  const auto c =
      nlohmann::json::parse(Lfcam("compare --json " + Path("c.png") + " " + Path("o.png")).output);
  EXPECT_GT(c["psnr_db"].get<double>(), 20.0);
  // Asked for the quadrilinear lookup in so many words, the cameras integrator takes that
  // lookup's limit (views prefiltered), as --integrator cameras-quadrilinear does.
  for (const std::string integrator :
       {"--integrator cameras --interpolation quadrilinear", "--integrator cameras-quadrilinear"}) {
    const CommandResult limit =
        Lfcam("render " + Path("small.lf") + camera + integrator + " --out " + Path("q.png"));
    ASSERT_EQ(limit.status, 0) << limit.output;
    EXPECT_NE(limit.output.find("views prefiltered"), std::string::npos) << limit.output;
  }
  EXPECT_EQ(Lfcam("render " + Path("small.lf") + camera +
                  "--integrator cameras-quadrilinear --interpolation depth --out " + Path("x.png"))
                .status,
            2);
  // A breathing film focuses beyond f (500 mm by default), and the command says so before any
  // work; a fixed film (--no-breathing) focuses anywhere in front of the lens.
  const CommandResult near = Lfcam("render " + Path("small.lf") +
                                   " --size 48 --focus-distance 300 --out " + Path("n.png"));
  EXPECT_EQ(near.status, 2) << near.output;
  EXPECT_NE(near.output.find("--focus-distance: 300 must exceed the focal length (500), or give "
                             "--no-breathing"),
            std::string::npos)
      << near.output;
  EXPECT_FALSE(fs::exists(Path("n.png")));
  EXPECT_EQ(Lfcam("render " + Path("small.lf") +
                  " --size 48 --focus-distance 300 --no-breathing --out " + Path("n.png"))
                .status,
            0);
  EXPECT_EQ(Lfcam("render " + Path("small.lf") +
                  " --size 48 --focal-length 600 --focus-distance 550 --out " + Path("x.png"))
                .status,
            2);
}

// An aperture wider than the rig: the rays that miss are left out of each pixel's mean (the
// frame as bright as a pinhole's), and the command says why the share of rays that hit is low.
TEST_F(Cli, AnApertureWiderThanTheRigSaysWhyRaysMissed) {
  ASSERT_EQ(Lfcam("simulate lightfield --scene paper --grid 1x7 --st-res 96x88 --quiet --out " +
                  Path("row.lf"))
                .status,
            0);
  const std::string camera = " --size 48 --focus-distance 3900 ";
  const CommandResult pinhole =
      Lfcam("render " + Path("row.lf") + camera + "--out " + Path("p.png"));
  ASSERT_EQ(pinhole.status, 0) << pinhole.output;
  EXPECT_EQ(pinhole.output.find("note:"), std::string::npos) << pinhole.output;
  const CommandResult wide =
      Lfcam("render " + Path("row.lf") + camera + "--aperture 100 --out " + Path("w.png"));
  ASSERT_EQ(wide.status, 0) << wide.output;
  EXPECT_NE(wide.output.find("33.3% of rays hit the slab"), std::string::npos) << wide.output;
  EXPECT_NE(wide.output.find("note: 66.7% of the aperture's rays missed the light field: the "
                             "aperture (d_l 100 mm) is wider than a single row of cameras (28 mm "
                             "tall)"),
            std::string::npos)
      << wide.output;
  const double pinhole_mean = cv::mean(cv::imread(Path("p.png")))[1];
  const double wide_mean = cv::mean(cv::imread(Path("w.png")))[1];
  EXPECT_GT(pinhole_mean, 20.0);
  EXPECT_NEAR(wide_mean, pinhole_mean, 0.1 * pinhole_mean);
  // Within the 4 x 4 rig (112 mm) every ray of a 96 mm aperture hits: nothing to say.
  const CommandResult within =
      Lfcam("render " + Path("small.lf") + camera + "--aperture 96 --out " + Path("i.png"));
  ASSERT_EQ(within.status, 0) << within.output;
  EXPECT_NE(within.output.find("100.0% of rays hit"), std::string::npos) << within.output;
  EXPECT_EQ(within.output.find("note:"), std::string::npos) << within.output;
  // Beyond the 4 x 4 rig: the array named with its size.
  const CommandResult beyond =
      Lfcam("render " + Path("small.lf") + camera + "--aperture 200 --out " + Path("b.png"));
  ASSERT_EQ(beyond.status, 0) << beyond.output;
  EXPECT_NE(beyond.output.find("is wider than the camera array (112 x 112 mm)"), std::string::npos)
      << beyond.output;
}

// The scene at a time (issue 24): its movers in, recorded in the file's metadata; the still
// without them; a time that is not one refused.
TEST_F(Cli, SimulatesTheSceneAtATime) {
  const std::string common = " --scene paper --grid 2x2 --st-res 96x88 --quiet --out ";
  ASSERT_EQ(Lfcam("simulate lightfield" + common + Path("still.lf")).status, 0);
  ASSERT_EQ(Lfcam("simulate lightfield --time 1.2" + common + Path("at.lf")).status, 0);
  const auto info = nlohmann::json::parse(Lfcam("info --json " + Path("at.lf")).output);
  EXPECT_DOUBLE_EQ(info["metadata"]["time_s"].get<double>(), 1.2);
  const auto still = nlohmann::json::parse(Lfcam("info --json " + Path("still.lf")).output);
  EXPECT_FALSE(still["metadata"].contains("time_s"));
  // The ball (and the bead) show: the two light fields' views differ.
  const CommandResult compare =
      Lfcam("compare " + Path("still.lf") + " " + Path("at.lf") + " --json");
  ASSERT_EQ(compare.status, 0) << compare.output;
  const auto difference = nlohmann::json::parse(compare.output);
  ASSERT_TRUE(difference["psnr_db"].is_number()) << compare.output;  // null: identical
  EXPECT_LT(difference["psnr_db"].get<double>(), 40.0);
  for (const char* bad : {"--time -1", "--time nan", "--time 1e9"})
    EXPECT_EQ(Lfcam(std::string("simulate lightfield ") + bad + common + Path("bad.lf")).status, 2)
        << bad;
  EXPECT_FALSE(fs::exists(Path("bad.lf")));
  // The oracle speaks of the same instant.
  const std::string frame = " --size 48x44 --samples 4 --quiet --out ";
  ASSERT_EQ(Lfcam("oracle --time 1.2" + frame + Path("at.png")).status, 0);
  ASSERT_EQ(Lfcam("oracle" + frame + Path("still.png")).status, 0);
  EXPECT_TRUE(fs::exists(Path("at.png")));
  EXPECT_EQ(Lfcam("oracle --time nan" + frame + Path("bad.png")).status, 2);
  EXPECT_FALSE(fs::exists(Path("bad.png")));
}

TEST_F(Cli, BenchTimesThePapersTablesBesideItsFigures) {
  const std::string fast = " --lightfield " + Path("small.lf") + " --min-runs 1 --min-seconds 0";
  CommandResult run = Lfcam("bench table1" + fast + " --json " + Path("t1.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("510.4"), std::string::npos) << run.output;  // the paper's 1024^2
  std::ifstream t1_file(Path("t1.json"));
  const auto t1 = nlohmann::json::parse(t1_file);
  ASSERT_EQ(t1["cells"].size(), 8u);
  for (const auto& cell : t1["cells"]) {
    for (const char* field : {"table", "size", "threads", "integrator", "aperture_mm", "lens_rate",
                              "median_ms", "paper_ms"})
      EXPECT_TRUE(cell.contains(field)) << field;
    EXPECT_EQ(cell["table"], "table1");
    EXPECT_GT(cell["median_ms"].get<double>(), 0.0);
    EXPECT_EQ(cell["aperture_mm"].get<double>(), 0.0);
  }
  EXPECT_EQ(t1["cells"][2]["size"], 1024);
  EXPECT_EQ(t1["cells"][2]["threads"], 1);
  EXPECT_DOUBLE_EQ(t1["cells"][2]["paper_ms"].get<double>(), 510.41);

  run = Lfcam("bench table2 --integrator cameras" + fast + " --json " + Path("t2.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream t2_file(Path("t2.json"));
  const auto t2 = nlohmann::json::parse(t2_file);
  ASSERT_EQ(t2["cells"].size(), 4u);  // one per aperture: gamma plays no part
  EXPECT_EQ(t2["cells"][3]["aperture_mm"].get<double>(), 256.0);
  EXPECT_TRUE(t2["cells"][3]["lens_rate"].is_null());
  EXPECT_DOUBLE_EQ(t2["cells"][3]["paper_ms"].get<double>(), 87.38);
  EXPECT_EQ(t2["cells"][3]["integrator"], "cameras");
  EXPECT_FALSE(t2["cells"][3].contains("users_case_ms"));
  // The quadrilinear limit's cells: one per aperture, the paper's lookup.
  run = Lfcam("bench table2 --integrator cameras-quadrilinear" + fast + " --json " +
              Path("t2q.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream t2q_file(Path("t2q.json"));
  const auto t2q = nlohmann::json::parse(t2q_file);
  ASSERT_EQ(t2q["cells"].size(), 4u);
  EXPECT_EQ(t2q["cells"][3]["integrator"], "cameras-quadrilinear");
  EXPECT_EQ(t2q["cells"][3]["interpolation"], "quadrilinear");
  EXPECT_NE(t2q["cells"][3]["renderer"].get<std::string>().find("views prefiltered"),
            std::string::npos);
  // The depth lookup's cells need the light field's depth maps, and a light field to go with.
  for (const std::string& flags : std::vector<std::string>{
           " --interpolation depth" + fast,
           " --interpolation depth --integrator cameras --depth " + Path("nowhere") + fast,
           " --depth " + Path("nowhere") + fast}) {
    run = Lfcam("bench table2" + flags);
    EXPECT_EQ(run.status, 2) << flags << ": " << run.output;
  }
  run = Lfcam("bench table2 --interpolation depth --depth " + Path("nowhere") + fast);
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("nowhere"), std::string::npos) << run.output;

  // The user's case beside: every cell timed on both, the ratio printed, no file left behind.
  const auto leftovers = [] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
      n += e.path().filename().string().rfind("lfcam-bench-users-case-", 0) == 0;
    return n;
  };
  const int before = leftovers();
  run = Lfcam("bench table2 --integrator cameras --users-case" + fast + " --json " +
              Path("t2u.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("user's ms"), std::string::npos) << run.output;
  std::ifstream t2u_file(Path("t2u.json"));
  const auto t2u = nlohmann::json::parse(t2u_file);
  ASSERT_EQ(t2u["cells"].size(), 4u);
  for (const auto& cell : t2u["cells"]) EXPECT_GT(cell["users_case_ms"].get<double>(), 0.0);
  EXPECT_TRUE(t2u.contains("users_case"));
  EXPECT_EQ(leftovers(), before);

  // The viewer's frames without a window: both paths of the eye, a frame's cost and its rate,
  // the viewer's default integrator on either backend.
  run = Lfcam("bench viewer --size 32x18 --aperture 30" + fast);
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* row : {"cameras-quadrilinear, d_l 30 mm", "across the array's plane",
                          "in front of it", "frames/s"})
    EXPECT_NE(run.output.find(row), std::string::npos) << row << ": " << run.output;
  for (const char* flags : {" --json x.json", " --users-case", " --size 0x18"}) {
    run = Lfcam("bench viewer" + fast + flags);
    EXPECT_EQ(run.status, 2) << flags << ": " << run.output;
  }

  // Bad flags are refused before any work.
  EXPECT_EQ(Lfcam("bench table3" + fast).status, 2);
  run = Lfcam("bench table1 --integrator cameras" + fast);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("table2"), std::string::npos) << run.output;
  run = Lfcam("bench table1" + fast + " --json " + Path("no/such/dir/t.json"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--json"), std::string::npos) << run.output;
}

TEST_F(Cli, RendersAndBenchesOnTheGlBackend) {
  const std::string camera = " --size 48 --aperture 60 --integrator cameras ";
  CommandResult run =
      Lfcam("render " + Path("small.lf") + camera + "--backend gl --out " + Path("gl.png"));
  if (run.status == 1 && run.output.find("--backend gl: no OpenGL") != std::string::npos) {
    const char* required = std::getenv("LFCAM_REQUIRE_GL");
    if (required != nullptr && std::string(required) == "1")
      FAIL() << "LFCAM_REQUIRE_GL=1 but: " << run.output;
    GTEST_SKIP() << run.output;
  }
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("gl ("), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("ms on the GPU"), std::string::npos) << run.output;
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + camera + "--out " + Path("cpu.png")).status, 0);
  const auto same = nlohmann::json::parse(
      Lfcam("compare --json " + Path("gl.png") + " " + Path("cpu.png")).output);
  EXPECT_GT(same["psnr_db"].get<double>(), 45.0);

  const std::string fast = " --lightfield " + Path("small.lf") + " --min-runs 1 --min-seconds 0";
  run = Lfcam("bench table1 --backend gl --workgroup 8x8" + fast + " --json " + Path("g1.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("work group 8x8"), std::string::npos) << run.output;
  std::ifstream g1_file(Path("g1.json"));
  const auto g1 = nlohmann::json::parse(g1_file);
  ASSERT_EQ(g1["cells"].size(), 4u);  // one per size: threads play no part on the GPU
  EXPECT_EQ(g1["backend"], "gl");
  EXPECT_TRUE(g1["gpu"].contains("renderer"));
  for (const auto& cell : g1["cells"]) {
    EXPECT_TRUE(cell["threads"].is_null());
    EXPECT_EQ(cell["backend"], "gl");
    EXPECT_GT(cell["median_ms"].get<double>(), 0.0);
  }

  // The viewer's frames on the GPU: its default there, the quadrilinear limit, and each
  // frame's wall-clock beside the GPU's time.
  run = Lfcam("bench viewer --backend gl --size 32x18" + fast);
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* row : {"cameras-quadrilinear, d_l 256 mm", "wall/GPU", "in front of it"})
    EXPECT_NE(run.output.find(row), std::string::npos) << row << ": " << run.output;

  // The scalar reference is the CPU's; a bad backend or work group is bad usage.
  EXPECT_EQ(Lfcam("render " + Path("small.lf") + " --backend gl --reference --out " + Path("x.png"))
                .status,
            2);
  EXPECT_EQ(Lfcam("bench table1 --backend metal" + fast).status, 2);
  run = Lfcam("render " + Path("small.lf") + " --backend gl --workgroup 4096x4096 --out " +
              Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--workgroup"), std::string::npos) << run.output;
}

TEST_F(Cli, MontageLaysImagesOutOnASheet) {
  const std::string camera = " --size 40x30 ";
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + camera + "--out " + Path("m1.png")).status, 0);
  ASSERT_EQ(
      Lfcam("render " + Path("small.lf") + camera + "--focal-length 800 --out " + Path("m2.png"))
          .status,
      0);
  const CommandResult run =
      Lfcam("montage " + Path("m1.png") + " " + Path("m2.png") +
            " --tile-width 100 --labels 'a;b' --title T --out " + Path("sheet.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("2 images"), std::string::npos);
  // Two 100-pixel tiles side by side with 8-pixel gaps.
  const CommandResult info = Lfcam("compare " + Path("sheet.png") + " " + Path("sheet.png"));
  EXPECT_EQ(info.status, 0);
  EXPECT_NE(info.output.find("over " + std::to_string((2 * 100 + 3 * 8) * (36 + 75 + 24 + 16)) +
                             " pixels"),
            std::string::npos)
      << info.output;
}

TEST_F(Cli, BadInputFailsClearlyAndWritesNothing) {
  struct Case {
    std::string args;
    std::string expect;  // in the message
  };
  std::ofstream(Path("corrupt.lf")) << "this is not a light field, it only pretends to be one";
  const std::vector<Case> cases = {
      {"render " + Path("missing.lf") + " --out " + Path("x.png"), "missing.lf"},
      {"render " + Path("corrupt.lf") + " --out " + Path("x.png"), "corrupt.lf"},
      {"render " + Path("small.lf") + " --eye 1,2 --out " + Path("x.png"), "--eye"},
      {"render " + Path("small.lf") + " --size 0 --out " + Path("x.png"), "--size"},
      {"render " + Path("small.lf") + " --focus-distance 100 --out " + Path("x.png"), "focus"},
      {"render " + Path("small.lf") + " --out " + Path("x.png") + " --bogus", "bogus"},
      {"oracle --scene nowhere --out " + Path("x.png"), "nowhere"},
      {"simulate lightfield --st-res 10x0 --out " + Path("x.lf"), "--st-res"},
      {"compare " + Path("missing.png") + " " + Path("missing2.png"), "missing.png"},
      {"info " + Path("corrupt.lf"), "magic"},
  };
  for (const auto& c : cases) {
    const CommandResult run = Lfcam(c.args);
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.args << "\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(Path("x.png")));
  EXPECT_FALSE(fs::exists(Path("x.lf")));
  for (const auto& entry : fs::directory_iterator(*dir_))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
}

}  // namespace

namespace {

// Exit status: 0 success, 1 an error in the work, 2 bad usage (docs/cli.md).
TEST_F(Cli, HelpListsTheCommandsAndExitCodesAreConsistent) {
  CommandResult run = Lfcam("");
  EXPECT_EQ(run.status, 0) << run.output;
  for (const char* word :
       {"simulate", "render", "oracle", "info", "compare", "montage", "help", "Exit status"})
    EXPECT_NE(run.output.find(word), std::string::npos) << word << "\n" << run.output;
  run = Lfcam("help");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("montage"), std::string::npos) << run.output;
  run = Lfcam("help render");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("--lens-rate"), std::string::npos) << run.output;
  EXPECT_EQ(Lfcam("help simulate lightfield").status, 0);
  EXPECT_EQ(Lfcam("render --help").status, 0);
  EXPECT_EQ(Lfcam("--version").status, 0);

  struct Case {
    std::string args;
    int status;
    std::string expect;
  };
  const std::string lf = Path("small.lf"), out = " --out " + Path("x.png");
  const std::vector<Case> cases = {
      {"help nosuch", 2, "nosuch"},
      {"frobnicate", 2, "frobnicate"},
      {"render " + lf + out + " --bogus", 2, "--bogus"},
      {"render " + lf, 2, "--out"},
      {"render " + lf + out + " --size 0", 2, "--size"},
      {"render " + lf + out + " --size 10.5", 2, "--size"},
      {"render " + lf + out + " --size 16385", 2, "16384"},
      {"render " + lf + out + " --threads -1", 2, "--threads"},
      {"render " + lf + out + " --threads 4294967297", 2, "--threads"},
      {"render " + lf + out + " --focus-distance 100", 2, "--focus-distance"},
      {"render " + lf + out + " --interpolation cubic", 2, "--interpolation"},
      {"render " + lf + out + " --integrator exact", 2, "--integrator"},
      {"render " + lf + out + " --eye 1,2,3 --look-at 1,2,3", 2, "coincide"},
      {"oracle --scene nowhere" + out, 2, "--scene"},
      {"oracle" + out + " --samples 100000000", 2, "--samples"},
      {"simulate lightfield --grid 5000x2 --out " + Path("x.lf"), 2, "--grid"},
      {"simulate lightfield --supersampling 0 --out " + Path("x.lf"), 2, "--supersampling"},
      {"simulate lightfield --st-res 65536x65536 --out " + Path("x.lf"), 2, "memory limit"},
      {"render " + Path("missing.lf") + out, 1, "missing.lf"},
      {"info " + Path("missing.lf"), 1, "no such file"},
      {"compare " + lf + " " + Path("missing.png"), 1, "not a PNG or JPEG"},
      {"compare " + lf + " " + Path("missing.lf"), 1, "missing.lf"},
  };
  for (const auto& c : cases) {
    run = Lfcam(c.args);
    EXPECT_EQ(run.status, c.status) << c.args << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.args << "\n" << run.output;
    EXPECT_EQ(run.output.find("terminate called"), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(Path("x.png")));
  EXPECT_FALSE(fs::exists(Path("x.lf")));
}

TEST_F(Cli, FlagsAndOutputsAreCheckedBeforeTheInputIsRead) {
  // The input does not exist: an error about a flag or an output proves they came first.
  const std::string missing = "render " + Path("missing.lf");
  CommandResult run = Lfcam(missing + " --size 0 --out " + Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--size"), std::string::npos) << run.output;
  run = Lfcam(missing + " --out " + Path("no/such/dir/x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--out"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("does not exist"), std::string::npos) << run.output;
  run = Lfcam(missing + " --out " + Path("x.tiff"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find(".tiff"), std::string::npos) << run.output;
  run = Lfcam(missing + " --out /proc/x.png");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("cannot write in /proc"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("Success"), std::string::npos) << run.output;
  // Two outputs: both can be written, or the command does not start.
  run = Lfcam("render " + Path("small.lf") + " --size 8 --out " + Path("both.png") +
              " --hit-mask " + Path("no/dir/mask.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_FALSE(fs::exists(Path("both.png")));
  run = Lfcam("render " + Path("small.lf") + " --size 8 --out " + Path("both.png") +
              " --hit-mask " + Path("./both.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("same file"), std::string::npos) << run.output;
}

TEST_F(Cli, WorkDerivedFromFlagsIsBoundedAndNamesTheFlag) {
  CommandResult run = Lfcam("render " + Path("small.lf") +
                            " --lens-rate 68359375 --aperture 512 --out " + Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--lens-rate"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("131072"), std::string::npos) << run.output;
  run = Lfcam("render " + Path("small.lf") + " --aperture 1e30 --out " + Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--aperture"), std::string::npos) << run.output;
  {
    const lfcam::testing::ScopedEnv limit("LFCAM_MEMORY_LIMIT", "100M");
    run = Lfcam("render " + Path("small.lf") + " --size 4096 --out " + Path("x.png"));
    EXPECT_EQ(run.status, 2);
    EXPECT_NE(run.output.find("--size: a 4096x4096 image needs"), std::string::npos) << run.output;
    run = Lfcam("simulate lightfield --st-res 4096 --out " + Path("x.lf"));
    EXPECT_EQ(run.status, 2);
    EXPECT_NE(run.output.find("memory limit"), std::string::npos) << run.output;
  }
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + " --size 8 --quiet --out " + Path("t.png")).status,
            0);
  run = Lfcam("montage " + Path("t.png") + " --tile-width 100000 --out " + Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("--tile-width"), std::string::npos) << run.output;
  run = Lfcam("montage " + Path("t.png") + " " + Path("t.png") + " --tile-width 9000 --out " +
              Path("x.png"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("limit"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(Path("x.png")));
}

TEST_F(Cli, JsonOutputIsValidJsonAndSaysWhatHappened) {
  CommandResult run = Lfcam("info --verify --json " + Path("small.lf"));
  ASSERT_EQ(run.status, 0) << run.output;
  auto j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["verified"], true);
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + " --size 8 --out " + Path("j.png")).status, 0);
  run = Lfcam("compare --json " + Path("j.png") + " " + Path("j.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  j = nlohmann::json::parse(run.output);
  EXPECT_EQ(j["identical"], true);
  EXPECT_TRUE(j["psnr_db"].is_null());
  EXPECT_EQ(run.output.find("inf"), std::string::npos);
  // Errors under --json are JSON too (on stdout), with the exit status in them.
  run = Lfcam("info --json " + Path("missing.lf") + " 2>/dev/null");
  EXPECT_EQ(run.status, 1);
  j = nlohmann::json::parse(run.output);
  EXPECT_NE(j["error"].get<std::string>().find("missing.lf"), std::string::npos);
  EXPECT_EQ(j["exit_status"], 1);
  // Regression: a file name that is not UTF-8 made the JSON error itself throw (abort).
  run = Lfcam("info --json " + Path("\xff\xfe.lf") + " 2>/dev/null");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_TRUE(nlohmann::json::parse(run.output).contains("error")) << run.output;
  run = Lfcam("info --json --bogus " + Path("small.lf") + " 2>/dev/null");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(nlohmann::json::parse(run.output)["exit_status"], 2);
}

TEST_F(Cli, ProgressIsDrawnOnlyOnATerminal) {
  const std::string render = "render " + Path("small.lf") + " --size 64 --aperture 96 --out ";
  // popen: stdout and stderr are pipes, so no progress bar.
  CommandResult run = Lfcam(render + Path("p.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find('\r'), std::string::npos) << run.output;
  if (std::system("command -v script >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "util-linux `script` is not installed: no terminal to test with";
  // Under a pseudo-terminal the bar is drawn; --quiet silences it.
  const std::string tty = "script -qec '" + std::string(LFCAM_CLI_PATH) + " ";
  run = Lfcam("x >/dev/null; " + tty + render + Path("q.png") +
              " --repeat 40 --reference' /dev/null");
  EXPECT_NE(run.output.find("rendering"), std::string::npos) << run.output;
  run = Lfcam("x >/dev/null; " + tty + render + Path("q.png") +
              " --repeat 40 --reference --quiet' /dev/null");
  EXPECT_EQ(run.output.find("rendering"), std::string::npos) << run.output;
}

TEST_F(Cli, SpecialAndHugeInputsAreRefusedQuickly) {
  const std::string fifo = Path("pipe.lf");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  CommandResult run = Lfcam("info " + fifo);
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("FIFO"), std::string::npos) << run.output;
  run = Lfcam("compare " + fifo + " " + fifo);
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("FIFO"), std::string::npos) << run.output;
  // A PNG whose header claims 20000 x 20000 pixels.
  ASSERT_EQ(Lfcam("render " + Path("small.lf") + " --size 8 --out " + Path("b.png")).status, 0);
  {
    std::fstream png(Path("b.png"), std::ios::in | std::ios::out | std::ios::binary);
    const char size[8] = {0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20};
    png.seekp(16);
    png.write(size, 8);
  }
  run = Lfcam("compare " + Path("b.png") + " " + Path("b.png"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("20000x20000 PNG image is larger than the limit"), std::string::npos)
      << run.output;
}

}  // namespace
