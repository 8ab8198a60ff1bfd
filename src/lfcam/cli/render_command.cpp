// `lfcam render` (a light field through the virtual camera) and `lfcam oracle` (the scene
// itself through the same camera: the ground truth).
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <numbers>
#include <vector>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/camera_flags.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/cli/render_flags.h"
#include "lfcam/cli/render_video.h"
#include "lfcam/cli/scene_flags.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/lightfield_video_file.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/depth_aware_sampler.h"
#include "lfcam/sim/oracle.h"

namespace lfcam::cli {
namespace {

double Degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// `samples`: what each pixel averages (the renderer's n_ls lens rays, the oracle's samples).
// `unit`: the light field's world lengths' (WorldLengthUnit); f is the film's, in mm.
std::string DescribeCamera(const VirtualCamera& camera, const std::string& samples,
                           const std::string& unit) {
  const auto& p = camera.params();
  return fmt::format("{}x{}, f {:.6g} mm, d_o {:.6g} {}, d_l {:.6g} {}, {}, fov {:.3f} deg ({})",
                     p.width, p.height, p.focal_length_mm, p.focus_distance_mm, unit, p.aperture_mm,
                     unit, samples, Degrees(camera.field_of_view_rad()),
                     p.breathing ? "breathing" : "no breathing");
}

// Why some of an aperture's rays missed the slab, where they did: each pixel is the mean of the
// rays that hit, so the frame is right, but a share under 100% reads like a fault. Empty for a
// pinhole or where every ray hit.
std::string MissedRaysNote(const LightField& lf, const VirtualCamera& camera, long long hit,
                           long long rays) {
  if (camera.is_pinhole() || rays <= 0 || hit >= rays || hit == 0) return {};
  const ArrayPlane& uv = lf.slab().uv;
  const std::string unit = WorldLengthUnit(lf.metadata());
  const double aperture = camera.params().aperture_mm;
  const std::string array =
      uv.rows == 1 || uv.cols == 1
          ? fmt::format("a single {} of cameras ({:.4g} {} {})", uv.rows == 1 ? "row" : "column",
                        uv.rows == 1 ? uv.height_mm() : uv.width_mm(), unit,
                        uv.rows == 1 ? "tall" : "wide")
          : fmt::format("the camera array ({:.4g} x {:.4g} {})", uv.width_mm(), uv.height_mm(),
                        unit);
  const std::string why =
      aperture > std::min(uv.width_mm(), uv.height_mm())
          ? fmt::format("the aperture (d_l {:.4g} {}) is wider than {}", aperture, unit, array)
          : fmt::format(
                "the aperture (d_l {:.4g} {}) reaches beyond {} or beyond what the views "
                "saw",
                aperture, unit, array);
  return fmt::format(
      "lfcam: note: {:.1f}% of the aperture's rays missed the light field: {}. Each pixel is the "
      "mean of the rays that hit it, not darkened by those that missed (--hit-mask marks the "
      "pixels no ray reached)",
      100.0 * double(rays - hit) / double(rays), why);
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void AddRenderCommand(CLI::App& app) {
  auto* render = app.add_subcommand("render", "Render a light field through the virtual camera");
  struct Flags {
    std::string input, out, hit_mask;
    int frame = 0;
    CameraFlags camera;
    BackendFlags backend;
    RenderOptionFlags render;
    int repeat = 1;
    bool quiet = false;
    VideoFlags video;
  };
  auto flags = std::make_shared<Flags>();
  render->add_option("lightfield", flags->input, "Light field file (.lf) or video (.lfv)")
      ->required();
  render->add_option("--frame", flags->frame, "A video's light field frame to render (from 0)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 30));
  auto* out_option = render->add_option("--out", flags->out, "Image to write (.png or .jpg)");
  flags->camera.AddTo(*render, /*rig_cameras=*/true, /*sweeps=*/true);
  auto* video_option = flags->video.AddTo(*render);
  out_option->excludes(video_option);
  flags->render.AddTo(*render);
  render->add_option("--repeat", flags->repeat, "Render this many times and report the median")
      ->check(CLI::Range(1, 1000));
  render->add_option("--hit-mask", flags->hit_mask,
                     "Also write where rays hit the slab (white) as an image; both images are "
                     "written, or neither");
  render->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  flags->backend.AddTo(*render);
  render->callback([flags, out_option, video_option] {
    if (out_option->count() == 0 && video_option->count() == 0)
      throw UsageError("--out IMAGE (a frame) or --video OUT.mp4 (a video) is required");
    // Every flag and output is checked before the light field is read.
    flags->camera.Validate();
    // A saved view (or a path's first) brings its integrator and lookup, unless the flags say
    // otherwise.
    FrameRenderOptions options = flags->render.Resolve(
        flags->video.path.empty() ? flags->camera.view() : flags->video.FirstView());
    if (video_option->count() > 0) {
      if (!flags->hit_mask.empty() || flags->repeat != 1)
        throw UsageError(fmt::format("{}: not with --video",
                                     flags->hit_mask.empty() ? "--repeat" : "--hit-mask"));
      flags->render.CheckDepthFlags(options);
      VideoRenderInput input{flags->input, flags->frame, flags->render.depth,
                             flags->render.antialias, flags->quiet};
      RenderVideoCommand(input, flags->video, flags->camera, options,
                         flags->backend.Validate(options));
      return;
    }
    flags->video.RequireNoVideoFlags();
    if (!flags->camera.sweep().empty())
      throw UsageError("a range A:B (a sweep) goes with --video OUT.mp4");
    RequireImageOutput(flags->out, "--out");
    std::error_code ec;
    if (std::filesystem::equivalent(flags->input, flags->out, ec))
      throw UsageError(
          fmt::format("--out {}: is the input light field; choose another name", flags->out));
    if (!flags->hit_mask.empty()) {
      RequireImageOutput(flags->hit_mask, "--hit-mask");
      if (std::filesystem::weakly_canonical(flags->hit_mask) ==
          std::filesystem::weakly_canonical(flags->out))
        throw UsageError("--hit-mask: must not be the same file as --out");
    }
    const Backend backend = flags->backend.Validate(options);
    const std::unique_ptr<FrameRenderer> renderer = BackendFlags::Open(backend);
    const LightField lf = ReadLightFieldFrame(flags->input, std::size_t(flags->frame));
    const VirtualCamera camera = flags->camera.MakeCamera(lf);
    if (flags->camera.StartsAtRigCentre(lf))
      fmt::print(stderr, "{}\n", CameraFlags::RigCentreNote(lf));
    if (const std::string note = flags->camera.FilledCameraNote(lf); !note.empty())
      fmt::print(stderr, "{}\n", note);
    DepthSet depth;
    flags->render.CheckDepthFlags(options);
    if (options.interpolation == Interpolation::kDepth) {
      depth = flags->render.depth.empty()
                  ? EstimateDepthForFrames(lf, {camera}, flags->input, flags->quiet)
                  : ReadDepthSet(flags->render.depth, lf,
                                 DepthsForRendering(DepthViewsNeeded(lf, camera)));
      options.depth = &depth;
      options.antialias = flags->render.antialias;
    }
    ProgressBar progress("rendering",
                         std::int64_t(flags->repeat) * camera.width() * camera.height(),
                         ProgressWanted(flags->quiet));
    options.progress = progress.callback();
    std::vector<double> times_ms, gpu_ms;
    RenderResult result;
    for (int i = 0; i < flags->repeat; ++i) {
      const auto start = std::chrono::steady_clock::now();
      result = renderer->Render(lf, camera, options);
      times_ms.push_back(SecondsSince(start) * 1e3);
      gpu_ms.push_back(result.gpu_ms);
    }
    progress.finish();
    std::sort(times_ms.begin(), times_ms.end());
    std::sort(gpu_ms.begin(), gpu_ms.end());
    std::vector<std::pair<std::filesystem::path, cv::Mat>> outputs = {{flags->out, result.image}};
    if (!flags->hit_mask.empty()) {
      cv::Mat rgb;
      cv::merge(std::vector<cv::Mat>{result.hit_mask, result.hit_mask, result.hit_mask}, rgb);
      outputs.emplace_back(flags->hit_mask, rgb);
    }
    WriteImages(outputs);
    if (result.rays_hit == 0)
      fmt::print(stderr,
                 "lfcam: warning: no ray met the slab (the PRP window and the st domain): the "
                 "image is black; check --eye and --look-at against `lfcam info {}`\n",
                 flags->input);
    fmt::print(
        "wrote {}: {}; {:.1f} ms{} (median of {}, {} renderer), {:.1f}% of rays hit the slab\n",
        flags->out,
        DescribeCamera(
            camera,
            options.integrator != Integrator::kLensSamples
                ? fmt::format("cameras integrator, {:.1f} cameras a pixel",
                              double(result.rays_hit) / (camera.width() * camera.height()))
                : fmt::format("{} lens samples", camera.lens_samples().size()),
            WorldLengthUnit(lf.metadata())),
        times_ms[times_ms.size() / 2],
        renderer->uses_gl() && gpu_ms[gpu_ms.size() / 2] >= 0
            ? fmt::format(", {:.2f} ms on the GPU", gpu_ms[gpu_ms.size() / 2])
            : std::string(),
        flags->repeat, result.path,
        100.0 * double(result.rays_hit) / double(std::max(1LL, result.rays)));
    if (const std::string note = MissedRaysNote(lf, camera, result.rays_hit, result.rays);
        !note.empty())
      fmt::print(stderr, "{}\n", note);
  });
}

void AddOracleCommand(CLI::App& app) {
  auto* oracle = app.add_subcommand(
      "oracle", "Render the simulated scene itself through the virtual camera (ground truth)");
  struct Flags {
    std::string scene = "paper", out;
    CameraFlags camera;
    int samples = 0, threads = 0;
    std::optional<double> time_s;
    bool quiet = false;
  };
  auto flags = std::make_shared<Flags>();
  oracle->add_option("--scene", flags->scene, "Built-in scene (paper)")->capture_default_str();
  oracle->add_option("--out", flags->out, "Image to write (.png or .jpg)")->required();
  flags->camera.AddTo(*oracle);
  oracle
      ->add_option("--samples", flags->samples,
                   "Samples per pixel (0 = 256 for a pinhole, 1024 with an aperture)")
      ->check(CLI::Range(0, kMaxOracleSamples));
  oracle->add_option("--threads", flags->threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  AddSceneTimeOption(*oracle, flags->time_s);
  oracle->add_flag("--quiet", flags->quiet, "No progress bar (it is drawn only on a terminal)");
  oracle->callback([flags] {
    flags->camera.Validate();
    RequireImageOutput(flags->out, "--out");
    const Scene scene = SceneAtTime(flags->scene, flags->time_s);
    const VirtualCamera camera = flags->camera.MakeCamera(scene.rig.array);
    const auto start = std::chrono::steady_clock::now();
    ProgressBar progress("oracle", std::int64_t(camera.width()) * camera.height(),
                         ProgressWanted(flags->quiet));
    const OracleOptions options{flags->samples, flags->threads, progress.callback()};
    const cv::Mat image = RenderSceneOracle(scene, camera, options);
    progress.finish();
    WriteImage(flags->out, image);
    fmt::print("wrote {}: oracle of scene '{}', {}; {:.1f} s\n", flags->out, scene.name,
               DescribeCamera(
                   camera,
                   fmt::format("{} samples a pixel", OracleSamplesPerPixel(camera, options)), "mm"),
               SecondsSince(start));
  });
}

}  // namespace lfcam::cli
