#pragma once
// Building the light field from a calibrated capture session (paper §5.2.3): for every camera,
// one resampling map from the st samples of the view window to its scene image (the plane's
// homography, then the lens distortion), the photometric correction, and a bilinear lookup in
// linear light, antialiased where the map shrinks (the image is decoded at 1/2, 1/4 or 1/8 size
// by libjpeg-turbo's scaled decoding, then blurred for what remains). JPEG chroma subsampled by
// the camera comes back at full resolution guided by the luma. Cameras in parallel.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calib/calibration_file.h"
#include "lfcam/core/jpeg_region.h"
#include "lfcam/core/lightfield.h"
#include "lfcam/session/session.h"

namespace lfcam {

// How a camera image is read between its pixels (OpenCV's kernels, in linear light).
enum class Resampling { kLinear, kCubic, kLanczos4 };
Resampling ResamplingFromString(const std::string& name);  // throws lfcam::Error
std::string ToString(Resampling resampling);

struct BuildOptions {
  int n_s = 1248, n_t = 1152;
  Resampling resampling = Resampling::kLinear;
  // JPEG chroma kept at half resolution (4:2:0, as the Pi camera writes it) comes back guided by
  // the luma (core/chroma_upsampling.h) or interpolated as any decoder does.
  ChromaUpsampling chroma = ChromaUpsampling::kGuided;
  std::optional<StDomain> st_domain;  // default: the calibration's (the world board, [0, 1]^2)
  // Each view in its own window (format version 4): the st domain's grid moved by whole samples
  // to be centred where the camera's image centre looks, so that together the views cover what
  // every camera saw. Otherwise every view samples the st domain itself.
  bool view_windows = false;
  bool allow_missing = false;  // fill cameras without an image or calibration from neighbours
  // Fill, from their neighbours, views too dark to be photographs of the scene (DarkViews in
  // core/view_filling.h: a covered lens, a failed exposure), whatever allow_missing says.
  bool fill_dark_views = true;
  bool photometric_correction = true;  // when the calibration has it
  std::string shot = "scene";  // the shot to build (the world shot shows the board at the st-plane)
  std::function<void()> view_done;  // once per view (serialised)
};

struct ColourSpread {
  // Over the st region every camera sees, each camera's mean linear colour against the array's
  // median: the largest relative deviation of any camera in any channel, and the RMS.
  double max_deviation = 0, rms_deviation = 0;
  int cameras = 0;
  double region_fraction = 0;  // of the st domain
};

struct BuildReport {
  std::vector<std::string> filled;         // "camera (r, c) from (r, c), ..." for each filled view
  std::vector<std::string> unreadable;     // images that could not be read (filled, allow_missing)
  std::vector<std::pair<int, int>> dark;   // (row, col) of each view too dark (filled)
  ColourSpread before, after;              // per-camera mean colour, without and with correction
  int reduction_max = 1;                   // the largest decode reduction used
  double seconds = 0, decode_seconds = 0;  // wall; decode summed over threads
};

// Throws lfcam::Error naming the camera and file for a missing image (unless allow_missing), an
// unreadable image, an image of the wrong size, or a calibration that does not match the
// session's grid or sensor.
LightField BuildLightField(const std::filesystem::path& session_dir,
                           const CaptureManifest& manifest, const CalibrationFile& calibration,
                           const BuildOptions& options, BuildReport* report = nullptr);

// A camera's image for one light field: its encoded bytes (a JPEG or PNG file's, or one frame of
// a recording's stream), read when its view is built, and a name for messages.
struct CameraImage {
  int row = 0, col = 0;
  std::string name;
  std::function<std::vector<std::uint8_t>()> read;
};

// Where a view's st samples fall in its camera's image (computed from the calibration and the
// sampling alone): what a video's frames share.
struct ViewMap {
  cv::Mat map_x, map_y;  // CV_32FC1, n_t x n_s: pixels of the image decoded at 1/reduction
  int reduction = 1;
  double footprint = 0;  // full-resolution pixels per st sample at the view's centre
  cv::Size scaled;       // the image's size at 1/reduction
  cv::Rect wanted;       // the part of it the map reads, with a margin
};

// What BuildLightField does once it has found the shot's images: `images` holds at most one per
// camera; a camera without one (`where` says of what: "in shot 'scene'") is missing, and with
// options.allow_missing filled from its neighbours, as is one whose image cannot be read (the
// report and the metadata say which and why). options.shot is not used. With `maps`, each
// camera's map is made once and kept there for the next call with the same calibration and
// options (a video's frames).
LightField BuildLightFieldFromImages(const CalibrationFile& calibration,
                                     const std::vector<CameraImage>& images,
                                     const std::string& where, const BuildOptions& options,
                                     BuildReport* report = nullptr,
                                     std::vector<ViewMap>* maps = nullptr);

}  // namespace lfcam
