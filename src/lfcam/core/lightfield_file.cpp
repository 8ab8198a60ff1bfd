#include "lfcam/core/lightfield_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <tbb/parallel_for.h>
#include <unistd.h>
#include <xxhash.h>
#include <zstd.h>

#include <array>
#include <bit>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/camera_model.h"
#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"
#include "lfcam/core/signal_cleanup.h"

namespace lfcam {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the .lf format is little-endian; big-endian hosts are not supported");

constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'L', 'F', 'C', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kPreambleBytes = 40;
constexpr std::uint64_t kMaxHeaderBytes = kMaxJsonBytes;

struct ViewRecord {
  std::uint64_t offset = 0;  // from the start of the data section
  std::uint64_t stored_bytes = 0;
  std::uint64_t xxh3 = 0;
};

std::uint64_t Checksum(const void* data, std::size_t size) { return XXH3_64bits(data, size); }

std::string Hex(std::uint64_t v) { return fmt::format("{:016x}", v); }

template <typename T>
void PutLe(std::uint8_t* out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = std::uint8_t(value >> (8 * i));
}
template <typename T>
T GetLe(const std::uint8_t* in) {
  T value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value |= T(in[i]) << (8 * i);
  return value;
}

std::uint64_t ParseHex64(const std::string& text, const std::string& where) {
  std::uint64_t value = 0;
  if (text.empty() || text.size() > 16)
    throw Error(fmt::format("{}: checksum '{}' is not 1-16 hex digits", where, text));
  for (const char c : text) {
    int digit = -1;
    if (c >= '0' && c <= '9') digit = c - '0';
    if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
    if (digit < 0) throw Error(fmt::format("{}: checksum '{}' is not hex", where, text));
    value = value << 4 | std::uint64_t(digit);
  }
  return value;
}

std::uint64_t RoundUp(std::uint64_t x, std::uint64_t a) { return (x + a - 1) / a * a; }

std::string ViewName(const LightFieldDims& dims, std::size_t index) {
  return fmt::format("view (row {}, col {})", index / dims.cols, index % dims.cols);
}

struct ParsedFile {
  LightFieldHeader header;
  std::uint64_t data_offset = 0;
  std::vector<ViewRecord> views;
};

template <typename F>
auto WithContext(const std::string& file, F&& f) {
  try {
    return f();
  } catch (const nlohmann::json::exception&) {
    throw Error(fmt::format("{}: malformed header (a field has the wrong type)", file));
  } catch (const Error& e) {
    if (std::string_view(e.what()).starts_with(file)) throw;
    throw Error(fmt::format("{}: {}", file, e.what()));
  }
}

ParsedFile ParseHeader(const InputFile& fd, const FileRegion& region) {
  const std::string& name = region.name;
  // The region's size stands for the file's below: a light field inside a video frame.
  struct {
    std::uint64_t bytes;
    std::uint64_t size() const { return bytes; }
  } file{region.size};
  const std::uint64_t base = region.offset;
  if (file.size() < kPreambleBytes)
    throw Error(fmt::format("{}: too short to be a light field ({} bytes)", name, file.size()));
  std::array<std::uint8_t, kPreambleBytes> pre{};
  fd.read_exactly(pre.data(), pre.size(), base);
  if (!std::equal(kMagic.begin(), kMagic.end(), pre.begin()))
    throw Error(fmt::format("{}: not an lfcam light field (bad magic bytes)", name));
  ParsedFile parsed;
  parsed.header.file_bytes = file.size();
  parsed.header.version = GetLe<std::uint32_t>(&pre[8]);
  if (parsed.header.version < kOldestLightFieldFormatVersion ||
      parsed.header.version > kLightFieldFormatVersion)
    throw Error(fmt::format("{}: format version {} is not supported (this build reads {} to {})",
                            name, parsed.header.version, kOldestLightFieldFormatVersion,
                            kLightFieldFormatVersion));
  const auto header_bytes = GetLe<std::uint64_t>(&pre[16]);
  const auto header_xxh3 = GetLe<std::uint64_t>(&pre[24]);
  parsed.data_offset = GetLe<std::uint64_t>(&pre[32]);
  if (header_bytes == 0 || header_bytes > kMaxHeaderBytes)
    throw Error(fmt::format("{}: header size {} is absurd", name, header_bytes));
  if (kPreambleBytes + header_bytes > file.size())
    throw Error(fmt::format("{}: truncated: header needs {} bytes, file has {}", name,
                            kPreambleBytes + header_bytes, file.size()));
  if (parsed.data_offset < kPreambleBytes + header_bytes ||
      parsed.data_offset % kLightFieldAlignment != 0 || parsed.data_offset > file.size())
    throw Error(fmt::format("{}: data offset {} does not fit the file ({} bytes)", name,
                            parsed.data_offset, file.size()));
  std::string text(header_bytes, '\0');
  fd.read_exactly(text.data(), text.size(), base + kPreambleBytes);
  if (Checksum(text.data(), text.size()) != header_xxh3)
    throw Error(fmt::format("{}: header checksum mismatch (the header is corrupt)", name));

  return WithContext(name, [&] {
    const auto j = ParseJsonBounded(text, "header");
    if (JsonString(j, "format", "header") != "lfcam-lightfield")
      throw Error("header format is not lfcam-lightfield");
    auto& h = parsed.header;
    const auto& d = JsonField(j, "dims", "header");
    const std::string dims = "header: dims";
    h.dims = {int(JsonInteger(d, "rows", 1, kMaxViewsPerSide, dims)),
              int(JsonInteger(d, "cols", 1, kMaxViewsPerSide, dims)),
              int(JsonInteger(d, "n_s", 1, kMaxStSamplesPerSide, dims)),
              int(JsonInteger(d, "n_t", 1, kMaxStSamplesPerSide, dims))};
    if (JsonInteger(d, "channels", 1, 64, dims) != LightFieldDims::kChannels)
      throw Error("only 3-channel (RGB) light fields are supported");
    h.sample_type = SampleTypeFromString(JsonString(j, "sample_type", "header"));
    // At most 4096² views of 65536² samples of 6 bytes (about 1e17 bytes): no 64-bit overflow.
    const std::uint64_t view_bytes =
        std::uint64_t(h.dims.samples_per_view()) * 3 * BytesPerChannel(h.sample_type);
    const double total_bytes = double(view_bytes) * double(h.dims.view_count());
    if (total_bytes > double(kMaxLightFieldBytes))
      throw Error(fmt::format("absurd dimensions: {} of samples (the format's limit is {})",
                              HumanBytes(total_bytes), HumanBytes(double(kMaxLightFieldBytes))));
    const auto compression = JsonString(j, "compression", "header");
    if (compression == "none")
      h.compression = Compression::kNone;
    else if (compression == "zstd")
      h.compression = Compression::kZstd;
    else
      throw Error(fmt::format("unknown compression '{}'", compression));
    if (JsonString(j, "checksum", "header") != "xxh3-64")
      throw Error("unknown checksum algorithm (expected xxh3-64)");
    h.slab = JsonField(j, "slab", "header").get<Slab>();
    if (h.slab.uv.rows != h.dims.rows || h.slab.uv.cols != h.dims.cols)
      throw Error("slab grid does not match the view grid");
    h.metadata = j.value("metadata", nlohmann::json::object());
    if (!h.metadata.is_object()) throw Error("header: metadata must be a JSON object");

    const auto& views = JsonField(j, "views", "header");
    if (!views.is_array() || views.size() != h.dims.view_count())
      throw Error(fmt::format("view table has {} entries, dims need {}", views.size(),
                              h.dims.view_count()));
    const std::uint64_t data_bytes = file.size() - parsed.data_offset;
    std::uint64_t next_free = 0;
    for (std::size_t i = 0; i < views.size(); ++i) {
      const auto& v = views[i];
      ViewRecord r;
      const std::string where = ViewName(h.dims, i);
      if (JsonUnsigned(v, "row", kMaxViewsPerSide, where) != i / std::size_t(h.dims.cols) ||
          JsonUnsigned(v, "col", kMaxViewsPerSide, where) != i % std::size_t(h.dims.cols))
        throw Error(fmt::format("{}: the view table lists views out of order", where));
      r.offset = JsonUnsigned(v, "offset", UINT64_MAX, where);
      r.stored_bytes = JsonUnsigned(v, "stored_bytes", UINT64_MAX, where);
      r.xxh3 = ParseHex64(JsonString(v, "xxh3", where), where);
      if (h.compression == Compression::kNone &&
          (r.stored_bytes != view_bytes || r.offset != i * view_bytes))
        throw Error(fmt::format("{}: stored at {} with {} bytes, expected {} with {}", where,
                                r.offset, r.stored_bytes, i * view_bytes, view_bytes));
      if (r.stored_bytes == 0 || r.offset < next_free || r.offset > data_bytes ||
          r.stored_bytes > data_bytes - r.offset)
        throw Error(
            fmt::format("{}: record (offset {}, {} bytes) does not fit the {} data bytes "
                        "of the file (truncated?)",
                        where, r.offset, r.stored_bytes, data_bytes));
      next_free = r.offset + r.stored_bytes;
      h.stored_sample_bytes += r.stored_bytes;
      parsed.views.push_back(r);
      // Version 2: the camera's measured pose, on every view or on none.
      const bool has_pose = v.contains("center");
      if (i > 0 && has_pose != !h.measured_poses.empty())
        throw Error(
            fmt::format("{}: measured camera poses must be given for every view or none", where));
      if (has_pose) {
        if (h.version < 2)
          throw Error(fmt::format("{}: a version 1 file has no measured camera poses", where));
        ViewPose pose{JsonVec3(v, "center", where),
                      RotationFromJson(JsonField(v, "orientation", where), where + ": orientation"),
                      std::nullopt};
        if (pose.center.cwiseAbs().maxCoeff() > 1e9)
          throw Error(fmt::format("{}: camera centre is out of range", where));
        // Version 3: the camera that recorded the view, on every view or on none.
        const bool has_intrinsics = v.contains("intrinsics");
        if (i > 0 && has_intrinsics != h.measured_poses.front().intrinsics.has_value())
          throw Error(
              fmt::format("{}: view intrinsics must be given for every view or none", where));
        if (has_intrinsics) {
          if (h.version < 3)
            throw Error(
                fmt::format("{}: a version {} file has no view intrinsics", where, h.version));
          pose.intrinsics =
              IntrinsicsFromJson(JsonField(v, "intrinsics", where), where + ": intrinsics");
        }
        h.measured_poses.push_back(pose);
      }
      // Version 4: the view's own st window, on every view or on none.
      const bool has_window = v.contains("st_offset");
      if (i > 0 && has_window != !h.st_offsets.empty())
        throw Error(fmt::format("{}: st windows must be given for every view or none", where));
      if (has_window) {
        if (h.version < 4)
          throw Error(
              fmt::format("{}: a version {} file has no view st windows", where, h.version));
        const auto& o = JsonField(v, "st_offset", where);
        const std::string field = where + ": st_offset";
        if (!o.is_array() || o.size() != 2 || !o[0].is_number_integer() ||
            !o[1].is_number_integer())
          throw Error(fmt::format("{} must be [k, l], two whole numbers of samples", field));
        const auto k = o[0].get<std::int64_t>(), l = o[1].get<std::int64_t>();
        if (std::abs(k) > kMaxStOffset || std::abs(l) > kMaxStOffset)
          throw Error(fmt::format("{} ({}, {}) is out of range (at most {} samples each way)",
                                  field, k, l, kMaxStOffset));
        h.st_offsets.push_back({int(k), int(l)});
      }
    }
    return parsed;
  });
}

// A read-only mapping of the whole file. Should the file be truncated while it is mapped, an
// access past the new end raises SIGBUS; the registration lets the handler name the file
// (core/signal_cleanup.h) instead of dying silently.
struct Mapping {
  void* address = MAP_FAILED;
  std::size_t size = 0;
  std::unique_ptr<MappingRegistration> registration;
  ~Mapping() {
    registration.reset();
    if (address != MAP_FAILED) ::munmap(address, size);
  }
};

std::shared_ptr<Mapping> MapFile(const InputFile& fd) {
  auto m = std::make_shared<Mapping>();
  m->size = fd.size();
  m->address = ::mmap(nullptr, m->size, PROT_READ, MAP_PRIVATE, fd.fd(), 0);
  if (m->address == MAP_FAILED)
    throw Error(fmt::format("{}: cannot map: {}", fd.name(), std::strerror(errno)));
  m->registration = std::make_unique<MappingRegistration>(m->address, m->size, fd.name());
  ::madvise(m->address, m->size, MADV_WILLNEED);
  return m;
}

}  // namespace

