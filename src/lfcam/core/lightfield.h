#pragma once
// The discrete light field L(u_i, v_j, s_k, t_l) (§5.2.1) with its slab geometry and metadata.
//
// Layout (also the file layout, docs/format.md): views in row-major (row, col) order; inside a
// view, st rows l = 0 .. n_t-1 from the bottom of the view window up, each holding n_s samples
// k = 0 .. n_s-1 along s, each sample R, G, B. View (row, col) is what camera (row, col) sees
// through st sample ((k + 0.5) / n_s, (l + 0.5) / n_t) of the st domain.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/camera_model.h"
#include "lfcam/core/slab.h"
#include "lfcam/core/st_sampling.h"

namespace lfcam {

enum class SampleType {
  kSrgb8,      // 8-bit sRGB-encoded RGB (the default, as captured)
  kLinearF16,  // IEEE half floats, linear light RGB
};
std::string ToString(SampleType type);
SampleType SampleTypeFromString(const std::string& name);  // throws lfcam::Error
std::size_t BytesPerChannel(SampleType type);

// Where a view's camera actually was: its centre of projection (world, mm) and the rotation
// world_from_camera (camera frame: OpenCV's, x right, y down, z forward); and, when known, the
// pinhole that recorded it (image size, focal length and principal point, lens distortion
// undone: a rectified rig's shifted principal point, a Pi module's calibrated one), which
// `render --as-camera` reproduces (format version 3).
struct ViewPose {
  Vec3 center = Vec3::Zero();
  Mat3 orientation = Mat3::Identity();
  std::optional<CameraIntrinsics> intrinsics;
};

struct LightFieldDims {
  int rows = 0, cols = 0;  // views (the camera grid)
  int n_s = 0, n_t = 0;    // st samples per view
  static constexpr int kChannels = 3;

  std::size_t view_count() const { return std::size_t(rows) * std::size_t(cols); }
  std::size_t samples_per_view() const { return std::size_t(n_s) * std::size_t(n_t); }
  bool operator==(const LightFieldDims&) const = default;
};

// A contiguous byte block that either owns its memory or keeps a file mapping alive. At least
// kReadableBefore bytes before data() are readable too (the vectorised renderer reads each
// sample as the 32-bit word that ends with it): an allocated buffer reserves them, a file
// mapping has the file's header there.
class SampleBuffer {
 public:
  static constexpr std::size_t kReadableBefore = 16;
  SampleBuffer() = default;
  static SampleBuffer Allocate(std::size_t size);        // uninitialised
  static SampleBuffer AllocateZeroed(std::size_t size);  // zeros, its pages mapped as written
  static SampleBuffer Wrap(std::shared_ptr<void> keep_alive, std::uint8_t* data, std::size_t size,
                           bool writable);
  const std::uint8_t* data() const { return data_; }
  std::uint8_t* mutable_data();  // throws if the buffer is a read-only mapping
  // A number no other buffer made by this process has: what a cache of the samples (the GL
  // renderer's textures) keys on, where an address could be reused by a later buffer.
  std::uint64_t serial() const { return serial_; }
  std::size_t size() const { return size_; }

 private:
  std::shared_ptr<void> keep_alive_;
  std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  bool writable_ = false;
  std::uint64_t serial_ = 0;
};

// The unit of a light field's world lengths (its metadata): "mm", or "units" where its import
// had no metric scale and took the cameras' spacing as 1 (views named by grid index only, no
// --pitch-mm: lengths are then in units of that spacing, and `info`, `render` and `depth` say so).
std::string WorldLengthUnit(const nlohmann::json& metadata);
// Whether a light field was imported from a folder of views made elsewhere (`lfcam import`: its
// metadata's "import", or its calibration's, as a parallel rig's import records it), not built
// from lfcam's own array: its rig is not the paper's, so the paper's view is no default for it.
bool ImportedFromViews(const nlohmann::json& metadata);

class LightField {
 public:
  LightField() = default;
  // A zero-filled light field of the given shape.
  LightField(const LightFieldDims& dims, SampleType type, const Slab& slab);
  LightField(const LightFieldDims& dims, SampleType type, const Slab& slab, SampleBuffer samples);

