#include "lfcam/depth/cost_volume.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"
#include "lfcam/core/huge_pages.h"
#include "lfcam/core/keys_cubic.h"
#include "lfcam/depth/noise_level.h"
#include "lfcam/depth/plane_sweep.h"
#include "lfcam/depth/sweep_reads.h"
#include "lfcam/depth/view_sharpness.h"

namespace lfcam {

void* AllocateVolumeMemory(std::size_t bytes) {
  const bool large = bytes >= kHugePagesFrom;
  const std::size_t alignment = large ? kHugePageBytes : 64;
  const std::size_t size =
      (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  void* block = std::aligned_alloc(alignment, size);
  if (!block) throw std::bad_alloc();
  if (large) AdviseHugePages(block, size);
  return block;
}

void FreeVolumeMemory(void* block) noexcept { std::free(block); }

namespace {

// The reads the two halves of the sweep share (depth/sweep_reads.h).
using sweep::IsScaledShift;
using sweep::IsShift;
using sweep::kChannels;
using sweep::kHalves;
using sweep::kPacked;
using sweep::kSubArrays;
using sweep::ReadWeights;

// A quarter-array's windowed mean counts this many times: a mean over fewer views is lower by
// chance alone, and a flat texture or a repeating one matches some quarter-array at a false
// depth (docs/depth.md, "Quarter-arrays": 1.25 to 2 measured, 1.75 the best balance).
constexpr float kQuarterWeight = 1.75f;
constexpr int kBandRows = 8;     // the rows the sweep takes through every view at a time
constexpr int kGroupPlanes = 8;  // the most planes swept together
// The largest error, in samples, of a scaled view's read along a row (below): a few thousandths
// of a sample, far below the reads' own interpolation error and the planes' spacing.
constexpr double kScaledReadError = 1.0 / 256;

// A view read shifted by (tx, ty): at (x + tx, y + ty), cubic, its edge repeated; the samples
// [x_lo, x_hi] x [y_lo, y_hi] read inside it. A view whose camera lies nearer to or farther from
// the st-plane than the reference's (a calibrated array's cameras: a millimetre or two off one
// plane) is scaled as well, read at (ax x + bx, ay y + by): each row at its own fraction, and
// along the row in runs of columns (`tiles`) read at one fraction each, the fraction at the run's
// middle, so that no read is more than kScaledReadError from where it belongs.
struct Shift {
  int x0 = 0, y0 = 0;
  std::array<float, 4> wx{}, wy{};
  int x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  int c_lo = 0, c_hi = -1;          // the columns the horizontal taps read
  int inner_lo = 0, inner_hi = -1;  // the samples whose four horizontal taps lie inside the row
  // A scaled view's mapping, the reads' kernel (ReadWeights), and its runs of columns.
  bool scaled = false;
  double ax = 1, bx = 0, ay = 1, by = 0, read_sigma = 0;
  struct Tile {
    int x_begin = 0, x_end = -1;  // the columns [x_begin, x_end]
    int x0 = 0;
    std::array<float, 4> wx{};
  };
  std::vector<Tile> tiles;
};

// The columns whose four taps at offset x0 lie inside a row of w samples.
int InnerLo(int x0) { return 1 - x0; }
int InnerHi(int x0, int w) { return w - 3 - x0; }

// `within`: also keep to these samples (x_lo .. y_hi), where given.
void KeepWithin(Shift& s, const Shift* within) {
  if (within == nullptr) return;
  s.x_lo = std::max(s.x_lo, within->x_lo);
  s.x_hi = std::min(s.x_hi, within->x_hi);
  s.y_lo = std::max(s.y_lo, within->y_lo);
  s.y_hi = std::min(s.y_hi, within->y_hi);
}

Shift MakeShift(double tx, double ty, int w, int h, double read_sigma,
                const Shift* within = nullptr) {
  Shift s;
  s.x0 = int(std::floor(tx));
  s.y0 = int(std::floor(ty));
  s.wx = ReadWeights(tx - s.x0, read_sigma);
  s.wy = ReadWeights(ty - s.y0, read_sigma);
  s.x_lo = std::max(0, int(std::ceil(-tx - 1e-6)));
  s.x_hi = std::min(w - 1, int(std::floor(w - 1 - tx + 1e-6)));
  s.y_lo = std::max(0, int(std::ceil(-ty - 1e-6)));
  s.y_hi = std::min(h - 1, int(std::floor(h - 1 - ty + 1e-6)));
  KeepWithin(s, within);
  s.c_lo = std::clamp(s.x_lo + s.x0 - 1, 0, w - 1);
  s.c_hi = std::clamp(s.x_hi + s.x0 + 2, 0, w - 1);
  s.inner_lo = std::max(s.x_lo, InnerLo(s.x0));
  s.inner_hi = std::min(s.x_hi, InnerHi(s.x0, w));
  return s;
}

// A view read through the scale and shift m (reference coordinates -> the view's: m(0, 0) x +
// m(0, 2), m(1, 1) y + m(1, 2)); a shift where it is one.
Shift MakeScaledShift(const cv::Matx33d& m, int w, int h, double read_sigma,
                      const Shift* within = nullptr) {
  if (IsShift(m)) return MakeShift(m(0, 2), m(1, 2), w, h, read_sigma, within);
  Shift s;
  s.scaled = true;
  s.ax = m(0, 0), s.bx = m(0, 2), s.ay = m(1, 1), s.by = m(1, 2);
  s.read_sigma = read_sigma;
  // The samples that land inside the view (both scales positive: a camera on the st-plane's
  // side of the scene).
  s.x_lo = std::max(0, int(std::ceil(-s.bx / s.ax - 1e-6)));
  s.x_hi = std::min(w - 1, int(std::floor((w - 1 - s.bx) / s.ax + 1e-6)));
  s.y_lo = std::max(0, int(std::ceil(-s.by / s.ay - 1e-6)));
  s.y_hi = std::min(h - 1, int(std::floor((h - 1 - s.by) / s.ay + 1e-6)));
  KeepWithin(s, within);
  if (s.x_lo > s.x_hi) return s;
  // Runs of columns: the read's place drifts by |ax - 1| a column from the run's middle's.
  const double drift = std::abs(s.ax - 1);
  const int run = drift > 0 ? int(std::clamp(2 * kScaledReadError / drift, 1.0, double(w))) : w;
  s.c_lo = w - 1;
  s.c_hi = 0;
  for (int x = s.x_lo; x <= s.x_hi; x += run) {
    Shift::Tile t;
    t.x_begin = x;
    t.x_end = std::min(s.x_hi, x + run - 1);
    const double middle = 0.5 * (t.x_begin + t.x_end);
    const double offset = s.ax * middle + s.bx - middle;  // the run's shift
    t.x0 = int(std::floor(offset));
    t.wx = ReadWeights(offset - t.x0, read_sigma);
    s.c_lo = std::min(s.c_lo, std::clamp(t.x_begin + t.x0 - 1, 0, w - 1));
    s.c_hi = std::max(s.c_hi, std::clamp(t.x_end + t.x0 + 2, 0, w - 1));
    s.tiles.push_back(t);
  }
  return s;
}

// One view's rows as floats, each converted from the packed samples once while the sweep is at
// it. Every plane of a group reads a row through four vertical taps, so converting at each read
// converted each row some 30 times a band (docs/benchmarks.md, "The views' rows converted once").
// Rows are kept in a ring by their index, each slot saying which row it holds, so a row outside
// those kept is converted again, never read stale; the values are the floats a conversion at the
// read gives.
class ViewRows {
 public:
  void Reset(const PackedPlanes& src, int w, int h) {
    src_ = src.data();
    w_ = w;
    h_ = h;
    data_.resize(std::size_t(kSlots) * kChannels * std::size_t(w));
    held_.fill(-1);
  }
  // Row r (clamped to the view: its edge repeated); channel c's samples at + c w.
  const float* Row(int r) {
    r = std::clamp(r, 0, h_ - 1);
    const std::size_t slot = std::size_t(r % kSlots);
    float* row = data_.data() + slot * kChannels * std::size_t(w_);
    if (held_[slot] == r) return row;
    const std::size_t plane = std::size_t(w_) * std::size_t(h_);
    for (int c = 0; c < kChannels; ++c)
      Convert(src_ + std::size_t(c) * plane + std::size_t(r) * std::size_t(w_), std::size_t(w_),
              row + std::size_t(c) * std::size_t(w_));
    held_[slot] = r;
    return row;
  }

 private:
  // More rows than a band's reads span (its rows, the taps' reach, the spread of the group's
  // shifts), so that a band's rows stay converted while it is swept.
  static constexpr int kSlots = 32;
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
  static void
  Convert(const std::int16_t* __restrict in, std::size_t n, float* __restrict out) {
    for (std::size_t x = 0; x < n; ++x) out[x] = float(in[x]);
  }
  const std::int16_t* src_ = nullptr;
  int w_ = 0, h_ = 0;
  std::vector<float> data_;
  std::array<int, kSlots> held_{};
};

// The two terms of a view's cost at a sample: each truncated, then weighted.
struct CostTerms {
  float color_cap, gradient_cap, color_weight, gradient_weight;
};

// A sample's cost: the shifted view's channels s0 .. s4 against the reference's f0 .. f4, the
// colour's mean and the gradients' sum each truncated, then weighted (one multiply-add, written
// out so that every loop that inlines it gives the same float).
[[gnu::always_inline]] inline float TruncatedCost(float s0, float s1, float s2, float s3, float s4,
                                                  float f0, float f1, float f2, float f3, float f4,
                                                  const CostTerms& terms) {
  const float color = (std::abs(s0 - f0) + std::abs(s1 - f1) + std::abs(s2 - f2)) * (1.0f / 3.0f);
  const float gradient = std::abs(s3 - f3) + std::abs(s4 - f4);
  return std::fma(terms.color_weight, std::min(color, terms.color_cap),
                  terms.gradient_weight * std::min(gradient, terms.gradient_cap));
}

// One row's comparison: the shifted view's channels s0 .. s4 against the reference's f0 .. f4,
// each term truncated and weighted, added to `sum`.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void CompareRow(const float* __restrict s0, const float* __restrict s1, const float* __restrict s2,
                const float* __restrict s3, const float* __restrict s4, const float* __restrict f0,
                const float* __restrict f1, const float* __restrict f2, const float* __restrict f3,
                const float* __restrict f4, const CostTerms terms, std::size_t n,
                float* __restrict sum) {
  for (std::size_t x = 0; x < n; ++x)
    sum[x] +=
        TruncatedCost(s0[x], s1[x], s2[x], s3[x], s4[x], f0[x], f1[x], f2[x], f3[x], f4[x], terms);
}

// A run of n samples' comparison (as CompareRow) with the view's row read across on the way:
// channel c's shifted sample x is wx[0] v_c[x] + .. + wx[3] v_c[x + 3], the taps all inside the
// row, so that the shifted row is never stored and read back. The multiply-adds are written out,
// in the order GCC contracted the separate pass's vectorised loop (wx[1]'s product first), so
// that a sample's cost is the same float whether the vectorised loop or its remainder takes it
// (a scaled view's runs of one fraction are some 30 columns, so a quarter of its samples fall in
// remainders; left to the compiler, those were contracted in another order).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void ShiftAndCompare(const float* __restrict v0, const float* __restrict v1,
                     const float* __restrict v2, const float* __restrict v3,
                     const float* __restrict v4, const float* __restrict f0,
                     const float* __restrict f1, const float* __restrict f2,
                     const float* __restrict f3, const float* __restrict f4,
                     const std::array<float, 4> wx, const CostTerms terms, std::size_t n,
                     float* __restrict sum) {
  const float a0 = wx[0], a1 = wx[1], a2 = wx[2], a3 = wx[3];
  for (std::size_t x = 0; x < n; ++x) {
    const float s0 =
        std::fma(a3, v0[x + 3], std::fma(a2, v0[x + 2], std::fma(a0, v0[x], a1 * v0[x + 1])));
    const float s1 =
        std::fma(a3, v1[x + 3], std::fma(a2, v1[x + 2], std::fma(a0, v1[x], a1 * v1[x + 1])));
    const float s2 =
        std::fma(a3, v2[x + 3], std::fma(a2, v2[x + 2], std::fma(a0, v2[x], a1 * v2[x + 1])));
    const float s3 =
        std::fma(a3, v3[x + 3], std::fma(a2, v3[x + 2], std::fma(a0, v3[x], a1 * v3[x + 1])));
    const float s4 =
        std::fma(a3, v4[x + 3], std::fma(a2, v4[x + 2], std::fma(a0, v4[x], a1 * v4[x + 1])));
    sum[x] += TruncatedCost(s0, s1, s2, s3, s4, f0[x], f1[x], f2[x], f3[x], f4[x], terms);
  }
}

// Row y of one view's truncated cost against the reference, the view shifted: added to row y's
// `sum_row` where the shifted view has a sample (the shift's rectangle). The shift (vertical taps
// into one row, then horizontal taps) and the comparison are fused, and the sweep runs row by row
// through all the views, so that the reference's row and the sums' rows stay in cache.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void AccumulateShiftedRow(ViewRows& src, const float* ref, int w, int h, int y,
                          const Shift& shift, const CostTerms& terms, std::vector<float>& rows,
                          float* sum_row) {
  if (y < shift.y_lo || y > shift.y_hi || shift.x_lo > shift.x_hi) return;
  const std::size_t plane = std::size_t(w) * h;
  const int x_lo = shift.x_lo, x_hi = shift.x_hi;
  // A scaled view's row: read at its own fraction.
  int y0 = shift.y0;
  std::array<float, 4> wy = shift.wy;
  if (shift.scaled) {
    const double ty = shift.ay * y + shift.by;
    const int at = int(std::floor(ty));
    y0 = at - y;
    wy = ReadWeights(ty - at, shift.read_sigma);
  }
  rows.resize(2 * kChannels * std::size_t(w));
  float* vertical = rows.data();
  float* shifted = rows.data() + kChannels * std::size_t(w);
  const float* tap_rows[4];
  for (int j = 0; j < 4; ++j) tap_rows[j] = src.Row(y + y0 - 1 + j);
  for (int c = 0; c < kChannels; ++c) {
    const float* r[4];
    for (int j = 0; j < 4; ++j) r[j] = tap_rows[j] + std::size_t(c) * w;
    // The vertical taps' weights take the packed unit out.
    const float unit = 1.0f / kPacked[std::size_t(c)];
    const float w0 = wy[0] * unit, w1 = wy[1] * unit, w2 = wy[2] * unit, w3 = wy[3] * unit;
    float* v = vertical + std::size_t(c) * w;
    for (int x = shift.c_lo; x <= shift.c_hi; ++x)
      v[x] = w0 * r[0][x] + w1 * r[1][x] + w2 * r[2][x] + w3 * r[3][x];
  }
  // Columns [from, to] read at offset x0 with weights wx and compared: the taps inside the row
  // in one pass with the comparison, the columns whose taps reach over its ends at the end
  // sample (a few at the row's ends).
  const std::size_t sw = std::size_t(w);
  const float* ref_row = ref + std::size_t(y) * sw;
  const auto across = [&](int from, int to, int x0, const std::array<float, 4>& wx, int inner_lo,
                          int inner_hi) {
    const auto edge = [&](int x) {
      for (int c = 0; c < kChannels; ++c) {
        const float* v = vertical + std::size_t(c) * sw;
        float value = 0;
        for (int i = 0; i < 4; ++i) value += wx[i] * v[std::clamp(x + x0 - 1 + i, 0, w - 1)];
        shifted[std::size_t(c) * sw + std::size_t(x)] = value;
      }
      const std::size_t at = std::size_t(x);
      CompareRow(shifted + at, shifted + sw + at, shifted + 2 * sw + at, shifted + 3 * sw + at,
                 shifted + 4 * sw + at, ref_row + at, ref_row + plane + at,
                 ref_row + 2 * plane + at, ref_row + 3 * plane + at, ref_row + 4 * plane + at,
                 terms, 1, sum_row + at);
    };
    for (int x = from; x <= to && x < inner_lo; ++x) edge(x);
    const int first = std::max(from, inner_lo), last = std::min(inner_hi, to);
    if (first <= last) {
      const float* v = vertical + std::ptrdiff_t(first + x0 - 1);
      const float* f = ref_row + first;
      ShiftAndCompare(v, v + sw, v + 2 * sw, v + 3 * sw, v + 4 * sw, f, f + plane, f + 2 * plane,
                      f + 3 * plane, f + 4 * plane, wx, terms, std::size_t(last - first + 1),
                      sum_row + first);
    }
    for (int x = std::max({from, inner_hi + 1, inner_lo}); x <= to; ++x) edge(x);
  };
  if (!shift.scaled)
    across(x_lo, x_hi, shift.x0, shift.wx, shift.inner_lo, shift.inner_hi);
  else
    for (const Shift::Tile& t : shift.tiles)
      across(t.x_begin, t.x_end, t.x0, t.wx, InnerLo(t.x0), InnerHi(t.x0, w));
}

