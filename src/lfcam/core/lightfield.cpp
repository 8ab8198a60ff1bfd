#include "lfcam/core/lightfield.h"

#include <fmt/format.h>
#include <sys/mman.h>

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/huge_pages.h"

namespace lfcam {

std::string ToString(SampleType type) {
  return type == SampleType::kSrgb8 ? "srgb8" : "linear_f16";
}

SampleType SampleTypeFromString(const std::string& name) {
  if (name == "srgb8") return SampleType::kSrgb8;
  if (name == "linear_f16") return SampleType::kLinearF16;
  throw Error(fmt::format("unknown sample type '{}' (expected srgb8 or linear_f16)", name));
}

std::size_t BytesPerChannel(SampleType type) { return type == SampleType::kSrgb8 ? 1 : 2; }

namespace {
std::uint64_t NextSampleBufferSerial() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1);
}
}  // namespace

SampleBuffer SampleBuffer::Allocate(std::size_t size) {
  std::shared_ptr<std::uint8_t[]> owned(new std::uint8_t[size + kReadableBefore]);
  std::fill_n(owned.get(), kReadableBefore, std::uint8_t{0});
  SampleBuffer b;
  b.data_ = owned.get() + kReadableBefore;
  b.keep_alive_ = std::move(owned);
  b.size_ = size;
  b.writable_ = true;
  b.serial_ = NextSampleBufferSerial();
  return b;
}

SampleBuffer SampleBuffer::AllocateZeroed(std::size_t size) {
  // Anonymous memory straight from the kernel reads as zero until first written: no pass over
  // the whole buffer, and pages nobody writes cost no memory. A large buffer is aligned to, and
  // advised onto, transparent huge pages (core/huge_pages.h: a filtered copy of the views writes
  // a third of each view, a fault every 4 KB being most of its time).
  const bool large = size >= kHugePagesFrom;
  const std::size_t mapped = size + kReadableBefore + (large ? kHugePageBytes : 0);
  void* memory =
      ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw std::bad_alloc();
  auto* base = static_cast<std::uint8_t*>(memory);
  std::uint8_t* start = base;
  if (large) {
    start = base + (kHugePageBytes - reinterpret_cast<std::uintptr_t>(base) % kHugePageBytes) %
                       kHugePageBytes;
    AdviseHugePages(start, mapped - std::size_t(start - base));
  }
  std::shared_ptr<std::uint8_t> owned(base, [mapped](std::uint8_t* p) { ::munmap(p, mapped); });
  SampleBuffer b;
  b.data_ = start + kReadableBefore;
  b.keep_alive_ = std::move(owned);
  b.size_ = size;
  b.writable_ = true;
  b.serial_ = NextSampleBufferSerial();
  return b;
}

SampleBuffer SampleBuffer::Wrap(std::shared_ptr<void> keep_alive, std::uint8_t* data,
                                std::size_t size, bool writable) {
  SampleBuffer b;
  b.keep_alive_ = std::move(keep_alive);
  b.data_ = data;
  b.size_ = size;
  b.writable_ = writable;
  b.serial_ = NextSampleBufferSerial();
  return b;
}

std::uint8_t* SampleBuffer::mutable_data() {
  if (!writable_) throw Error("light field samples are a read-only file mapping");
  return data_;
}

LightField::LightField(const LightFieldDims& dims, SampleType type, const Slab& slab)
    : dims_(dims), type_(type), slab_(slab) {
  CheckShape();
  samples_ = SampleBuffer::AllocateZeroed(total_bytes());
}

LightField::LightField(const LightFieldDims& dims, SampleType type, const Slab& slab,
                       SampleBuffer samples)
    : dims_(dims), type_(type), slab_(slab), samples_(std::move(samples)) {
  CheckShape();
  if (samples_.size() != total_bytes())
    throw Error(fmt::format("light field buffer holds {} bytes, dims need {}", samples_.size(),
                            total_bytes()));
}

void LightField::CheckShape() const {
  if (dims_.rows < 1 || dims_.cols < 1 || dims_.n_s < 1 || dims_.n_t < 1)
    throw Error(fmt::format("light field dims {}x{}x{}x{} must be positive", dims_.rows, dims_.cols,
                            dims_.n_s, dims_.n_t));
  if (dims_.rows != slab_.uv.rows || dims_.cols != slab_.uv.cols)
    throw Error(fmt::format("light field has {}x{} views but its array has {}x{} cameras",
                            dims_.rows, dims_.cols, slab_.uv.rows, slab_.uv.cols));
}

std::size_t LightField::view_offset(int row, int col) const {
  return (std::size_t(row) * std::size_t(dims_.cols) + std::size_t(col)) * view_bytes();
}

const std::uint8_t* LightField::view_data(int row, int col) const {
  return samples_.data() + view_offset(row, col);
}

