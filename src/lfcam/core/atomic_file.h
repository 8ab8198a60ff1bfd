#pragma once
// Writes a file so that readers never see it half-written: the bytes go to a temporary name in
// the same directory, are flushed, and the file is renamed into place on commit(). A writer
// destroyed without commit() removes its temporary file.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

namespace lfcam {

class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::filesystem::path& path);  // throws lfcam::Error
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(const void* data, std::size_t size);
  void write(std::span<const std::uint8_t> bytes) { write(bytes.data(), bytes.size()); }
  void pad_to(std::size_t offset);  // zero bytes up to `offset`
  std::size_t position() const { return position_; }
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  std::FILE* file_ = nullptr;
  std::size_t position_ = 0;
};

// Convenience: write a whole byte string atomically.
void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace lfcam