// Where the homography m (reference coordinates -> the view's) lands inside the view: 1, else 0.
void ValidUnder(const cv::Matx33d& m, int w, int h, std::vector<float>& valid) {
  valid.resize(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const cv::Vec3d p = m * cv::Vec3d(x, y, 1);
      const double u = p[0] / p[2], v = p[1] / p[2];
      valid[std::size_t(y) * w + x] =
          p[2] > 0 && u >= -1e-6 && u <= w - 1 + 1e-6 && v >= -1e-6 && v <= h - 1 + 1e-6 ? 1.0f
                                                                                         : 0.0f;
    }
}

// The same through a general homography m (reference coordinates -> the view's).
void WarpCubic(const std::vector<float>& src, int w, int h, const cv::Matx33d& m,
               std::vector<float>& dst, std::vector<float>& valid) {
  const std::size_t plane = std::size_t(w) * h;
  dst.resize(plane * kChannels);
  for (int c = 0; c < kChannels; ++c) {
    const cv::Mat in(h, w, CV_32FC1, const_cast<float*>(src.data() + c * plane));
    cv::Mat out(h, w, CV_32FC1, dst.data() + c * plane);
    cv::warpPerspective(in, out, m, {w, h}, cv::INTER_CUBIC | cv::WARP_INVERSE_MAP,
                        cv::BORDER_REPLICATE);
  }
  ValidUnder(m, w, h, valid);
}

