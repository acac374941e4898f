// siloscope detect FRAMES_OR_VIDEO --out TRACKS.csv: the disks of a film located in every frame and linked
// into tracks (vision/detect.h), written as the CSV `import` reads, with TRACKS.meta.toml beside it (the
// calibration, the settings, the counts, the version). A siloscope movie calibrates itself from its
// recording's metadata; a lab film takes --scale and --origin, or two marked points.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/services/cli.h"
#include "app/services/lab.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "io/output.h"
#include "lab/tracks.h"
#include "record/mp4.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct DetectCliOptions {
  std::string input, geometry, out, origin, points, frames, lens, pattern = "9x6", rectified;
  std::vector<std::string> overrides;
  double scale = 0, fps = 0, rotation = 0;
  double band = 0.25, edge = 60, max_step = 0.8;
  int memory = 2;
  bool bright = false, force = false, quiet = false;
};

constexpr const char* kHeader = "frame,particle,x,y,r,t,species";

// The numeric options in their ranges (before any work).
void check_options(const DetectCliOptions& o) {
  if (!(o.band > 0 && o.band < 0.6))
    throw core::InputError("--radius-band " + core::format_g(o.band) + ": expected 0 to 0.6");
  if (!(o.edge > 0 && o.edge < 1000))
    throw core::InputError("--edge " + core::format_g(o.edge) + ": expected 1 to 1000");
  if (!(o.max_step > 0 && o.max_step <= 5))
    throw core::InputError("--max-step " + core::format_g(o.max_step) + ": expected 0 to 5 radii");
  if (o.memory < 0 || o.memory > 100)
    throw core::InputError("--memory " + std::to_string(o.memory) + ": expected 0 to 100 frames");
  if (o.scale < 0 || !std::isfinite(o.scale))
    throw core::InputError("--scale " + core::format_g(o.scale) + ": expected metres per pixel, > 0");
  if (o.fps < 0 || !std::isfinite(o.fps))
    throw core::InputError("--fps " + core::format_g(o.fps) + ": expected > 0");
  if (o.rotation != 0 && !(o.scale > 0))
    throw core::InputError("--rotation goes with --scale and --origin (--points finds the rotation itself)");
}

// What detect found, on the terminal; a warning when the video ended early.
void print_detect(const DetectCliOptions& o, const vision::FrameSource& source, const DetectStats& st,
                  const Calibration& cal, const fs::path& out) {
  if (source.ended_early())
    std::fprintf(
        stderr,
        "siloscope: warning: %s ended after %ld of the %ld frames its header announces (cut short?); "
        "the tracks stop there\n",
        o.input.c_str(), source.frames_read(), source.count());
  if (o.quiet) return;
  std::printf("calibration %s: %s mm a pixel, the outlet's centre at (%s, %s) px, turned %s deg",
              cal.from.c_str(), core::format_g(1e3 * cal.scale, 4).c_str(),
              core::format_g(cal.origin_x, 6).c_str(), core::format_g(cal.origin_y, 6).c_str(),
              core::format_g(cal.rotation * 180 / M_PI, 3).c_str());
  if (cal.residual > 1e-6)
    std::printf(" (the points lie %s mm from the fit)", core::format_g(1e3 * cal.residual, 3).c_str());
  std::printf("\n");
  if (!o.bright)
    std::printf(
        "disks       %s on a %s background (the first frame: %ld disks taken as dark, %ld as bright)\n",
        st.bright ? "bright" : "dark", st.bright ? "dark" : "light", st.first_as_dark, st.first_as_bright);
  if (st.species > 1)
    std::printf(
        "species     each track's, the likeliest for the median of its radii (spread %.1f%%; the scene's "
        "sizes leave %.2f%% of grains among another species' sizes)\n",
        100 * st.size_spread, 100 * st.size_error_rate);
  std::printf(
      "%ld frames, %ld disks (%.1f a frame; %ld outside the container or inside the obstacle dropped), %ld "
      "tracks, "
      "%.3f s a frame -> %s\n",
      st.frames, st.detections, static_cast<double>(st.detections) / std::max(1L, st.frames),
      st.dropped_outside, st.tracks, st.seconds / std::max(1L, st.frames), out.string().c_str());
}

