#include "lfcam/core/input_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "lfcam/core/error.h"
#include "lfcam/core/limits.h"

namespace lfcam {
namespace {

std::string Kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(const std::filesystem::path& path) : name_(path.string()) {
  // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd_ < 0) {
    const int e = errno;
    throw Error(
        fmt::format("{}: cannot open: {}", name_, e == ENOENT ? "no such file" : std::strerror(e)));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    const std::string kind = Kind(st.st_mode);
    ::close(fd_);
    throw Error(fmt::format("{}: is {}, not a regular file", name_, kind));
  }
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
  size_ = std::uint64_t(st.st_size);
}

InputFile::~InputFile() { ::close(fd_); }

void InputFile::read_exactly(void* out, std::size_t size, std::uint64_t offset) const {
  auto* p = static_cast<std::uint8_t*>(out);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd_, p + done, size - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw Error(
          fmt::format("{}: read failed at byte {}: {}", name_, offset + done,
                      n == 0 ? "unexpected end of file (truncated?)" : std::strerror(errno)));
    done += std::size_t(n);
  }
}

std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path, std::uint64_t max_bytes,
                                        const std::string& what) {
  const InputFile file(path);
  if (file.size() > max_bytes)
    throw Error(fmt::format("{}: {} of {} is larger than the limit of {}", file.name(), what,
                            HumanBytes(double(file.size())), HumanBytes(double(max_bytes))));
  std::vector<std::uint8_t> bytes(file.size());
  file.read_exactly(bytes.data(), bytes.size(), 0);
  return bytes;
}

}  // namespace lfcam