// One plane of a group being swept: the views read shifted (their index and shift), the warped
// views' sums per class over the whole plane (empty when none is warped), and the last rows of
// each half-array's sums (row y at slot y modulo the ring's rows).
struct PlaneScratch {
  std::vector<std::pair<std::size_t, Shift>> shifted;
  std::vector<float> class_sum, class_count;
  std::vector<float> ring_sum, ring_count;
  // Each half-array's count row where every view read shifted sees the row (most rows: the
  // same row for all of them), so that it is counted once per plane rather than once per row.
  std::vector<float> inner_count;
  int inner_lo = 0, inner_hi = -1;
};

// Per-thread working memory of a group of planes.
struct Scratch {
  std::vector<PlaneScratch> planes;
  std::vector<float> band_sum;     // per plane of the group and class of views, over a band
  std::vector<std::size_t> order;  // the views read shifted, class by class
  std::vector<int> steps;
  std::vector<float> across, unpacked, warped, valid;
  ViewRows view_rows;
  std::vector<float> window_sum, best;
};

// sum[x] += row[x] for x < n (each sum its own float, so the same at any vector width):
// a sub-array's sums are its classes' rows added, which inlined in the sweep's per-band lambda
// ran at x86-64's baseline width (docs/benchmarks.md, "Semi-global matching at the machine's
// vector width").
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void AddRow(const float* __restrict row, std::size_t n, float* __restrict sum) {
  for (std::size_t x = 0; x < n; ++x) sum[x] += row[x];
}

