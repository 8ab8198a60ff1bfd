// `lfcam calibrate DIR`: a capture session's array calibration (calibration.json), and
// `lfcam calibrate intrinsics IMAGES...`: one module's intrinsics.
#include <fmt/core.h>

#include <algorithm>
#include <memory>

#include "lfcam/calib/array_calibration.h"
#include "lfcam/calib/board_detection.h"
#include "lfcam/calib/calibration_file.h"
#include "lfcam/calib/calibration_report.h"
#include "lfcam/calib/intrinsics_calibration.h"
#include "lfcam/calib/photometry.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/progress.h"

namespace lfcam::cli {
namespace {

void WriteJsonFile(const std::string& path, const nlohmann::json& j) {
  const std::string text = JsonToText(j, 2) + "\n";
  WriteFileAtomically(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

std::optional<BoardSpec> OptionalBoard(const std::string& flag, const std::string& text) {
  if (text.empty()) return std::nullopt;
  return FlagValue(flag, [&] { return ParseBoardSpec(text); });
}

void PrintSummary(const ArrayCalibration& a, const std::string& out) {
  const auto& ba = a.bundle_adjustment;
  fmt::print("calibrated {} of {} cameras in {:.1f} s (board search {:.1f} s)\n",
             a.calibrated_count(), a.cameras.size(), a.seconds, a.detection_seconds);
  fmt::print("  bundle adjustment  {} corners, RMS {:.3f} px -> {:.3f} px in {} iterations{}\n",
             ba.residual_blocks, ba.initial_rms_px, ba.final_rms_px, ba.iterations,
             ba.converged ? "" : " (not converged)");
  fmt::print(
      "  array plane        centres within {:.3f} mm RMS; grid fit {:.3f} mm RMS, "
      "theta {:.4f} deg\n",
      a.fit.plane_rms_mm, a.fit.grid_rms_mm, a.fit.theta_newton * 180 / M_PI);
  const Vec3 c = a.fit.array.center();
  fmt::print("  array centre       ({:.1f}, {:.1f}, {:.1f}) mm, n_ca ({:.4f}, {:.4f}, {:.4f})\n",
             c.x(), c.y(), c.z(), a.fit.array.n_ca.x(), a.fit.array.n_ca.y(), a.fit.array.n_ca.z());
  if (a.world_board_turned)
    fmt::print(
        "  world board        hung the other way up (its bottom-left square, seen from the "
        "array, is white): its corners were numbered from the other end, so the world's origin "
        "is still its bottom-left corner as seen from the array\n");
  for (const auto& cam : a.cameras) {
    if (!cam.calibrated)
      fmt::print(stderr, "lfcam: warning: {} not calibrated: {}\n", CameraLabel(cam.row, cam.col),
                 cam.reason);
    for (const auto& w : cam.warnings)
      fmt::print(stderr, "lfcam: warning: {}: {}\n", CameraLabel(cam.row, cam.col), w);
  }
  fmt::print("wrote {}\n", out);
}

void AddIntrinsicsSubcommand(CLI::App& calibrate) {
  auto* command = calibrate.add_subcommand(
      "intrinsics", "Calibrate one camera module from its photographs of a board");
  struct Flags {
    std::vector<std::string> images;
    std::string board, out;
    bool json = false;
  };
  auto flags = std::make_shared<Flags>();
  command->add_option("images", flags->images, "Photographs of the board (PNG or JPEG)")
      ->required();
  command
      ->add_option("--board", flags->board,
                   "Chessboard COLSxROWS@MM (inner corners) or charuco:SXxSY@SQUARE/MARKER")
      ->required();
  command->add_option("--out", flags->out, "Camera file to write (.json)")->required();
  command->add_flag("--json", flags->json, "Print the result as JSON on stdout");
  command->callback([flags] {
    const BoardSpec board = FlagValue("--board", [&] { return ParseBoardSpec(flags->board); });
    RequireWritableOutput(flags->out, "--out");
    std::vector<std::vector<cv::Point2f>> views;
    std::vector<std::string> used, not_found;
    // Every image's size from its header before any is searched (mixed sizes are refused first).
    int width = 0, height = 0;
    const auto same_size = [&](const std::string& path, int image_width, int image_height) {
      if (width == 0) {
        width = image_width;
        height = image_height;
      } else if (image_width != width || image_height != height) {
        throw Error(fmt::format("{}: the image is {}x{}, the first was {}x{} (mixed sizes)", path,
                                image_width, image_height, width, height));
      }
    };
    for (const auto& path : flags->images) {
      const ImageHeader header = ProbeImageFile(path);
      same_size(path, header.width, header.height);
    }
    for (const auto& path : flags->images) {
      const cv::Mat gray = ReadImageGray8(path);
      same_size(path, gray.cols, gray.rows);
      BoardDetectionOptions thorough;
      thorough.thorough = true;
      if (auto corners = DetectBoard(gray, board, thorough)) {
        views.push_back(std::move(*corners));
        used.push_back(path);
      } else {
        not_found.push_back(path);
      }
    }
    if (views.size() < 3)
      throw Error(fmt::format("the board {} was found in {} of {} images; at least 3 are needed",
                              board.spec(), views.size(), flags->images.size()));
    const SingleCameraCalibration c = CalibrateSingleCamera(views, board, width, height);
    nlohmann::json j = {
        {"format", "lfcam-camera"},        {"version", 1},
        {"board", BoardToJson(board)},     {"intrinsics", IntrinsicsToJson(c.intrinsics)},
        {"reprojection_rms_px", c.rms_px}, {"images_used", used},
        {"board_not_found", not_found}};
    WriteJsonFile(flags->out, j);
    if (flags->json) {
      fmt::print("{}\n", JsonToText(j, 2));
      return;
    }
    fmt::print(
        "fx {:.2f} fy {:.2f} cx {:.2f} cy {:.2f} px, RMS {:.3f} px over {} images ({} "
        "without the board)\nwrote {}\n",
        c.intrinsics.fx, c.intrinsics.fy, c.intrinsics.cx, c.intrinsics.cy, c.rms_px, used.size(),
        not_found.size(), flags->out);
  });
}

}  // namespace

void AddCalibrateCommand(CLI::App& app) {
  auto* calibrate = app.add_subcommand(
      "calibrate", "Calibrate a camera array from a capture session (or one module: intrinsics)");
  struct Flags {
    std::string session, out, report, intrinsics_board, world_board;
    bool json = false, quiet = false;
  };
  auto flags = std::make_shared<Flags>();
  calibrate->add_option("session", flags->session, "Capture session directory");
  calibrate->add_option("--out", flags->out, "Calibration file to write (.json)");
  calibrate->add_option("--report", flags->report,
                        "Picture of the calibration to write (default: --out with .png)");
  calibrate->add_option("--intrinsics-board", flags->intrinsics_board,
                        "Intrinsics chessboard COLSxROWS@MM (default: the manifest's)");
  calibrate->add_option("--world-board", flags->world_board,
                        "World chessboard COLSxROWS@MM (default: the manifest's)");
  calibrate->add_flag("--json", flags->json, "Print the calibration as JSON on stdout");
  calibrate->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  calibrate->require_subcommand(0, 1);
  AddIntrinsicsSubcommand(*calibrate);
  calibrate->callback([calibrate, flags] {
    if (calibrate->get_subcommands().size() > 0) return;  // `calibrate intrinsics` ran
    if (flags->session.empty()) throw UsageError("calibrate: give the capture session directory");
    if (flags->out.empty()) throw UsageError("calibrate: --out is required");
    CalibrationOptions o;
    o.intrinsics_board = OptionalBoard("--intrinsics-board", flags->intrinsics_board);
    o.world_board = OptionalBoard("--world-board", flags->world_board);
    RequireWritableOutput(flags->out, "--out");
    std::filesystem::path report = flags->report;
    if (report.empty()) report = std::filesystem::path(flags->out).replace_extension(".png");
    if (report == std::filesystem::path(flags->out))
      throw UsageError("--report: it must not be the --out file");
    RequireImageOutput(report, "--report");
    const CaptureManifest manifest = ReadManifest(flags->session);
    std::int64_t images = 0;
    for (const Shot& s : manifest.shots)
      if (s.kind == ShotKind::kIntrinsics || s.kind == ShotKind::kWorld)
        images += std::int64_t(s.images.size()) * (s.kind == ShotKind::kWorld ? 2 : 1);
    ProgressBar progress("finding boards", images, ProgressWanted(flags->quiet || flags->json));
    if (const auto advance = progress.callback()) o.image_done = [advance] { advance(1); };
    const ArrayCalibration a = CalibrateArray(flags->session, manifest, o);
    nlohmann::json j = CalibrationToJson(a);
    // The modules' photometric response, from the world shot, on the calibrated geometry.
    const PhotometryEstimate photometry = EstimatePhotometry(
        flags->session, manifest, CalibrationFromJson(j, flags->out), a.world_board, o.image_done);
    AddPhotometryToCalibration(j, photometry);
    progress.finish();
    WriteJsonFile(flags->out, j);
    WriteImage(report, DrawCalibrationReport(a));
    if (flags->json)
      fmt::print("{}\n", JsonToText(j, 2));
    else
      PrintSummary(a, flags->out + " and " + report.string());
  });
}

}  // namespace lfcam::cli
