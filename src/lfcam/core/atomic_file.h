#pragma once
// Writes a file so that readers never see it half-written: the bytes go to a temporary name in
// the same directory (NAME.tmp-PID), are flushed, and the file is renamed into place on
// commit(). A writer destroyed without commit() removes its temporary file, and so does a
// SIGINT, SIGTERM or SIGHUP (core/signal_cleanup.h). A temporary left by a process that no
// longer runs (SIGKILL, power loss) is removed by the next write to the same name.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "lfcam/core/signal_cleanup.h"

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
  const std::filesystem::path& path() const { return path_; }
  // Flushes and closes the temporary file (the data is on disk, under its temporary name).
  void stage();
  // Stages if needed, then renames the temporary file into place.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  std::FILE* file_ = nullptr;
  std::size_t position_ = 0;
  bool staged_ = false, committed_ = false;
  std::unique_ptr<TemporaryFileRegistration> registration_;
};

// Several outputs of one command, all or none: each is staged first, and only when every one
// is on disk are they renamed into place.
void CommitAll(std::span<const std::unique_ptr<AtomicFileWriter>> writers);

// Convenience: write a whole byte string atomically.
void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

// Checks, before any work, that `path` can be written: its directory exists and lets a file be
// created there (tried, then removed), and the path is not a directory. Throws lfcam::UsageError
// naming `flag` and the path.
void RequireWritableOutput(const std::filesystem::path& path, const std::string& flag);

// Whether no process with this id runs (a temporary it owned is stale).
bool ProcessIsGone(long pid);

// The process id in a temporary name "NAME.tmp-PID", if `name` is one for `target_name`.
std::optional<long> TemporaryOwner(const std::string& name, const std::string& target_name);

}  // namespace lfcam
