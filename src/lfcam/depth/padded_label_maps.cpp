#include "lfcam/depth/padded_label_maps.h"

#include <limits>

namespace lfcam {

PaddedLabelMaps PadLabelMaps(const cv::Mat& label, const cv::Mat& guide_rgb8, int radius,
                             int lanes) {
  PaddedLabelMaps m;
  m.width = label.cols;
  m.height = label.rows;
  m.radius = radius;
  const int vectors = (m.width + lanes - 1) / lanes;
  m.stride = std::size_t(vectors * lanes + 2 * radius);
  const std::size_t padded = m.stride * std::size_t(m.height);
  m.label.assign(padded, std::numeric_limits<float>::quiet_NaN());
  for (auto* map : {&m.red, &m.green, &m.blue}) map->assign(padded, 0.0f);
  for (int y = 0; y < m.height; ++y) {
    const float* l = label.ptr<float>(y);
    const cv::Vec3b* g = guide_rgb8.ptr<cv::Vec3b>(y);
    for (int x = 0; x < m.width; ++x) {
      const std::size_t at = m.At(y, x);
      m.label[at] = l[x];
      m.red[at] = g[x][0];
      m.green[at] = g[x][1];
      m.blue[at] = g[x][2];
    }
  }
  return m;
}

}  // namespace lfcam
