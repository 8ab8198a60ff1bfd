#pragma once
// `lfcam view FILE`: the interactive light field viewer (the paper's Fig. 9). A GLFW window
// with Dear ImGui controls: two toggleable control windows (Camera, Rendering) and a help
// overlay, mouse and key navigation, click to focus, screenshots that re-render offline, and a
// script mode for tests (viewer/viewer_script.h). docs/viewer.md is the user's guide.
#include <string>

#include "lfcam/render/frame_renderer.h"
#include "lfcam/render/view_file.h"

namespace lfcam {

struct ViewerOptions {
  std::string light_field;           // the file to open
  Backend backend = Backend::kAuto;  // auto: the window's GPU when it is hardware, else the CPU
  int workgroup_x = 16, workgroup_y = 8;
  int threads = 0;                               // CPU backend
  int width = 1280, height = 960;                // the window, in screen coordinates
  double render_scale = 1.0;                     // render resolution over the framebuffer's
  std::string view_file;                         // start from a saved view (--camera)
  std::string script;                            // run these commands, then quit (viewer_script.h)
  std::string screenshot_prefix = "lfcam_view";  // F12: PREFIX_NNN.png and .json
  double frame_budget_ms = 40;  // frames costlier than this render reduced while moving
  std::string depth_dir;        // the views' depth maps (`lfcam depth --all`): the depth lookup
};

// Opens the light field (before any window: a missing or corrupt file is an lfcam::Error and no
// window appears), then the window; returns when it is closed or the script ends. Throws
// lfcam::Error when no window or GL 3.3 context can be made, naming why.
void RunViewer(const ViewerOptions& options);

}  // namespace lfcam
