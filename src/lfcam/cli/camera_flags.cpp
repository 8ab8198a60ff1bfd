#include "lfcam/cli/camera_flags.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "lfcam/cli/keyword_arguments.h"
#include "lfcam/cli/parse.h"
#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/view_filling.h"
#include "lfcam/render/lens_sampling.h"
#include "lfcam/render/rig_camera.h"

namespace lfcam::cli {
namespace {

// "A:B" split at its colon (no colon: the text twice).
std::pair<std::string, std::string> RangeEnds(const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) return {text, text};
  return {text.substr(0, colon), text.substr(colon + 1)};
}

// A vector flag's value, or with a range, its start.
Vec3 Vec3Start(const std::string& flag, const std::string& text) {
  return ParseVec3(flag, RangeEnds(text).first);
}

// A range's two ends, or the one value without a range.
std::vector<double> Ends(const std::optional<std::pair<double, double>>& range, double value) {
  return range ? std::vector<double>{range->first, range->second} : std::vector<double>{value};
}

}  // namespace

void CameraFlags::AddTo(CLI::App& c, bool rig_cameras, bool sweeps) {
  sweeps_ = sweeps;
  const std::string range_help = sweeps ? "; A:B sweeps it over the video's frames" : "";
  // A number, or with sweeps a range "A:B" (kept for sweep(); the number becomes A).
  const auto number = [this](const std::string& flag, double* value) {
    return [this, flag, value](const std::string& text) {
      const auto [start, end] = RangeEnds(text);
      *value = ParseNumbers(flag, start, 1)[0];
      if (start != text) {
        ParseNumbers(flag, end, 1);
        ranges_[flag] = text;
      } else {
        ranges_.erase(flag);
      }
    };
  };
  if (rig_cameras)
    options_["--as-camera"] = c.add_option(
        "--as-camera", as_camera,
        "R,C: render what the rig's camera at grid row R, column C (row 0 at the bottom, as "
        "`lfcam info` lists them) recorded: its position, orientation, image size, focal length "
        "and principal point; fractional R, C for a camera between them. --aperture, "
        "--focus-distance (default: the st-plane) and --lens-rate still apply, and --size renders "
        "its field of view at another size");
  options_["--camera"] = c.add_option(
      "--camera", view_file,
      "A saved view (FILE.json, as the viewer writes beside a screenshot): its camera, "
      "integrator and lookup; camera flags given too override it (--size renders it at "
      "another size)");
  options_["--size"] =
      c.add_option(
           "--size", size,
           fmt::format("Image size in pixels: N (square) or WxH, at most {} a side", kMaxImageSide))
          ->capture_default_str();
  options_["--eye"] = c.add_option(
      "--eye", eye, "Camera position e_c, X,Y,Z in world mm (default: array centre)" + range_help);
  options_["--look-at"] = c.add_option(
      "--look-at", look_at,
      "Point looked at, X,Y,Z in world mm (default: straight ahead, along -n_ca)" + range_help);
  options_["--up"] = c.add_option("--up", up, "Up direction X,Y,Z (default: v_ca)");
  options_["--focal-length"] = c.add_option_function<std::string>(
                                    "--focal-length", number("--focal-length", &focal_length_mm),
                                    "Focal length f in mm (film is 56 mm)" + range_help)
                                   ->default_str(fmt::format("{}", focal_length_mm));
  options_["--focus-distance"] =
      c.add_option_function<std::string>(
           "--focus-distance", number("--focus-distance", &focus_distance_mm),
           "Focus distance d_o in mm, from the lens; must exceed f" + range_help)
          ->default_str(fmt::format("{}", focus_distance_mm));
  options_["--aperture"] =
      c.add_option_function<std::string>("--aperture", number("--aperture", &aperture_mm),
                                         "Aperture diameter d_l in mm (0 = pinhole)" + range_help)
          ->default_str(fmt::format("{}", aperture_mm));
  options_["--lens-rate"] =
      c.add_option(
           "--lens-rate", lens_rate,
           fmt::format("Lens sampling rate gamma_ls: n_ls = gamma (d_l/2)^2 / 210 rays a pixel, "
                       "at most {} (4 to 9 looks good)",
                       kMaxLensSamples))
          ->capture_default_str();
  options_["--no-breathing"] =
      c.add_flag("--no-breathing", no_breathing,
                 "Keep the film at f (fixed field of view) and focus with f_e = f d_o / (f + d_o)");
}

