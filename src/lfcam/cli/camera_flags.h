#pragma once
// The virtual camera flags shared by `render`, `oracle` and every later command that looks
// through the paper's camera.
#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/core/slab.h"
#include "lfcam/render/camera_path.h"
#include "lfcam/render/view_file.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam::cli {

struct CameraFlags {
  std::string size = "1024";
  std::string eye, look_at, up;  // empty: from the array (its centre, looking along -n_ca)
  double focal_length_mm = 500.0;
  double focus_distance_mm = 4000.0;
  double aperture_mm = 0.0;
  double lens_rate = 4.0;
  bool no_breathing = false;
  std::string view_file;  // --camera FILE.json: a saved view (the viewer's), flags override it
  std::string as_camera;  // --as-camera R,C: the rig's camera at grid position (R, C)

  // `rig_cameras`: also --as-camera (commands that read a light field file). `sweeps`: --eye,
  // --look-at, --focal-length, --focus-distance and --aperture also take a range A:B, swept over
  // a video's frames (`render --video`); the camera MakeCamera gives is the range's start.
  void AddTo(CLI::App& command, bool rig_cameras = false, bool sweeps = false);
  // The ranges given (empty without any). Call after Validate().
  CameraSweep sweep() const;
  // The same flags over another saved view (a camera path's, `render --path`).
  CameraFlags WithView(const std::string& view_path) const;
  // The saved view (--camera), read once; none without the flag. Throws UsageError naming it.
  const std::optional<ViewSettings>& view() const;
  // Whether a flag was given on the command line (not just defaulted).
  bool given(const std::string& flag) const;
  // Checks every flag that does not depend on the array (size, vectors, lens, the lens sample
  // count) before anything large is read; throws lfcam::UsageError naming the flag.
  void Validate() const;
  // The camera; unset eye/look-at/up default from the array plane. Throws lfcam::UsageError.
  VirtualCamera MakeCamera(const ArrayPlane& array) const;
  // The same for a light field: with --as-camera, the rig's camera (render/rig_camera.h) with
  // the aperture, focus and lens rate flags over it. An imported light field that records its
  // cameras (ImportedFromViews), given none of --camera, --eye, --look-at, --up and
  // --focal-length, starts from its rig's central camera (StartsAtRigCentre) rather than the
  // paper's view (f 500 mm, d_o 4000 mm: meaningless for another rig and scene), --size,
  // --focus-distance, --aperture and --lens-rate over it.
  VirtualCamera MakeCamera(const LightField& lf) const;
  // Whether MakeCamera(lf) starts from the rig's central camera, and the line that says so.
  bool StartsAtRigCentre(const LightField& lf) const;
  static std::string RigCentreNote(const LightField& lf);
  // With --as-camera at a camera the light field filled from its neighbours (core/
  // view_filling.h): the line that says the render is their blend, not a photograph; else empty.
  std::string FilledCameraNote(const LightField& lf) const;

 private:
  VirtualCameraParams Resolve(const ArrayPlane& array) const;
  // Whether the camera's focal length is --focal-length's (given or defaulted) before any light
  // field is read: not a saved view's, a rig camera's, nor where the rig's central camera may be
  // the start (no --eye, --look-at, --up, --focal-length).
  bool FocalLengthIsTheFlags() const;
  // Throws UsageError unless the focus (`focus`, or both ends of a swept --focus-distance) lies
  // beyond the focal length (`focal_length`, or both ends of a swept one) of a breathing film.
  void RequireFocusBeyondFocalLength(double focus, double focal_length, bool breathing) const;
  std::map<std::string, CLI::Option*> options_;
  std::map<std::string, std::string> ranges_;  // flag -> "A:B" as given (numbers only)
  bool sweeps_ = false;
  mutable std::optional<ViewSettings> view_;
  mutable bool view_read_ = false;
};

// Camera flags parsed on their own, as a command parses them: `args` as typed (first to last)
// through CLI11, the flags then held with their parser (they keep pointers into it); with
// `allow_extras`, arguments that are no camera flag are left over, not refused. A parse error
// comes out as UsageError. For callers without a command of their own (the fuzz targets of the
// flags and of the Python module's keywords), so that CLI11's parser is compiled once, here.
struct ParsedCameraFlags {
  CLI::App parser;
  CameraFlags flags;
};
std::unique_ptr<ParsedCameraFlags> ParseCameraFlags(std::vector<std::string> args,
                                                    bool rig_cameras = false, bool sweeps = false,
                                                    bool allow_extras = false);

}  // namespace lfcam::cli
