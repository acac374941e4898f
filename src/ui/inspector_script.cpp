// The inspector's script language (docs/inspector.md): each line parsed into one of the Inspector's typed
// actions (ui/inspector.h), which do the work and log the line that repeats them.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/interrupt.h"
#include "render/camera.h"
#include "render/palette.h"
#include "ui/inspector.h"

namespace ui {

namespace {
long to_long(const std::string& s, const char* what) {
  char* end = nullptr;
  long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end) throw core::InputError(std::string(what) + " '" + s + "' is not a whole number");
  return v;
}
double to_double(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !std::isfinite(v))
    throw core::InputError(std::string(what) + " '" + s + "' is not a number");
  return v;
}
const char* kCommands =
    "goto, step, next, prev, zoom, pan, camera-path, color, colormap, chains, palette, overlay, arch, track, "
    "freeze, select, snapshot, export, print, clogs, background, font-scale, species-color, branch, remove, "
    "kick, set, continue, save";

// A script line's words, a comment cut off.
std::vector<std::string> words_of(const std::string& line) {
  std::stringstream ss(line);
  std::vector<std::string> a;
  for (std::string word; ss >> word;) {
    if (word[0] == '#') break;
    a.push_back(word);
  }
  return a;
}
}  // namespace

void Inspector::execute(const std::string& line, Painter* painter) {
  const std::vector<std::string> a = words_of(line);
  if (a.empty()) return;
  const std::string& cmd = a[0];
  auto need = [&](size_t n, const char* usage) {
    if (a.size() != n + 1) throw core::InputError(std::string("usage: ") + usage);
  };
  try {
    if (cmd == "goto") {
      if (a.size() == 2 && a[1] == "start") return goto_start();
      if (a.size() == 2 && a[1] == "end") return goto_end();
      if (a.size() == 4 && a[1] == "clog" && a[3] == "arch") return goto_clog_arch(to_long(a[2], "clog"));
      need(2, "goto frame N | goto time T | goto clog K [arch] | goto arch K | goto start | goto end");
      if (a[1] == "frame") return goto_frame(to_long(a[2], "frame"));
      if (a[1] == "time") return goto_time(to_double(a[2], "time"));
      if (a[1] == "clog") return goto_clog(to_long(a[2], "clog"));
      if (a[1] == "arch") return goto_arch(to_long(a[2], "arch"));
      throw core::InputError("goto frame|time|clog|arch|start|end");
    }
    if (cmd == "step") return need(1, "step N"), step_frames(to_long(a[1], "step"));
    if (cmd == "next" || cmd == "prev") {
      need(1, "next clog|arch | prev clog|arch");
      if (a[1] == "arch") return next_arch_change(cmd == "next");
      if (a[1] != "clog") throw core::InputError("usage: next clog|arch | prev clog|arch");
      return next_clog(cmd == "next");
    }
    if (cmd == "zoom") {
      if (a.size() == 3 && a[1] == "by") return zoom_by(to_double(a[2], "zoom factor"));
      if (a.size() == 3 && a[1] == "to") return zoom_to(to_double(a[2], "zoom"));
      need(1, "zoom hopper|outlet|split|window:X0,Y0,X1,Y1 | zoom by F | zoom to F");
      return set_camera(render::parse_camera(a[1]));
    }
    if (cmd == "pan") {
      if (a.size() == 4 && a[1] == "to") return pan_to(to_double(a[2], "X"), to_double(a[3], "Y"));
      return need(2, "pan DX DY | pan to X Y (metres)"), pan_by(to_double(a[1], "DX"), to_double(a[2], "DY"));
    }
    if (look_command(a, line)) return;
    if (cmd == "camera-path") {
      // camera-path T:CAMERA,... | off: pictures follow the key frames by each frame's time (record
      // --camera-path).
      need(1, "camera-path T:CAMERA,T:CAMERA,... | camera-path off");
      if (a[1] == "off") return path = {}, log("camera-path off");
      path = render::parse_camera_path(a[1]);
      return log("camera-path " + a[1]);
    }
    if (cmd == "freeze") {
      // freeze clog|rule SECONDS | off: clips hold the picture at each event (record --freeze).
      const char* form = "freeze clog|rule SECONDS | freeze off";
      if (a.size() == 2 && a[1] == "off") return freeze = {}, log("freeze off");
      if (a.size() != 3) throw core::InputError(std::string("usage: ") + form);
      freeze = render::parse_freeze(a[1], a[2], "freeze", form);
      return log("freeze " + a[1] + " " + a[2]);
    }
    if (cmd == "track") return track_command(a);
    if (cmd == "select") {
      need(1, "select ID|off");
      return select_grain(a[1] == "off" ? -1 : to_long(a[1], "grain id"));
    }
    if (cmd == "print") {
      if (a.size() == 1) return (void)print_frame();
      need(1, "print | print grain | print arch");
      if (a[1] == "grain") return (void)print_grain();
      if (a[1] == "arch") return (void)print_arch();
      throw core::InputError("usage: print | print grain | print arch");
    }
    if (cmd == "clogs") return (void)print_clogs();
    if (cmd == "snapshot") {
      if (a.size() < 2 || a.size() > 3) throw core::InputError("usage: snapshot FILE.png|.svg|.pdf [WxH]");
      int w = 1920, h = 1080;
      if (a.size() == 3) render::parse_size(a[2], "snapshot size", w, h);
      return (void)snapshot(a[1], w, h, painter);
    }
    if (cmd == "export") return export_command(a, painter);
    if (branch_command(a)) return;
  } catch (const core::InputError& e) {
    throw core::InputError("'" + line + "': " + e.what());
  }
  throw core::InputError("unknown command '" + cmd + "'; commands are " + kCommands);
}

