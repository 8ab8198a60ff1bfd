// The fit vectorised across a row's samples with Highway's dynamic dispatch (as the renderer's
// kernels, render/simd_kernels.cpp): this file is compiled once per instruction set
// (foreach_target.h includes it again for each), and HWY_DYNAMIC_DISPATCH picks the best the
// machine supports. Each lane is one sample; the neighbourhood's sums are taken offset by
// offset, so every load is a contiguous run of the maps, padded so that no lane needs a bounds
// check (docs/benchmarks.md, "Depth for every view").
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lfcam/depth/local_planes.cpp"
#include "lfcam/depth/local_planes.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#ifndef LFCAM_DEPTH_LOCAL_PLANES_ONCE
#define LFCAM_DEPTH_LOCAL_PLANES_ONCE
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/depth/colour_weights.h"
#include "lfcam/depth/padded_label_maps.h"

namespace lfcam::local_planes {

// The maps a fit reads: the labels and colours, and beside them, laid out alike (padding 0), each
// sample's weight, max(confidence, floor).
struct PaddedMaps : PaddedLabelMaps {
  std::vector<float> weight;
};

// The fit's constants, as the kernel takes them.
struct FitConstants {
  std::vector<float> space;  // the distance weight per offset, (2r + 1)² of them, row by row
  ColourWeights colour;      // the colour weight per squared distance, σ in 8-bit levels
  float gap = 0;             // max_label_gap
};

// The sums a sample's fit takes: of 1, dx, dy, dx², dy², dx·dy, l, l·dx and l·dy, each weighted.
constexpr int kSums = 9;

}  // namespace lfcam::local_planes
#endif  // LFCAM_DEPTH_LOCAL_PLANES_ONCE