std::uint8_t* LightField::mutable_view_data(int row, int col) {
  return samples_.mutable_data() + view_offset(row, col);
}

Eigen::Vector3f LightField::linear_rgb(int row, int col, int k, int l) const {
  const std::size_t index = (std::size_t(l) * dims_.n_s + k) * 3;
  if (type_ == SampleType::kSrgb8) {
    const auto& lut = SrgbDecodeTable();
    const std::uint8_t* p = view_data(row, col) + index;
    return {lut[p[0]], lut[p[1]], lut[p[2]]};
  }
  const auto* p = reinterpret_cast<const Eigen::half*>(view_data(row, col)) + index;
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
}

void LightField::set_linear_rgb(int row, int col, int k, int l, const Eigen::Vector3f& rgb) {
  const std::size_t index = (std::size_t(l) * dims_.n_s + k) * 3;
  if (type_ == SampleType::kSrgb8) {
    std::uint8_t* p = mutable_view_data(row, col) + index;
    for (int c = 0; c < 3; ++c) p[c] = LinearToSrgb8(rgb[c]);
    return;
  }
  auto* p = reinterpret_cast<Eigen::half*>(mutable_view_data(row, col)) + index;
  for (int c = 0; c < 3; ++c) p[c] = Eigen::half(rgb[c]);
}

void LightField::set_measured_poses(std::vector<ViewPose> poses) {
  if (!poses.empty() && poses.size() != dims_.view_count())
    throw Error(
        fmt::format("{} measured view poses for {} views", poses.size(), dims_.view_count()));
  for (const ViewPose& pose : poses)
    if (pose.intrinsics.has_value() != poses.front().intrinsics.has_value())
      throw Error("view intrinsics must be given for every view or none");
  measured_poses_ = std::move(poses);
}

void LightField::set_st_offsets(std::vector<StOffset> offsets) {
  if (!offsets.empty() && offsets.size() != dims_.view_count())
    throw Error(fmt::format("{} view windows for {} views", offsets.size(), dims_.view_count()));
  for (const StOffset& o : offsets)
    if (std::abs(o.k) > kMaxStOffset || std::abs(o.l) > kMaxStOffset)
      throw Error(fmt::format("a view window moved by ({}, {}) samples (at most {} each way)", o.k,
                              o.l, kMaxStOffset));
  const bool shared = std::all_of(offsets.begin(), offsets.end(),
                                  [](const StOffset& o) { return o == StOffset{}; });
  st_offsets_ = shared ? std::vector<StOffset>{} : std::move(offsets);
}

LightField::SampleRange LightField::st_union_samples() const {
  SampleRange r{0, 0, dims_.n_s - 1, dims_.n_t - 1};
  if (st_offsets_.empty()) return r;
  r = {INT_MAX, INT_MAX, INT_MIN, INT_MIN};
  for (const StOffset& o : st_offsets_) {
    r.k0 = std::min(r.k0, o.k);
    r.l0 = std::min(r.l0, o.l);
    r.k1 = std::max(r.k1, o.k + dims_.n_s - 1);
    r.l1 = std::max(r.l1, o.l + dims_.n_t - 1);
  }
  return r;
}

StDomain LightField::st_union() const {
  if (st_offsets_.empty()) return slab_.st_domain;
  const SampleRange r = st_union_samples();
  const StSampling st = st_sampling();
  const double ds = st.domain.s_extent() / dims_.n_s, dt = st.domain.t_extent() / dims_.n_t;
  return {st.domain.s0 + r.k0 * ds, st.domain.t0 + r.l0 * dt, st.domain.s0 + (r.k1 + 1) * ds,
          st.domain.t0 + (r.l1 + 1) * dt};
}

Vec3 LightField::camera_center(int row, int col) const {
  if (!measured_poses_.empty()) return measured_poses_[std::size_t(row) * dims_.cols + col].center;
  return slab_.uv.camera_center(row, col);
}

std::string WorldLengthUnit(const nlohmann::json& metadata) {
  if (!metadata.is_object() || !metadata.contains("import")) return "mm";
  const nlohmann::json& import = metadata["import"];
  if (!import.is_object() || !import.contains("length_unit") || !import["length_unit"].is_string())
    return "mm";
  return import["length_unit"].get<std::string>() == "units" ? "units" : "mm";
}

bool ImportedFromViews(const nlohmann::json& metadata) {
  if (!metadata.is_object()) return false;
  if (metadata.contains("import") && metadata["import"].is_object()) return true;
  if (!metadata.contains("calibration") || !metadata["calibration"].is_object()) return false;
  const nlohmann::json& calibration = metadata["calibration"];
  return calibration.contains("import") && calibration["import"].is_object();
}

}  // namespace lfcam
