// `lfcam simulate lightfield`: the light field an ideal array would capture of a built-in scene.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/cli/scene_flags.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/sim/depth_truth.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::cli {
namespace {

// cameras[].center of a ground_truth.json or calibration.json, row-major; every grid position.
std::vector<Vec3> ReadCameraCenters(const std::string& path, int rows, int cols) {
  const auto bytes = ReadFileBytes(path, kMaxJsonBytes, "--centers-from file");
  const auto j = ParseJsonBounded(std::string(bytes.begin(), bytes.end()), path);
  const auto& cameras = JsonField(j, "cameras", path);
  if (!cameras.is_array()) throw Error(fmt::format("{}: cameras must be an array", path));
  std::vector<Vec3> centers(std::size_t(rows) * std::size_t(cols), Vec3::Constant(NAN));
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const std::string where = fmt::format("{}: cameras[{}]", path, i);
    const int r = int(JsonInteger(cameras[i], "row", 0, kMaxViewsPerSide, where));
    const int c = int(JsonInteger(cameras[i], "col", 0, kMaxViewsPerSide, where));
    if (r >= rows || c >= cols)
      throw Error(
          fmt::format("{}: camera ({}, {}) is outside the {}x{} grid", where, r, c, rows, cols));
    if (cameras[i].contains("center"))
      centers[std::size_t(r * cols + c)] = JsonVec3(cameras[i], "center", where);
  }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (!centers[std::size_t(r * cols + c)].allFinite())
        throw Error(fmt::format("{}: no centre for camera ({}, {})", path, r, c));
  return centers;
}

}  // namespace

void AddSimulateCommand(CLI::App& app) {
  auto* simulate = app.add_subcommand("simulate", "Play the camera array without hardware");
  simulate->require_subcommand(1);
  auto* command =
      simulate->add_subcommand("lightfield", "Write the light field an ideal array captures");
  struct Flags {
    std::string scene = "paper", out, grid = "10x10", st_res = "1248x1152", st_domain = "0,0,1,1",
                sample_type = "srgb8", compression = "none", centers_from, depth_out;
    int supersampling = 2;
    std::optional<double> time_s;
    bool quiet = false;
  };
  auto flags = std::make_shared<Flags>();
  command->add_option("--scene", flags->scene, "Built-in scene (paper)")->capture_default_str();
  command->add_option("--out", flags->out, "Light field file to write (.lf)")->required();
  command->add_option("--grid", flags->grid, "Camera grid ROWSxCOLS (28 mm pitch)")
      ->capture_default_str();
  command->add_option("--st-res", flags->st_res, "st samples per view, N_SxN_T")
      ->capture_default_str();
  command
      ->add_option("--st-domain", flags->st_domain,
                   "Sampled st domain S0,T0,S1,T1 (view-window units)")
      ->capture_default_str();
  command->add_option("--supersampling", flags->supersampling, "Rays per st cell, per axis")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  command->add_option("--sample-type", flags->sample_type, "srgb8 or linear_f16")
      ->capture_default_str();
  command->add_option("--compress", flags->compression, "none or zstd")->capture_default_str();
  command->add_option("--centers-from", flags->centers_from,
                      "Put the cameras where this ground_truth.json or calibration.json says "
                      "(cameras[].row, col, center) instead of on the ideal grid");
  command->add_option("--depth-out", flags->depth_out,
                      "Also write the true depth of every view (the first surface along each st "
                      "sample's ray), as the folder `lfcam depth --all` writes and `lfcam render "
                      "--interpolation depth --depth DIR` reads");
  AddSceneTimeOption(*command, flags->time_s);
  command->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([flags] {
    const Scene scene = SceneAtTime(flags->scene, flags->time_s);
    SimulateLightFieldOptions o;
    // Grid and st resolution: the limits the light field reader accepts.
    const auto [rows, cols] = ParseSize("--grid", flags->grid, kMaxViewsPerSide);
    o.rows = rows;
    o.cols = cols;
    std::tie(o.n_s, o.n_t) = ParseSize("--st-res", flags->st_res, kMaxStSamplesPerSide);
    o.st_domain = ParseStDomain("--st-domain", flags->st_domain);
    o.supersampling = flags->supersampling;
    o.sample_type =
        FlagValue("--sample-type", [&] { return SampleTypeFromString(flags->sample_type); });
    LightFieldWriteOptions w;
    if (flags->compression == "zstd")
      w.compression = Compression::kZstd;
    else if (flags->compression != "none")
      throw UsageError(fmt::format("--compress: '{}' is not none or zstd", flags->compression));
    if (!flags->centers_from.empty())
      o.camera_centers = ReadCameraCenters(flags->centers_from, rows, cols);
    RequireWritableOutput(flags->out, "--out");
    if (!flags->depth_out.empty()) RequireNewOrEmptyFolder("--depth-out", flags->depth_out);
    const double bytes =
        double(rows) * cols * o.n_s * o.n_t * 3 * double(BytesPerChannel(o.sample_type));
    FlagValue(fmt::format("--grid {} --st-res {}", flags->grid, flags->st_res),
              [&] { RequireMemory(bytes, "the light field"); });
    ProgressBar progress("simulating views", std::int64_t(rows) * cols,
                         ProgressWanted(flags->quiet));
    if (const auto advance = progress.callback()) o.progress = [advance](int, int) { advance(1); };
    const auto start = std::chrono::steady_clock::now();
    LightField lf = SimulateLightField(scene, o);
    if (flags->time_s) lf.metadata()["time_s"] = *flags->time_s;
    progress.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!flags->depth_out.empty()) {
      DepthSet truth(lf.dims());
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) truth.set(GroundTruthDepth(scene, lf, r, c).map);
      WriteDepthSet(flags->depth_out, truth,
                    std::filesystem::path(flags->out).filename().string() + " (true depth)");
    }
    WriteLightField(lf, flags->out, w);
    fmt::print("wrote {}: {}x{} views of {}x{} samples ({}, {:.1f} MB) in {:.1f} s\n", flags->out,
               rows, cols, o.n_s, o.n_t, ToString(o.sample_type), lf.total_bytes() / 1e6, seconds);
  });
  AddSimulateCaptureCommand(*simulate);
}

}  // namespace lfcam::cli