HWY_BEFORE_NAMESPACE();
namespace lfcam {
namespace HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;

// The weighted sums over the neighbourhoods of samples [x0, x0 + lanes) of row y, into
// `sums` (kSums runs of `lanes` floats: s0, sx, sy, sxx, syy, sxy, sl, slx, sly), the
// labels taken relative to each sample's own.
void NeighbourhoodSumsT(const local_planes::PaddedMaps& m, const local_planes::FitConstants& c,
                        int y, int x0, float* sums) {
  const DF d;
  const int r = m.radius, side = 2 * r + 1;
  const std::size_t centre = m.At(y, x0);
  const VF own = hn::LoadU(d, m.label.data() + centre);
  const VF red0 = hn::LoadU(d, m.red.data() + centre);
  const VF green0 = hn::LoadU(d, m.green.data() + centre);
  const VF blue0 = hn::LoadU(d, m.blue.data() + centre);
  const VF gap = hn::Set(d, c.gap);
  const DI di;
  const float* colour_weight = c.colour.weight.data();
  const auto last = hn::Set(di, c.colour.last);
  VF s0 = hn::Zero(d), sx = s0, sy = s0, sxx = s0, syy = s0, sxy = s0, sl = s0, slx = s0, sly = s0;
  for (int dy = -r; dy <= r; ++dy) {
    const int yy = y + dy;
    if (yy < 0 || yy >= m.height) continue;
    const VF fy = hn::Set(d, float(dy));
    const float* space = c.space.data() + std::size_t((dy + r) * side + r);
    for (int dx = -r; dx <= r; ++dx) {
      const std::size_t at = m.At(yy, x0 + dx);
      VF l = hn::Sub(hn::LoadU(d, m.label.data() + at), own);
      const auto near = hn::Le(hn::Abs(l), gap);  // false for NaN: the padding
      const VF dr = hn::Sub(hn::LoadU(d, m.red.data() + at), red0);
      const VF dg = hn::Sub(hn::LoadU(d, m.green.data() + at), green0);
      const VF db = hn::Sub(hn::LoadU(d, m.blue.data() + at), blue0);
      const VF d2 = hn::MulAdd(dr, dr, hn::MulAdd(dg, dg, hn::Mul(db, db)));
      const VF colour = hn::GatherIndex(d, colour_weight, hn::Min(hn::ConvertTo(di, d2), last));
      const VF w = hn::IfThenElseZero(near, hn::Mul(hn::Mul(colour, hn::Set(d, space[dx])),
                                                    hn::LoadU(d, m.weight.data() + at)));
      l = hn::IfThenElseZero(near, l);
      const VF fx = hn::Set(d, float(dx));
      const VF wx = hn::Mul(w, fx), wy = hn::Mul(w, fy);
      s0 = hn::Add(s0, w);
      sx = hn::Add(sx, wx);
      sy = hn::Add(sy, wy);
      sxx = hn::MulAdd(wx, fx, sxx);
      syy = hn::MulAdd(wy, fy, syy);
      sxy = hn::MulAdd(wx, fy, sxy);
      sl = hn::MulAdd(w, l, sl);
      slx = hn::MulAdd(wx, l, slx);
      sly = hn::MulAdd(wy, l, sly);
    }
  }
  const std::size_t lanes = hn::Lanes(d);
  int k = 0;
  for (const VF& v : {s0, sx, sy, sxx, syy, sxy, sl, slx, sly})
    hn::StoreU(v, d, sums + std::size_t(k++) * lanes);
}

int LanesT() { return int(hn::Lanes(DF())); }

}  // namespace
}  // namespace HWY_NAMESPACE
}  // namespace lfcam
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace lfcam {
namespace {

HWY_EXPORT(NeighbourhoodSumsT);
HWY_EXPORT(LanesT);

// The plane label = a + b·dx + c·dy from a sample's sums (s0, sx, sy, sxx, syy, sxy, sl, slx,
// sly): the normal equations [s0 sx sy; sx sxx sxy; sy sxy syy] [a b c]' = [sl slx sly]', the
// slopes lightly damped (a neighbourhood along a line fixes no slope across it). False where
// nothing counted or the system is singular.
bool SolvePlane(const double (&sum)[local_planes::kSums], double (&plane)[3]) {
  const double s0 = sum[0], sx = sum[1], sy = sum[2], sxx = sum[3], syy = sum[4], sxy = sum[5],
               sl = sum[6], slx = sum[7], sly = sum[8];
  if (s0 <= 0) return false;
  const double damp = 1e-3 * s0;
  const double a11 = s0, a12 = sx, a13 = sy, a22 = sxx + damp, a23 = sxy, a33 = syy + damp;
  const double c11 = a22 * a33 - a23 * a23, c12 = a13 * a23 - a12 * a33,
               c13 = a12 * a23 - a13 * a22;
  const double det = a11 * c11 + a12 * c12 + a13 * c13;
  if (!(std::abs(det) > 1e-12 * s0 * s0 * s0)) return false;
  const double c22 = a11 * a33 - a13 * a13, c23 = a12 * a13 - a11 * a23,
               c33 = a11 * a22 - a12 * a12;
  plane[0] = (sl * c11 + slx * c12 + sly * c13) / det;
  plane[1] = (sl * c12 + slx * c22 + sly * c23) / det;
  plane[2] = (sl * c13 + slx * c23 + sly * c33) / det;
  return true;
}

}  // namespace

cv::Mat FitLocalPlanes(const cv::Mat& label, const cv::Mat& guide_rgb8, const cv::Mat& confidence,
                       const LocalPlaneOptions& options, cv::Mat* slopes) {
  if (label.type() != CV_32FC1 || guide_rgb8.type() != CV_8UC3 || confidence.type() != CV_32FC1 ||
      guide_rgb8.size() != label.size() || confidence.size() != label.size())
    throw Error(
        "FitLocalPlanes: labels, guide and confidence must be float, RGB8 and float maps "
        "of one size");
  const int w = label.cols, h = label.rows, r = std::max(0, options.radius);
  const int lanes = HWY_DYNAMIC_DISPATCH(LanesT)();
  local_planes::PaddedMaps m;
  static_cast<PaddedLabelMaps&>(m) = PadLabelMaps(label, guide_rgb8, r, lanes);
  m.weight.assign(m.label.size(), 0.0f);
  const float floor = float(options.min_confidence);
  for (int y = 0; y < h; ++y) {
    const float* c = confidence.ptr<float>(y);
    for (int x = 0; x < w; ++x) m.weight[m.At(y, x)] = std::max(c[x], floor);
  }
  local_planes::FitConstants constants;
  constants.space.resize(std::size_t((2 * r + 1) * (2 * r + 1)));
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      constants.space[std::size_t((dy + r) * (2 * r + 1) + dx + r)] =
          float(std::exp(-(dx * dx + dy * dy) / (2.0 * options.sigma_space * options.sigma_space)));
  const double s = options.sigma_colour * 255.0;
  constants.colour = MakeColourWeights(float(-1.0 / (2 * s * s)));
  constants.gap = float(options.max_label_gap);

  cv::Mat out = label.clone();
  if (slopes && (slopes->type() != CV_32FC2 || slopes->size() != label.size()))
    *slopes = cv::Mat(label.size(), CV_32FC2, cv::Scalar(0, 0));
  if (!options.refit_only.empty() &&
      (options.refit_only.type() != CV_8UC1 || options.refit_only.size() != label.size()))
    throw Error("FitLocalPlanes: the refit mask must be an 8-bit map of the labels' size");
  tbb::parallel_for(0, h, [&](int y) {
    const float* c = confidence.ptr<float>(y);
    const std::uint8_t* only =
        options.refit_only.empty() ? nullptr : options.refit_only.ptr<std::uint8_t>(y);
    const auto refit = [&](const float* cc, int x) {
      return x < w && cc[x] < options.refit_below_confidence && (!only || only[x] != 0);
    };
    std::vector<float> sums(std::size_t(local_planes::kSums * lanes));
    for (int x0 = 0; x0 < w; x0 += lanes) {
      bool any = false;
      for (int i = 0; i < lanes && !any; ++i) any = refit(c, x0 + i);
      if (!any) continue;
      HWY_DYNAMIC_DISPATCH(NeighbourhoodSumsT)(m, constants, y, x0, sums.data());
      for (int i = 0; i < lanes; ++i) {
        const int x = x0 + i;
        if (!refit(c, x)) continue;
        double sum[local_planes::kSums];
        for (int k = 0; k < local_planes::kSums; ++k)
          sum[k] = double(sums[std::size_t(k * lanes + i)]);
        double plane[3];
        if (!SolvePlane(sum, plane)) continue;
        out.at<float>(y, x) = label.at<float>(y, x) + float(plane[0]);
        if (slopes) slopes->at<cv::Vec2f>(y, x) = {float(plane[1]), float(plane[2])};
      }
    }
  });
  return out;
}

}  // namespace lfcam
#endif  // HWY_ONCE
