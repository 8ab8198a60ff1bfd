#include "lfcam/core/jpeg_region.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "lfcam/core/chroma_upsampling.h"
#include "lfcam/core/error.h"
#include "lfcam/core/libjpeg_errors.h"
#include "lfcam/core/limits.h"

namespace lfcam {
namespace {

// How many luma samples a YCbCr JPEG has per chroma sample each way, when that is 1 or 2 and
// both chroma components are sampled alike; (0, 0) for anything else (grey, CMYK, RGB, odd
// factors), which libjpeg converts as usual.
cv::Size ChromaFactor(const jpeg_decompress_struct& cinfo) {
  if (cinfo.num_components != 3 || cinfo.jpeg_color_space != JCS_YCbCr) return {0, 0};
  const jpeg_component_info* c = cinfo.comp_info;
  for (int i = 1; i < 3; ++i)
    if (c[i].h_samp_factor != 1 || c[i].v_samp_factor != 1) return {0, 0};
  if (c[0].h_samp_factor < 1 || c[0].h_samp_factor > 2 || c[0].v_samp_factor < 1 ||
      c[0].v_samp_factor > 2)
    return {0, 0};
  return {c[0].h_samp_factor, c[0].v_samp_factor};
}

// The decode itself, with only trivially destructible locals between setjmp and longjmp.
// Returns an empty string on success, else libjpeg's message. With `*chroma_factor` set to
// anything but 1 x 1 on return, out->rgb holds Y, Cb, Cr with each chroma sample repeated over
// its luma pixels (libjpeg's plain upsampling), the region starting on a chroma sample.
std::string Decode(const std::uint8_t* data, std::size_t size, int reduction, cv::Rect region,
                   ChromaUpsampling chroma, JpegRegion* out, cv::Size* chroma_factor) {
  jpeg_decompress_struct cinfo;
  LibjpegErrors error;
  cinfo.err = error.install();
  // Changed after setjmp and read after a longjmp: volatile, so the value is not stale.
  std::uint8_t* volatile pixels = nullptr;
  std::size_t stride = 0;
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&cinfo);
    std::free(pixels);
    return error.message[0] ? error.message : "decoding failed";
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.image_width > unsigned(kMaxImageSide) || cinfo.image_height > unsigned(kMaxImageSide)) {
    jpeg_destroy_decompress(&cinfo);
    return fmt::format("a {}x{} image is larger than the limit of {} pixels a side",
                       cinfo.image_width, cinfo.image_height, kMaxImageSide);
  }
  cinfo.scale_num = 1;
  cinfo.scale_denom = unsigned(reduction);
  *chroma_factor = ChromaFactor(cinfo);
  const bool guided =
      chroma == ChromaUpsampling::kGuided && reduction == 1 && chroma_factor->area() > 1;
  if (guided) {
    cinfo.out_color_space = JCS_YCbCr;
    cinfo.do_fancy_upsampling = FALSE;
  } else {
    *chroma_factor = cv::Size(1, 1);
    cinfo.out_color_space = JCS_EXT_RGB;
  }
  jpeg_start_decompress(&cinfo);
  const int width = int(cinfo.output_width), height = int(cinfo.output_height);
  out->scaled = cv::Size(width, height);
  region &= cv::Rect(0, 0, width, height);
  // Chroma upsampling reads a pixel's neighbours: at the edges of a crop they are replicated, so
  // a few columns there differ from a whole decode. Decode a block more on each side.
  if (region.area() > 0)
    region = cv::Rect(region.x - 16, region.y - 16, region.width + 32, region.height + 32) &
             cv::Rect(0, 0, width, height);
  if (guided && region.area() > 0) {  // whole chroma samples: start and end on even rows
    const int fy = chroma_factor->height;
    const int y0 = region.y - region.y % fy;
    const int y1 = std::min(height, (region.y + region.height + fy - 1) / fy * fy);
    region = cv::Rect(region.x, y0, region.width, y1 - y0);
  }
  if (region.area() == 0) {
    jpeg_abort_decompress(&cinfo);
    jpeg_destroy_decompress(&cinfo);
    out->rgb = cv::Mat();
    out->origin = cv::Point(0, 0);
    return "";
  }
  JDIMENSION x = JDIMENSION(region.x), w = JDIMENSION(region.width);
  jpeg_crop_scanline(&cinfo, &x, &w);  // widens to block boundaries
  if (region.y > 0) jpeg_skip_scanlines(&cinfo, JDIMENSION(region.y));
  stride = std::size_t(w) * 3;
  pixels = static_cast<std::uint8_t*>(std::malloc(stride * std::size_t(region.height)));
  if (!pixels) {
    jpeg_destroy_decompress(&cinfo);
    return "out of memory";
  }
  for (int row = 0; row < region.height;) {
    JSAMPROW line = pixels + std::size_t(row) * stride;
    const JDIMENSION n = jpeg_read_scanlines(&cinfo, &line, 1);
    if (n == 0) break;
    row += int(n);
  }
  jpeg_abort_decompress(&cinfo);  // the rows below are not needed
  jpeg_destroy_decompress(&cinfo);
  if (error.truncated) {
    std::free(pixels);
    return "the file ends before the image does";
  }
  out->rgb = cv::Mat(region.height, int(w), CV_8UC3, pixels).clone();
  std::free(pixels);
  out->origin = cv::Point(int(x), region.y);
  return "";
}

