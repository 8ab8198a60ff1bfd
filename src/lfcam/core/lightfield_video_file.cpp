#include "lfcam/core/lightfield_video_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>
#include <xxhash.h>

#include <array>
#include <bit>
#include <cerrno>
#include <cstring>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the video file is little-endian; this build assumes a little-endian machine");

constexpr std::array<std::uint8_t, 8> kVideoMagic = {0x89, 'L', 'F', 'V', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::array<std::uint8_t, 8> kStillMagic = {0x89, 'L', 'F', 'C', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::array<std::uint8_t, 8> kFrameMagic = {'L', 'F', 'V', 'F', 'R', 'A', 'M', 'E'};
constexpr std::size_t kVideoPreambleBytes = 64, kFrameRecordBytes = 64;
constexpr std::uint64_t kFrameAlignment = 4096;
constexpr std::uint32_t kVideoComplete = 1;

std::uint64_t RoundUpToFrame(std::uint64_t x) {
  return (x + kFrameAlignment - 1) / kFrameAlignment * kFrameAlignment;
}

template <typename T>
void Put(std::uint8_t* out, T value) {
  std::memcpy(out, &value, sizeof(T));
}
template <typename T>
T Get(const std::uint8_t* in) {
  T value;
  std::memcpy(&value, in, sizeof(T));
  return value;
}

void WriteVideoAt(int fd, const void* data, std::size_t size, std::uint64_t offset,
                  const std::filesystem::path& path) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, p, size, off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw Error(fmt::format("{}: cannot write: {}", path.string(), std::strerror(errno)));
    p += n;
    size -= std::size_t(n);
    offset += std::uint64_t(n);
  }
}

nlohmann::json VideoHeaderToJson(const LightFieldVideoHeader& h) {
  return {{"format", "lfcam-lightfield-video"},
          {"version", kLightFieldVideoVersion},
          {"fps", h.fps},
          {"frames_planned", h.frames_planned},
          {"start_unix_ns", h.start_unix_ns},
          {"frame_format", "lfcam-lightfield (.lf), views zstd-compressed"},
          {"metadata", h.metadata}};
}

LightFieldVideoHeader VideoHeaderFromJson(const nlohmann::json& j, const std::string& where) {
  if (JsonString(j, "format", where) != "lfcam-lightfield-video")
    throw Error(where + ": format is not lfcam-lightfield-video");
  LightFieldVideoHeader h;
  h.fps = JsonNumber(j, "fps", where);
  if (!(h.fps > 0 && h.fps <= 100000))
    throw Error(fmt::format("{}: fps {} is out of range", where, h.fps));
  h.frames_planned = JsonInteger(j, "frames_planned", 0, std::int64_t(1) << 40, where);
  h.start_unix_ns = JsonInteger(j, "start_unix_ns", 0, INT64_MAX, where);
  h.metadata = j.value("metadata", nlohmann::json::object());
  if (!h.metadata.is_object()) throw Error(where + ": metadata must be a JSON object");
  return h;
}

// A frame record's fields, checksummed.
std::array<std::uint8_t, kFrameRecordBytes> FrameRecord(const VideoFrameInfo& f) {
  std::array<std::uint8_t, kFrameRecordBytes> r{};
  std::copy(kFrameMagic.begin(), kFrameMagic.end(), r.begin());
  Put<std::int64_t>(&r[8], f.index);
  Put<std::int64_t>(&r[16], f.time_ns);
  Put<std::int64_t>(&r[24], f.spread_ns.value_or(-1));
  Put<std::uint64_t>(&r[32], f.bytes);
  Put<std::uint64_t>(&r[48], XXH3_64bits(r.data(), 48));
  return r;
}

}  // namespace

LightFieldVideoWriter::LightFieldVideoWriter(const std::filesystem::path& path,
                                             const LightFieldVideoHeader& header)
    : path_(path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error(fmt::format("{}: exists and is not a regular file", path.string()));
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw Error(fmt::format("{}: cannot create: {}", path.string(), std::strerror(errno)));
  try {
    const std::string text = JsonToText(VideoHeaderToJson(header), 1);
    std::array<std::uint8_t, kVideoPreambleBytes> pre{};
    std::copy(kVideoMagic.begin(), kVideoMagic.end(), pre.begin());
    Put<std::uint32_t>(&pre[8], kLightFieldVideoVersion);
    Put<std::uint32_t>(&pre[12], 0);
    Put<std::uint64_t>(&pre[16], text.size());
    Put<std::uint64_t>(&pre[24], XXH3_64bits(text.data(), text.size()));
    position_ = RoundUpToFrame(kVideoPreambleBytes + text.size());
    Put<std::uint64_t>(&pre[32], position_);
    Put<std::uint64_t>(&pre[40], 0);
    WriteVideoAt(fd_, pre.data(), pre.size(), 0, path_);
    WriteVideoAt(fd_, text.data(), text.size(), kVideoPreambleBytes, path_);
  } catch (...) {
    ::close(fd_);
    ::unlink(path_.c_str());
    fd_ = -1;
    throw;
  }
}