// The look's commands (color, chains, colormap, palette, overlay, background, font-scale, species-color,
// arch, annotate): true when `a` was one.
bool Inspector::look_command(const std::vector<std::string>& a, const std::string& line) {
  const std::string& cmd = a[0];
  auto need = [&](size_t n, const char* usage) {
    if (a.size() != n + 1) throw core::InputError(std::string("usage: ") + usage);
  };
  if (cmd == "color") return color_command(a, line), true;
  if (cmd == "chains") {
    // chains MIN[:MAX] | off: the force chains (record --force-chains), from the run's contacts.sscon.
    need(1, "chains MIN[:MAX]|off (newtons)");
    if (a[1] == "off") return style.chains = false, log("chains off"), true;
    if (!traj_.has_contacts())
      throw core::InputError(
          "chains: this trajectory has no contacts beside it (contacts.sscon: record and run "
          "--trajectory-fps write one; runs made before they did have none)");
    render::set_chains(style, a[1], "chains");
    return log("chains " + a[1]), true;
  }
  if (cmd == "colormap")
    return need(1, "colormap viridis|magma|inferno|cividis"), style.colormap = render::parse_colormap(a[1]),
                                                              log("colormap " + a[1]), true;
  if (cmd == "palette")
    return need(1, "palette paper|colorblind"), set_palette(render::parse_palette(a[1]), a[1]), true;
  if (cmd == "overlay")
    return need(1, "overlay all|none|time,counts,rate,timer,arch,legend,scale"), set_overlay(a[1]), true;
  if (cmd == "background") {
    need(1, "background white|dark");
    if (a[1] != "white" && a[1] != "dark") throw core::InputError("usage: background white|dark");
    style.dark = a[1] == "dark";
    return log("background " + a[1]), true;
  }
  if (cmd == "font-scale") {
    need(1, "font-scale F (0.5 to 4)");
    const double f = to_double(a[1], "font-scale");
    if (!(f >= 0.5 && f <= 4)) throw core::InputError("font-scale " + a[1] + ": allowed range is 0.5 to 4");
    overlay.font_scale = f;
    return log("font-scale " + a[1]), true;
  }
  if (cmd == "species-color") return species_color_command(a), true;
  if (cmd == "arch") {
    // arch on|off: the halo and bonds; arch forces on|off: the arrows of the forces on it from outside.
    if (a.size() == 3 && a[1] == "forces" && (a[2] == "on" || a[2] == "off")) {
      if (a[2] == "on") require_contact_forces("arch forces");
      style.arch_forces = a[2] == "on";
      return log(line), true;
    }
    if (a.size() != 2 || (a[1] != "on" && a[1] != "off"))
      throw core::InputError("usage: arch on|off | arch forces on|off");
    return show_arch(a[1] == "on"), true;
  }
  if (cmd == "annotate") {
    // The note's text may hold spaces: everything after the command word.
    if (a.size() < 2) throw core::InputError("usage: annotate T0:T1:X,Y:TEXT | annotate off");
    if (a.size() == 2 && a[1] == "off") return notes.clear(), true;
    std::string spec;
    for (size_t k = 1; k < a.size(); ++k) spec += (k > 1 ? " " : "") + a[k];
    notes.push_back(render::parse_note(spec, "annotate"));
    return true;
  }
  return false;
}

