#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "render/camera.h"
#include "render/context.h"
#include "render/overlay.h"
#include "render/renderer.h"
#include "render/target.h"

namespace {
core::Particle disk(float x, float y, float r, core::Species s) {
  return {x, y, 0, 0, 0, r, 0, s};
}

// Distance between a pixel and a colour, 0..255 per channel (max over channels).
int distance(const std::uint8_t* px, render::Rgba c) {
  int d = 0;
  const float want[3] = {c.r, c.g, c.b};
  for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(px[k] - static_cast<int>(std::lround(want[k] * 255))));
  return d;
}

struct Fixture {
  render::OffscreenContext ctx;
  render::Renderer renderer;
  core::Scene scene;
  core::Geometry geo = core::make_geometry(scene);
};
Fixture& fixture() {
  static Fixture f;  // one GL context per test process
  return f;
}
}  // namespace

TEST_CASE("camera mapping round-trips between metres and pixels", "[render]") {
  core::Scene s;
  auto geo = core::make_geometry(s);
  for (const char* spec : {"hopper", "outlet", "split", "window:-0.3,0.1,0.5,0.9"}) {
    auto views = render::layout_views(render::parse_camera(spec), geo, 640, 360);
    for (const auto& v : views) {
      for (core::Vec2 p : {core::Vec2{0.0, 0.0}, core::Vec2{0.2, 0.5}, core::Vec2{-0.4, 1.3}}) {
        core::Vec2 back = v.pixel_to_world(v.world_to_pixel(p));
        CHECK(back.x == Approx(p.x).margin(1e-12));
        CHECK(back.y == Approx(p.y).margin(1e-12));
      }
      // The view's centre maps to the centre of its rectangle; y grows downwards in pixels.
      core::Vec2 c = v.world_to_pixel({v.cam.cx, v.cam.cy});
      CHECK(c.x == Approx(v.rect.x + 0.5 * v.rect.w));
      CHECK(c.y == Approx(v.rect.y + 0.5 * v.rect.h));
      CHECK(v.world_to_pixel({v.cam.cx, v.cam.cy + 0.1}).y < c.y);
    }
  }
  auto w = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), geo, 400, 400);
  CHECK(w[0].px_per_m() == Approx(400));
  CHECK_THROWS_AS(render::layout_views(render::parse_camera("window:1,0,0,1"), geo, 400, 400),
                  core::InputError);
  CHECK_THROWS_AS(render::layout_views(render::parse_camera("sideways"), geo, 400, 400), core::InputError);
}

TEST_CASE("a camera path: the keys' cameras at their times, an eased glide between, still outside",
          "[render]") {
  const core::Geometry geo = core::make_geometry(core::Scene{});
  const render::CameraPath path = render::parse_camera_path("0:hopper,2:outlet,5:window:-0.5,0,0.5,1");
  REQUIRE(path.keys.size() == 3);
  CHECK(path.keys[2].camera.x1 == 0.5);
  const render::View hopper = render::layout_views(path.keys[0].camera, geo, 640, 360).front();
  const render::View outlet = render::layout_views(path.keys[1].camera, geo, 640, 360).front();
  CHECK(path.view_at(-3, geo, 640, 360).cam.height == hopper.cam.height);
  CHECK(path.view_at(0, geo, 640, 360).cam.cy == hopper.cam.cy);
  CHECK(path.view_at(2, geo, 640, 360).cam.height == Approx(outlet.cam.height));
  CHECK(path.view_at(99, geo, 640, 360).cam.height == Approx(1.0));  // the window's 1 m, still after
  // Half-way in time is half-way in zoom (geometric mean), eased: slow at the keys.
  const render::View mid = path.view_at(1, geo, 640, 360);
  CHECK(mid.cam.height == Approx(std::sqrt(hopper.cam.height * outlet.cam.height)));
  // The zoom is about the point that sits at the same place in both keys' pictures: there at mid-glide too.
  const double ha = hopper.cam.height, hb = outlet.cam.height;
  const double fixed = (hopper.cam.cy * hb - outlet.cam.cy * ha) / (hb - ha);
  CHECK((fixed - mid.cam.cy) / mid.cam.height == Approx((fixed - hopper.cam.cy) / ha));
  CHECK((fixed - outlet.cam.cy) / hb == Approx((fixed - hopper.cam.cy) / ha));
  const double early = path.view_at(0.1, geo, 640, 360).cam.cy - hopper.cam.cy;
  CHECK(std::fabs(early) < 0.05 * std::fabs(outlet.cam.cy - hopper.cam.cy));
  for (const char* bad : {"0:split", "1:hopper,1:outlet", "2:hopper,1:outlet", "x:hopper", "0:funnel", ""}) {
    INFO(bad);
    CHECK_THROWS_AS(render::parse_camera_path(bad), core::InputError);
  }
  CHECK_THROWS_WITH(render::parse_camera_path("0:split"), Catch::Contains("a path moves one"));
  CHECK_THROWS_WITH(render::parse_camera_path("2:hopper,1:outlet"), Catch::Contains("times must increase"));
}

