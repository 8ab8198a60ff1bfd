// `lfcam build SESSION --calibration calibration.json --out FILE`: the light field of a
// calibrated capture session.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <cmath>
#include <memory>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/calib/lightfield_build.h"
#include "lfcam/calib/lightfield_video_build.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/session/session.h"

namespace lfcam::cli {

namespace {

void BuildVideo(const std::string& session, const CaptureManifest& manifest,
                const CalibrationFile& calibration, const Shot& shot, const std::string& out,
                VideoBuildOptions v, bool quiet, bool json) {
  const auto seconds = shot.video->seconds, fps = shot.video->fps;
  const auto planned = v.frame_count > 0
                           ? v.frame_count
                           : std::int64_t(std::ceil(seconds * fps - 1e-9)) - v.first_frame;
  ProgressBar progress("building frames", std::max<std::int64_t>(planned, 1),
                       ProgressWanted(quiet));
  if (const auto advance = progress.callback()) v.frame_done = [advance] { advance(1); };
  const VideoBuildReport r =
      BuildLightFieldVideo(session, manifest, calibration, shot.name, out, v);
  progress.finish();
  if (json) {
    fmt::print(
        "{}\n",
        JsonToText(
            {{"out", out},
             {"frames", r.frames},
             {"fps", fps},
             {"n_s", v.build.n_s},
             {"n_t", v.build.n_t},
             {"seconds", r.seconds},
             {"frames_per_second", double(r.frames) / r.seconds},
             {"bytes", r.bytes},
             {"bytes_per_frame", double(r.bytes) / double(r.frames)},
             {"filled_views", r.filled_views},
             {"spread_us",
              {{"median", r.spread.median_us}, {"p95", r.spread.p95_us}, {"max", r.spread.max_us}}},
             {"problems", r.problems}},
            2));
    return;
  }
  fmt::print(
      "built {} light field frames of {}x{} views of {}x{} samples in {:.1f} s ({:.2f} frames "
      "a second); {} camera frames filled from their neighbours\n",
      r.frames, calibration.rows, calibration.cols, v.build.n_s, v.build.n_t, r.seconds,
      double(r.frames) / r.seconds, r.filled_views);
  fmt::print("  sync spread over the recording: median {:.1f} us, max {:.1f} us\n",
             r.spread.median_us, r.spread.max_us);
  for (const auto& p : r.problems) fmt::print(stderr, "lfcam: warning: {}\n", p);
  fmt::print("wrote {} ({}, {} a frame)\n", out, HumanBytes(double(r.bytes)),
             HumanBytes(double(r.bytes) / double(r.frames)));
}

}  // namespace

void AddBuildCommand(CLI::App& app) {
  auto* command =
      app.add_subcommand("build", "Build the light field of a calibrated capture session");
  struct Flags {
    std::string session, calibration, out, st_res = "1248x1152", st_domain, compression = "none",
                                           shot = "scene", resampling = "linear", chroma = "guided",
                                           st_windows = "shared", frames;
    bool allow_missing = false, keep_dark_views = false, no_color = false, json = false,
         quiet = false;
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
  command
      ->add_option("--shot", flags->shot,
                   "The session's shot to build: scene, world, or a recording (rec_00: a light "
                   "field video, .lfv)")
      ->capture_default_str();
  command->add_option("--frames", flags->frames,
                      "A recording: its light field frames FIRST:COUNT (default: all)");
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
  command->add_flag("--keep-dark-views", flags->keep_dark_views,
                    "Keep views that recorded black, or nearly (darker than 1/16 of the median "
                    "view: a covered lens, a failed exposure), as they are; by default they are "
                    "filled from their neighbours, as missing cameras are (recorded)");
  command->add_flag("--no-color-correction", flags->no_color,
                    "Do not apply the calibration's per-module gain and vignetting correction");
  command->add_flag("--json", flags->json, "Print a summary as JSON on stdout");
  command->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([flags, command] {
    BuildOptions o;
    std::tie(o.n_s, o.n_t) = ParseSize("--st-res", flags->st_res, kMaxStSamplesPerSide);
    if (!flags->st_domain.empty()) o.st_domain = ParseStDomain("--st-domain", flags->st_domain);
    LightFieldWriteOptions w;
    w.compression = ParseCompression("--compress", flags->compression);
    o.allow_missing = flags->allow_missing;
    o.fill_dark_views = !flags->keep_dark_views;
    o.shot = flags->shot;
    o.resampling =
        FlagValue("--resampling", [&] { return ResamplingFromString(flags->resampling); });
    o.chroma = FlagValue("--chroma", [&] { return ChromaUpsamplingFromString(flags->chroma); });
    o.photometric_correction = !flags->no_color;
    o.view_windows = ParseStWindows("--st-windows", flags->st_windows);
    RequireWritableOutput(flags->out, "--out");
    const CaptureManifest manifest = ReadManifest(flags->session);
    const CalibrationFile calibration = ReadCalibration(flags->calibration);
    for (const Shot& s : manifest.shots)
      if (s.name == flags->shot && s.kind == ShotKind::kVideo) {
        VideoBuildOptions v;
        v.build = o;
        if (command->count("--st-res") == 0)
          std::tie(v.build.n_s, v.build.n_t) = DefaultVideoStSamples(s.video->width);
        if (command->count("--compress") == 0)
          v.write = {Compression::kZstd, 1};
        else
          v.write = w;
        if (!flags->frames.empty()) {
          long long a = 0, b = 0;
          char x = 0;
          if (std::sscanf(flags->frames.c_str(), "%lld:%lld%c", &a, &b, &x) != 2 || a < 0 || b < 1)
            throw UsageError(fmt::format(
                "--frames '{}': expected FIRST:COUNT, FIRST >= 0, COUNT >= 1", flags->frames));
          v.first_frame = a;
          v.frame_count = b;
        }
        return BuildVideo(flags->session, manifest, calibration, s, flags->out, v,
                          flags->quiet || flags->json, flags->json);
      }
    if (!flags->frames.empty()) throw UsageError("--frames: the shot is not a recording");
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
    if (!report.dark.empty()) {
      std::vector<std::string> dark;
      for (const auto& [row, col] : report.dark) dark.push_back(CameraLabel(row, col));
      fmt::print("  note: {}\n", DarkViewsNote(dark));
    }
    for (const auto& f : report.filled) fmt::print(stderr, "lfcam: warning: filled {}\n", f);
    fmt::print("wrote {}\n", flags->out);
  });
}

}  // namespace lfcam::cli
