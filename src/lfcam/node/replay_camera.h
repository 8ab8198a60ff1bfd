#pragma once
// A camera that replays images from a folder: for shot S of kind K it serves FOLDER/S.jpg, or
// else FOLDER/K.jpg (so one scene.jpg answers every scene shot). For testing the capture system
// at full scale without cameras (docs/benchmarks.md measures 100 agents with it), and for
// serving images taken some other way through the same host tools.
#include <filesystem>
#include <memory>

#include "lfcam/node/camera_backend.h"

namespace lfcam {

std::unique_ptr<CameraBackend> MakeReplayCamera(const std::filesystem::path& folder);

}  // namespace lfcam
