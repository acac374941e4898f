// siloscope scene --keys | scene FILE [--set k=v ...]: every scene key with its unit, default, range and
// meaning; or a scene file validated and resolved (what the file and --set made of it, and the derived
// facts).
#include <chrono>
#include <cstdio>

#include "app/services/cli.h"
#include "app/services/process.h"
#include "app/services/run_outputs.h"
#include "app/services/terminal.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"
#include "sim/silo.h"

namespace app {

namespace {
struct SceneCmdOptions {
  SceneOptions scene;
  bool keys = false;
  bool no_settle = false;
};

template <class F, class S>
std::string range_of(const F& f) {
  return std::visit(
      [&](auto ptr) -> std::string {
        using T = std::decay_t<decltype(S{}.*ptr)>;
        if constexpr (std::is_same_v<T, bool>)
          return "true|false";
        else if constexpr (std::is_same_v<T, std::string>)
          return f.choices ? f.choices : "text";
        else if constexpr (std::is_integral_v<T>) {
          // Whole numbers as whole numbers, at most TOML's largest integer (the seed's bound is 2^63 - 1, not
          // 2^63 as the double holds it).
          const auto whole = [](double v) {
            constexpr long long top = std::numeric_limits<long long>::max();
            return v >= static_cast<double>(top) ? top : static_cast<long long>(v);
          };
          return "[" + std::to_string(whole(f.min)) + ", " + std::to_string(whole(f.max)) + "]";
        } else
          return "[" + core::format_g(f.min, 15) + ", " + core::format_g(f.max, 15) +
                 "]";  // 0.02, not 0.0200...04
      },
      f.ptr);
}

// One key per line, at most 100 columns: key, default, unit, allowed, then the meaning, wrapped under itself
// when it does not fit.
void key_line(const std::string& key, const std::string& def, const char* unit, const std::string& allowed,
              const std::string& doc) {
  const std::string u = (unit && *unit && std::string(unit) != "1") ? unit : "";
  const std::string value = u.empty() ? def : def + " " + u;
  char head[160];
  std::snprintf(head, sizeof head, "  %-21s %-16s %-16s", key.c_str(), value.c_str(), allowed.c_str());
  std::string line = head;
  const size_t width = 100, indent = line.size() + 1;
  // The meaning in the room left, wrapped at blanks under its own first word.
  std::string rest = doc;
  bool first = true;
  while (!rest.empty()) {
    const size_t room = width - indent;
    size_t take = rest.size();
    if (take > room) {
      take = rest.rfind(' ', room);
      if (take == std::string::npos || take == 0) take = room;
    }
    std::printf("%s %s\n", first ? line.c_str() : std::string(indent - 1, ' ').c_str(),
                rest.substr(0, take).c_str());
    first = false;
    rest = take < rest.size() ? rest.substr(take + (rest[take] == ' ' ? 1 : 0)) : "";
  }
  if (first) std::printf("%s\n", line.c_str());
}

int scene_cmd(const SceneCmdOptions& o) {
  if (o.keys) {
    const core::Scene defaults;
    std::printf(
        "siloscope scene keys by section: key, default, unit, allowed, meaning (SI units, angles in\n"
        "degrees). A scene file sets them as `key = value`; the command line as --set key=value.\n");
    const std::pair<const char*, const char*> sections[] = {
        {"particles", "[[species]] tables replace the paper's radius_original, size_ratio, chi, mu"},
        {"container", "the outlet is centred at x = 0, y = 0"},
        {"drive", "random kicks, a harmonically vibrated container, both or none"},
        {"protocol", "settling, clogs, arches, re-injection"},
        {"numerics", "chosen by the speed-versus-accuracy study (docs/accuracy)"},
        {"run", ""}};
    for (const auto& [name, about] : sections) {
      std::printf("\n[%s]%s%s\n", name, *about ? "  " : "", about);
      for (const auto& f : core::scene_fields())
        if (std::string(f.section) == name)
          key_line(f.key, core::field_text(defaults, f), f.unit, range_of<core::Field, core::Scene>(f),
                   f.doc);
    }
    std::printf("\n[[species]]  one table per species (a scene file), or --set species.NAME.KEY=VALUE\n");
    const core::SpeciesSpec sp;
    for (const auto& f : core::species_fields()) {
      std::string def = core::species_field_text(sp, f);
      if (def.empty()) def = "(scene's)";
      key_line(f.key, def, f.unit, range_of<core::SpeciesField, core::SpeciesSpec>(f), f.doc);
    }
    return 0;
  }
  if (o.scene.path.empty())
    throw core::InputError("scene: give a scene file to check, or --keys to list every key");
  const core::Model model = o.scene.compile();
  const core::Scene& s = model.scene;
  // The checks run makes before its discharge need the grains deposited and settled (every grain below the
  // top, the health monitor content): done here too, so that a scene called valid is one run accepts.
  std::string settled = " (not settled: --no-settle)";
  if (!o.no_settle) {
    const auto t0 = std::chrono::steady_clock::now();
    { const sim::Silo world(model); }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    settled = " (deposited and settled as run does, " + core::format_g(wall, 2) + " s: every grain fits)";
  }
  std::printf("# %s is valid%s. Resolved scene (file, then --set, --seed, --duration):\n%s\n[derived]\n",
              o.scene.path.c_str(), settled.c_str(), core::scene_toml(s).c_str());
  if (!o.scene.path.empty() && s.species.empty() && s.origin.empty())
    std::printf("# (the file sets no key: every key has its default, the paper's scene)\n");
  for (const auto& f : io::derived_facts(model)) std::printf("%s = %s\n", f.key().c_str(), f.toml().c_str());
  return 0;
}
}  // namespace

void define_scene_command(CLI::App& command, Action& action) {
  auto o = std::make_shared<SceneCmdOptions>();
  CLI::App* cmd = &command;
  o->scene.add_to(*cmd, false);
  cmd->add_flag("--keys", o->keys, "list every key: unit, default, allowed values, meaning");
  cmd->add_flag(
      "--no-settle", o->no_settle,
      "check the keys only: do not deposit and settle the grains (run's own checks after settling are "
      "then not made)");
  cmd->callback([o, &action] { action = [o] { return scene_cmd(*o); }; });
}

}  // namespace app