void Inspector::require_contact_forces(const char* what) const {
  if (!traj_.has_contact_forces())
    throw core::InputError(std::string(what) +
                           ": this trajectory has no contact forces beside it (contacts.sscon of version 2, "
                           "with each contact's point and its walls' contacts: record and run "
                           "--trajectory-fps write one; runs made before have normal forces only, or none)");
}

void Inspector::color_command(const std::vector<std::string>& a, const std::string& line) {
  // color MODE [MAX|MIN:MAX|auto] [from T]: the mode, the scale's range (auto: each frame's largest
  // displacement; speed and force keep their defaults) and, for displacement, the reference time.
  const char* usage =
      "color species|speed|force|displacement|coordination|stress|id [MAX|MIN:MAX|auto] [from T]";
  if (a.size() < 2 || a.size() > 5) throw core::InputError(std::string("usage: ") + usage);
  const render::ColorMode m = render::parse_color_mode(a[1]);
  if (m == render::ColorMode::Stress) require_contact_forces("color stress");
  size_t k = 2;
  render::Style next = style;
  ColorMins mins = color_mins_;  // kept only if the line is taken
  switch_color(next, m, mins);
  if (k < a.size() && a[k] != "from") render::set_color_range(next, a[k++]);
  if (k < a.size()) {
    if (a[k] != "from" || k + 2 != a.size() || m != render::ColorMode::Displacement)
      throw core::InputError(std::string("usage: ") + usage + " (from T: displacement only)");
    next.displacement_from = to_double(a[k + 1], "from");
  }
  style = next;
  color_mins_ = mins;
  return set_color(m, line.substr(line.find_first_not_of(" \t") + 6));
}

void Inspector::species_color_command(const std::vector<std::string>& a) {
  // species-color NAME=#rrggbb[,NAME=#rrggbb...] | scene: each named species' colour (as --species-color);
  // scene: the scene's own colours again.
  const char* usage = "species-color NAME=#rrggbb[,NAME=#rrggbb...] | species-color scene";
  if (a.size() != 2) throw core::InputError(std::string("usage: ") + usage);
  std::vector<render::Rgba> colors = render::overlay_data_for(model_).species_colors;
  colors.resize(overlay_data.species_names.size(), render::Rgba{0, 0, 0, 0});
  if (a[1] != "scene") {
    std::stringstream items(a[1]);
    for (std::string item; std::getline(items, item, ',');) {
      const size_t eq = item.find('=');
      const std::string name = item.substr(0, eq);
      const auto it = std::find(overlay_data.species_names.begin(), overlay_data.species_names.end(), name);
      std::array<float, 3> rgb{};
      if (eq == std::string::npos || it == overlay_data.species_names.end() ||
          !core::parse_hex_color(item.substr(eq + 1), rgb))
        throw core::InputError("species-color " + item +
                               ": expected NAME=#rrggbb with NAME a species of the run");
      colors[static_cast<size_t>(it - overlay_data.species_names.begin())] = {rgb[0], rgb[1], rgb[2], 1};
    }
  }
  overlay_data.species_colors = colors;
  log("species-color " + a[1]);
}

