#include "lfcam/core/signal_cleanup.h"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>

namespace lfcam {
namespace {

// A slot is free (0), being filled or emptied (1), or in use (2); handlers read only slots in use.
enum SlotState : int { kFree = 0, kBusy = 1, kInUse = 2 };

struct TemporarySlot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};

struct MappingSlot {
  std::atomic<int> state{kFree};
  std::uintptr_t begin = 0, end = 0;
  char file[1024];
};

constexpr int kSlots = 256;
std::array<TemporarySlot, kSlots> g_temporaries;
std::array<MappingSlot, kSlots> g_mappings;

template <typename Slot>
int Claim(std::array<Slot, kSlots>& slots) {
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (slots[std::size_t(i)].state.compare_exchange_strong(expected, kBusy)) return i;
  }
  return -1;
}

void CopyBounded(char* out, std::size_t capacity, const std::string& text) {
  const std::size_t n = std::min(capacity - 1, text.size());
  std::memcpy(out, text.data(), n);
  out[n] = '\0';
}

void WriteStderr(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= std::size_t(n);
  }
}

void RemoveTemporaries() {
  for (auto& slot : g_temporaries)
    if (slot.state.load(std::memory_order_acquire) == kInUse) ::unlink(slot.path);
}

void OnTerminatingSignal(int signal_number) {
  RemoveTemporaries();
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

void OnBusError(int, siginfo_t* info, void*) {
  const auto address = reinterpret_cast<std::uintptr_t>(info->si_addr);
  for (auto& slot : g_mappings) {
    if (slot.state.load(std::memory_order_acquire) != kInUse) continue;
    if (address < slot.begin || address >= slot.end) continue;
    WriteStderr("lfcam: error: ");
    WriteStderr(slot.file);
    WriteStderr(
        ": the file changed on disk while lfcam was reading it (truncated?); nothing "
        "was written\n");
    RemoveTemporaries();
    ::_exit(1);
  }
  // Not ours: the default action (the faulting access repeats and ends the process).
  ::signal(SIGBUS, SIG_DFL);
}

}  // namespace

void InstallSignalCleanup() {
  struct sigaction action {};
  sigemptyset(&action.sa_mask);
  action.sa_handler = OnTerminatingSignal;
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous {};
    // A signal the parent chose to ignore (nohup, a background job) stays ignored.
    if (::sigaction(s, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    ::sigaction(s, &action, nullptr);
  }
  struct sigaction bus {};
  sigemptyset(&bus.sa_mask);
  bus.sa_sigaction = OnBusError;
  bus.sa_flags = SA_SIGINFO;
  ::sigaction(SIGBUS, &bus, nullptr);
}

TemporaryFileRegistration::TemporaryFileRegistration(const std::filesystem::path& path) {
  if (path.native().size() >= PATH_MAX) return;
  slot_ = Claim(g_temporaries);
  if (slot_ < 0) return;
  auto& slot = g_temporaries[std::size_t(slot_)];
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  CopyBounded(slot.path, sizeof slot.path, ec ? path.native() : absolute.native());
  slot.state.store(kInUse, std::memory_order_release);
}

TemporaryFileRegistration::~TemporaryFileRegistration() {
  if (slot_ >= 0) g_temporaries[std::size_t(slot_)].state.store(kFree, std::memory_order_release);
}

MappingRegistration::MappingRegistration(const void* address, std::size_t size,
                                         const std::filesystem::path& file) {
  slot_ = Claim(g_mappings);
  if (slot_ < 0) return;
  auto& slot = g_mappings[std::size_t(slot_)];
  slot.begin = reinterpret_cast<std::uintptr_t>(address);
  slot.end = slot.begin + size;
  CopyBounded(slot.file, sizeof slot.file, file.string());
  slot.state.store(kInUse, std::memory_order_release);
}

MappingRegistration::~MappingRegistration() {
  if (slot_ >= 0) g_mappings[std::size_t(slot_)].state.store(kFree, std::memory_order_release);
}

}  // namespace lfcam
