// Issue 41: the overlay's boxes (information box, discharge plot, colour bar, scale bar) keep off the subject
// in every container and at projector text sizes. Each preset scene is planned as `record` plans it (its
// margin, its views), simulated, and every sampled frame drawn twice on the same views: without an overlay
// (what the subject is: every pixel that is not background) and with one; no pixel the overlay changed may be
// a pixel of the subject, and every box lies whole inside the picture. Issue 57: every fifth frame is drawn
// again with an event's caption, the slow-motion badge and two notes, which the layout places after the boxes
// (Overlay::texts): none over a box or another text, and each clear of the grains (the record plan makes room
// for them with the boxes: render::overlay_margin's texts).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/record_plan.h"
#include "app/services/recording.h"
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
  // Texts over the scene (an event's caption, the slow-motion badge, two notes): drawn on every fifth frame
  // with the boxes, each checked against every box and text of its panel from the layout's own rectangles.
  long texts = 0, texts_overlap = 0, texts_not_clear = 0, headings = 0;
  std::string first_overlap, first_not_clear, first_outside, first_differ;
};

bool overlap(const std::array<float, 4>& a, const std::array<float, 4>& b) {
  const bool drawn = a[2] > a[0] && b[2] > b[0];
  return drawn && a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

bool is_background(const std::uint8_t* px, render::Rgba bg) {
  const float want[3] = {bg.r, bg.g, bg.b};
  for (int k = 0; k < 3; ++k)
    if (std::abs(px[k] - static_cast<int>(std::lround(want[k] * 255))) > 2) return false;
  return true;
}

// Two notes (--annotate), which the record plan makes room for with the caption and the badge.
const char* const kNotes[2] = {"the outlet", "a grain in the middle of the pile"};

// The picture again with an event's caption, the badge and two notes (one at the outlet, one at a grain): no
// text over a box or another text, each where the layout found clear space.
void check_texts(std::vector<render::PanelInput> in, const std::vector<app::Panel>& panels,
                 const app::Plan& plan, render::OverlayOptions overlay, int w, int h, Tally& tally) {
  static render::Painter painter;
  core::Image img;
  std::vector<render::Annotations> notes(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    notes[i].caption = "arch removed (5 s rule): 3 disks";
    notes[i].slowdown = 4;
    const auto& grains = in[i].frame->particles;
    notes[i].texts.push_back({0.0f, 0.0f, kNotes[0]});
    if (!grains.empty())
      notes[i].texts.push_back({grains[grains.size() / 2].x, grains[grains.size() / 2].y, kNotes[1]});
    in[i].notes = &notes[i];
  }
  overlay.events = true;
  painter.paint(img, in, plan.style, overlay, w, h);
  for (size_t i = 0; i < panels.size(); ++i) {
    const render::Overlay* ov = painter.overlay(i);
    std::vector<std::pair<std::string, std::array<float, 4>>> boxes = {{"info", ov->info_rect()},
                                                                       {"plot", ov->plot_rect()},
                                                                       {"scale", ov->scale_rect()},
                                                                       {"colorbar", ov->colorbar_rect()}};
    for (const auto& t : ov->texts()) {
      ++tally.texts;
      if (t.name == "heading") {  // a comparison panel's: inside its panel, above its views
        ++tally.headings;
        const float x0 = static_cast<float>(panels[i].odata.panel_x);
        CHECK(t.rect[0] >= x0);
        CHECK(t.rect[2] <= x0 + panels[i].odata.panel_w);
        CHECK(t.rect[3] <= panels[i].odata.heading_h);
      }
      tally.texts_not_clear += !t.clear;
      if (!t.clear && tally.first_not_clear.empty()) tally.first_not_clear = t.name;
      for (const auto& [name, r] : boxes)
        if (overlap(t.rect, r)) {
          ++tally.texts_overlap;
          if (tally.first_overlap.empty()) tally.first_overlap = t.name + " over " + name;
        }
      boxes.push_back({t.name, t.rect});
    }
  }
}

// Record-plan `o`, simulate its panels over `seconds` of discharge and draw `frames` frames each way. The
// frames are simulated once per scene: `cache` keeps them for the next size and text scale.
Tally check_movie(app::RecordOptions o, int frames, double seconds,
                  std::vector<std::vector<core::Frame>>& cache, int every = 1) {
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
  for (int k = 0; k < frames; k += every) {
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
    if (k % (5 * every) == 0) check_texts(in, panels, plan, overlay, w, h, tally);
    // Every box whole inside its panel (no legend row cut off), and at the same place in every panel.
    for (size_t i = 0; i < panels.size(); ++i) {
      const render::Overlay* ov = with.overlay(i);
      REQUIRE(ov != nullptr);
      const float px0 = static_cast<float>(panels[i].odata.panel_x);
      const float px1 = panels[i].odata.panel_w > 0 ? px0 + panels[i].odata.panel_w : static_cast<float>(w);
      for (const auto& r : {ov->info_rect(), ov->plot_rect(), ov->scale_rect()})
        if (r[2] > r[0] && !(r[0] >= px0 && r[2] <= px1 && r[1] >= 0 && r[3] <= h)) {
          if (tally.boxes_outside++ == 0)
            tally.first_outside = "(" + std::to_string(r[0]) + ", " + std::to_string(r[1]) + ") to (" +
                                  std::to_string(r[2]) + ", " + std::to_string(r[3]) + ")";
        }
      // The same place: the boxes' right edges and tops, to within a cell of the layout's grid (a quarter of
      // the text's height: a falling grain can move a box in a band a cell aside).
      const auto a = with.overlay(0)->info_rect(), b = ov->info_rect();
      const float cell = std::max(2.0f, 0.25f * render::overlay_em(h, o.looks.font_scale));
      if (i > 0 && (std::abs((a[2] - panels[0].odata.panel_x) - (b[2] - px0)) > cell ||
                    std::abs(a[1] - b[1]) > cell)) {
        if (tally.panels_differ++ == 0)
          tally.first_differ =
              "t = " + std::to_string(t) + " s: x1 " + std::to_string(a[2] - panels[0].odata.panel_x) + " " +
              std::to_string(b[2] - px0) + " y " + std::to_string(a[1]) + "-" + std::to_string(a[3]) +
              " against " + std::to_string(b[1]) + "-" + std::to_string(b[3]);
      }
    }
  }
  return tally;
}

// `notes`: with the two notes and the slow motion check_texts draws, so that the plan makes room for them.
app::RecordOptions options(const std::string& scene, const std::string& size, double font, bool notes) {
  app::RecordOptions o;
  o.scene.path = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + scene;
  o.scene.seed = 3;
  o.size = size;
  o.looks.overlay = "all+plot";
  o.looks.font_scale = font;
  if (notes) {
    o.looks.annotate = {std::string("0:1000:0,0:") + kNotes[0], std::string("0:1000:0,0.05:") + kNotes[1]};
    o.slowmo = 4;
  }
  o.quiet = true;
  return o;
}

}  // namespace

