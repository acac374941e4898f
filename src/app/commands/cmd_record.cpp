// siloscope record SCENE --out recordings/NAME: a discharge movie (NAME.mp4) and, in NAME/, the events, the
// measurements, the metadata and optional PNG frames. The simulation produces Frames on this thread;
// app/pipeline.h renders and encodes them on two more (bounded queues keep memory flat).
//
// Over 400 lines because a recording's plan (panels, cameras, colour scale, slow motion), its metadata and
// its outputs are all decided from RecordOptions; each step is its own function below.
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <optional>
#include <sstream>

#include "analysis/measure.h"
#include "analysis/tidy.h"
#include "app/commands/record_plan.h"
#include "app/services/cli.h"
#include "app/services/hindsight.h"
#include "app/services/looks.h"
#include "app/services/pipeline.h"
#include "app/services/process.h"
#include "app/services/recording.h"
#include "app/services/replay.h"
#include "app/services/run_outputs.h"
#include "app/services/session.h"
#include "app/services/sinks.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/setup.h"
#include "io/events_csv.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "io/trajectory.h"
#include "record/mp4.h"
#include "render/camera.h"
#include "render/overlay.h"
#include "sim/silo.h"

namespace app {

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Stages {
  double sim = 0, draw = 0, readback = 0, convert = 0, encode = 0, png = 0;
};

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void print_recording(const RecordOptions& o, const Stages& st, long encoded, double shown, double wall,
                     bool was_interrupted, const std::string& gl_renderer, const std::vector<Panel>& panels,
                     const Session& session, const std::vector<analysis::Measurements>& ms,
                     const fs::path& movie_path, const fs::path& base) {
  const double per = 1e3 / std::max(1L, encoded);
  std::printf("renderer    %s\n", gl_renderer.c_str());
  std::printf(
      "recorded    %ld frames (%.1f s of discharge%s) in %.1f s wall: %.2fx real time, %.1f frames/s\n",
      encoded, shown, was_interrupted ? ", interrupted" : "", wall, shown / wall, encoded / wall);
  std::printf(
      "per frame   sim %.1f ms, draw %.1f ms, readback %.1f ms, convert %.1f ms, encode %.1f ms, png %.1f ms"
      " (stages overlap)\n",
      st.sim * per, st.draw * per, st.readback * per, st.convert * per, st.encode * per, st.png * per);
  for (size_t k = 0; k < panels.size(); ++k) {
    if (panels.size() > 1) std::printf("--- panel %zu: %s\n", k, panels[k].label.c_str());
    if (panels[k].replay) continue;
    const auto& setup = session.world(k).setup();
    std::printf("%s", analysis::summary_text(ms[k], setup.species_names(), setup.clog_rule).c_str());
  }
  if (!o.no_movie) std::printf("movie       %s\n", movie_path.c_str());
  std::printf("run data    %s/\n", base.c_str());
}

// The movie's sink: each frame tick becomes one picture of every panel with its annotations, pushed to the
// render and encode stages; the time between pushes is the simulation's share.
class MovieSink : public Sink {
 public:
  MovieSink(FramePipeline& pipeline, std::vector<Panel>& panels, const Plan& plan, double speed, int width)
      : pipeline_(pipeline),
        panels_(panels),
        clock_(plan.clock),
        plan_(plan),
        speed_(speed),
        width_(width),
        height_(plan.video.height),
        t0_(Clock::now()) {}
  void frame(const FrameTick& tick) override {
    PipelineFrame pf;
    pf.frames = tick.frames;
    bool freeze = false;
    for (size_t i = 0; i < panels_.size(); ++i) {
      if (panels_[i].replay) {  // a run played back: its frame at this time, no marks of the simulation's
        pf.frames.push_back(panels_[i].replay->at(tick.frames[0].t));
        render::Annotations notes;
        notes.slowdown = (1.0 / speed_) * (tick.slow ? clock_.effective_slowmo : 1.0);
        pf.notes.push_back(std::move(notes));
        if (!plan_.path.empty()) {
          pf.views.push_back(
              {path_view(plan_, panels_[i], i, panels_.size(), width_, height_, tick.frames[0].t)});
        }
        continue;
      }
      render::Annotations notes = panels_[i].marks.update(*tick.worlds[i], tick.events[i], tick.frames[i]);
      notes.slowdown = (1.0 / speed_) * (tick.slow ? clock_.effective_slowmo : 1.0);
      pf.notes.push_back(std::move(notes));
      if (!plan_.path.empty()) {
        pf.views.push_back(
            {path_view(plan_, panels_[i], i, panels_.size(), width_, height_, tick.frames[i].t)});
      }
      freeze = freezes(i, tick.frames[i], tick.events[i]) || freeze;
    }
    // The user's notes due at this time, in every panel.
    for (auto& n : pf.notes)
      for (const auto& note : plan_.notes)
        if (tick.frames[0].t >= note.t0 - 1e-9 && tick.frames[0].t <= note.t1 + 1e-9)
          n.texts.push_back({static_cast<float>(note.x), static_cast<float>(note.y), note.text});
    last_t = tick.frames[0].t;
    slow_frames += tick.slow;
    sim_seconds += since(t0_);
    if (freeze) {
      // A freeze at a clog shows its whole arch: where no view of a panel has every member whole (a camera on
      // a window or a grain, a glide half-way), the view showing most of it widens until it does.
      show_arches(pf);
      // Hold this picture for the freeze's seconds of video (the frame itself is the first of them).
      const long copies = plan_.freeze.copies(clock_.video_fps);
      for (auto& n : pf.notes)
        if (n.caption.empty()) n.caption = plan_.freeze.caption();
      for (long c = 0; c < copies && open_; ++c) open_ = pipeline_.push(PipelineFrame(pf));
      frozen_frames += copies;
    }
    if (open_) open_ = pipeline_.push(std::move(pf));
    t0_ = Clock::now();
  }
  bool wants_forces() const override {
    return true;
  }  // the trajectory keeps them, force colouring shows them
  bool done() const override { return !open_; }
  double last_t = 0, sim_seconds = 0;
  long slow_frames = 0, frozen_frames = 0;
  long widened_freezes = 0;  // freezes whose view widened to show the whole arch

