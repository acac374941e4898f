#include <catch2/catch.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
}

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb_image.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
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
  std::vector<double> times;        // presentation time of each decoded frame, s
  std::vector<std::uint8_t> first;  // the first frame as RGB (BT.709, limited range, converted here)
  double rate = 0;                  // the stream's average frame rate
};

// One yuv420p pixel to RGB by the BT.709 limited-range equations (independent of the encoder's code).
void yuv_to_rgb(int y, int u, int v, std::uint8_t* rgb) {
  const double Y = (y - 16) / 219.0, U = (u - 128) / 224.0, V = (v - 128) / 224.0;
  const double r = Y + 1.5748 * V, g = Y - 0.1873 * U - 0.4681 * V, b = Y + 1.8556 * U;
  for (double c : {r, g, b}) *rgb++ = static_cast<std::uint8_t>(std::clamp(c * 255.0 + 0.5, 0.0, 255.0));
}

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
  p.rate = av_q2d(st->avg_frame_rate);
  auto receive = [&] {
    while (avcodec_receive_frame(c, frame) == 0) {
      p.times.push_back(frame->best_effort_timestamp * av_q2d(st->time_base));
      if (p.frames == 0 && frame->format == AV_PIX_FMT_YUV420P) {
        p.first.resize(static_cast<size_t>(frame->width) * frame->height * 3);
        for (int y = 0; y < frame->height; ++y)
          for (int x = 0; x < frame->width; ++x)
            yuv_to_rgb(frame->data[0][y * frame->linesize[0] + x],
                       frame->data[1][(y / 2) * frame->linesize[1] + x / 2],
                       frame->data[2][(y / 2) * frame->linesize[2] + x / 2],
                       &p.first[(static_cast<size_t>(y) * frame->width + x) * 3]);
      }
      ++p.frames;
    }
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
  fs::path d = fs::temp_directory_path() / ("siloscope_test_" + name + "_" + std::to_string(::getpid()));
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
  CHECK_THROWS_WITH(record::validate(v),
                    Catch::Matchers::Contains("--size 1921x1080") && Catch::Matchers::Contains("even"));
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
  for (const auto& e : fs::directory_iterator(dir))
    CHECK(e.path().filename() == "f.png");  // no temporary left
}

#include "helpers.h"
#include "io/trajectory.h"

TEST_CASE("frames at exact times: whole steps per frame, the trajectory and the MP4 carry the same times",
          "[record][app]") {
  fs::path d = temp_dir("exact_times");
  // 30 fps at dt = 1 ms: 33 steps per frame, 0.033 s of simulation per frame, 1000/33 frames per video
  // second.
  auto r = test::cli("record " + test::kScene + " --duration 2 --size 64x48 --png-every 1 --quiet --out " +
                     (d / "m").string());
  REQUIRE(r.code == 0);
  const std::string meta = test::slurp(d / "m" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("steps_per_frame = 33\n") &&
                       Catch::Matchers::Contains("frame_interval_s = 0.033\n"));
  io::Trajectory t(d / "m" / "trajectory.sstraj");
  REQUIRE(t.size() == 61);  // 0, 0.033, ..., 1.98
  for (long k = 0; k < t.size(); ++k) CHECK(t.time(k) == Approx(0.033 * k).margin(1e-9));
  CHECK(t.info().frame_interval == Approx(0.033));
  const Probe p = probe(d / "m.mp4");
  REQUIRE(p.frames == 61);
  CHECK(p.rate == Approx(1000.0 / 33.0).epsilon(1e-9));
  for (size_t k = 0; k < p.times.size(); ++k) CHECK(p.times[k] == Approx(0.033 * k).margin(1e-6));
  // The decoded first frame matches the RGBA frame it was made from (the PNG of the same frame).
  int w = 0, h = 0, ch = 0;
  unsigned char* png = stbi_load((d / "m" / "frames" / "frame_000000.png").c_str(), &w, &h, &ch, 4);
  REQUIRE(png);
  REQUIRE(p.first.size() == static_cast<size_t>(w) * h * 3);
  double sum = 0;
  for (int i = 0; i < w * h; ++i)
    for (int c = 0; c < 3; ++c)
      sum += std::abs(int(png[i * 4 + c]) - int(p.first[static_cast<size_t>(i) * 3 + c]));
  stbi_image_free(png);
  const double mean_error = sum / (3.0 * w * h);
  INFO("mean absolute error " << mean_error << " of 255");
  CHECK(mean_error < 8.0);  // chroma subsampling at 64x48 blurs the disk edges; colours must agree

  // A speed that no whole number of steps per frame gives closely is refused with the nearest good ones.
  r = test::cli("record " + test::kScene + " --duration 1 --size 64x48 --speed 0.05 --quiet --out " +
                (d / "bad").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output,
             Catch::Matchers::Contains("whole number") && Catch::Matchers::Contains("--speed 0.06"));
  CHECK_FALSE(fs::exists(d / "bad"));
}

