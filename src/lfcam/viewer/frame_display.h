#pragma once
// Draws a rendered frame into the viewer's window: a linear RGB float texture (the GL renderer's
// output, or a CPU frame uploaded) scaled into a rectangle of the window and encoded to sRGB on
// the way (the window's framebuffer is not assumed to be sRGB-capable).
#include <opencv2/core.hpp>

namespace lfcam {

class FrameDisplay {
 public:
  FrameDisplay();  // needs a current GL 3.3+ context
  ~FrameDisplay();
  FrameDisplay(const FrameDisplay&) = delete;
  FrameDisplay& operator=(const FrameDisplay&) = delete;

  // Uploads a CPU frame (CV_32FC3, linear, row 0 at the top) into the display's own texture.
  void Upload(const cv::Mat& linear_rgb);
  unsigned uploaded_texture() const { return texture_; }

  // Draws `texture` (row 0 at the top when `top_down`, as an uploaded frame; at the bottom as
  // the GL renderer writes) to fill the window's framebuffer of the given size.
  void Draw(unsigned texture, bool top_down, int framebuffer_width, int framebuffer_height) const;

 private:
  unsigned program_ = 0, vertex_array_ = 0, texture_ = 0;
  int texture_width_ = 0, texture_height_ = 0;
};

}  // namespace lfcam
