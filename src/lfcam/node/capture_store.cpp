#include "lfcam/node/capture_store.h"

#include <fmt/format.h>
#include <sys/statvfs.h>

#include <algorithm>

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
  return {{"id", r.id},
          {"kind", r.kind},
          {"shot", r.shot},
          {"requested_unix_ns", r.requested_unix_ns},
          {"trigger_unix_ns", r.trigger_unix_ns},
          {"settings", r.settings},
          {"size", r.size},
          {"sha256", r.sha256}};
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
  if (r.sha256.size() != 64) throw Error(fmt::format("{}: sha256 must be 64 hex digits", where));
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
}

fs::path CaptureStore::ImagePath(std::string_view id) const {
  if (!IsValidCaptureId(id)) throw Error(fmt::format("bad capture id '{}'", id));
  return folder_ / (std::string(id) + ".jpg");
}

CaptureRecord CaptureStore::Save(CaptureRecord record, std::string_view jpeg) {
  record.size = jpeg.size();
  record.sha256 = Sha256Hex(jpeg);
  const fs::path image = ImagePath(record.id);
  const std::string text = RecordToJson(record).dump(2) + "\n";
  std::lock_guard lock(mutex_);
  WriteFileAtomically(image, {reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()});
  WriteFileAtomically(folder_ / (record.id + ".json"),
                      {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  return record;
}

std::optional<CaptureRecord> CaptureStore::Find(std::string_view id) const {
  if (!IsValidCaptureId(id)) return std::nullopt;
  const fs::path path = folder_ / (std::string(id) + ".json");
  std::lock_guard lock(mutex_);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || !fs::is_regular_file(ImagePath(id), ec))
    return std::nullopt;
  try {
    const auto bytes = ReadFileBytes(path, 1 << 20, "capture record");
    return RecordFromJson(
        ParseJsonBounded({reinterpret_cast<const char*>(bytes.data()), bytes.size()},
                         path.string()),
        path.string());
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
  return had;
}

std::size_t CaptureStore::count() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder_, ec)) {
    const fs::path& p = entry.path();
    n += p.extension() == ".json" && IsValidCaptureId(p.stem().string()) &&
         fs::is_regular_file(folder_ / (p.stem().string() + ".jpg"), ec);
  }
  return n;
}

std::uint64_t CaptureStore::FreeBytes() const {
  struct statvfs st {};
  if (::statvfs(folder_.c_str(), &st) != 0) return 0;
  return std::uint64_t(st.f_bavail) * st.f_frsize;
}

}  // namespace lfcam
