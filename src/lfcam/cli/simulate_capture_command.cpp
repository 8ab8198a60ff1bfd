// `lfcam simulate capture`: a raw capture session of a simulated Raspberry Pi camera array.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <optional>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/sim/capture_simulation.h"

namespace lfcam::cli {

void AddSimulateCaptureCommand(CLI::App& simulate) {
  auto* command = simulate.add_subcommand(
      "capture", "Write the raw capture session a simulated Pi camera array takes");
  struct Flags {
    std::string scene = "paper", out, grid = "10x10", sensor = "2592x1944", defects = "realistic",
                board = "chessboard", intrinsics_board;
    std::uint64_t seed = 1;
    int shots = 14, supersampling = 2;
    bool no_noise = false, quiet = false, world_board_turned = false;
    std::optional<double> lens_blur_um;
  };
  auto flags = std::make_shared<Flags>();
  command->add_option("--scene", flags->scene, "Built-in scene (paper)")->capture_default_str();
  command->add_option("--out", flags->out, "Session directory to write (new or empty)")->required();
  command->add_option("--grid", flags->grid, "Camera grid ROWSxCOLS (28 mm pitch)")
      ->capture_default_str();
  command
      ->add_option("--sensor", flags->sensor, "Each module's image size WxH (Pi v1.3: 2592x1944)")
      ->capture_default_str();
  command
      ->add_option("--defects", flags->defects,
                   "realistic (mounting, intrinsics, distortion, the lens's blur, vignetting, "
                   "exposure, white balance) or none")
      ->capture_default_str();
  command->add_option("--seed", flags->seed, "Seed of the defects, board poses and noise")
      ->capture_default_str();
  command
      ->add_option("--board", flags->board,
                   "Intrinsics board kind: chessboard or charuco (the world board is a "
                   "chessboard)")
      ->capture_default_str();
  command->add_option("--intrinsics-board", flags->intrinsics_board,
                      fmt::format("Intrinsics board: COLSxROWS@MM (inner corners, square mm) or "
                                  "charuco:SXxSY@SQUARE/MARKER[:DICT] [default: {} or {}]",
                                  kSimulatedChessboard, kSimulatedCharuco));
  command->add_option("--shots", flags->shots, "Intrinsics board poses")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  command
      ->add_option("--supersampling", flags->supersampling,
                   "Scene rays per pixel, per axis, each drawn within its stratum of the pixel's "
                   "footprint as the lens spreads it (1: the pixel's centre ray, no blur)")
      ->capture_default_str()
      ->check(CLI::Range(1, 8));
  command
      ->add_option("--lens-blur", flags->lens_blur_um,
                   fmt::format("Every lens's point spread, a Gaussian's sigma on the sensor in um "
                               "(0: perfect lenses) [default: with --defects realistic each "
                               "module's drawn within {}+-{}, with none 0]",
                               kPiLensBlurUm, kPiLensBlurSpreadUm))
      ->check(CLI::Range(0.0, kMaxLensBlurUm));
  command->add_flag("--no-noise", flags->no_noise, "An ideal sensor: no shot or read noise");
  command->add_flag("--world-board-turned", flags->world_board_turned,
                    "Hang the world board the other way up (turned 180 degrees in its plane: its "
                    "bottom-left square, seen from the array, white), as people do");
  command->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([flags] {
    CaptureSimulationOptions o;
    std::tie(o.rows, o.cols) = ParseSize("--grid", flags->grid, kMaxViewsPerSide);
    std::tie(o.sensor_width, o.sensor_height) = ParseSize("--sensor", flags->sensor, kMaxImageSide);
    if (o.sensor_width < 64 || o.sensor_height < 48)
      throw UsageError(fmt::format("--sensor: {} is too small (at least 64x48)", flags->sensor));
    if (flags->defects == "realistic")
      o.defects = ModuleDefects::kRealistic;
    else if (flags->defects == "none")
      o.defects = ModuleDefects::kNone;
    else
      throw UsageError(fmt::format("--defects: '{}' is not realistic or none", flags->defects));
    if (flags->board != "chessboard" && flags->board != "charuco")
      throw UsageError(fmt::format("--board: '{}' is not chessboard or charuco", flags->board));
    const bool charuco = flags->board == "charuco";
    const std::string spec = !flags->intrinsics_board.empty() ? flags->intrinsics_board
                             : charuco                        ? kSimulatedCharuco
                                                              : kSimulatedChessboard;
    o.intrinsics_board = FlagValue("--intrinsics-board", [&] { return ParseBoardSpec(spec); });
    if (o.intrinsics_board.charuco() != charuco)
      throw UsageError(fmt::format("--intrinsics-board {} is not a {} (--board {})", spec,
                                   flags->board, flags->board));
    o.seed = flags->seed;
    o.intrinsics_shots = flags->shots;
    o.scene_supersampling = flags->supersampling;
    o.noise = !flags->no_noise;
    o.lens_blur_um = flags->lens_blur_um;
    o.world_board_turned = flags->world_board_turned;
    const Scene scene = FlagValue("--scene", [&] { return MakeScene(flags->scene); });
    const std::filesystem::path out = flags->out;
    std::error_code ec;
    if (std::filesystem::exists(out, ec) &&
        (!std::filesystem::is_directory(out, ec) || !std::filesystem::is_empty(out, ec)))
      throw UsageError(fmt::format("--out {}: exists and is not an empty directory", out.string()));
    const auto parent = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(parent, ec))
      throw UsageError(
          fmt::format("--out {}: its directory {} does not exist", out.string(), parent.string()));
    const std::int64_t images = std::int64_t(o.rows) * o.cols * (o.intrinsics_shots + 2);
    ProgressBar progress("simulating captures", images, ProgressWanted(flags->quiet));
    if (const auto advance = progress.callback()) o.image_done = [advance] { advance(1); };
    const auto result = SimulateCapture(scene, o, out);
    progress.finish();
    fmt::print(
        "wrote {}: {} images from {}x{} modules of {}x{} ({} intrinsics shots, world, "
        "scene) in {:.1f} s\n",
        out.string(), result.images, o.rows, o.cols, o.sensor_width, o.sensor_height,
        o.intrinsics_shots, result.seconds);
  });
}

}  // namespace lfcam::cli
