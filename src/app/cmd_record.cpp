// siloscope record SCENE --out recordings/NAME: a discharge movie (NAME.mp4) and, in NAME/, the events, the
// measurements, the metadata and optional PNG frames. Three threads: the simulation produces Frames, the
// renderer turns them into Images (OSMesa), the encoder writes them; bounded queues keep memory flat.
#include <cmath>
#include <cstdio>
#include <exception>
#include <thread>

#include "analysis/measure.h"
#include "core/format.h"
#include "analysis/tidy.h"
#include "app/common.h"
#include "app/queue.h"
#include "core/error.h"
#include "io/events_csv.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/trajectory.h"
#include "record/mp4.h"
#include "record/png.h"
#include "render/camera.h"
#include "render/context.h"
#include "render/overlay.h"
#include "render/renderer.h"
#include "render/target.h"
#include "sim/hopper.h"

namespace app {

namespace {
std::string num6(double v) { return core::format_g(v, 6); }
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct RecordOptions {
  SceneOptions scene;
  std::string out, size = "1920x1080", camera = "split", palette = "paper", color = "species", overlay = "all";
  int fps = 30, crf = 20, png_every = 0;
  double speed = 1.0, slowmo = 1.0;
  double color_max = 0;  // top of the speed (m/s) or force (N) colour scale; 0: the fixed default
  std::string preset = "veryfast";
  bool transparent = false, no_movie = false, force = false, quiet = false;
};

struct Stages {
  double sim = 0, draw = 0, readback = 0, convert = 0, encode = 0, png = 0;
};



double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

void EventMarks::update(const sim::Hopper& h, core::Frame& f) {
  const auto& arches = h.events().arches;
  const auto& clogs = h.events().clogs;
  if (arches.size() > arches_seen_) {
    const core::ArchEvent& a = arches.back();
    rings_.clear();
    for (size_t k = 0; k < a.ids.size() && k < a.x.size(); ++k)
      rings_.push_back({a.x[k], a.y[k], static_cast<float>(h.radii()[static_cast<size_t>(a.ids[k])])});
    char text[96];
    std::snprintf(text, sizeof text, "arch removed (%.0f s rule): %zu disks", h.scene().clog_timeout, a.ids.size());
    start(text, a.t, true);
    arches_seen_ = arches.size();
  }
  if (clogs.size() > clogs_seen_) {
    const core::ClogEvent& c = clogs.back();
    if (c.ended_by == core::ClogEnd::Vibration) {
      char text[96];
      std::snprintf(text, sizeof text, "clog broken by vibration after %.1f s", c.end - c.start);
      start(text, c.end, false);
    }
    clogs_seen_ = clogs.size();
  }
  if (frames_left_ > 0 || f.t - since_ < kMinSeconds) {
    f.marks.caption = caption_;
    f.marks.removed = rings_;
    if (frames_left_ > 0) --frames_left_;
  } else {
    rings_.clear();
  }
}

void EventMarks::start(const std::string& caption, double t, bool keep_rings) {
  caption_ = caption;
  since_ = t;
  frames_left_ = kMinFrames;
  if (!keep_rings) rings_.clear();
}

FrameClock make_frame_clock(double dt, int fps, double speed, double slowmo) {
  FrameClock c;
  const double wanted = speed / fps;  // simulated seconds per video frame asked for
  const double exact = wanted / dt;
  if (exact < 0.5)
    throw core::InputError("--speed " + num6(speed) + " at --fps " + std::to_string(fps) + " asks for a frame every " +
                           num6(wanted) + " s of simulation, less than one time step (dt = " + num6(dt) +
                           " s); use --speed >= " + num6(fps * dt) + " or a lower --fps");
  c.steps = std::max(1L, std::lround(exact));
  // A whole number of steps per frame; the rate written into the movie follows it (33 steps of 1 ms at 30 fps:
  // 1000/33 = 30.30 frames per video second), so video time stays equal to simulated time / speed.
  if (std::abs(c.steps - exact) / exact > 0.05)
    throw core::InputError("--speed " + num6(speed) + " at --fps " + std::to_string(fps) + " needs " + num6(exact) +
                           " time steps per frame; the nearest whole number (" + std::to_string(c.steps) +
                           ") would change the frame rate by more than 5%; use --speed " +
                           num6(c.steps * dt * fps) + " or " + num6(std::max(1L, c.steps + (exact > c.steps ? 1 : -1)) * dt * fps));
  c.slow_steps = std::max(1L, std::lround(c.steps / slowmo));
  if (slowmo > 1 && c.steps / slowmo < 0.5)
    throw core::InputError("--slowmo " + num6(slowmo) + " would need less than one time step per frame (" +
                           std::to_string(c.steps) + " steps per frame at this --speed); the most is " +
                           std::to_string(2 * c.steps));
  c.frame_interval = c.steps * dt;
  c.video_fps = speed / c.frame_interval;
  c.effective_slowmo = static_cast<double>(c.steps) / static_cast<double>(c.slow_steps);
  return c;
}

namespace {

int record_movie(const RecordOptions& o) {
  // --- everything the user typed is checked before any work starts ---
  core::Scene scene = o.scene.load();
  record::VideoSettings video;
  render::parse_size(o.size, "--size", video.width, video.height);
  video.fps = o.fps;
  video.crf = o.crf;
  video.preset = o.preset;
  if (!o.no_movie) record::validate(video);
  if (!(o.speed > 0) || o.speed > 1000) throw core::InputError("--speed " + num6(o.speed) + ": allowed range is (0, 1000] simulated s per video s");
  if (!(o.slowmo >= 1) || o.slowmo > 100) throw core::InputError("--slowmo " + num6(o.slowmo) + ": allowed range is 1 (off) to 100");
  const FrameClock clock = make_frame_clock(scene.dt, o.fps, o.speed, o.slowmo);
  video.frame_rate = clock.video_fps;
  if (o.png_every < 0) throw core::InputError("--png-every " + std::to_string(o.png_every) + ": must be >= 0");
  if (o.no_movie && o.png_every == 0) throw core::InputError("--no-movie without --png-every would record nothing");
  if (o.fps < 1 || o.fps > 240) throw core::InputError("--fps " + std::to_string(o.fps) + ": allowed range is 1 to 240");
  render::Style style;
  style.palette = render::parse_palette(o.palette);
  style.color = render::parse_color_mode(o.color);
  style.transparent = o.transparent;
  if (o.color_max < 0 || !std::isfinite(o.color_max))
    throw core::InputError("--color-max " + num6(o.color_max) + ": expected a positive number (m/s or N)");
  if (o.color_max > 0) {
    if (style.color == render::ColorMode::Species)
      throw core::InputError("--color-max applies to --color speed or force, not species");
    (style.color == render::ColorMode::Speed ? style.speed_max : style.force_max) = o.color_max;
  }
  const render::OverlayOptions overlay = render::parse_overlay(o.overlay);
  const core::Geometry geo = core::make_geometry(scene);
  const auto views = render::layout_views(o.camera, geo, video.width, video.height);

  fs::path base = o.out;
  if (base.extension() == ".mp4") base.replace_extension();
  if (base.filename().empty()) throw core::InputError("--out " + o.out + ": expected recordings/NAME");
  fs::path movie_path = base;
  movie_path += ".mp4";
  // The directory's lock also guards NAME.mp4: one writer for both.
  io::OutputDir dir(base, o.force);
  if (!o.no_movie) {
    io::check_destination(movie_path, o.force, "movie", io::OutputKind::Movie);
    io::remove_dead_leftovers(base, {movie_path.filename().string() + ".partial"});
  }
  if (o.png_every > 0) fs::create_directory(dir.file("frames"));

  const render::OverlayData odata = render::overlay_data_for(scene);

  io::RunInfo info;
  info.command = command_line();
  install_interrupt_handler();

  // --- the three stages ---
  BoundedQueue<core::Frame> frames(8);
  BoundedQueue<core::Image> images(4);
  std::exception_ptr render_error, encode_error;
  Stages st;
  std::string gl_renderer;
  long encoded = 0;
  std::unique_ptr<record::Mp4Writer> mp4;
  if (!o.no_movie) {
    video.comment = io::metadata_toml(scene, info);
    mp4 = std::make_unique<record::Mp4Writer>(movie_path, video);
  }

  std::thread render_thread([&] {
    try {
      render::OffscreenContext ctx;
      gl_renderer = ctx.description();
      if (!o.quiet) std::fprintf(stderr, "siloscope: OpenGL %s\n", gl_renderer.c_str());
      render::Renderer renderer;
      render::Overlay ov;
      render::Target target(video.width, video.height);
      core::Frame f;
      while (frames.pop(f)) {
        auto t0 = Clock::now();
        target.bind();
        renderer.draw(f, geo, views, style, video.width, video.height);
        ov.draw(f, odata, overlay, views, style, video.width, video.height);
        auto t1 = Clock::now();
        core::Image img;
        target.read(img, style.transparent);
        img.t = f.t;
        st.draw += std::chrono::duration<double>(t1 - t0).count();
        st.readback += since(t1);
        if (!images.push(std::move(img))) break;
      }
    } catch (...) {
      render_error = std::current_exception();
      frames.close();
    }
    images.close();
  });

  std::thread encode_thread([&] {
    try {
      core::Image img;
      while (images.pop(img)) {
        if (mp4) mp4->add(img);
        if (o.png_every > 0 && encoded % o.png_every == 0) {
          auto t0 = Clock::now();
          char name[32];
          std::snprintf(name, sizeof name, "frame_%06ld.png", encoded);
          record::write_png(dir.file("frames") / name, img);
          st.png += since(t0);
        }
        ++encoded;
      }
    } catch (...) {
      encode_error = std::current_exception();
      images.close();
      frames.close();
    }
  });

  // --- the simulation, on this thread ---
  Progress progress("record", scene.duration, !o.quiet);
  double last_t = 0;
  long slow_frames = 0;
  auto wall0 = Clock::now();
  bool was_interrupted = false;
  std::exception_ptr sim_error;
  std::unique_ptr<sim::Hopper> hopper;
  std::unique_ptr<io::TrajectoryWriter> trajectory;
  try {
    auto t0 = Clock::now();
    hopper = std::make_unique<sim::Hopper>(scene);
    io::TrajectoryInfo tinfo = trajectory_info(*hopper, clock.frame_interval, video.comment.empty() ? io::metadata_toml(scene, info) : video.comment);
    trajectory = std::make_unique<io::TrajectoryWriter>(dir.file("trajectory.sstraj"), tinfo);
    // Frames every clock.steps time steps, or every clock.slow_steps around a long-lasting arch's removal (from
    // 0.5 s before the clog_timeout rule fires to 1 s after), both known from the current state. Whole steps:
    // every frame shows the state at an exact multiple of dt, and the trajectory and the MP4 carry that time.
    long next_steps = 0;
    // Events on screen: the last rule removal's members stay ringed, and a caption says what happened, for at
    // least 10 frames and at least 0.7 s of simulated time.
    EventMarks marks;
    for (long k = 0; hopper->time() <= scene.duration - 0.5 * clock.frame_interval + 1e-9 || k == 0; ++k) {
      for (long s = 0; s < next_steps; ++s) hopper->step();
      if (k > 0 && hopper->time() > scene.duration - 0.5 * clock.frame_interval + 1e-9) break;
      // Forces are summed only when they are shown or kept (the trajectory keeps them).
      core::Frame f = hopper->frame(true, true);
      const auto& arches = hopper->events().arches;
      const bool slow = o.slowmo > 1 && (f.since_last_exit >= scene.clog_timeout - 0.5 ||
                                         (!arches.empty() && f.t - arches.back().t < 1.0));
      next_steps = slow ? clock.slow_steps : clock.steps;
      marks.update(*hopper, f);
      f.marks.slowdown = (1.0 / o.speed) * (slow ? clock.effective_slowmo : 1.0);
      last_t = f.t;
      slow_frames += slow;
      trajectory->add(f, static_cast<int>(arches.size()));
      st.sim += since(t0);
      if (!frames.push(std::move(f))) break;
      t0 = Clock::now();
      if (interrupted()) {
        was_interrupted = true;
        break;
      }
      char extra[96];
      std::snprintf(extra, sizeof extra, "t = %.1f s, %ld frames, %zu exits", hopper->time(), k + 1,
                    hopper->events().exits.size());
      progress.update(hopper->time(), extra);
    }
  } catch (...) {
    sim_error = std::current_exception();
  }
  frames.close();
  render_thread.join();
  encode_thread.join();
  progress.finish();
  if (sim_error) std::rethrow_exception(sim_error);
  if (render_error) std::rethrow_exception(render_error);
  if (encode_error) std::rethrow_exception(encode_error);
  const double wall = since(wall0);

  // --- finish: movie into place first, then the directory that describes it ---
  if (trajectory) trajectory->close();
  if (mp4) {
    mp4->finish();
    st.convert = mp4->convert_seconds();
    st.encode = mp4->encode_seconds();
  }
  hopper->finish();
  const double shown = last_t;  // simulated seconds shown
  const double analysed = was_interrupted ? std::max(hopper->time(), 1e-9) : scene.duration;
  analysis::Measurements m = analysis::measure(hopper->events(), analysed);
  m.health_warnings = hopper->health_warnings();
  m.airborne_fraction = hopper->airborne().mean();
  m.ballistic = hopper->ballistic();
  info.health = health_facts(*hopper);
  io::write_events(dir.file(""), hopper->events());
  io::write_file_atomic(dir.file("summary.csv"), analysis::summary_header() + "\n" + analysis::summary_row(scene, m) + "\n");
  io::write_file_atomic(dir.file("survival.csv"), analysis::survival_csv(scene, hopper->events().exits));
  const double per = 1e3 / std::max(1L, encoded);
  info.facts = {{"movie", core::toml_string((o.no_movie ? std::string() : movie_path.filename().string()))},
                {"frames", std::to_string(encoded)},
                {"trajectory", "\"trajectory.sstraj\""},
                {"trajectory_bytes_per_frame", std::to_string(io::TrajectoryWriter::frame_bytes(static_cast<std::uint32_t>(scene.n_total)))},
                {"size", core::toml_string(std::to_string(video.width) + "x" + std::to_string(video.height))},
                {"fps", std::to_string(o.fps)},
                {"steps_per_frame", std::to_string(clock.steps)},
                {"frame_interval_s", core::format_toml_float(clock.frame_interval)},
                {"video_fps", core::format_toml_float(clock.video_fps)},
                {"slowmo_effective", core::format_toml_float(clock.effective_slowmo)},
                {"speed_sim_s_per_video_s", num6(o.speed)},
                {"slowmo", num6(o.slowmo)},
                {"slowmo_frames", std::to_string(slow_frames)},
                {"camera", core::toml_string(o.camera)},
                {"palette", core::toml_string(o.palette)},
                {"color", core::toml_string(o.color)},
                {"color_scale_max", core::format_toml_float(style.color == render::ColorMode::Speed ? style.speed_max
                                                                                                  : style.force_max)},
                {"overlay", core::toml_string(o.overlay)},
                {"crf", std::to_string(o.crf)},
                {"preset", core::toml_string(o.preset)},
                {"png_every", std::to_string(o.png_every)},
                {"interrupted", was_interrupted ? "true" : "false"},
                {"simulated_s", num6(hopper->time())},
                {"gl_renderer", core::toml_string(gl_renderer)},
                {"wall_s", num6(wall)},
                {"ms_per_frame_sim", num6(st.sim * per)},
                {"ms_per_frame_draw", num6(st.draw * per)},
                {"ms_per_frame_readback", num6(st.readback * per)},
                {"ms_per_frame_convert", num6(st.convert * per)},
                {"ms_per_frame_encode", num6(st.encode * per)},
                {"ms_per_frame_png", num6(st.png * per)}};
  io::write_file_atomic(dir.file("metadata.toml"), io::metadata_toml(scene, info));
  dir.commit();

  if (!o.quiet) {
    std::printf("renderer    %s\n", gl_renderer.c_str());
    std::printf("recorded    %ld frames (%.1f s of discharge%s) in %.1f s wall: %.2fx real time, %.1f frames/s\n",
                encoded, shown, was_interrupted ? ", interrupted" : "", wall, shown / wall, encoded / wall);
    std::printf("per frame   sim %.1f ms, draw %.1f ms, readback %.1f ms, convert %.1f ms, encode %.1f ms, png %.1f ms"
                " (stages overlap)\n",
                st.sim * per, st.draw * per, st.readback * per, st.convert * per, st.encode * per, st.png * per);
    std::printf("%s", analysis::summary_text(m).c_str());
    if (!o.no_movie) std::printf("movie       %s\n", movie_path.c_str());
    std::printf("run data    %s/\n", base.c_str());
  }
  return was_interrupted ? 130 : 0;
}
}  // namespace

void add_record_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RecordOptions>();
  auto* cmd = app.add_subcommand("record", "film a discharge: an MP4 movie, optional PNG frames, events and metadata");
  cmd->set_version_flag("--version", io::version_string());
  o->scene.add_to(*cmd);
  cmd->add_option("--out", o->out, "recordings/NAME: writes NAME.mp4 and the directory NAME/")->required();
  cmd->add_option("--size", o->size, "image size WIDTHxHEIGHT in pixels (even for movies)")->capture_default_str();
  cmd->add_option("--fps", o->fps, "video frames per second")->check(whole_number(1, 240))->capture_default_str();
  cmd->add_option("--speed", o->speed, "simulated seconds per video second (0.25 = 4x slow motion)")->capture_default_str();
  cmd->add_option("--slowmo", o->slowmo,
                  "slow the video this many times around each long-lasting arch's removal (0.5 s before to 1 s after)")
      ->capture_default_str();
  cmd->add_option("--camera", o->camera, "hopper, outlet, split or window:X0,Y0,X1,Y1 (metres)")->capture_default_str();
  cmd->add_option("--png-every", o->png_every, "also write every Nth frame as PNG into NAME/frames (0: none)")->check(whole_number(0, 1000000))->capture_default_str();
  cmd->add_option("--crf", o->crf, "H.264 quality, 0 (lossless) to 51")->check(whole_number(0, 51))->capture_default_str();
  cmd->add_option("--preset", o->preset, "x264 preset, ultrafast .. veryslow")->capture_default_str();
  cmd->add_option("--palette", o->palette, "paper (red/blue) or colorblind (Okabe-Ito)")->capture_default_str();
  cmd->add_option("--color", o->color, "colour disks by species, speed or force")->capture_default_str();
  cmd->add_option("--overlay", o->overlay, "all, none, or a list of time,counts,rate,timer,arch,legend,scale")->capture_default_str();
  cmd->add_flag("--transparent", o->transparent, "transparent background in PNG frames");
  cmd->add_flag("--no-movie", o->no_movie, "PNG frames only");
  cmd->add_flag("--force", o->force, "replace existing outputs");
  cmd->add_option("--color-max", o->color_max,
                  "top of the colour scale for --color speed (m/s) or force (N); default: the fixed scale "
                  "(0.5 m/s, 20 N), the same in every movie");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return record_movie(*o); }; });
}

}  // namespace app
