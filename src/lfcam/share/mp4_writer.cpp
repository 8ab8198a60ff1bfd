#include "lfcam/share/mp4_writer.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <system_error>

#include "lfcam/core/error.h"
#include "lfcam/core/signal_cleanup.h"
#include "lfcam/share/ffmpeg_library.h"

namespace lfcam {
namespace {

std::string AvError(const FfmpegLibrary& ff, int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  ff.av_strerror(code, text, sizeof text);
  return text;
}

// libx264 by name (Debian's libavcodec has it); any other H.264 encoder otherwise.
const AVCodec* FindH264Encoder(const FfmpegLibrary& ff) {
  if (const AVCodec* codec = ff.avcodec_find_encoder_by_name("libx264")) return codec;
  return ff.avcodec_find_encoder(AV_CODEC_ID_H264);
}

}  // namespace

void RequireMp4Frame(int width, int height, const Mp4Options& options) {
  if (width <= 0 || height <= 0 || width % 2 != 0 || height % 2 != 0)
    throw UsageError(fmt::format(
        "a {}x{} video: H.264 in 4:2:0 (what players and browsers read) needs an even width "
        "and height",
        width, height));
  if (!(options.fps > 0.0 && options.fps <= 1000.0))
    throw UsageError(fmt::format("{} frames a second: must be in (0, 1000]", options.fps));
  if (options.crf < 0 || options.crf > 51)
    throw UsageError(fmt::format("crf {}: must be 0 (lossless) to 51", options.crf));
  if (FindH264Encoder(Ffmpeg()) == nullptr)
    throw Error("this FFmpeg (libavcodec) has no H.264 encoder: install Debian's libavcodec59");
}

struct Mp4Writer::State {
  const FfmpegLibrary& ff = Ffmpeg();
  std::filesystem::path path, temp_path;
  std::unique_ptr<TemporaryFileRegistration> registration;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  int width = 0, height = 0, frames = 0;
  bool header_written = false, finished = false;
  std::string encoder;

  [[noreturn]] void Fail(const std::string& what, int code) const {
    throw Error(fmt::format("{}: {}: {}", path.string(), what, AvError(ff, code)));
  }

  // Sends a frame (nullptr: the end) and writes every packet the encoder has ready.
  void Encode(AVFrame* input) {
    int status = ff.avcodec_send_frame(codec, input);
    if (status < 0) Fail("encoding a frame", status);
    while (true) {
      status = ff.avcodec_receive_packet(codec, packet);
      if (status == AVERROR(EAGAIN) || status == AVERROR_EOF) return;
      if (status < 0) Fail("encoding a frame", status);
      ff.av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      status = ff.av_interleaved_write_frame(format, packet);
      if (status < 0) Fail("writing a frame", status);
    }
  }