namespace {

// The file's bytes, in order, to `out` (write, pad_to): an AtomicFileWriter, or memory.
template <typename Out>
void EmitLightField(const LightField& lf, const std::string& name,
                    const LightFieldWriteOptions& options, Out& out) {
  const auto& dims = lf.dims();
  const std::size_t n_views = dims.view_count();
  const std::size_t view_bytes = lf.view_bytes();
  std::vector<ViewRecord> records(n_views);
  std::vector<std::vector<std::uint8_t>> compressed(
      options.compression == Compression::kZstd ? n_views : 0);

  tbb::parallel_for(std::size_t(0), n_views, [&](std::size_t i) {
    const std::uint8_t* view = lf.data() + i * view_bytes;
    if (options.compression == Compression::kNone) {
      records[i] = {i * view_bytes, view_bytes, Checksum(view, view_bytes)};
      return;
    }
    auto& packed = compressed[i];
    packed.resize(ZSTD_compressBound(view_bytes));
    const std::size_t n =
        ZSTD_compress(packed.data(), packed.size(), view, view_bytes, options.zstd_level);
    if (ZSTD_isError(n))
      throw Error(
          fmt::format("{}: zstd failed on {}: {}", name, ViewName(dims, i), ZSTD_getErrorName(n)));
    packed.resize(n);
    records[i] = {0, n, Checksum(packed.data(), n)};
  });
  if (options.compression == Compression::kZstd) {
    std::uint64_t offset = 0;
    for (auto& r : records) {
      r.offset = offset;
      offset += r.stored_bytes;
    }
  }

  const std::uint32_t version = lf.has_view_windows() ? 4 : lf.has_view_cameras() ? 3 : 2;
  nlohmann::json views = nlohmann::json::array();
  for (std::size_t i = 0; i < n_views; ++i) {
    nlohmann::json view = {{"row", i / dims.cols},
                           {"col", i % dims.cols},
                           {"offset", records[i].offset},
                           {"stored_bytes", records[i].stored_bytes},
                           {"xxh3", Hex(records[i].xxh3)}};
    if (!lf.measured_poses().empty()) {
      const ViewPose& pose = lf.measured_poses()[i];
      view["center"] = {pose.center.x(), pose.center.y(), pose.center.z()};
      view["orientation"] = RotationToJson(pose.orientation);
      if (pose.intrinsics) view["intrinsics"] = IntrinsicsToJson(*pose.intrinsics);
    }
    if (lf.has_view_windows()) {
      const StOffset& o = lf.st_offsets()[i];
      view["st_offset"] = {o.k, o.l};
    }
    views.push_back(view);
  }
  const nlohmann::json header = {
      {"format", "lfcam-lightfield"},
      {"version", version},
      {"dims",
       {{"rows", dims.rows},
        {"cols", dims.cols},
        {"n_s", dims.n_s},
        {"n_t", dims.n_t},
        {"channels", LightFieldDims::kChannels}}},
      {"sample_type", ToString(lf.sample_type())},
      {"layout",
       "views row-major by (row, col); in a view, st rows l bottom-up, samples k along "
       "s, RGB interleaved"},
      {"compression", options.compression == Compression::kNone ? "none" : "zstd"},
      {"checksum", "xxh3-64"},
      {"slab", lf.slab()},
      {"metadata", lf.metadata()},
      {"views", views},
  };
  const std::string text = JsonToText(header, 1);
  const std::uint64_t data_offset = RoundUp(kPreambleBytes + text.size(), kLightFieldAlignment);

  std::array<std::uint8_t, kPreambleBytes> pre{};
  std::copy(kMagic.begin(), kMagic.end(), pre.begin());
  PutLe<std::uint32_t>(&pre[8], version);
  PutLe<std::uint32_t>(&pre[12], 0);
  PutLe<std::uint64_t>(&pre[16], text.size());
  PutLe<std::uint64_t>(&pre[24], Checksum(text.data(), text.size()));
  PutLe<std::uint64_t>(&pre[32], data_offset);

  out.write(pre.data(), pre.size());
  out.write(text.data(), text.size());
  out.pad_to(data_offset);
  if (options.compression == Compression::kNone)
    out.write(lf.data(), lf.total_bytes());
  else
    for (const auto& c : compressed) out.write(c.data(), c.size());
}

struct MemoryOut {
  std::vector<std::uint8_t> bytes;
  void write(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes.insert(bytes.end(), p, p + size);
  }
  void pad_to(std::uint64_t offset) {
    if (bytes.size() < offset) bytes.resize(offset, 0);
  }
};

}  // namespace

