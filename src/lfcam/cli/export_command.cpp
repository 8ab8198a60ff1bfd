// `lfcam export FILE --format png-views|nerf|colmap|quilt --out DIR [--depth DIR]`: a light
// field's views and cameras for other tools (docs/format.md, "Exporting"); 3D points from depth
// maps (`lfcam depth --all`) for COLMAP and nerfstudio; a Looking Glass quilt of a still or a
// video (docs/sharing.md).
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/camera_flags.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/core/progress.h"
#include "lfcam/io/lightfield_export.h"
#include "lfcam/session/session.h"
#include "lfcam/share/quilt_export.h"
#include "lfcam/share/web_export.h"

namespace lfcam::cli {
namespace {

struct ExportFlags {
  int frame = 0, frames = 0;
  std::string input, format, out, depth, preset = "portrait", integrator = "lens-samples";
  double baseline_mm = -1, max_download_mb = 30;
  CameraFlags camera;
  BackendFlags backend;
  bool quiet = false;
};

// The flags that only a rendered export (quilt) takes.
const std::vector<std::string> kRenderedExportFlags = {
    "--camera",         "--eye",      "--look-at",   "--up",          "--focal-length",
    "--focus-distance", "--aperture", "--lens-rate", "--no-breathing"};

void ExportQuiltCommand(const ExportFlags& f, const CLI::App& command) {
  if (f.camera.given("--size"))
    throw UsageError("--size: a quilt's size is its display's (--preset)");
  if (!f.depth.empty()) throw UsageError("--depth: not with --format quilt");
  const QuiltPreset& preset = QuiltPresetNamed(f.preset);
  FrameRenderOptions options;
  options.integrator =
      FlagValue("--integrator", [&] { return IntegratorFromString(f.integrator); });
  const Backend backend = f.backend.Validate(options);
  f.camera.Validate();
  RequireNewOrEmptyFolder("--out", f.out);

  const LightFieldVideo source(f.input);
  if (std::size_t(f.frame) >= source.frame_count())
    throw UsageError(fmt::format("--frame {}: {} has {} frame{}", f.frame, f.input,
                                 source.frame_count(), source.frame_count() == 1 ? "" : "s"));
  const int available = int(source.frame_count()) - f.frame;
  // A video's frames make an MP4 of quilts: all of them by default; --frame N alone, one quilt.
  const bool video =
      source.is_video() &&
      (f.frames > 1 || (f.frames == 0 && available > 1 && command.count("--frame") == 0));
  const int frames = video ? (f.frames > 0 ? f.frames : available) : 1;
  if (frames > available)
    throw UsageError(fmt::format("--frames {}: {} has {} frames from --frame {}", frames, f.input,
                                 available, f.frame));
  std::array<LightField, 2> slots;
  slots[0] = source.ReadFrame(std::size_t(f.frame));
  QuiltExportJob job;
  job.preset = preset;
  job.centre = f.camera.MakeCamera(slots[0]).params();
  job.baseline_mm = f.baseline_mm >= 0 ? f.baseline_mm : ArrayBaselineMm(slots[0]);
  const std::string unit = WorldLengthUnit(slots[0].metadata());  // mm, or the import's units
  job.render = options;
  job.stem = std::filesystem::path(f.input).stem().string();
  job.video = video;
  job.frames = frames;
  job.fps = source.header().fps;
  job.light_field = [&](int k) -> const LightField& {
    if (k == 0) return slots[0];
    slots[std::size_t(k % 2)] = source.ReadFrame(std::size_t(f.frame + k));
    return slots[std::size_t(k % 2)];
  };
  const QuiltLayout layout = LayoutQuilt(preset, video);
  ProgressBar progress("rendering the quilt", std::int64_t(frames) * layout.views(),
                       ProgressWanted(f.quiet));
  job.progress = progress.callback();
  const std::unique_ptr<FrameRenderer> renderer = BackendFlags::Open(backend);
  const QuiltExportReport report = ExportQuilt(job, *renderer, f.out);
  progress.finish();
  fmt::print(
      "wrote {}: {}, {} views ({}x{} tiles of {}x{}), {}; baseline {:.1f} {}, zero parallax at "
      "{:g} {}; the views' cameras in {}/cameras\n",
      report.file.string(), preset.display, layout.views(), layout.cols, layout.rows,
      layout.tile_width, layout.tile_height,
      video ? fmt::format("{} frames at {:g} fps", report.frames, job.fps) : "a still",
      job.baseline_mm, unit, job.centre.focus_distance_mm, unit, f.out);
}

void ExportWebCommand(const ExportFlags& f, const CLI::App& command) {
  for (const char* flag : {"--camera", "--eye", "--look-at", "--up", "--as-camera"})
    if (f.camera.given(flag))
      throw UsageError(fmt::format(
          "{}: the page's eye starts at the array's centre, on its plane (drag moves it)", flag));
  for (const char* flag : {"--preset", "--baseline", "--frames", "--integrator"})
    if (command.count(flag) > 0) throw UsageError(std::string(flag) + ": not with --format web");
  if (!f.depth.empty()) throw UsageError("--depth: not with --format web");
  f.camera.Validate();
  RequireNewOrEmptyFolder("--out", f.out);
  const LightField lf = ReadLightFieldFrame(f.input, std::size_t(f.frame));
  WebExportOptions options;
  options.name = std::filesystem::path(f.input).filename().string();
  options.camera = f.camera.MakeCamera(lf).params();
  if (f.camera.StartsAtRigCentre(lf)) fmt::print(stderr, "{}\n", CameraFlags::RigCentreNote(lf));
  options.max_download_bytes = std::uint64_t(f.max_download_mb * 1e6);
  const WebExportReport report = ExportWeb(lf, options, f.out);
  fmt::print(
      "wrote {}/index.html: {}x{} views of {}x{} ({}), {:.1f} MB in all; open it in a browser, "
      "from disk or any static web server\n",
      f.out, lf.dims().cols, lf.dims().rows, report.view_width, report.view_height, report.note,
      report.download_bytes / 1e6);
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto* command = app.add_subcommand(
      "export",
      "Export the views and their cameras (PNGs, NeRF transforms.json, COLMAP) or a Looking "
      "Glass quilt, or a web page anyone opens in a browser");
  auto f = std::make_shared<ExportFlags>();
  command->add_option("lightfield", f->input, "Light field file (.lf) or video (.lfv)")->required();
  command
      ->add_option("--frame", f->frame,
                   "A video's light field frame (from 0); a quilt of a video starts there")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 30));
  command->add_option("--format", f->format, "png-views, nerf, colmap, quilt or web")->required();
  command->add_option("--out", f->out, "The folder to write (new or empty)")->required();
  command->add_option("--depth", f->depth,
                      "Depth maps of the light field (`lfcam depth --all`): 3D points from them, "
                      "with their tracks in COLMAP's points3D.txt (--format colmap), or in "
                      "sparse_pc.ply for nerfstudio's Gaussian splatting (--format nerf)");
  std::string presets;
  for (const QuiltPreset& p : QuiltPresets())
    presets +=
        fmt::format("{}{} ({}x{} views)", presets.empty() ? "" : ", ", p.name, p.cols, p.rows);
  command->add_option("--preset", f->preset, "quilt: the Looking Glass display: " + presets)
      ->capture_default_str();
  command
      ->add_option("--baseline", f->baseline_mm,
                   "quilt: mm between the leftmost and the rightmost view's eye (default: "
                   "between the array's outer cameras)")
      ->check(CLI::Range(0.0, 1e6));
  command
      ->add_option("--frames", f->frames,
                   "quilt of a video: how many light field frames from --frame (default: all)")
      ->check(CLI::Range(1, 1 << 30));
  command
      ->add_option("--integrator", f->integrator,
                   "quilt: how each view renders (as `lfcam render --integrator`)")
      ->capture_default_str();
  command
      ->add_option("--max-download-mb", f->max_download_mb,
                   "web: the folder's size at most (the views' resolution and JPEG quality are "
                   "chosen to fit)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 10000.0));
  f->camera.AddTo(*command);
  f->backend.AddTo(*command);
  command->add_flag("--quiet", f->quiet, "No progress bar (it is drawn only on a terminal)");
  command->callback([f, command] {
    if (f->format == "quilt") return ExportQuiltCommand(*f, *command);
    if (f->format == "web") return ExportWebCommand(*f, *command);
    const ExportFormat format = ExportFormatFromString(f->format);
    for (const std::string& flag : kRenderedExportFlags)
      if (f->camera.given(flag)) throw UsageError(flag + ": only with --format quilt or web");
    for (const char* flag : {"--preset", "--baseline", "--frames", "--integrator"})
      if (command->count(flag) > 0)
        throw UsageError(std::string(flag) + ": only with --format quilt");
    for (const char* flag : {"--size", "--max-download-mb"})
      if (command->count(flag) > 0)
        throw UsageError(std::string(flag) + ": only with --format web");
    if (!f->depth.empty() && format == ExportFormat::kPngViews)
      throw UsageError("--depth goes with --format colmap (points3D.txt) or nerf (sparse_pc.ply)");
    RequireNewOrEmptyFolder("--out", f->out);
    const LightField lf = ReadLightFieldFrame(f->input, std::size_t(f->frame));
    std::optional<DepthSet> depth;
    if (!f->depth.empty()) depth = ReadDepthSet(f->depth, lf);
    const ExportReport report = ExportLightField(lf, format, f->out, depth ? &*depth : nullptr);
    fmt::print("wrote {} views and their cameras to {} ({})\n", report.views, f->out,
               report.main_file.string());
    if (!report.filled_left_out.empty()) {
      std::vector<std::string> left_out;
      for (const auto& [r, c] : report.filled_left_out) left_out.push_back(CameraLabel(r, c));
      fmt::print(
          "  left out {} view{} the light field filled from {} neighbours (no photograph{}): "
          "{}\n",
          left_out.size(), left_out.size() == 1 ? "" : "s", left_out.size() == 1 ? "its" : "their",
          left_out.size() == 1 ? "" : "s", fmt::join(left_out, ", "));
    }
    if (depth && format == ExportFormat::kColmap)
      fmt::print("  {} points from the depth maps of {} views, seen {} times in all\n",
                 report.points, depth->count(), report.observations);
    else if (depth)
      fmt::print("  {} points from the depth maps of {} views in sparse_pc.ply\n", report.points,
                 depth->count());
  });
}

}  // namespace lfcam::cli