TEST_CASE(
    "the overlay's boxes never cover a grain, a wall, an obstacle or an arch: every preset, 720p, 1080p "
    "and 4K, text at 1x and 2x",
    "[app][pictures][slow]") {
  const std::vector<std::string> scenes = {"paper.toml",         "paper-vibrated.toml", "pure.toml",
                                           "three-species.toml", "hopper-drain.toml",   "pentagons.toml",
                                           "silo-obstacle.toml", "vibrated-silo.toml",  "tilted-silo.toml"};
  for (const auto& scene : scenes) {
    std::vector<std::vector<core::Frame>> frames;
    for (const char* size : {"1280x720", "1920x1080", "3840x2160"})
      for (double font : {1.0, 2.0}) {
        // 4K: the frames of the 720p run, every fifth (a picture nine times as large).
        const bool uhd = std::string(size) == "3840x2160";
        const Tally t = check_movie(options(scene, size, font, true), 50, 10.0, frames, uhd ? 5 : 1);
        INFO(scene << " at " << size << ", font scale " << font << ": " << t.on_subject
                   << " overlay pixels on the subject in " << t.frames << " frames (first at " << t.first_bad
                   << "), " << t.boxes_outside << " boxes outside the picture (first " << t.first_outside
                   << ")");
        CHECK(t.not_clear == 0);
        CHECK(t.frames == (uhd ? 10 : 50));
        CHECK(t.overlay_px > 0);
        CHECK(t.on_subject == 0);
        CHECK(t.boxes_outside == 0);
        INFO(t.texts << " texts placed, " << t.texts_overlap
                     << " over a box or a text (first: " << t.first_overlap << "), " << t.texts_not_clear
                     << " without clear space (first: " << t.first_not_clear << ")");
        CHECK(t.texts >= (uhd ? 2 : 10) * 4);
        CHECK(t.texts_overlap == 0);
        // Every text clear of the grains too: the record plan makes room for the caption, the badge and the
        // notes with the boxes (a column, or a band as high as 65% of the picture where text at 2x fills
        // it), and the overlay places them widest first (a short note placed first near its point left the
        // long one no clear spot in the vibrated flat silo at 2x).
        CHECK(t.texts_not_clear == 0);
      }
  }
}

