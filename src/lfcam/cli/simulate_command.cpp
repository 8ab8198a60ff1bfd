// `lfcam simulate lightfield`: the light field an ideal array would capture of a built-in scene.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
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
      ->capture_default_str();
  command->add_option("--sample-type", flags->sample_type, "srgb8 or linear_f16")
      ->capture_default_str();
  command->add_option("--compress", flags->compression, "none or zstd")->capture_default_str();
  command->add_flag("--quiet", flags->quiet, "No progress on stderr");
  command->callback([flags] {
    SimulateLightFieldOptions o;
    const auto [rows, cols] = ParseSize("--grid", flags->grid);
    o.rows = rows;
    o.cols = cols;
    std::tie(o.n_s, o.n_t) = ParseSize("--st-res", flags->st_res);
    const auto d = ParseNumbers("--st-domain", flags->st_domain, 4);
    if (!(d[2] > d[0]) || !(d[3] > d[1]))
      throw Error(fmt::format("--st-domain: '{}' needs S1 > S0 and T1 > T0", flags->st_domain));
    o.st_domain = {d[0], d[1], d[2], d[3]};
    o.supersampling = flags->supersampling;
    try {
      o.sample_type = SampleTypeFromString(flags->sample_type);
    } catch (const Error& e) {
      throw Error(fmt::format("--sample-type: {}", e.what()));
    }
    LightFieldWriteOptions w;
    if (flags->compression == "zstd")
      w.compression = Compression::kZstd;
    else if (flags->compression != "none")
      throw Error(fmt::format("--compress: '{}' is not none or zstd", flags->compression));
    if (!flags->quiet)
      o.progress = [](int done, int total) {
        if (done % std::max(1, total / 10) == 0 || done == total)
          fmt::print(stderr, "simulating views: {}/{}\n", done, total);
      };
    const Scene scene = MakeScene(flags->scene);
    const auto start = std::chrono::steady_clock::now();
    const LightField lf = SimulateLightField(scene, o);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WriteLightField(lf, flags->out, w);
    fmt::print("wrote {}: {}x{} views of {}x{} samples ({}, {:.1f} MB) in {:.1f} s\n", flags->out,
               rows, cols, o.n_s, o.n_t, ToString(o.sample_type), lf.total_bytes() / 1e6, seconds);
  });
}

}  // namespace lfcam::cli
