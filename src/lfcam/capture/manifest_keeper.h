#pragma once
// The session's manifest while a controller changes it from many threads: held in memory,
// written to disk (atomically) after a change, at most every 0.25 s while images stream in (a
// manifest of 1600 images is about 1 MB: rewriting it after each would cost more than the
// downloads) and always on Flush. An image renamed into place but not yet recorded is found by
// the next fetch by its checksum.
#include <chrono>
#include <filesystem>
#include <mutex>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/session/session.h"

namespace lfcam {

class ManifestKeeper {
 public:
  ManifestKeeper(std::filesystem::path session, CaptureManifest manifest)
      : path_(std::move(session) / kManifestName), manifest_(std::move(manifest)) {}
  ~ManifestKeeper() {
    try {
      Flush();
    } catch (const Error&) {
    }
  }

  template <typename F>
  void Update(F&& change) {
    std::lock_guard lock(mutex_);
    change(manifest_);
    dirty_ = true;
    if (std::chrono::steady_clock::now() - written_ > std::chrono::milliseconds(250)) WriteLocked();
  }
  void Flush() {
    std::lock_guard lock(mutex_);
    if (dirty_) WriteLocked();
  }
  CaptureManifest Snapshot() {
    std::lock_guard lock(mutex_);
    return manifest_;
  }

 private:
  void WriteLocked() {
    const std::string text = JsonToText(ManifestToJson(manifest_), 2) + "\n";
    WriteFileAtomically(path_, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
    written_ = std::chrono::steady_clock::now();
    dirty_ = false;
  }

  std::filesystem::path path_;
  std::mutex mutex_;
  CaptureManifest manifest_;
  bool dirty_ = false;
  std::chrono::steady_clock::time_point written_{};
};

}  // namespace lfcam
