#pragma once
// The captures a node holds, in one folder: IMAGE ID.jpg and its record ID.json (what was asked,
// when it fired, the settings, size and SHA-256). Both are written to a temporary name and
// renamed, so a node that dies mid-write holds no half image; records survive a restart.
// A recording (node/recording.h) is ID.mjpeg, its frame index ID.frames.jsonl and its record;
// one that a dead node left "recording" is closed as "truncated" when the store opens again.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lfcam/node/recording.h"

namespace lfcam {

// A capture id: 1..64 of [A-Za-z0-9_.-], not starting with '.', so that it names a file in the
// capture folder and nothing outside it.
bool IsValidCaptureId(std::string_view id);

struct CaptureRecord {
  std::string id;
  std::string kind, shot;                // what the host asked for ("scene", "scene")
  std::int64_t requested_unix_ns = 0;    // the trigger time T
  std::int64_t trigger_unix_ns = 0;      // when the node fired (its clock)
  nlohmann::json settings;               // the settings in force
  std::uint64_t size = 0;                // the image's or the stream's (0 while recording)
  std::string sha256;                    // empty while recording
  std::optional<VideoRecordInfo> video;  // a recording's
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
  // The image, or a recording's stream.
  std::filesystem::path DataPath(const CaptureRecord& record) const;

  // A recording being written: frames go to the stream and then the index, one by one.
  class Recording {
   public:
    ~Recording();
    Recording(const Recording&) = delete;
    Recording& operator=(const Recording&) = delete;
    // Appends a frame (its offset and size are filled in here). Throws lfcam::Error.
    void Append(VideoFrameEntry entry, std::string_view jpeg);
    std::int64_t frames() const { return frames_; }
    // Closes the stream and writes the record as "complete", "truncated" or "failed" (with
    // the reason), with the stream's size and SHA-256.
    CaptureRecord Finish(const std::string& status, const std::string& reason);

   private:
    friend class CaptureStore;
    Recording(CaptureStore& store, CaptureRecord record);
    CaptureStore& store_;
    CaptureRecord record_;
    std::FILE* stream_ = nullptr;
    std::FILE* index_ = nullptr;
    std::uint64_t bytes_ = 0;
    std::int64_t frames_ = 0;
  };
  // Starts a recording of `record` (its video info set): the record is written "recording".
  std::unique_ptr<Recording> BeginRecording(CaptureRecord record);
  // A recording's frames as its index lists them (bytes all in the stream).
  std::vector<VideoFrameEntry> Frames(const CaptureRecord& record) const;
  bool Remove(std::string_view id);
  std::size_t count() const;
  // Bytes free for an unprivileged writer on the folder's file system.
  std::uint64_t FreeBytes() const;

 private:
  std::filesystem::path folder_;
  mutable std::mutex mutex_;
};

}  // namespace lfcam