bool CameraFlags::given(const std::string& flag) const {
  const auto it = options_.find(flag);
  return it != options_.end() && it->second != nullptr && it->second->count() > 0;
}

const std::optional<ViewSettings>& CameraFlags::view() const {
  if (!view_read_) {
    view_read_ = true;
    if (!view_file.empty()) view_ = FlagValue("--camera", [&] { return ReadViewFile(view_file); });
  }
  return view_;
}

CameraFlags CameraFlags::WithView(const std::string& view_path) const {
  CameraFlags flags = *this;
  flags.view_file = view_path;
  flags.view_.reset();
  flags.view_read_ = false;
  return flags;
}

CameraSweep CameraFlags::sweep() const {
  CameraSweep sweep;
  const auto numbers = [&](const std::string& flag) -> std::optional<std::pair<double, double>> {
    const auto it = ranges_.find(flag);
    if (it == ranges_.end()) return std::nullopt;
    const auto [a, b] = RangeEnds(it->second);
    return std::pair{ParseNumbers(flag, a, 1)[0], ParseNumbers(flag, b, 1)[0]};
  };
  const auto vectors = [&](const std::string& flag,
                           const std::string& text) -> std::optional<std::pair<Vec3, Vec3>> {
    if (text.find(':') == std::string::npos) return std::nullopt;
    const auto [a, b] = RangeEnds(text);
    return std::pair{ParseVec3(flag, a), ParseVec3(flag, b)};
  };
  sweep.eye = vectors("--eye", eye);
  sweep.look_at = vectors("--look-at", look_at);
  sweep.focal_length_mm = numbers("--focal-length");
  sweep.focus_distance_mm = numbers("--focus-distance");
  sweep.aperture_mm = numbers("--aperture");
  return sweep;
}

void CameraFlags::Validate() const {
  view();
  for (const auto& [flag, text] :
       std::map<std::string, std::string>{{"--eye", eye}, {"--look-at", look_at}, {"--up", up}}) {
    if (text.find(':') == std::string::npos) continue;
    if (!sweeps_ || flag == "--up")
      throw UsageError(fmt::format("{} {}: a range A:B {}", flag, text,
                                   sweeps_ ? "is not for --up" : "goes with --video"));
    const auto [a, b] = RangeEnds(text);
    ParseVec3(flag, a);
    ParseVec3(flag, b);
  }
  if (!ranges_.empty() && !sweeps_)
    throw UsageError(fmt::format("{} {}: a range A:B goes with --video", ranges_.begin()->first,
                                 ranges_.begin()->second));
  if (!ranges_.empty() || sweep().eye || sweep().look_at) {
    if (!as_camera.empty()) throw UsageError("--as-camera: not with a range (A:B) swept");
    // Every combination of the ranges' ends must make a camera.
    const CameraSweep s = sweep();
    CameraFlags at_end = *this;
    at_end.ranges_.clear();
    at_end.eye = eye.empty() ? eye : RangeEnds(eye).first;
    at_end.look_at = look_at.empty() ? look_at : RangeEnds(look_at).first;
    for (double f : Ends(s.focal_length_mm, focal_length_mm))
      for (double d : Ends(s.focus_distance_mm, focus_distance_mm))
        for (double a : Ends(s.aperture_mm, aperture_mm)) {
          at_end.focal_length_mm = f;
          at_end.focus_distance_mm = d;
          at_end.aperture_mm = a;
          at_end.Validate();
        }
  }
  const std::pair<int, int> image = ParseSize("--size", size, kMaxImageSide);
  // The linear image, its hit mask and their encoded copies: about 25 bytes a pixel.
  FlagValue("--size", [&] {
    RequireMemory(25.0 * image.first * image.second,
                  fmt::format("a {}x{} image", image.first, image.second));
  });
  if (!eye.empty()) Vec3Start("--eye", eye);
  if (!look_at.empty()) Vec3Start("--look-at", look_at);
  if (!up.empty()) ParseVec3("--up", up);
  if (!(focal_length_mm > 0) || !std::isfinite(focal_length_mm))
    throw UsageError(
        fmt::format("--focal-length: {} must be a positive number of mm", focal_length_mm));
  if (!as_camera.empty()) {
    for (const char* flag :
         {"--camera", "--eye", "--look-at", "--up", "--focal-length", "--no-breathing"})
      if (given(flag))
        throw UsageError(
            fmt::format("{} does not go with --as-camera (the rig's camera sets it)", flag));
    ParseNumbers("--as-camera", as_camera, 2);
    if (given("--focus-distance") &&
        (!(focus_distance_mm > 0) || !std::isfinite(focus_distance_mm)))
      throw UsageError(fmt::format("--focus-distance: {} mm must be positive", focus_distance_mm));
  } else if (!(focus_distance_mm > 0) || !std::isfinite(focus_distance_mm)) {
    throw UsageError(fmt::format("--focus-distance: {} mm must be positive", focus_distance_mm));
  } else if (FocalLengthIsTheFlags()) {
    RequireFocusBeyondFocalLength(focus_distance_mm, focal_length_mm, !no_breathing);
  }
  if (!(aperture_mm >= 0) || !std::isfinite(aperture_mm))
    throw UsageError(
        fmt::format("--aperture: {} must be 0 (pinhole) or a positive number of mm", aperture_mm));
  if (!(lens_rate > 0) || !std::isfinite(lens_rate))
    throw UsageError(fmt::format("--lens-rate: {} must be positive", lens_rate));
  if (aperture_mm > 0) {
    try {
      LensSampleCount(lens_rate, aperture_mm);
    } catch (const Error& e) {
      throw UsageError(fmt::format("--lens-rate/--aperture: {}", e.what()));
    }
  }
}

