#include "lfcam/core/atomic_file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {

AtomicFileWriter::AtomicFileWriter(const std::filesystem::path& path) : path_(path) {
  temp_path_ = path;
  temp_path_ += fmt::format(".tmp-{}", ::getpid());
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (!file_)
    throw Error(fmt::format("{}: cannot create: {}", path.string(), std::strerror(errno)));
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_) {
    std::fclose(file_);
    std::error_code ec;
    std::filesystem::remove(temp_path_, ec);
  }
}

void AtomicFileWriter::write(const void* data, std::size_t size) {
  if (size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size)
    throw Error(fmt::format("{}: write failed: {}", path_.string(), std::strerror(errno)));
  position_ += size;
}

void AtomicFileWriter::pad_to(std::size_t offset) {
  if (offset < position_) throw Error(fmt::format("{}: internal: pad backwards", path_.string()));
  const std::vector<std::uint8_t> zeros(offset - position_, 0);
  write(zeros.data(), zeros.size());
}

void AtomicFileWriter::commit() {
  const bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  std::error_code ec;
  if (!flushed || !closed) {
    std::filesystem::remove(temp_path_, ec);
    throw Error(fmt::format("{}: write failed: {}", path_.string(), std::strerror(errno)));
  }
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) {
    std::filesystem::remove(temp_path_, ec);
    throw Error(fmt::format("{}: cannot rename into place: {}", path_.string(), ec.message()));
  }
}

void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  AtomicFileWriter writer(path);
  writer.write(bytes);
  writer.commit();
}

}  // namespace lfcam
