// The window's session written down as a script (ui/inspector.h): the state the pictures depend on as script
// lines, the recorder that appends what changed, and saving it.
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "render/palette.h"
#include "ui/inspector.h"

namespace ui {

namespace {
std::string num(double v) {
  return core::format_shortest(v);
}

// The overlay's elements as the `overlay` line that sets exactly them.
std::string overlay_spec(const render::OverlayOptions& o) {
  const std::pair<bool, const char*> items[] = {
      {o.time, "time"},       {o.counts, "counts"}, {o.rate, "rate"},         {o.timer, "timer"},
      {o.arch, "arch"},       {o.legend, "legend"}, {o.scale, "scale"},       {o.events, "events"},
      {o.zoombox, "zoombox"}, {o.plot, "plot"},     {o.colorbar, "colorbar"}, {o.ids, "ids"}};
  std::string spec;
  for (const auto& [on, name] : items)
    if (on) spec += (spec.empty() ? "" : ",") + std::string(name);
  return spec.empty() ? "none" : spec;
}

// The colouring as the `color` line that sets it: the mode, its scale's range, the displacement's reference.
std::string color_line(const render::Style& s) {
  std::string line = std::string("color ") + render::color_mode_name(s.color);
  const std::string lo = num(s.color_min) + ":";
  switch (s.color) {
    case render::ColorMode::Speed:
      return line + " " + lo + num(s.speed_max);
    case render::ColorMode::Force:
      return line + " " + lo + num(s.force_max);
    case render::ColorMode::Coordination:
      return line + " " + lo + num(s.coordination_max);
    case render::ColorMode::Stress:
      return line + " " + lo + num(s.stress_max);
    case render::ColorMode::Displacement:
      return line + " " + (s.displacement_max > 0 ? lo + num(s.displacement_max) : "auto") + " from " +
             num(s.displacement_from);
    default:
      return line;
  }
}

// The key of a line a run of changes is merged on: "goto frame", "zoom to", "pan to" (the state's value
// changes, the command stays).
bool mergeable(const std::string& a, const std::string& b) {
  for (const char* key : {"goto frame ", "zoom to ", "pan to "})
    if (a.rfind(key, 0) == 0 && b.rfind(key, 0) == 0) return true;
  return false;
}
}  // namespace

std::vector<std::string> Inspector::state_lines() const {
  std::vector<std::string> lines;
  lines.push_back("goto frame " + std::to_string(frame_));
  lines.push_back("zoom " + camera.text);
  lines.push_back("zoom to " + num(zoom));
  lines.push_back("pan to " + num(pan.x) + " " + num(pan.y));
  lines.push_back(std::string("palette ") +
                  (style.palette == render::Palette::ColorBlind ? "colorblind" : "paper"));
  lines.push_back(color_line(style));
  lines.push_back(std::string("colormap ") + render::colormap_name(style.colormap));
  lines.push_back(style.show_arch ? "arch on" : "arch off");
  lines.push_back(style.arch_forces ? "arch forces on" : "arch forces off");
  lines.push_back(style.chains ? "chains " + num(style.chain_min) + ":" + num(style.chain_max)
                               : "chains off");
  lines.push_back("overlay " + overlay_spec(overlay));
  lines.push_back(std::string("background ") + (style.dark ? "dark" : "white"));
  lines.push_back("font-scale " + num(overlay.font_scale));
  std::string colors;
  for (size_t k = 0; k < overlay_data.species_colors.size() && k < overlay_data.species_names.size(); ++k)
    if (overlay_data.species_colors[k].a > 0)
      colors += (colors.empty() ? "" : ",") + overlay_data.species_names[k] + "=" +
                render::hex_rgb(overlay_data.species_colors[k]);
  lines.push_back("species-color " + (colors.empty() ? std::string("scene") : colors));
  std::string ids;
  for (int id : style.tracked) ids += (ids.empty() ? "" : ",") + std::to_string(id);
  lines.push_back("track " + (ids.empty() ? std::string("off") : ids));
  lines.push_back(selected < 0 ? "select off" : "select " + std::to_string(selected));
  return lines;
}

void Inspector::sync_history() {
  const std::vector<std::string> now = state_lines();
  if (!session_started_) {
    // The session starts from the whole state the window opened with (flags included); chains are left out
    // when off and the run has no contacts (the line would be refused nowhere, but says nothing).
    session_started_ = true;
    history_.clear();
    for (const auto& line : now)
      if (line != "chains off" || traj_.has_contacts()) history_.push_back(line);
    recorded_ = now;
    synced_tail_ = false;
    return;
  }
  if (now == recorded_) return;
  for (size_t k = 0; k < now.size(); ++k) {
    // A camera line resets zoom and pan (lines 2 and 3): they follow it whenever it is written.
    const bool after_camera = (k == 2 || k == 3) && now[1] != recorded_[1];
    if (now[k] == recorded_[k] && !after_camera) continue;
    if (synced_tail_ && !history_.empty() && mergeable(history_.back(), now[k]))
      history_.back() = now[k];
    else
      history_.push_back(now[k]);
    synced_tail_ = true;
  }
  recorded_ = now;
}

void Inspector::log(const std::string& command) {
  history_.push_back(command);
  synced_tail_ = false;
  if (session_started_) recorded_ = state_lines();
}

std::string Inspector::save_session(const std::string& pattern, const std::string& trajectory_name) {
  if (!files_) throw core::InputError("this inspector has nowhere to write files");
  const std::string path = output_name(pattern, "save " + pattern);
  std::string text = "# siloscope inspector session on " + trajectory_name +
                     "\n# replay: siloscope inspect " + trajectory_name + " --script " + path + "\n";
  for (const auto& line : history_) text += line + "\n";
  files_->write_text(path, text);
  last_output = path;
  return path;
}

}  // namespace ui
