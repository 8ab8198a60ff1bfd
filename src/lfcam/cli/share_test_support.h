#pragma once
// Tests only: the small light fields the sharing commands' tests work on (render --video,
// export --format quilt|web): a 4x4 light field of the moving `paper` scene at three instants
// 0.5 s apart, as a still (still.lf, the first instant) and as a light field video at 2 fps
// (moving.lfv).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/sim/scene.h"
#include "lfcam/sim/simulate_lightfield.h"
#include "lfcam/sim/test_capture.h"

namespace lfcam::testing {

inline void WriteSharingLightFields(const std::filesystem::path& dir) {
  SimulateLightFieldOptions o;
  o.rows = o.cols = 4;
  o.n_s = 96;
  o.n_t = 88;
  o.supersampling = 1;
  const Scene scene = MakePaperScene();
  LightFieldVideoHeader header;
  header.fps = 2;
  header.frames_planned = 3;
  LightFieldVideoWriter writer(dir / "moving.lfv", header);
  for (int k = 0; k < 3; ++k) {
    const LightField lf = SimulateLightField(scene.AtTime(0.5 * k), o);
    if (k == 0) WriteLightField(lf, dir / "still.lf");
    VideoFrameInfo info;
    info.index = k;
    info.time_ns = std::int64_t(k) * 500'000'000;
    writer.Append(lf, info);
  }
  writer.Finish();
}

// The same two files, made once per build and shared by every test process
// (sim/test_capture.h): the folder that holds them.
inline std::filesystem::path SharedSharingLightFields() {
  return SharedTestArtifact("sharing_lightfields", "ready", [](const std::filesystem::path& out) {
    std::filesystem::create_directories(out);
    WriteSharingLightFields(out);
    std::ofstream(out / "ready") << "ok\n";
  });
}

// A suite of the sharing commands' tests: a folder of its own for outputs (one per process: ctest
// runs each suite in its own) and the shared inputs.
class SharingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                     ("lfcam_sharing_test_" + std::to_string(::getpid())));
    std::filesystem::remove_all(*dir_);
    std::filesystem::create_directories(*dir_);
    inputs_ = new std::filesystem::path(SharedSharingLightFields());
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
    delete inputs_;
    dir_ = inputs_ = nullptr;
  }
  // An output of the test.
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  // The shared inputs: still.lf and moving.lfv.
  static std::string Input(const std::string& name) { return (*inputs_ / name).string(); }
  static inline std::filesystem::path* dir_ = nullptr;
  static inline std::filesystem::path* inputs_ = nullptr;
};

}  // namespace lfcam::testing
