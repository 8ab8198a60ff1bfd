#include "lfcam/render/view_file.h"

#include <fmt/format.h>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"

namespace lfcam {
namespace {

constexpr const char* kFormat = "lfcam-view";
constexpr std::int64_t kVersion = 1;

nlohmann::json Array(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::json ViewToJson(const ViewSettings& view) {
  const VirtualCameraParams& c = view.camera;
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["camera"] = {{"width", c.width},
                 {"height", c.height},
                 {"eye", Array(c.eye)},
                 {"look_at", Array(c.look_at)},
                 {"up", Array(c.up)},
                 {"focal_length_mm", c.focal_length_mm},
                 {"focus_distance_mm", c.focus_distance_mm},
                 {"aperture_mm", c.aperture_mm},
                 {"lens_rate", c.lens_rate},
                 {"breathing", c.breathing}};
  if (c.principal_offset_px != Vec2::Zero())
    j["camera"]["principal_offset_px"] = {c.principal_offset_px.x(), c.principal_offset_px.y()};
  j["render"] = {{"integrator", ToString(view.integrator)},
                 {"interpolation", ToString(view.interpolation)}};
  if (!view.light_field.empty()) j["light_field"] = view.light_field;
  return j;
}

ViewSettings ViewFromJson(const nlohmann::json& j, const std::string& where) {
  JsonFormatVersion(j, kFormat, kVersion, "view", where);
  ViewSettings view;
  const std::string at_camera = where + ": camera";
  const nlohmann::json& c = JsonField(j, "camera", where);
  VirtualCameraParams& p = view.camera;
  p.width = int(JsonInteger(c, "width", 1, kMaxImageSide, at_camera));
  p.height = int(JsonInteger(c, "height", 1, kMaxImageSide, at_camera));
  p.eye = JsonVec3(c, "eye", at_camera);
  p.look_at = JsonVec3(c, "look_at", at_camera);
  p.up = JsonVec3(c, "up", at_camera);
  p.focal_length_mm = JsonNumber(c, "focal_length_mm", at_camera);
  p.focus_distance_mm = JsonNumber(c, "focus_distance_mm", at_camera);
  p.aperture_mm = JsonNumber(c, "aperture_mm", at_camera);
  p.lens_rate = JsonNumber(c, "lens_rate", at_camera);
  const nlohmann::json& breathing = JsonField(c, "breathing", at_camera);
  if (!breathing.is_boolean()) throw Error(at_camera + ".breathing: must be true or false");
  p.breathing = breathing.get<bool>();
  if (c.contains("principal_offset_px")) {
    const nlohmann::json& o = c["principal_offset_px"];
    const std::string at_offset = at_camera + ".principal_offset_px";
    if (!o.is_array() || o.size() != 2) throw Error(at_offset + ": must be [x, y] (pixels)");
    p.principal_offset_px = {JsonNumber(o[0], "", at_offset), JsonNumber(o[1], "", at_offset)};
  }
  if (j.contains("render")) {
    const std::string at_render = where + ": render";
    const nlohmann::json& r = JsonField(j, "render", where);
    try {
      view.integrator = IntegratorFromString(JsonString(r, "integrator", at_render));
      view.interpolation = InterpolationFromString(JsonString(r, "interpolation", at_render));
    } catch (const Error& e) {
      throw Error(at_render + ": " + e.what());
    }
  }
  if (j.contains("light_field")) view.light_field = JsonString(j, "light_field", where);
  // The camera itself must make sense (VirtualCamera checks the rest).
  try {
    VirtualCamera camera(p);
  } catch (const Error& e) {
    throw Error(at_camera + ": " + e.what());
  }
  return view;
}

ViewSettings ReadViewFile(const std::string& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path, kMaxJsonBytes, "view file");
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return ViewFromJson(ParseJsonBounded(text, path), path);
}

void WriteViewFile(const std::string& path, const ViewSettings& view) {
  const std::string text = JsonToText(ViewToJson(view), 2) + "\n";
  WriteFileAtomically(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

}  // namespace lfcam