  ~State() {
    ff.sws_freeContext(sws);
    ff.av_packet_free(&packet);
    ff.av_frame_free(&frame);
    ff.avcodec_free_context(&codec);
    if (format != nullptr) {
      if (format->pb != nullptr) ff.avio_closep(&format->pb);
      ff.avformat_free_context(format);
    }
    if (!finished && !temp_path.empty()) {
      std::error_code ec;
      std::filesystem::remove(temp_path, ec);
    }
  }
};

Mp4Writer::Mp4Writer(const std::filesystem::path& path, int width, int height,
                     const Mp4Options& options)
    : state_(std::make_unique<State>()) {
  RequireMp4Frame(width, height, options);
  State& s = *state_;
  const FfmpegLibrary& ff = s.ff;
  s.path = path;
  s.width = width;
  s.height = height;
  s.temp_path = path;
  s.temp_path += fmt::format(".tmp-{}", long(::getpid()));
  s.registration = std::make_unique<TemporaryFileRegistration>(s.temp_path);
  ff.av_log_set_level(AV_LOG_ERROR);

  int status = ff.avformat_alloc_output_context2(&s.format, nullptr, "mp4", s.temp_path.c_str());
  if (status < 0 || s.format == nullptr) s.Fail("opening the MP4 muxer", status);
  const AVCodec* encoder = FindH264Encoder(ff);
  if (encoder == nullptr) throw Error(path.string() + ": this FFmpeg has no H.264 encoder");
  s.encoder = encoder->name;
  s.stream = ff.avformat_new_stream(s.format, nullptr);
  s.codec = ff.avcodec_alloc_context3(encoder);
  if (s.stream == nullptr || s.codec == nullptr) throw Error(path.string() + ": out of memory");
  s.codec->width = width;
  s.codec->height = height;
  s.codec->framerate = ff.av_d2q(options.fps, 100000);
  s.codec->time_base = av_inv_q(s.codec->framerate);
  s.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  s.codec->gop_size = std::max(1, int(std::lround(options.fps)));  // a key frame a second
  s.codec->thread_count = 0;  // x264's own choice: frame threads on every core
  s.codec->color_range = AVCOL_RANGE_MPEG;
  s.codec->colorspace = AVCOL_SPC_BT709;
  s.codec->color_primaries = AVCOL_PRI_BT709;
  s.codec->color_trc = AVCOL_TRC_IEC61966_2_1;  // the frames are sRGB-encoded
  if (s.format->oformat->flags & AVFMT_GLOBALHEADER) s.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* codec_options = nullptr;
  if (s.encoder == "libx264") {
    ff.av_dict_set(&codec_options, "preset", options.preset.c_str(), 0);
    ff.av_dict_set(&codec_options, "crf", std::to_string(options.crf).c_str(), 0);
  }
  status = ff.avcodec_open2(s.codec, encoder, &codec_options);
  ff.av_dict_free(&codec_options);
  if (status < 0) s.Fail(fmt::format("opening the {} encoder", s.encoder), status);
  status = ff.avcodec_parameters_from_context(s.stream->codecpar, s.codec);
  if (status < 0) s.Fail("setting up the video stream", status);
  s.stream->time_base = s.codec->time_base;
  s.stream->avg_frame_rate = s.codec->framerate;

  status = ff.avio_open(&s.format->pb, s.temp_path.c_str(), AVIO_FLAG_WRITE);
  if (status < 0) s.Fail("creating " + s.temp_path.string(), status);
  AVDictionary* muxer_options = nullptr;
  ff.av_dict_set(&muxer_options, "movflags", "+faststart", 0);
  status = ff.avformat_write_header(s.format, &muxer_options);
  ff.av_dict_free(&muxer_options);
  if (status < 0) s.Fail("writing the MP4 header", status);
  s.header_written = true;

  s.frame = ff.av_frame_alloc();
  s.packet = ff.av_packet_alloc();
  if (s.frame == nullptr || s.packet == nullptr) throw Error(path.string() + ": out of memory");
  s.frame->format = AV_PIX_FMT_YUV420P;
  s.frame->width = width;
  s.frame->height = height;
  s.frame->color_range = AVCOL_RANGE_MPEG;
  s.frame->colorspace = AVCOL_SPC_BT709;
  s.frame->color_primaries = AVCOL_PRI_BT709;
  s.frame->color_trc = AVCOL_TRC_IEC61966_2_1;
  status = ff.av_frame_get_buffer(s.frame, 0);
  if (status < 0) s.Fail("allocating a frame", status);
  // Full-range RGB to limited-range BT.709 Y'CbCr, chroma averaged over each 2x2 block.
  s.sws = ff.sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P,
                            SWS_AREA | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
  if (s.sws == nullptr) throw Error(path.string() + ": no RGB to Y'CbCr conversion");
  ff.sws_setColorspaceDetails(s.sws, ff.sws_getCoefficients(SWS_CS_ITU709), 1,
                              ff.sws_getCoefficients(SWS_CS_ITU709), 0, 0, 1 << 16, 1 << 16);
}

Mp4Writer::~Mp4Writer() = default;

void Mp4Writer::Write(const cv::Mat& srgb8_rgb) {
  State& s = *state_;
  const FfmpegLibrary& ff = s.ff;
  if (s.finished) throw Error(s.path.string() + ": frame written after Finish()");
  if (srgb8_rgb.type() != CV_8UC3 || srgb8_rgb.cols != s.width || srgb8_rgb.rows != s.height)
    throw Error(fmt::format("{}: frame {} is {}x{} ({} channels), the video is {}x{} RGB",
                            s.path.string(), s.frames, srgb8_rgb.cols, srgb8_rgb.rows,
                            srgb8_rgb.channels(), s.width, s.height));
  const int status = ff.av_frame_make_writable(s.frame);
  if (status < 0) s.Fail("allocating a frame", status);
  const cv::Mat rgb = srgb8_rgb.isContinuous() ? srgb8_rgb : srgb8_rgb.clone();
  const std::uint8_t* source[1] = {rgb.data};
  const int stride[1] = {int(rgb.step[0])};
  ff.sws_scale(s.sws, source, stride, 0, s.height, s.frame->data, s.frame->linesize);
  s.frame->pts = s.frames;
  s.Encode(s.frame);
  ++s.frames;
}

void Mp4Writer::Finish() {
  State& s = *state_;
  const FfmpegLibrary& ff = s.ff;
  if (s.finished) return;
  if (s.frames == 0) throw Error(s.path.string() + ": a video needs at least one frame");
  s.Encode(nullptr);
  int status = ff.av_write_trailer(s.format);
  if (status < 0) s.Fail("writing the MP4 index", status);
  status = ff.avio_closep(&s.format->pb);
  if (status < 0) s.Fail("closing " + s.temp_path.string(), status);
  std::error_code ec;
  std::filesystem::rename(s.temp_path, s.path, ec);
  if (ec)
    throw Error(fmt::format("{}: cannot move {} into place: {}", s.path.string(),
                            s.temp_path.string(), ec.message()));
  s.finished = true;
}

int Mp4Writer::frames() const { return state_->frames; }
const std::string& Mp4Writer::encoder_name() const { return state_->encoder; }

}  // namespace lfcam
