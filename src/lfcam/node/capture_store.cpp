#include "lfcam/node/capture_store.h"

#include <fmt/format.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/node/request_signature.h"

namespace lfcam {

namespace fs = std::filesystem;

bool IsValidCaptureId(std::string_view id) {
  if (id.empty() || id.size() > 64 || id.front() == '.') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

nlohmann::json RecordToJson(const CaptureRecord& r) {
  nlohmann::json j = {{"id", r.id},
                      {"kind", r.kind},
                      {"shot", r.shot},
                      {"requested_unix_ns", r.requested_unix_ns},
                      {"trigger_unix_ns", r.trigger_unix_ns},
                      {"settings", r.settings},
                      {"size", r.size},
                      {"sha256", r.sha256}};
  if (r.video) j["video"] = VideoInfoToJson(*r.video);
  return j;
}

CaptureRecord RecordFromJson(const nlohmann::json& j, const std::string& where) {
  CaptureRecord r;
  r.id = JsonString(j, "id", where);
  if (!IsValidCaptureId(r.id)) throw Error(fmt::format("{}: bad capture id '{}'", where, r.id));
  r.kind = JsonString(j, "kind", where);
  r.shot = JsonString(j, "shot", where);
  r.requested_unix_ns = JsonInteger(j, "requested_unix_ns", 0, INT64_MAX, where);
  r.trigger_unix_ns = JsonInteger(j, "trigger_unix_ns", 0, INT64_MAX, where);
  r.settings = JsonField(j, "settings", where);
  r.size = JsonUnsigned(j, "size", UINT64_MAX, where);
  r.sha256 = JsonString(j, "sha256", where);
  if (j.contains("video"))
    r.video = VideoInfoFromJson(JsonField(j, "video", where), where + ": video");
  const bool recording = r.video && r.video->status == "recording";
  if (r.sha256.size() != (recording ? 0 : 64))
    throw Error(fmt::format("{}: sha256 must be 64 hex digits", where));
  return r;
}

CaptureStore::CaptureStore(fs::path folder) : folder_(std::move(folder)) {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec || !fs::is_directory(folder_))
    throw Error(fmt::format("{}: cannot use as the capture folder: {}", folder_.string(),
                            ec ? ec.message() : "not a directory"));
  // Temporaries of a writer that died ("NAME.tmp-PID-..."): atomic_file's naming.
  for (const auto& entry : fs::directory_iterator(folder_, ec)) {
    const std::string name = entry.path().filename().string();
    const auto dot = name.find(".tmp-");
    if (dot == std::string::npos) continue;
    const auto owner = TemporaryOwner(name, name.substr(0, dot));
    if (owner && ProcessIsGone(*owner)) fs::remove(entry.path(), ec);
  }
  // Recordings a node that died left open: closed with the frames that reached the disk.
  for (CaptureRecord& r : List())
    if (r.video && r.video->status == "recording") {
      const auto frames = Frames(r);
      std::error_code size_ec;
      if (!frames.empty())
        fs::resize_file(DataPath(r), frames.back().offset + frames.back().size, size_ec);
      Recording closing(*this, std::move(r));
      closing.bytes_ = frames.empty() ? 0 : frames.back().offset + frames.back().size;
      closing.frames_ = std::int64_t(frames.size());
      closing.Finish(frames.empty() ? "failed" : "truncated",
                     fmt::format("the node stopped mid-recording ({} frames kept)", frames.size()));
    }
}

fs::path CaptureStore::DataPath(const CaptureRecord& record) const {
  if (!record.video) return ImagePath(record.id);
  if (!IsValidCaptureId(record.id)) throw Error(fmt::format("bad capture id '{}'", record.id));
  return folder_ / (record.id + ".mjpeg");
}

namespace {

fs::path IndexPath(const fs::path& folder, const std::string& id) {
  return folder / (id + ".frames.jsonl");
}

void WriteRecord(const fs::path& folder, const CaptureRecord& record) {
  const std::string text = RecordToJson(record).dump(2) + "\n";
  WriteFileAtomically(folder / (record.id + ".json"),
                      {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

}  // namespace

CaptureStore::Recording::Recording(CaptureStore& store, CaptureRecord record)
    : store_(store), record_(std::move(record)) {}

CaptureStore::Recording::~Recording() {
  if (stream_) std::fclose(stream_);
  if (index_) std::fclose(index_);
}

std::unique_ptr<CaptureStore::Recording> CaptureStore::BeginRecording(CaptureRecord record) {
  if (!record.video) throw Error("a recording needs its video settings");
  record.video->status = "recording";
  record.video->frames = 0;
  record.size = 0;
  record.sha256.clear();
  std::unique_ptr<Recording> r(new Recording(*this, std::move(record)));
  const fs::path stream = DataPath(r->record_), index = IndexPath(folder_, r->record_.id);
  std::lock_guard lock(mutex_);
  r->stream_ = std::fopen(stream.c_str(), "wb");
  r->index_ = std::fopen(index.c_str(), "wb");
  if (!r->stream_ || !r->index_)
    throw Error(
        fmt::format("{}: cannot write the recording: {}", stream.string(), std::strerror(errno)));
  WriteRecord(folder_, r->record_);
  return r;
}

void CaptureStore::Recording::Append(VideoFrameEntry entry, std::string_view jpeg) {
  if (!stream_) throw Error("the recording is closed");
  entry.offset = bytes_;
  entry.size = jpeg.size();
  const std::string line = FrameIndexLine(entry);
  // The frame's bytes reach the file before the index names them.
  if (std::fwrite(jpeg.data(), 1, jpeg.size(), stream_) != jpeg.size() ||
      std::fflush(stream_) != 0 ||
      std::fwrite(line.data(), 1, line.size(), index_) != line.size() || std::fflush(index_) != 0)
    throw Error(fmt::format("{}: cannot append frame {}: {}", record_.id, entry.sequence,
                            std::strerror(errno)));
  bytes_ += jpeg.size();
  ++frames_;
}

CaptureRecord CaptureStore::Recording::Finish(const std::string& status,
                                              const std::string& reason) {
  if (stream_) std::fclose(stream_);
  if (index_) std::fclose(index_);
  stream_ = index_ = nullptr;
  record_.video->status = status;
  record_.video->frames = frames_;
  record_.video->reason = reason;
  record_.size = bytes_;
  record_.sha256 = Sha256OfFile(store_.DataPath(record_));
  std::lock_guard lock(store_.mutex_);
  WriteRecord(store_.folder_, record_);
  return record_;
}

std::vector<VideoFrameEntry> CaptureStore::Frames(const CaptureRecord& record) const {
  if (!record.video) return {};
  const fs::path index = IndexPath(folder_, record.id);
  std::error_code ec;
  const std::uint64_t stream_size = fs::file_size(DataPath(record), ec);
  if (ec) return {};
  const auto bytes = ReadFileBytes(index, std::uint64_t(1) << 30, "frame index");
  return ParseFrameIndex({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, stream_size,
                         index.string());
}

fs::path CaptureStore::ImagePath(std::string_view id) const {
  if (!IsValidCaptureId(id)) throw Error(fmt::format("bad capture id '{}'", id));
  return folder_ / (std::string(id) + ".jpg");
}

CaptureRecord CaptureStore::Save(CaptureRecord record, std::string_view jpeg) {
  record.size = jpeg.size();
  record.sha256 = Sha256Hex(jpeg);
  const fs::path image = ImagePath(record.id);
  std::lock_guard lock(mutex_);
  WriteFileAtomically(image, {reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()});
  WriteRecord(folder_, record);
  return record;
}

std::optional<CaptureRecord> CaptureStore::Find(std::string_view id) const {
  if (!IsValidCaptureId(id)) return std::nullopt;
  const fs::path path = folder_ / (std::string(id) + ".json");
  std::lock_guard lock(mutex_);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  try {
    const auto bytes = ReadFileBytes(path, 1 << 20, "capture record");
    CaptureRecord record =
        RecordFromJson(ParseJsonBounded({reinterpret_cast<const char*>(bytes.data()), bytes.size()},
                                        path.string()),
                       path.string());
    if (!fs::is_regular_file(DataPath(record), ec)) return std::nullopt;
    return record;
  } catch (const Error&) {
    return std::nullopt;  // a damaged record: the capture is not offered
  }
}

std::vector<CaptureRecord> CaptureStore::List() const {
  std::vector<std::string> ids;
  {
    std::lock_guard lock(mutex_);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder_, ec)) {
      const fs::path& p = entry.path();
      if (p.extension() == ".json" && IsValidCaptureId(p.stem().string()))
        ids.push_back(p.stem().string());
    }
  }
  std::sort(ids.begin(), ids.end());
  std::vector<CaptureRecord> out;
  for (const std::string& id : ids)
    if (auto r = Find(id)) out.push_back(std::move(*r));
  return out;
}

bool CaptureStore::Remove(std::string_view id) {
  if (!IsValidCaptureId(id)) return false;
  std::lock_guard lock(mutex_);
  std::error_code ec;
  const bool had = fs::remove(folder_ / (std::string(id) + ".json"), ec);
  fs::remove(ImagePath(id), ec);
  fs::remove(folder_ / (std::string(id) + ".mjpeg"), ec);
  fs::remove(IndexPath(folder_, std::string(id)), ec);
  return had;
}

std::size_t CaptureStore::count() const { return List().size(); }

std::uint64_t CaptureStore::FreeBytes() const {
  struct statvfs st {};
  if (::statvfs(folder_.c_str(), &st) != 0) return 0;
  return std::uint64_t(st.f_bavail) * st.f_frsize;
}

}  // namespace lfcam
