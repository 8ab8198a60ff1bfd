#pragma once
// The .lf light field file (docs/format.md): a fixed 40-byte preamble, a JSON header, then one
// record per view, each with its own XXH3-64 checksum. Uncompressed views start on 4096-byte
// boundaries so the file can be memory-mapped and used in place.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfcam/core/input_file.h"
#include "lfcam/core/lightfield.h"

namespace lfcam {

// Version 2 adds each view's measured camera pose (optional), version 3 the intrinsics of the
// camera that recorded each view (optional), version 4 each view's own st window (optional: its
// offset from the reference grid in whole samples); older files are still read, and a file is
// written with the oldest version that holds what it carries (an older lfcam reads it then).
inline constexpr std::uint32_t kLightFieldFormatVersion = 4;
inline constexpr std::uint32_t kOldestLightFieldFormatVersion = 1;
inline constexpr std::size_t kLightFieldAlignment = 4096;

enum class Compression { kNone, kZstd };

struct LightFieldWriteOptions {
  Compression compression = Compression::kNone;
  int zstd_level = 3;
};

// Writes atomically (temporary name, then rename). Throws lfcam::Error.
void WriteLightField(const LightField& lf, const std::filesystem::path& path,
                     const LightFieldWriteOptions& options = {});

struct LightFieldReadOptions {
  bool verify_checksums = true;
  bool memory_map = true;  // uncompressed files are used in place when true
};

// Reads and verifies a light field. Any inconsistency (truncation, bad checksum, sizes that do
// not add up, absurd dimensions) throws lfcam::Error naming the file and the view.
LightField ReadLightField(const std::filesystem::path& path,
                          const LightFieldReadOptions& options = {});

// The header alone (cheap: does not touch the samples), for `lfcam info`.
struct LightFieldHeader {
  std::uint32_t version = 0;
  LightFieldDims dims;
  SampleType sample_type = SampleType::kSrgb8;
  Compression compression = Compression::kNone;
  Slab slab;
  nlohmann::json metadata;
  std::vector<ViewPose> measured_poses;  // empty, or one per view
  std::vector<StOffset> st_offsets;  // empty (the views share the reference grid), or one per view
  std::uint64_t file_bytes = 0;
  std::uint64_t stored_sample_bytes = 0;
};
LightFieldHeader ReadLightFieldHeader(const std::filesystem::path& path);

// A light field stored inside a larger file (a frame of a light field video,
// core/lightfield_video_file.h): `size` bytes from `offset`, named `name` in errors.
struct FileRegion {
  std::uint64_t offset = 0, size = 0;
  std::string name;
};
LightField ReadLightField(const InputFile& file, const FileRegion& region,
                          const LightFieldReadOptions& options = {});
LightFieldHeader ReadLightFieldHeader(const InputFile& file, const FileRegion& region);
// The bytes WriteLightField writes, in memory (`name` in errors).
std::vector<std::uint8_t> EncodeLightField(const LightField& lf, const std::string& name,
                                           const LightFieldWriteOptions& options = {});

}  // namespace lfcam
