#include "app/services/looks.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"
#include "core/format.h"

namespace app {

void LookOptions::add_to(CLI::App& cmd) {
  cmd.add_option(
      "--force-chains", chains,
      "draw the contact network: a segment between the centres of each pair in contact whose normal "
      "force is at least MIN newtons, width and colour growing with the force up to MAX (MIN or "
      "MIN:MAX; e.g. 2 or 2:30; MAX default 20)");
  cmd.add_option("--background", background, "white, or dark (light walls and text: projectors, dark slides)")
      ->capture_default_str();
  cmd.add_option("--font-scale", font_scale,
                 "text size over the default (1/42 of the picture's height); 1.5-2 for a projector")
      ->capture_default_str();
  cmd.add_option(
         "--track", track,
         "follow these grains (ids, comma-separated; the inspector's panel and the exports show ids): a "
         "green ring and a trail of their last --trail seconds")
      ->delimiter(',');
  cmd.add_option("--trail", trail_s, "length of the tracked grains' trails, s")->capture_default_str();
}

void LookOptions::apply(int n_grains, bool transparent, render::Style& style,
                        render::OverlayOptions& overlay) const {
  const auto num = [](double v) { return core::format_g(v, 6); };
  if (background != "white" && background != "dark")
    throw core::InputError("--background " + background + ": expected white or dark");
  style.dark = background == "dark";
  if (transparent && style.dark)
    throw core::InputError(
        "--background dark and --transparent: choose one (a transparent frame has no background)");
  if (!(font_scale >= 0.5 && font_scale <= 4))
    throw core::InputError("--font-scale " + num(font_scale) + ": allowed range is 0.5 to 4");
  overlay.font_scale = font_scale;
  if (!(trail_s >= 0 && trail_s <= 1000))
    throw core::InputError("--trail " + num(trail_s) + ": allowed range is 0 to 1000 s");
  style.trail_s = trail_s;
  for (const auto& id : track) {
    char* end = nullptr;
    const long v = std::strtol(id.c_str(), &end, 10);
    if (id.empty() || *end != '\0' || v < 0 || v >= n_grains)
      throw core::InputError("--track " + id + ": expected grain ids from 0 to " +
                             std::to_string(n_grains - 1) + " (this scene has " + std::to_string(n_grains) +
                             " grains), comma-separated");
    style.tracked.push_back(static_cast<int>(v));
  }
  if (chains.empty()) return;
  // --force-chains MIN[:MAX] (N): contacts at least MIN drawn, width and colour growing up to MAX.
  const size_t colon = chains.find(':');
  char* end = nullptr;
  const double lo = std::strtod(chains.c_str(), &end);
  double hi = style.chain_max;
  bool ok = end != chains.c_str() && (*end == '\0' || *end == ':') && lo >= 0 && std::isfinite(lo);
  if (ok && colon != std::string::npos) {
    const char* s = chains.c_str() + colon + 1;
    hi = std::strtod(s, &end);
    ok = end != s && *end == '\0' && std::isfinite(hi);
  }
  if (!ok || !(hi > lo))
    throw core::InputError(
        "--force-chains " + chains +
        ": expected MIN or MIN:MAX in N with 0 <= MIN < MAX (e.g. 2 or 2:30; MAX default " +
        num(style.chain_max) + ")");
  style.chains = true;
  style.chain_min = lo;
  style.chain_max = hi;
}

io::Facts LookOptions::facts(const render::Style& style) const {
  std::string ids;
  for (int id : style.tracked) ids += (ids.empty() ? "" : ",") + std::to_string(id);
  return {{"background", background},
          {"font_scale", font_scale},
          {"tracked_grains", ids},
          {"trail_s", style.trail_s},
          {"force_chains", style.chains},
          {"force_chain_min_N", style.chain_min},
          {"force_chain_max_N", style.chain_max}};
}

}  // namespace app