#include "record/yuv.h"

TEST_CASE("the RGBA to yuv420p converter gives BT.709 limited-range values for known colours", "[record]") {
  struct Known {
    std::uint8_t r, g, b;
    int y, u, v;
  };
  // Y = 16 + 219 (0.2126 R + 0.7152 G + 0.0722 B) / 255; Cb, Cr = 128 + 224 (B - Y', R - Y') / (255
  // * 1.8556, 1.5748).
  const Known known[] = {{255, 255, 255, 235, 128, 128}, {0, 0, 0, 16, 128, 128},
                         {255, 0, 0, 63, 102, 240},      {0, 255, 0, 173, 42, 26},
                         {0, 0, 255, 32, 240, 118},      {128, 128, 128, 126, 128, 128}};
  for (const auto& k : known) {
    std::vector<std::uint8_t> rgba(4 * 4 * 2);
    for (size_t i = 0; i < rgba.size(); i += 4)
      rgba[i] = k.r, rgba[i + 1] = k.g, rgba[i + 2] = k.b, rgba[i + 3] = 255;
    std::uint8_t y[8], u[2], v[2];
    record::rgba_to_yuv420p(rgba.data(), 4, 2, y, 4, u, 2, v, 2);
    INFO("colour " << int(k.r) << "," << int(k.g) << "," << int(k.b));
    CHECK(std::abs(y[0] - k.y) <= 1);
    CHECK(std::abs(y[7] - k.y) <= 1);
    CHECK(std::abs(u[1] - k.u) <= 1);
    CHECK(std::abs(v[1] - k.v) <= 1);
  }
}

TEST_CASE("events on screen: a rule removal stays marked >= 10 frames, the badge shows only while slowed",
          "[record][app]") {
  fs::path d = temp_dir("events_on_screen");
  // Seed 1: the rule fires at t = 6.521 s; --slowmo 4 slows 6.021..7.521 s.
  auto r = test::cli("record " + test::kScene + " --duration 7.2 --slowmo 4 --size 320x240 --png-every 1 " +
                     "--no-movie --quiet --out " + (d / "m").string());
  REQUIRE(r.code == 0);
  io::Trajectory t(d / "m" / "trajectory.sstraj");
  const std::string meta = test::slurp(d / "m" / "metadata.toml");
  const auto at = meta.find("slowmo_frames = ");
  REQUIRE(at != std::string::npos);
  const long slow_frames = std::stol(meta.substr(at + 16));
  long marked = 0, badged = 0, marked_before_rule = 0, first_marked = -1;
  for (long k = 0; k < t.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06ld.png", k);
    int w = 0, h = 0, ch = 0;
    unsigned char* px = stbi_load((d / "m" / "frames" / name).c_str(), &w, &h, &ch, 4);
    REQUIRE(px);
    long ring = 0, badge = 0;
    for (int i = 0; i < w * h; ++i) {
      const unsigned char* p = px + 4 * i;
      ring +=
          std::abs(p[0] - 200) < 25 && p[1] < 40 && std::abs(p[2] - 160) < 25;  // the magenta rings/caption
      // The badge's yellow text (255, 220, 0), wherever the layout put it: the arch's gold (255, 194, 0) and
      // its blends with the white background or the halo's dark edge stay outside this band.
      badge += p[0] > 230 && std::abs(p[1] - 220) < 12 && p[2] < 40;
    }
    stbi_image_free(px);
    if (ring > 20) {
      ++marked;
      if (first_marked < 0) first_marked = k;
      if (t.time(k) < 6.521 - 1e-6) ++marked_before_rule;
    }
    badged += badge > 3;
  }
  INFO("marked " << marked << " first at frame " << first_marked << ", badged " << badged << " of "
                 << slow_frames);
  CHECK(marked >= 10);
  CHECK(marked_before_rule == 0);
  CHECK(badged == slow_frames);
}

