#include "lfcam/core/lightfield_compare.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "lfcam/core/error.h"

namespace lfcam {

LightFieldComparison CompareLightFields(const LightField& a, const LightField& b) {
  if (a.dims() != b.dims())
    throw Error(
        fmt::format("the light fields differ in shape: {}x{} views of {}x{} against "
                    "{}x{} of {}x{}",
                    a.dims().rows, a.dims().cols, a.dims().n_s, a.dims().n_t, b.dims().rows,
                    b.dims().cols, b.dims().n_s, b.dims().n_t));
  if (a.sample_type() != SampleType::kSrgb8 || b.sample_type() != SampleType::kSrgb8)
    throw Error("only srgb8 light fields can be compared");
  if (a.st_offsets() != b.st_offsets())
    throw Error(
        "the light fields' views sample different st windows (format version 4): their samples "
        "are not the same points; compare renders instead");
  const auto& d = a.dims();
  LightFieldComparison out;
  out.worst_view_psnr_db = std::numeric_limits<double>::infinity();
  double squared = 0, absolute = 0, ssim = 0;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      const cv::Mat va(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(a.view_data(r, c)));
      const cv::Mat vb(d.n_t, d.n_s, CV_8UC3, const_cast<std::uint8_t*>(b.view_data(r, c)));
      const ImageComparison v = CompareImages(va, vb);
      const double mse =
          std::isinf(v.psnr_db) ? 0.0 : 255.0 * 255.0 / std::pow(10.0, v.psnr_db / 10);
      squared += mse * double(v.pixels);
      absolute += v.mean_abs_error * double(v.pixels);
      ssim += v.ssim;
      out.all.pixels += v.pixels;
      if (v.psnr_db < out.worst_view_psnr_db) {
        out.worst_view_psnr_db = v.psnr_db;
        out.worst_row = r;
        out.worst_col = c;
      }
    }
  const double mse = squared / double(out.all.pixels);
  out.all.psnr_db =
      mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
  out.all.mean_abs_error = absolute / double(out.all.pixels);
  out.all.ssim = ssim / double(d.view_count());
  return out;
}

}  // namespace lfcam
