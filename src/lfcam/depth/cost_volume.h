#pragma once
// The matching cost of one view (the reference) against the views around it, plane by plane: the
// plane sweep's cost volume (docs/depth.md, "The estimate").
//
// Planes parallel to the array's plane at inverse depths q_i. For each plane every view within
// `reach` grid steps of the reference (rows and columns: a square of up to (2 reach + 1)^2 - 1
// views) is warped onto the reference's st samples through that plane (a homography, exact for
// any slab; where the st-plane is parallel to the array's plane it is a shift, and the shift is
// done separably with Keys' cubic kernel, fused with the comparison row by row: bilinear
// interpolation smooths by an amount that depends on the shift's fraction and biases sub-sample
// matching) and compared with the reference: the mean absolute difference of the sRGB channels
// and the absolute difference of the grey gradients, each truncated. Occlusion: an occluder's edge
// splits the views around the reference into those that see past it and those that do not, along a
// line through the reference. So the views' costs are averaged over each of 8 half-arrays (the
// views whose grid offset lies within 90 degrees of one of 8 directions a 45 degrees apart) and,
// where the views reach 2 grid steps or more, over each of 8 quarter-arrays too (those within 45
// degrees of each direction: where the occluder wraps around the sample, a pocket of background
// between its parts, no half-array sees past it); each one's cost is averaged over a small
// window, a quarter-array's counts kQuarterWeight times (fewer views: its mean is lower by chance
// alone), and the cheapest counts (docs/depth.md, "Quarter-arrays").
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lfcam/core/lightfield.h"

