// `lfcam view FILE`: the interactive viewer (viewer/viewer.h; docs/viewer.md).
#include <memory>
#include <string>

#include "lfcam/cli/backend_flags.h"
#include "lfcam/cli/commands.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/viewer/viewer.h"

namespace lfcam::cli {

void AddViewCommand(CLI::App& app) {
  auto* view = app.add_subcommand(
      "view", "Explore a light field interactively (F1 in the window lists the keys)");
  struct Flags {
    std::string input, window = "1280x960", camera, script, screenshot_prefix = "lfcam_view", depth;
    BackendFlags backend;
    int threads = 0;
    double scale = 1.0, budget_ms = 40;
  };
  auto flags = std::make_shared<Flags>();
  flags->backend.backend = "auto";
  view->add_option("lightfield", flags->input, "Light field file (.lf)")->required();
  flags->backend.AddTo(*view);
  view->add_option("--window", flags->window, "Window size in screen pixels, WxH")
      ->capture_default_str();
  view->add_option("--scale", flags->scale,
                   "Render resolution over the window's (0.05-2; the Rendering window changes it)")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 2.0));
  view->add_option("--camera", flags->camera,
                   "Start from a saved view (FILE.json, as a screenshot writes beside its PNG)");
  view->add_option("--threads", flags->threads, "cpu backend: worker threads (0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  view->add_option("--frame-budget", flags->budget_ms,
                   "Frames costlier than this (ms) render at reduced scale while the view moves")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 10000.0));
  view->add_option("--screenshot-prefix", flags->screenshot_prefix,
                   "F12 writes PREFIX_NNN.png and PREFIX_NNN.json (the view, for render --camera)")
      ->capture_default_str();
  view->add_option("--depth", flags->depth,
                   "The views' depth maps (a folder from `lfcam depth --all`): offers the depth "
                   "lookup (no ghosts between cameras)");
  view->add_option("--script", flags->script,
                   "Run the commands in FILE (docs/viewer.md), then quit: for tests and demos");
  view->callback([flags] {
    ViewerOptions o;
    o.light_field = flags->input;
    FrameRenderOptions render_options;
    o.backend = flags->backend.Validate(render_options);
    o.workgroup_x = render_options.workgroup_x;
    o.workgroup_y = render_options.workgroup_y;
    std::tie(o.width, o.height) = ParseSize("--window", flags->window, kMaxImageSide);
    o.render_scale = flags->scale;
    o.view_file = flags->camera;
    o.script = flags->script;
    o.threads = flags->threads;
    o.frame_budget_ms = flags->budget_ms;
    o.screenshot_prefix = flags->screenshot_prefix;
    o.depth_dir = flags->depth;
    RunViewer(o);
  });
}

}  // namespace lfcam::cli