// Row y of sub-array g's count: how many of its views read shifted see each sample there.
void CountRow(const std::vector<std::pair<std::size_t, Shift>>& shifted,
              const std::vector<unsigned>& sub_arrays, int g, int y, int w, std::vector<int>& steps,
              float* count) {
  steps.assign(std::size_t(w) + 1, 0);
  for (const auto& [v, shift] : shifted) {
    if (!(sub_arrays[v] >> g & 1) || y < shift.y_lo || y > shift.y_hi || shift.x_lo > shift.x_hi)
      continue;
    ++steps[std::size_t(shift.x_lo)];
    --steps[std::size_t(shift.x_hi) + 1];
  }
  int views = 0;
  for (int x = 0; x < w; ++x) {
    views += steps[std::size_t(x)];
    count[x] = float(views);
  }
}

// Row y of a plane's cost: each half-array's sums over the window (its edge repeated, as
// cv::boxFilter's BORDER_REPLICATE), the cheapest half-array whose count exceeds `min_count`;
// where none does (near the frame's edges, where the views on one side no longer see the
// sample), the cheapest pair of opposite half-arrays (the views off a line through the reference)
// whose count exceeds `pair_min_count`; infinity where none does. Each sum is taken in the same
// order as a running sum from zero would (the same floats), but written rather than added to zeroed
// rows, and the choice made without a branch, so that the loops vectorise (docs/benchmarks.md).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void WindowedBest(const PlaneScratch& ps, int y, int w, int h, int ring, int radius,
                  int sub_arrays, float min_count, float pair_min_count, bool counts_as_before,
                  Scratch& s, float* best) {
  const std::size_t sw = std::size_t(w);
  s.window_sum.resize((2 + 2 * std::size_t(sub_arrays)) * sw);
  float* vs = s.window_sum.data();  // sums and counts down the window's rows, per column
  float* vc = vs + sw;
  // Those summed across the window, the whole window's, per sub-array.
  float* const window_sums = vs + 2 * sw;
  float* const window_counts = window_sums + std::size_t(sub_arrays) * sw;
  // Sums along the row over the window, the row's ends repeated.
  const auto across = [&](const float* v, float* out) {
    if (radius == 1 && w >= 2) {
      out[0] = v[0] + v[0] + v[1];
      for (std::size_t x = 1; x + 1 < sw; ++x) out[x] = v[x - 1] + v[x] + v[x + 1];
      out[sw - 1] = v[sw - 2] + v[sw - 1] + v[sw - 1];
      return;
    }
    std::fill(out, out + sw, 0.0f);
    for (int dx = -radius; dx <= radius; ++dx) {
      const int lo = std::clamp(-dx, 0, w), hi = std::clamp(w - dx, lo, w);
      for (int x = 0; x < lo; ++x) out[x] += v[0];
      for (int x = lo; x < hi; ++x) out[x] += v[x + dx];
      for (int x = hi; x < w; ++x) out[x] += v[w - 1];
    }
  };
  // Larger than any mean: a sub-array without enough views is never the cheapest.
  constexpr float kNotEnough = 1e30f;
  std::fill(best, best + sw, INFINITY);
  for (int g = 0; g < sub_arrays; ++g) {
    for (int dy = -radius; dy <= radius; ++dy) {
      const int row = std::clamp(y + dy, 0, h - 1);
      const std::size_t slot = (std::size_t(g) * ring + std::size_t(row % ring)) * sw;
      const float* rs = ps.ring_sum.data() + slot;
      const float* rc = ps.ring_count.data() + slot;
      if (dy == -radius) {
        std::copy(rs, rs + sw, vs);
        if (!counts_as_before) std::copy(rc, rc + sw, vc);
        continue;
      }
      for (std::size_t x = 0; x < sw; ++x) vs[x] += rs[x];
      if (!counts_as_before)
        for (std::size_t x = 0; x < sw; ++x) vc[x] += rc[x];
    }
    float* bs = window_sums + std::size_t(g) * sw;
    float* bc = window_counts + std::size_t(g) * sw;
    across(vs, bs);
    if (!counts_as_before) across(vc, bc);
    // min_count > 0, so the division is safe wherever it is taken.
    const float weight = g < kHalves ? 1.0f : kQuarterWeight;
    for (std::size_t x = 0; x < sw; ++x)
      best[x] = std::min(best[x], weight * bs[x] / std::max(bc[x], min_count) +
                                      (bc[x] > min_count ? 0.0f : kNotEnough));
  }
  // The pairs of opposite half-arrays, where no half-array counts. Within a sweep that keeps the
  // same views at every plane their counts are every plane's, so the choice between half-arrays
  // and pairs is every plane's too (docs/depth.md, "The frame's edges").
  // (Few samples: those along the frame's edges. A branch per sample, well predicted.)
  for (std::size_t x = 0; x < sw; ++x) {
    if (best[x] < kNotEnough) continue;
    float fallback = INFINITY;
    for (int g = 0; g < kHalves / 2; ++g) {
      const std::size_t a = std::size_t(g) * sw + x, b = std::size_t(g + kHalves / 2) * sw + x;
      const float c = window_counts[a] + window_counts[b];
      if (c > pair_min_count) fallback = std::min(fallback, (window_sums[a] + window_sums[b]) / c);
    }
    best[x] = fallback;
  }
}

}  // namespace

