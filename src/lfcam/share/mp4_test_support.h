#pragma once
// Tests' reader of the MP4 files lfcam writes: every frame decoded to sRGB RGB (CV_8UC3), with
// the stream's frame rate and colour tags, through FFmpeg's libraries, opened as lfcam opens
// them (share/ffmpeg_library.h: the tests link no FFmpeg either).
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "lfcam/share/ffmpeg_library.h"

namespace lfcam::testing {

// The decoder's functions, beside the writer's (Ffmpeg()).
// clang-format off
#define LFCAM_FFMPEG_DECODER_FUNCTIONS(F) \
  F(avformat_open_input) \
  F(avformat_find_stream_info) \
  F(av_find_best_stream) \
  F(avcodec_parameters_to_context) \
  F(av_read_frame) \
  F(av_packet_unref) \
  F(avcodec_send_packet) \
  F(avcodec_receive_frame) \
  F(sws_getCachedContext) \
  F(avformat_close_input)
// clang-format on

struct FfmpegDecoder {
  LFCAM_FFMPEG_DECODER_FUNCTIONS(LFCAM_FFMPEG_MEMBER)
  void Find() { LFCAM_FFMPEG_DECODER_FUNCTIONS(LFCAM_FFMPEG_FIND) }
};

inline const FfmpegDecoder& Decoder() { return FfmpegTable<FfmpegDecoder>(); }

struct DecodedMp4 {
  std::vector<cv::Mat> frames;  // RGB, CV_8UC3
  double fps = 0;
  std::string codec;
  AVColorSpace colorspace = AVCOL_SPC_UNSPECIFIED;
  AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
};

inline DecodedMp4 DecodeMp4(const std::string& path) {
  const FfmpegLibrary& ff = Ffmpeg();
  const FfmpegDecoder& fd = Decoder();
  DecodedMp4 out;
  AVFormatContext* format = nullptr;
  if (fd.avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0)
    throw std::runtime_error("cannot open " + path);
  fd.avformat_find_stream_info(format, nullptr);
  const AVCodec* decoder = nullptr;
  const int index = fd.av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (index < 0 || decoder == nullptr) throw std::runtime_error("no video stream in " + path);
  AVStream* stream = format->streams[index];
  out.fps = av_q2d(stream->avg_frame_rate);
  out.codec = decoder->name;
  out.colorspace = stream->codecpar->color_space;
  out.range = stream->codecpar->color_range;
  AVCodecContext* codec = ff.avcodec_alloc_context3(decoder);
  fd.avcodec_parameters_to_context(codec, stream->codecpar);
  ff.avcodec_open2(codec, decoder, nullptr);
  AVPacket* packet = ff.av_packet_alloc();
  AVFrame* frame = ff.av_frame_alloc();
  SwsContext* sws = nullptr;
  const auto drain = [&] {
    while (fd.avcodec_receive_frame(codec, frame) == 0) {
      cv::Mat rgb(frame->height, frame->width, CV_8UC3);
      sws = fd.sws_getCachedContext(sws, frame->width, frame->height, AVPixelFormat(frame->format),
                                    frame->width, frame->height, AV_PIX_FMT_RGB24,
                                    SWS_POINT | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr,
                                    nullptr, nullptr);
      ff.sws_setColorspaceDetails(sws, ff.sws_getCoefficients(SWS_CS_ITU709), 0,
                                  ff.sws_getCoefficients(SWS_CS_ITU709), 1, 0, 1 << 16, 1 << 16);
      std::uint8_t* target[1] = {rgb.data};
      const int stride[1] = {int(rgb.step[0])};
      ff.sws_scale(sws, frame->data, frame->linesize, 0, frame->height, target, stride);
      out.frames.push_back(rgb);
    }
  };
  while (fd.av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == index && fd.avcodec_send_packet(codec, packet) >= 0) drain();
    fd.av_packet_unref(packet);
  }
  fd.avcodec_send_packet(codec, nullptr);
  drain();
  ff.sws_freeContext(sws);
  ff.av_frame_free(&frame);
  ff.av_packet_free(&packet);
  ff.avcodec_free_context(&codec);
  fd.avformat_close_input(&format);
  return out;
}

}  // namespace lfcam::testing
