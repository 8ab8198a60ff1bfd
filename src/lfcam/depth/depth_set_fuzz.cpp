// libFuzzer target: a depth set's index (depth.json, depth/depth_set.h) parsed against a light
// field's grid. Whatever it accepts names views on the grid, in files that stay in the folder.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/depth/depth_set.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("LFCAM_MEMORY_LIMIT", "256M", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lfcam::LightFieldDims dims;
  dims.rows = 10;
  dims.cols = 10;
  dims.n_s = 64;
  dims.n_t = 48;
  try {
    const auto entries = lfcam::ParseDepthSetIndex(
        std::string_view(reinterpret_cast<const char*>(data), size), dims, "fuzz");
    if (entries.empty()) std::abort();
    for (const auto& e : entries) {
      if (e.row < 0 || e.row >= dims.rows || e.col < 0 || e.col >= dims.cols) std::abort();
      if (e.file.empty() || e.file.find('/') != std::string::npos || e.file[0] == '.') std::abort();
    }
  } catch (const lfcam::Error&) {
  }
  return 0;
}