TEST_CASE(
    "a comparison's panels: boxes off the subject and laid out alike in every panel, or the plan says they "
    "cannot be",
    "[app][pictures][slow]") {
  // At text scale 2 a comparison's panel (640 pixels wide at 720p) cannot hold the information box (its clog
  // timer alone is 14 em: 476 pixels) in a column beside the container, half the panel at most: the plan
  // gives it a band below the views instead (up to 65% of the height), and the default overlay is clear of
  // the subject.
  {
    app::RecordOptions o = options("paper.toml", "1280x720", 2.0, false);
    o.looks.overlay = "all";
    o.compare = {"mu=0", "mu=2.2"};
    std::vector<std::vector<core::Frame>> frames;
    const Tally t = check_movie(o, 5, 1.0, frames);
    INFO(t.on_subject << " overlay pixels on the subject (first at " << t.first_bad << ")");
    CHECK(t.on_subject == 0);
    CHECK(t.not_clear == 0);
    CHECK(t.texts_overlap == 0);
  }
  // With the discharge plot and two notes as well, nothing holds them all: the overlay knows it, and record
  // says so (the count of such pictures, on standard error).
  {
    app::RecordOptions o = options("paper.toml", "1280x720", 2.0, true);
    o.compare = {"mu=0", "mu=2.2"};
    std::vector<std::vector<core::Frame>> frames;
    const Tally t = check_movie(o, 5, 1.0, frames);
    CHECK(t.on_subject > 0);
    CHECK(t.not_clear == t.frames);
  }
  // Headed by long titles (two rows at 720p), at 720p, 1080p and 4K: the headings, the boxes, the caption,
  // the badge and the notes none over another, in every panel.
  std::vector<std::vector<core::Frame>> frames;
  for (const char* size : {"1280x720", "1920x1080", "3840x2160"})
    for (double font : {1.0}) {
      app::RecordOptions o = options("paper.toml", size, font, true);
      o.compare = {"mu=0", "mu=2.2"};
      o.panel_titles = {"no magnetic repulsion between the added disks",
                        "magnetic repulsion, mu = 2.2 A m^2"};
      const bool uhd = std::string(size) == "3840x2160";
      const Tally t = check_movie(o, 50, 10.0, frames, uhd ? 5 : 1);
      INFO("two panels at " << size << ", font scale " << font << ": " << t.on_subject
                            << " overlay pixels on the subject in " << t.frames << " frames (first at "
                            << t.first_bad << "), " << t.boxes_outside << " boxes outside their panel, "
                            << t.panels_differ << " frames with the panels' boxes apart (first "
                            << t.first_differ << ")");
      CHECK(t.not_clear == 0);
      CHECK(t.frames == (uhd ? 10 : 50));
      CHECK(t.on_subject == 0);
      CHECK(t.boxes_outside == 0);
      CHECK(t.panels_differ == 0);
      INFO(t.texts << " texts placed, " << t.texts_overlap
                   << " over a box or a text (first: " << t.first_overlap << "), " << t.texts_not_clear
                   << " without clear space (first: " << t.first_not_clear << ")");
      CHECK(t.headings == (uhd ? 2 : 10) * 2);
      CHECK(t.texts_overlap == 0);
      CHECK(t.texts_not_clear == 0);
    }
}

