#include "lfcam/node/capture_store.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "lfcam/core/error.h"
#include "lfcam/node/capture_settings.h"
#include "lfcam/node/request_signature.h"
#include "lfcam/node/system_status.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

TEST(CaptureStore, IdsNameAFileInTheFolderAndNothingElse) {
  for (const std::string& good : {std::string("scene"), std::string("a1b2-shot_03"),
                                  std::string("x.y"), std::string(64, 'a')})
    EXPECT_TRUE(IsValidCaptureId(good)) << good;
  for (const std::string& bad : {std::string(), std::string(65, 'a'), std::string(".hidden"),
                                 std::string(".."), std::string("a/b"), std::string("../x"),
                                 std::string("a b"), std::string("a\\b"), std::string("a\0b", 3)})
    EXPECT_FALSE(IsValidCaptureId(bad)) << bad;
}

TEST(CaptureStore, KeepsImagesAndRecordsAcrossARestart) {
  const fs::path dir = fs::temp_directory_path() / ("lfcam_store_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  {
    CaptureStore store(dir);
    CaptureRecord r;
    r.id = "s1-scene";
    r.kind = r.shot = "scene";
    r.requested_unix_ns = 5;
    r.trigger_unix_ns = 6;
    r.settings = SettingsToJson(CaptureSettings{});
    const CaptureRecord saved = store.Save(r, "jpeg bytes");
    EXPECT_EQ(saved.size, 10u);
    EXPECT_EQ(saved.sha256, Sha256Hex("jpeg bytes"));
    EXPECT_GT(store.FreeBytes(), 0u);
  }
  CaptureStore again(dir);
  ASSERT_EQ(again.List().size(), 1u);
  const auto found = again.Find("s1-scene");
  ASSERT_TRUE(found);
  EXPECT_EQ(found->trigger_unix_ns, 6);
  EXPECT_EQ(Sha256OfFile(again.ImagePath("s1-scene")), found->sha256);
  EXPECT_FALSE(again.Find("../s1-scene"));
  EXPECT_THROW(again.ImagePath("../x"), Error);
  EXPECT_TRUE(again.Remove("s1-scene"));
  EXPECT_FALSE(again.Remove("s1-scene"));
  EXPECT_EQ(again.count(), 0u);
  fs::remove_all(dir);
}

TEST(CaptureSettings, RoundTripAndRangeChecks) {
  CaptureSettings s;
  s.exposure_us = 12000;
  s.awb_red = 1.9;
  EXPECT_EQ(SettingsFromJson(SettingsToJson(s), "s"), s);
  // Absent fields keep the base's values.
  EXPECT_EQ(SettingsFromJson({{"jpeg_quality", 80}}, "s", s).exposure_us, 12000);
  for (const nlohmann::json& bad :
       {nlohmann::json{{"width", 0}}, nlohmann::json{{"exposure_us", 1.5}},
        nlohmann::json{{"analogue_gain", 0.5}}, nlohmann::json{{"awb_gains", {1.0}}},
        nlohmann::json{{"denoise", "max"}}, nlohmann::json{{"jpeg_quality", 101}},
        nlohmann::json{{"colour", 1}}, nlohmann::json::array()})
    EXPECT_THROW(SettingsFromJson(bad, "s"), Error) << bad.dump();
  CaptureSettings other = s;
  other.denoise = "cdn_fast";
  other.width = 1296;
  const auto diffs = SettingsDifferences(other, s);
  ASSERT_EQ(diffs.size(), 2u);
  EXPECT_EQ(diffs[0], "width 1296 (array: 2592)");
  EXPECT_EQ(diffs[1], "denoise cdn_fast (array: off)");
}

TEST(SystemStatus, ReadsChronysTrackingLine) {
  const auto offset = ParseChronyTracking(
      "C0A80001,192.168.0.1,3,1700000000.123456789,-0.000123456,0.000010,0.000020,-1.2,0.01,0.05,"
      "0.001,0.002,64.0,Normal");
  ASSERT_TRUE(offset);
  EXPECT_NEAR(offset->offset_ms, -0.123456, 1e-9);
  EXPECT_EQ(offset->source, "chrony (server 192.168.0.1)");
  EXPECT_FALSE(ParseChronyTracking(""));
  EXPECT_FALSE(ParseChronyTracking("a,b,c"));
  EXPECT_FALSE(ParseChronyTracking("0,,0,0,0.0,0"));    // stratum 0: not synchronised
  EXPECT_FALSE(ParseChronyTracking("0,x,3,0,0.0x,0"));  // not a number
  const SystemStatus s = ReadSystemStatus(fs::temp_directory_path());
  EXPECT_GT(s.disk_free_bytes, 0u);
  EXPECT_TRUE(s.memory_available_bytes);
}

}  // namespace
}  // namespace lfcam