namespace lfcam {

struct CostVolumeOptions {
  int reach = 4;              // views up to this many grid steps away in rows and in columns
  double color_cap = 0.1;     // the colour term's truncation (sRGB, 0 .. 1)
  double gradient_cap = 0.1;  // the gradient term's truncation
  int window_radius = 1;      // the sub-arrays' averaging window (box) radius in samples
  double scale = 1.0;         // > 1: match at 1/scale of the views' resolution (coarse sweeps)
  // A view counts at a sample only if it sees the sample at every plane swept, so that every
  // plane's cost there is over the same views (docs/depth.md, "The frame's edges"); where no
  // half-array keeps two such views, a pair of opposite half-arrays counts. Off for sweeps over a
  // wide bracket of depths (EstimateDepthRange), where no view would remain.
  bool same_views_at_every_plane = false;
  // Each view's brightness made the reference's, channel by channel (a gain from their means over
  // the middle of the frame): for views narrowly apart, which see the same things (a plenoptic
  // camera's outer views are darker than its centre's). Not for views far apart, whose means
  // differ by what each sees (docs/depth.md, "An eighth round"). A view darker than the
  // reference by more than kMaxBrightnessGain (black: a plenoptic view outside the main lens's
  // image, a camera that recorded nothing) is left out of the sweep, unless no view would
  // remain: a clamped gain would leave it mismatched at every plane (docs/depth.md, "Views too
  // dark to match").
  bool equalise_brightness = false;
  // Views whose noise (NoiseLevel of the reference) is above kNoisyViewLevels, or whose texture
  // is sharper than their sampling (NearNyquistShare), read through a Gaussian rather than Keys'
  // cubic, the reference filtered alike, so that no plane matches better because its reads fall
  // between samples and smooth the noise, or blur the sharp edges, away (docs/depth.md, "Noisy
  // views" and "Sharp views").
  bool adapt_to_noise = false;
  // Where the light field records the cameras its views were built from and a camera's pixel
  // spans more than kFinerThanCameraSamples of the views' samples (a Pi capture built at the st
  // sampling's default), every view is blurred by a Gaussian of kCameraBlurPixels of that pixel
  // before matching: what lies between a camera's samples is its interpolation's, and a camera
  // that sampled a sharp edge sharply places it differently from its neighbour, so absolute
  // differences lean towards whole camera pixels (docs/depth.md, "Views finer than their
  // cameras").
  bool blur_to_cameras = false;
};

// CostVolumeOptions::blur_to_cameras: above this span of a camera pixel (in the views' samples
// at the matching resolution) the views are blurred, by a Gaussian of this share of the span.
inline constexpr double kFinerThanCameraSamples = 1.5;
inline constexpr double kCameraBlurPixels = 0.5;

// The noise (8-bit levels) above which views are noisy (CostVolumeOptions::adapt_to_noise).
inline constexpr double kNoisyViewLevels = 1.0;

// The most a view's brightness is scaled by to match the reference's, and the least
// (CostVolumeOptions::equalise_brightness): a view at a sixteenth of the reference's brightness
// (16 levels of 255) still has texture to match.
inline constexpr double kMaxBrightnessGain = 16.0;
inline constexpr double kMinBrightnessGain = 1.0 / kMaxBrightnessGain;

// A sweep's geometry, from the light field's alone (no view loaded): what SweepViews(lf, row,
// col, options) will have.
struct SweepGeometry {
  int width = 0, height = 0;        // the matching resolution
  double scale_x = 1, scale_y = 1;  // full-resolution samples per matching sample
  double st_depth = 0;              // D of the st-plane at the reference's centre, from its camera
  double farthest_mm = 0, nearest_mm = 0;  // the views within reach, from the reference
  double sample_mm = 0, full_sample_mm = 0;
  // How far, in matching samples, a point moves between the reference and its farthest (and its
  // nearest) view per unit of inverse depth (1/mm).
  double farthest_shift_per_q() const { return farthest_mm * st_depth / sample_mm; }
  double nearest_shift_per_q() const { return nearest_mm * st_depth / sample_mm; }
};
SweepGeometry GeometryOf(const LightField& lf, int row, int col, const CostVolumeOptions& options);

// Memory for a cost volume: blocks of 4 MB and more aligned to 2 MB and offered to the kernel
// for transparent huge pages (madvise), so that a fresh volume of tens of megabytes faults in a
// page per 2 MB rather than per 4 kB (docs/benchmarks.md, "Depth for every view"). Freed with
// FreeVolumeMemory.
void* AllocateVolumeMemory(std::size_t bytes);
void FreeVolumeMemory(void* block) noexcept;

// An allocator whose value-less construction leaves an element uninitialised, so that a volume
// of hundreds of megabytes whose every element is written anyway is not zeroed first; its
// memory comes from AllocateVolumeMemory.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(AllocateVolumeMemory(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { FreeVolumeMemory(p); }
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A view's planes as the sweep reads them (SweepViews: 16-bit fixed point).
using PackedPlanes = std::vector<std::int16_t, UninitialisedAllocator<std::int16_t>>;

// The cost of every plane at every sample, as 16-bit integers (kCostUnit a unit of cost; at
// most 2 ((1 - a) color_cap + a gradient_cap) * kCostUnit, a the gradient term's share: see
// SweepViews::Sweep), stored label-fastest: cost(x, y)[i].
struct CostVolume {
  static constexpr double kCostUnit = 4000.0;
  int width = 0, height = 0, labels = 0;
  std::vector<std::uint16_t, UninitialisedAllocator<std::uint16_t>> cost;
  std::uint16_t* at(int x, int y) { return cost.data() + (std::size_t(y) * width + x) * labels; }
  const std::uint16_t* at(int x, int y) const {
    return cost.data() + (std::size_t(y) * width + x) * labels;
  }
};

// A sweep whose every view is read shifted at every plane (the st-plane parallel to the array's
// plane, as a rectified, parallel or built light field has it), scaled too where a camera lies
// off the reference's plane, laid out for a GPU to compute the same volume as SweepViews::Sweep
// (depth/gl_cost_volume.h).
struct ShiftedSweep {
  static constexpr int kChannels = 5;    // R, G, B (sRGB, 0 .. 1), the grey gradients along x, y
  static constexpr int kHalves = 8;      // half-arrays: bits 0 .. 7 of a view's `sub_arrays`
  static constexpr int kSubArrays = 16;  // and quarter-arrays: bits 8 .. 15 (g + 8: direction g)
  int width = 0, height = 0, labels = 0;
  const float* reference = nullptr;            // kChannels planes of width x height
  std::vector<const std::int16_t*> views;      // each view's kChannels planes, 16-bit fixed point
  std::array<float, kChannels> packed_unit{};  // a channel's value is its integer / this
  std::vector<unsigned> sub_arrays;            // each view's half- and quarter-arrays (bit g)
  // The sub-arrays that count: the half-arrays (kHalves), or all kSubArrays where the
  // quarter-arrays hold other views than the half-arrays (reach 2 or more).
  int sub_array_count = kHalves;
  float quarter_weight = 1.0f;  // a quarter-array's mean counts this many times
  // How a view is read at a plane: at (x + x0 - 1 + i, y + y0 - 1 + j), i, j = 0 .. 3, with
  // Keys' weights wx[i] wy[j], the view's edge repeated; only at the samples x_lo .. x_hi,
  // y_lo .. y_hi.
  // A view whose camera lies nearer to or farther from the st-plane than the reference's (a
  // calibrated array's cameras, a millimetre or two off one plane) is scaled as well: read at
  // (ax x + bx, ay y + by), each sample at its own fraction with `read_sigma`'s weights
  // (sweep::ReadWeights), in place of x0, y0, wx and wy.
  struct Read {
    int x0 = 0, y0 = 0;
    std::array<float, 4> wx{}, wy{};
    int x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
    bool scaled = false;
    double ax = 1, bx = 0, ay = 1, by = 0;
  };
  std::vector<Read> reads;  // [label * views.size() + view]
  double read_sigma = 0;    // the reads' kernel: 0 Keys' cubic, else a Gaussian this wide
  float color_cap = 0, gradient_cap = 0, color_weight = 0, gradient_weight = 0;
  int window_radius = 0;
  float min_count = 0;  // a sub-array counts where its windowed count exceeds this
  // Where no half-array counts, a pair of opposite half-arrays (g and g + 4) counts where theirs
  // exceeds this (infinity: never).
  float pair_min_count = INFINITY;
  std::uint16_t most = 0;  // the cost where no half-array counts
};

// Computes a ShiftedSweep's volume (depth/gl_cost_volume.h: on the GPU, through OpenGL).
class CostVolumeEngine {
 public:
  virtual ~CostVolumeEngine() = default;
  virtual CostVolume Sweep(const ShiftedSweep& sweep) = 0;
  // Why this engine cannot take the sweep (too large for it), or empty when it can; a sweep it
  // refuses runs on the CPU, and RanOnCpu is told why.
  virtual std::string Refuses(const ShiftedSweep& /*sweep*/) const { return {}; }
  // Called when a sweep was not a ShiftedSweep and ran on the CPU instead.
  virtual void RanOnCpu(const std::string& why) = 0;
};

// The reference view and its neighbours, prepared for sweeping.
class SweepViews {
 public:
  // Throws lfcam::Error when the light field has no other view within reach.
  SweepViews(const LightField& lf, int row, int col, const CostVolumeOptions& options);

