// libFuzzer target: campaign files. The base scene is resolved next to the (virtual) campaign file, in the
// source tree, so `scene = "paper.toml"` and friends are reachable.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/services/campaign.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    app::Campaign c = app::parse_campaign(text, SILOSCOPE_SOURCE_DIR "/assets/campaigns/fuzz.toml");
    for (size_t p = 0; p < c.points.size() && p < 4; ++p)
      (void)c.realization_seed(p, 0), (void)c.run_dir(p, 0);
  } catch (const core::InputError&) {
  }
  return 0;
}
