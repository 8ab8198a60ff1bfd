// The web page `lfcam export --format web` writes, in a real browser: Debian's Chromium,
// headless (WebGL2 on its software GPU), sets views through the page's URL, and each screenshot
// is compared with `lfcam render --integrator cameras` of the same view (the page's model). A
// mutation of the shader's refocus must fail the comparison, so the test can see a wrong page.
// Without Chromium the test skips, unless LFCAM_REQUIRE_BROWSER=1 (scripts/test.sh installs
// it), where that fails.
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/image_metrics.h"
#include "lfcam/core/test_support.h"
#include "lfcam/sim/test_capture.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;

constexpr double kTargetPsnrDb = 35.0;  // issue 25's target, same camera, same size

bool BrowserRequired() {
  const char* required = std::getenv("LFCAM_REQUIRE_BROWSER");
  return required != nullptr && std::string(required) == "1";
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class WebPageBrowser : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (testing::RunOnce("command -v chromium >/dev/null 2>&1").status != 0) return;
    has_browser_ = true;
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("lfcam_web_browser_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    // The light field and its page, made once per build for every test process.
    shared_ = new fs::path(
        testing::SharedTestArtifact("web_page", "page/index.html", [](const fs::path& out) {
          fs::create_directories(out);
          const auto sim = Lfcam(fmt::format(
              "simulate lightfield --scene paper --grid 10x10 --st-res 312x288 --quiet --out {}",
              (out / "paper.lf").string()));
          if (sim.status != 0) throw Error(sim.output);
          const auto run = Lfcam(fmt::format("export {} --format web --out {}",
                                             (out / "paper.lf").string(), (out / "page").string()));
          if (run.status != 0) throw Error(run.output);
        }));
  }
  static void TearDownTestSuite() {
    if (dir_ != nullptr) fs::remove_all(*dir_);
    delete dir_;
    delete shared_;
    dir_ = shared_ = nullptr;
  }
  void SetUp() override {
    if (!has_browser_) {
      if (BrowserRequired()) FAIL() << "LFCAM_REQUIRE_BROWSER=1 but chromium is not installed";
      GTEST_SKIP() << "chromium is not installed (Debian's package chromium)";
    }
  }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  // The shared light field (paper.lf) and its page (page/).
  static std::string Shared(const std::string& name) { return (*shared_ / name).string(); }

  // bench/page_screenshot.js with `arguments`, its temporary folder one of the test's own: the
  // Chromium profile it makes there must be gone when it returns (on a loaded machine Chromium's
  // helper processes once outlived it and left a third of the profiles behind). The folder's
  // name is short: the script puts the profile in /tmp where TMPDIR is over 40 bytes long.
  static testing::CommandResult RunScript(const std::string& arguments) {
    const fs::path tmp = *dir_ / "t";
    fs::create_directories(tmp);
    const auto run =
        testing::RunOnce(fmt::format("TMPDIR={} node {}/bench/page_screenshot.js {} 2>&1",
                                     tmp.string(), LFCAM_SOURCE_DIR, arguments));
    EXPECT_TRUE(fs::is_empty(tmp))
        << "page_screenshot.js left " << fs::begin(fs::directory_iterator(tmp))->path();
    return run;
  }
  // Headless Chromium's screenshot of `page` (a folder) with the URL's `query`, at w x h, taken
  // once the page says its first picture is drawn (bench/page_screenshot.js: the DevTools
  // protocol over a pipe, waiting in real time, so a loaded machine only makes it slower).
  static cv::Mat Screenshot(const std::string& page, const std::string& query, int w, int h,
                            const std::string& name) {
    const std::string shot = Path(name + ".png");
    const auto run =
        RunScript(fmt::format("'file://{}/index.html?ui=0&size={}x{}&{}' --size {}x{} --png {}",
                              fs::absolute(page).string(), w, h, query, w, h, shot));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_TRUE(fs::is_regular_file(shot)) << run.output;
    return fs::is_regular_file(shot) ? ReadImageSrgb8(shot) : cv::Mat();
  }
  // `lfcam render` of the same view: the cameras integrator, eye at the array window's (u, v).
  static cv::Mat Render(const std::string& flags, int w, int h, const std::string& name) {
    const std::string png = Path(name + ".png");
    const auto run =
        Lfcam(fmt::format("render {} --integrator cameras --size {}x{} {} --out {} "
                          "--quiet",
                          Shared("paper.lf"), w, h, flags, png));
    EXPECT_EQ(run.status, 0) << run.output;
    return ReadImageSrgb8(png);
  }
  static double Psnr(const cv::Mat& a, const cv::Mat& b) {
    if (a.empty() || b.empty() || a.size() != b.size()) return 0;
    return CompareImages(a, b).psnr_db;
  }

  static inline bool has_browser_ = false;
  static inline fs::path* dir_ = nullptr;
  static inline fs::path* shared_ = nullptr;
};

