// siloscope export RUN --format xyz|csv|vtu: a recording's trajectory for the field's tools. Extended XYZ
// (one frame per trajectory frame) loads in OVITO and ASE; CSV (one row per grain and frame) in pandas, R or
// a spreadsheet; VTU (a directory of VTK files and a .pvd time series) in ParaView.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

#include "app/services/cli.h"
#include "app/services/inspect_files.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "core/geometry.h"
#include "core/interrupt.h"
#include "core/setup.h"
#include "io/manifest.h"
#include "io/metadata.h"
#include "io/output.h"
#include "io/run.h"
#include "io/vtu.h"

namespace app {

namespace {
namespace fs = std::filesystem;

struct ExportOptions {
  std::string run, format = "xyz", frames, out, vtu_encoding = "binary";
  bool force = false;
};

const char* kCsvHeader =
    "frame,t_s,id,species,x_m,y_m,radius_m,vx_m_per_s,vy_m_per_s,force_n,in_arch,angle_rad,sides";
// Species as chemical symbols by species index, which ASE requires (docs/export.md): H = the first species
// (the paper's original disks), He = the second (added disks), then Li, Be, ...
const char* kSymbols[] = {"H", "He", "Li", "Be", "B",  "C",  "N", "O",
                          "F", "Ne", "Na", "Mg", "Al", "Si", "P", "S"};

// "K" or "A:B" (inclusive; either end may be left out) -> [first, last]; the whole trajectory when empty.
void frame_range(const std::string& spec, long count, long& first, long& last) {
  first = 0;
  last = count - 1;
  if (spec.empty()) return;
  auto number = [&](const std::string& s, long fallback) {
    if (s.empty()) return fallback;
    if (s.find_first_not_of("0123456789") != std::string::npos)
      throw core::InputError("--frames " + spec + ": expected K or A:B with whole numbers from 0 to " +
                             std::to_string(count - 1));
    return std::stol(s);
  };
  const auto colon = spec.find(':');
  if (colon == std::string::npos) {
    first = last = number(spec, 0);
  } else {
    first = number(spec.substr(0, colon), 0);
    last = number(spec.substr(colon + 1), count - 1);
  }
  if (first > last || last >= count)
    throw core::InputError("--frames " + spec + ": the trajectory has frames 0 to " +
                           std::to_string(count - 1));
}

std::string num(double v) {
  return core::format_g(v, 7);
}

// ParaView: a directory with one VTK UnstructuredGrid per frame (grains_NNNNNN.vtu), the container's walls
// (walls.vtu, or walls_NNNNNN.vtu when it vibrates), trajectory.pvd tying them into a time series, and the
// run's metadata.
int export_vtu(const ExportOptions& o, const io::Run& run, long first, long last) {
  const io::Trajectory& t = run.trajectory();
  const core::Model& model = run.model();
  const core::Setup& setup = model.setup;
  const fs::path out = o.out.empty() ? run.dir() / "vtu" : fs::path(o.out);
  io::OutputDir dir(out.string(), o.force, io::DirKind::Export);
  std::vector<io::PvdEntry> entries;
  const bool moving = setup.drive.vibrating();
  const io::VtuEncoding enc = o.vtu_encoding == "ascii" ? io::VtuEncoding::Ascii : io::VtuEncoding::Binary;
  const std::vector<std::string> names = setup.species_names();
  const bool obstacle = setup.geo.obstacle.present();
  bool polygons = false;
  for (const auto& sp : setup.species) polygons = polygons || (sp.count > 0 && sp.polygon());
  // Force chains when the recording kept its contacts (record always does).
  const io::Contacts* contacts = run.contacts();
  if (!moving) {
    io::write_file_atomic(dir.file("walls.vtu"), io::vtu_walls(setup.geo, 0, 0, enc), false);
    if (obstacle)
      io::write_file_atomic(dir.file("obstacle.vtu"), io::vtu_obstacle(setup.geo, 0, 0, enc), false);
  }
  char name[48];
  auto per_frame = [&](const char* stem, long k) {
    std::snprintf(name, sizeof name, "%s_%06ld.vtu", stem, k);
    return std::string(name);
  };
  for (long k = first; k <= last; ++k) {
    core::Frame f = t.frame(k);
    if (contacts && k < contacts->size())
      f.contacts = contacts->frame(k), f.wall_contacts = contacts->walls(k);
    const std::string grains = per_frame("grains", k);
    io::write_file_atomic(dir.file(grains), io::vtu_grains(f, names, enc), false);
    entries.push_back({f.t, 0, grains});
    if (moving) {
      const std::string walls = per_frame("walls", k);
      io::write_file_atomic(dir.file(walls), io::vtu_walls(setup.geo, f.container_x, f.container_y, enc),
                            false);
      entries.push_back({f.t, 1, walls});
      if (obstacle) {
        const std::string ob = per_frame("obstacle", k);
        io::write_file_atomic(dir.file(ob), io::vtu_obstacle(setup.geo, f.container_x, f.container_y, enc),
                              false);
        entries.push_back({f.t, 5, ob});
      }
    } else {
      entries.push_back({f.t, 1, "walls.vtu"});
      if (obstacle) entries.push_back({f.t, 5, "obstacle.vtu"});
    }
    if (polygons) {
      const std::string shapes = per_frame("shapes", k);
      io::write_file_atomic(dir.file(shapes), io::vtu_shapes(f, enc), false);
      entries.push_back({f.t, 2, shapes});
    }
    const std::string arch = per_frame("arch", k);
    io::write_file_atomic(dir.file(arch), io::vtu_arch(f, enc), false);
    entries.push_back({f.t, 3, arch});
    if (contacts && k < contacts->size()) {
      const std::string chains = per_frame("chains", k);
      io::write_file_atomic(dir.file(chains), io::vtu_chains(f, enc), false);
      entries.push_back({f.t, 4, chains});
    }
    core::throw_if_interrupted();
  }
  io::write_file_atomic(dir.file("trajectory.pvd"), io::pvd(entries), false);
  io::RunInfo info{command_line(),
                   {{"export", "vtu"},
                    {"trajectory", fs::absolute(run.dir() / io::run_file::kTrajectory).string()},
                    {"first_frame", first},
                    {"vtu_encoding", o.vtu_encoding},
                    {"last_frame", last},
                    {"open_in_paraview", "trajectory.pvd"}},
                   {},
                   {}};
  io::write_file_atomic(dir.file(io::kMetadataFile), io::metadata_toml(model, info));
  dir.commit();
  std::printf(
      "%ld frames of %d grains -> %s/trajectory.pvd (ParaView: open it and Apply; disks: Point Gaussian "
      "scaled by radius)\n",
      last - first + 1, setup.n_total, out.c_str());
  return 0;
}

// GSD (HOOMD-blue; OVITO reads it): each species a type with its shape, orientations as quaternions. Written
// by the package's writer (src/python/siloscope/_gsd.py, python3-gsd) under a temporary name.
int export_gsd(const ExportOptions& o, const io::Run& run, long first, long last) {
  const core::Geometry& geo = run.model().setup.geo;
  const fs::path traj = run.dir() / io::run_file::kTrajectory;
  const fs::path out = o.out.empty() ? run.dir() / "trajectory.gsd" : fs::path(o.out);
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "export file", io::OutputKind::Gsd);
  const fs::path partial = out.string() + ".partial-" + std::to_string(::getpid()) + ".gsd";
  const int status =
      run_python(script_path("export_gsd.py"),
                 {traj.string(), partial.string(), std::to_string(first), std::to_string(last),
                  num(geo.x_left), num(-0.05 * geo.total_height), num(geo.x_right), num(geo.total_height)});
  std::error_code ec;
  if (status != 0) {
    fs::remove(partial, ec);
    throw core::RuntimeFault("export: the GSD writer (export_gsd.py, python3-gsd) failed");
  }
  io::place_output(partial, out);
  std::printf("%ld frames -> %s (GSD: a type per species with its shape, orientations as quaternions)\n",
              last - first + 1, out.c_str());
  return 0;
}

// Each species' exits so far as XYZ comment keys: " exits_original=40 exits_added=12" (the scene's names).
std::string exit_counts(const core::Frame& f, const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k)
    out += " exits_" + names[k] + "=" + std::to_string(f.exits_of(static_cast<int>(k)));
  return out;
}

