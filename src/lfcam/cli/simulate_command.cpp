// `lfcam simulate lightfield`: the light field an ideal array would capture of a built-in scene.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/sim/simulate_lightfield.h"

namespace lfcam::cli {

void AddSimulateCommand(CLI::App& app) {
  auto* simulate = app.add_subcommand("simulate", "Play the camera array without hardware");
  simulate->require_subcommand(1);
  auto* command =
      simulate->add_subcommand("lightfield", "Write the light field an ideal array captures");
  struct Flags {
    std::string scene = "paper", out, grid = "10x10", st_res = "1248x1152", st_domain = "0,0,1,1",
                sample_type = "srgb8", compression = "none";
    int supersampling = 2;
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
  command->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([flags] {
    SimulateLightFieldOptions o;
    // Grid and st resolution: the limits the light field reader accepts.
    const auto [rows, cols] = ParseSize("--grid", flags->grid, kMaxViewsPerSide);
    o.rows = rows;
    o.cols = cols;
    std::tie(o.n_s, o.n_t) = ParseSize("--st-res", flags->st_res, kMaxStSamplesPerSide);
    const auto d = ParseNumbers("--st-domain", flags->st_domain, 4);
    if (!(d[2] > d[0]) || !(d[3] > d[1]))
      throw UsageError(
          fmt::format("--st-domain: '{}' needs S1 > S0 and T1 > T0", flags->st_domain));
    for (const double x : d)
      if (std::abs(x) > kMaxStDomainBound)
        throw UsageError(fmt::format("--st-domain: {} is outside -{}..{}", x, kMaxStDomainBound,
                                     kMaxStDomainBound));
    o.st_domain = {d[0], d[1], d[2], d[3]};
    o.supersampling = flags->supersampling;
    o.sample_type =
        FlagValue("--sample-type", [&] { return SampleTypeFromString(flags->sample_type); });
    LightFieldWriteOptions w;
    if (flags->compression == "zstd")
      w.compression = Compression::kZstd;
    else if (flags->compression != "none")
      throw UsageError(fmt::format("--compress: '{}' is not none or zstd", flags->compression));
    const Scene scene = FlagValue("--scene", [&] { return MakeScene(flags->scene); });
    RequireWritableOutput(flags->out, "--out");
    const double bytes =
        double(rows) * cols * o.n_s * o.n_t * 3 * double(BytesPerChannel(o.sample_type));
    FlagValue(fmt::format("--grid {} --st-res {}", flags->grid, flags->st_res),
              [&] { RequireMemory(bytes, "the light field"); });
    ProgressBar progress("simulating views", std::int64_t(rows) * cols,
                         ProgressWanted(flags->quiet));
    if (const auto advance = progress.callback()) o.progress = [advance](int, int) { advance(1); };
    const auto start = std::chrono::steady_clock::now();
    const LightField lf = SimulateLightField(scene, o);
    progress.finish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WriteLightField(lf, flags->out, w);
    fmt::print("wrote {}: {}x{} views of {}x{} samples ({}, {:.1f} MB) in {:.1f} s\n", flags->out,
               rows, cols, o.n_s, o.n_t, ToString(o.sample_type), lf.total_bytes() / 1e6, seconds);
  });
  AddSimulateCaptureCommand(*simulate);
}

}  // namespace lfcam::cli