TEST_CASE("camera keys naming an arch or a grain: parsed for record only, framed whole, followed",
          "[render]") {
  const render::CameraSpec arch = render::parse_camera("arch:2", true);
  CHECK(arch.kind == render::CameraSpec::Kind::Arch);
  CHECK(arch.subject == 2);
  CHECK_FALSE(arch.resolved());
  CHECK(render::parse_camera("grain:0", true).kind == render::CameraSpec::Kind::Grain);
  // Elsewhere (the inspector, live, lab) nothing simulates ahead: refused, saying where they work.
  CHECK_THROWS_WITH(render::parse_camera("arch:2"), Catch::Contains("`record` does"));
  CHECK_THROWS_WITH(render::parse_camera_path("0:outlet,2:grain:5"), Catch::Contains("`record` does"));
  for (const char* bad :
       {"arch:0", "arch:-1", "arch:x", "arch:", "grain:-1", "grain:1.5", "grain:", "arch:1,2"}) {
    INFO(bad);
    CHECK_THROWS_AS(render::parse_camera(bad, true), core::InputError);
  }
  CHECK_THROWS_WITH(render::parse_camera("arch:0", true), Catch::Contains("K a whole number >= 1"));
  const core::Geometry geo = core::make_geometry(core::Scene{});
  CHECK_THROWS_WITH(render::layout_views(arch, geo, 640, 360), Catch::Contains("simulating ahead"));
  const render::CameraPath path = render::parse_camera_path("0:outlet,2:arch:1,4:grain:7", true);
  REQUIRE(path.keys.size() == 3);
  CHECK(path.keys[1].camera.subject == 1);
  CHECK(path.keys[2].camera.subject == 7);
  // An arch of three disks over the outlet: framed whole, at least six diameters tall.
  render::CameraSpec a = arch;
  const double d = geo.grain_diameter, r = 0.5 * d;
  render::frame_arch(a, {{-0.12, 0.05}, {0, 0.13}, {0.12, 0.05}}, r, d);
  CHECK(a.resolved());
  CHECK(a.y1 - a.y0 >= 6 * d - 1e-12);
  const render::View v = render::layout_views(a, geo, 640, 360).front();
  for (const core::Vec2 p :
       {core::Vec2{-0.12 - r, 0.05}, core::Vec2{0.12 + r, 0.05}, core::Vec2{0, 0.13 + r}}) {
    const core::Vec2 px = v.world_to_pixel(p);
    CHECK((px.x > 0 && px.x < 640 && px.y > 0 && px.y < 360));
  }
  // A grain followed: at the centre of the picture wherever its track has it, read between samples.
  render::CameraSpec g = render::parse_camera("grain:7", true);
  auto track = std::make_shared<render::SubjectTrack>();
  track->t = {0, 1, 2};
  track->x = {0, 0.4, 0.4};
  track->y = {3, 2, 1};
  g.track = track;
  CHECK(track->at(0.5).x == Approx(0.2));
  CHECK(track->at(1.5).y == Approx(1.5));
  CHECK(track->at(9).y == Approx(1));
  for (double t : {0.0, 0.5, 1.5, 3.0}) {
    const render::View gv = render::layout_views(g, geo, 640, 360, t).front();
    const core::Vec2 px = gv.world_to_pixel(track->at(t));
    CHECK(px.x == Approx(320).margin(1e-6));
    CHECK(px.y == Approx(180).margin(1e-6));
    CHECK(gv.cam.height == Approx(8 * d));
  }
}

