#pragma once
// Tests' reader of the MP4 files lfcam writes: every frame decoded to sRGB RGB (CV_8UC3), with
// the stream's frame rate and colour tags, through FFmpeg's libraries.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace lfcam::testing {

struct DecodedMp4 {
  std::vector<cv::Mat> frames;  // RGB, CV_8UC3
  double fps = 0;
  std::string codec;
  AVColorSpace colorspace = AVCOL_SPC_UNSPECIFIED;
  AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
};

inline DecodedMp4 DecodeMp4(const std::string& path) {
  DecodedMp4 out;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0)
    throw std::runtime_error("cannot open " + path);
  avformat_find_stream_info(format, nullptr);
  const AVCodec* decoder = nullptr;
  const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (index < 0 || decoder == nullptr) throw std::runtime_error("no video stream in " + path);
  AVStream* stream = format->streams[index];
  out.fps = av_q2d(stream->avg_frame_rate);
  out.codec = decoder->name;
  out.colorspace = stream->codecpar->color_space;
  out.range = stream->codecpar->color_range;
  AVCodecContext* codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(codec, stream->codecpar);
  avcodec_open2(codec, decoder, nullptr);
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  SwsContext* sws = nullptr;
  const auto drain = [&] {
    while (avcodec_receive_frame(codec, frame) == 0) {
      cv::Mat rgb(frame->height, frame->width, CV_8UC3);
      sws = sws_getCachedContext(sws, frame->width, frame->height, AVPixelFormat(frame->format),
                                 frame->width, frame->height, AV_PIX_FMT_RGB24,
                                 SWS_POINT | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr,
                                 nullptr, nullptr);
      sws_setColorspaceDetails(sws, sws_getCoefficients(SWS_CS_ITU709), 0,
                               sws_getCoefficients(SWS_CS_ITU709), 1, 0, 1 << 16, 1 << 16);
      std::uint8_t* target[1] = {rgb.data};
      const int stride[1] = {int(rgb.step[0])};
      sws_scale(sws, frame->data, frame->linesize, 0, frame->height, target, stride);
      out.frames.push_back(rgb);
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == index && avcodec_send_packet(codec, packet) >= 0) drain();
    av_packet_unref(packet);
  }
  avcodec_send_packet(codec, nullptr);
  drain();
  sws_freeContext(sws);
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  return out;
}

}  // namespace lfcam::testing
