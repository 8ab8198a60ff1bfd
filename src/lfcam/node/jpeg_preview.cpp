#include "lfcam/node/jpeg_preview.h"

#include <fmt/format.h>

#include <vector>

#include "lfcam/core/error.h"
#include "lfcam/core/libjpeg_errors.h"

namespace lfcam {

std::string ScaledJpeg(std::string_view jpeg, int max_width, int quality, const std::string& name) {
  jpeg_decompress_struct in{};
  jpeg_compress_struct out{};
  LibjpegErrors errors;
  std::vector<unsigned char> pixels;
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  in.err = errors.install();
  out.err = in.err;
  jpeg_create_decompress(&in);
  jpeg_create_compress(&out);
  auto cleanup = [&] {
    jpeg_destroy_decompress(&in);
    jpeg_destroy_compress(&out);
    std::free(buffer);
  };
  if (setjmp(errors.jump) != 0) {
    const std::string message = errors.message;
    cleanup();
    throw Error(fmt::format("{}: not a readable JPEG: {}", name, message));
  }
  jpeg_mem_src(&in, reinterpret_cast<const unsigned char*>(jpeg.data()), jpeg.size());
  jpeg_read_header(&in, TRUE);
  in.out_color_space = JCS_RGB;
  in.scale_num = 1;
  in.scale_denom = 1;
  while (in.scale_denom < 8 && int(in.image_width / in.scale_denom) > max_width)
    in.scale_denom *= 2;
  jpeg_start_decompress(&in);
  const std::size_t stride = std::size_t(in.output_width) * 3;
  pixels.resize(stride * in.output_height);
  while (in.output_scanline < in.output_height) {
    unsigned char* row = pixels.data() + stride * in.output_scanline;
    jpeg_read_scanlines(&in, &row, 1);
  }
  jpeg_finish_decompress(&in);

  jpeg_mem_dest(&out, &buffer, &size);
  out.image_width = in.output_width;
  out.image_height = in.output_height;
  out.input_components = 3;
  out.in_color_space = JCS_RGB;
  jpeg_set_defaults(&out);
  jpeg_set_quality(&out, quality, TRUE);
  jpeg_start_compress(&out, TRUE);
  while (out.next_scanline < out.image_height) {
    unsigned char* row = pixels.data() + stride * out.next_scanline;
    jpeg_write_scanlines(&out, &row, 1);
  }
  jpeg_finish_compress(&out);
  std::string result(reinterpret_cast<const char*>(buffer), size);
  cleanup();
  return result;
}

}  // namespace lfcam
