// siloscope import TRACKS.csv [--geometry SCENE.toml] --out RUN: a lab experiment's tracked particles as a
// run directory like a recording's (trajectory, exits, clogs, the clogs' arches with their descriptors,
// summary, metadata, manifest), its clogs and arches found by the simulation's own rules from positions alone
// (lab/import.h). Every command that reads a recording reads it: inspect, export, gallery, analyze, timeline.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "analysis/measure.h"
#include "analysis/tidy.h"
#include "app/services/cli.h"
#include "app/services/lab.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "core/model.h"
#include "io/csv_table.h"
#include "io/events_csv.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "io/trajectory.h"
#include "lab/import.h"

#include <toml++/toml.h>

namespace app {

namespace {
namespace fs = std::filesystem;

struct ImportCliOptions {
  std::string tracks, geometry, out, columns, origin;
  std::vector<std::string> overrides;
  double scale = 0, fps = 0, rotation = 0;
  bool y_up = false, force = false, quiet = false;
  lab::ImportOptions import;
};

// trackpy's HDF5 (TRACKS.h5 or .hdf5) as a CSV in the system's temporary directory, removed when done: pandas
// reads it (SHARE/python/siloscope/_trackpy_hdf5.py, with Debian's python3-pandas and python3-tables).
class Hdf5AsCsv {
 public:
  explicit Hdf5AsCsv(const std::string& path)
      : csv_((fs::temp_directory_path() / ("siloscope-" + std::to_string(::getpid()) + "-tracks.csv"))
                 .string()) {
    const int status =
        run_python((share_dir() / "python" / "siloscope" / "_trackpy_hdf5.py").string(), {path, csv_});
    if (status == 0) return;
    remove();
    throw core::InputError(path + (status == 3
                                       ? ": trackpy's HDF5 is read with pandas: install Debian's "
                                         "python3-pandas and python3-tables, or export the tracks as CSV"
                                       : ": not trackpy's HDF5 (pandas tables), nor read as such"));
  }
  ~Hdf5AsCsv() { remove(); }
  Hdf5AsCsv(const Hdf5AsCsv&) = delete;
  Hdf5AsCsv& operator=(const Hdf5AsCsv&) = delete;
  const std::string& csv() const { return csv_; }

