// The command line's shared pieces: scene options, integer checks, "did you mean", the command line itself.
#include "app/services/cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "app/services/process.h"
#include "core/error.h"
#include "core/format.h"

namespace app {

namespace {
std::string g_command;
}  // namespace

void SceneOptions::add_to(CLI::App& cmd, bool scene_required) {
  auto* opt = cmd.add_option("scene", path,
                             "scene file (TOML), e.g. assets/scenes/paper.toml, a run's metadata.toml, or a "
                             "preset by name (paper, paper-vibrated, pentagons, silo-obstacle, ...)");
  if (scene_required) opt->required();
  cmd.add_option("--seed", seed, "random seed (overrides the scene's)")
      ->check(whole_number(0, 9223372036854775807.0L));  // 2^63 - 1: what metadata.toml can hold
  cmd.add_option("--duration", duration,
                 "seconds of discharge after the aperture opens (overrides the scene's)");
  cmd.add_option("--set", overrides, "override a scene key, e.g. --set mu=1.0 (repeatable)")->take_all();
  cmd.add_flag("--unsafe", unsafe,
               "let the health monitor warn instead of stopping (results may be garbage)");
}

namespace {
// A scene file siloscope wrote (a run's metadata, a sweep's point scene): its [siloscope] table, or the
// comment sweep writes at the top of a point's scene.
bool written_by_siloscope(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.find("\n[siloscope]\n") != std::string::npos || text.rfind("[siloscope]\n", 0) == 0 ||
         text.rfind("# siloscope", 0) == 0;
}
}  // namespace

core::Scene SceneOptions::load() const {
  return compile().scene;
}

std::string scene_file(const std::string& given) {
  std::error_code ec;
  if (given.empty() || std::filesystem::exists(given, ec) || given.find('/') != std::string::npos ||
      (given.size() > 5 && given.compare(given.size() - 5, 5, ".toml") == 0))
    return given;
  // A preset by its name: SHARE/scenes/NAME.toml (beside the binary, or installed).
  std::filesystem::path dir;
  try {
    dir = share_dir() / "scenes";
  } catch (const core::RuntimeFault&) {
    return given;
  }
  if (std::filesystem::is_regular_file(dir / (given + ".toml"), ec))
    return (dir / (given + ".toml")).string();
  std::vector<std::string> presets;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".toml") presets.push_back(e.path().stem().string());
  std::sort(presets.begin(), presets.end());
  std::string names;
  for (const auto& n : presets) names += (names.empty() ? "" : ", ") + n;
  throw core::InputError(given + ": no such scene file, and no preset scene of that name (presets: " + names +
                         ")");
}

core::Model SceneOptions::compile() const {
  const std::string path = scene_file(this->path);
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
  core::Model m = core::compile(s);
  // Warnings about keys are for what the user wrote: a scene siloscope wrote itself (a run's metadata.toml, a
  // sweep's point) holds every key, so of those only the command line's own settings are weighed.
  core::Model weighed = m;
  if (!path.empty() && written_by_siloscope(path))
    for (auto it = weighed.scene.origin.begin(); it != weighed.scene.origin.end();)
      it = it->second.rfind("--", 0) == 0 ? std::next(it) : weighed.scene.origin.erase(it);
  for (const auto& w : core::ineffective_keys(weighed))
    std::fprintf(stderr, "siloscope: warning: %s\n", w.c_str());
  return m;
}

std::string command_line() {
  return g_command;
}

void set_command_line(int argc, char** argv) {
  g_command.clear();
  // The program as its name, not the path it was started by: a figure's footer or a run's metadata names no
  // directory of the machine that made it.
  for (int i = 0; i < argc; ++i) g_command += i ? " " + std::string(argv[i]) : std::string("siloscope");
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

CLI::Validator number_in(double lo, double hi, const std::string& unit) {
  const std::string allowed =
      "a number from " + core::format_g(lo) + " to " + core::format_g(hi) + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [lo, hi, allowed](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
          return "'" + s + "' is not allowed; expected " + allowed;
        if (v < lo || v > hi) return s + " is out of range; expected " + allowed;
        return "";
      },
      "NUMBER", "number_in");
}

}  // namespace app
