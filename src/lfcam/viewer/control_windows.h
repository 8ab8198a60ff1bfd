#pragma once
// The viewer's two control windows, as in the paper's Fig. 9 (Camera: position and
// orientation, focal length, focus distance, aperture, breathing, reset; Rendering: integrator,
// lookup, lens sampling rate, render scale, backend and device, milliseconds a frame, lookups a
// pixel), and the help overlay with every key. Each draws with Dear ImGui and edits the view in
// place.
#include <cstdint>
#include <map>
#include <string>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/slab.h"
#include "lfcam/render/view_file.h"

namespace lfcam {

struct PanelVisibility {
  bool camera = true;     // F2
  bool rendering = true;  // F3
  bool video = true;      // F4 (a light field video only)
  bool help = false;      // F1
};

class VideoPlayback;

// What the Video window reports about playback.
struct PlaybackStats {
  double shown_fps = 0;     // light field frames drawn a second, over the last second
  double shown_scale = 1;   // the resolution they were drawn at, over the full one
  std::int64_t shown = -1;  // the frame on screen
};

// What the Rendering window reports about the frame on screen.
struct FrameStats {
  std::string backend;             // FrameRenderer::description()
  double frame_ms = 0;             // the shown frame's render, wall-clock
  double gpu_ms = -1;              // GL: its compute pass
  double scale = 1;                // the shown frame's resolution over the full one
  int parts_shown = 1, parts = 1;  // an accumulating lens-samples frame: its parts so far
  int width = 0, height = 0;
  double rays_per_pixel = 0;   // lens samples cast (or cameras read) a pixel
  double reads_per_pixel = 0;  // camera views read a pixel (lens samples: 4 a ray); 0 unknown
  std::string status;          // the last click-to-focus, screenshot, ...
  // What a full-resolution frame of each mode (RenderModeName) last cost here, wall-clock ms.
  std::map<std::string, double> mode_ms;
};

// The integrator and lookup of a view, for people: "lens samples, focal-plane lookup",
// "cameras (exact limit)", "quadrilinear limit".
std::string RenderModeName(const ViewSettings& view);

// Each returns true when it changed the view. `render_scale` is the render resolution over the
// window's framebuffer.
// With a light field that records its cameras, the Camera window also stands the view as the
// rig's camera at `rig_position` (row, col; fractional between cameras).
bool DrawCameraWindow(ViewSettings& view, const LightField& lf, double rig_position[2], bool* open);
// `has_depth`: the depth lookup is offered (the viewer has the views' depth maps).
bool DrawRenderingWindow(ViewSettings& view, double& render_scale, const FrameStats& stats,
                         bool has_depth, bool* open);
// A light field video's controls: play/pause, loop, the timeline (drag to scrub), a frame back
// and on, and the frame rate kept. Acts on `playback` directly; true when it changed the frame.
bool DrawVideoWindow(VideoPlayback& playback, const PlaybackStats& stats, bool* open);
void DrawHelpOverlay(bool* open);

}  // namespace lfcam