TEST_CASE("a followed grain that vanishes holds the camera where it was, then glides (issue 57)",
          "[render]") {
  // A grain resting in an arch at (0.1, 0.05), taken out at t = 2 s and re-injected at (0.2, 3.0), then
  // falling.
  render::SubjectTrack tr;
  for (int k = 0; k <= 600; ++k) {
    const double t = 0.01 * k;
    tr.t.push_back(t);
    tr.x.push_back(t < 2.0 ? 0.1 : 0.2);
    tr.y.push_back(t < 2.0 ? 0.05 : 3.0 - 0.1 * (t - 2.0));
  }
  const render::SubjectTrack seen = tr;
  CHECK(render::hold_through_jumps(tr, 0.65) == 1);
  // Before: unchanged. Through the removal and a second after it: where it was.
  CHECK(tr.at(1.5).y == Approx(0.05));
  for (double t : {2.0, 2.3, 2.99}) CHECK(tr.at(t).y == Approx(0.05));
  // Then a glide (no frame jumps more than a smooth step's slope allows), arriving after 1 s.
  double worst = 0;
  for (double t = 2.99; t < 4.0; t += 0.01)
    worst = std::max(worst, std::fabs(tr.at(t + 0.01).y - tr.at(t).y));
  CHECK(worst < 0.1);  // a 2.9 m glide in 1 s: at most 1.5 x 2.9 m/s x 0.01 s per sample (smoothstep)
  CHECK(tr.at(4.2).y == Approx(seen.at(4.2).y));
  CHECK(tr.at(5.5).x == Approx(0.2));
  // A grain that moves as grains do is left alone.
  render::SubjectTrack calm = seen;
  calm.y = std::vector<double>(seen.y.size(), 1.0);
  calm.x = std::vector<double>(seen.x.size(), 0.0);
  CHECK(render::hold_through_jumps(calm, 0.65) == 0);
}

TEST_CASE("a view widened to show disks whole keeps its rectangle and angle and grows no more than needed",
          "[render]") {
  render::View v{render::fit(0.5, 1, 1.5, 2, 640, 360, 0.3), {40, 0, 640, 360}, "window"};
  const std::vector<core::Vec2> arch = {{-0.15, 0.07}, {0, 0.15}, {0.15, 0.07}};
  const std::vector<double> r = {0.065, 0.065, 0.065};
  CHECK_FALSE(render::shows_disks(v, arch, r));
  const render::View w = render::widened_to_show(v, arch, r, 0.065);
  CHECK(render::shows_disks(w, arch, r));
  CHECK(render::shows_disks(w, {{1.0, 1.5}}, {0.4}));  // what it showed before, still shown
  CHECK(w.rect.x == 40);
  CHECK(w.rect.w == 640);
  CHECK(w.cam.angle == 0.3);
  // Tight: with 10% less height the padded disks no longer fit.
  render::View smaller = w;
  smaller.cam.height *= 0.9;
  CHECK_FALSE(render::shows_disks(smaller, arch, {0.13, 0.13, 0.13}));
  CHECK(render::shows_disks(v, {{1.0, 1.5}}, {0.1}));
}

TEST_CASE("the outlet camera is sized by the grain: ten diameters tall at any grain size", "[render]") {
  core::Scene paper;
  const auto at_paper =
      render::layout_views(render::parse_camera("outlet"), core::make_geometry(paper), 600, 600);
  CHECK(at_paper[0].cam.height == Approx(1.3));  // the paper's 0.13 m disks: 1.3 m, as before
  core::Scene small = paper;
  core::apply_overrides(small, {"radius_original=0.0065", "silo_width=0.2", "aperture=0.0249",
                                "hopper_height=0.0877", "silo_height=0.4"});
  const auto geo = core::make_geometry(small);
  const auto v = render::layout_views(render::parse_camera("outlet"), geo, 600, 600);
  CHECK(v[0].cam.height == Approx(10 * geo.grain_diameter));
  const auto split = render::layout_views(render::parse_camera("split"), geo, 1920, 1080);
  CHECK(split[1].cam.height == Approx(10 * geo.grain_diameter));
  CHECK(render::parse_camera("window:-1,0,1,2").kind == render::CameraSpec::Kind::Window);
  CHECK_THROWS_WITH(render::parse_camera("window:0,0,0,0"), Catch::Contains("X1 > X0"));
}

