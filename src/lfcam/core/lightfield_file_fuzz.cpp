// libFuzzer target: the light field reader (preamble, JSON header, view table, views; both
// compressions; mapped and read), and the filled views its metadata names. Any input must be
// read or refused with lfcam::Error.
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
#include "lfcam/core/lightfield_file.h"
#include "lfcam/core/view_filling.h"

namespace {
std::filesystem::path g_path;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("LFCAM_MEMORY_LIMIT", "256M", 1);  // keep decoded sizes well under libFuzzer's limit
  const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                        ? std::filesystem::path("/dev/shm")
                                        : std::filesystem::temp_directory_path();
  g_path = dir / ("lfcam_fuzz_lightfield_" + std::to_string(::getpid()) + ".lf");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The header's checksum would stop almost every mutation of the JSON at the door: recompute
  // it, so that the mutations reach the parser and the checks behind it.
  std::vector<std::uint8_t> bytes(data, data + size);
  if (bytes.size() >= 40) {
    std::uint64_t header_bytes = 0;
    std::memcpy(&header_bytes, &bytes[16], 8);
    if (header_bytes <= bytes.size() - 40) {
      const std::uint64_t hash = XXH3_64bits(&bytes[40], header_bytes);
      std::memcpy(&bytes[24], &hash, 8);
    }
  }
  {
    const int fd = ::open(g_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0) std::abort();
    if (size > 0 && ::write(fd, bytes.data(), size) != ssize_t(size)) std::abort();
    ::close(fd);
  }
  try {
    lfcam::ReadLightFieldHeader(g_path);
  } catch (const lfcam::Error&) {
    return 0;  // a header refused is refused by the full read too
  }
  // Mapped without view checksums (so corrupt zstd frames reach the decoder), and read with.
  for (const bool map : {true, false}) {
    try {
      const lfcam::LightField lf = lfcam::ReadLightField(g_path, {!map, map});
      volatile std::uint8_t sink = 0;
      for (std::size_t i = 0; i < lf.total_bytes(); i += 4096) sink = sink + lf.data()[i];
      // The views the metadata says were filled (read by depth, export and render): any
      // metadata is read or passed over, and only views of the grid come back.
      for (const auto& [r, c] : lfcam::FilledViews(lf))
        if (r < 0 || r >= lf.dims().rows || c < 0 || c >= lf.dims().cols) std::abort();
    } catch (const lfcam::Error&) {
    }
  }
  return 0;
}