TEST_F(WebPageBrowser, APinholeViewMatchesTheRenderer) {
  const cv::Mat page =
      Screenshot(Shared("page"), "f=500&focus=4000&aperture=0", 320, 240, "pinhole");
  const cv::Mat render =
      Render("--focal-length 500 --focus-distance 4000 --aperture 0", 320, 240, "pinhole_render");
  EXPECT_GT(Psnr(page, render), kTargetPsnrDb);
}

TEST_F(WebPageBrowser, ARefocusedViewOffCentreMatchesTheRenderer) {
  // The eye at the array window's (0.3, 0.6): world position from the array plane.
  const auto meta_text = ReadAll(Shared("page/lightfield.js"));
  const auto json = nlohmann::json::parse(
      meta_text.substr(meta_text.find('{'), meta_text.rfind('}') - meta_text.find('{') + 1));
  const auto& a = json["array"];
  const auto at = [&](int i) {
    return a["p_ca"][i].get<double>() +
           0.3 * a["width_mm"].get<double>() * a["u_ca"][i].get<double>() +
           0.6 * a["height_mm"].get<double>() * a["v_ca"][i].get<double>();
  };
  const std::string eye = fmt::format("{},{},{}", at(0), at(1), at(2));
  const std::string look = fmt::format("{},{},{}", at(0) - 1000 * a["n_ca"][0].get<double>(),
                                       at(1) - 1000 * a["n_ca"][1].get<double>(),
                                       at(2) - 1000 * a["n_ca"][2].get<double>());
  const std::string view = "eye=0.3,0.6&f=400&focus=3400&aperture=120";
  const cv::Mat page = Screenshot(Shared("page"), view, 320, 240, "refocus");
  const cv::Mat render = Render(fmt::format("--eye {} --look-at {} --focal-length 400 "
                                            "--focus-distance 3400 --aperture 120",
                                            eye, look),
                                320, 240, "refocus_render");
  EXPECT_GT(Psnr(page, render), kTargetPsnrDb);

  // The same page with its refocus put wrong (the point in focus 8% too far): the comparison
  // must see it.
  const std::string mutated = Path("mutated");
  fs::create_directories(mutated);
  for (const char* file : {"index.html", "lightfield.js"})
    fs::copy_file(Shared("page") / fs::path(file), fs::path(mutated) / file);
  std::string script = ReadAll(Shared("page/lfcam-web.js"));
  const std::string refocus = "vec3 po = u_eye + u_focus * dir;";
  ASSERT_NE(script.find(refocus), std::string::npos) << "the shader's refocus line moved";
  script.replace(script.find(refocus), refocus.size(), "vec3 po = u_eye + 1.08 * u_focus * dir;");
  std::ofstream(fs::path(mutated) / "lfcam-web.js") << script;
  const cv::Mat wrong = Screenshot(mutated, view, 320, 240, "mutated_shot");
  EXPECT_LT(Psnr(wrong, render), kTargetPsnrDb) << "a wrong refocus passed the comparison";
}

TEST_F(WebPageBrowser, ThePageSaysWhenItIsReadyAndWhatItWasNotGiven) {
  // The page's DOM once it is ready: its first picture timed, and a bad URL value named (the
  // script exits 1 for a page that reports an error).
  const std::string dom = Path("dom.html");
  const auto run = RunScript(fmt::format("'file://{}/index.html?f=abc' --size 320x240 --dom {}",
                                         fs::absolute(Shared("page")).string(), dom));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("the page says: URL parameters not understood: f"), std::string::npos)
      << run.output;
  const std::string html = ReadAll(dom);
  EXPECT_NE(html.find("data-ready=\"1\""), std::string::npos) << html.substr(0, 2000);
  EXPECT_NE(html.find("data-first-picture-ms="), std::string::npos);
}

}  // namespace
}  // namespace lfcam