TEST_CASE("disks show their species colour at the expected pixels, arch members carry the halo", "[render]") {
  auto& fx = fixture();
  const int w = 400, h = 400;
  core::Frame f;
  f.particles = {disk(-0.25f, 0.75f, 0.065f, core::Species::Original),
                 disk(0.25f, 0.75f, 0.026f, core::Species::Added),
                 disk(-0.065f, 0.25f, 0.065f, core::Species::Original),
                 disk(0.065f, 0.25f, 0.065f, core::Species::Original)};
  f.arch = {2, 3};          // two members in contact
  f.since_last_exit = 3.0;  // clogged: the arch is drawn at full strength
  auto views = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), fx.geo, w, h);
  render::Style style;
  render::Target target(w, h);
  target.bind();
  fx.renderer.draw(f, fx.geo, views, style, w, h);
  core::Image img;
  target.read(img);
  REQUIRE(img.width == w);
  const auto& v = views[0];
  auto at = [&](double x, double y) {
    core::Vec2 p = v.world_to_pixel({x, y});
    return img.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  };
  CHECK(distance(at(-0.25, 0.75), render::species_color(style.palette, core::Species::Original)) < 8);
  CHECK(distance(at(0.25, 0.75), render::species_color(style.palette, core::Species::Added)) < 8);
  CHECK(distance(at(0.0, 0.6), render::background_color(style)) == 0);  // empty space
  CHECK(distance(at(0.25, 0.75 + 0.04), render::background_color(style)) ==
        0);  // just outside the small disk
  // The halo: a gold ring just outside each arch member (here 4.8 px wide, sampled 2.4 px out).
  const double ring = 0.065 + 2.4 / v.px_per_m();
  CHECK(distance(at(-0.065, 0.25 - ring), render::arch_color(style.palette)) < 40);
  CHECK(distance(at(-0.25, 0.75 - ring), render::background_color(style)) == 0);  // a non-member has none
  // The bond between the two members is dark, mid-way between them (over their contact).
  CHECK(at(-0.03, 0.25)[0] < 60);
  // Rows come from the top: the top row of the image shows world y = 1 (empty), not y = 0.
  CHECK(distance(img.pixel(200, 0), render::background_color(style)) == 0);
  // GL's own top-down read-back (GL_MESA_pack_invert, where offered) and the flip on the CPU give the same
  // bytes.
  INFO("GL_MESA_pack_invert offered: " << render::has_pack_invert());
  core::Image gl_rows, flipped;
  std::vector<std::uint8_t> scratch;
  render::read_framebuffer(target.framebuffer(), w, h, gl_rows, scratch, render::has_pack_invert());
  CHECK(gl_rows.rgba == img.rgba);
  render::read_framebuffer(target.framebuffer(), w, h, flipped, scratch, false);
  CHECK(flipped.rgba == img.rgba);
}

