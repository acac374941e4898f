// Issue 41: the overlay's boxes (information box, discharge plot, colour bar, scale bar) keep off the subject
// in every container and at projector text sizes. Each preset scene is planned as `record` plans it (its
// margin, its views), simulated, and every sampled frame drawn twice on the same views: without an overlay
// (what the subject is: every pixel that is not background) and with one; no pixel the overlay changed may be
// a pixel of the subject, and every box lies whole inside the picture.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/record_plan.h"
#include "render/context.h"
#include "render/painter.h"
#include "sim/silo.h"

namespace {

render::OffscreenContext& context() {
  static render::OffscreenContext ctx;  // one GL context per test process
  return ctx;
}

struct Tally {
  long frames = 0, overlay_px = 0, on_subject = 0, boxes_outside = 0, panels_differ = 0;
  std::string first_bad;
  long not_clear = 0;  // pictures in which the overlay says a box found no clear space
};

bool is_background(const std::uint8_t* px, render::Rgba bg) {
  const float want[3] = {bg.r, bg.g, bg.b};
  for (int k = 0; k < 3; ++k)
    if (std::abs(px[k] - static_cast<int>(std::lround(want[k] * 255))) > 2) return false;
  return true;
}

// Record-plan `o`, simulate its panels over `seconds` of discharge and draw `frames` frames each way. The
// frames are simulated once per scene: `cache` keeps them for the next size and text scale.
Tally check_movie(app::RecordOptions o, int frames, double seconds,
                  std::vector<std::vector<core::Frame>>& cache) {
  context();
  std::vector<app::Panel> panels = app::make_panels(o);
  const app::Plan plan = app::plan_recording(o, panels);
  if (cache.empty()) {
    std::vector<std::unique_ptr<sim::Silo>> silos;
    for (const auto& p : panels) silos.push_back(std::make_unique<sim::Silo>(p.model));
    for (int k = 0; k < frames; ++k) {
      std::vector<core::Frame> fs;
      for (auto& s : silos) {
        s->advance_to(seconds * (k + 1) / frames);
        fs.push_back(s->frame(false));
      }
      cache.push_back(std::move(fs));
    }
  }
  render::Painter with, without;
  render::OverlayOptions overlay = plan.overlay;
  overlay.zoombox = overlay.events = false;  // outlines and marks drawn on the container by design
  const int w = plan.video.width, h = plan.video.height;
  const render::Rgba bg = render::background_color(plan.style);
  Tally tally;
  core::Image clean, full;
  // The lines between views and between panels are borders, drawn on the boundary column by design: not
  // boxes that could move elsewhere.
  std::vector<char> border(static_cast<size_t>(w), 0);
  auto mark_border = [&](int x) {
    for (int dx = -3; dx <= 3; ++dx)
      if (x + dx >= 0 && x + dx < w) border[static_cast<size_t>(x + dx)] = 1;
  };
  for (const auto& p : panels) {
    if (p.odata.panel_x > 0) mark_border(p.odata.panel_x);
    for (size_t k = 1; k < p.views.size(); ++k) mark_border(p.views[k].rect.x);
  }
  for (int k = 0; k < frames; ++k) {
    const double t = seconds * (k + 1) / frames;
    const std::vector<core::Frame>& fs = cache[static_cast<size_t>(k)];
    std::vector<render::PanelInput> in;
    for (size_t i = 0; i < panels.size(); ++i)
      in.push_back({&fs[i], &panels[i].geo, &panels[i].views, &panels[i].odata});
    without.paint(clean, in, plan.style, render::OverlayOptions::none(), w, h);
    with.paint(full, in, plan.style, overlay, w, h);
    ++tally.frames;
    tally.not_clear += !with.boxes_clear();
    long bad = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::uint8_t *a = clean.pixel(x, y), *b = full.pixel(x, y);
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) continue;
        if (border[static_cast<size_t>(x)]) continue;
        ++tally.overlay_px;
        if (!is_background(a, bg)) {
          ++bad;
          if (tally.first_bad.empty())
            tally.first_bad = "t = " + std::to_string(t) + " s, pixel (" + std::to_string(x) + ", " +
                              std::to_string(y) + ")";
        }
      }
    tally.on_subject += bad;
    // Every box whole inside its panel (no legend row cut off), and at the same place in every panel.
    for (size_t i = 0; i < panels.size(); ++i) {
      const render::Overlay* ov = with.overlay(i);
      REQUIRE(ov != nullptr);
      const float px0 = static_cast<float>(panels[i].odata.panel_x);
      const float px1 = panels[i].odata.panel_w > 0 ? px0 + panels[i].odata.panel_w : static_cast<float>(w);
      for (const auto& r : {ov->info_rect(), ov->plot_rect(), ov->scale_rect()})
        if (r[2] > r[0] && !(r[0] >= px0 && r[2] <= px1 && r[1] >= 0 && r[3] <= h)) ++tally.boxes_outside;
      // The same corner: the boxes' right edges and tops (a longer panel title makes a wider box).
      const auto a = with.overlay(0)->info_rect(), b = ov->info_rect();
      if (i > 0 &&
          (std::abs((a[2] - panels[0].odata.panel_x) - (b[2] - px0)) > 1 || std::abs(a[1] - b[1]) > 1))
        ++tally.panels_differ;
    }
  }
  return tally;
}

