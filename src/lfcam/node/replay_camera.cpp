#include "lfcam/node/replay_camera.h"

#include <fmt/format.h>

#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/node/jpeg_preview.h"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

class ReplayCamera final : public CameraBackend {
 public:
  explicit ReplayCamera(fs::path folder) : folder_(std::move(folder)) {}

  std::string name() const override { return "replay"; }

  CameraProbe Probe() override {
    std::error_code ec;
    if (!fs::is_directory(folder_, ec))
      return {false, "replay", fmt::format("{}: not a folder", folder_.string())};
    return {true, fmt::format("replay {}", folder_.string()), ""};
  }

  void Configure(const CaptureSettings&) override {}

  void Prepare(const ShotRequest& shot) override {
    const fs::path file = Source(shot);
    image_ = Read(file);
  }

  void Fire() override {}

  std::string Collect(std::chrono::milliseconds) override {
    if (image_.empty()) throw Error("replay: Collect without Prepare");
    return std::exchange(image_, {});
  }

  std::string Preview(int max_width) override {
    std::error_code ec;
    for (const char* candidate : {"preview.jpg", "scene.jpg"})
      if (fs::is_regular_file(folder_ / candidate, ec))
        return ScaledJpeg(Read(folder_ / candidate), max_width, 80, (folder_ / candidate).string());
    throw Error(fmt::format("replay: {} has no preview.jpg or scene.jpg", folder_.string()));
  }

 private:
  fs::path Source(const ShotRequest& shot) const {
    std::error_code ec;
    for (const std::string& stem : {shot.shot, shot.kind}) {
      // The names come from a verified request and were checked as capture ids or shot names.
      if (stem.empty() || stem.find('/') != std::string::npos || stem.front() == '.') continue;
      const fs::path candidate = folder_ / (stem + ".jpg");
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
    throw Error(
        fmt::format("replay: nothing to replay for shot '{}' ({}): no {}.jpg or {}.jpg in {}",
                    shot.shot, shot.kind, shot.shot, shot.kind, folder_.string()));
  }

  static std::string Read(const fs::path& file) {
    const auto bytes = ReadFileBytes(file, std::uint64_t(1) << 30, "replayed image");
    return {bytes.begin(), bytes.end()};
  }

  fs::path folder_;
  std::string image_;
};

}  // namespace

std::unique_ptr<CameraBackend> MakeReplayCamera(const fs::path& folder) {
  return std::make_unique<ReplayCamera>(folder);
}

}  // namespace lfcam