  int width() const { return geometry_.width; }
  int height() const { return geometry_.height; }
  // The reference view at the matching resolution, 8-bit RGB (a guide for edge-aware filters).
  const cv::Mat& reference_rgb8() const { return reference_rgb8_; }
  // D of the st-plane at the reference's centre, seen from the reference camera (mm).
  double st_depth() const { return geometry_.st_depth; }
  // How far, in matching samples, a point moves between the reference and its farthest view
  // (and its nearest) per unit of inverse depth (1/mm).
  double farthest_shift_per_q() const { return geometry_.farthest_shift_per_q(); }
  double nearest_shift_per_q() const { return geometry_.nearest_shift_per_q(); }
  // The reference's noise in 8-bit levels and its texture's share near the sampling limit
  // (depth/view_sharpness.h; both measured with adapt_to_noise, else 0), and the Gaussian's width
  // in samples its views are read through (0: Keys' cubic): noisy views (above
  // kNoisyViewLevels) and sharp ones are.
  double noise_level() const { return noise_level_; }
  double near_nyquist_share() const { return near_nyquist_share_; }
  double read_sigma() const { return read_sigma_; }
  // The Gaussian every view was blurred by before matching (CostVolumeOptions::blur_to_cameras),
  // in samples at the matching resolution; 0: none.
  double camera_blur_sigma() const { return camera_blur_sigma_; }
  // The views within reach that were too dark to match the reference (grid row, col), left out
  // (CostVolumeOptions::equalise_brightness, kMaxBrightnessGain).
  const std::vector<std::pair<int, int>>& too_dark() const { return too_dark_; }