CostVolume SweepViews::Sweep(const std::vector<double>& q, double gradient_share,
                             CostVolumeEngine* engine) const {
  const int w = geometry_.width, h = geometry_.height, n = int(q.size());
  const std::size_t plane = std::size_t(w) * h;
  CostVolume volume;
  volume.width = w;
  volume.height = h;
  volume.labels = n;
  tbb::enumerable_thread_specific<Scratch> scratches;
  if (!(gradient_share >= 0.0 && gradient_share <= 1.0))
    throw Error(fmt::format("the gradient term's share {} is not within 0 .. 1", gradient_share));
  const CostTerms terms{float(options_.color_cap), float(options_.gradient_cap),
                        float(2.0 * (1.0 - gradient_share)), float(2.0 * gradient_share)};
  const float unit = float(CostVolume::kCostUnit);
  const auto most = std::uint16_t(std::lround(
      (terms.color_weight * options_.color_cap + terms.gradient_weight * options_.gradient_cap) *
      unit));
  const int radius = std::max(0, options_.window_radius);
  // A half-array counts where at least two of its views see the sample (one alone, the rest
  // cut off by the frame's edge, matches too easily by chance), unless none has two.
  int largest_half = 0;
  for (int g = 0; g < kHalves; ++g) {
    int views = 0;
    for (const View& view : views_) views += view.sub_arrays >> g & 1;
    largest_half = std::max(largest_half, views);
  }
  const float min_count =
      float(std::min(2, largest_half) * (2 * radius + 1) * (2 * radius + 1)) - 0.01f;
  // Where none has two, a pair of opposite half-arrays counts where one view sees the sample; only
  // where every plane is over the same views (elsewhere it would be over other views at each).
  const float pair_min_count = options_.same_views_at_every_plane
                                   ? float((2 * radius + 1) * (2 * radius + 1)) - 0.01f
                                   : INFINITY;
  // Where each view sees the reference's samples at both ends of the planes (and so at every
  // plane between: a sample's image moves along a line as the plane moves): a shift's rectangle,
  // or a homography's mask.
  std::vector<Shift> stable(views_.size());
  std::vector<std::vector<float>> stable_mask(views_.size());
  if (options_.same_views_at_every_plane)
    for (std::size_t v = 0; v < views_.size(); ++v) {
      const cv::Matx33d a = Homography(views_[v], 1.0 / q.front());
      const cv::Matx33d b = Homography(views_[v], 1.0 / q.back());
      if (IsScaledShift(a) && IsScaledShift(b)) {
        const Shift sa = MakeScaledShift(a, w, h, read_sigma_);
        stable[v] = MakeScaledShift(b, w, h, read_sigma_, &sa);
        continue;
      }
      std::vector<float> at_b;
      ValidUnder(a, w, h, stable_mask[v]);
      ValidUnder(b, w, h, at_b);
      for (std::size_t p = 0; p < plane; ++p) stable_mask[v][p] *= at_b[p];
    }
  if (engine != nullptr) {
    // Every view's read at every plane; the engine takes the sweep when all are shifts.
    ShiftedSweep sweep;
    sweep.width = w;
    sweep.height = h;
    sweep.labels = n;
    sweep.reference = reference_.channels.data();
    sweep.packed_unit = kPacked;
    for (const View& view : views_) {
      sweep.views.push_back(view.packed.data());
      sweep.sub_arrays.push_back(view.sub_arrays);
    }
    sweep.color_cap = terms.color_cap;
    sweep.gradient_cap = terms.gradient_cap;
    sweep.color_weight = terms.color_weight;
    sweep.gradient_weight = terms.gradient_weight;
    sweep.window_radius = radius;
    sweep.min_count = min_count;
    sweep.pair_min_count = pair_min_count;
    sweep.most = most;
    sweep.sub_array_count = sub_array_count_;
    sweep.quarter_weight = kQuarterWeight;
    sweep.read_sigma = read_sigma_;
    bool shifts = true;
    for (int i = 0; i < n && shifts; ++i)
      for (std::size_t v = 0; v < views_.size() && shifts; ++v) {
        const cv::Matx33d m = Homography(views_[v], 1.0 / q[std::size_t(i)]);
        if (!IsScaledShift(m) || (options_.same_views_at_every_plane && !stable_mask[v].empty())) {
          shifts = false;
          break;
        }
        const Shift shift = MakeScaledShift(
            m, w, h, read_sigma_, options_.same_views_at_every_plane ? &stable[v] : nullptr);
        sweep.reads.push_back({shift.x0, shift.y0, shift.wx, shift.wy, shift.x_lo, shift.x_hi,
                               shift.y_lo, shift.y_hi, shift.scaled, shift.ax, shift.bx, shift.ay,
                               shift.by});
      }
    const std::string refused = shifts ? engine->Refuses(sweep) : std::string();
    if (shifts && refused.empty()) return engine->Sweep(sweep);
    engine->RanOnCpu(shifts ? refused
                            : "its views are not parallel to the st-plane (each plane warps them "
                              "by a homography, not a shift)");
  }
  // A plane's views: those read shifted listed, the others warped whole and compared, their sums
  // kept per class of views (the views in the same half-arrays).
  const auto prepare = [&](double plane_q, PlaneScratch& ps, Scratch& s) {
    const double depth = 1.0 / plane_q;
    const float* ref = reference_.channels.data();
    ps.shifted.clear();
    ps.class_sum.clear();
    ps.class_count.clear();
    const std::size_t classes = class_sub_arrays_.size();
    for (std::size_t v = 0; v < views_.size(); ++v) {
      const View& view = views_[v];
      const cv::Matx33d m = Homography(view, depth);
      if (IsScaledShift(m)) {
        ps.shifted.emplace_back(
            v, MakeScaledShift(m, w, h, read_sigma_,
                               options_.same_views_at_every_plane ? &stable[v] : nullptr));
        continue;
      }
      if (ps.class_sum.empty()) {
        ps.class_sum.assign(plane * classes, 0.0f);
        ps.class_count.assign(plane * classes, 0.0f);
      }
      float* sum = ps.class_sum.data() + std::size_t(view.view_class) * plane;
      float* count = ps.class_count.data() + std::size_t(view.view_class) * plane;
      s.unpacked.resize(plane * kChannels);
      for (int c = 0; c < kChannels; ++c)
        for (std::size_t p = 0; p < plane; ++p)
          s.unpacked[c * plane + p] = float(view.packed[c * plane + p]) / kPacked[std::size_t(c)];
      WarpCubic(s.unpacked, w, h, m, s.warped, s.valid);
      if (!stable_mask[v].empty())
        for (std::size_t p = 0; p < plane; ++p) s.valid[p] *= stable_mask[v][p];
      // The same comparison as a shifted view's, over each run of samples the view sees.
      const float* war = s.warped.data();
      const std::size_t sw = std::size_t(w);
      for (int y = 0; y < h; ++y) {
        const float* valid = s.valid.data() + std::size_t(y) * sw;
        for (int x = 0; x < w;) {
          if (valid[x] == 0.0f) {
            ++x;
            continue;
          }
          int end = x;
          while (end < w && valid[end] != 0.0f) ++end;
          const std::size_t at = std::size_t(y) * sw + std::size_t(x);
          CompareRow(war + at, war + plane + at, war + 2 * plane + at, war + 3 * plane + at,
                     war + 4 * plane + at, ref + at, ref + plane + at, ref + 2 * plane + at,
                     ref + 3 * plane + at, ref + 4 * plane + at, terms, std::size_t(end - x),
                     sum + at);
          for (int i = x; i < end; ++i) count[std::size_t(y) * sw + std::size_t(i)] += 1.0f;
          x = end;
        }
      }
    }
  };
  volume.cost.resize(plane * std::size_t(n));  // every cost written below
  // Planes in groups, a band of rows at a time through every plane of the group and every view:
  // a view's rows for the band are read from memory once for the group (they stay in cache from
  // one plane to the next), each plane's sums per class of views stay in cache while the views
  // add to them, and each half-array's windowed mean is taken from the few rows kept per plane,
  // so no plane-sized intermediate reaches memory; the group's costs are written together,
  // label-fastest as the volume keeps them. A sweep with warped views takes a plane at a time
  // (their sums are kept over the whole plane).
  bool all_shifts = true;
  for (int i = 0; i < n && all_shifts; ++i)
    for (const View& view : views_)
      if (!IsScaledShift(Homography(view, 1.0 / q[std::size_t(i)]))) {
        all_shifts = false;
        break;
      }
  const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
  const int group = all_shifts ? std::clamp(n / (2 * threads), 1, kGroupPlanes) : 1;
  const int groups = (n + group - 1) / group;
  // Every plane's counts are the same where each view counts at a sample at every plane or none
  // and every view is read shifted: a group's first plane counts for all of them (its rings'
  // counts and its windowed counts), the others' are not made (docs/benchmarks.md, "The sweep's
  // counts once a group of planes").
  const bool counts_shared = all_shifts && options_.same_views_at_every_plane;
  const std::size_t sw = std::size_t(w);
  const int ring = kBandRows + 2 * radius;  // rows kept per plane: a band and its window
  const std::size_t classes = class_sub_arrays_.size();
  std::vector<unsigned> view_sub_arrays;
  for (const View& view : views_) view_sub_arrays.push_back(view.sub_arrays);
  // A group of planes, its count of sub-arrays a constant (the half-arrays' loops as they were
  // before the quarter-arrays: compiled for 8, `--all` ran 5% slower with the count a variable).
  const auto sweep_group = [&](int group_index, auto count) {
    constexpr int sub_arrays = decltype(count)::value;
    tbb::this_task_arena::isolate([&] {
      Scratch& s = scratches.local();
      const int i0 = group_index * group, planes = std::min(n, i0 + group) - i0;
      s.planes.resize(std::size_t(planes));
      for (int j = 0; j < planes; ++j) prepare(q[std::size_t(i0 + j)], s.planes[std::size_t(j)], s);
      for (PlaneScratch& ps : s.planes) {
        ps.ring_sum.resize(std::size_t(sub_arrays) * std::size_t(ring) * sw);
        ps.ring_count.resize(std::size_t(sub_arrays) * std::size_t(ring) * sw);
        ps.inner_lo = 0;
        ps.inner_hi = h - 1;
        for (const auto& [v, shift] : ps.shifted)
          if (shift.x_lo <= shift.x_hi) {  // (a view that sees no column counts nowhere)
            ps.inner_lo = std::max(ps.inner_lo, shift.y_lo);
            ps.inner_hi = std::min(ps.inner_hi, shift.y_hi);
          }
        if (ps.inner_lo > ps.inner_hi) continue;
        ps.inner_count.resize(std::size_t(sub_arrays) * sw);
        for (int g = 0; g < sub_arrays; ++g)
          CountRow(ps.shifted, view_sub_arrays, g, ps.inner_lo, w, s.steps,
                   ps.inner_count.data() + std::size_t(g) * sw);
      }
      const std::size_t band_size = std::size_t(kBandRows) * sw;
      const float* ref = reference_.channels.data();
      s.best.resize(std::size_t(planes) * sw);
      int next_out = 0;  // the first row whose costs are still to be written
      // The views read shifted, class by class (each class's in their order at every plane).
      // Every plane of a group reads the same views (a group of more than one plane has no
      // warped view), so the group's planes take the same list.
      const auto& listed = s.planes.front().shifted;
      s.order.resize(listed.size());
      std::iota(s.order.begin(), s.order.end(), std::size_t(0));
      std::stable_sort(s.order.begin(), s.order.end(), [&](std::size_t a, std::size_t b) {
        return views_[listed[a].first].view_class < views_[listed[b].first].view_class;
      });
      for (const PlaneScratch& ps : s.planes)
        if (ps.shifted.size() != listed.size() ||
            !std::equal(listed.begin(), listed.end(), ps.shifted.begin(),
                        [](const auto& a, const auto& b) { return a.first == b.first; }))
          throw std::logic_error("the planes of a group read different views");
      const std::size_t plane_band = band_size * classes;
      for (int y0 = 0; y0 < h; y0 += kBandRows) {
        const int y1 = std::min(h, y0 + kBandRows);
        // Each view's band once for the whole group: its rows are read from memory for the
        // first plane and from cache for the rest, and its class's sums for the group's planes
        // stay in cache while the class's views add to them (docs/benchmarks.md, "The sweep's
        // views read once a group of planes").
        s.band_sum.assign(plane_band * std::size_t(planes), 0.0f);
        // A row at a time through the group's planes, so that the rows each plane's taps read
        // are converted once for all of them (ViewRows); each sum takes the views in the same
        // order as before, so it is the same float.
        for (const std::size_t k : s.order) {
          const View& view = views_[listed[k].first];
          s.view_rows.Reset(view.packed, w, h);
          const std::size_t at = std::size_t(view.view_class) * band_size;
          for (int y = y0; y < y1; ++y)
            for (int j = 0; j < planes; ++j)
              AccumulateShiftedRow(
                  s.view_rows, ref, w, h, y, s.planes[std::size_t(j)].shifted[k].second, terms,
                  s.across,
                  s.band_sum.data() + std::size_t(j) * plane_band + at + std::size_t(y - y0) * sw);
        }
        for (int j = 0; j < planes; ++j) {
          PlaneScratch& ps = s.planes[std::size_t(j)];
          const float* band_sum = s.band_sum.data() + std::size_t(j) * plane_band;
          // Each sub-array's sums: its classes' sums added; its counts: the shifted views that
          // see each sample (their rectangles), and the warped views' counts.
          for (int y = y0; y < y1; ++y)
            for (int g = 0; g < sub_arrays; ++g) {
              const std::size_t slot = (std::size_t(g) * ring + std::size_t(y % ring)) * sw;
              float* hs = ps.ring_sum.data() + slot;
              float* hc = ps.ring_count.data() + slot;
              if (j > 0 && counts_shared) {
                // (the first plane's counts serve: WindowedBest reads no other's)
              } else if (y >= ps.inner_lo && y <= ps.inner_hi) {
                const float* inner = ps.inner_count.data() + std::size_t(g) * sw;
                std::copy(inner, inner + sw, hc);
              } else {
                CountRow(ps.shifted, view_sub_arrays, g, y, w, s.steps, hc);
              }
              // The first class's sums written, the others' added: the same floats as adding
              // every class's to zeros, one pass fewer.
              bool first = true;
              for (std::size_t k = 0; k < classes; ++k) {
                if (!(class_sub_arrays_[k] >> g & 1)) continue;
                const float* cs = band_sum + k * band_size + std::size_t(y - y0) * sw;
                if (first)
                  std::copy(cs, cs + sw, hs);
                else
                  AddRow(cs, sw, hs);
                first = false;
                if (ps.class_sum.empty()) continue;
                AddRow(ps.class_sum.data() + k * plane + std::size_t(y) * sw, sw, hs);
                AddRow(ps.class_count.data() + k * plane + std::size_t(y) * sw, sw, hc);
              }
              if (first) std::fill(hs, hs + sw, 0.0f);  // a sub-array without a view
            }
        }
        // The rows whose window lies within the rows summed so far.
        const int last = y1 == h ? h - 1 : y1 - 1 - radius;
        for (int y = next_out; y <= last; ++y) {
          for (int j = 0; j < planes; ++j)
            WindowedBest(s.planes[std::size_t(j)], y, w, h, ring, radius, sub_arrays, min_count,
                         pair_min_count, j > 0 && counts_shared, s,
                         s.best.data() + std::size_t(j) * sw);
          std::uint16_t* out = volume.cost.data() + std::size_t(y) * sw * std::size_t(n) + i0;
          for (int x = 0; x < w; ++x, out += n)
            for (int j = 0; j < planes; ++j) {
              const float b = s.best[std::size_t(j) * sw + std::size_t(x)];
              // b >= 0: rounded half up, as std::lround (inline; lround is a library call).
              out[j] = std::isfinite(b) ? std::uint16_t(b * unit + 0.5f) : most;
            }
        }
        next_out = std::max(next_out, last + 1);
      }
    });
  };
  // Each group isolated: OpenCV's filters run on TBB too, and a thread waiting in one must not
  // take up another group meanwhile, which would reuse this thread's scratch under it.
  tbb::parallel_for(0, groups, [&](int group_index) {
    if (sub_array_count_ == kSubArrays)
      sweep_group(group_index, std::integral_constant<int, kSubArrays>());
    else
      sweep_group(group_index, std::integral_constant<int, kHalves>());
  });
  return volume;
}

}  // namespace lfcam
