#include "lfcam/depth/local_planes.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "lfcam/core/error.h"

namespace lfcam {

cv::Mat FitLocalPlanes(const cv::Mat& label, const cv::Mat& guide_rgb8, const cv::Mat& confidence,
                       const LocalPlaneOptions& options, cv::Mat* slopes) {
  if (label.type() != CV_32FC1 || guide_rgb8.type() != CV_8UC3 || confidence.type() != CV_32FC1 ||
      guide_rgb8.size() != label.size() || confidence.size() != label.size())
    throw Error(
        "FitLocalPlanes: labels, guide and confidence must be float, RGB8 and float maps "
        "of one size");
  const int w = label.cols, h = label.rows, r = std::max(0, options.radius);
  // The weights' factors as tables: distance per offset, colour per squared 8-bit difference.
  std::vector<float> space(std::size_t((2 * r + 1) * (2 * r + 1)));
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      space[std::size_t((dy + r) * (2 * r + 1) + dx + r)] =
          float(std::exp(-(dx * dx + dy * dy) / (2.0 * options.sigma_space * options.sigma_space)));
  constexpr int kMaxColour = 3 * 255 * 255;
  std::vector<float> colour(kMaxColour + 1);
  const double s = options.sigma_colour * 255.0;
  for (int d2 = 0; d2 <= kMaxColour; ++d2)
    colour[std::size_t(d2)] = float(std::exp(-d2 / (2 * s * s)));
  const float gap = float(options.max_label_gap), floor = float(options.min_confidence);

  cv::Mat out = label.clone();
  if (slopes && (slopes->type() != CV_32FC2 || slopes->size() != label.size()))
    *slopes = cv::Mat(label.size(), CV_32FC2, cv::Scalar(0, 0));
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      if (!(confidence.at<float>(y, x) < options.refit_below_confidence)) continue;
      const float own = label.at<float>(y, x);
      const cv::Vec3b c0 = guide_rgb8.at<cv::Vec3b>(y, x);
      // Sums over the neighbourhood of weight times 1, dx, dy, dx², dy², dx·dy, label,
      // label·dx, label·dy; labels taken relative to the sample's own (better conditioned).
      double s0 = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sl = 0, slx = 0, sly = 0;
      for (int dy = -r; dy <= r; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= h) continue;
        const float* lrow = label.ptr<float>(yy);
        const float* crow = confidence.ptr<float>(yy);
        const cv::Vec3b* grow = guide_rgb8.ptr<cv::Vec3b>(yy);
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx;
          if (xx < 0 || xx >= w) continue;
          const float l = lrow[xx] - own;
          if (!(std::abs(l) <= gap)) continue;
          const int dr = int(grow[xx][0]) - c0[0], dg = int(grow[xx][1]) - c0[1],
                    db = int(grow[xx][2]) - c0[2];
          const double wgt = double(space[std::size_t((dy + r) * (2 * r + 1) + dx + r)]) *
                             colour[std::size_t(dr * dr + dg * dg + db * db)] *
                             std::max(crow[xx], floor);
          s0 += wgt, sx += wgt * dx, sy += wgt * dy;
          sxx += wgt * dx * dx, syy += wgt * dy * dy, sxy += wgt * dx * dy;
          sl += wgt * l, slx += wgt * l * dx, sly += wgt * l * dy;
        }
      }
      if (s0 <= 0) continue;
      // The normal equations [s0 sx sy; sx sxx sxy; sy sxy syy] [a b c]' = [sl slx sly]',
      // the slopes lightly damped (a neighbourhood along a line fixes no slope across it).
      const double damp = 1e-3 * s0;
      const double a11 = s0, a12 = sx, a13 = sy, a22 = sxx + damp, a23 = sxy, a33 = syy + damp;
      const double c11 = a22 * a33 - a23 * a23, c12 = a13 * a23 - a12 * a33,
                   c13 = a12 * a23 - a13 * a22;
      const double det = a11 * c11 + a12 * c12 + a13 * c13;
      if (!(std::abs(det) > 1e-12 * s0 * s0 * s0)) continue;
      const double a = (sl * c11 + slx * c12 + sly * c13) / det;
      out.at<float>(y, x) = own + float(a);
      if (slopes) {
        const double c22 = a11 * a33 - a13 * a13, c23 = a12 * a13 - a11 * a23,
                     c33 = a11 * a22 - a12 * a12;
        const double b = (sl * c12 + slx * c22 + sly * c23) / det,
                     c = (sl * c13 + slx * c23 + sly * c33) / det;
        slopes->at<cv::Vec2f>(y, x) = {float(b), float(c)};
      }
    }
  });
  return out;
}

}  // namespace lfcam
