#pragma once
// What lfcam does when a signal ends it. With InstallSignalCleanup() (the CLI calls it first
// thing):
//   SIGINT, SIGTERM, SIGHUP: every temporary file registered below is removed, then the process
//     dies of the same signal, as it would have (exit status 128 + N in a shell);
//   SIGBUS inside a registered file mapping (the file was truncated while it was in use):
//     "lfcam: error: FILE changed on disk while lfcam was reading it (truncated?)", the
//     temporaries are removed, exit status 1. A SIGBUS elsewhere is left to the default action.
// Everything the handlers touch is a fixed table of slots, so they are async-signal-safe.
// SIGKILL cannot be caught: docs/robustness.md says how a stale temporary is recognised.
#include <cstddef>
#include <filesystem>

namespace lfcam {

void InstallSignalCleanup();

// Registers a temporary file for removal should a signal end the process; unregisters on
// destruction. Paths longer than PATH_MAX, or beyond the table's 256 slots, are not covered.
class TemporaryFileRegistration {
 public:
  explicit TemporaryFileRegistration(const std::filesystem::path& path);
  ~TemporaryFileRegistration();
  TemporaryFileRegistration(const TemporaryFileRegistration&) = delete;
  TemporaryFileRegistration& operator=(const TemporaryFileRegistration&) = delete;

 private:
  int slot_ = -1;
};

// Registers a read-only file mapping, so that a SIGBUS inside it names the file.
class MappingRegistration {
 public:
  MappingRegistration(const void* address, std::size_t size, const std::filesystem::path& file);
  ~MappingRegistration();
  MappingRegistration(const MappingRegistration&) = delete;
  MappingRegistration& operator=(const MappingRegistration&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace lfcam
