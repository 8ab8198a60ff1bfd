#include "lfcam/capture/array_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;
using testing::Lfcam;

TEST(ArrayFile, RoundTripsAndNamesWhatIsWrong) {
  ArrayConfig a;
  a.rows = 2;
  a.cols = 3;
  a.key_file = "k.key";
  a.nodes = NodesFromPattern(2, 3, "pi-{row02}-{col}.local:{index1}");
  a.nodes[4].group = 1;
  a.intrinsics_board = ParseBoardSpec("10x7@30");
  const ArrayConfig back = ArrayFromJson(ArrayToJson(a), "a");
  ASSERT_EQ(back.nodes.size(), 6u);
  EXPECT_EQ(back.nodes[4].address, "pi-01-1.local:5");
  EXPECT_EQ(back.nodes[4].group, 1);
  EXPECT_EQ(back.intrinsics_board->spec(), "10x7@30");
  EXPECT_EQ(back.node_at(1, 2)->address, "pi-01-2.local:6");
  EXPECT_EQ(KeyFilePath(back, "/etc/lfcam/array.json"), fs::path("/etc/lfcam/k.key"));

  auto refused = [&](const std::function<void(nlohmann::json&)>& change, const std::string& what) {
    nlohmann::json j = ArrayToJson(a);
    change(j);
    try {
      ArrayFromJson(j, "array.json");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused([](auto& j) { j["nodes"][1]["col"] = 0; }, "appears twice");
  refused([](auto& j) { j["nodes"][0]["row"] = 2; }, "nodes[0]");
  refused([](auto& j) { j["nodes"][0]["address"] = "no-port"; }, "HOST:PORT");
  refused([](auto& j) { j["nodes"][0]["address"] = "h:80x"; }, "HOST:PORT");
  refused([](auto& j) { j["settings"]["jpeg_quality"] = 0; }, "jpeg_quality");
  refused([](auto& j) { j["boards"]["world"] = "12x12@5"; }, "boards: world");
  refused([](auto& j) { j["format"] = "lfcam-capture"; }, "not an lfcam array file");
  EXPECT_THROW(NodesFromPattern(1, 1, "{host}:1"), UsageError);
  EXPECT_THROW(NodesFromPattern(1, 1, "{row:1"), UsageError);
}

TEST(ArrayFile, CaptureCommandsRefuseBadInputNamingIt) {
  const fs::path dir =
      fs::temp_directory_path() / ("lfcam_array_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string array = (dir / "array.json").string();
  auto run = Lfcam("capture keygen --out " + (dir / "array.key").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(fs::status(dir / "array.key").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  // Never over an existing key.
  run = Lfcam("capture keygen --out " + (dir / "array.key").string());
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("never overwritten"), std::string::npos) << run.output;
  run = Lfcam("capture init --out " + array + " --grid 2x2 --addresses 127.0.0.1:{index1}");
  ASSERT_EQ(run.status, 0) << run.output;
  // Nodes on ports 1..4 of loopback: nobody there. Status says so for each, and shoot fires
  // nothing, names every camera, and exits 1.
  run = Lfcam("capture status " + array);
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("0 of 4 nodes ready"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("connection refused"), std::string::npos) << run.output;
  run = Lfcam("capture shoot " + array + " --session " + (dir / "s").string() + " --quiet");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("camera (1, 1) missing"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("4 images are not in the session"), std::string::npos) << run.output;
  // Bad flags and files: usage errors (2) or errors (1), each naming what.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"capture status " + (dir / "missing.json").string(), "missing.json"},
      {"capture shoot " + array + " --session " + (dir / "s2").string() + " --kind portrait",
       "--kind 'portrait'"},
      {"capture init --out " + array + " --addresses 'x:{bad}'", "unknown placeholder {bad}"},
      {"capture status " + array + " --key-file " + array, "not a key"},
      {"capture fetch " + array + " --session " + (dir / "nothing").string(),
       "not a capture session"},
      {"capture identify " + array + " --camera 5,5", "no such node"},
      {"capture", "subcommand"},
  };
  for (const auto& [args, expected] : cases) {
    run = Lfcam(args);
    EXPECT_NE(run.status, 0) << args;
    EXPECT_NE(run.output.find(expected), std::string::npos) << args << "\n" << run.output;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