  // The cost volume over the planes of inverse depth q[i] (1/mm). Each view's cost at a sample
  // is 2 ((1 - a) min(colour, color_cap) + a min(gradient, gradient_cap)), a the gradient term's
  // share (0.5: the two terms alike).
  // With an `engine`, a sweep whose views are all read shifted is computed by it.
  CostVolume Sweep(const std::vector<double>& q, double gradient_share = 0.5,
                   CostVolumeEngine* engine = nullptr) const;

  // Every view but the reference, in the order of their index below.
  int view_count() const { return int(views_.size()); }
  // Where view i reads the reference's sample (x, y) at the plane of inverse depth q (1/mm), for
  // views read shifted (the st-plane parallel to the array's plane): (x, y) + offset + q per_q,
  // in matching samples; a view scaled as well (its camera off the reference's plane parallel to
  // the st-plane) at (x, y) scaled by 1 + scale + q scale_per_q along each axis, then shifted so.
  // Nullopt where a view is warped by a homography.
  struct ReadShift {
    cv::Point2d offset, per_q;
    cv::Point2d scale{0, 0}, scale_per_q{0, 0};
    cv::Point2d At(double x, double y, double q) const {
      return {x * (1 + scale.x + q * scale_per_q.x) + offset.x + q * per_q.x,
              y * (1 + scale.y + q * scale_per_q.y) + offset.y + q * per_q.y};
    }
  };
  std::optional<std::vector<ReadShift>> ReadShifts() const;
  // View i's colour planes (R, G, B: sRGB 0 .. 1, its brightness made the reference's where the
  // sweep does) at the matching resolution; i = -1: the reference's.
  std::array<cv::Mat, 3> Colour(int i) const;
  // View i's colour planes as the sweep keeps them, without a copy (valid while this lives;
  // i >= 0): 16-bit (CV_16SC1), Colour(i)'s values times kPackedColour, whose float product with
  // 1 / kPackedColour is exactly Colour(i)'s value.
  std::array<cv::Mat, 3> PackedColour(int i) const;
  static constexpr float kPackedColour = 255.0f;

 private:
  struct View {
    // kChannels planes of width x height, sRGB and gradients: as floats for the reference, as
    // 16-bit fixed point (kPacked) for the others (the sweep reads every view at every plane:
    // half the bytes, and the sweep is bound by reading them).
    // (Allocated uninitialised, large ones on huge pages: every element is written as the view is
    // loaded.)
    std::vector<float, UninitialisedAllocator<float>> channels;
    PackedPlanes packed;
    Vec3 center;
    StSampling sampling;
    // Bit g < 8: in the half-array of direction g * 45 degrees; bit g + 8: in its quarter-array.
    unsigned sub_arrays = 0;
    int view_class = 0;     // index in class_sub_arrays_
    bool too_dark = false;  // darker than the reference by more than kMaxBrightnessGain
  };
  cv::Matx33d Homography(const View& view, double depth) const;

  const LightField& lf_;
  CostVolumeOptions options_;
  SweepGeometry geometry_;
  View reference_;
  std::vector<View> views_;
  std::vector<unsigned> class_sub_arrays_;       // the distinct sub-array memberships of the views
  int sub_array_count_ = ShiftedSweep::kHalves;  // as ShiftedSweep::sub_array_count
  double noise_level_ = 0, near_nyquist_share_ = 0, read_sigma_ = 0, camera_blur_sigma_ = 0;
  std::vector<std::pair<int, int>> too_dark_;
  cv::Mat reference_rgb8_;
};

}  // namespace lfcam