namespace {
// WCAG 2's relative luminance and contrast ratio of two pixels.
double luminance(const std::uint8_t* px) {
  double l = 0;
  const double weight[3] = {0.2126, 0.7152, 0.0722};
  for (int k = 0; k < 3; ++k) {
    const double c = px[k] / 255.0;
    l += weight[k] * (c <= 0.03928 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  return l;
}
double contrast(const std::uint8_t* a, const std::uint8_t* b) {
  const double la = luminance(a), lb = luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}
}  // namespace

TEST_CASE("the colour-blind palette's seven species stay apart for every kind of colour blindness",
          "[render]") {
  // Each pair of the colour-blind palette's species colours (Okabe and Ito's seven) seen as a protanope,
  // a deuteranope and a tritanope (Machado, Oliveira and Fernandes 2009, severity 1, on linear RGB) stays
  // at least 15 apart in CIELAB (about three times the difference a viewer tells at a glance; measured
  // 16.0 at the closest, bluish green and sky blue for a tritanope). The grey for an eighth species and on
  // is not in the set (8.5 from reddish purple for a deuteranope).
  const double sim[3][9] = {
      {0.152286, 1.052583, -0.204868, 0.114503, 0.786281, 0.099216, -0.003882, -0.048116, 1.051998},
      {0.367322, 0.860646, -0.227968, 0.280085, 0.672501, 0.047413, -0.011820, 0.042940, 0.968881},
      {1.255528, -0.076749, -0.178779, -0.078411, 0.930809, 0.147602, 0.004733, 0.691367, 0.303900}};
  auto lab = [](const double* m, render::Rgba c) {
    auto linear = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
    const double rgb[3] = {linear(c.r), linear(c.g), linear(c.b)};
    double s[3];
    for (int i = 0; i < 3; ++i)
      s[i] = std::clamp(m[3 * i] * rgb[0] + m[3 * i + 1] * rgb[1] + m[3 * i + 2] * rgb[2], 0.0, 1.0);
    const double xyz[3] = {(0.4124 * s[0] + 0.3576 * s[1] + 0.1805 * s[2]) / 0.95047,
                           0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2],
                           (0.0193 * s[0] + 0.1192 * s[1] + 0.9505 * s[2]) / 1.08883};
    double f[3];
    for (int i = 0; i < 3; ++i) f[i] = xyz[i] > 0.008856 ? std::cbrt(xyz[i]) : 7.787 * xyz[i] + 16.0 / 116;
    return std::array<double, 3>{116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
  };
  double closest = 1e9;
  for (int kind = 0; kind < 3; ++kind)
    for (int a = 0; a < 7; ++a)
      for (int b = a + 1; b < 7; ++b) {
        const auto p =
            lab(sim[kind], render::species_color(render::Palette::ColorBlind, static_cast<core::Species>(a)));
        const auto q =
            lab(sim[kind], render::species_color(render::Palette::ColorBlind, static_cast<core::Species>(b)));
        const double d = std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
        INFO("vision " << kind << " (protan, deutan, tritan), species " << a << " and " << b << ": " << d);
        CHECK(d >= 15);
        closest = std::min(closest, d);
      }
  INFO("closest pair " << closest);
  CHECK(closest >= 15);
}

TEST_CASE(
    "every species and the arch's ring stand 3 to 1 against the background, white or dark, in both palettes",
    "[render]") {
  // WCAG's contrast for graphics: what bounds a grain (its fill or its dark rim) and the arch's halo (the
  // gold, or its dark edge on white: gold alone has 1.6:1 there) reaches 3:1 against the background. Read
  // from the pixels on a line from outside each grain to its centre: the largest contrast met on the way.
  auto& fx = fixture();
  const int w = 600, h = 200;
  core::Frame f;
  for (int k = 0; k < 8; ++k)  // the paper's two, five more, and the grey beyond them
    f.particles.push_back(disk(-0.7f + 0.2f * k, 0.5f, 0.065f, static_cast<core::Species>(k)));
  f.particles.push_back(disk(0.0f, 0.2f, 0.065f, core::Species::Original));
  f.arch = {8};
  f.since_last_exit = 3.0;
  f.clog_open = true;
  auto views = render::layout_views(render::parse_camera("window:-0.9,0,0.9,0.6"), fx.geo, w, h);
  render::Target target(w, h);
  for (const bool dark : {false, true})
    for (const auto palette : {render::Palette::Paper, render::Palette::ColorBlind}) {
      render::Style style;
      style.dark = dark;
      style.palette = palette;
      target.bind();
      fx.renderer.draw(f, fx.geo, views, style, w, h);
      core::Image img;
      target.read(img);
      const auto& v = views[0];
      const std::uint8_t* bg = img.pixel(2, 2);
      auto largest = [&](const core::Particle& p, double from, double to) {  // along y below the grain
        double best = 0;
        for (double r = from; r >= to; r -= 0.25 / v.px_per_m()) {
          const core::Vec2 q = v.world_to_pixel({p.x, p.y - r});
          best = std::max(best, contrast(img.pixel(static_cast<int>(q.x), static_cast<int>(q.y)), bg));
        }
        return best;
      };
      INFO((dark ? "dark" : "white") << " background, palette " << static_cast<int>(palette));
      REQUIRE(distance(bg, render::background_color(style)) <= 1);
      for (int k = 0; k < 8; ++k) {
        INFO("species " << k);
        CHECK(largest(f.particles[static_cast<size_t>(k)], 0.065 + 0.01, 0.0) >= 3.0);
      }
      // The halo: from outside it to the grain's edge (not into the grain: the ring alone must stand out).
      CHECK(largest(f.particles[8], 0.065 + 0.04, 0.065 + 1.0 / v.px_per_m()) >= 3.0);
    }
}

TEST_CASE("force chains are drawn between touching grains in the colour map, over the grains", "[render]") {
  auto& fx = fixture();
  const int w = 400, h = 400;
  core::Frame f;
  f.particles = {disk(-0.065f, 0.5f, 0.065f, core::Species::Original),
                 disk(0.065f, 0.5f, 0.065f, core::Species::Original),
                 disk(0.195f, 0.5f, 0.065f, core::Species::Original)};
  f.contacts = {{0, 1, 30.0f}, {1, 2, 0.1f}};  // a strong contact and one below the threshold
  auto views = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), fx.geo, w, h);
  render::Style style;
  style.chains = true;
  style.chain_min = 1.0;
  style.chain_max = 20.0;
  render::Target target(w, h);
  target.bind();
  fx.renderer.draw(f, fx.geo, views, style, w, h);
  core::Image img;
  target.read(img);
  const auto& v = views[0];
  auto at = [&](double x, double y) {
    core::Vec2 p = v.world_to_pixel({x, y});
    return img.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  };
  // On the first grain, between its centre and the contact: the chain's colour (the map's top), not red.
  CHECK(distance(at(-0.03, 0.5), render::colormap(1.0)) < 40);
  // On the third grain, where the weak contact would run: the grain's own red.
  CHECK(distance(at(0.16, 0.5), render::species_color(style.palette, core::Species::Original)) < 8);
}