LightFieldVideoWriter::~LightFieldVideoWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  if (!finished_) ::unlink(path_.c_str());
}

void LightFieldVideoWriter::Append(const LightField& frame, const VideoFrameInfo& info,
                                   const LightFieldWriteOptions& options) {
  if (fd_ < 0 || finished_) throw Error(fmt::format("{}: the video is closed", path_.string()));
  if (info.index != frames_)
    throw Error(fmt::format("{}: frame {} appended where frame {} is due", path_.string(),
                            info.index, frames_));
  const std::vector<std::uint8_t> bytes =
      EncodeLightField(frame, fmt::format("{} frame {}", path_.string(), info.index), options);
  VideoFrameInfo f = info;
  f.offset = position_ + kFrameRecordBytes;
  f.bytes = bytes.size();
  // The frame's light field first, its record after: a reader never sees a record whose bytes
  // are not all there.
  WriteVideoAt(fd_, bytes.data(), bytes.size(), f.offset, path_);
  const auto record = FrameRecord(f);
  WriteVideoAt(fd_, record.data(), record.size(), position_, path_);
  ++frames_;
  std::uint8_t count[8];
  Put<std::uint64_t>(count, std::uint64_t(frames_));
  WriteVideoAt(fd_, count, sizeof count, 40, path_);
  position_ = RoundUpToFrame(f.offset + f.bytes);
}

void LightFieldVideoWriter::Finish() {
  if (fd_ < 0 || finished_) return;
  if (::fdatasync(fd_) != 0)
    throw Error(fmt::format("{}: cannot flush: {}", path_.string(), std::strerror(errno)));
  std::uint8_t flags[4];
  Put<std::uint32_t>(flags, kVideoComplete);
  WriteVideoAt(fd_, flags, sizeof flags, 12, path_);
  if (::close(fd_) != 0)
    throw Error(fmt::format("{}: cannot close: {}", path_.string(), std::strerror(errno)));
  fd_ = -1;
  finished_ = true;
}

LightField ReadLightFieldFrame(const std::filesystem::path& path, std::size_t frame,
                               const LightFieldReadOptions& options) {
  if (!IsLightFieldVideo(path)) {
    if (frame != 0)
      throw Error(fmt::format("{}: a still light field has frame 0 only, not frame {}",
                              path.string(), frame));
    return ReadLightField(path, options);
  }
  return LightFieldVideo(path).ReadFrame(frame, options);
}

bool IsLightFieldVideo(const std::filesystem::path& path) {
  try {
    const InputFile file(path);
    if (file.size() < kVideoMagic.size()) return false;
    std::array<std::uint8_t, 8> magic{};
    file.read_exactly(magic.data(), magic.size(), 0);
    return magic == kVideoMagic;
  } catch (const Error&) {
    return false;
  }
}

LightFieldVideo::LightFieldVideo(const std::filesystem::path& path) : path_(path) { Refresh(); }

std::uint64_t LightFieldVideo::file_bytes() const { return file_->size(); }