TEST_CASE(
    "a camera on an arch or a grain: the arch whole as its clog forms, the grain followed, each kept in the "
    "picture on the way to it",
    "[app][record][heavy]") {
  app::RecordOptions o;
  o.scene.path = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/paper.toml";
  o.scene.seed = 1;
  o.scene.duration = 10.0;
  o.size = "640x360";
  o.quiet = true;
  constexpr int kGrain = 60;
  o.camera_path = "0:outlet,2:arch:1,6:grain:" + std::to_string(kGrain);
  std::vector<app::Panel> panels = app::make_panels(o);
  const app::Plan plan = app::plan_recording(o, panels);
  const auto& tracked = plan.style.tracked;
  CHECK(std::find(tracked.begin(), tracked.end(), kGrain) != tracked.end());  // ringed, with its trail
  REQUIRE(plan.path.keys.size() == 3);
  CHECK(plan.path.keys[1].camera.resolved());
  CHECK(plan.path.keys[2].camera.resolved());
  const core::Geometry& geo = panels[0].geo;
  const int w = 640 - panels[0].odata.margin_w, h = 360;
  // Whether the disk at p of radius r is whole inside view v.
  auto inside = [](const render::View& v, core::Vec2 p, double r) {
    const core::Vec2 px = v.world_to_pixel(p);
    const double rp = r * v.px_per_m();
    return px.x - rp >= v.rect.x - 1 && px.x + rp <= v.rect.x + v.rect.w + 1 && px.y - rp >= v.rect.y - 1 &&
           px.y + rp <= v.rect.y + v.rect.h + 1;
  };
  sim::Silo silo(panels[0].model);
  const std::vector<double> radii = silo.radii();
  std::vector<core::Vec2> arch;  // clog 1's arch where it stood as the clog formed
  std::vector<double> arch_r;
  long frames = 0, arch_missing = 0, grain_missing = 0, off_centre = 0;
  double next = 0;
  while (silo.time() < 10.0) {
    const core::StepEvents& e = silo.step();
    for (int n : e.clogs_opened)
      if (n == 1 && silo.clog().open && silo.clog().number == 1) {
        const core::Frame f = silo.frame(false);
        for (int id : silo.clog().arch) {
          arch.push_back({f.particles[static_cast<size_t>(id)].x, f.particles[static_cast<size_t>(id)].y});
          arch_r.push_back(radii[static_cast<size_t>(id)]);
        }
        // The picture a freeze at this clog holds: every member whole in it.
        const render::View v = plan.path.view_at(silo.time(), geo, w, h);
        for (size_t k = 0; k < arch.size(); ++k) CHECK(inside(v, arch[k], arch_r[k]));
      }
    if (silo.time() < next) continue;
    next += 1.0 / 30;
    ++frames;
    const double t = silo.time();
    const render::View v = plan.path.view_at(t, geo, w, h);
    // From the arch's key to half-way to the grain's, the arch (as it formed) stays whole in the picture;
    // from half-way on, the grain does; from its key on, it is at the centre.
    if (t >= 2 && t <= 4)
      for (size_t k = 0; k < arch.size(); ++k) arch_missing += !inside(v, arch[k], arch_r[k]);
    const core::Frame f = silo.frame(false);  // kept: the grain is read from it below
    const auto& p = f.particles[kGrain];
    if (t >= 4) grain_missing += !inside(v, {p.x, p.y}, radii[kGrain]);
    if (t >= 6.05) {
      const core::Vec2 px = v.world_to_pixel({p.x, p.y});
      // Its track is sampled every 0.01 s and read between by straight lines: a tenth of a diameter.
      off_centre +=
          std::hypot(px.x - (v.rect.x + 0.5 * w), px.y - 0.5 * h) > 0.1 * geo.grain_diameter * v.px_per_m();
    }
  }
  REQUIRE(!arch.empty());
  CHECK(frames >= 295);
  CHECK(arch_missing == 0);
  CHECK(grain_missing == 0);
  CHECK(off_centre == 0);
  // The arch's window: the whole arch and at least six diameters tall.
  const render::CameraSpec& a = plan.path.keys[1].camera;
  CHECK(a.y1 - a.y0 >= 6 * geo.grain_diameter - 1e-9);
  for (const auto& m : arch) CHECK((m.x > a.x0 && m.x < a.x1 && m.y > a.y0 && m.y < a.y1));
}