 private:
  void remove() {
    std::error_code ec;
    fs::remove(csv_, ec);
  }
  std::string csv_;
};

bool is_hdf5(const std::string& path) {
  const std::string ext = core::lower_extension(path);
  return ext == ".h5" || ext == ".hdf5" || ext == ".hdf";
}

// detect's metadata beside its CSV (TRACKS.meta.toml): the calibration it used, when the command line gives
// none.
fs::path detect_metadata(const fs::path& tracks) {
  fs::path m = tracks;
  m.replace_extension(".meta.toml");
  return m;
}

std::string clog_arches_csv(const lab::Imported& im, const std::vector<std::string>& names) {
  std::string out =
      "clog,t_s,grains,ids,track_ids,species,span_m,rise_m,aspect_rise_over_half_span,theta_max_deg,defects,"
      "bead_angle_sd_deg\n";
  auto g = [](double v) { return core::format_g(v, 6); };
  for (const lab::ClogArch& a : im.clog_arches) {
    std::string ids, tracks, species;
    for (size_t k = 0; k < a.ids.size(); ++k) {
      const char* sep = k ? " " : "";
      ids += sep + std::to_string(a.ids[k]);
      tracks += sep + std::to_string(a.track_ids[k]);
      species +=
          sep + names[static_cast<size_t>(core::species_index(im.species[static_cast<size_t>(a.ids[k])]))];
    }
    const core::ArchDescriptors& d = a.descriptors;
    out += std::to_string(a.clog) + "," + g(a.t) + "," + std::to_string(d.grains) + "," + ids + "," + tracks +
           "," + species + "," + g(d.span) + "," + g(d.rise) + "," + g(d.aspect) + "," + g(d.theta_max_deg) +
           "," + std::to_string(d.defects) + "," + g(d.angle_sd_deg) + "\n";
  }
  return out;
}

// Every setting and count of the import, for the run's metadata ([run]).
io::Facts import_facts(const ImportCliOptions& o, const lab::Tracks& tracks, const lab::Units& units,
                       const std::string& calibration, const lab::ImportReport& r) {
  return {{"imported", true},
          {"imported_from", o.tracks},
          {"imported_hash", io::file_hash(o.tracks)},
          {"columns", tracks.columns_used},
          {"untracked_spots_skipped", tracks.untracked},
          {"species_by_size", tracks.species_by_size},
          {"size_spread", tracks.size_spread},
          {"size_error_rate", tracks.size_error_rate},
          {"calibration", calibration},
          {"scale_m_per_px", units.scale},
          {"origin_x", units.origin_x},
          {"origin_y", units.origin_y},
          {"rotation_deg", units.rotation * 180 / M_PI},
          {"contact_tolerance", o.import.contact_tolerance},
          {"max_gap_frames", static_cast<long>(o.import.max_gap)},
          {"join_distance_diameters", o.import.join_distance},
          {"frames", r.frames},
          {"rows", r.rows},
          {"tracks", r.tracks},
          {"grains", r.grains},
          {"particles", r.particles},
          {"position_noise_m", r.noise},
          {"arrest_floor_m", r.arrest_floor},
          {"ids_joined", r.joined},
          {"ids_split_at_jumps", r.split},
          {"positions_interpolated", r.interpolated},
          {"gaps_too_long", r.long_gaps},
          {"exits_seen_below_outlet", r.exits_below},
          {"exits_from_tracks_ending_in_outlet", r.exits_lost},
          {"tracks_leaving_view", r.left_view},
          {"tracks_entering_view", r.entered},
          {"frame_interval_median_s", r.interval_median},
          {"frame_interval_min_s", r.interval_min},
          {"frame_interval_max_s", r.interval_max},
          {"frame_interval_changes", r.interval_changes},
          {"time_offset_s", r.time_offset},
          {"frames_with_arch", r.frames_with_arch}};
}

// What the import did, on the terminal.
void print_import(const lab::Imported& im, const lab::Tracks& tracks, const ImportCliOptions& o,
                  const fs::path& out) {
  const lab::ImportReport& r = im.report;
  std::printf("read        %ld rows, %ld frames (%s s apart", r.rows, r.frames,
              core::format_g(r.interval_median, 4).c_str());
  if (r.interval_changes)
    std::printf("; %ld intervals differ by > 1%%: %s to %s s", r.interval_changes,
                core::format_g(r.interval_min, 4).c_str(), core::format_g(r.interval_max, 4).c_str());
  std::printf("), %ld tracks\n", r.tracks);
  if (tracks.untracked)
    std::printf("skipped     %ld spots without a track id (the tracker linked them to no track)\n",
                tracks.untracked);
  if (tracks.size_spread > 0)
    std::printf(
        "species     the likeliest for each grain's %s (spread %.1f%%; the scene's size laws overlap for "
        "%.2f%% of grains, which no size tells apart)\n",
        tracks.species_by_size ? "size in the file's size column" : "radius", 100 * tracks.size_spread,
        100 * tracks.size_error_rate);
  std::printf(
      "grains      %ld (%ld ids joined where a track broke off, %ld split where one jumped; %ld positions "
      "filled in gaps of <= %d frames; %ld longer gaps left empty), as %ld particles in the run\n",
      r.grains, r.joined, r.split, r.interpolated, o.import.max_gap, r.long_gaps, r.particles);
  std::printf("field       %ld tracks entered after the first frame, %ld left it away from the outlet\n",
              r.entered, r.left_view);
  std::printf("exits       %zu (%ld seen below the outlet, %ld from tracks ending inside it)\n",
              im.events.exits.size(), r.exits_below, r.exits_lost);
  std::printf(
      "noise       %s m in the positions (%s of the largest grain's diameter)",
      core::format_g(r.noise, 3).c_str(),
      core::format_g(r.noise / (2 * *std::max_element(im.radius.begin(), im.radius.end())), 3).c_str());
  if (r.arrest_floor > 0)
    std::printf("; arrested where no grain near the outlet moves %s m or more",
                core::format_g(r.arrest_floor, 3).c_str());
  std::printf("\n");
  std::printf(
      "clogs       %zu (%zu with an arch; arches in %ld of %ld frames, contact gap <= %s of a diameter)\n",
      im.events.clogs.size(), im.clog_arches.size(), r.frames_with_arch, r.frames,
      core::format_g(o.import.contact_tolerance, 3).c_str());
  std::printf("written     %s (trajectory.sstraj, exits, clogs, clog_arches, summary, metadata)\n",
              out.string().c_str());
}

// The numeric options in their ranges (before any work).
void check_options(const ImportCliOptions& o) {
  if (!(o.import.contact_tolerance >= 0 && o.import.contact_tolerance <= 0.5))
    throw core::InputError("--contact-tolerance " + core::format_g(o.import.contact_tolerance) +
                           ": expected a gap from 0 to 0.5 of the smaller diameter");
  if (o.import.max_gap < 0 || o.import.max_gap > 1000)
    throw core::InputError("--max-gap " + std::to_string(o.import.max_gap) + ": expected 0 to 1000 frames");
  if (!(o.import.join_distance >= 0 && o.import.join_distance <= 5))
    throw core::InputError("--join-distance " + core::format_g(o.import.join_distance) +
                           ": expected 0 to 5 diameters");
  if (o.scale < 0 || !std::isfinite(o.scale))
    throw core::InputError("--scale " + core::format_g(o.scale) + ": expected metres per pixel, > 0");
  if (o.fps < 0 || !std::isfinite(o.fps))
    throw core::InputError("--fps " + core::format_g(o.fps) + ": expected > 0");
}

// Pixels to metres: the command line's, else the calibration detect wrote beside the tracks; `calibration`
// says which.
lab::Units import_units(const ImportCliOptions& o, std::string& calibration) {
  lab::Units units;
  units.scale = o.scale;
  units.y_up = o.y_up;
  units.rotation = rotation_radians(o.rotation);
  units.fps = o.fps;
  calibration = "command line";
  if (!o.origin.empty()) lab::parse_origin(o.origin, units.origin_x, units.origin_y);
  const fs::path meta = detect_metadata(o.tracks);
  if (o.scale == 0 && fs::exists(meta)) {
    // The calibration detect used (pixels of a siloscope movie or of --scale/--origin given to detect).
    toml::table t;
    try {
      t = toml::parse_file(meta.string());
    } catch (const toml::parse_error& e) {
      throw core::InputError(meta.string() + ": not valid TOML (" + std::string(e.description()) + ")");
    }
    const auto s = t["calibration"]["scale_m_per_px"].value<double>();
    const auto ox = t["calibration"]["origin_x_px"].value<double>();
    const auto oy = t["calibration"]["origin_y_px"].value<double>();
    if (s && ox && oy && *s > 0) {
      units.scale = *s;
      if (o.origin.empty()) units.origin_x = *ox, units.origin_y = *oy;
      if (o.rotation == 0) units.rotation = t["calibration"]["rotation_deg"].value_or(0.0) * M_PI / 180;
      calibration = meta.filename().string();
    }
    if (o.fps == 0)
      if (auto f = t["calibration"]["fps"].value<double>(); f && *f > 0) units.fps = *f;
  }
  return units;
}

int import_run(ImportCliOptions o) {
  check_options(o);
  core::check_input_file(o.tracks, "tracked particles", lab::kMaxTrackBytes, "");
  const fs::path out = io::output_path(o.out);
  io::check_not_input(out, {fs::absolute(o.tracks)}, "run");
  // Before reading: the files a long film's detections are kept in go beside it.
  io::check_destination(out, o.force, "output directory");

  std::string calibration;
  const lab::Units units = import_units(o, calibration);
  const fs::path meta = detect_metadata(o.tracks);

  // The container: --geometry, or the scene detect wrote beside the tracks (a siloscope movie's own).
  std::string geometry_file = scene_file(o.geometry);  // a file, or a preset's name
  if (geometry_file.empty()) {
    if (!fs::exists(meta))
      throw core::InputError(
          "--geometry: needed (a scene file with the container and its species), unless the "
          "tracks come from detect with its " +
          meta.filename().string() + " beside them");
    geometry_file = meta.string();
  }
  core::Scene scene = core::load_scene(geometry_file);
  core::apply_overrides(scene, o.overrides);
  const core::Model geometry = core::compile(scene);
  std::optional<Hdf5AsCsv> h5;
  if (is_hdf5(o.tracks)) h5.emplace(o.tracks);
  // A long film's detections and paths are kept in hidden files on the output's disk, not in memory.
  std::error_code ec;
  const std::string spill_dir = fs::is_directory(out.parent_path(), ec) ? out.parent_path().string() : "";
  lab::Tracks tracks;
  try {
    tracks = lab::read_tracks(h5 ? h5->csv() : o.tracks, lab::parse_column_map(o.columns, "--columns"), units,
                              geometry.setup, geometry.setup.geo, spill_dir);
  } catch (const core::InputError& e) {
    if (!h5) throw;
    std::string what = e.what();  // the temporary CSV's name is the user's file's, its rows the tables'
    for (size_t at; (at = what.find(h5->csv())) != std::string::npos;)
      what.replace(at, h5->csv().size(), o.tracks + " (its tables as CSV, row line - 1)");
    throw core::InputError(what);
  }
  tracks.source = o.tracks;
  if (tracks.frames.size() < 2)
    throw core::InputError(o.tracks + ": one frame only; a run needs at least two");
  lab::ImportOptions how = o.import;
  how.arrest_shift_given = std::any_of(o.overrides.begin(), o.overrides.end(), [](const std::string& kv) {
    return kv.rfind("arrest_shift=", 0) == 0;
  });
  how.spill_dir = spill_dir;
  lab::Imported im = lab::import_tracks(tracks, geometry, how);
  const lab::ImportReport& r = im.report;
  // The run's scene: the geometry's, lasting as long as the film (what every reader of the run takes as its
  // duration) and without the clog rule (nothing removes an arch in a lab).
  scene.duration = std::max(im.frames.back().t, 1e-3);
  scene.clog_timeout = 0;
  const core::Model model = core::compile(scene);

  io::OutputDir dir(o.out, o.force, io::DirKind::Run);
  io::RunInfo info;
  info.command = command_line();
  info.facts = import_facts(o, tracks, units, calibration, r);
  // No simulation to watch: the health table says so (readers of runs require one).
  info.health = {{"status", "imported"}, {"warnings", 0L}, {"ballistic", false}};
  const std::string metadata = io::metadata_toml(model, info);
  {
    io::TrajectoryInfo ti;
    ti.n_particles = static_cast<std::uint32_t>(im.radius.size());
    ti.n_species = static_cast<std::uint32_t>(model.setup.species.size());
    ti.frame_interval = r.interval_median;
    ti.clog_timeout = 0;
    ti.clog_min_gap = scene.clog_min_gap;
    ti.radius_original = model.setup.reference_radius;
    for (double v : im.radius) ti.radius.push_back(static_cast<float>(v));
    ti.species = im.species;
    ti.metadata = metadata;
    io::TrajectoryWriter w(dir.file(io::run_file::kTrajectory), ti);
    std::vector<core::Particle> particles;  // one frame's at a time (lab/import.h)
    for (size_t k = 0; k < im.frames.size(); ++k) {
      core::throw_if_interrupted();
      core::Frame& f = im.frames[k];
      im.particles_at(k, particles);
      f.particles.swap(particles);
      w.add(f, 0, im.between[k]);
      f.particles.swap(particles);
    }
    w.add_events(im.after);
    w.close();
  }
  const std::vector<std::string> names = model.setup.species_names();
  const analysis::Measurements m =
      analysis::measure(im.events, scene.duration, scene.clog_min_gap, static_cast<int>(names.size()),
                        analysis::avalanche_end_for(scene));
  io::write_events(dir.file(""), im.events, names);
  io::write_file_atomic(dir.file("arch_shapes.csv"), arch_shapes_csv(im.events, im.radius));
  io::write_file_atomic(dir.file(io::run_file::kClogArches), clog_arches_csv(im, names));
  io::write_file_atomic(dir.file("species.csv"), analysis::species_csv(model.setup, m));
  io::write_file_atomic(dir.file("summary.csv"),
                        analysis::summary_header() + "\n" + analysis::summary_row(scene, m) + "\n");
  io::write_file_atomic(dir.file("survival.csv"), analysis::survival_csv(scene, im.events.exits));
  io::write_file_atomic(dir.file(io::run_file::kMetadata), metadata);
  dir.commit();

  if (!o.quiet) print_import(im, tracks, o, out);
  return 0;
}
}  // namespace

void define_import_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<ImportCliOptions>();
  CLI::App* cmd = &command;
  cmd->add_option(
         "tracks", o->tracks,
         "CSV, one row per particle per frame: t or frame, particle (id), x, y, optional r or "
         "diameter, angle, species (trackpy's and TrackMate's names work as they are); or TrackMate's "
         "XML, or trackpy's HDF5 (.h5, read through pandas)")
      ->required();
  cmd->add_option("--geometry", o->geometry,
                  "a scene file or a preset's name: the container (walls, outlet, obstacle) and species "
                  "(default: the scene in TRACKS.meta.toml, which detect writes)");
  cmd->add_option("--set", o->overrides, "KEY=VALUE: change a key of the geometry scene (repeatable)");
  cmd->add_option("--out", o->out, "the run directory to write")->required();
  cmd->add_option("--columns", o->columns,
                  "ROLE=COLUMN,...: which column is the time, frame, id, x, y, radius, "
                  "diameter, angle, species");
  cmd->add_option("--scale", o->scale,
                  "metres per pixel (positions and sizes in pixels, image rows downwards)");
  cmd->add_option("--origin", o->origin, "X,Y: where the outlet's centre is, in the file's units");
  cmd->add_flag("--y-up", o->y_up, "with --scale: y grows upwards in the file");
  cmd->add_option("--rotation", o->rotation,
                  "with --scale: degrees the container is turned counter-clockwise in the picture (default: "
                  "detect's calibration, else 0)");
  cmd->add_option("--fps", o->fps, "frames per second, for a file with frame numbers and no times");
  cmd->add_option(
      "--contact-tolerance", o->import.contact_tolerance,
      "largest gap between two grains (or a grain and a wall) that counts as a contact, as a fraction "
      "of the smaller diameter (default 0.1)");
  cmd->add_option("--max-gap", o->import.max_gap,
                  "missing detections of at most this many frames are filled by interpolation (default 3)");
  cmd->add_option("--join-distance", o->import.join_distance,
                  "a track starting within this many diameters of where another broke off is the same grain "
                  "(default 0.5)");
  cmd->add_flag("--force", o->force, "replace a run directory siloscope wrote");
  cmd->add_flag("--quiet", o->quiet, "print nothing but errors");
  cmd->callback([o, &action] { action = [o] { return import_run(*o); }; });
}

}  // namespace app