void LightFieldVideo::Refresh() {
  file_ = std::make_unique<InputFile>(path_);
  const InputFile& f = *file_;
  const std::string& name = f.name();
  if (f.size() < 8)
    throw Error(
        fmt::format("{}: too short to be a light field or a video ({} bytes)", name, f.size()));
  std::array<std::uint8_t, 8> magic{};
  f.read_exactly(magic.data(), magic.size(), 0);
  if (magic == kStillMagic) {
    // A still: a video of one frame.
    const LightFieldHeader h = ReadLightFieldHeader(f, {0, f.size(), name});
    video_ = false;
    complete_ = true;
    header_ = {};
    header_.fps = 0;
    header_.frames_planned = 1;
    header_.metadata = h.metadata;
    frames_ = {{0, 0, std::nullopt, 0, f.size()}};
    return;
  }
  if (magic != kVideoMagic)
    throw Error(
        fmt::format("{}: neither a light field nor a light field video (bad magic bytes)", name));
  video_ = true;
  if (f.size() < kVideoPreambleBytes)
    throw Error(fmt::format("{}: truncated: {} bytes, the preamble needs {}", name, f.size(),
                            kVideoPreambleBytes));
  std::array<std::uint8_t, kVideoPreambleBytes> pre{};
  f.read_exactly(pre.data(), pre.size(), 0);
  const auto version = Get<std::uint32_t>(&pre[8]);
  if (version != kLightFieldVideoVersion)
    throw Error(fmt::format("{}: video format version {} is not supported (this build reads {})",
                            name, version, kLightFieldVideoVersion));
  complete_ = (Get<std::uint32_t>(&pre[12]) & kVideoComplete) != 0;
  const auto header_bytes = Get<std::uint64_t>(&pre[16]);
  const auto header_xxh3 = Get<std::uint64_t>(&pre[24]);
  first_frame_ = Get<std::uint64_t>(&pre[32]);
  if (header_bytes == 0 || header_bytes > kMaxJsonBytes ||
      kVideoPreambleBytes + header_bytes > f.size())
    throw Error(fmt::format("{}: header of {} bytes does not fit the file ({} bytes)", name,
                            header_bytes, f.size()));
  if (first_frame_ < kVideoPreambleBytes + header_bytes || first_frame_ % kFrameAlignment != 0)
    throw Error(
        fmt::format("{}: the first frame's offset {} is not after the header on a "
                    "{}-byte boundary",
                    name, first_frame_, kFrameAlignment));
  std::string text(header_bytes, '\0');
  f.read_exactly(text.data(), text.size(), kVideoPreambleBytes);
  if (XXH3_64bits(text.data(), text.size()) != header_xxh3)
    throw Error(fmt::format("{}: header checksum mismatch (the header is corrupt)", name));
  header_ = VideoHeaderFromJson(ParseJsonBounded(text, name + ": header"), name + ": header");

  // The frames: record after record, each whole before it counts.
  frames_.clear();
  std::uint64_t at = first_frame_;
  while (at + kFrameRecordBytes <= f.size()) {
    std::array<std::uint8_t, kFrameRecordBytes> r{};
    f.read_exactly(r.data(), r.size(), at);
    const std::int64_t k = std::int64_t(frames_.size());
    const bool ok = std::equal(kFrameMagic.begin(), kFrameMagic.end(), r.begin()) &&
                    Get<std::uint64_t>(&r[48]) == XXH3_64bits(r.data(), 48);
    if (!ok) {
      // A record not yet written (zeros), or half written, while the file is still being
      // written; in a complete file, a corrupt one.
      if (!complete_) break;
      throw Error(fmt::format("{}: frame {}'s record at byte {} is corrupt", name, k, at));
    }
    VideoFrameInfo info;
    info.index = Get<std::int64_t>(&r[8]);
    info.time_ns = Get<std::int64_t>(&r[16]);
    const auto spread = Get<std::int64_t>(&r[24]);
    if (spread >= 0) info.spread_ns = spread;
    info.bytes = Get<std::uint64_t>(&r[32]);
    info.offset = at + kFrameRecordBytes;
    if (info.index != k)
      throw Error(fmt::format("{}: the record at byte {} is frame {}, frame {} is due", name, at,
                              info.index, k));
    if (spread < -1 || info.bytes == 0 || info.bytes > f.size() - info.offset)
      throw Error(
          fmt::format("{}: frame {}'s record (at byte {}, {} bytes) does not fit the "
                      "file ({} bytes): truncated?",
                      name, k, at, info.bytes, f.size()));
    if (!frames_.empty() && info.time_ns <= frames_.back().time_ns)
      throw Error(fmt::format("{}: frame {}'s time is not after frame {}'s", name, k, k - 1));
    frames_.push_back(info);
    at = RoundUpToFrame(info.offset + info.bytes);
  }
  if (complete_ && at < f.size())
    throw Error(fmt::format("{}: {} bytes after the last frame ({}) are no frame", name,
                            f.size() - at, frames_.size()));
}

const VideoFrameInfo& LightFieldVideo::frame(std::size_t k) const {
  if (k >= frames_.size())
    throw Error(fmt::format("{}: there is no frame {} ({} frame{}{})", path_.string(), k,
                            frames_.size(), frames_.size() == 1 ? "" : "s",
                            complete_ ? "" : " so far: the video is still being written"));
  return frames_[k];
}

LightField LightFieldVideo::ReadFrame(std::size_t k, const LightFieldReadOptions& options) const {
  const VideoFrameInfo& f = frame(k);
  if (!video_) return ReadLightField(*file_, {0, f.bytes, file_->name()}, options);
  LightFieldReadOptions read = options;
  read.memory_map = false;
  return ReadLightField(*file_, {f.offset, f.bytes, fmt::format("{} frame {}", file_->name(), k)},
                        read);
}

LightFieldHeader LightFieldVideo::FrameHeader(std::size_t k) const {
  const VideoFrameInfo& f = frame(k);
  return ReadLightFieldHeader(
      *file_,
      {f.offset, f.bytes, video_ ? fmt::format("{} frame {}", file_->name(), k) : file_->name()});
}

}  // namespace lfcam
