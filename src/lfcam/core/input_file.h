#pragma once
// A file opened for reading that is known to be a regular file: FIFOs, devices, sockets and
// directories are refused without blocking (the open is non-blocking, the type is checked on
// the open descriptor, so nothing can swap the file in between). Errors name the file.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lfcam {

class InputFile {
 public:
  explicit InputFile(const std::filesystem::path& path);  // throws lfcam::Error
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  int fd() const { return fd_; }
  std::uint64_t size() const { return size_; }
  const std::string& name() const { return name_; }

  // Exactly `size` bytes at `offset`, or an error naming the file and the offset.
  void read_exactly(void* out, std::size_t size, std::uint64_t offset) const;

 private:
  std::string name_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// The whole of a regular file, refused (naming `what` and the limit) when it is larger than
// max_bytes.
std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path, std::uint64_t max_bytes,
                                        const std::string& what);

}  // namespace lfcam
