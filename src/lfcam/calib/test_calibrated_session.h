#pragma once
// Tests only: a small realistic capture (3x3 simulated modules of 648x486, seed 11) and its
// calibration, made once per build and shared by every test process (sim/test_capture.h), with a
// scratch folder per process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "lfcam/calib/array_calibration.h"
#include "lfcam/calib/calibration_file.h"
#include "lfcam/calib/lightfield_build.h"
#include "lfcam/calib/photometry.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/sim/test_capture.h"

namespace lfcam::testing {

class CalibratedSessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                         ("build_test_" + std::to_string(::getpid())));
    std::filesystem::remove_all(*scratch_);
    std::filesystem::create_directories(*scratch_);
    CaptureSimulationOptions o;
    o.rows = o.cols = 3;
    o.sensor_width = 648;
    o.sensor_height = 486;
    o.seed = 11;
    session_ = new std::filesystem::path(lfcam::testing::SharedTestCapture("build-3x3", o));
    // Calibrated once for every test process of the build (a minute under the sanitizers).
    const std::filesystem::path calibration = lfcam::testing::SharedTestArtifact(
        "build-3x3-calibration", "calibration.json", [](const std::filesystem::path& dir) {
          const CaptureManifest manifest = ReadManifest(session());
          const ArrayCalibration a = CalibrateArray(session(), manifest, {});
          nlohmann::json j = CalibrationToJson(a);
          AddPhotometryToCalibration(
              j, EstimatePhotometry(session(), manifest, CalibrationFromJson(j, "cal"),
                                    a.world_board));
          std::filesystem::create_directories(dir);
          const std::string text = JsonToText(j);
          WriteFileAtomically(dir / "calibration.json",
                              {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
        });
    calibration_ = new CalibrationFile(ReadCalibration(calibration / "calibration.json"));
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    std::filesystem::remove_all(*scratch_, ec);
    delete scratch_;
    delete calibration_;
    delete session_;
  }
  static std::filesystem::path session() { return *session_; }
  static BuildOptions Small() {
    BuildOptions o;
    o.n_s = 150;
    o.n_t = 138;
    return o;
  }
  static std::filesystem::path* scratch_;
  static std::filesystem::path* session_;  // shared between test processes: read only
  static CalibrationFile* calibration_;
};
inline std::filesystem::path* CalibratedSessionTest::session_ = nullptr;
inline std::filesystem::path* CalibratedSessionTest::scratch_ = nullptr;
inline CalibrationFile* CalibratedSessionTest::calibration_ = nullptr;

}  // namespace lfcam::testing
