#include "app/services/common.h"
#include "core/arch.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "analysis/tidy.h"
#include "core/error.h"
#include "core/format.h"
#include "io/events_csv.h"
#include "io/output.h"
#include "io/trajectory.h"
#include "sim/silo.h"

namespace app {

namespace {
std::string g_command;
std::atomic<int> g_signals{0};

void on_signal(int sig) {
  if (g_signals.fetch_add(1) >= 1) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}
}  // namespace

void SceneOptions::add_to(CLI::App& cmd, bool scene_required) {
  auto* opt = cmd.add_option("scene", path,
                             "scene file (TOML), e.g. assets/scenes/paper.toml, or a run's metadata.toml");
  if (scene_required) opt->required();
  cmd.add_option("--seed", seed, "random seed (overrides the scene's)")
      ->check(whole_number(0, 9223372036854775807.0L));  // 2^63 - 1: what metadata.toml can hold
  cmd.add_option("--duration", duration,
                 "seconds of discharge after the aperture opens (overrides the scene's)");
  cmd.add_option("--set", overrides, "override a scene key, e.g. --set mu=1.0 (repeatable)")->take_all();
  cmd.add_flag("--unsafe", unsafe,
               "let the health monitor warn instead of stopping (results may be garbage)");
}

core::Scene SceneOptions::load() const {
  return compile().scene;
}

core::Model SceneOptions::compile() const {
  core::Scene s = path.empty() ? core::Scene{} : core::load_scene(path);
  if (!path.empty() && core::scene_is_empty_file(path))
    std::fprintf(stderr, "siloscope: %s sets no keys: running the built-in default scene\n", path.c_str());
  core::apply_overrides(s, overrides);
  if (seed) s.seed = *seed, s.origin["seed"] = "--seed";
  if (duration) {
    if (!(*duration >= 0))
      throw core::InputError("--duration " + std::to_string(*duration) + ": must be >= 0 s");
    s.duration = *duration;
    s.origin["duration"] = "--duration";  // a range error names the option, not the file's line
  }
  if (unsafe) s.unsafe = true;
  return core::compile(s);
}

std::string python_interpreter() {
  return ::access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

std::string command_line() {
  return g_command;
}

analysis::Measurements measure_run(const sim::Silo& h, double duration) {
  analysis::Measurements m = analysis::measure(h.events(), duration, h.scene().clog_min_gap,
                                               static_cast<int>(h.setup().species.size()));
  m.health_warnings = h.health_warnings();
  m.airborne_fraction = h.airborne().mean();
  m.ballistic = h.ballistic();
  return m;
}

std::string arch_shapes_csv(const core::Events& ev, const std::vector<double>& radii) {
  std::string out =
      "t_s,grains,span_m,rise_m,aspect_rise_over_half_span,half_span_over_rise,theta_max_deg,defects,"
      "bead_angle_sd_deg\n";
  for (const auto& a : ev.arches) {
    std::vector<core::Vec2> pos(radii.size());
    std::vector<int> local;
    std::vector<double> r;
    for (size_t k = 0; k < a.ids.size() && k < a.x.size(); ++k) {
      local.push_back(static_cast<int>(k));
      pos[k] = {a.x[k], a.y[k]};
      r.push_back(radii[static_cast<size_t>(a.ids[k])]);
    }
    pos.resize(local.size());
    const core::ArchDescriptors d = core::arch_descriptors(local, pos, r);
    auto g = [](double v) { return core::format_g(v, 6); };
    out += g(a.t) + "," + std::to_string(d.grains) + "," + g(d.span) + "," + g(d.rise) + "," + g(d.aspect) +
           "," + g(d.inverse_aspect) + "," + g(d.theta_max_deg) + "," + std::to_string(d.defects) + "," +
           g(d.angle_sd_deg) + "\n";
  }
  return out;
}

analysis::Measurements write_run_outputs(const std::filesystem::path& dir, const sim::Silo& h,
                                         double duration, io::RunInfo info) {
  const core::Scene& scene = h.scene();
  const analysis::Measurements m = measure_run(h, duration);
  io::write_events(dir, h.events(), h.setup().species_names());
  // The arch literature's descriptors of each removed arch, beside arches.csv (whose bytes the paper's golden
  // events fix).
  io::write_file_atomic(dir / "arch_shapes.csv", arch_shapes_csv(h.events(), h.radii()));
  io::write_file_atomic(dir / "species.csv", analysis::species_csv(h.setup(), m));
  io::write_file_atomic(dir / "summary.csv",
                        analysis::summary_header() + "\n" + analysis::summary_row(scene, m) + "\n");
  io::write_file_atomic(dir / "survival.csv", analysis::survival_csv(scene, h.events().exits));
  info.health = health_facts(h);
  // The shortcut's work, only where it was on (metadata of ordinary runs stays as it was).
  if (scene.arrest_skip > 0) {
    info.facts.push_back({"arrest_skips", h.arrest_skips()});
    info.facts.push_back({"arrest_skipped_s", h.skipped_seconds()});
  }
  io::write_file_atomic(dir / "metadata.toml", io::metadata_toml(h.model(), info));
  return m;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

CLI::Validator whole_number(long double lo, long double hi) {
  char range[96];
  std::snprintf(range, sizeof range, "a whole number from %.0Lf to %.0Lf", lo, hi);
  const std::string allowed = range;
  return CLI::Validator(
      [lo, hi, allowed](std::string& s) -> std::string {
        size_t start = (!s.empty() && s[0] == '-' && lo < 0) ? 1 : 0;
        bool digits = s.size() > start && s.find_first_not_of("0123456789", start) == std::string::npos;
        if (!digits) return "'" + s + "' is not allowed; expected " + allowed;
        long double v = std::strtold(s.c_str(), nullptr);
        if (v < lo || v > hi) return s + " is out of range; expected " + allowed;
        return "";
      },
      "INT", "whole_number");
}

io::Facts health_facts(const sim::Silo& h) {
  const bool ballistic = h.ballistic();
  const char* status = h.health_warnings() > 0 ? "unsafe" : ballistic ? "ballistic" : "ok";
  return {{"status", status},
          {"warnings", h.health_warnings()},
          {"ballistic", ballistic},
          {"airborne_fraction_mean", h.airborne().mean()},
          {"airborne_fraction_max", h.airborne().max},
          {"ballistic_threshold", sim::Silo::kBallisticFraction}};
}

io::TrajectoryInfo trajectory_info(const sim::Silo& h, double frame_interval, const std::string& metadata) {
  io::TrajectoryInfo t;
  t.n_particles = static_cast<std::uint32_t>(h.particle_count());
  t.n_species = static_cast<std::uint32_t>(h.setup().species.size());
  t.frame_interval = frame_interval;
  t.clog_timeout = h.scene().clog_timeout;
  t.clog_min_gap = h.scene().clog_min_gap;
  t.radius_original = h.setup().reference_radius;
  for (double r : h.radii()) t.radius.push_back(static_cast<float>(r));
  t.species = h.species();
  t.metadata = metadata;
  return t;
}
void set_command_line(int argc, char** argv) {
  g_command.clear();
  for (int i = 0; i < argc; ++i) g_command += (i ? " " : "") + std::string(argv[i]);
}

void install_interrupt_handler() {
  // No SA_RESTART: a blocking waitpid() returns EINTR so the sweep can pass the interrupt on to its workers.
  struct sigaction sa = {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}
bool interrupted() {
  return g_signals.load() > 0;
}

Progress::Progress(std::string label, double total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && ::isatty(STDERR_FILENO)) {
  start_ = last_ = std::chrono::steady_clock::now();
}

void Progress::update(double done, const std::string& extra) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double frac = total_ > 0 ? std::min(1.0, done / total_) : 1.0;
  double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  constexpr int kWidth = 30;
  std::string bar(static_cast<size_t>(frac * kWidth), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %s  ETA %4.0f s ", label_.c_str(), bar.c_str(), 100 * frac,
               extra.c_str(), eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace app
