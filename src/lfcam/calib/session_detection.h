#pragma once
// Every board in a capture session, found: all images are read and searched in parallel.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/calib/board_detection.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct BoardView {
  int shot = 0;                      // index among the session's intrinsics shots
  std::vector<cv::Point2f> corners;  // board point order
};

struct CameraDetections {
  int row = 0, col = 0;
  std::vector<BoardView> intrinsics;              // shots where the whole board was found
  std::optional<std::vector<cv::Point2f>> world;  // the world board, if found
  std::vector<std::string> not_found;             // shots whose whole board was not found
  std::vector<std::string> warnings;              // unreadable images
};

struct SessionDetections {
  int width = 0, height = 0;  // every image's size (the manifest's sensor)
  int intrinsics_shots = 0;
  std::vector<std::string> intrinsics_shot_names;
  std::vector<CameraDetections> cameras;  // one per grid position, row-major
  CameraDetections& camera(int row, int col, int cols) {
    return cameras[std::size_t(row * cols + col)];
  }
};

// Reads and searches every intrinsics and world image of the session. An image that cannot be
// read, or whose board is not found, becomes a warning on its camera; an image whose size is not
// the manifest's sensor size throws lfcam::Error naming the file (a session of mixed sizes),
// before any image is searched (the sizes come from the images' headers).
// `image_done` is called once per image (serialised).
//
// Every image is searched with the plain detector first; the thorough one (adaptive thresholds,
// the sector-based detector) then retries the world image of every camera that missed its world
// board and the missed intrinsics images of every camera left with fewer than `min_views`.
SessionDetections DetectSessionBoards(const std::filesystem::path& session_dir,
                                      const CaptureManifest& manifest,
                                      const BoardSpec& intrinsics_board,
                                      const BoardSpec& world_board,
                                      const std::function<void()>& image_done = {},
                                      int min_views = 4);

}  // namespace lfcam
