#include "record/mp4.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
}

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "io/output.h"
#include "record/yuv.h"

namespace record {

namespace {
std::string av_error(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof buf);
  return buf;
}
// Every libav call goes through here: a negative code becomes a RuntimeFault naming the call.
int check(int code, const char* what) {
  if (code < 0)
    throw core::RuntimeFault(std::string("video encoder: ") + what + " failed: " + av_error(code));
  return code;
}
using Clock = std::chrono::steady_clock;
}  // namespace

void validate(const VideoSettings& v) {
  auto even_in_range = [](int x) { return x >= 16 && x <= 8192 && x % 2 == 0; };
  if (!even_in_range(v.width) || !even_in_range(v.height))
    throw core::InputError("--size " + std::to_string(v.width) + "x" + std::to_string(v.height) +
                           ": a movie needs even width and height from 16 to 8192 pixels (yuv420p)");
  if (v.fps < 1 || v.fps > 240)
    throw core::InputError("--fps " + std::to_string(v.fps) + ": allowed range is 1 to 240");
  if (v.crf < 0 || v.crf > 51)
    throw core::InputError("--crf " + std::to_string(v.crf) + ": allowed range is 0 to 51");
  static const char* presets[] = {"ultrafast", "superfast", "veryfast", "faster",  "fast",
                                  "medium",    "slow",      "slower",   "veryslow"};
  bool ok = false;
  for (const char* p : presets) ok = ok || v.preset == p;
  if (!ok)
    throw core::InputError(
        "--preset " + v.preset +
        ": expected ultrafast, superfast, veryfast, faster, fast, medium, slow, slower or veryslow");
}

struct Mp4Writer::Impl {
  std::filesystem::path final_path, partial_path;
  VideoSettings s;
  AVFormatContext* oc = nullptr;
  AVCodecContext* c = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* pkt = nullptr;
  long frames = 0;
  bool finished = false, header_written = false;
  double convert_s = 0, encode_s = 0;

  void drain(bool flushing) {
    for (;;) {
      int r = avcodec_receive_packet(c, pkt);
      if (r == AVERROR(EAGAIN) || (flushing && r == AVERROR_EOF)) return;
      check(r, "avcodec_receive_packet");
      // libx264 leaves durations at 0: one frame in the codec's time base, or the file probes a frame short.
      if (pkt->duration == 0) pkt->duration = 1;
      av_packet_rescale_ts(pkt, c->time_base, stream->time_base);
      pkt->stream_index = stream->index;
      check(av_interleaved_write_frame(oc, pkt), "av_interleaved_write_frame");
    }
  }

  void release() {
    av_packet_free(&pkt);
    av_frame_free(&frame);
    avcodec_free_context(&c);
    if (oc) {
      if (oc->pb) avio_closep(&oc->pb);
      avformat_free_context(oc);
      oc = nullptr;
    }
  }
};

