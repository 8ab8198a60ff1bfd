#pragma once
// An output folder that appears whole or not at all (`lfcam export`): everything is written into
// a sibling staging folder (NAME.partial-PID), renamed into place by Commit(); a StagedFolder
// destroyed without Commit() (an error) removes it.
#include <filesystem>

namespace lfcam {

class StagedFolder {
 public:
  // Throws lfcam::Error when `out` exists and is not an empty folder, or the staging folder
  // cannot be created.
  explicit StagedFolder(const std::filesystem::path& out);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // Where to write (the staging folder).
  const std::filesystem::path& path() const { return staging_; }
  const std::filesystem::path& out() const { return out_; }
  void Commit();  // throws lfcam::Error

 private:
  std::filesystem::path out_, staging_;
  bool committed_ = false;
};

}  // namespace lfcam
