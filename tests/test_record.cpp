#include <catch2/catch.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
}

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb_image.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "record/mp4.h"
#include "record/png.h"

namespace fs = std::filesystem;

namespace {
core::Image gradient(int w, int h, int seed) {
  core::Image img;
  img.width = w;
  img.height = h;
  img.rgba.resize(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = &img.rgba[(static_cast<size_t>(y) * w + x) * 4];
      p[0] = static_cast<std::uint8_t>(x * 255 / w);
      p[1] = static_cast<std::uint8_t>(y * 255 / h);
      p[2] = static_cast<std::uint8_t>(seed * 37);
      p[3] = 255;
    }
  return img;
}

struct Probe {
  int width = 0, height = 0, frames = 0;
  double duration = 0;
  std::string pix_fmt, codec, comment;
};

// Decode a movie with libavformat/libavcodec and count what is really in it.
Probe probe(const fs::path& path) {
  Probe p;
  AVFormatContext* fmt = nullptr;
  REQUIRE(avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) == 0);
  REQUIRE(avformat_find_stream_info(fmt, nullptr) >= 0);
  int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  REQUIRE(si >= 0);
  AVStream* st = fmt->streams[si];
  const AVCodec* dec = avcodec_find_decoder(st->codecpar->codec_id);
  AVCodecContext* c = avcodec_alloc_context3(dec);
  avcodec_parameters_to_context(c, st->codecpar);
  REQUIRE(avcodec_open2(c, dec, nullptr) == 0);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  auto receive = [&] {
    while (avcodec_receive_frame(c, frame) == 0) ++p.frames;
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == si) {
      avcodec_send_packet(c, pkt);
      receive();
    }
    av_packet_unref(pkt);
  }
  avcodec_send_packet(c, nullptr);
  receive();
  p.width = c->width;
  p.height = c->height;
  p.pix_fmt = av_get_pix_fmt_name(c->pix_fmt);
  p.codec = dec->name;
  p.duration = fmt->duration / static_cast<double>(AV_TIME_BASE);
  if (auto* e = av_dict_get(fmt->metadata, "comment", nullptr, 0)) p.comment = e->value;
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&c);
  avformat_close_input(&fmt);
  return p;
}

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("siloscope_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("an MP4 decodes back with the requested frame count, size, duration and pixel format", "[record]") {
  fs::path dir = temp_dir("mp4");
  record::VideoSettings v;
  v.width = 160;
  v.height = 90;
  v.fps = 24;
  v.preset = "ultrafast";
  v.comment = "scene = test";
  {
    record::Mp4Writer w(dir / "movie.mp4", v);
    for (int i = 0; i < 48; ++i) w.add(gradient(160, 90, i));
    CHECK_FALSE(fs::exists(dir / "movie.mp4"));  // only the partial file exists while writing
    CHECK(fs::exists(dir / "movie.mp4.partial"));
    w.finish();
  }
  CHECK_FALSE(fs::exists(dir / "movie.mp4.partial"));
  Probe p = probe(dir / "movie.mp4");
  CHECK(p.frames == 48);
  CHECK(p.width == 160);
  CHECK(p.height == 90);
  CHECK(p.duration == Approx(2.0).margin(1.0 / 24));
  CHECK(p.pix_fmt == "yuv420p");
  CHECK(p.codec == "h264");
  CHECK(p.comment == "scene = test");
}

TEST_CASE("an MP4 that is never finished leaves nothing under any name", "[record]") {
  fs::path dir = temp_dir("mp4_abort");
  record::VideoSettings v;
  v.width = 64;
  v.height = 64;
  v.preset = "ultrafast";
  {
    record::Mp4Writer w(dir / "movie.mp4", v);
    w.add(gradient(64, 64, 1));
  }
  CHECK(fs::is_empty(dir));
}

TEST_CASE("movie settings are validated with the option's name", "[record]") {
  record::VideoSettings v;
  v.width = 1921;
  CHECK_THROWS_WITH(record::validate(v), Catch::Matchers::Contains("--size 1921x1080") && Catch::Matchers::Contains("even"));
  v = {};
  v.crf = 60;
  CHECK_THROWS_WITH(record::validate(v), Catch::Matchers::Contains("--crf"));
  v = {};
  v.preset = "ludicrous";
  CHECK_THROWS_WITH(record::validate(v), Catch::Matchers::Contains("--preset ludicrous"));
}

TEST_CASE("a PNG read back equals the frame, alpha included", "[record]") {
  fs::path dir = temp_dir("png");
  core::Image img = gradient(123, 45, 3);
  img.rgba[7] = 17;  // one translucent pixel
  record::write_png(dir / "f.png", img);
  int w = 0, h = 0, n = 0;
  unsigned char* back = stbi_load((dir / "f.png").c_str(), &w, &h, &n, 4);
  REQUIRE(back);
  CHECK(w == 123);
  CHECK(h == 45);
  CHECK(std::equal(img.rgba.begin(), img.rgba.end(), back));
  stbi_image_free(back);
  CHECK(fs::directory_iterator(dir) != fs::directory_iterator());
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename() == "f.png");  // no temporary left
}