int export_run(const ExportOptions& o) {
  if (o.vtu_encoding != "binary" && o.vtu_encoding != "ascii")
    throw core::InputError("--vtu-encoding " + o.vtu_encoding +
                           ": allowed values are binary (appended, zlib-compressed) and ascii");
  if (o.vtu_encoding != "binary" && o.format != "vtu")
    throw core::InputError("--vtu-encoding is for --format vtu (this is --format " + o.format + ")");
  if (o.format != "xyz" && o.format != "csv" && o.format != "vtu" && o.format != "gsd")
    throw core::InputError("--format " + o.format + " is not allowed; allowed values are xyz, csv, vtu, gsd");
  const io::Run run = io::Run::open(o.run, "export", io::Run::kTrajectory);
  const io::Trajectory& t = run.trajectory();
  if (t.size() == 0) throw core::InputError(o.run + ": the trajectory holds no frames");
  long first = 0, last = 0;
  frame_range(o.frames, t.size(), first, last);
  const core::Model& model = run.model();
  const core::Setup& setup = model.setup;
  const core::Geometry& geo = setup.geo;
  const std::vector<std::string> names = setup.species_names();
  std::string names_text;
  for (const auto& nm : names) names_text += (names_text.empty() ? "" : " ") + nm;

  if (o.format == "vtu") return export_vtu(o, run, first, last);
  if (o.format == "gsd") return export_gsd(o, run, first, last);
  fs::path out = o.out.empty() ? run.dir() / ("trajectory." + o.format) : fs::path(o.out);
  io::OutputLock lock(out);
  io::check_destination(out, o.force, "export file",
                        o.format == "csv" ? io::OutputKind::Csv : io::OutputKind::Xyz,
                        o.format == "csv" ? kCsvHeader : "");

  const size_t n = t.info().n_particles;
  std::string text;
  if (o.format == "csv") text = std::string(kCsvHeader) + "\n";
  // The lattice is the container's bounding box at rest (x from its left wall, y from the aperture line), z a
  // unit thickness; a vibrating container's displacement is in each frame's `container`.
  const double w = geo.x_right - geo.x_left, h = geo.total_height;
  for (long k = first; k <= last; ++k) {
    core::throw_if_interrupted();
    const core::Frame f = t.frame(k);
    std::vector<char> in_arch(n, 0);
    for (int id : f.arch) in_arch[static_cast<size_t>(id)] = 1;
    if (o.format == "xyz") {
      text += std::to_string(n) + "\n";
      text +=
          "Lattice=\"" + num(w) + " 0 0 0 " + num(h) + " 0 0 0 1\" Origin=\"" + num(geo.x_left) + " 0 0\" " +
          "Properties=species:S:1:pos:R:3:radius:R:1:velo:R:3:force:R:1:arch:I:1:id:I:1:angle:R:1:sides:I:1:"
          "kind:S:1:orientation:R:4 Time=" +
          num(f.t) + " frame=" + std::to_string(k) + exit_counts(f, names) + " species_names=\"" +
          names_text + "\" container=\"" + num(f.container_x) + " " + num(f.container_y) +
          "\" units=SI pbc=\"F F F\" siloscope=\"" + io::version_string() + "\"\n";
    }
    for (size_t i = 0; i < n; ++i) {
      const core::Particle& p = f.particles[i];
      const size_t sp = static_cast<size_t>(core::species_index(p.species));
      const std::string& name = sp < names.size() ? names[sp] : names.back();
      if (o.format == "xyz")
        text += std::string(kSymbols[sp % 16]) + " " + num(p.x) + " " + num(p.y) + " 0 " + num(p.radius) +
                " " + num(p.vx) + " " + num(p.vy) + " 0 " + num(p.force) + " " + (in_arch[i] ? "1" : "0") +
                " " + std::to_string(i) + " " + num(p.angle) + " " + std::to_string(p.sides) + " " + name +
                " 0 0 " + num(std::sin(0.5 * p.angle)) + " " + num(std::cos(0.5 * p.angle)) + "\n";
      else
        text += std::to_string(k) + "," + num(f.t) + "," + std::to_string(i) + "," + name + "," + num(p.x) +
                "," + num(p.y) + "," + num(p.radius) + "," + num(p.vx) + "," + num(p.vy) + "," +
                num(p.force) + "," + (in_arch[i] ? "1" : "0") + "," + num(p.angle) + "," +
                std::to_string(p.sides) + "\n";
    }
  }
  io::write_output(out, text);
  std::printf("%ld frames of %zu grains -> %s\n", last - first + 1, n, out.c_str());
  return 0;
}
}  // namespace

void define_export_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = &command;
  cmd->add_option("run", o->run,
                  "a recording (or run with --trajectory-fps) directory, or its trajectory.sstraj")
      ->required();
  cmd->add_option(
         "--format", o->format,
         "xyz (extended XYZ: OVITO, ASE; orientation as a quaternion x y z w), csv, vtu (ParaView: a "
         "directory) or gsd (HOOMD, OVITO: a type per species with its shape)")
      ->capture_default_str();
  cmd->add_option("--frames", o->frames, "K or A:B (inclusive; default: every frame)");
  cmd->add_option("--out", o->out,
                  "output file (default: RUN/trajectory.xyz, .csv or .gsd; vtu: the directory RUN/vtu)");
  cmd->add_option(
         "--vtu-encoding", o->vtu_encoding,
         "vtu: binary (VTK's appended raw data, each array zlib-compressed) or ascii (readable, larger)")
      ->capture_default_str();
  cmd->add_flag("--force", o->force, "replace an earlier export");
  cmd->callback([o, &action] { action = [o] { return export_run(*o); }; });
}

}  // namespace app