void WriteLightField(const LightField& lf, const std::filesystem::path& path,
                     const LightFieldWriteOptions& options) {
  AtomicFileWriter out(path);
  EmitLightField(lf, path.string(), options, out);
  out.commit();
}

std::vector<std::uint8_t> EncodeLightField(const LightField& lf, const std::string& name,
                                           const LightFieldWriteOptions& options) {
  MemoryOut out;
  out.bytes.reserve(options.compression == Compression::kNone ? lf.total_bytes() + 65536
                                                              : lf.total_bytes() / 2);
  EmitLightField(lf, name, options, out);
  return std::move(out.bytes);
}

LightFieldHeader ReadLightFieldHeader(const std::filesystem::path& path) {
  const InputFile fd(path);
  return ParseHeader(fd, {0, fd.size(), fd.name()}).header;
}

LightFieldHeader ReadLightFieldHeader(const InputFile& fd, const FileRegion& region) {
  return ParseHeader(fd, region).header;
}

LightField ReadLightField(const std::filesystem::path& path, const LightFieldReadOptions& options) {
  const InputFile fd(path);
  return ReadLightField(fd, {0, fd.size(), fd.name()}, options);
}

LightField ReadLightField(const InputFile& fd, const FileRegion& region,
                          const LightFieldReadOptions& options) {
  const ParsedFile parsed = ParseHeader(fd, region);
  const std::uint64_t base = region.offset;
  const auto& h = parsed.header;
  const std::size_t view_bytes = h.dims.samples_per_view() * 3 * BytesPerChannel(h.sample_type);
  const std::size_t total = view_bytes * h.dims.view_count();
  // Decoded (zstd) or read samples take memory; mapped ones do not.
  if (h.compression == Compression::kZstd || !options.memory_map)
    RequireMemory(double(total),
                  fmt::format("{}: reading {} of samples", region.name, HumanBytes(double(total))));

  // The stored bytes, in place (mapped) or read into memory.
  std::shared_ptr<Mapping> mapping;
  std::vector<std::uint8_t> read_copy;
  const std::uint8_t* data = nullptr;
  SampleBuffer samples;
  if (options.memory_map) {
    mapping = MapFile(fd);
    data = static_cast<const std::uint8_t*>(mapping->address) + base + parsed.data_offset;
  } else if (h.compression == Compression::kNone) {
    samples = SampleBuffer::Allocate(total);
    fd.read_exactly(samples.mutable_data(), total, base + parsed.data_offset);
    data = samples.data();
  } else {
    read_copy.resize(region.size - parsed.data_offset);
    fd.read_exactly(read_copy.data(), read_copy.size(), base + parsed.data_offset);
    data = read_copy.data();
  }

  const auto check_view = [&](std::size_t i) {
    const ViewRecord& r = parsed.views[i];
    if (options.verify_checksums && Checksum(data + r.offset, r.stored_bytes) != r.xxh3)
      throw Error(
          fmt::format("{}: {} is corrupt (checksum mismatch)", region.name, ViewName(h.dims, i)));
    if (h.compression == Compression::kZstd) {
      const auto content = ZSTD_getFrameContentSize(data + r.offset, r.stored_bytes);
      if (content != view_bytes)
        throw Error(fmt::format("{}: {} does not hold a zstd frame of {} bytes", region.name,
                                ViewName(h.dims, i), view_bytes));
    }
  };
  tbb::parallel_for(std::size_t(0), parsed.views.size(), check_view);

  if (h.compression == Compression::kNone) {
    if (options.memory_map)
      samples = SampleBuffer::Wrap(mapping, const_cast<std::uint8_t*>(data), total, false);
  } else {
    samples = SampleBuffer::Allocate(total);
    std::uint8_t* out = samples.mutable_data();
    tbb::parallel_for(std::size_t(0), parsed.views.size(), [&](std::size_t i) {
      const ViewRecord& r = parsed.views[i];
      const std::size_t n =
          ZSTD_decompress(out + i * view_bytes, view_bytes, data + r.offset, r.stored_bytes);
      if (ZSTD_isError(n) || n != view_bytes)
        throw Error(fmt::format("{}: {} does not decompress: {}", region.name, ViewName(h.dims, i),
                                ZSTD_isError(n) ? ZSTD_getErrorName(n) : "wrong size"));
    });
  }
  LightField lf(h.dims, h.sample_type, h.slab, std::move(samples));
  lf.metadata() = h.metadata;
  lf.set_measured_poses(h.measured_poses);
  lf.set_st_offsets(h.st_offsets);
  return lf;
}

}  // namespace lfcam