  const LightFieldDims& dims() const { return dims_; }
  SampleType sample_type() const { return type_; }
  const Slab& slab() const { return slab_; }
  Slab& mutable_slab() { return slab_; }
  nlohmann::json& metadata() { return metadata_; }
  const nlohmann::json& metadata() const { return metadata_; }

  std::size_t view_bytes() const { return dims_.samples_per_view() * 3 * BytesPerChannel(type_); }
  std::size_t total_bytes() const { return view_bytes() * dims_.view_count(); }
  const std::uint8_t* view_data(int row, int col) const;
  std::uint8_t* mutable_view_data(int row, int col);
  const std::uint8_t* data() const { return samples_.data(); }
  std::uint64_t samples_serial() const { return samples_.serial(); }  // SampleBuffer::serial
  const SampleBuffer& samples() const { return samples_; }            // shares them

  // Each view's measured camera pose (a calibrated capture), row-major; empty when the views sit
  // on the slab's ideal grid (a simulated light field, a format version 1 file).
  const std::vector<ViewPose>& measured_poses() const { return measured_poses_; }
  // view_count() entries, or none; the intrinsics on every pose or on none.
  void set_measured_poses(std::vector<ViewPose> poses);
  // Whether every view records the camera that took it (ViewPose::intrinsics).
  bool has_view_cameras() const {
    return !measured_poses_.empty() && measured_poses_.front().intrinsics.has_value();
  }
  // Camera (row, col)'s centre: measured when known, else its ideal grid position.
  Vec3 camera_center(int row, int col) const;

  // How the views sample the st-plane (core/st_sampling.h): the one mapping between the plane and
  // the samples that every reader uses. st_sampling() is the reference grid (the slab's st
  // domain); st_sampling(row, col) is view (row, col)'s own window, the reference grid moved by
  // st_offset(row, col) whole samples.
  StSampling st_sampling() const { return {slab_.st, slab_.st_domain, dims_.n_s, dims_.n_t}; }
  StSampling st_sampling(int row, int col) const {
    return st_sampling().Moved(st_offset(row, col));
  }
  // Each view's window (format version 4), row-major; empty when every view has the reference
  // grid's. set_st_offsets() takes view_count() entries or none (all zero is stored as none).
  const std::vector<StOffset>& st_offsets() const { return st_offsets_; }
  void set_st_offsets(std::vector<StOffset> offsets);
  bool has_view_windows() const { return !st_offsets_.empty(); }
  StOffset st_offset(int row, int col) const {
    return st_offsets_.empty() ? StOffset{} : st_offsets_[std::size_t(row) * dims_.cols + col];
  }
  // What the views cover together: the union of their windows, in reference samples (the first
  // and last sample along each axis) and in window units (the samples' outer edges).
  struct SampleRange {
    int k0 = 0, l0 = 0, k1 = 0, l1 = 0;
  };
  SampleRange st_union_samples() const;
  StDomain st_union() const;
  // The slab with st_union() as its st domain: what Slab::contains must test a line against.
  Slab sampled_slab() const {
    Slab s = slab_;
    s.st_domain = st_union();
    return s;
  }
  // The st-plane position of reference sample (k, l), in view-window units (a view's own samples:
  // st_sampling(row, col).s_of, t_of).
  double s_of(double k) const { return st_sampling().s_of(k); }
  double t_of(double l) const { return st_sampling().t_of(l); }
  // Linear-light RGB of sample (row, col, k, l), whatever the sample type.
  Eigen::Vector3f linear_rgb(int row, int col, int k, int l) const;
  void set_linear_rgb(int row, int col, int k, int l, const Eigen::Vector3f& rgb);

 private:
  std::size_t view_offset(int row, int col) const;
  void CheckShape() const;

  LightFieldDims dims_;
  SampleType type_ = SampleType::kSrgb8;
  Slab slab_;
  nlohmann::json metadata_ = nlohmann::json::object();
  SampleBuffer samples_;
  std::vector<ViewPose> measured_poses_;
  std::vector<StOffset> st_offsets_;
};

// The largest st offset a view may have, in samples (keeps every sample coordinate in 32 bits).
inline constexpr int kMaxStOffset = 1 << 20;

}  // namespace lfcam
