#include "lfcam/share/web_export.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lfcam/core/test_support.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

LightField SmallLightField() {
  SimulateLightFieldOptions o;
  o.rows = o.cols = 4;
  o.n_s = 96;
  o.n_t = 88;
  o.supersampling = 1;
  return SimulateLightField(MakePaperScene(), o);
}

// lightfield.js's object (after "window.LFCAM_LIGHTFIELD = ").
nlohmann::json PageData(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  const auto start = s.find("window.LFCAM_LIGHTFIELD = ");
  EXPECT_NE(start, std::string::npos);
  const std::string json = s.substr(start + 26);
  return nlohmann::json::parse(json.substr(0, json.rfind(';')));
}

std::uint64_t FolderBytes(const fs::path& dir) {
  std::uint64_t bytes = 0;
  for (const auto& entry : fs::directory_iterator(dir)) bytes += entry.file_size();
  return bytes;
}

TEST(WebExport, WritesThePageItsScriptAndTheLightFieldWithItsOwnSize) {
  const fs::path dir = testing::MakeScratchDir("web_export");
  const LightField lf = SmallLightField();
  WebExportOptions options;
  options.name = "small";
  options.camera.focus_distance_mm = 4300;
  options.camera.aperture_mm = 40;
  const WebExportReport report = ExportWeb(lf, options, dir / "page");
  for (const char* file : {"index.html", "lfcam-web.js", "lightfield.js"})
    EXPECT_TRUE(fs::is_regular_file(dir / "page" / file)) << file;
  EXPECT_EQ(report.scale, 1);
  EXPECT_EQ(report.jpeg_quality, 90);
  EXPECT_EQ(report.download_bytes, FolderBytes(dir / "page")) << "the page states its own size";
  const nlohmann::json meta = PageData(dir / "page" / "lightfield.js");
  EXPECT_EQ(meta["download_bytes"].get<std::uint64_t>(), report.download_bytes);
  EXPECT_EQ(meta["views"].size(), 16u);
  EXPECT_EQ(meta["view_size"], nlohmann::json({96, 88}));
  EXPECT_EQ(meta["camera"]["focus_distance_mm"], 4300.0);
  EXPECT_EQ(meta["camera"]["aperture_mm"], 40.0);
  EXPECT_EQ(meta["grid"]["rows"], 4);
  EXPECT_EQ(meta["centers"].size(), 16u);
  EXPECT_TRUE(meta["offsets"].is_null()) << "shared st windows";
  EXPECT_EQ(meta["length_unit"], "mm");  // the page's labels: mm and m
  EXPECT_EQ(meta["views"][0].get<std::string>().rfind("data:image/jpeg;base64,/9j/", 0), 0u)
      << "a JPEG (FF D8 FF) in a data URL";
}

// A light field imported without a metric scale: the page labels its lengths in its units.
TEST(WebExport, SaysWhatItsLengthsAreWithoutAMetricScale) {
  const fs::path dir = testing::MakeScratchDir("web_export_units");
  LightField lf = SmallLightField();
  lf.metadata()["import"]["length_unit"] = "units";
  ExportWeb(lf, {}, dir / "page");
  EXPECT_EQ(PageData(dir / "page" / "lightfield.js")["length_unit"], "units");
  std::ifstream in(dir / "page" / "index.html");
  const std::string page((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(page.find("meta.length_unit"), std::string::npos);
}

TEST(WebExport, ABudgetCostsQualityFirstThenResolutionAndTooSmallAOneIsRefused) {
  const fs::path dir = testing::MakeScratchDir("web_export");
  const LightField lf = SmallLightField();
  WebExportOptions options;
  const std::uint64_t full = ExportWeb(lf, options, dir / "full").download_bytes;
  // Just under the full page: the quality goes down first.
  options.max_download_bytes = full - 1;
  const WebExportReport lower = ExportWeb(lf, options, dir / "lower");
  EXPECT_EQ(lower.scale, 1);
  EXPECT_LT(lower.jpeg_quality, 90);
  EXPECT_LE(lower.download_bytes, options.max_download_bytes);
  // Far under it: fewer samples too, and the page says so.
  options.max_download_bytes = full / 3;
  const WebExportReport smaller = ExportWeb(lf, options, dir / "smaller");
  EXPECT_GT(smaller.scale, 1);
  EXPECT_LE(smaller.download_bytes, options.max_download_bytes);
  EXPECT_NE(smaller.note.find("of the st samples"), std::string::npos) << smaller.note;
  EXPECT_EQ(PageData(dir / "smaller" / "lightfield.js")["note"], smaller.note);
  // A texture budget under the views' size halves them too.
  options = {};
  options.max_texture_bytes = 4ull * 96 * 88 * 16 - 1;
  EXPECT_EQ(ExportWeb(lf, options, dir / "texture").scale, 2);
  // Nothing fits: refused, naming the budget, and nothing written.
  options = {};
  options.max_download_bytes = 1000;
  EXPECT_NE(
      testing::ErrorOf([&] { ExportWeb(lf, options, dir / "none"); }).find("page of 0.001 MB"),
      std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "none"));
  // A folder that is not empty is refused.
  EXPECT_NE(testing::ErrorOf([&] { ExportWeb(lf, {}, dir / "full"); }).find("not an empty folder"),
            std::string::npos);
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".partial-"), std::string::npos);
}

}  // namespace
}  // namespace lfcam
