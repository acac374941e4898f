// libFuzzer target: the scene parser, overrides and validation must answer any input with a value or a
// core::InputError, never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    core::Scene s = core::parse_scene(text, "fuzz.toml");
    core::validate(s);
    // The same bytes as command-line overrides, one per line.
    std::vector<std::string> sets;
    size_t start = 0;
    for (size_t i = 0; i <= text.size(); ++i)
      if (i == text.size() || text[i] == '\n') sets.push_back(text.substr(start, i - start)), start = i + 1;
    core::apply_overrides(s, sets);
    core::validate(s);
    (void)core::scene_toml(s);
  } catch (const core::InputError&) {
  }
  return 0;
}
