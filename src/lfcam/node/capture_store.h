#pragma once
// The captures a node holds, in one folder: IMAGE ID.jpg and its record ID.json (what was asked,
// when it fired, the settings, size and SHA-256). Both are written to a temporary name and
// renamed, so a node that dies mid-write holds no half image; records survive a restart.
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lfcam {

// A capture id: 1..64 of [A-Za-z0-9_.-], not starting with '.', so that it names a file in the
// capture folder and nothing outside it.
bool IsValidCaptureId(std::string_view id);

struct CaptureRecord {
  std::string id;
  std::string kind, shot;              // what the host asked for ("scene", "scene")
  std::int64_t requested_unix_ns = 0;  // the trigger time T
  std::int64_t trigger_unix_ns = 0;    // when the node fired (its clock)
  nlohmann::json settings;             // the settings in force
  std::uint64_t size = 0;
  std::string sha256;
};

nlohmann::json RecordToJson(const CaptureRecord& record);
CaptureRecord RecordFromJson(const nlohmann::json& j, const std::string& where);

class CaptureStore {
 public:
  // Creates the folder if needed; removes temporaries a dead writer left.
  explicit CaptureStore(std::filesystem::path folder);

  const std::filesystem::path& folder() const { return folder_; }
  // Writes the image and its record (size and sha256 filled in here). Throws lfcam::Error.
  CaptureRecord Save(CaptureRecord record, std::string_view jpeg);
  std::vector<CaptureRecord> List() const;
  std::optional<CaptureRecord> Find(std::string_view id) const;
  std::filesystem::path ImagePath(std::string_view id) const;
  bool Remove(std::string_view id);
  std::size_t count() const;
  // Bytes free for an unprivileged writer on the folder's file system.
  std::uint64_t FreeBytes() const;

 private:
  std::filesystem::path folder_;
  mutable std::mutex mutex_;
};

}  // namespace lfcam