// The [NAME] section of a calibration (and its lens, when present) in a metadata file.
std::string calibration_toml(const std::string& name, const Calibration& cal, const vision::Lens& lens) {
  std::string t = "\n[" + name + "]\nfrom = " + core::toml_string(cal.from) +
                  "\nscale_m_per_px = " + core::format_toml_float(cal.scale, 12) +
                  "\norigin_x_px = " + core::format_toml_float(cal.origin_x, 12) +
                  "\norigin_y_px = " + core::format_toml_float(cal.origin_y, 12) +
                  "\nrotation_deg = " + core::format_toml_float(cal.rotation * 180 / M_PI, 12) +
                  "\npoints_residual_m = " + core::format_toml_float(cal.residual, 6) +
                  "\nfps = " + core::format_toml_float(cal.fps, 12) + "\n";
  if (lens.present)
    t += "lens = " + core::toml_string(lens.from) + "  # chessboard pictures: x, y are ideal pixels" +
         "\nlens_views = " + std::to_string(lens.views) +
         "\nlens_rms_px = " + core::format_toml_float(lens.rms, 6) +
         "\nlens_focal_px = " + core::format_toml_float(lens.camera(0, 0), 12) +
         "\nlens_centre_x_px = " + core::format_toml_float(lens.camera(0, 2), 12) +
         "\nlens_centre_y_px = " + core::format_toml_float(lens.camera(1, 2), 12) +
         "\nlens_k1 = " + core::format_toml_float(lens.distortion[0], 12) +
         "\nlens_k2 = " + core::format_toml_float(lens.distortion[1], 12) + "\n";
  return t;
}

// --rectified: the film as the tracks see it, written frame by frame while detect reads it (app/services/
// lab.h's Rectifier). Its MP4 comment holds the metadata: the scene, the command, and the upright film's own
// calibration ([calibration]) beside the one it was made with ([rectified_from]).
class RectifiedFilm {
 public:
  RectifiedFilm(const fs::path& path, const DetectJob& job, const core::Model& model, int width, int height)
      : rect_(job.cal, job.lens, width, height) {
    record::VideoSettings v;
    v.width = rect_.width(), v.height = rect_.height();
    v.fps = std::clamp(static_cast<int>(std::lround(job.cal.fps)), 1, 240);
    v.frame_rate = job.cal.fps;
    v.crf = 18;
    io::RunInfo info;
    info.command = command_line();
    v.comment = io::metadata_toml(model, info) + calibration_toml("calibration", rect_.upright(), {}) +
                calibration_toml("rectified_from", job.cal, job.lens);
    mp4_ = std::make_unique<record::Mp4Writer>(path, v);
  }
  void add(const cv::Mat& frame) {
    rect_.apply(frame, image_);
    mp4_->add(image_);
  }
  void finish() { mp4_->finish(); }
  const Calibration& upright() const { return rect_.upright(); }

 private:
  Rectifier rect_;
  std::unique_ptr<record::Mp4Writer> mp4_;  // removes its partial file unless finished
  core::Image image_;
};

// The lens (from --lens), then the calibration of ideal pixels: --scale and --origin, marked points, or a
// siloscope movie's own (true: `model` is then its scene).
bool calibrate(const DetectCliOptions& o, DetectJob& job, core::Model& model) {
  if (!o.lens.empty()) {
    int cols = 0, rows = 0;
    char x = 0, extra = 0;
    if (std::sscanf(o.pattern.c_str(), "%d%c%d%c", &cols, &x, &rows, &extra) != 3 || x != 'x' || cols < 3 ||
        rows < 3 || cols > 100 || rows > 100)
      throw core::InputError(
          "--pattern '" + o.pattern +
          "': expected COLUMNSxROWS, the chessboard's inner corners (3 to 100 each, e.g. 9x6)");
    job.lens = vision::lens_from_chessboard(o.lens, cv::Size(cols, rows));
  }
  bool have_model = false;
  std::string why;
  if (o.scale > 0 || !o.origin.empty()) {
    if (!(o.scale > 0) || o.origin.empty())
      throw core::InputError(
          "--scale and --origin go together (metres per pixel, and the outlet centre's pixel X,Y)");
    job.cal.scale = o.scale;
    lab::parse_origin(o.origin, job.cal.origin_x, job.cal.origin_y);
    job.cal.rotation = rotation_radians(o.rotation);
    job.cal.from = "command line";
  } else if (!o.points.empty()) {
    job.cal = points_calibration(o.points, "--points", job.lens);
  } else if (!movie_calibration(o.input, job.cal, model, why)) {
    throw core::InputError(o.input + ": no calibration: give --scale and --origin, or --points (" +
                           "it is not a siloscope movie that calibrates itself: " + why + ")");
  } else {
    have_model = true;
  }
  return have_model;
}

