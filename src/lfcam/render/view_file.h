#pragma once
// A view: the virtual camera and how it is rendered, as the viewer saves it beside a screenshot
// and `lfcam render --camera FILE.json` reads it, so that a view found interactively renders
// again offline at any size (docs/format.md):
//   {"format": "lfcam-view", "version": 1,
//    "camera": {"width", "height", "eye": [x, y, z], "look_at": [...], "up": [...],
//               "focal_length_mm", "focus_distance_mm", "aperture_mm", "lens_rate", "breathing"},
//    "render": {"integrator", "interpolation"}, "light_field": "path it was made on"}
#include <string>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

struct ViewSettings {
  VirtualCameraParams camera;
  Integrator integrator = Integrator::kLensSamples;
  Interpolation interpolation = Interpolation::kQuadrilinear;
  std::string light_field;  // informational
};

nlohmann::json ViewToJson(const ViewSettings& view);
// Throws lfcam::Error naming `where` and the field at fault.
ViewSettings ViewFromJson(const nlohmann::json& j, const std::string& where);
ViewSettings ReadViewFile(const std::string& path);
void WriteViewFile(const std::string& path, const ViewSettings& view);  // atomically

}  // namespace lfcam