TEST_CASE("a dark background: dark empty space, light walls, the grains' own colours", "[render]") {
  auto& fx = fixture();
  const int w = 400, h = 400;
  core::Frame f;
  f.particles = {disk(0.0f, 0.5f, 0.065f, core::Species::Original)};
  auto views = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), fx.geo, w, h);
  render::Style style;
  style.dark = true;
  render::Target target(w, h);
  target.bind();
  fx.renderer.draw(f, fx.geo, views, style, w, h);
  core::Image img;
  target.read(img);
  const auto& v = views[0];
  auto at = [&](double x, double y) {
    core::Vec2 p = v.world_to_pixel({x, y});
    return img.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  };
  CHECK(at(0.3, 0.8)[0] < 30);  // empty space is dark
  CHECK(distance(at(0.0, 0.5), render::species_color(style.palette, core::Species::Original)) < 8);
  // The hopper's left wall at mid height of the funnel: light.
  const core::Segment& wall = fx.geo.walls[static_cast<int>(core::Wall::HopperLeft)];
  const core::Vec2 mid = 0.5 * (wall.a + wall.b);
  CHECK(at(mid.x, mid.y)[0] > 150);
}

TEST_CASE("colour by speed uses the colour map on its fixed scale", "[render]") {
  auto& fx = fixture();
  core::Frame f;
  f.particles = {disk(0, 0.5f, 0.1f, core::Species::Original)};
  f.particles[0].vx = 0.5f;  // the top of the default 0.5 m/s scale
  auto views = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), fx.geo, 200, 200);
  render::Style style;
  style.color = render::ColorMode::Speed;
  render::Target target(200, 200);
  target.bind();
  fx.renderer.draw(f, fx.geo, views, style, 200, 200);
  core::Image img;
  target.read(img);
  CHECK(distance(img.pixel(100, 100), render::colormap(1.0)) < 8);
}

TEST_CASE("a transparent background reads back with zero alpha and straight colours", "[render]") {
  auto& fx = fixture();
  core::Frame f;
  f.particles = {disk(0, 0.5f, 0.1f, core::Species::Added)};
  auto views = render::layout_views(render::parse_camera("window:-0.5,0,0.5,1"), fx.geo, 100, 100);
  render::Style style;
  style.transparent = true;
  render::Target target(100, 100);
  target.bind();
  fx.renderer.draw(f, fx.geo, views, style, 100, 100);
  core::Image img;
  target.read(img, true);
  CHECK(img.pixel(2, 50)[3] == 0);
  CHECK(img.pixel(50, 50)[3] == 255);
  CHECK(distance(img.pixel(50, 50), render::species_color(style.palette, core::Species::Added)) < 8);
}

TEST_CASE("the overlay draws into the frame and a clean frame has none", "[render]") {
  auto& fx = fixture();
  static render::Overlay overlay;
  core::Frame f;
  f.t = 12.5;
  f.exits = {10, 0};
  auto views = render::layout_views(render::parse_camera("hopper"), fx.geo, 320, 240);
  render::Style style;
  render::Target target(320, 240);
  auto render_with = [&](const render::OverlayOptions& o) {
    target.bind();
    fx.renderer.draw(f, fx.geo, views, style, 320, 240);
    overlay.draw(f, {}, o, views, style, 320, 240);
    core::Image img;
    target.read(img);
    return img;
  };
  core::Image clean = render_with(render::OverlayOptions::none());
  core::Image full = render_with({});
  long differing = 0;
  for (size_t i = 0; i < clean.rgba.size(); ++i) differing += clean.rgba[i] != full.rgba[i];
  CHECK(differing > 1000);
  CHECK(render::parse_overlay("none").any() == false);
  CHECK(render::parse_overlay("time,scale").time);
  CHECK_THROWS_WITH(render::parse_overlay("time,clock"), Catch::Matchers::Contains("'clock'"));
  // --overlay-at: one corner for the information box, or each box its own.
  render::OverlayOptions at;
  render::parse_placement("top-left", "--overlay-at", at);
  CHECK(at.info_at == 1);
  render::parse_placement("plot=bottom-left,scale=top-right,info=auto", "--overlay-at", at);
  CHECK((at.plot_at == 3 && at.scale_at == 0 && at.info_at == -1 && at.colorbar_at == -1));
  CHECK_THROWS_WITH(render::parse_placement("legend=top-left", "--overlay-at", at),
                    Catch::Matchers::Contains("'legend=top-left'") &&
                        Catch::Matchers::Contains("info, plot, colorbar or scale"));
  CHECK_THROWS_WITH(render::parse_placement("plot=middle", "--overlay-at", at),
                    Catch::Matchers::Contains("--overlay-at plot=") && Catch::Matchers::Contains("middle"));
  // The colour bar without the legend, beside the information box: never under it (two frames, the second
  // with the sizes of the first, as a movie's frames are).
  style.color = render::ColorMode::Speed;
  render::OverlayOptions o = render::parse_overlay("time,counts,rate,timer,colorbar");
  views = render::layout_views(render::parse_camera("split"), fx.geo, 1280, 720);
  render::Target big(1280, 720);
  for (int k = 0; k < 2; ++k) {
    big.bind();
    fx.renderer.draw(f, fx.geo, views, style, 1280, 720);
    overlay.draw(f, {}, o, views, style, 1280, 720);
    const auto a = overlay.info_rect(), b = overlay.colorbar_rect();
    REQUIRE(a[2] > a[0]);
    REQUIRE(b[2] > b[0]);
    const bool overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
    CHECK_FALSE(overlap);
  }
}

