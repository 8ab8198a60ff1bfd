#include "lfcam/depth/semi_global.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

using Cost = std::uint16_t;
constexpr int kHuge = 0x3fff;  // a label that does not exist (the padding either side)

// One step along a path: cur[i] = c[i] + min(prev[i], prev[i -+ 1] + p1, min(prev) + p2) -
// min(prev). `prev` and `cur` are padded by one label each side; returns min(cur). With a
// `shift` (a slanted surface's expected label change), prev[i - shift] takes prev[i]'s place.
// Compiled for the machine's vector width as well (its loop vectorises; without, x86-64's
// baseline SSE2 has no 16- or 32-bit minimum and builds each from compares and masks).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
int Step(const Cost* c, const Cost* prev, int prev_min, Cost* cur, int n, int p1, int p2,
         int shift = 0) {
  const int jump = prev_min + p2;
  int lowest = kHuge * 4;
  if (shift != 0) {  // the expected label is i - shift
    const auto at = [&](int j) { return j < -1 || j > n ? int(kHuge) : int(prev[j + 1]); };
    for (int i = 0; i < n; ++i) {
      const int j = i - shift;
      int v = std::min(at(j), std::min(at(j - 1), at(j + 1)) + p1);
      v = std::min(v, jump);
      const int out = c[i] + v - prev_min;
      cur[i + 1] = Cost(out);
      lowest = std::min(lowest, out);
    }
    return lowest;
  }
  for (int i = 0; i < n; ++i) {
    int v = std::min<int>(prev[i + 1], std::min<int>(prev[i], prev[i + 2]) + p1);
    v = std::min(v, jump);
    const int out = c[i] + v - prev_min;
    cur[i + 1] = Cost(out);
    lowest = std::min(lowest, out);
  }
  return lowest;
}

// A path's first sample: its own cost.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
int Start(const Cost* c, Cost* cur, int n) {
  int lowest = kHuge * 4;
  for (int i = 0; i < n; ++i) {
    cur[i + 1] = c[i];
    lowest = std::min<int>(lowest, c[i]);
  }
  return lowest;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void Accumulate(const Cost* path, Cost* sum, int n) {
  for (int i = 0; i < n; ++i) sum[i] = Cost(sum[i] + path[i + 1]);
}

}  // namespace

CostVolume AggregateSemiGlobal(const CostVolume& volume, const cv::Mat& guide,
                               const SemiGlobalOptions& options, const cv::Mat& expected_step) {
  const int w = volume.width, h = volume.height, n = volume.labels, stride = n + 2;
  if (w <= 0 || h <= 0 || n <= 0) throw Error("semi-global matching: an empty cost volume");
  const int p1 = options.p1;
  if (guide.type() != CV_8UC1 || guide.cols != w || guide.rows != h)
    throw Error("semi-global matching: the guide must be an 8-bit grey view of the volume's size");
  // The jump penalty between two samples: P2, less across an edge of the guide (where depth
  // edges are), never under P1 + 1.
  std::array<int, 256> jump_penalty{};
  for (int g = 0; g < 256; ++g)
    jump_penalty[std::size_t(g)] = std::max(
        p1 + 1, int(std::lround(options.p2 / (1.0 + g / std::max(1.0, options.edge_grey)))));
  const auto p2_between = [&](int x0, int y0, int x1, int y1) {
    return jump_penalty[std::size_t(
        std::abs(int(guide.at<std::uint8_t>(y0, x0)) - int(guide.at<std::uint8_t>(y1, x1))))];
  };
  const bool slanted = !expected_step.empty();
  if (slanted && (expected_step.type() != CV_32FC2 || expected_step.size() != guide.size()))
    throw Error("semi-global matching: the expected steps must be a CV_32FC2 map of its size");
  // The label change expected from the path's previous sample (x - dx, y - dy) to (x, y).
  const auto shift = [&](int x, int y, int dx, int dy) {
    if (!slanted) return 0;
    const cv::Vec2f s = expected_step.at<cv::Vec2f>(y, x);
    return int(std::lround(s[0] * dx + s[1] * dy));
  };
  CostVolume sum;
  sum.width = w;
  sum.height = h;
  sum.labels = n;
  sum.cost.resize(volume.cost.size());  // not zeroed: the first path writes every sum
  const auto padded = [&](std::vector<Cost>& row, int samples) {
    row.assign(std::size_t(samples) * stride, Cost(kHuge));
  };
  // Along rows (dx = +-1, dy = 0): rows are independent.
  for (const int dx : {1, -1})
    tbb::parallel_for(0, h, [&](int y) {
      std::vector<Cost> a, b;
      padded(a, 1);
      padded(b, 1);
      int prev_min = 0;
      for (int i = 0; i < w; ++i) {
        const int x = dx > 0 ? i : w - 1 - i;
        prev_min = i == 0 ? Start(volume.at(x, y), b.data(), n)
                          : Step(volume.at(x, y), a.data(), prev_min, b.data(), n, p1,
                                 p2_between(x, y, x - dx, y), shift(x, y, dx, 0));
        if (dx > 0)
          std::copy_n(b.data() + 1, n, sum.at(x, y));
        else
          Accumulate(b.data(), sum.at(x, y), n);
        std::swap(a, b);
      }
    });
  // Down or up the view: a row's samples are independent given the row before.
  for (const int dy : {1, -1}) {
    std::vector<Cost> prev, cur;
    padded(prev, w);
    padded(cur, w);
    std::vector<int> prev_min(std::size_t(w), 0), cur_min(std::size_t(w), 0);
    for (int j = 0; j < h; ++j) {
      const int y = dy > 0 ? j : h - 1 - j;
      tbb::parallel_for(tbb::blocked_range<int>(0, w, 64), [&](const tbb::blocked_range<int>& r) {
        for (int x = r.begin(); x < r.end(); ++x) {
          const std::size_t at = std::size_t(x);
          Cost* out = cur.data() + at * stride;
          cur_min[at] = j == 0 ? Start(volume.at(x, y), out, n)
                               : Step(volume.at(x, y), prev.data() + at * stride, prev_min[at], out,
                                      n, p1, p2_between(x, y, x, y - dy), shift(x, y, 0, dy));
          Accumulate(out, sum.at(x, y), n);
        }
      });
      std::swap(prev, cur);
      std::swap(prev_min, cur_min);
    }
  }
  return sum;
}

}  // namespace lfcam
