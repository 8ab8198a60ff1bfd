#pragma once
// An H.264 video in an MP4 file, written through FFmpeg's libraries (libavcodec's libx264
// encoder, libavformat's MP4 muxer; Debian's packages): what `lfcam render --video` and
// `lfcam export --format quilt` of a recording write, playable in any browser and player.
//
// Frames are sRGB, 8 bits a channel; they are stored as 4:2:0 Y'CbCr (BT.709, limited range,
// tagged so: what browsers and players expect), so the width and height must be even. The
// index sits at the front of the file (faststart), so a browser starts playing before the whole
// file is downloaded. The file appears only when Finish() succeeds: until then the bytes go to
// a temporary name beside it, removed if the writer is destroyed unfinished or a signal ends
// the process (core/signal_cleanup.h).
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace lfcam {

struct Mp4Options {
  double fps = 30.0;
  // x264's constant rate factor: 0 (lossless) to 51; 18 looks like the source to most eyes.
  int crf = 18;
  // x264's speed preset: ultrafast ... veryslow (docs/benchmarks.md measures the choice).
  std::string preset = "veryfast";
};

// Throws lfcam::UsageError when `width` or `height` is odd or not positive, or fps or crf make
// no sense, naming them; lfcam::Error when FFmpeg has no H.264 encoder.
void RequireMp4Frame(int width, int height, const Mp4Options& options);

class Mp4Writer {
 public:
  // Opens the encoder and the temporary file; throws lfcam::Error (naming `path`).
  Mp4Writer(const std::filesystem::path& path, int width, int height, const Mp4Options& options);
  ~Mp4Writer();
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  // The next frame: CV_8UC3, RGB order, width x height. Throws lfcam::Error.
  void Write(const cv::Mat& srgb8_rgb);
  // Flushes the encoder, writes the index and renames the file into place.
  void Finish();
  int frames() const;
  const std::string& encoder_name() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lfcam