// Y, Cb, Cr with chroma repeated over each `factor` block (from Decode) to R, G, B.
cv::Mat GuidedRgb(const cv::Mat& ycc, cv::Size factor) {
  cv::Mat luma;
  cv::extractChannel(ycc, luma, 0);
  const cv::Size low((ycc.cols + factor.width - 1) / factor.width,
                     (ycc.rows + factor.height - 1) / factor.height);
  cv::Mat cb(low, CV_8UC1), cr(low, CV_8UC1);
  for (int row = 0; row < low.height; ++row) {
    const cv::Vec3b* in = ycc.ptr<cv::Vec3b>(row * factor.height);
    for (int x = 0; x < low.width; ++x) {
      cb.at<std::uint8_t>(row, x) = in[x * factor.width][1];
      cr.at<std::uint8_t>(row, x) = in[x * factor.width][2];
    }
  }
  return GuidedChromaToRgb(luma, cb, cr, factor);
}

}  // namespace

ChromaUpsampling ChromaUpsamplingFromString(const std::string& name) {
  if (name == "guided") return ChromaUpsampling::kGuided;
  if (name == "interpolated") return ChromaUpsampling::kInterpolated;
  throw Error(fmt::format("'{}' is not a chroma upsampling (guided, interpolated)", name));
}

std::string ToString(ChromaUpsampling chroma) {
  return chroma == ChromaUpsampling::kGuided ? "guided" : "interpolated";
}

bool LooksLikeJpeg(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

JpegRegion DecodeJpegRegion(std::span<const std::uint8_t> bytes, const std::string& name,
                            int reduction, cv::Rect region, ChromaUpsampling chroma) {
  if (reduction != 1 && reduction != 2 && reduction != 4 && reduction != 8)
    throw Error(fmt::format("{}: JPEG reduction {} is not 1, 2, 4 or 8", name, reduction));
  if (!LooksLikeJpeg(bytes)) throw Error(fmt::format("{}: not a JPEG file", name));
  JpegRegion out;
  cv::Size chroma_factor(1, 1);
  const std::string message =
      Decode(bytes.data(), bytes.size(), reduction, region, chroma, &out, &chroma_factor);
  if (!message.empty())
    throw Error(
        fmt::format("{}: not a readable JPEG image (corrupt or truncated): {}", name, message));
  if (chroma_factor != cv::Size(1, 1) && !out.rgb.empty())
    out.rgb = GuidedRgb(out.rgb, chroma_factor);
  return out;
}

}  // namespace lfcam