TEST_CASE("the boxes are sized for the picture being drawn, not the one before it", "[render]") {
  // A movie's frame whose box grows a row (a clog opens: the timer and the arch) was drawn with the previous
  // frame's size, and lost its last row (1.3% of frames); so was an inspector snapshot after a shorter one.
  auto& fx = fixture();
  core::Frame a;
  a.t = 2.0;
  a.exits = {10, 4};
  a.particles = {disk(-0.15f, 0.1f, 0.065f, core::Species::Original),
                 disk(0.0f, 0.12f, 0.065f, core::Species::Original),
                 disk(0.15f, 0.1f, 0.065f, core::Species::Original)};
  core::Frame b = a;
  b.t = 2.1;
  b.clog_open = true;
  b.clog_start = 1.5;
  b.arch = {0, 1, 2};
  render::Style style;
  const render::OverlayOptions o = render::parse_overlay("all");
  constexpr int w = 1280, h = 720;
  const auto views = render::layout_views(render::parse_camera("split"), fx.geo, w, h);
  render::Target target(w, h);
  auto rect_of = [&](render::Overlay& overlay, const core::Frame& f) {
    target.bind();
    fx.renderer.draw(f, fx.geo, views, style, w, h);
    overlay.draw(f, {}, o, views, style, w, h);
    return overlay.info_rect();
  };
  render::Overlay fresh, after;
  const auto alone = rect_of(fresh, b);
  const auto before = rect_of(after, a);
  REQUIRE(alone[3] - alone[1] > before[3] - before[1]);  // b's box is taller: the case is real
  const auto grown = rect_of(after, b);
  CHECK(grown[3] - grown[1] == alone[3] - alone[1]);
  CHECK(grown[2] - grown[0] == alone[2] - alone[0]);
  // And back: the shorter box is not drawn at the taller one's size.
  const auto shrunk = rect_of(after, a);
  CHECK(shrunk[3] - shrunk[1] == before[3] - before[1]);
}

TEST_CASE("in a window the information box never covers the container: a clear corner or beside the picture",
          "[render]") {
  auto& fx = fixture();
  core::Frame f;
  f.t = 3.5;
  f.exits = {4, 0};
  render::Style style;
  render::OverlayOptions o = render::parse_overlay("time,counts,rate,timer,arch,legend");
  o.place_clear = o.may_leave = true;
  constexpr int w = 640, h = 360;
  render::Target target(w, h);
  // The pixels the overlay changed, against the same frame without it.
  auto changed = [&](render::Overlay& overlay, const std::vector<render::View>& views,
                     const render::OverlayOptions& opts) {
    core::Image img[2];
    for (int k = 0; k < 2; ++k) {
      target.bind();
      fx.renderer.draw(f, fx.geo, views, style, w, h);
      if (k == 1) overlay.draw(f, {}, opts, views, style, w, h, &fx.geo);
      target.read(img[k]);
    }
    std::vector<core::Vec2> px;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = 4 * (static_cast<size_t>(y) * w + x);
        if (std::abs(img[0].rgba[i] - img[1].rgba[i]) + std::abs(img[0].rgba[i + 1] - img[1].rgba[i + 1]) > 0)
          px.push_back({x + 0.5, y + 0.5});
      }
    return px;
  };
  SECTION("with the silo on the right, the box moves to a free corner on the left, off the container") {
    render::Overlay overlay;
    const auto views = render::layout_views(render::parse_camera("window:-2.5,3.0,0.6,4.0"), fx.geo, w, h);
    const auto px = changed(overlay, views, o);
    CHECK_FALSE(overlay.info_left());
    CHECK(px.size() > 1000);
    long inside = 0;
    for (const auto& p : px) inside += fx.geo.contains(views[0].pixel_to_world(p), 0.0);
    CHECK(inside == 0);
  }
  SECTION("zoomed into the column, no corner is free: the box leaves the picture") {
    render::Overlay overlay;
    const auto views = render::layout_views(render::parse_camera("window:-0.3,2.0,0.3,2.5"), fx.geo, w, h);
    CHECK(changed(overlay, views, o).empty());
    CHECK(overlay.info_left());
    // Where it may not leave (a snapshot has no side panel), it is drawn in the least-covering corner.
    render::OverlayOptions stay = o;
    stay.may_leave = false;
    CHECK(changed(overlay, views, stay).size() > 1000);
    CHECK_FALSE(overlay.info_left());
  }
}