bool CameraFlags::FocalLengthIsTheFlags() const {
  // Not with a saved view (its own focal length) nor where a light field may start from its
  // rig's central camera (StartsAtRigCentre: the rig's focal length, known once it is read).
  if (!view_file.empty()) return false;
  if (!as_camera.empty()) return false;
  for (const char* flag : {"--eye", "--look-at", "--up", "--focal-length"})
    if (given(flag)) return true;
  return false;
}

void CameraFlags::RequireFocusBeyondFocalLength(double focus, double focal_length,
                                                bool breathing) const {
  // A breathing film sits at d_i = 1 / (1/f - 1/d_o): the focus must lie beyond f, at both ends
  // of a range swept. A fixed film (--no-breathing) focuses anywhere in front of the lens.
  if (!breathing) return;
  const CameraSweep s = sweep();
  for (const double f : Ends(s.focal_length_mm, focal_length))
    for (const double d : Ends(s.focus_distance_mm, focus))
      if (!(d > f))
        throw UsageError(fmt::format(
            "--focus-distance: {} must exceed the focal length ({}), or give --no-breathing", d,
            f));
}

VirtualCameraParams CameraFlags::Resolve(const ArrayPlane& array) const {
  if (const auto& saved = view()) {
    // The saved view, with the flags given on the command line over it.
    VirtualCameraParams p = saved->camera;
    if (given("--size")) {
      const auto [width, height] = ParseSize("--size", size, kMaxImageSide);
      p = WithFrameSize(p, width, height);
    }
    if (given("--eye")) p.eye = Vec3Start("--eye", eye);
    if (given("--look-at")) p.look_at = Vec3Start("--look-at", look_at);
    if (given("--up")) p.up = ParseVec3("--up", up);
    if (given("--focal-length")) p.focal_length_mm = focal_length_mm;
    if (given("--focus-distance")) p.focus_distance_mm = focus_distance_mm;
    if (given("--aperture")) p.aperture_mm = aperture_mm;
    if (given("--lens-rate")) p.lens_rate = lens_rate;
    if (given("--no-breathing")) p.breathing = false;
    return p;
  }
  VirtualCameraParams p;
  std::tie(p.width, p.height) = ParseSize("--size", size, kMaxImageSide);
  p.eye = eye.empty() ? array.center() : Vec3Start("--eye", eye);
  p.look_at = look_at.empty() ? Vec3(p.eye - 1000.0 * array.n_ca) : Vec3Start("--look-at", look_at);
  p.up = up.empty() ? array.v_ca : ParseVec3("--up", up);
  p.focal_length_mm = focal_length_mm;
  p.focus_distance_mm = focus_distance_mm;
  p.aperture_mm = aperture_mm;
  p.lens_rate = lens_rate;
  p.breathing = !no_breathing;
  return p;
}