TEST_CASE("a comparison movie: panels side by side on one clock, each labelled, each its own exact run",
          "[record][app]") {
  fs::path d = temp_dir("compare");
  const std::string common = test::kScene + " --duration 1.5 --set settle_time=2 --quiet ";
  auto r = test::cli("record " + common + "--compare mu=0 --compare mu=2.2,friction=0.4 --size 320x240 " +
                     "--png-every 45 --out " + (d / "c").string());
  REQUIRE(r.code == 0);
  const std::string meta = test::slurp(d / "c" / "metadata.toml");
  CHECK_THAT(meta, Catch::Matchers::Contains("panels = 2\n") &&
                       Catch::Matchers::Contains("panel_labels = [\"mu=0\", \"mu=2.2,friction=0.4\"]"));
  CHECK_THAT(test::slurp(d / "c" / "panel1" / "metadata.toml"),
             Catch::Matchers::Contains("\nmu = 2.2 ") && Catch::Matchers::Contains("\nfriction = 0.4 "));
  // Each panel is exactly the run of its own scene: stepping in parallel changes nothing.
  REQUIRE(
      test::cli("run " + common + "--set mu=2.2 --set friction=0.4 --out " + (d / "alone").string()).code ==
      0);
  CHECK(test::slurp(d / "c" / "panel1" / "exits.csv") == test::slurp(d / "alone" / "exits.csv"));
  // Layout: a dark separator down the middle, disks (red originals) in both halves, the info box in both.
  int w = 0, h = 0, ch = 0;
  unsigned char* px = stbi_load((d / "c" / "frames" / "frame_000000.png").c_str(), &w, &h, &ch, 4);
  REQUIRE(px);
  long separator = 0, red[2] = {0, 0};
  for (int y = 0; y < h; ++y) {
    bool dark = false;
    for (int x = w / 2 - 2; x <= w / 2 + 1; ++x) {
      const unsigned char* p = px + 4 * (y * w + x);
      dark = dark || (p[0] < 60 && p[1] < 60 && p[2] < 60);
    }
    separator += dark;
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = px + 4 * (y * w + x);
      if (p[0] > 180 && p[1] < 70 && p[2] < 70) ++red[x < w / 2 ? 0 : 1];
    }
  }
  stbi_image_free(px);
  CHECK(separator > 0.9 * h);
  CHECK(red[0] > 200);
  CHECK(red[1] > 200);
  // Bad comparisons: five panels, a panel with another time step.
  r = test::cli("record " + common +
                "--compare mu=0 --compare mu=1 --compare mu=2 --compare mu=3 --compare mu=4 " +
                "--size 64x48 --out " + (d / "five").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("2 to 4"));
  r = test::cli("record " + common + "--compare dt=0.0005 --size 64x48 --out " + (d / "dt").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Matchers::Contains("one clock"));
  CHECK_FALSE(fs::exists(d / "five"));
  CHECK_FALSE(fs::exists(d / "dt"));
}
