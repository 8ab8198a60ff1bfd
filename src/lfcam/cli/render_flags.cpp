#include "lfcam/cli/render_flags.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>

#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/progress.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/render/depth_aware_sampler.h"

namespace lfcam::cli {

void RenderOptionFlags::AddTo(CLI::App& render) {
  render
      .add_option("--threads", threads,
                  "Worker threads (0 = all cores; 1 = the paper's single-threaded CPU column)")
      ->capture_default_str()
      ->check(CLI::Range(0, kMaxThreads));
  integrator_option_ =
      render.add_option("--integrator", integrator,
                        "lens-samples (the paper's: n_ls rays a pixel, with --interpolation) or "
                        "cameras (their limit with the focal-plane lookup: every camera under the "
                        "aperture read once, exactly weighted; noise-free, sharp on the plane of "
                        "focus, out-of-focus objects as one copy per camera) or "
                        "cameras-quadrilinear (= cameras --interpolation quadrilinear: the limit "
                        "of the paper's own estimator, each camera read through its hat scaled "
                        "to the st-plane; noise-free, the paper's smooth out-of-focus blur)");
  integrator_option_->capture_default_str();
  interpolation_option_ = render.add_option(
      "--interpolation", interpolation,
      "With lens-samples: quadrilinear (the paper's; smooth out-of-focus blur, "
      "noisy at low --lens-rate) or focal-plane (each camera read along its own ray "
      "through the point in focus; Isaksen et al. 2000) or depth (each camera read where the "
      "scene point the ray hits projects into it, occlusion-checked: no ghosts between cameras, "
      "true blur at every depth; needs depth maps, --depth)");
  interpolation_option_->capture_default_str();
  render.add_option("--depth", depth,
                    "With --interpolation depth: the views' depth maps (a folder from `lfcam "
                    "depth --all`); without it the maps the frame needs are estimated first");
  depth_blend_option_ = render.add_option(
      "--depth-blend", depth_blend,
      "With --interpolation depth: which cameras that see the ray's scene point are blended: "
      "agreeing (also those within two grid steps whose colour agrees with the four around the "
      "ray: their noise averages down; a render at a camera stays its photograph) or four (the "
      "four cameras around the ray alone, about a quarter less CPU time)");
  depth_blend_option_->capture_default_str();
  render.add_flag("--antialias", antialias,
                  "With --interpolation depth: spread each pixel's rays over its area on the "
                  "film (a sensor's pixel) instead of through its centre (the paper's pixel): "
                  "sharp edges without stair steps; a pinhole pixel casts 4 rays");
  render.add_flag("--reference", reference,
                  "Use the scalar reference renderer (one pixel at a time, every ray in double "
                  "precision; the definition the vectorised renderer is tested against) instead "
                  "of the vectorised one");
}

FrameRenderOptions RenderOptionFlags::Resolve(const std::optional<ViewSettings>& view) const {
  FrameRenderOptions options;
  options.threads = threads;
  options.reference = reference;
  options.interpolation =
      FlagValue("--interpolation", [&] { return InterpolationFromString(interpolation); });
  options.integrator = FlagValue("--integrator", [&] { return IntegratorFromString(integrator); });
  options.depth_blend =
      FlagValue("--depth-blend", [&] { return DepthBlendFromString(depth_blend); });
  const bool integrator_given = integrator_option_ && integrator_option_->count() > 0;
  const bool interpolation_given = interpolation_option_ && interpolation_option_->count() > 0;
  // A saved view brings its integrator and lookup, unless the flags say otherwise.
  if (view) {
    if (!integrator_given) options.integrator = view->integrator;
    if (!interpolation_given) options.interpolation = view->interpolation;
  }
  // The cameras integrator reads along the focal-plane lookup; asked for the quadrilinear
  // lookup in so many words, it takes that lookup's limit.
  if (options.integrator == Integrator::kCameras && interpolation_given &&
      options.interpolation == Interpolation::kQuadrilinear)
    options.integrator = Integrator::kCamerasQuadrilinear;
  return options;
}

void RenderOptionFlags::CheckDepthFlags(const FrameRenderOptions& options) const {
  if (options.interpolation == Interpolation::kDepth) {
    if (options.integrator != Integrator::kLensSamples)
      throw UsageError("--interpolation depth goes with --integrator lens-samples");
  } else if (!depth.empty() || antialias ||
             (depth_blend_option_ && depth_blend_option_->count() > 0)) {
    throw UsageError(fmt::format("{}: only with --interpolation depth", antialias ? "--antialias"
                                                                        : depth.empty()
                                                                            ? "--depth-blend"
                                                                            : "--depth"));
  }
}

std::unique_ptr<RenderRequest> ParseRenderKeywords(const std::vector<KeywordArgument>& arguments) {
  const KeywordTable& table = RenderKeywordTable();
  auto request = std::make_unique<RenderRequest>();
  request->parser = std::make_unique<CLI::App>("lfcam.render", "render");
  CLI::App& app = *request->parser;
  request->camera.AddTo(app, /*rig_cameras=*/true, /*sweeps=*/false);
  request->render.AddTo(app);
  request->backend.AddTo(app);
  ParseKeywords(app, table, arguments);
  try {
    request->camera.Validate();
    request->options = request->render.Resolve(request->camera.view());
    request->render.CheckDepthFlags(request->options);
    request->chosen_backend = request->backend.Validate(request->options);
  } catch (const UsageError& e) {
    throw UsageError(InKeywords(table, e.what()));
  }
  return request;
}

namespace {

double SecondsSinceStart(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DepthSet EstimateDepthForFrames(const LightField& lf, const std::vector<VirtualCamera>& cameras,
                                const std::string& input, bool quiet) {
  DepthSet depth(lf.dims());
  std::vector<bool> needed(lf.dims().view_count(), false);
  for (const VirtualCamera& camera : cameras) {
    const std::vector<bool> more = DepthViewsNeeded(lf, camera);
    for (std::size_t i = 0; i < needed.size(); ++i) needed[i] = needed[i] || more[i];
  }
  const int count = int(std::count(needed.begin(), needed.end(), true));
  const auto start = std::chrono::steady_clock::now();
  ProgressBar progress("estimating depth", count, ProgressWanted(quiet));
  const auto advance = progress.callback();
  EstimateDepthSet(
      lf, depth, [&](int r, int c) { return bool(needed[std::size_t(r) * lf.dims().cols + c]); },
      {},
      [&](int, int) {
        if (advance) advance(1);
      });
  progress.finish();
  if (!quiet)
    fmt::print(stderr,
               "estimated the depth of the {} views {} reads in {:.1f} s (`lfcam depth {} --all "
               "--out DIR` keeps them for --depth DIR)\n",
               count, cameras.size() > 1 ? "the video" : "this frame", SecondsSinceStart(start),
               input);
  return depth;
}

}  // namespace lfcam::cli
