// `lfcam build SESSION --calibration calibration.json --out FILE`: the light field of a
// calibrated capture session.
#include <fmt/core.h>

#include <cmath>
#include <memory>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/calib/lightfield_build.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"

namespace lfcam::cli {

void AddBuildCommand(CLI::App& app) {
  auto* command =
      app.add_subcommand("build", "Build the light field of a calibrated capture session");
  struct Flags {
    std::string session, calibration, out, st_res = "1248x1152", st_domain, compression = "none",
                                           shot = "scene", resampling = "linear", chroma = "guided",
                                           st_windows = "shared";
    bool allow_missing = false, no_color = false, json = false, quiet = false;
  };
  auto flags = std::make_shared<Flags>();
  command->add_option("session", flags->session, "Capture session directory")->required();
  command->add_option("--calibration", flags->calibration, "calibration.json of the session")
      ->required();
  command->add_option("--out", flags->out, "Light field file to write (.lf)")->required();
  command->add_option("--st-res", flags->st_res, "st samples per view, N_SxN_T")
      ->capture_default_str();
  command->add_option("--st-domain", flags->st_domain,
                      "Sampled st domain S0,T0,S1,T1 (view-window units; default 0,0,1,1)");
  command
      ->add_option("--st-windows", flags->st_windows,
                   "shared (every view samples the st domain: what the paper's array all sees) "
                   "or views (each view the st domain's grid moved to where its camera looks: "
                   "together they cover what every camera saw; format version 4)")
      ->capture_default_str();
  command->add_option("--compress", flags->compression, "none or zstd")->capture_default_str();
  command->add_option("--shot", flags->shot, "The session's shot to build (scene, or world)")
      ->capture_default_str();
  command
      ->add_option(
          "--resampling", flags->resampling,
          "Kernel between camera pixels: linear (closest to the truth sample by sample), cubic "
          "(sharper renders) or lanczos4")
      ->capture_default_str();
  command
      ->add_option("--chroma", flags->chroma,
                   "JPEG colour kept at half resolution (4:2:0, as the Pi camera writes it): "
                   "guided (restored along the full-resolution brightness) or interpolated (as "
                   "any decoder does)")
      ->capture_default_str();
  command->add_flag("--allow-missing", flags->allow_missing,
                    "Fill cameras without an image or calibration from their nearest neighbours "
                    "(recorded in the file's metadata)");
  command->add_flag("--no-color-correction", flags->no_color,
                    "Do not apply the calibration's per-module gain and vignetting correction");
  command->add_flag("--json", flags->json, "Print a summary as JSON on stdout");
  command->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([flags] {
    BuildOptions o;
    std::tie(o.n_s, o.n_t) = ParseSize("--st-res", flags->st_res, kMaxStSamplesPerSide);
    if (!flags->st_domain.empty()) o.st_domain = ParseStDomain("--st-domain", flags->st_domain);
    LightFieldWriteOptions w;
    w.compression = ParseCompression("--compress", flags->compression);
    o.allow_missing = flags->allow_missing;
    o.shot = flags->shot;
    o.resampling =
        FlagValue("--resampling", [&] { return ResamplingFromString(flags->resampling); });
    o.chroma = FlagValue("--chroma", [&] { return ChromaUpsamplingFromString(flags->chroma); });
    o.photometric_correction = !flags->no_color;
    o.view_windows = ParseStWindows("--st-windows", flags->st_windows);
    RequireWritableOutput(flags->out, "--out");
    const CaptureManifest manifest = ReadManifest(flags->session);
    const CalibrationFile calibration = ReadCalibration(flags->calibration);
    ProgressBar progress("building views", std::int64_t(calibration.rows) * calibration.cols,
                         ProgressWanted(flags->quiet || flags->json));
    if (const auto advance = progress.callback()) o.view_done = [advance] { advance(1); };
    BuildReport report;
    const LightField lf = BuildLightField(flags->session, manifest, calibration, o, &report);
    progress.finish();
    WriteLightField(lf, flags->out, w);
    if (flags->json) {
      fmt::print("{}\n", JsonToText({{"out", flags->out},
                                     {"rows", lf.dims().rows},
                                     {"cols", lf.dims().cols},
                                     {"n_s", lf.dims().n_s},
                                     {"n_t", lf.dims().n_t},
                                     {"seconds", report.seconds},
                                     {"decode_seconds", report.decode_seconds},
                                     {"metadata", lf.metadata()}},
                                    2));
      return;
    }
    fmt::print(
        "built {}x{} views of {}x{} samples in {:.2f} s (JPEG decoding {:.2f} s of thread "
        "time, at up to 1/{} size)\n",
        lf.dims().rows, lf.dims().cols, lf.dims().n_s, lf.dims().n_t, report.seconds,
        report.decode_seconds, report.reduction_max);
    fmt::print(
        "  mean colour over the common st region ({:.0f}% of it): cameras within "
        "{:.2f}% of the median (RMS {:.2f}%), {:.2f}% before correction\n",
        100 * report.after.region_fraction, 100 * report.after.max_deviation,
        100 * report.after.rms_deviation, 100 * report.before.max_deviation);
    for (const auto& f : report.filled) fmt::print(stderr, "lfcam: warning: filled {}\n", f);
    fmt::print("wrote {}\n", flags->out);
  });
}

}  // namespace lfcam::cli
