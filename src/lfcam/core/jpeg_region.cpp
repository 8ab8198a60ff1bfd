#include "lfcam/core/jpeg_region.h"

#include <fmt/format.h>

#include <cstdlib>
#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/libjpeg_errors.h"
#include "lfcam/core/limits.h"

namespace lfcam {
namespace {

// The decode itself, with only trivially destructible locals between setjmp and longjmp.
// Returns an empty string on success, else libjpeg's message.
std::string Decode(const std::uint8_t* data, std::size_t size, int reduction, cv::Rect region,
                   JpegRegion* out) {
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
  cinfo.out_color_space = JCS_EXT_RGB;
  jpeg_start_decompress(&cinfo);
  const int width = int(cinfo.output_width), height = int(cinfo.output_height);
  out->scaled = cv::Size(width, height);
  region &= cv::Rect(0, 0, width, height);
  // Chroma upsampling reads a pixel's neighbours: at the edges of a crop they are replicated, so
  // a few columns there differ from a whole decode. Decode a block more on each side.
  if (region.area() > 0)
    region = cv::Rect(region.x - 16, region.y - 16, region.width + 32, region.height + 32) &
             cv::Rect(0, 0, width, height);
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

}  // namespace

bool LooksLikeJpeg(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

JpegRegion DecodeJpegRegion(std::span<const std::uint8_t> bytes, const std::string& name,
                            int reduction, cv::Rect region) {
  if (reduction != 1 && reduction != 2 && reduction != 4 && reduction != 8)
    throw Error(fmt::format("{}: JPEG reduction {} is not 1, 2, 4 or 8", name, reduction));
  if (!LooksLikeJpeg(bytes)) throw Error(fmt::format("{}: not a JPEG file", name));
  JpegRegion out;
  const std::string message = Decode(bytes.data(), bytes.size(), reduction, region, &out);
  if (!message.empty())
    throw Error(
        fmt::format("{}: not a readable JPEG image (corrupt or truncated): {}", name, message));
  return out;
}

}  // namespace lfcam