 private:
  void show_arches(PipelineFrame& pf) {
    for (size_t i = 0; i < panels_.size(); ++i) {
      if (i >= pf.frames.size() || panels_[i].replay) continue;
      const core::Frame& f = pf.frames[i];
      if (f.arch.empty()) continue;
      std::vector<core::Vec2> centres;
      std::vector<double> radii;
      for (int id : f.arch) {
        const core::Particle& p = f.particles[static_cast<size_t>(id)];
        centres.push_back({p.x, p.y});
        radii.push_back(p.radius * core::polygon_extent(p.sides));
      }
      const std::vector<render::View>& views = i < pf.views.size() ? pf.views[i] : panels_[i].views;
      size_t best = 0;
      long best_n = -1;
      bool whole = false;
      for (size_t k = 0; k < views.size() && !whole; ++k) {
        long n = 0;
        for (size_t m = 0; m < centres.size(); ++m)
          n += render::shows_disks(views[k], {centres[m]}, {radii[m]});
        whole = n == static_cast<long>(centres.size());
        if (n > best_n) best = k, best_n = n;
      }
      if (whole || views.empty()) continue;
      while (pf.views.size() <= i) pf.views.push_back(panels_[pf.views.size()].views);
      pf.views[i][best] =
          render::widened_to_show(pf.views[i][best], centres, radii, 0.5 * panels_[i].geo.grain_diameter);
      ++widened_freezes;
    }
  }
  // Whether a panel's frame is a freeze's event, as its steps reported it: a clog opened since the previous
  // frame, or the rule falls due before the next frame (the last frame before it fires) with an arch shown.
  bool freezes(size_t panel, const core::Frame& f, const core::StepEvents& e) {
    if (last_.size() <= panel) last_.resize(panel + 1);
    const bool fires =
        plan_.freeze && render::freeze_fires(plan_.freeze, last_[panel] ? &*last_[panel] : nullptr, f,
                                             e.rule_due_in > 0 && e.rule_due_in <= clock_.frame_interval);
    last_[panel] = f;
    return fires;
  }
  std::vector<std::optional<core::Frame>> last_;  // each panel's previous frame (the freeze rule compares)
  FramePipeline& pipeline_;
  std::vector<Panel>& panels_;
  const FrameClock& clock_;
  const Plan& plan_;
  double speed_;
  int width_, height_;
  Clock::time_point t0_;
  bool open_ = true;
};

// The facts each panel's metadata carries about the recording.
io::Facts recording_facts(const RecordOptions& o, const Plan& plan, const Panel& p, const sim::Silo& h,
                          const Stages& st, long encoded, long slow_frames, long frozen_frames,
                          size_t n_panels, bool interrupted_run, const std::string& gl_renderer, double wall,
                          const fs::path& movie_path) {
  const double per = 1e3 / std::max(1L, encoded);
  io::Facts facts = {{"movie", o.no_movie ? std::string() : movie_path.filename().string()},
                     {"frames", encoded},
                     {"trajectory", io::run_file::kTrajectory},
                     {"trajectory_bytes_per_frame",
                      io::TrajectoryWriter::frame_bytes(static_cast<std::uint32_t>(h.particle_count()))},
                     {"size", std::to_string(plan.video.width) + "x" + std::to_string(plan.video.height)},
                     {"fps", o.fps},
                     {"steps_per_frame", plan.clock.steps},
                     {"frame_interval_s", plan.clock.frame_interval},
                     {"video_fps", plan.clock.video_fps},
                     {"slowmo_effective", plan.clock.effective_slowmo},
                     {"speed_sim_s_per_video_s", o.speed, 6},
                     {"slowmo", o.slowmo, 6},
                     {"slowmo_frames", slow_frames},
                     {"camera", o.camera},
                     {"camera_path", o.camera_path},
                     {"freeze", o.freeze},
                     {"frozen_frames", frozen_frames},
                     {"color_scale_min", plan.style.color_min, 6},
                     {"color_scale_max", render::color_scale_max(plan.style), 6},
                     {"color_scale", plan.style.color == render::ColorMode::Displacement &&
                                             !(plan.style.displacement_max > 0)
                                         ? "each frame's largest"
                                         : "fixed"},
                     {"crf", o.crf},
                     {"preset", o.preset},
                     {"png_every", o.png_every},
                     {"panels", n_panels},
                     {"panel_label", p.label},
                     {"interrupted", interrupted_run},
                     {"simulated_s", h.time(), 6},
                     {"gl_renderer", gl_renderer},
                     {"wall_s", wall, 6},
                     {"ms_per_frame_sim", st.sim * per, 6},
                     {"ms_per_frame_draw", st.draw * per, 6},
                     {"ms_per_frame_readback", st.readback * per, 6},
                     {"ms_per_frame_convert", st.convert * per, 6},
                     {"ms_per_frame_encode", st.encode * per, 6},
                     {"ms_per_frame_png", st.png * per, 6}};
  for (auto& f : o.track.facts(plan.style)) facts.push_back(std::move(f));
  return facts;
}

// Each panel's events, measurements and metadata (with the recording's facts); for a comparison, the whole's
// metadata too. Returns each panel's measurements.
std::vector<analysis::Measurements> write_recording_outputs(
    const RecordOptions& o, const Plan& plan, const std::vector<Panel>& panels, const Session& session,
    const io::OutputDir& dir, const io::RunInfo& info, const Stages& st, long encoded, long slow_frames,
    long frozen_frames, bool was_interrupted, const std::string& gl_renderer, double wall,
    const fs::path& movie_path) {
  const size_t n_panels = panels.size();
  std::vector<analysis::Measurements> ms;
  for (size_t k = 0; k < n_panels; ++k) {
    if (panels[k].replay) continue;  // a played-back run has its own directory already
    const sim::Silo& h = session.world(k);
    const double analysed = was_interrupted ? std::max(h.time(), 1e-9) : panels[k].model.scene.duration;
    io::RunInfo pinfo = info;
    pinfo.facts = recording_facts(o, plan, panels[k], h, st, encoded, slow_frames, frozen_frames, n_panels,
                                  was_interrupted, gl_renderer, wall, movie_path);
    Look look = plan.look;
    look.style.species_colors = look.species_colors = panels[k].odata.species_colors;
    pinfo.look = o.looks.facts(look);
    ms.push_back(write_run_outputs(dir.file(panels[k].subdir), h, analysed, pinfo));
  }
  if (n_panels > 1) {
    // The comparison as a whole: the base scene, and which panel is which (each panelK/ repeats its own run).
    io::RunInfo cinfo = info;
    std::vector<std::string> labels;
    for (const auto& p : panels) labels.push_back(p.label);
    cinfo.facts = {{"movie", o.no_movie ? std::string() : movie_path.filename().string()},
                   {"frames", encoded},
                   {"panels", n_panels},
                   {"panel_labels", labels},
                   {"interrupted", was_interrupted},
                   {"simulated_s", session.world(0).time(), 6},
                   {"wall_s", wall, 6}};
    io::write_file_atomic(dir.file(io::run_file::kMetadata),
                          "# a comparison movie: each panelK/ holds one panel's run\n" +
                              io::metadata_toml(panels.front().model, cinfo));
  }
  return ms;
}

// recordings/NAME, recordings/NAME.mp4 or recordings/NAME/: the recording's directory, NAME.
fs::path recording_base(const std::string& out) {
  fs::path base = out;
  if (base.extension() == ".mp4") base.replace_extension();
  if (base.filename().empty()) base = base.parent_path();  // recordings/NAME/ names NAME
  if (base.filename().empty() || base.filename() == "." || base.filename() == "..")
    throw core::InputError("--out " + out + ": expected recordings/NAME");
  return base;
}

// What the pictures could not do as asked, said once at the end.
void print_picture_notes(long covered, long encoded, long widened_freezes) {
  if (covered > 0)
    std::fprintf(
        stderr,
        "siloscope: in %ld of %ld pictures a box of the overlay found no clear space and covers part "
        "of the container or its grains: a larger --size, a smaller --font-scale, fewer elements "
        "(--overlay) or --overlay-at would give them room\n",
        covered, encoded);
  if (widened_freezes > 0)
    std::fprintf(stderr,
                 "siloscope: at %ld freeze%s the camera had part of the arch out of view: the held picture "
                 "widens to show it whole\n",
                 widened_freezes, widened_freezes == 1 ? "" : "s");
}

int record_movie(const RecordOptions& o) {
  std::vector<Panel> panels = make_panels(o);
  const Plan plan = plan_recording(o, panels);
  const core::Scene& scene = panels.front().model.scene;
  const size_t n_panels = panels.size();

  const fs::path base = recording_base(o.out);
  fs::path movie_path = base;
  movie_path += ".mp4";
  // The directory's lock also guards NAME.mp4: one writer for both.
  io::OutputDir dir(base.string(), o.force, io::DirKind::Run);
  if (!o.no_movie) {
    io::check_destination(movie_path, o.force, "movie", io::OutputKind::Movie);
    io::remove_dead_leftovers(base, {movie_path.filename().string() + ".partial"});
  }
  if (o.png_every > 0) fs::create_directory(dir.file("frames"));
  for (const auto& p : panels)
    if (!p.subdir.empty()) fs::create_directory(dir.file(p.subdir));
  io::RunInfo info;
  info.command = command_line();

  // --- the back half: render and encode stages on threads of their own (app/pipeline.h) ---
  Stages st;
  record::VideoSettings video = plan.video;
  std::unique_ptr<record::Mp4Writer> mp4;
  if (!o.no_movie) {
    video.comment = io::metadata_toml(panels.front().model, info);
    mp4 = std::make_unique<record::Mp4Writer>(movie_path, video);
  }
  std::vector<PanelLayout> layouts;
  for (const auto& p : panels) layouts.push_back({&p.geo, &p.views, &p.odata});
  PipelineOutputs outputs;
  outputs.mp4 = mp4.get();
  outputs.png_every = o.png_every;
  if (o.png_every > 0) outputs.png_dir = dir.file("frames");
  FramePipeline pipeline(std::move(layouts), plan.style, plan.overlay, video.width, video.height, outputs,
                         o.quiet);

  // --- the front half: one session steps every panel's world on one clock ---
  Progress progress("record", scene.duration, !o.quiet, false);
  auto wall0 = Clock::now();
  bool completed = false;
  std::exception_ptr sim_error;
  std::unique_ptr<Session> session;
  std::vector<std::unique_ptr<TrajectorySink>> trajectories;
  std::unique_ptr<MovieSink> movie;
  std::unique_ptr<HindsightSink> hindsight;
  try {
    std::vector<core::Model> scenes;
    for (const auto& p : panels)
      if (!p.replay) scenes.push_back(p.model);
    session = std::make_unique<Session>(scenes);
    std::vector<Sink*> sinks;
    for (size_t k = 0; k < session->size(); ++k) {
      const std::string meta =
          n_panels == 1 && !video.comment.empty() ? video.comment : io::metadata_toml(panels[k].model, info);
      trajectories.push_back(std::make_unique<TrajectorySink>(
          dir.file(panels[k].subdir + io::run_file::kTrajectory),
          trajectory_info(session->world(k), plan.clock.frame_interval, meta), k));
      sinks.push_back(trajectories.back().get());
    }
    movie = std::make_unique<MovieSink>(pipeline, panels, plan, o.speed, video.width);
    sinks.push_back(movie.get());
    // The movie and the trajectories see each arch from its formation: frames reach them clog_min_gap late.
    double latency = 0;
    for (const auto& p : panels) latency = std::max(latency, p.model.scene.clog_min_gap);
    hindsight = std::make_unique<HindsightSink>(sinks, latency + plan.clock.frame_interval);
    completed = session->run(scene.duration, plan.clock, {hindsight.get()}, interrupted, [&](double t) {
      char extra[96];
      std::snprintf(extra, sizeof extra, "t = %.1f s, %zu exits", t, session->world(0).events().exits.size());
      progress.update(t, extra);
    });
    // The run's end closes open clogs (the trajectories keep them); the frames held for hindsight go on.
    session->finish({hindsight.get()});
  } catch (...) {
    sim_error = std::current_exception();
  }
  std::exception_ptr stage_error;
  try {
    pipeline.finish();
  } catch (...) {
    stage_error = std::current_exception();
  }
  progress.finish();
  if (sim_error) std::rethrow_exception(sim_error);
  if (stage_error) std::rethrow_exception(stage_error);
  const bool was_interrupted = !completed && interrupted();
  const long encoded = pipeline.frames_written();
  st.sim = movie->sim_seconds;
  st.draw = pipeline.draw_seconds();
  st.readback = pipeline.readback_seconds();
  st.png = pipeline.png_seconds();
  const double wall = since(wall0);

  // --- finish: the run's end closes open clogs (the trajectories keep them), the movie goes into place
  // first, then the directory that describes it ---
  for (auto& t : trajectories) t->close();
  if (mp4) {
    mp4->finish();
    st.convert = mp4->convert_seconds();
    st.encode = mp4->encode_seconds();
  }
  const std::vector<analysis::Measurements> ms = write_recording_outputs(
      o, plan, panels, *session, dir, info, st, encoded, movie->slow_frames, movie->frozen_frames,
      was_interrupted, pipeline.gl_renderer(), wall, movie_path);
  dir.commit();
  if (!o.quiet)
    print_recording(o, st, encoded, movie->last_t, wall, was_interrupted, pipeline.gl_renderer(), panels,
                    *session, ms, movie_path, base);
  if (!o.quiet) print_picture_notes(pipeline.covered_frames(), encoded, movie->widened_freezes);
  return was_interrupted ? 130 : 0;
}
}  // namespace

