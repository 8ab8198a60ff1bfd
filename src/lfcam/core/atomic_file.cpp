#include "lfcam/core/atomic_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {

bool ProcessIsGone(long pid) { return pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH; }
namespace {

std::string Reason(int error_number) { return std::strerror(error_number); }

std::filesystem::path DirectoryOf(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

// Removes NAME.tmp-PID files whose writer no longer runs.
void RemoveStaleTemporaries(const std::filesystem::path& path) {
  std::error_code ec;
  const std::string target = path.filename().string();
  for (std::filesystem::directory_iterator it(DirectoryOf(path), ec), end; !ec && it != end;
       it.increment(ec)) {
    const auto owner = TemporaryOwner(it->path().filename().string(), target);
    if (owner && ProcessIsGone(*owner)) std::filesystem::remove(it->path(), ec);
  }
}

}  // namespace

std::optional<long> TemporaryOwner(const std::string& name, const std::string& target_name) {
  const std::string prefix = target_name + ".tmp-";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0)
    return std::nullopt;
  long pid = 0;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size();
  const auto [end, error] = std::from_chars(first, last, pid);
  if (error != std::errc() || end != last) return std::nullopt;
  return pid;
}

AtomicFileWriter::AtomicFileWriter(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(fmt::format("{}: is a directory, not a file to write", path.string()));
  RemoveStaleTemporaries(path);
  temp_path_ = path;
  temp_path_ += fmt::format(".tmp-{}", ::getpid());
  registration_ = std::make_unique<TemporaryFileRegistration>(temp_path_);
  const int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT)
      throw Error(fmt::format("{}: cannot create: directory {} does not exist", path.string(),
                              DirectoryOf(path).string()));
    throw Error(fmt::format("{}: cannot create: {}", path.string(), Reason(e)));
  }
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int e = errno;
    ::close(fd);
    ::unlink(temp_path_.c_str());
    throw Error(fmt::format("{}: cannot create: {}", path.string(), Reason(e)));
  }
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_) std::fclose(file_);
  if (!committed_) ::unlink(temp_path_.c_str());
}

void AtomicFileWriter::write(const void* data, std::size_t size) {
  if (size == 0) return;
  if (!file_) throw Error(fmt::format("{}: internal: write after stage", path_.string()));
  if (std::fwrite(data, 1, size, file_) != size)
    throw Error(fmt::format("{}: write failed: {}", path_.string(), Reason(errno)));
  position_ += size;
}

void AtomicFileWriter::pad_to(std::size_t offset) {
  if (offset < position_) throw Error(fmt::format("{}: internal: pad backwards", path_.string()));
  const std::vector<std::uint8_t> zeros(offset - position_, 0);
  write(zeros.data(), zeros.size());
}

void AtomicFileWriter::stage() {
  if (staged_) return;
  errno = 0;
  int error_number = 0;
  if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) error_number = errno;
  if (std::fclose(file_) != 0 && error_number == 0) error_number = errno;
  file_ = nullptr;
  if (error_number != 0)
    throw Error(fmt::format("{}: write failed: {}", path_.string(), Reason(error_number)));
  staged_ = true;
}

void AtomicFileWriter::commit() {
  stage();
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0)
    throw Error(fmt::format("{}: cannot move the finished file into place: {}", path_.string(),
                            Reason(errno)));
  committed_ = true;
}

void CommitAll(std::span<const std::unique_ptr<AtomicFileWriter>> writers) {
  for (const auto& w : writers) w->stage();
  for (const auto& w : writers) w->commit();
}

void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  AtomicFileWriter writer(path);
  writer.write(bytes);
  writer.commit();
}

void RequireWritableOutput(const std::filesystem::path& path, const std::string& flag) {
  const std::string where =
      flag.empty() ? path.string() : fmt::format("{} {}", flag, path.string());
  if (path.empty()) throw UsageError(fmt::format("{}: the output path is empty", flag));
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw UsageError(fmt::format("{}: is a directory, not a file to write", where));
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw UsageError(fmt::format("{}: exists and is not a regular file", where));
  const auto directory = DirectoryOf(path);
  if (!std::filesystem::is_directory(directory, ec))
    throw UsageError(
        fmt::format("{}: cannot write: directory {} does not exist", where, directory.string()));
  // Creating a file is the only test that tells the truth (permissions, read-only mounts, root).
  auto probe = path;
  probe += fmt::format(".tmp-{}", ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int e = errno;
    if (e != EEXIST)
      throw UsageError(
          fmt::format("{}: cannot write in {}: {}", where, directory.string(), Reason(e)));
    return;
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace lfcam