app::RecordOptions options(const std::string& scene, const std::string& size, double font) {
  app::RecordOptions o;
  o.scene.path = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + scene;
  o.scene.seed = 3;
  o.size = size;
  o.overlay = "all+plot";
  o.looks.font_scale = font;
  o.quiet = true;
  return o;
}

}  // namespace

TEST_CASE(
    "the overlay's boxes never cover a grain, a wall, an obstacle or an arch: every preset, 720p and "
    "1080p, text at 1x and 2x",
    "[app][pictures][slow]") {
  const std::vector<std::string> scenes = {"paper.toml",         "paper-vibrated.toml", "pure.toml",
                                           "three-species.toml", "hopper-drain.toml",   "pentagons.toml",
                                           "silo-obstacle.toml", "vibrated-silo.toml",  "tilted-silo.toml"};
  for (const auto& scene : scenes) {
    std::vector<std::vector<core::Frame>> frames;
    for (const char* size : {"1280x720", "1920x1080"})
      for (double font : {1.0, 2.0}) {
        const Tally t = check_movie(options(scene, size, font), 50, 10.0, frames);
        INFO(scene << " at " << size << ", font scale " << font << ": " << t.on_subject
                   << " overlay pixels on the subject in " << t.frames << " frames (first at " << t.first_bad
                   << ")");
        CHECK(t.not_clear == 0);
        CHECK(t.frames == 50);
        CHECK(t.overlay_px > 0);
        CHECK(t.on_subject == 0);
        CHECK(t.boxes_outside == 0);
      }
  }
}

TEST_CASE(
    "a comparison's panels: boxes off the subject and laid out alike in every panel, or the plan says they "
    "cannot be",
    "[app][pictures][slow]") {
  // At text scale 2 a comparison's panel (640 or 960 pixels wide) cannot hold the information box (its clog
  // timer alone is 14 em: 476 or 720 pixels) beside the container: the overlay knows it, and record says so
  // (the count of such pictures, on standard error).
  {
    app::RecordOptions o = options("paper.toml", "1280x720", 2.0);
    o.compare = {"mu=0", "mu=2.2"};
    std::vector<std::vector<core::Frame>> frames;
    const Tally t = check_movie(o, 5, 1.0, frames);
    CHECK(t.on_subject > 0);
    CHECK(t.not_clear == t.frames);
  }
  std::vector<std::vector<core::Frame>> frames;
  for (const char* size : {"1280x720", "1920x1080"})
    for (double font : {1.0}) {
      app::RecordOptions o = options("paper.toml", size, font);
      o.compare = {"mu=0", "mu=2.2"};
      const Tally t = check_movie(o, 50, 10.0, frames);
      INFO("two panels at " << size << ", font scale " << font << ": " << t.on_subject
                            << " overlay pixels on the subject in " << t.frames << " frames (first at "
                            << t.first_bad << "), " << t.boxes_outside << " boxes outside their panel, "
                            << t.panels_differ << " frames with the panels' boxes apart");
      CHECK(t.not_clear == 0);
      CHECK(t.frames == 50);
      CHECK(t.on_subject == 0);
      CHECK(t.boxes_outside == 0);
      CHECK(t.panels_differ == 0);
    }
}
