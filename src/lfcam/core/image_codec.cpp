#include "lfcam/core/image_codec.h"

#include <fmt/format.h>
#include <png.h>
#include <zlib.h>

#include <cstdlib>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/libjpeg_errors.h"

namespace lfcam {
namespace {

// The decoders' error paths jump over destructors (longjmp), so nothing between their setjmp and
// the jump may need one: the pixels live in a cv::Mat on the heap, held by a plain pointer that
// the error path deletes, and are moved out once the decode is done (no copy).
cv::Mat* NewPixels(int height, int width, int type) {
  try {
    return new cv::Mat(height, width, type);
  } catch (const std::exception&) {
    return nullptr;
  }
}

cv::Mat Adopt(cv::Mat* pixels) {
  cv::Mat m = std::move(*pixels);
  delete pixels;
  return m;
}

// ---- PNG ----

struct PngSource {
  const std::uint8_t* data;
  std::size_t size, at;
};

struct PngErrors {
  std::jmp_buf jump;
  char message[256];
};

void PngRead(png_structp png, png_bytep out, png_size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->size - source->at) png_error(png, "the file ends before the image does");
  std::memcpy(out, source->data + source->at, length);
  source->at += length;
}

void PngError(png_structp png, png_const_charp message) {
  auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
  std::snprintf(errors->message, sizeof errors->message, "%s", message);
  std::longjmp(errors->jump, 1);
}

void PngWarning(png_structp, png_const_charp) {}  // data libpng decodes around stays quiet

// The decode itself; an empty string on success, else libpng's reason.
std::string DecodePng(const std::uint8_t* data, std::size_t size, ImageDecodeMode mode,
                      cv::Mat** out) {
  PngErrors errors;
  errors.message[0] = '\0';
  PngSource source{data, size, 0};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, PngError, PngWarning);
  if (!png) return "out of memory";
  png_infop info = png_create_info_struct(png);
  // Changed after setjmp and read after a longjmp: volatile, so the values are not stale.
  cv::Mat* volatile pixels = nullptr;
  png_bytep* volatile rows = nullptr;
  if (setjmp(errors.jump)) {
    png_destroy_read_struct(&png, &info, nullptr);
    delete pixels;
    std::free(rows);
    return errors.message[0] ? errors.message : "decoding failed";
  }
  if (!info) png_error(png, "out of memory");
  png_set_read_fn(png, &source, PngRead);
  png_read_info(png, info);
  const int width = int(png_get_image_width(png, info));
  const int height = int(png_get_image_height(png, info));
  int depth = png_get_bit_depth(png, info);
  const int colour = png_get_color_type(png, info);
  const bool palette = colour == PNG_COLOR_TYPE_PALETTE;
  const bool grey = colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA;
  const bool palette_alpha = palette && png_get_valid(png, info, PNG_INFO_tRNS);
  const bool alpha = (colour & PNG_COLOR_MASK_ALPHA) != 0 || palette_alpha;
  if (palette) png_set_palette_to_rgb(png);
  if (palette_alpha) png_set_tRNS_to_alpha(png);
  if (grey && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (depth < 8) depth = 8;
  int channels = 0;
  if (mode == ImageDecodeMode::kUnchanged) {
    if (depth == 16) png_set_swap(png);  // PNG's samples are big-endian
    if (grey && alpha) png_set_gray_to_rgb(png);
    channels = grey && !alpha ? 1 : alpha ? 4 : 3;
  } else {
    if (depth == 16) png_set_strip_16(png);
    depth = 8;
    if (alpha) png_set_strip_alpha(png);
    if (mode == ImageDecodeMode::kGray8) {
      if (!grey) png_set_rgb_to_gray(png, 1, 0.299, 0.587);  // OpenCV's weights
      channels = 1;
    } else {
      if (grey) png_set_gray_to_rgb(png);
      channels = 3;
    }
  }
  if (channels >= 3) png_set_bgr(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t stride = std::size_t(width) * std::size_t(channels) * std::size_t(depth / 8);
  if (png_get_rowbytes(png, info) != stride) png_error(png, "an unexpected row layout");
  pixels = NewPixels(height, width, CV_MAKETYPE(depth == 16 ? CV_16U : CV_8U, channels));
  rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * std::size_t(height)));
  if (!pixels || !rows) png_error(png, "out of memory");
  for (int y = 0; y < height; ++y) rows[y] = pixels->ptr<std::uint8_t>(y);
  png_read_image(png, rows);
  png_destroy_read_struct(&png, &info, nullptr);
  std::free(rows);
  *out = pixels;
  return "";
}

struct PngSink {
  std::vector<std::uint8_t>* bytes;
};

void PngWrite(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  sink->bytes->insert(sink->bytes->end(), data, data + length);
}

void PngFlush(png_structp) {}

