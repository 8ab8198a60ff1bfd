#include "lfcam/depth/disparity_map.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/depth/plane_sweep.h"

namespace lfcam {

cv::Mat DisparityOf(const LightField& lf, const DepthMap& map) {
  const StSampling sampling = lf.st_sampling(map.row, map.col);
  if (map.depth.type() != CV_32FC1 || map.n_s() != sampling.n_s || map.n_t() != sampling.n_t)
    throw Error(
        fmt::format("the depth map of view ({}, {}) is {}x{}, its light field's views {}x{}",
                    map.row, map.col, map.n_s(), map.n_t(), sampling.n_s, sampling.n_t));
  const Slab& slab = lf.slab();
  const double camera = DepthOf(slab, lf.camera_center(map.row, map.col));
  const double plane =
      DepthOf(slab, sampling.Point(0.5 * (sampling.n_s - 1), 0.5 * (sampling.n_t - 1))) - camera;
  const double scale = slab.uv.pitch_mm / sampling.ds_mm();
  cv::Mat out(map.depth.size(), CV_32FC1);
  for (int l = 0; l < map.n_t(); ++l)
    for (int k = 0; k < map.n_s(); ++k) {
      const double z = double(map.depth.at<float>(l, k)) - camera;
      out.at<float>(l, k) =
          std::isfinite(z) && z > 0 ? float(scale * (plane / z - 1.0)) : float(NAN);
    }
  return out;
}

int WriteDisparityPfm(const std::filesystem::path& path, const cv::Mat& disparity) {
  static_assert(std::endian::native == std::endian::little, "PFM is written little-endian");
  if (disparity.type() != CV_32FC1 || disparity.empty())
    throw Error(fmt::format("{}: a disparity map is one float per sample", path.string()));
  const std::string header = fmt::format("Pf\n{} {}\n-1.0\n", disparity.cols, disparity.rows);
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  int unknown = 0;
  // Row l = 0 is the bottom of the view: the PFM's first row.
  for (int l = 0; l < disparity.rows; ++l)
    for (int k = 0; k < disparity.cols; ++k) {
      float v = disparity.at<float>(l, k);
      if (!std::isfinite(v)) {
        v = 0.0f;
        ++unknown;
      }
      std::uint8_t b[4];
      std::memcpy(b, &v, 4);
      bytes.insert(bytes.end(), b, b + 4);
    }
  WriteFileAtomically(path, bytes);
  return unknown;
}

}  // namespace lfcam