TEST_CASE("a camera following an arch member holds through the rule's removal, so the removal is in view",
          "[app][pictures]") {
  // The paper's hopper, seed 3: its first clog's arch is removed by the rule; follow one of its members.
  core::Scene s;
  core::apply_overrides(s, {"seed=3", "duration=8"});
  const core::Model model = core::compile(s);
  sim::Silo h(model);
  while (h.events().arches.empty() && h.time() < 8) h.step();
  REQUIRE(!h.events().arches.empty());
  const core::ArchEvent& removal = h.events().arches.front();
  const int member = removal.ids.front();
  const core::Vec2 there{removal.x.front(), removal.y.front()};
  render::CameraPath path = render::parse_camera_path("0:grain:" + std::to_string(member), true);
  app::resolve_camera_subjects(model, path, "--camera", false);
  REQUIRE(path.keys.front().camera.track);
  const render::SubjectTrack& track = *path.keys.front().camera.track;
  // Through the removal and half a second after it, the view is centred where the member stood (within a
  // diameter); two seconds later it has glided to the grain again, far up the column.
  for (double dt : {0.0, 0.2, 0.5}) {
    const core::Vec2 c = track.at(removal.t + dt);
    INFO("t = removal + " << dt << " s: centre (" << c.x << ", " << c.y << ")");
    CHECK(std::hypot(c.x - there.x, c.y - there.y) < model.setup.geo.grain_diameter);
  }
  CHECK(track.at(removal.t + 2.5).y > there.y + 0.5);
}

TEST_CASE(
    "a two-panel comparison at 720p shows the outlet's grains at least 50 pixels across, under headings",
    "[app][pictures]") {
  // Issue 57: the panels' outlet views were barely zoomed (19 px a grain at 720p against 72 in a single
  // movie): each panel's boxes took a column beside its container. Now the panel is headed by its title and
  // the boxes take a band below the views where that leaves them more zoom.
  for (const std::string scene : {"paper.toml", "paper-vibrated.toml", "three-species.toml"})
    for (const char* size : {"1280x720", "1920x1080"}) {
      app::RecordOptions o = options(scene, size, 1.0, false);
      o.looks.overlay = "all";
      o.compare = {"seed=4", "seed=5"};
      o.panel_titles = {"one filling", "another filling"};
      std::vector<app::Panel> panels = app::make_panels(o);
      const app::Plan plan = app::plan_recording(o, panels);
      REQUIRE(panels.size() == 2);
      const int h = plan.video.height;
      for (size_t k = 0; k < panels.size(); ++k) {
        const app::Panel& p = panels[k];
        CHECK(p.odata.heading == o.panel_titles[k]);
        CHECK(p.odata.heading_h >= render::overlay_em(h, 1.0) * render::kHeadingScale);
        CHECK(p.odata.title.empty());  // the heading names the panel; the box does not repeat it
        const render::View* outlet = nullptr;
        for (const auto& v : p.views) {
          if (v.name == "outlet") outlet = &v;
          CHECK(v.rect.y >= p.odata.heading_h);  // the views below the heading
          CHECK(v.rect.y + v.rect.h <= h - p.odata.margin_h);
        }
        REQUIRE(outlet != nullptr);
        const double grain_px = 2 * p.model.setup.reference_radius * outlet->px_per_m();
        INFO(scene << " at " << size << ", panel " << k << ": a grain " << std::to_string(grain_px)
                   << " px across");
        CHECK(grain_px >= 50 * h / 720.0);
      }
    }
}
