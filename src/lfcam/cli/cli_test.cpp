// End-to-end checks of the lfcam command: a small simulate -> info -> render -> compare run, and
// bad input (missing files, corrupt files, wrong flags) giving a clear message, a non-zero exit
// and nothing half-written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr
};

CommandResult Lfcam(const std::string& args) {
  const std::string command = std::string(LFCAM_CLI_PATH) + " " + args + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  CommandResult run{-1, ""};
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = ::pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

class Cli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One directory per process: ctest runs each test in its own process, in parallel.
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