void Inspector::track_command(const std::vector<std::string>& a) {
  auto need = [&](size_t n, const char* usage) {
    if (a.size() != n + 1) throw core::InputError(std::string("usage: ") + usage);
  };
  // track IDS (comma-separated) | off: a ring and a trail of the last 2 s on each, as record --track.
  // track region X0,Y0,X1,Y1 | track arch K | track clog K: tagged by region or role
  // (Inspector::track_*).
  if (a.size() == 3 && a[1] == "region") {
    double x0, y0, x1, y1;
    char tail = 0;
    if (std::sscanf(a[2].c_str(), "%lf,%lf,%lf,%lf%c", &x0, &y0, &x1, &y1, &tail) != 4)
      throw core::InputError("usage: track region X0,Y0,X1,Y1 (metres)");
    return track_region(x0, y0, x1, y1);
  }
  if (a.size() == 3 && (a[1] == "arch" || a[1] == "clog"))
    return track_arch_of(a[1] == "clog", to_long(a[2], "K"));
  need(1, "track ID[,ID...]|off | track region X0,Y0,X1,Y1 | track arch K | track clog K");
  style.tracked.clear();
  if (a[1] == "off") return;
  const long n = static_cast<long>(traj_.frame(frame_).particles.size());
  std::stringstream ids(a[1]);
  for (std::string id; std::getline(ids, id, ',');) {
    const long v = to_long(id, "ID");
    if (v < 0 || v >= n)
      throw core::InputError("track: grain " + id + " does not exist; ids run from 0 to " +
                             std::to_string(n - 1));
    style.tracked.push_back(static_cast<int>(v));
  }
  return;
}

// The "what if" lines (ui/inspector_branch.cpp): true when `a` was one.
bool Inspector::branch_command(const std::vector<std::string>& a) {
  const std::string& cmd = a[0];
  auto need = [&](size_t n, const char* usage) {
    if (a.size() != n + 1) throw core::InputError(std::string("usage: ") + usage);
  };
  if (cmd == "branch") {
    if (a.size() == 2 && a[1] == "off") return branch_off(), true;
    need(2, "branch at FRAME | branch off");
    if (a[1] != "at") throw core::InputError("usage: branch at FRAME | branch off");
    return branch_at(to_long(a[2], "frame")), true;
  }
  if (cmd == "remove") {
    need(2, "remove grain ID");
    if (a[1] != "grain") throw core::InputError("usage: remove grain ID");
    return branch_remove(to_long(a[2], "grain id")), true;
  }
  if (cmd == "kick") return need(1, "kick DV (m/s)"), branch_kick(to_double(a[1], "kick")), true;
  if (cmd == "set")
    return need(2, "set kick_impulse_max J | set mu M | set species.NAME.dipole M"),
           branch_set(a[1], to_double(a[2], a[1].c_str())), true;
  if (cmd == "continue")
    return need(1, "continue SECONDS"), branch_continue(to_double(a[1], "continue")), true;
  if (cmd == "save") {
    need(2, "save branch DIR");
    if (a[1] != "branch") throw core::InputError("usage: save branch DIR");
    return (void)save_branch(a[2]), true;
  }
  return false;
}

void Inspector::export_command(const std::vector<std::string>& a, Painter* painter) {
  const bool clog = a.size() >= 3 && a[1] == "clog";
  if (clog ? a.size() > 5 : (a.size() < 4 || a.size() > 6))
    throw core::InputError(
        clog ? "usage: export clog FILE.mp4 [WxH] [FPS]"
             : "usage: export FILE.mp4 FROM TO [WxH] [FPS] | export clog FILE.mp4 [WxH] [FPS]");
  const size_t opt = clog ? 3 : 4;  // index of the first optional argument
  int width = 1280, height = 720;
  if (a.size() > opt) render::parse_size(a[opt], "export size", width, height);
  const int fps = a.size() > opt + 1
                      ? static_cast<int>(to_long(a[opt + 1], "FPS"))
                      : std::max(1, static_cast<int>(std::lround(1.0 / traj_.frame_interval())));
  if (clog)
    export_clog(a[2], width, height, fps, painter);
  else
    export_frames(a[1], to_long(a[2], "FROM"), to_long(a[3], "TO"), width, height, fps, painter);
}

int run_script(Inspector& insp, Painter& painter, const std::string& path) {
  core::check_text_file(path, "inspector script", "");
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot open script");
  int line_no = 0, commands = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    core::throw_if_interrupted();
    try {
      const size_t before = line.find_first_not_of(" \t");
      if (before == std::string::npos || line[before] == '#') continue;
      insp.execute(line, &painter);
      ++commands;
    } catch (const core::InputError& e) {
      throw core::InputError(path + ":" + std::to_string(line_no) + ": " + e.what());
    }
  }
  return commands;
}

}  // namespace ui
