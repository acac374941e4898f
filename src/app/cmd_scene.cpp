// siloscope scene --keys | scene FILE [--set k=v ...]: every scene key with its unit, default, range and
// meaning; or a scene file validated and resolved (what the file and --set made of it, and the derived
// facts).
#include <cstdio>

#include "app/common.h"
#include "core/error.h"
#include "core/format.h"
#include "io/metadata.h"

namespace app {

namespace {
struct SceneCmdOptions {
  SceneOptions scene;
  bool keys = false;
};

std::string range_of(const core::Field& f) {
  return std::visit(
      [&](auto ptr) -> std::string {
        using T = std::decay_t<decltype(core::Scene{}.*ptr)>;
        if constexpr (std::is_same_v<T, bool>)
          return "true|false";
        else if constexpr (std::is_same_v<T, std::string>)
          return f.choices ? f.choices : "";
        else
          return "[" + core::format_g(f.min, 10) + ", " + core::format_g(f.max, 20) + "]";
      },
      f.ptr);
}

int scene_cmd(const SceneCmdOptions& o) {
  if (o.keys) {
    const core::Scene defaults;
    std::printf("%-22s %-8s %-14s %-26s %s\n", "key", "unit", "default", "allowed", "meaning");
    for (const auto& f : core::scene_fields()) {
      const std::string unit = (f.unit && *f.unit) ? f.unit : "-";
      std::printf("%-22s %-8s %-14s %-26s %s\n", f.key, unit.c_str(), core::field_text(defaults, f).c_str(),
                  range_of(f).c_str(), f.doc);
    }
    return 0;
  }
  if (o.scene.path.empty())
    throw core::InputError("scene: give a scene file to check, or --keys to list every key");
  const core::Scene s = o.scene.load();
  std::printf("# %s is valid. Resolved scene (file, then --set, --seed, --duration):\n%s\n[derived]\n",
              o.scene.path.c_str(), core::scene_toml(s).c_str());
  for (const auto& f : io::derived_facts(s)) std::printf("%s = %s\n", f.key().c_str(), f.toml().c_str());
  return 0;
}
}  // namespace

void add_scene_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<SceneCmdOptions>();
  auto* cmd =
      app.add_subcommand("scene", "list every scene key (--keys), or validate and resolve a scene file");
  cmd->set_version_flag("--version", io::version_string());
  o->scene.add_to(*cmd, false);
  cmd->add_flag("--keys", o->keys, "list every key: unit, default, allowed values, meaning");
  cmd->callback([o, &action] { action = [o] { return scene_cmd(*o); }; });
}

}  // namespace app