TEST_CASE("image sizes outside what GL allows are refused", "[render]") {
  fixture();
  CHECK_THROWS_AS(render::Target(0, 100), core::InputError);
  CHECK_THROWS_AS(render::Target(100000, 100), core::InputError);
}

TEST_CASE(
    "the information box goes to the corner --overlay-at asks for in the corner asked for, whatever it "
    "covers",
    "[render]") {
  auto& fx = fixture();
  core::Frame f;
  f.t = 1.0;
  f.exits = {3, 1};
  f.particles = {disk(0.0f, 0.3f, 0.065f, core::Species::Original)};
  render::Style style;
  constexpr int w = 640, h = 360;
  const auto views = render::layout_views(render::parse_camera("outlet"), fx.geo, w, h);
  render::Target target(w, h);
  for (const char* corner : {"top-right", "top-left", "bottom-right", "bottom-left"}) {
    render::OverlayOptions o = render::parse_overlay("time,counts,legend");
    o.place_clear = true;  // what auto would do: overridden by the user's corner
    o.info_at = render::parse_corner(corner, "--overlay-at");
    render::Overlay overlay;
    std::array<float, 4> r{};
    for (int pass = 0; pass < 2; ++pass) {  // the first picture sizes the box, as in a movie
      target.bind();
      fx.renderer.draw(f, fx.geo, views, style, w, h);
      overlay.draw(f, {}, o, views, style, w, h, &fx.geo);
      r = overlay.info_rect();
    }
    INFO(corner);
    const bool right = std::string(corner).find("right") != std::string::npos;
    const bool top = std::string(corner).find("top") != std::string::npos;
    CHECK((right ? r[2] > 0.9f * w : r[0] < 0.1f * w));
    CHECK((top ? r[1] < 0.1f * h : r[3] > 0.9f * h));
  }
  CHECK_THROWS_WITH(render::parse_corner("middle", "--overlay-at"),
                    Catch::Contains("expected auto, top-right, top-left, bottom-right or bottom-left"));
}

TEST_CASE(
    "the README's camera path keeps the outlet and the region of its arches in the picture at every frame",
    "[render]") {
  // record --camera-path 0:hopper,3:outlet,9:outlet,12:hopper: gliding from the whole hopper to the outlet,
  // the centre and the height once moved apart and the outlet dropped below the frame half way.
  const core::Geometry geo = core::make_geometry(core::Scene{});
  const render::CameraPath path = render::parse_camera_path("0:hopper,3:outlet,9:outlet,12:hopper");
  const double d = 2 * 0.065;
  long frames = 0;
  for (double t = 0; t <= 15; t += 1.0 / 30, ++frames) {
    const render::View v = path.view_at(t, geo, 1920, 1080);
    // The outlet's edges and the region an arch over it stands in (two diameters up, across the outlet).
    for (const core::Vec2 p :
         {core::Vec2{-geo.half_aperture, 0}, core::Vec2{geo.half_aperture, 0},
          core::Vec2{-geo.half_aperture - d, 2 * d}, core::Vec2{geo.half_aperture + d, 2 * d}}) {
      const core::Vec2 px = v.world_to_pixel(p);
      INFO("t = " << t << " s, point " << p.x << ", " << p.y);
      REQUIRE(px.x >= 0);
      REQUIRE(px.x <= 1920);
      REQUIRE(px.y >= 0);
      REQUIRE(px.y <= 1080);
    }
  }
  CHECK(frames > 400);
}