// The container and its species (a siloscope movie's own scene, or --geometry), each species' radius in
// pixels at the calibration.
core::Model detect_geometry(const DetectCliOptions& o, DetectJob& job) {
  core::Model model;
  bool have_model = calibrate(o, job, model);
  if (!o.geometry.empty()) {
    core::Scene s = core::load_scene(scene_file(o.geometry));  // a file, or a preset's name
    core::apply_overrides(s, o.overrides);
    model = core::compile(s);
    have_model = true;
  }
  if (!have_model)
    throw core::InputError(
        "--geometry: needed for a film that is not a siloscope movie (the container and its species' sizes)");
  for (const core::SpeciesDef& sp : model.setup.species) {
    // Found as disks, polygons would come back as disks quietly: their outlines are not circles.
    if (sp.polygon())
      throw core::InputError(
          "species." + sp.name + ".sides = " + std::to_string(sp.sides) +
          ": detect finds disks only, and a polygon's outline is not a circle; track "
          "polygons with a tool that measures their outlines and import the tracks, or give "
          "--set species." +
          sp.name + ".sides=0 to find them as disks of equal area");
    job.detect.radius_px.push_back(sp.radius / job.cal.scale);
  }
  for (double r : job.detect.radius_px)
    if (r < 3)
      throw core::InputError(
          "the grains are " + core::format_g(r, 3) +
          " pixels in radius at this calibration: at least 3 are needed (film closer, or a larger "
          "picture)");
  return model;
}

int detect(const DetectCliOptions& o) {
  check_options(o);
  const fs::path out = io::output_path(o.out);
  if (out.extension() != ".csv") throw core::InputError("--out " + o.out + ": expected a .csv file");
  fs::path meta_out = out;
  meta_out.replace_extension(".meta.toml");
  io::check_not_input(out, {fs::absolute(o.input)}, "tracks");
  fs::path film_out;
  if (!o.rectified.empty()) {
    film_out = io::output_path(o.rectified);
    if (film_out.extension() != ".mp4")
      throw core::InputError("--rectified " + o.rectified + ": expected an .mp4 file");
    io::check_not_input(film_out, {fs::absolute(o.input)}, "rectified film");
  }

  DetectJob job;
  core::Model model = detect_geometry(o, job);
  job.detect.band = o.band;
  job.detect.edge_threshold = o.edge;
  job.max_step = o.max_step;
  job.memory = o.memory;
  job.bright = job.bright_given = o.bright;
  if (!o.frames.empty()) {
    const size_t colon = o.frames.find(':');
    char* e = nullptr;
    job.first = std::strtol(o.frames.c_str(), &e, 10);
    job.last = colon == std::string::npos ? job.first : std::strtol(o.frames.c_str() + colon + 1, &e, 10);
    if (*e || job.first < 0 || job.last < job.first)
      throw core::InputError("--frames '" + o.frames + "': expected K or A:B (frame numbers from 0, A <= B)");
  }

  vision::FrameSource source(o.input);
  if (job.lens.present && job.lens.size != cv::Size(source.width(), source.height()))
    throw core::InputError("--lens " + o.lens + ": its pictures are " + std::to_string(job.lens.size.width) +
                           "x" + std::to_string(job.lens.size.height) + " and the film's frames " +
                           std::to_string(source.width()) + "x" + std::to_string(source.height()) +
                           " (the chessboard is filmed by the same camera, at the same size)");
  if (o.fps > 0) job.cal.fps = o.fps;
  if (!(job.cal.fps > 0)) job.cal.fps = source.fps();
  if (!(job.cal.fps > 0))
    throw core::InputError(o.input + ": the frame rate is unknown (a directory of frames): give --fps");
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "tracks", io::OutputKind::Csv, kHeader);
  // The sidecar is an output too: never over a file of the user's, replaced by --force only as written.
  io::check_destination(meta_out, o.force, "tracks' metadata", io::OutputKind::Csv, io::kMetadataFirstLine);
  std::unique_ptr<io::OutputLock> film_lock;
  std::unique_ptr<RectifiedFilm> film;
  if (!film_out.empty()) {
    film_lock = std::make_unique<io::OutputLock>(film_out);
    io::check_destination(film_out, o.force, "rectified film", io::OutputKind::Movie);
    film = std::make_unique<RectifiedFilm>(film_out, job, model, source.width(), source.height());
    job.on_frame = [&film](const cv::Mat& frame, long) { film->add(frame); };
  }

  Progress progress("detect", source.count() > 0 ? static_cast<double>(source.count()) : 1.0, !o.quiet);
  job.progress = [&](long k) { progress.update(static_cast<double>(k + 1)); };
  DetectStats st;
  const std::string csv = detect_tracks(source, job, model, st);
  progress.finish();
  if (st.frames == 0)
    throw core::InputError(o.input + ": no frame could be decoded (or --frames lies past its end)");
  if (film) film->finish();

  io::RunInfo info;
  info.command = command_line();
  info.facts = {{"input", o.input},
                {"frames", st.frames},
                {"frames_announced", source.count()},
                {"ended_early", source.ended_early()},
                {"detections", st.detections},
                {"dropped_outside_container", st.dropped_outside},
                {"tracks", st.tracks},
                {"wall_time_s", st.seconds},
                {"seconds_per_frame", st.seconds / std::max(1L, st.frames)},
                {"radius_band", o.band},
                {"edge_threshold", o.edge},
                {"max_step_radii", o.max_step},
                {"memory_frames", static_cast<long>(o.memory)},
                {"bright", st.bright},
                {"bright_found_from_first_frame", !o.bright},
                {"size_spread", st.size_spread},
                {"size_error_rate", st.size_error_rate}};
  if (film) info.facts.push_back({"rectified_film", o.rectified});
  std::string meta = io::metadata_toml(model, info);
  meta += calibration_toml("calibration", job.cal, job.lens);
  io::write_output(out, csv);
  io::write_output(meta_out, meta);
  print_detect(o, source, st, job.cal, out);
  if (film && !o.quiet) {
    const Calibration& up = film->upright();
    std::printf("rectified film -> %s (upright, ideal pixels: --scale %s --origin %s,%s)\n", film_out.c_str(),
                core::format_g(up.scale, 9).c_str(), core::format_g(up.origin_x, 9).c_str(),
                core::format_g(up.origin_y, 9).c_str());
  }
  return 0;
}
}  // namespace