void define_record_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<RecordOptions>();
  CLI::App* cmd = &command;
  o->scene.add_to(*cmd);
  cmd->add_option("--out", o->out, "recordings/NAME: writes NAME.mp4 and the directory NAME/")->required();
  cmd->add_option("--size", o->size, "image size WIDTHxHEIGHT in pixels (even for movies)")
      ->capture_default_str();
  cmd->add_option("--fps", o->fps, "video frames per second")
      ->check(whole_number(1, 240))
      ->capture_default_str();
  cmd->add_option("--speed", o->speed, "simulated seconds per video second (0.25 = 4x slow motion)")
      ->capture_default_str();
  cmd->add_option(
         "--slowmo", o->slowmo,
         "slow the video this many times around each long-lasting arch's removal (0.5 s before to 1 s after)")
      ->capture_default_str();
  auto* camera =
      cmd->add_option("--camera", o->camera,
                      "hopper, outlet, split, window:X0,Y0,X1,Y1 (metres), arch:K (the K-th clog's arch, "
                      "whole) or grain:ID (a grain followed); arch and grain are found by simulating ahead")
          ->capture_default_str();
  cmd->add_option(
         "--camera-path", o->camera_path,
         "a camera move: key frames T:CAMERA,... (simulated s; hopper, outlet, window:X0,Y0,X1,Y1, arch:K or "
         "grain:ID), e.g. 0:hopper,3:outlet,8:arch:1,10:hopper; eased between keys, still before and after "
         "(a grain's key follows it); not with --camera")
      ->excludes(camera);
  cmd->add_option(
      "--freeze", o->freeze,
      "hold the picture at each event: clog:SECONDS (a clog has formed) or rule:SECONDS (the last "
      "frame before the clog rule fires), SECONDS of video");
  cmd->add_option("--png-every", o->png_every, "also write every Nth frame as PNG into NAME/frames (0: none)")
      ->check(whole_number(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--crf", o->crf, "H.264 quality, 0 (lossless) to 51")
      ->check(whole_number(0, 51))
      ->capture_default_str();
  cmd->add_option("--preset", o->preset, "x264 preset, ultrafast .. veryslow")->capture_default_str();
  o->looks.add_to(*cmd);
  o->track.add_to(*cmd);
  cmd->add_flag("--no-movie", o->no_movie, "PNG frames only");
  cmd->add_flag("--force", o->force, "replace existing outputs");
  cmd->add_option("--panel-title", o->panel_titles,
                  "each panel's title, a heading in large type above it, in order (repeatable, one per "
                  "panel; default: the --compare keys, the scene's name, or the run's)");
  cmd->add_option("--compare-run", o->compare_run,
                  "a recorded or imported run (an experiment from siloscope import) played back beside the "
                  "simulation, on one clock from the opening; its container must be the scene's")
      ->check(CLI::ExistingPath);
  cmd->add_option(
      "--compare", o->compare,
      "a comparison panel: the scene with key=value[,key=value...] (repeatable; 2-4 panels side by side, "
      "one clock; with a single --compare the base scene is the first panel)");
  cmd->add_option("--compare-scene", o->compare_scene,
                  "a comparison panel from another scene file (repeatable)");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return record_movie(*o); }; });
}

}  // namespace app