bool CameraFlags::StartsAtRigCentre(const LightField& lf) const {
  if (!as_camera.empty() || !view_file.empty()) return false;
  for (const char* flag : {"--eye", "--look-at", "--up", "--focal-length"})
    if (given(flag)) return false;
  return lf.has_view_cameras() && ImportedFromViews(lf.metadata());
}

std::string CameraFlags::RigCentreNote(const LightField& lf) {
  const auto& d = lf.dims();
  return fmt::format(
      "lfcam: note: the view of the rig's central camera (--as-camera {},{}): this light field "
      "was imported and no --focal-length, --eye or --camera was given",
      0.5 * (d.rows - 1), 0.5 * (d.cols - 1));
}

std::string CameraFlags::FilledCameraNote(const LightField& lf) const {
  if (as_camera.empty()) return {};
  const std::vector<double> at = ParseNumbers("--as-camera", as_camera, 2);
  for (const auto& [r, c] : FilledViews(lf))
    if (at[0] == r && at[1] == c)
      return fmt::format(
          "lfcam: note: camera ({}, {}) was not photographed (or recorded black): the light field "
          "filled its view from its neighbours, and this render shows their blend",
          r, c);
  return {};
}

VirtualCamera CameraFlags::MakeCamera(const LightField& lf) const {
  const bool rig_centre = StartsAtRigCentre(lf);
  if (!rig_centre && as_camera.empty()) {
    VirtualCameraParams p = MakeCamera(lf.slab().uv).params();
    p.lens_length_scale = LensLengthScale(lf);
    return VirtualCamera(p);
  }
  Validate();
  // A camera of the rig, then the lens flags over it.
  const auto& d = lf.dims();
  VirtualCameraParams p;
  if (rig_centre) {
    p = RigCameraParams(lf, 0.5 * (d.rows - 1), 0.5 * (d.cols - 1));
  } else {
    const std::vector<double> at = ParseNumbers("--as-camera", as_camera, 2);
    p = FlagValue("--as-camera", [&] { return RigCameraParams(lf, at[0], at[1]); });
  }
  if (given("--size")) {  // another frame for the same field of view across
    const auto [width, height] = ParseSize("--size", size, kMaxImageSide);
    p = WithFrameSize(p, width, height);
  }
  if (given("--focus-distance")) p.focus_distance_mm = focus_distance_mm;
  p.aperture_mm = aperture_mm;
  p.lens_rate = lens_rate;
  try {
    return VirtualCamera(p);
  } catch (const Error& e) {
    throw UsageError(fmt::format(
        "{}: {}",
        rig_centre ? "the rig's central camera and the flags" : "--as-camera " + as_camera,
        e.what()));
  }
}

VirtualCamera CameraFlags::MakeCamera(const ArrayPlane& array) const {
  Validate();
  const VirtualCameraParams p = Resolve(array);
  if (given("--focus-distance") || given("--focal-length"))
    RequireFocusBeyondFocalLength(p.focus_distance_mm, p.focal_length_mm, p.breathing);
  try {
    return VirtualCamera(p);
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(fmt::format(
        "camera flags ({}): {}",
        view_file.empty() ? "--eye, --look-at, --up" : "--camera " + view_file + " and the flags",
        e.what()));
  }
}

std::unique_ptr<ParsedCameraFlags> ParseCameraFlags(std::vector<std::string> args, bool rig_cameras,
                                                    bool sweeps, bool allow_extras) {
  auto parsed = std::make_unique<ParsedCameraFlags>();
  parsed->parser.allow_extras(allow_extras);
  parsed->flags.AddTo(parsed->parser, rig_cameras, sweeps);
  ParseArguments(parsed->parser, std::move(args));
  return parsed;
}

}  // namespace lfcam::cli