void define_detect_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<DetectCliOptions>();
  CLI::App* cmd = &command;
  cmd->add_option(
         "input", o->input,
         "a video (MP4, AVI, ...), a multi-page TIFF stack, or a directory of frames (PNG, JPEG, BMP, TIFF)")
      ->required();
  cmd->add_option("--out", o->out, "the tracks CSV to write (TRACKS.meta.toml beside it)")->required();
  cmd->add_option(
      "--geometry", o->geometry,
      "a scene file or a preset's name: the container and the species' sizes (default: a siloscope "
      "movie's own scene)");
  cmd->add_option("--set", o->overrides, "KEY=VALUE: change a key of the geometry scene (repeatable)");
  cmd->add_option("--scale", o->scale, "metres per pixel");
  cmd->add_option("--origin", o->origin, "X,Y: the pixel of the outlet's centre");
  cmd->add_option("--points", o->points,
                  "PX,PY=X,Y:PX,PY=X,Y[:...]: two or more marked pixels and where they are (m, the outlet's "
                  "centre at 0,0): the scale, origin and the camera's rotation");
  cmd->add_option("--lens", o->lens,
                  "a picture of a chessboard filmed by the same camera (or a directory of them): the lens's "
                  "distortion taken out of every position, the tracks then in ideal pixels");
  cmd->add_option(
      "--rectified", o->rectified,
      "also write the film as the tracks see it, MP4: the lens's distortion taken out and the "
      "container turned upright, the outlet's centre where it was (the calibration in its comment)");
  cmd->add_option("--pattern", o->pattern, "the chessboard's inner corners, COLUMNSxROWS (default 9x6)");
  cmd->add_option(
      "--rotation", o->rotation,
      "with --scale and --origin: degrees the container is turned counter-clockwise in the picture");
  cmd->add_option("--fps", o->fps,
                  "frames per second (default: the video's, or a siloscope movie's simulated rate)");
  cmd->add_option("--frames", o->frames, "K or A:B: only these frames (from 0)");
  cmd->add_option("--radius-band", o->band,
                  "a species' disks are searched from r(1 - B) to r(1 + B), and a track links disks within "
                  "a factor 1 + B of its size (default 0.25)");
  cmd->add_option("--edge", o->edge,
                  "edge strength for the sub-pixel circle fit, on the flattened picture (default 60)");
  cmd->add_option("--max-step", o->max_step,
                  "largest move between frames beyond the predicted one, in radii of the largest grains, for "
                  "linking (default 0.8)");
  cmd->add_option("--memory", o->memory, "frames a disk may go unseen and keep its id (default 2)");
  cmd->add_flag("--bright", o->bright,
                "bright disks on a dark background (default: found from the first frame, by which way round "
                "clearly more disks are found)");
  cmd->add_flag("--force", o->force, "replace tracks siloscope wrote");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return detect(*o); }; });
}

}  // namespace app
