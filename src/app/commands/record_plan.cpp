// record's options turned into panels and a plan (app/commands/record_plan.h).
#include "app/commands/record_plan.h"
#include "app/services/cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"

namespace app {

namespace {
namespace fs = std::filesystem;
std::string num6(double v) {
  return core::format_g(v, 6);
}
}  // namespace

// The panels: the base scene alone, or one per --compare / --compare-scene (with a single one, the base scene
// is the first panel so that the comparison has two sides).
static std::vector<Panel> make_panels_untitled(const RecordOptions& o) {
  std::vector<Panel> panels;
  // Each panel's scene compiled once, here: everything below reads its Model.
  const core::Model base_model = o.scene.compile();
  const core::Scene& base = base_model.scene;
  auto add_model = [&](core::Model m, const std::string& label) {
    Panel p;
    p.model = std::move(m);
    p.label = label;
    panels.push_back(std::move(p));
  };
  auto add = [&](const core::Scene& s, const std::string& label) { add_model(core::compile(s), label); };
  const size_t n_compare = o.compare.size() + o.compare_scene.size();
  if (!o.compare_run.empty()) {
    // An experiment (or any run) beside the simulation of its container, on one clock from the opening.
    if (n_compare > 0)
      throw core::InputError("--compare-run goes alone (not with --compare or --compare-scene)");
    auto replay = std::make_shared<Replay>(o.compare_run);
    const std::string diff = container_difference(base_model.setup.geo, replay->model().setup.geo);
    if (!diff.empty())
      throw core::InputError("--compare-run " + o.compare_run + ": its container is not the scene's (" +
                             diff + "): a comparison shows one geometry");
    add_model(base_model, "simulation: " + fs::path(o.scene.path).stem().string());
    add_model(replay->model(), (replay->imported() ? "experiment: " : "run: ") + replay->name());
    panels.front().subdir = "panel0/";
    panels.back().replay = std::move(replay);
    return panels;
  }
  if (n_compare == 0) {
    add_model(base_model, "");
    return panels;
  }
  if (n_compare == 1) add_model(base_model, "base: " + fs::path(o.scene.path).stem().string());
  for (const auto& c : o.compare) {
    core::Scene s = base;
    std::vector<std::string> sets;
    std::stringstream ss(c);
    for (std::string item; std::getline(ss, item, ',');) sets.push_back(item);
    if (sets.empty())
      throw core::InputError("--compare '" + c + "': expected key=value[,key=value...], e.g. mu=2.2");
    core::apply_overrides(s, sets);
    if (o.scene.seed) s.seed = *o.scene.seed;
    if (o.scene.duration) s.duration = *o.scene.duration;
    add(s, c);
  }
  for (const auto& f : o.compare_scene) {
    core::Scene s = core::load_scene(f);
    core::apply_overrides(s, o.scene.overrides);
    if (o.scene.seed) s.seed = *o.scene.seed;
    s.duration = base.duration;
    add(s, fs::path(f).stem().string());
  }
  if (panels.size() > 4)
    throw core::InputError("--compare: " + std::to_string(panels.size()) +
                           " panels; a comparison has 2 to 4");
  for (const auto& p : panels)
    if (p.model.scene.dt != base.dt || p.model.scene.duration != base.duration)
      throw core::InputError("--compare " + p.label +
                             ": dt and duration must equal the base scene's (dt = " + num6(base.dt) +
                             " s, duration = " + num6(base.duration) + " s): the panels run on one clock");
  for (size_t k = 0; k < panels.size(); ++k) panels[k].subdir = "panel" + std::to_string(k) + "/";
  return panels;
}

std::vector<Panel> make_panels(const RecordOptions& o) {
  std::vector<Panel> panels = make_panels_untitled(o);
  if (o.panel_titles.empty()) return panels;
  if (panels.size() == 1)
    throw core::InputError(
        "--panel-title: a single movie has no panels to title (with --compare, --compare-scene "
        "or --compare-run it has 2 to 4)");
  if (o.panel_titles.size() != panels.size())
    throw core::InputError("--panel-title: " + std::to_string(o.panel_titles.size()) + " given for " +
                           std::to_string(panels.size()) + " panels (one each, in order)");
  for (size_t k = 0; k < panels.size(); ++k) panels[k].label = o.panel_titles[k];
  return panels;
}

// The video and its clock: size, rate, quality, speed and slow motion, checked.
static void plan_video(const RecordOptions& o, const core::Scene& scene, Plan& plan) {
  record::VideoSettings& video = plan.video;
  render::parse_size(o.size, "--size", video.width, video.height);
  video.fps = o.fps;
  video.crf = o.crf;
  video.preset = o.preset;
  if (!o.no_movie) record::validate(video);
  if (!(o.speed > 0) || o.speed > 1000)
    throw core::InputError("--speed " + num6(o.speed) +
                           ": allowed range is (0, 1000] simulated s per video s");
  if (!(o.slowmo >= 1) || o.slowmo > 100)
    throw core::InputError("--slowmo " + num6(o.slowmo) + ": allowed range is 1 (off) to 100");
  if (o.fps < 1 || o.fps > 240)
    throw core::InputError("--fps " + std::to_string(o.fps) + ": allowed range is 1 to 240");
  plan.clock = FrameClock::video(scene.dt, o.fps, o.speed, o.slowmo);
  video.frame_rate = plan.clock.video_fps;
  if (o.png_every < 0)
    throw core::InputError("--png-every " + std::to_string(o.png_every) + ": must be >= 0");
  if (o.no_movie && o.png_every == 0)
    throw core::InputError("--no-movie without --png-every would record nothing");
}

// The texts the overlay may write over the scene at once: an event's caption (the longest this scene can
// have, with an arch of up to 9 disks), the slow-motion badge, and every note of --annotate (all at once: the
// plan does not look at their times).
static std::vector<std::string> over_scene_texts(const RecordOptions& o, const Plan& plan,
                                                 const core::Model& model) {
  std::vector<std::string> texts;
  if (plan.overlay.events) {
    std::string caption;
    auto longer = [&](const std::string& c) {
      if (c.size() > caption.size()) caption = c;
    };
    const core::Scene& scene = model.scene;
    if (model.setup.clog_rule)
      longer("arch removed (" + num6(scene.clog_timeout) + " s rule): 9 " +
             (model.setup.any_polygon() ? "grains" : "disks"));
    if (scene.vibration_amplitude > 0 || scene.vibration_gamma > 0)
      longer("clog broken by vibration after 10.0 s");
    if (plan.freeze) longer(plan.freeze.caption());
    if (!caption.empty()) texts.push_back(caption);
  }
  if (o.speed < 1 || o.slowmo > 1 || plan.freeze) texts.push_back("slow motion 12.34x");
  for (const auto& n : plan.notes) texts.push_back(n.text);
  return texts;
}

// Each panel's views, its heading and the room for the overlay's boxes (a column on its right or a band below
// its views), the same in every panel.
// `texts`: what the overlay writes over the scene after the boxes (over_scene_texts), which need room too.
static void lay_out_panels(const render::CameraSpec& camera, bool quiet, Plan& plan,
                           std::vector<Panel>& panels, const std::vector<std::string>& texts) {
  const record::VideoSettings& video = plan.video;
  const size_t n_panels = panels.size();
  const int panel_w = video.width / static_cast<int>(n_panels);
  // A comparison's panels are headed by their titles in large type (the information box no longer repeats
  // them), the same band over each.
  const float em = render::overlay_em(video.height, plan.overlay.font_scale);
  int heading_h = 0;
  if (n_panels > 1)
    for (const auto& p : panels)
      heading_h = std::max(heading_h, render::heading_height(p.label, em, panel_w));
  // Where the container leaves the overlay's boxes no clear space (a flat silo fills its outlet view; large
  // text; a comparison's narrow panels), every panel gets the same room for them, the most any panel needs:
  // a column on its right, or a band below its views where that leaves the views more zoom (a panel taller
  // than wide: a column would halve its outlet view's width).
  auto views_in = [&](const Panel& p, size_t k, int width, int height) {
    std::vector<std::vector<render::View>> sets;
    if (plan.path.empty()) {
      sets.push_back(render::layout_views(camera, p.geo, width, height));
    } else {  // each key, and half-way between keys
      const auto& keys = plan.path.keys;
      for (size_t i = 0; i < keys.size(); ++i) {
        sets.push_back({plan.path.view_at(keys[i].t, p.geo, width, height)});
        if (i + 1 < keys.size())
          sets.push_back({plan.path.view_at(0.5 * (keys[i].t + keys[i + 1].t), p.geo, width, height)});
      }
    }
    for (auto& views : sets)
      for (auto& v : views) v.rect.x += static_cast<int>(k) * panel_w, v.rect.y += heading_h;
    return sets;
  };
  const bool colour_rows = !render::color_scale_label(plan.style).empty() || plan.style.chains;
  std::vector<std::pair<float, float>> text_sizes;
  for (const auto& t : texts) text_sizes.push_back(render::text_box_estimate(t, em));
  auto column_for = [&](int band, bool* fits = nullptr) {  // the column the panels need, a band below
    int need = 0;
    for (size_t k = 0; k < n_panels; ++k) {
      const Panel& p = panels[k];
      const int height = video.height - heading_h - band;
      bool panel_fits = true;
      need = std::max(need, render::overlay_margin(
                                [&](int width) { return views_in(p, k, width, height); }, p.geo, plan.overlay,
                                static_cast<int>(k) * panel_w, panel_w, video.height, p.odata.species_names,
                                p.odata.title, colour_rows, heading_h, band, text_sizes, &panel_fits,
                                n_panels > 1 ? render::heading_width(p.label, em, panel_w) : 0.0f));
      if (fits && !panel_fits) *fits = false;
    }
    return need;
  };
  auto zoom = [&](int column, int band) {  // px/m of the most magnified view (the first panel, first key)
    const auto sets = views_in(panels.front(), 0, panel_w - column, video.height - heading_h - band);
    double best = 0;
    for (const auto& v : sets.front()) best = std::max(best, v.px_per_m());
    return best;
  };
  bool column_fits = true;
  int margin = column_for(0, &column_fits), band = 0;
  if (margin > 0) {
    // The lowest band that holds the boxes and the texts (where the views leave room at their bottom, below
    // the outlet, it can be lower than the boxes), in steps of a hundredth of the height: up to 45% of it
    // where the column holds them too (the band then only where it leaves the views more zoom), up to 65%
    // where the column does not (large text in a small picture: the views smaller, the texts clear).
    const int step = std::max(4, video.height / 100);
    const double most = column_fits ? 0.45 : 0.65;
    for (int b = step; b < most * (video.height - heading_h); b += step)
      if (column_for(b) == 0) {
        if (!column_fits || zoom(0, b) > zoom(margin, 0)) band = b, margin = 0;
        break;
      }
  }
  for (size_t k = 0; k < n_panels; ++k) {
    Panel& p = panels[k];
    p.odata.margin_w = margin;
    p.odata.margin_h = band;
    if (band > 0)
      p.odata.info_h = static_cast<int>(
          std::ceil(render::info_box_estimate(plan.overlay, em, p.odata.species_names, p.odata.title,
                                              colour_rows, render::info_title_wrap(em, 0))
                        .second));
    p.odata.heading_h = heading_h;
    if (n_panels > 1) p.odata.heading = p.label;
    const render::Rect area = panel_area(p, k, n_panels, video.width, video.height);
    p.views = plan.path.empty() ? render::layout_views(camera, p.geo, area.w, area.h)
                                : std::vector<render::View>{plan.path.view_at(0, p.geo, area.w, area.h)};
    for (auto& v : p.views) v.rect.x += area.x, v.rect.y += area.y;
  }
  // (Whether the boxes then find room is known when each picture is drawn: record counts the pictures where
  // they could not.)
  if (!quiet && (margin > 0 || band > 0))
    std::fprintf(
        stderr, "siloscope: the overlay takes a %d-pixel %s of %s (the container leaves it no clear space)\n",
        margin > 0 ? margin : band, margin > 0 ? "column on the right" : "band at the bottom",
        n_panels > 1 ? "each panel" : "the picture");
}

Plan plan_recording(const RecordOptions& o, std::vector<Panel>& panels) {
  Plan plan;
  record::VideoSettings& video = plan.video;
  plan_video(o, panels.front().model.scene, plan);
  // The look, checked and resolved once (app/services/looks.h).
  plan.look = o.looks.resolve(panels.front().model);
  plan.style = plan.look.style;
  plan.overlay = plan.look.overlay;
  plan.notes = plan.look.notes;
  const core::Setup& setup = panels.front().model.setup;
  o.track.apply(setup.n_total, plan.style);
  // The information box goes to the corner of each panel that covers the least of the container and its
  // grains (below the outlet in the default split view), as in the windows; it stays there unless another
  // corner is strictly clearer. With the discharge plot on request, the plot takes the free space below the
  // outlet and the box keeps the top-right corner (narrow comparison panels have no room there for both).
  plan.overlay.place_clear = !plan.overlay.plot;
  const render::CameraSpec camera =
      for_flag("--camera", [&] { return render::parse_camera(o.camera, true); });
  if (!o.camera_path.empty())
    plan.path = for_flag("--camera-path", [&] { return render::parse_camera_path(o.camera_path, true); });
  // A camera on an arch or a grain moves with its subject: a path of one key.
  if (camera.names_subject()) plan.path = render::subject_path(camera);
  if (!o.freeze.empty()) {
    const size_t colon = o.freeze.find(':');
    plan.freeze = render::parse_freeze(o.freeze.substr(0, colon),
                                       colon == std::string::npos ? "" : o.freeze.substr(colon + 1),
                                       "--freeze " + o.freeze, "clog:SECONDS or rule:SECONDS");
    if (plan.freeze.at == render::Freeze::At::Rule && !setup.clog_rule)
      throw core::InputError(
          "--freeze rule: the scene's clog rule is off (clog_timeout = 0); use clog:SECONDS");
  }
  const bool look_ahead = plan.look.color_scale_from_data;
  double top = 0;
  // Panels side by side, equal widths, the same camera (and so the same scales) in each.
  const size_t n_panels = panels.size();
  const int panel_w = video.width / static_cast<int>(n_panels);
  for (size_t k = 0; k < n_panels; ++k) {
    Panel& p = panels[k];
    p.geo = p.model.setup.geo;
    p.odata = render::overlay_data_for(p.model);
    p.odata.species_colors = o.looks.resolve(p.model).species_colors;
    if (n_panels > 1) {
      p.odata.title.clear();  // the panel's heading names it
      p.odata.panel_x = static_cast<int>(k) * panel_w;
      p.odata.panel_w = panel_w;
    }
  }
  // Arches and grains the camera shows, found by simulating ahead (in the first panel's run).
  resolve_camera_subjects(panels.front().model, plan.path,
                          o.camera_path.empty() ? "--camera" : "--camera-path", !o.quiet);
  // A grain the camera follows is marked as a tracked one (its ring and trail): the eye finds it at once.
  for (const auto& key : plan.path.keys)
    if (key.camera.kind == render::CameraSpec::Kind::Grain &&
        std::find(plan.style.tracked.begin(), plan.style.tracked.end(), key.camera.subject) ==
            plan.style.tracked.end())
      plan.style.tracked.push_back(key.camera.subject);
  lay_out_panels(camera, o.quiet, plan, panels, over_scene_texts(o, plan, panels.front().model));
  // The look-ahead last: everything it could be refused for has been checked.
  if (look_ahead) {
    // The same scale in every panel: the largest of the panels' own.
    for (const auto& p : panels)
      top = std::max(
          top, color_scale_from_data(p.model, plan.style.color == render::ColorMode::Force, 2.0, !o.quiet));
    if (!o.quiet)
      std::fprintf(stderr, "siloscope: --color-max auto: %s %s (99th percentile over the first 2 s)\n",
                   num6(top).c_str(), plan.style.color == render::ColorMode::Force ? "N" : "m/s");
  }
  if (top > 0)
    (plan.style.color == render::ColorMode::Speed ? plan.style.speed_max : plan.style.force_max) = top;
  o.track.resolve_tags(panels.front().model, plan.style, o.quiet);
  plan.look.style = plan.style;  // with the scale the look-ahead found and the grains followed
  return plan;
}

render::Rect panel_area(const Panel& p, size_t k, size_t n, int w, int h) {
  const int panel_w = w / static_cast<int>(n);
  return {static_cast<int>(k) * panel_w, p.odata.heading_h, panel_w - p.odata.margin_w,
          h - p.odata.heading_h - p.odata.margin_h};
}

render::View path_view(const Plan& plan, const Panel& p, size_t k, size_t n, int w, int h, double t) {
  const render::Rect area = panel_area(p, k, n, w, h);
  render::View v = plan.path.view_at(t, p.geo, area.w, area.h);
  v.rect.x += area.x, v.rect.y += area.y;
  return v;
}

}  // namespace app
