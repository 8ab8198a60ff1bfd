// The Pis' own lfcam-node: the agent cross-built for arm64 (Raspberry Pi OS bookworm is Debian 12
// arm64; scripts/package.sh builds it with Debian's cross toolchain), run here under user-mode
// emulation (qemu-user-static) as real nodes on loopback, and driven by this machine's
// `lfcam capture` through status, configure, shoot and fetch, each image checked byte for byte.
// LFCAM_ARM64_NODE names the arm64 binary; without it the test says it skipped, unless
// LFCAM_REQUIRE_ARM64=1 (scripts/package.sh), where a missing binary fails.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lfcam/capture/local_array_test_support.h"
#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/test_support.h"
#include "lfcam/node/request_signature.h"
#include "lfcam/session/session.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;
using testing::LocalArray;

std::string EnvOr(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value && *value ? value : fallback;
}

// The ELF header's machine field: 183 is AArch64 (the Pis), 62 x86-64.
int ElfMachine(const fs::path& binary) {
  std::ifstream in(binary, std::ios::binary);
  unsigned char header[20] = {};
  if (!in.read(reinterpret_cast<char*>(header), sizeof header)) return -1;
  if (header[0] != 0x7f || header[1] != 'E' || header[2] != 'L' || header[3] != 'F') return -1;
  return header[18] | (header[19] << 8);
}

TEST(EmulatedArm64Node, ThePisAgentAnswersStatusConfigureShootAndFetchUnderEmulation) {
  const std::string node = EnvOr("LFCAM_ARM64_NODE", "");
  const bool required = EnvOr("LFCAM_REQUIRE_ARM64", "0") == "1";
  if (node.empty()) {
    if (required) FAIL() << "LFCAM_REQUIRE_ARM64=1 but LFCAM_ARM64_NODE names no binary";
    GTEST_SKIP() << "LFCAM_ARM64_NODE is not set (scripts/package.sh cross-builds the Pis' "
                    "lfcam-node and runs this test)";
  }
  ASSERT_TRUE(fs::exists(node)) << node;
  ASSERT_EQ(ElfMachine(node), 183) << node << " is not an arm64 (AArch64) program";
  const std::string emulator = EnvOr("LFCAM_ARM64_EMULATOR", "/usr/bin/qemu-aarch64-static");
  ASSERT_TRUE(fs::exists(emulator)) << emulator << " (Debian's qemu-user-static)";

  const fs::path dir = testing::MakeScratchDir("lfcam_arm64_node");  // gone when the test passes
  // A small array (emulation is slow): 2 x 2 nodes, each replaying photographs of its own, so
  // that every image that comes home can be told apart and checked against its source.
  LocalArray array(dir / "nodes", 2, 2, {"--backend", "replay"});
  array.SetNodeCommand({emulator, node});
  std::vector<std::string> scene_sha(std::size_t(array.size())),
      intrinsics_sha(std::size_t(array.size()));
  cv::RNG rng(26);
  for (int i = 0; i < array.size(); ++i) {
    const fs::path replay = dir / fmt::format("replay-{}", i);
    fs::create_directories(replay);
    for (const char* kind : {"scene", "intrinsics"}) {
      cv::Mat photo(240, 320, CV_8UC3);
      rng.fill(photo, cv::RNG::UNIFORM, 0, 256);
      cv::imwrite((replay / fmt::format("{}.jpg", kind)).string(), photo);
    }
    scene_sha[std::size_t(i)] = Sha256OfFile(replay / "scene.jpg");
    intrinsics_sha[std::size_t(i)] = Sha256OfFile(replay / "intrinsics.jpg");
    array.Start(i, {"--replay", replay.string()});
  }
  const std::string array_file = array.WriteArrayFile(320, 240).string();
  const std::string session = (dir / "session").string();

  // status: every node answers, as the arm64 agent of this very version.
  auto run = Lfcam("capture status " + array_file + " --json");
  const auto status = nlohmann::json::parse(run.output, nullptr, false);
  ASSERT_FALSE(status.is_discarded()) << run.output;
  ASSERT_EQ(status["nodes"].size(), 4u) << run.output;
  for (const auto& n : status["nodes"]) {
    ASSERT_TRUE(n["reachable"].get<bool>()) << n.dump();
    EXPECT_EQ(n["status"]["system"]["machine"], "aarch64") << n.dump();
    EXPECT_EQ(n["status"]["lfcam_version"], LFCAM_VERSION) << n.dump();
    EXPECT_EQ(n["status"]["backend"], "replay");
  }

  // configure: the settings locked on every node.
  run = Lfcam("capture configure " + array_file);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("4 of 4 nodes ready"), std::string::npos) << run.output;

  // shoot, leaving the images on the nodes; then fetch them. Emulation answers slowly: the
  // trigger is set a generous second ahead.
  run = Lfcam("capture shoot " + array_file + " --session " + session +
              " --kind scene --margin 1 --no-fetch --quiet --json");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto shot = nlohmann::json::parse(run.output, nullptr, false);
  ASSERT_FALSE(shot.is_discarded()) << run.output;
  EXPECT_EQ(shot["fired"], 4) << run.output;
  EXPECT_EQ(shot["left_on_nodes"], 4) << run.output;
  run = Lfcam("capture fetch " + array_file + " --session " + session + " --quiet");
  ASSERT_EQ(run.status, 0) << run.output;
  // And a shot fetched as it is taken, as `capture shoot` does by default.
  run = Lfcam("capture shoot " + array_file + " --session " + session +
              " --kind intrinsics --margin 1 --quiet");
  ASSERT_EQ(run.status, 0) << run.output;

  // Every photograph came home whole: the node's own file, byte for byte, and the checksum the
  // node sent with it is the one the host recorded.
  const CaptureManifest m = ReadManifest(session);
  ASSERT_EQ(m.shots.size(), 2u);
  std::size_t checked = 0;
  for (const Shot& s : m.shots) {
    EXPECT_TRUE(s.pending.empty()) << s.name;
    const auto& expected = s.kind == ShotKind::kScene ? scene_sha : intrinsics_sha;
    ASSERT_EQ(s.images.size(), 4u) << s.name;
    for (const ShotImage& image : s.images) {
      const std::string sha = Sha256OfFile(fs::path(session) / image.file);
      EXPECT_EQ(sha, expected[std::size_t(array.index(image.row, image.col))]) << image.file;
      EXPECT_EQ(image.capture.value("sha256", ""), sha) << image.file;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8u);
}

}  // namespace
}  // namespace lfcam
