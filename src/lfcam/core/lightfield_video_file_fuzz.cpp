// libFuzzer target: the light field video reader (preamble, JSON header, the walk over the
// frame records that is the video's index, a frame's light field). Any input must be read or
// refused with lfcam::Error.
#include <fcntl.h>
#include <unistd.h>
#include <xxhash.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/lightfield_video_file.h"

namespace {
std::filesystem::path g_path;

template <typename T>
T Get(const std::vector<std::uint8_t>& b, std::size_t at) {
  T v;
  std::memcpy(&v, &b[at], sizeof v);
  return v;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("LFCAM_MEMORY_LIMIT", "256M", 1);
  const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                        ? std::filesystem::path("/dev/shm")
                                        : std::filesystem::temp_directory_path();
  g_path = dir / ("lfcam_fuzz_video_" + std::to_string(::getpid()) + ".lfv");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Checksums would stop almost every mutation at the door: recompute the header's and those of
  // the frame records the reader will visit, so that mutations reach the checks behind them.
  std::vector<std::uint8_t> bytes(data, data + size);
  if (bytes.size() >= 64) {
    const auto header_bytes = Get<std::uint64_t>(bytes, 16);
    if (header_bytes <= bytes.size() - 64) {
      const std::uint64_t hash = XXH3_64bits(&bytes[64], header_bytes);
      std::memcpy(&bytes[24], &hash, 8);
    }
    std::uint64_t at = Get<std::uint64_t>(bytes, 32);
    for (int frames = 0; frames < 64 && at % 4096 == 0 && at >= 64 && at + 64 <= bytes.size();
         ++frames) {
      const std::uint64_t hash = XXH3_64bits(&bytes[at], 48);
      std::memcpy(&bytes[at + 48], &hash, 8);
      const auto frame_bytes = Get<std::uint64_t>(bytes, at + 32);
      if (frame_bytes > bytes.size()) break;
      at = (at + 64 + frame_bytes + 4095) / 4096 * 4096;
    }
  }
  {
    const int fd = ::open(g_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0) std::abort();
    if (size > 0 && ::write(fd, bytes.data(), size) != ssize_t(size)) std::abort();
    ::close(fd);
  }
  try {
    lfcam::LightFieldVideo video(g_path);
    for (std::size_t k = 0; k < video.frame_count() && k < 4; ++k) {
      try {
        const lfcam::LightField lf = video.ReadFrame(k);
        volatile std::uint8_t sink = 0;
        for (std::size_t i = 0; i < lf.total_bytes(); i += 4096) sink = sink + lf.data()[i];
      } catch (const lfcam::Error&) {
      }
    }
  } catch (const lfcam::Error&) {
  }
  return 0;
}
