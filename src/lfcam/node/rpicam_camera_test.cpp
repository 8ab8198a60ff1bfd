// The rpicam backend against a stand-in for rpicam-still: a script that, like rpicam-still in
// signal mode, keeps running and writes one JPEG per SIGUSR1 to its --output pattern.
#include "lfcam/node/rpicam_camera.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

TEST(RpicamCamera, ExpandsTheCommandTemplate) {
  CaptureSettings s;
  s.exposure_us = 10000;
  s.analogue_gain = 2.5;
  const auto args = ExpandCameraCommand(kDefaultRpicamCommand, "rpicam-still", s, "/w/f%05d.jpg");
  const std::string line = fmt::format("{}", fmt::join(args, " "));
  EXPECT_EQ(line,
            "rpicam-still --nopreview --timeout 0 --signal --width 2592 --height 1944 --shutter "
            "10000 --gain 2.5 --awbgains 1.6,1.5 --denoise off --quality 95 --output "
            "/w/f%05d.jpg");
  EXPECT_THROW(ExpandCameraCommand("{program} --iso {iso}", "p", s, "o"), Error);
  EXPECT_THROW(ExpandCameraCommand("   ", "p", s, "o"), Error);
}

TEST(RpicamCamera, TakesAStillPerSignalFromARunningCamera) {
  const fs::path dir = fs::temp_directory_path() / ("lfcam_rpicam_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The stand-in: counts SIGUSR1s and writes "frame N" to the pattern's Nth name.
  const fs::path fake = dir / "fake-rpicam-still";
  std::ofstream(fake) << R"(#!/bin/bash
out=""
while [ $# -gt 0 ]; do [ "$1" = --output ] && out=$2; shift; done
n=0
trap 'f=$(printf "$out" $n); echo "frame $n" > "$f.tmp"; mv "$f.tmp" "$f"; n=$((n+1))' USR1
trap 'exit 0' USR2 TERM
while true; do sleep 0.01; done
)";
  fs::permissions(fake, fs::perms::owner_all);
  RpicamOptions o;
  o.program = fake.string();
  o.work_folder = dir / "work";
  o.warmup_ms = 200;
  auto camera = MakeRpicamCamera(o);
  EXPECT_THROW(camera->Prepare({"a", "scene", "scene"}), Error);  // not configured
  camera->Configure(CaptureSettings{});
  for (int k = 0; k < 3; ++k) {
    camera->Prepare({"a", "scene", "scene"});
    camera->Fire();
    EXPECT_EQ(camera->Collect(std::chrono::seconds(5)), fmt::format("frame {}\n", k));
  }
  EXPECT_TRUE(camera->Probe().present);
  // No signal, no frame: a clear timeout.
  camera->Prepare({"b", "scene", "scene"});
  try {
    camera->Collect(std::chrono::milliseconds(200));
    ADD_FAILURE() << "collected a frame that was never taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no frame"), std::string::npos) << e.what();
  }
  camera.reset();  // stops the camera process
  fs::remove_all(dir);
}

TEST(RpicamCamera, SaysWhenThereIsNoCameraProgram) {
  RpicamOptions o;
  o.program = "";
  o.work_folder = fs::temp_directory_path() / ("lfcam_rpicam_none_" + std::to_string(::getpid()));
  const char* path = std::getenv("PATH");
  const std::string saved = path ? path : "";
  ::setenv("PATH", "/nonexistent", 1);
  auto camera = MakeRpicamCamera(o);
  ::setenv("PATH", saved.c_str(), 1);
  const CameraProbe probe = camera->Probe();
  EXPECT_FALSE(probe.present);
  EXPECT_NE(probe.detail.find("rpicam-still"), std::string::npos);
  fs::remove_all(o.work_folder);
}

}  // namespace
}  // namespace lfcam