Mp4Writer::Mp4Writer(std::filesystem::path final_path, const VideoSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  validate(settings);
  Impl& m = *impl_;
  m.s = settings;
  m.final_path = std::move(final_path);
  m.partial_path = m.final_path;
  m.partial_path += ".partial";
  av_log_set_level(AV_LOG_ERROR);  // x264's statistics are noise on the user's terminal
  try {
    check(avformat_alloc_output_context2(&m.oc, nullptr, "mp4", m.partial_path.c_str()),
          "avformat_alloc_output_context2");
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) throw core::RuntimeFault("video encoder: libx264 is not available in this FFmpeg build");
    m.stream = avformat_new_stream(m.oc, nullptr);
    m.c = avcodec_alloc_context3(codec);
    m.frame = av_frame_alloc();
    m.pkt = av_packet_alloc();
    if (!m.stream || !m.c || !m.frame || !m.pkt) throw core::RuntimeFault("video encoder: out of memory");
    m.c->width = m.s.width;
    m.c->height = m.s.height;
    // The exact frame rate as a fraction (1000/33 for 33 steps of 1 ms per frame), so every timestamp is the
    // real time of the state shown; x264 and MP4 take any rational rate.
    const AVRational rate = m.s.frame_rate > 0 ? av_d2q(m.s.frame_rate, 100000) : AVRational{m.s.fps, 1};
    m.c->time_base = AVRational{rate.den, rate.num};
    m.c->framerate = rate;
    m.c->pix_fmt = AV_PIX_FMT_YUV420P;
    m.c->gop_size = 2 * m.s.fps;  // keyframe interval in frames  // a keyframe every 2 s: quick seeking in
                                  // players and the inspector
    m.c->color_primaries = AVCOL_PRI_BT709;
    m.c->color_trc = AVCOL_TRC_BT709;
    m.c->colorspace = AVCOL_SPC_BT709;
    m.c->color_range = AVCOL_RANGE_MPEG;
    if (m.oc->oformat->flags & AVFMT_GLOBALHEADER) m.c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    check(av_opt_set(m.c->priv_data, "preset", m.s.preset.c_str(), 0), "setting the x264 preset");
    check(av_opt_set(m.c->priv_data, "crf", std::to_string(m.s.crf).c_str(), 0), "setting crf");
    check(avcodec_open2(m.c, codec, nullptr), "avcodec_open2");
    check(avcodec_parameters_from_context(m.stream->codecpar, m.c), "avcodec_parameters_from_context");
    m.stream->time_base = m.c->time_base;
    if (!m.s.comment.empty()) av_dict_set(&m.oc->metadata, "comment", m.s.comment.c_str(), 0);
    av_dict_set(&m.oc->metadata, "encoder", "siloscope", 0);
    check(avio_open(&m.oc->pb, m.partial_path.c_str(), AVIO_FLAG_WRITE),
          ("opening " + m.partial_path.string()).c_str());
    AVDictionary* opts = nullptr;
    av_dict_set(&opts, "movflags", "+faststart", 0);
    int r = avformat_write_header(m.oc, &opts);
    av_dict_free(&opts);
    check(r, "avformat_write_header");
    m.header_written = true;
    m.frame->format = m.c->pix_fmt;
    m.frame->width = m.s.width;
    m.frame->height = m.s.height;
    check(av_frame_get_buffer(m.frame, 0), "av_frame_get_buffer");
  } catch (...) {
    m.release();
    std::remove(m.partial_path.c_str());
    throw;
  }
}

Mp4Writer::~Mp4Writer() {
  if (impl_->finished) return;
  impl_->release();
  std::remove(impl_->partial_path.c_str());
}

void Mp4Writer::add(const core::Image& img) {
  Impl& m = *impl_;
  if (img.width != m.s.width || img.height != m.s.height)
    throw core::RuntimeFault("video encoder: frame of " + std::to_string(img.width) + "x" +
                             std::to_string(img.height) + " in a " + std::to_string(m.s.width) + "x" +
                             std::to_string(m.s.height) + " movie");
  auto t0 = Clock::now();
  check(av_frame_make_writable(m.frame), "av_frame_make_writable");
  rgba_to_yuv420p(img.rgba.data(), img.width, img.height, m.frame->data[0], m.frame->linesize[0],
                  m.frame->data[1], m.frame->linesize[1], m.frame->data[2], m.frame->linesize[2]);
  m.frame->pts = m.frames++;
  auto t1 = Clock::now();
  check(avcodec_send_frame(m.c, m.frame), "avcodec_send_frame");
  m.drain(false);
  auto t2 = Clock::now();
  m.convert_s += std::chrono::duration<double>(t1 - t0).count();
  m.encode_s += std::chrono::duration<double>(t2 - t1).count();
}

void Mp4Writer::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  auto t0 = Clock::now();
  check(avcodec_send_frame(m.c, nullptr), "flushing the encoder");
  m.drain(true);
  check(av_write_trailer(m.oc), "av_write_trailer");
  check(avio_closep(&m.oc->pb), "closing the movie file");
  m.encode_s += std::chrono::duration<double>(Clock::now() - t0).count();
  m.release();
  io::place_output(m.partial_path, m.final_path);
  m.finished = true;
}

long Mp4Writer::frames() const {
  return impl_->frames;
}
double Mp4Writer::convert_seconds() const {
  return impl_->convert_s;
}
double Mp4Writer::encode_seconds() const {
  return impl_->encode_s;
}

}  // namespace record