std::string EncodePng(const cv::Mat& image, std::vector<std::uint8_t>* bytes) {
  PngErrors errors;
  errors.message[0] = '\0';
  PngSink sink{bytes};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, PngError, PngWarning);
  if (!png) return "out of memory";
  png_infop info = png_create_info_struct(png);
  png_bytep* volatile rows = nullptr;
  if (setjmp(errors.jump)) {
    png_destroy_write_struct(&png, &info);
    std::free(rows);
    return errors.message[0] ? errors.message : "encoding failed";
  }
  if (!info) png_error(png, "out of memory");
  png_set_write_fn(png, &sink, PngWrite, PngFlush);
  const int channels = image.channels(), depth = image.depth() == CV_16U ? 16 : 8;
  const int colour = channels == 1   ? PNG_COLOR_TYPE_GRAY
                     : channels == 3 ? PNG_COLOR_TYPE_RGB
                                     : PNG_COLOR_TYPE_RGB_ALPHA;
  png_set_IHDR(png, info, png_uint_32(image.cols), png_uint_32(image.rows), depth, colour,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(png, Z_BEST_SPEED);
  png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, info);
  if (channels >= 3) png_set_bgr(png);
  if (depth == 16) png_set_swap(png);
  rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * std::size_t(image.rows)));
  if (!rows) png_error(png, "out of memory");
  for (int y = 0; y < image.rows; ++y) rows[y] = const_cast<png_bytep>(image.ptr<std::uint8_t>(y));
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::free(rows);
  return "";
}

// ---- JPEG ----

std::string DecodeJpeg(const std::uint8_t* data, std::size_t size, ImageDecodeMode mode,
                       int reduction, cv::Mat** out) {
  jpeg_decompress_struct cinfo;
  LibjpegErrors errors;
  cinfo.err = errors.install();
  cv::Mat* volatile pixels = nullptr;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&cinfo);
    delete pixels;
    return errors.message[0] ? errors.message : "decoding failed";
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK) {
    jpeg_destroy_decompress(&cinfo);
    return "CMYK JPEGs are not supported";
  }
  const bool grey = mode == ImageDecodeMode::kGray8 ||
                    (mode == ImageDecodeMode::kUnchanged && cinfo.num_components == 1);
  cinfo.out_color_space = grey ? JCS_GRAYSCALE : JCS_EXT_BGR;
  cinfo.scale_num = 1;
  cinfo.scale_denom = unsigned(reduction);
  jpeg_start_decompress(&cinfo);
  const int width = int(cinfo.output_width), height = int(cinfo.output_height);
  const int channels = int(cinfo.output_components);
  pixels = NewPixels(height, width, CV_MAKETYPE(CV_8U, channels));
  if (!pixels) {
    jpeg_destroy_decompress(&cinfo);
    return "out of memory";
  }
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = pixels->ptr<std::uint8_t>(int(cinfo.output_scanline));
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  if (errors.truncated) {
    delete pixels;
    return "the file ends before the image does";
  }
  *out = pixels;
  return "";
}

std::string EncodeJpeg(const cv::Mat& image, int quality, std::vector<std::uint8_t>* bytes) {
  jpeg_compress_struct cinfo;
  LibjpegErrors errors;
  cinfo.err = errors.install();
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&cinfo);
    std::free(buffer);
    return errors.message[0] ? errors.message : "encoding failed";
  }
  jpeg_create_compress(&cinfo);
  jpeg_mem_dest(&cinfo, &buffer, &size);
  cinfo.image_width = JDIMENSION(image.cols);
  cinfo.image_height = JDIMENSION(image.rows);
  cinfo.input_components = image.channels();
  cinfo.in_color_space = image.channels() == 1 ? JCS_GRAYSCALE : JCS_EXT_BGR;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.ptr<std::uint8_t>(int(cinfo.next_scanline)));
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  bytes->assign(buffer, buffer + size);
  jpeg_destroy_compress(&cinfo);
  std::free(buffer);
  return "";
}

void RequireEncodable(const cv::Mat& image, bool png) {
  const int type = image.type();
  const bool ok = png ? type == CV_8UC1 || type == CV_8UC3 || type == CV_8UC4 || type == CV_16UC1
                      : type == CV_8UC1 || type == CV_8UC3;
  if (!ok || image.empty())
    throw Error(fmt::format("cannot encode a {} image of type {} as {}",
                            image.empty() ? "empty" : "non-empty", type, png ? "PNG" : "JPEG"));
}

}  // namespace

cv::Mat DecodePngBytes(std::span<const std::uint8_t> bytes, ImageDecodeMode mode, int reduction,
                       std::string& error) {
  cv::Mat* pixels = nullptr;
  error = DecodePng(bytes.data(), bytes.size(), mode, &pixels);
  if (!error.empty()) return cv::Mat();
  cv::Mat m = Adopt(pixels);
  if (reduction > 1)
    cv::resize(m, m, cv::Size(m.cols / reduction, m.rows / reduction), 0, 0,
               cv::INTER_LINEAR_EXACT);
  return m;
}

cv::Mat DecodeJpegBytes(std::span<const std::uint8_t> bytes, ImageDecodeMode mode, int reduction,
                        std::string& error) {
  cv::Mat* pixels = nullptr;
  error = DecodeJpeg(bytes.data(), bytes.size(), mode, reduction, &pixels);
  if (!error.empty()) return cv::Mat();
  return Adopt(pixels);
}

std::vector<std::uint8_t> EncodePngBytes(const cv::Mat& image) {
  RequireEncodable(image, true);
  std::vector<std::uint8_t> bytes;
  const std::string error = EncodePng(image, &bytes);
  if (!error.empty()) throw Error("PNG encoding failed: " + error);
  return bytes;
}

std::vector<std::uint8_t> EncodeJpegBytes(const cv::Mat& image, int quality) {
  RequireEncodable(image, false);
  std::vector<std::uint8_t> bytes;
  const std::string error = EncodeJpeg(image, quality, &bytes);
  if (!error.empty()) throw Error("JPEG encoding failed: " + error);
  return bytes;
}

}  // namespace lfcam
