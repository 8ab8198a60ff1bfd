#pragma once
// FFmpeg's libraries (libavformat, libavcodec, libavutil, libswscale: Debian's packages), opened
// when lfcam first writes a video rather than when it starts. They and the codec libraries they
// bring are about 80 of the 250 shared libraries lfcam would otherwise load at every start, and
// 30% of its start-up (0.26 -> 0.19 s for `lfcam --version`; docs/benchmarks.md, "Start-up"),
// paid by every command, script and `import lfcam`, most of which write no video.
//
// The entry points are FFmpeg's own declarations (decltype of each), so a call through them is
// checked by the compiler as a direct call is.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

// Every FFmpeg function lfcam calls (share/mp4_writer.cpp).
// clang-format off
#define LFCAM_FFMPEG_FUNCTIONS(F) \
  F(av_strerror) \
  F(av_log_set_level) \
  F(av_d2q) \
  F(av_dict_set) \
  F(av_dict_free) \
  F(av_frame_alloc) \
  F(av_frame_free) \
  F(av_frame_get_buffer) \
  F(av_frame_make_writable) \
  F(av_packet_alloc) \
  F(av_packet_free) \
  F(av_packet_rescale_ts) \
  F(avcodec_find_encoder) \
  F(avcodec_find_encoder_by_name) \
  F(avcodec_alloc_context3) \
  F(avcodec_free_context) \
  F(avcodec_open2) \
  F(avcodec_parameters_from_context) \
  F(avcodec_send_frame) \
  F(avcodec_receive_packet) \
  F(avformat_alloc_output_context2) \
  F(avformat_new_stream) \
  F(avformat_free_context) \
  F(avformat_write_header) \
  F(av_interleaved_write_frame) \
  F(av_write_trailer) \
  F(avio_open) \
  F(avio_closep) \
  F(sws_getContext) \
  F(sws_freeContext) \
  F(sws_scale) \
  F(sws_setColorspaceDetails) \
  F(sws_getCoefficients)
// clang-format on

namespace lfcam {

// One FFmpeg function by name, from the libraries opened on the first call (once a process,
// from any thread). Throws lfcam::Error naming the library that could not be opened and the
// Debian package that provides it, or the function it lacks.
void* FfmpegFunction(const char* name);

// A table of FFmpeg functions, one member per name of a list such as LFCAM_FFMPEG_FUNCTIONS:
//   struct Table { LIST(LFCAM_FFMPEG_MEMBER)  void Find() { LIST(LFCAM_FFMPEG_FIND) } };
// FfmpegTable<Table>() finds them once a process and throws as FfmpegFunction does.
#define LFCAM_FFMPEG_MEMBER(name) decltype(&::name) name = nullptr;
#define LFCAM_FFMPEG_FIND(name) \
  name = reinterpret_cast<decltype(name)>(::lfcam::FfmpegFunction(#name));
template <typename Table>
const Table& FfmpegTable() {
  static const Table table = [] {
    Table t;
    t.Find();
    return t;
  }();
  return table;
}

struct FfmpegLibrary {
  LFCAM_FFMPEG_FUNCTIONS(LFCAM_FFMPEG_MEMBER)
  void Find() { LFCAM_FFMPEG_FUNCTIONS(LFCAM_FFMPEG_FIND) }
};

// FFmpeg's functions that lfcam calls, found on the first call.
inline const FfmpegLibrary& Ffmpeg() { return FfmpegTable<FfmpegLibrary>(); }

}  // namespace lfcam
