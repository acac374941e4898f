// The inspector: trajectories, scripts, the ImGui panels under synthetic input, and the window under Xvfb.
#include <catch2/catch.hpp>

#include <imgui.h>
#include <sys/wait.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <functional>
#include <set>
#include "app/services/inspect_files.h"
#include "app/services/live_silo.h"
#include "core/error.h"
#include "core/format.h"
#include "fixtures.h"
#include "helpers.h"
#include "io/contacts.h"
#include "io/metadata.h"
#include "io/trajectory.h"
#include "render/camera.h"
#include "render/context.h"
#include "render/palette.h"
#include "ui/inspector.h"
#include "ui/live_panel.h"
#include "ui/panels.h"

bool ImGui_ImplOpenGL3_Init(const char* glsl_version);
void ImGui_ImplOpenGL3_Shutdown();
void ImGui_ImplOpenGL3_NewFrame();

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {
using test::kBin;
using test::sh;
fs::path temp_dir(const std::string& name) {
  return test::temp_dir("ui_" + name);
}

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> px;
  const unsigned char* at(int x, int y) const { return &px[(static_cast<size_t>(y) * w + x) * 4]; }
};
Png read_png(const fs::path& p) {
  Png img;
  int n = 0;
  unsigned char* d = stbi_load(p.c_str(), &img.w, &img.h, &n, 4);
  REQUIRE(d);
  img.px.assign(d, d + static_cast<size_t>(img.w) * img.h * 4);
  stbi_image_free(d);
  return img;
}
bool near(const unsigned char* px, render::Rgba c, int tol = 10) {
  return std::abs(px[0] - c.r * 255) <= tol && std::abs(px[1] - c.g * 255) <= tol &&
         std::abs(px[2] - c.b * 255) <= tol;
}

core::Scene two_disk_scene() {
  core::Scene s;
  core::apply_overrides(s, {"n_total=2", "chi=0.5"});
  return s;
}

render::OffscreenContext& gl() {
  static render::OffscreenContext ctx;
  return ctx;
}
}  // namespace

TEST_CASE("a script off-screen makes the expected images", "[ui]") {
  gl();
  fs::path d = temp_dir("script");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  const app::RecordFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  REQUIRE(insp.clogs().size() == 1);
  // The recording's events say the clog began at t = 0 and ended at frame 4 by the rule: frames 0 to 3.
  CHECK(insp.clogs()[0].first == 0);
  CHECK(insp.clogs()[0].last == 3);
  CHECK(insp.clog_caption(0) == "clog 1 of 1, 0.000-0.133 s, ended by the rule (arrested), arches.csv row 1");
  insp.execute("goto clog 1");  // its start
  CHECK(insp.frame_index() == 0);
  insp.execute("goto clog 1 arch");  // its final arch [0, 1] stands from frame 2 on
  CHECK(insp.frame_index() == 2);
  insp.execute("next arch");  // frame 4: the rule removed it
  CHECK(insp.frame_index() == 4);
  insp.execute("prev arch");
  CHECK(insp.frame_index() == 3);
  ui::Painter painter;
  std::ofstream(d / "fig.txt") << "# a figure\ngoto clog 1 arch\nstep 1\nzoom window:-0.5,0,0.5,1\noverlay "
                               << "none\nsnapshot " << (d / "a.png").string() << " 400x400\nstep -3\nprint\n"
                               << "snapshot " << (d / "b.png").string() << " 400x400\n";
  CHECK(ui::run_script(insp, painter, (d / "fig.txt").string()) == 8);
  CHECK(insp.frame_index() == 0);
  CHECK_THAT(insp.last_output, Contains("b.png"));  // the file the last command wrote
  insp.execute("print");
  CHECK_THAT(insp.last_output, Contains("frame 0"));
  const render::Style style;
  const Png a = read_png(d / "a.png"), b = read_png(d / "b.png");
  REQUIRE(a.w == 400);
  // Frame 3: the original disk at x = 0.1 m -> pixel 240; frame 0: at x = -0.2 m -> pixel 120. y = 0.5 m ->
  // row 200. In frame 3 the arch bond runs through the centres: sample 3 cm to the side of it.
  CHECK(near(a.at(228, 200), render::species_color(style.palette, core::Species::Original)));
  CHECK(near(a.at(120, 200), render::background_color(style)));
  CHECK(near(b.at(120, 200), render::species_color(style.palette, core::Species::Original)));
  CHECK(near(b.at(240, 200), render::background_color(style)));
  // The added disk at (0.2, 0.8) -> pixel (280, 80); in frame 3 it is an arch member with a gold halo.
  CHECK(near(a.at(286, 80), render::species_color(style.palette, core::Species::Added)));
  const double halo_px = 0.026 * 400 + 2;  // radius 10.4 px, then 2 px into the halo
  CHECK(near(a.at(280, static_cast<int>(80 + halo_px)), render::arch_color(style.palette), 60));
  CHECK(near(b.at(280, static_cast<int>(80 + halo_px)), render::background_color(style)));
}

TEST_CASE("script errors name the line, frames out of range are refused", "[ui]") {
  gl();
  fs::path d = temp_dir("script_err");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  const app::RecordFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  ui::Painter painter;
  std::ofstream(d / "bad.txt") << "goto frame 1\nzom outlet\n";
  CHECK_THROWS_WITH(ui::run_script(insp, painter, (d / "bad.txt").string()),
                    Contains("bad.txt:2: unknown command 'zom'"));
  std::ofstream(d / "range.txt") << "# ok\n\ngoto frame 99\n";
  CHECK_THROWS_WITH(ui::run_script(insp, painter, (d / "range.txt").string()),
                    Contains("range.txt:3") && Contains("out of range (0 to 4)"));
  CHECK_THROWS_WITH(insp.execute("goto clog 2"), Contains("1 clogs"));
  // A value the command cannot take is blamed on the script's line, not on a command-line flag.
  std::ofstream(d / "zoom.txt") << "zoom sideways\n";
  CHECK_THROWS_WITH(
      ui::run_script(insp, painter, (d / "zoom.txt").string()),
      Contains("zoom.txt:1: 'zoom sideways': camera 'sideways': expected hopper") && !Contains("--camera"));
  std::ofstream(d / "colors.txt") << "colormap rainbow\n";
  CHECK_THROWS_WITH(ui::run_script(insp, painter, (d / "colors.txt").string()),
                    Contains("colors.txt:1:") && Contains("colormap 'rainbow'") && !Contains("--colormap"));
  // The window's "go to" field: a frame, a time or a step.
  ui::go_to(insp, " 3 ");
  CHECK(insp.frame_index() == 3);
  ui::go_to(insp, "-2");
  CHECK(insp.frame_index() == 1);
  ui::go_to(insp, "+1");
  CHECK(insp.frame_index() == 2);
  ui::go_to(insp, "0.1 s");
  CHECK(insp.frame_index() == 3);
  CHECK_THROWS_WITH(ui::go_to(insp, "soon"), Contains("give a frame (120), a time (4.5 s) or a step"));
  CHECK_THROWS_WITH(ui::go_to(insp, "99"), Contains("out of range"));
  CHECK_THROWS_WITH(insp.execute("step -9"), Contains("out of range"));
  CHECK_THROWS_WITH(insp.execute("color rainbow"), Contains("color 'rainbow'") && !Contains("--color"));
  insp.execute("color displacement 0.5 from 0.1");
  CHECK(insp.style.color == render::ColorMode::Displacement);
  CHECK(insp.style.displacement_max == 0.5);
  CHECK(insp.style.displacement_from == 0.1);
  insp.execute("colormap inferno");
  CHECK(insp.style.colormap == render::Colormap::Inferno);
  insp.execute("color coordination 1:5");
  CHECK(insp.style.color_min == 1);
  CHECK_THROWS_WITH(insp.execute("color speed from 2"), Contains("displacement only"));
  CHECK_THROWS_WITH(insp.execute("color id 4"), Contains("not id"));
  CHECK_THROWS_WITH(insp.execute("color stress"), Contains("no contact forces beside it"));
  CHECK_THROWS_WITH(insp.execute("arch forces on"), Contains("no contact forces beside it"));
  CHECK_THROWS_WITH(insp.execute("arch forces"), Contains("usage: arch on|off | arch forces on|off"));
  insp.execute("arch forces off");
  CHECK_THROWS_WITH(insp.execute("colormap jet"), Contains("viridis, magma"));
  CHECK(insp.style.color == render::ColorMode::Coordination);  // a refused line changes nothing
  insp.execute("color species");
  CHECK_THROWS_WITH(insp.execute("track 0,7"), Contains("grain 7 does not exist; ids run from 0 to 1"));
  insp.execute("track 1");
  CHECK(insp.style.tracked == std::vector<int>{1});
  insp.execute("track off");
  CHECK(insp.style.tracked.empty());
  // Tags by role and region, found without moving: the arch shown before the rule's first removal (frame 3)
  // and the grains in a box in the current frame.
  insp.execute("goto frame 0");
  const size_t logged = insp.history().size();
  insp.execute("track arch 1");
  CHECK(insp.style.tracked == std::vector<int>{0, 1});
  CHECK(insp.frame_index() == 0);
  CHECK(insp.history().size() == logged + 1);
  CHECK(insp.history().back() == "track arch 1");
  insp.execute("track region 0.3,0.9,0.1,0.7");
  CHECK(insp.style.tracked == std::vector<int>{1});
  insp.execute("track clog 1");
  CHECK(insp.style.tracked == std::vector<int>{0, 1});
  CHECK_THROWS_WITH(insp.execute("track arch 2"), Contains("not in the trajectory"));
  CHECK_THROWS_WITH(insp.execute("track region 5,5,6,6"), Contains("no grain's centre is in the box"));
  CHECK_THROWS_WITH(insp.execute("track region 5,5"), Contains("track region X0,Y0,X1,Y1"));
  CHECK(insp.frame_index() == 0);
  insp.execute("track off");
}

TEST_CASE("snapshots and clips are named by frame and never written over and export clog cuts the clog",
          "[ui]") {
  gl();
  fs::path d = temp_dir("names");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  const app::RecordFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  ui::Painter painter;
  const std::string pattern = (d / "shot-{frame}-{t}.png").string();
  insp.execute("goto frame 3");
  insp.execute("snapshot " + pattern + " 64x64", &painter);
  const std::string first = insp.last_output;
  CHECK_THAT(first, Contains("shot-000003-"));
  CHECK(fs::exists(first));
  const auto size = fs::file_size(first);
  // The same frame again: refused, the first file untouched.
  CHECK_THROWS_WITH(insp.execute("snapshot " + pattern + " 64x64", &painter),
                    Contains("exists") && Contains("{frame}"));
  CHECK(fs::file_size(first) == size);
  std::ofstream(d / "mine.png") << "not siloscope's";
  CHECK_THROWS_WITH(insp.execute("snapshot " + (d / "mine.png").string(), &painter),
                    Contains("never writes over"));
  // export clog: the one clog (frames 2-3) with 1 s before and 0.5 s after, clamped to the trajectory (0-4).
  insp.execute("goto start");
  insp.execute("export clog " + (d / "clog-{frame}.mp4").string() + " 64x64", &painter);
  CHECK_THAT(insp.last_output, Contains("clog-000000.mp4") && Contains("(frames 0 to 4)"));
  CHECK(fs::exists(d / "clog-000000.mp4"));
  insp.execute("goto end");
  CHECK_THROWS_WITH(insp.execute("export clog " + (d / "late.mp4").string(), &painter),
                    Contains("no clog at or after"));
  CHECK_FALSE(fs::exists(d / "late.mp4"));
}

TEST_CASE("the live panel drags a key from 0 on the scale of its default, not of its range", "[ui]") {
  // Issue 56: a 20-pixel drag from 0 set kick_impulse_max to 4 N s (its range is 0 to 1000); its default is
  // 5e-5 N s.
  const double kick = ui::drag_step("kick_impulse_max", 0);
  CHECK(20 * kick == Approx(5e-6));
  CHECK(ui::drag_step("kick_impulse_max", 2e-4) == Approx(1e-6));  // 0.5% of the value, as before
  CHECK(ui::drag_step("mu", 0) > 0);                               // a key whose default is 0: its range's
  CHECK(ui::drag_step("mu", 0) < 1e-2);
}

TEST_CASE("a live run that fails after a restart names the edits it ran with", "[ui]") {
  // Issue 56: after a bad edit the error blamed the time step, not the edit.
  core::Scene a, b = a;
  core::set_field(b, "kick_impulse_max", "0.5", "test");
  core::set_field(b, "mu", "0.001", "test");
  const std::string edits = ui::edits_between(a, b);
  CHECK(edits.find("kick_impulse_max 5e-05 -> 0.5") != std::string::npos);
  INFO(edits);
  CHECK(edits.find("mu 0.0 -> 0.001") != std::string::npos);
  CHECK(ui::edits_between(a, a).empty());
  ui::LiveState st;
  CHECK(ui::blame_edits(st, "disk 3 moved 2 m in one step") == "disk 3 moved 2 m in one step");
  st.restart_edits = edits;
  const std::string m = ui::blame_edits(st, "disk 3 moved 2 m in one step");
  CHECK(m.rfind("the restart with kick_impulse_max", 0) == 0);
  CHECK(m.find("failed: disk 3 moved 2 m in one step") != std::string::npos);
}

TEST_CASE("synthetic ImGui input drives the panels: a button steps a frame, a slider zooms", "[ui]") {
  gl();
  fs::path d = temp_dir("panels");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  const app::RecordFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  ImGuiContext* ctx = ImGui::CreateContext();
  ImGui::SetCurrentContext(ctx);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(1280, 720);
  REQUIRE(ImGui_ImplOpenGL3_Init("#version 330 core"));
  ui::PanelState ps;
  auto frame = [&](ImVec2 mouse, bool down) {
    io.DeltaTime = 1.0f / 60;
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    ui::draw_panels(insp, ps, nullptr, 880, 400, 720, 672, 880, 48);
    ImGui::Render();
  };
  auto click = [&](const std::string& name, float fx = 0.5f) {
    REQUIRE(ps.rects.count(name));
    const auto r = ps.rects[name];
    ImVec2 p(r[0] + fx * (r[2] - r[0]), 0.5f * (r[1] + r[3]));
    frame(p, false);
    frame(p, true);
    frame(p, false);
  };
  frame(ImVec2(-1, -1), false);  // lay out once so the widgets have rectangles
  REQUIRE(insp.frame_index() == 0);
  click("step forward");
  CHECK(insp.frame_index() == 1);
  click("prev clog");  // the start of the clog (frame 0)
  CHECK(insp.frame_index() == 0);
  click("final arch");  // where its final arch first stands
  CHECK(insp.frame_index() == 2);
  click("next arch");
  CHECK(insp.frame_index() == 4);
  click("step back");
  CHECK(insp.frame_index() == 3);
  click("play to clog");  // no later clog: playback does not start
  CHECK_FALSE(ps.playing);
  click("step back");
  CHECK(insp.frame_index() == 2);
  click("zoom", 0.98f);
  CHECK(insp.zoom > 5.0);
  click("timeline", 0.999f);
  CHECK(insp.frame_index() == 4);
  // The panel keeps its place between a clogged frame (a wrapped caption) and a flowing one.
  frame(ImVec2(-1, -1), false);
  const float zoom_y_flowing = ps.rects.at("zoom")[1];
  insp.set_frame(1);
  REQUIRE(insp.clog_at(1) >= 0);
  frame(ImVec2(-1, -1), false);
  CHECK(ps.rects.at("zoom")[1] == zoom_y_flowing);
  // A grain's id typed and Return: selected, as `select ID`; "track off" shows while grains are tracked.
  insp.execute("track 1");
  frame(ImVec2(-1, -1), false);
  REQUIRE(ps.rects.count("track off"));
  click("track off");
  CHECK(insp.style.tracked.empty());
  io.KeyMap[ImGuiKey_Enter] = 257;  // as GLFW numbers it (no backend here)
  click("grain id");
  io.AddInputCharacter('1');
  frame(ImVec2(-1, -1), false);
  io.KeysDown[io.KeyMap[ImGuiKey_Enter]] = true;
  frame(ImVec2(-1, -1), false);
  io.KeysDown[io.KeyMap[ImGuiKey_Enter]] = false;
  frame(ImVec2(-1, -1), false);
  CHECK(insp.selected == 1);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(ctx);
}

namespace {
// A branch that only records what the panel asked of it (the app's re-simulation: tests/ui/test_branch.cpp).
struct FakeBranch : ui::Branch {
  core::Frame f;
  std::vector<std::string> done;
  double t = 0;
  long k = 0;
  bool was_saved = false;
  long from_frame() const override { return k; }
  double time() const override { return t; }
  core::Frame frame() const override { return f; }
  void advance_to(double to) override { t = to; }
  void remove_grain(int id) override { done.push_back("remove " + std::to_string(id)); }
  void kick(double dv) override { done.push_back("kick " + core::format_g(dv, 3)); }
  void set_key(const std::string& k, double) override { done.push_back("set " + k); }
  std::vector<std::string> changes() const override { return done; }
  void save(const std::string& dir) override { was_saved = true, done.push_back("save " + dir); }
  bool saved() const override { return was_saved; }
};
struct FakeBrancher : ui::Brancher {
  const ui::FrameSource& frames;
  mutable FakeBranch* last = nullptr;
  explicit FakeBrancher(const ui::FrameSource& s) : frames(s) {}
  std::unique_ptr<ui::Branch> branch(long k) const override {
    auto b = std::make_unique<FakeBranch>();
    b->f = frames.frame(k);
    b->t = frames.time(k);
    b->k = k;
    last = b.get();
    return b;
  }
};
}  // namespace

TEST_CASE("the what-if tab's buttons branch, remove the selected grain, kick, continue and save", "[ui]") {
  gl();
  fs::path d = temp_dir("branch_panel");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  const app::RecordFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  const FakeBrancher brancher(frames);
  insp.set_brancher(&brancher);
  ImGuiContext* ctx = ImGui::CreateContext();
  ImGui::SetCurrentContext(ctx);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(1280, 720);
  REQUIRE(ImGui_ImplOpenGL3_Init("#version 330 core"));
  ui::PanelState ps;
  std::snprintf(ps.branch_path, sizeof ps.branch_path, "%s", (d / "b-{frame}").string().c_str());
  auto frame = [&](ImVec2 mouse, bool down) {
    io.DeltaTime = 1.0f / 60;
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    ui::draw_panels(insp, ps, nullptr, 880, 400, 720, 672, 880, 48);
    ImGui::Render();
  };
  auto click = [&](const std::string& name) {
    frame(ImVec2(-1, -1), false);
    INFO(name);
    REQUIRE(ps.rects.count(name));
    const auto r = ps.rects[name];
    ImVec2 p(0.5f * (r[0] + r[2]), 0.5f * (r[1] + r[3]));
    frame(p, false);
    frame(p, true);
    frame(p, false);
  };
  frame(ImVec2(-1, -1), false);  // a tab bar sizes its tabs from its second frame
  insp.goto_frame(3);
  click("what if tab");
  click("branch here");
  REQUIRE(insp.branch());
  CHECK(insp.branch()->from_frame() == 3);
  CHECK(insp.history().back() == "branch at 3");
  insp.select_grain(1);
  click("remove grain");
  click("kick now");
  const double t0 = insp.branch()->time();
  click("continue 1 s");
  CHECK(insp.branch()->time() == Approx(t0 + 1));
  CHECK(insp.frame_index() == 4);  // the recording followed the branch's clock
  click("save branch");
  REQUIRE(brancher.last);
  const std::vector<std::string> want = {"remove 1", "kick 0.2", "save " + (d / "b-000004").string()};
  CHECK(brancher.last->done == want);
  CHECK(ps.message == "wrote " + (d / "b-000004").string());
  // The session holds the lines that make it again.
  const std::vector<std::string>& h = insp.history();
  CHECK(std::find(h.begin(), h.end(), "remove grain 1") != h.end());
  CHECK(std::find(h.begin(), h.end(), "continue 1") != h.end());
  click("branch off");
  CHECK_FALSE(insp.branch());
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(ctx);
}

TEST_CASE("the window opens under Xvfb, draws the hopper and the panel, and says when there is no display",
          "[ui]") {
  fs::path d = temp_dir("window");
  REQUIRE(
      sh(kBin + " record " + std::string(SILOSCOPE_SOURCE_DIR) +
         "/assets/scenes/paper.toml --duration 1 --set settle_time=2 --size 320x240 --fps 10 --quiet --out " +
         (d / "rec").string()) == 0);
  const std::string shot = (d / "window.png").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' " + kBin + " inspect " + (d / "rec").string() +
             " --quiet --screenshot " + shot + " --frames 4") == 0);
  const Png w = read_png(shot);
  CHECK(w.w == 1280);
  CHECK(w.h == 720);
  long red = 0, panel = 0;
  const render::Rgba original = render::species_color(render::Palette::Paper, core::Species::Original);
  for (int y = 0; y < w.h; ++y)
    for (int x = 0; x < w.w; ++x) {
      const unsigned char* p = w.at(x, y);
      if (x < 880 && near(p, original, 12)) ++red;  // disks of the hopper in the scene area
      if (x > 900 && p[0] > 200 && p[0] < 250 && p[0] == p[1] && p[1] == p[2])
        ++panel;  // the panel's light grey
    }
  CHECK(red > 5000);
  CHECK(panel > 50000);
  // The live simulation in a window: it settles, runs and draws the hopper beside its panel.
  const std::string live = (d / "live.png").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' " + kBin + " live " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/assets/scenes/paper.toml --set settle_time=2 --screenshot " + live + " --frames 5") == 0);
  const Png l = read_png(live);
  long live_red = 0;
  for (int y = 0; y < l.h; ++y)
    for (int x = 0; x < 880; ++x) live_red += near(l.at(x, y), original, 12);
  CHECK(live_red > 5000);
  // Without a display: a clear message pointing to the scripted mode, exit 2.
  CHECK(sh("env -u DISPLAY -u WAYLAND_DISPLAY " + kBin + " inspect " + (d / "rec").string() + " > " +
           (d / "err.txt").string() + " 2>&1") == 2);
  std::ifstream in(d / "err.txt");
  std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK_THAT(err, Contains("no display") && Contains("--script"));
}

TEST_CASE("the inspector window idles without CPU and never loses a key tap (Xvfb, xdotool)", "[ui][heavy]") {
  fs::path d = temp_dir("window_keys");
  REQUIRE(
      sh(kBin + " record " + std::string(SILOSCOPE_SOURCE_DIR) +
         "/assets/scenes/paper.toml --duration 2 --set settle_time=2 --size 320x240 --fps 10 --quiet --out " +
         (d / "rec").string()) == 0);
  const std::string log = (d / "log.txt").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' bash " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/tests/ui/ui_keys.sh " + kBin + " " + (d / "rec").string() + " " + d.string() + " > " + log +
             " 2>&1") == 0);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  INFO(text);
  const auto at = text.find("idle_cpu_fraction ");
  REQUIRE(at != std::string::npos);
  const double idle = std::stod(text.substr(at + 18));
  CHECK(idle < 0.05);  // was 0.75-0.93 when the window redrew continuously
  CHECK_THAT(text, Contains("exit 0") && Contains("inspector closed at frame 5\n"));  // 5 quick taps, 5 steps
  CHECK_THAT(text, Contains("key to picture: median ") && Contains(" that changed the picture)"));
}

TEST_CASE(
    "the live window pauses without CPU, steps one frame and snapshots without overwriting (Xvfb, xdotool)",
    "[ui][heavy]") {
  fs::path d = temp_dir("live_keys");
  const std::string log = (d / "log.txt").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' bash " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/tests/ui/ui_live.sh " + kBin + " " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/assets/scenes/paper.toml " + d.string() + " > " + log + " 2>&1") == 0);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  INFO(text);
  const auto at = text.find("paused_cpu_fraction ");
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(text.substr(at + 20)) < 0.05);
  CHECK_THAT(text, Contains("exit 0"));
  // Two snapshots while paused share a time: the second gets -2, the first is kept. Three steps later: +0.1
  // s.
  std::vector<std::string> shots;
  for (size_t p = text.find("snapshot "); p != std::string::npos; p = text.find("snapshot ", p + 1))
    shots.push_back(text.substr(p + 9, text.find('\n', p) - p - 9));
  REQUIRE(shots.size() == 3);
  auto time_of = [](const std::string& name) { return std::stod(name.substr(6)); };  // live-tSSS.SSSs...
  auto second = std::find_if(shots.begin(), shots.end(),
                             [](const std::string& n) { return n.find("s-2.png") != n.npos; });
  REQUIRE(second != shots.end());
  const std::string first = second->substr(0, second->size() - 6) + ".png";
  CHECK(std::count(shots.begin(), shots.end(), first) == 1);
  std::string later;
  for (const auto& n : shots)
    if (n != first && n != *second) later = n;
  CHECK(time_of(later) - time_of(first) == Approx(0.1).margin(3.5e-3));  // each step rounds up to whole dt
  const Png img = read_png((d / first).string());
  CHECK(img.w == 1920);
  CHECK(img.h == 1080);
}

TEST_CASE("the inspector's clog bars start at each clog's start_s in clogs.csv, not clog_min_gap later",
          "[ui][heavy]") {
  fs::path d = temp_dir("clog_bars");
  REQUIRE(test::cli("run " + test::kScene + " --duration 25 --seed 2 --quiet --trajectory-fps 10 --out " +
                    (d / "r").string())
              .code == 0);
  gl();
  io::Trajectory t(d / "r" / "trajectory.sstraj");
  const app::TrajectoryFrames frames(t);
  ui::Inspector insp(frames, core::compile(core::Scene{}), nullptr);
  std::vector<double> starts;
  std::ifstream in(d / "r" / "clogs.csv");
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) starts.push_back(std::stod(line.substr(0, line.find(','))));
  REQUIRE(starts.size() >= 2);
  size_t matched = 0;
  for (const auto& c : insp.clogs()) {
    const double t0 = t.time(c.first);
    // The nearest clog start: the bar's first frame is the first frame at or after it.
    double best = 1e9;
    for (double s : starts) best = std::min(best, std::abs(t0 - s));
    CHECK(best <= t.info().frame_interval + 1e-6);
    matched += best <= t.info().frame_interval + 1e-6;
  }
  CHECK(matched >= 2);
}

TEST_CASE("an inspector snapshot at 3000x2000 places its information box clear of the grains",
          "[ui][render][heavy]") {
  // The first picture of a size used to keep the box top-right (its size was not yet known), over the funnel.
  fs::path d = temp_dir("snapshot_clear");
  REQUIRE(test::cli("record " + test::kScene +
                    " --duration 8 --size 320x180 --no-movie --png-every 1000 --quiet --out " +
                    (d / "run").string())
              .code == 0);
  // Every element but the zoom box (an outline over the whole-hopper panel by design).
  std::ofstream(d / "s.txt") << "goto frame 240\noverlay time,counts,rate,timer,arch,legend,scale\nsnapshot "
                             << (d / "with.png").string() << " 3000x2000\noverlay none\nsnapshot "
                             << (d / "without.png").string() << " 3000x2000\n";
  REQUIRE(test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "s.txt").string()).code ==
          0);
  const Png a = read_png(d / "with.png");
  const Png b = read_png(d / "without.png");
  REQUIRE(a.w == 3000);
  io::Trajectory t(d / "run" / "trajectory.sstraj");
  const core::Frame f = t.frame(240);
  const auto views =
      render::layout_views(render::parse_camera("split"), core::make_geometry(core::Scene{}), 3000, 2000);
  long overlay_px = 0, on_grains = 0;
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x) {
      if (std::memcmp(a.at(x, y), b.at(x, y), 3) == 0) continue;
      ++overlay_px;
      for (const auto& v : views) {
        if (x < v.rect.x || x >= v.rect.x + v.rect.w || y < v.rect.y || y >= v.rect.y + v.rect.h) continue;
        const core::Vec2 w = v.pixel_to_world({x + 0.5, y + 0.5});
        for (const auto& p : f.particles)
          if (std::hypot(w.x - p.x, w.y - p.y) < p.radius) {
            ++on_grains;
            break;
          }
      }
    }
  INFO(overlay_px << " overlay pixels, " << on_grains << " on grains");
  CHECK(overlay_px > 50000);
  CHECK(on_grains == 0);
}

TEST_CASE("the inspector draws force chains from a recording's contacts, and says when a run has none",
          "[ui][render][heavy]") {
  fs::path d = temp_dir("inspector_chains");
  REQUIRE(test::cli("record " + test::kScene +
                    " --duration 8 --size 320x180 --no-movie --png-every 1000 --quiet --out " +
                    (d / "run").string())
              .code == 0);
  REQUIRE(fs::exists(d / "run" / "contacts.sscon"));
  std::ofstream(d / "s.txt") << "goto frame 238\noverlay none\nsnapshot " << (d / "plain.png").string()
                             << " 640x360\nchains 1:10\nsnapshot " << (d / "chains.png").string()
                             << " 640x360\nsnapshot " << (d / "v.svg").string() << " 640x360\nsnapshot "
                             << (d / "v.pdf").string() << "\nchains off\nsnapshot "
                             << (d / "plain.svg").string() << " 640x360\n";
  REQUIRE(test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "s.txt").string()).code ==
          0);
  const Png a = read_png(d / "plain.png"), b = read_png(d / "chains.png");
  // The chains are drawn in the colour map over the grains: many pixels change, and some are viridis' dark
  // purple end (a weak chain), which no grain or wall has.
  long changed = 0, purple = 0;
  const render::Rgba weak = render::colormap(0.0);
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x) {
      changed += std::memcmp(a.at(x, y), b.at(x, y), 3) != 0;
      purple += near(b.at(x, y), weak, 25);
    }
  CHECK(changed > 2000);
  CHECK(purple > 50);
  // The vector snapshots: no bitmap, grains and chains as paths, the caption as text.
  const std::string svg = test::slurp(d / "v.svg"), plain = test::slurp(d / "plain.svg");
  const auto count = test::count_of;
  CHECK(count(svg, "<image") == 0);
  CHECK(count(plain, "<path") > 60);                        // the grains in the outlet view, the walls
  CHECK(count(svg, "<path") > count(plain, "<path") + 10);  // and the chains
  CHECK(count(svg, "(frame 238)") == 1);
  const std::string pdf = test::slurp(d / "v.pdf");
  CHECK(pdf.rfind("%PDF", 0) == 0);
  CHECK(count(pdf, "/Subtype /Image") == 0);
  // Displacement is measured from the trajectory's frame at the reference time, however the inspector got to
  // the frame shown: straight there, or stepping from earlier.
  std::ofstream(d / "u.txt") << "overlay none\ncolor displacement 0.3 from 6\ngoto frame 230\nsnapshot "
                             << (d / "direct.png").string() << " 320x180\n";
  std::ofstream(d / "w.txt") << "overlay none\ncolor displacement 0.3 from 6\ngoto frame 200\nsnapshot "
                             << (d / "early.png").string() << " 320x180\ngoto frame 230\nsnapshot "
                             << (d / "stepped.png").string() << " 320x180\n";
  REQUIRE(test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "u.txt").string()).code ==
          0);
  REQUIRE(test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "w.txt").string()).code ==
          0);
  const Png direct = read_png(d / "direct.png"), stepped = read_png(d / "stepped.png");
  CHECK(direct.px == stepped.px);
  // Its contacts file removed: the run is refused, naming the file its manifest lists.
  fs::remove(d / "run" / "contacts.sscon");
  std::ofstream(d / "t.txt") << "chains 2\n";
  auto r = test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "t.txt").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Contains("contacts.sscon is missing"));
  // A run written before contacts were kept (and before manifests): the chains command says there are none.
  fs::remove(d / "run" / "manifest.toml");
  {
    std::string meta = test::slurp(d / "run" / "metadata.toml");
    const std::string declared = "manifest = \"manifest.toml\"\n";
    meta.erase(meta.find(declared), declared.size());
    std::ofstream(d / "run" / "metadata.toml") << meta;
  }
  r = test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "t.txt").string());
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Contains("t.txt:1") && Contains("no contacts beside it"));
}

namespace {
// Counts what a clip would hold, and remembers each picture's hash.
struct CountingFiles : ui::ImageFiles {
  mutable std::vector<std::size_t> frames;
  struct Sink : ui::MovieSink {
    std::vector<std::size_t>* out;
    void add(const core::Image& img) override {
      out->push_back(std::hash<std::string>{}(std::string(img.rgba.begin(), img.rgba.end())));
    }
    void finish() override {}
  };
  void write_png(const std::string&, const core::Image&) const override {}
  void write_vector(const std::string&, const std::string&, double, double, const std::string&,
                    const std::string&) const override {}
  void write_text(const std::string&, const std::string&) const override {}
  void check_movie(int, int, int) const override {}
  std::unique_ptr<ui::MovieSink> open_movie(const std::string&, int, int, int) const override {
    auto s = std::make_unique<Sink>();
    s->out = &frames;
    return s;
  }
};
}  // namespace

TEST_CASE("inspector clips freeze at a clog forming or before the rule fires, and follow a camera path",
          "[ui]") {
  gl();
  fs::path d = temp_dir("freeze");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  CountingFiles files;
  ui::Inspector insp(frames, core::compile(two_disk_scene()), &files);
  ui::Painter painter;
  // The synthetic clog: the timer passes clog_min_gap at frame 2; the rule fires between frames 3 and 4.
  insp.execute("freeze clog 1", &painter);
  insp.execute("export " + (d / "a.mp4").string() + " 0 4 160x120 10", &painter);
  REQUIRE(files.frames.size() == 5 + 9);
  for (size_t k = 3; k < 12; ++k) CHECK(files.frames[k] == files.frames[2]);
  files.frames.clear();
  insp.execute("freeze rule 0.5", &painter);
  insp.execute("export " + (d / "b.mp4").string() + " 0 4 160x120 10", &painter);
  REQUIRE(files.frames.size() == 5 + 4);
  CHECK(files.frames[4] == files.frames[3]);
  files.frames.clear();
  insp.execute("freeze off", &painter);
  insp.execute("camera-path 0:hopper,0.1:outlet", &painter);
  const double h0 = insp.views(160, 120).front().cam.height;
  insp.execute("goto frame 4", &painter);
  CHECK(insp.views(160, 120).front().cam.height < 0.5 * h0);  // zoomed in on the outlet by t = 0.13 s
  CHECK(insp.views(160, 120).size() == 1);
  insp.execute("camera-path off", &painter);
  CHECK(insp.views(160, 120).size() == 2);  // back to split
  CHECK_THROWS_WITH(insp.execute("freeze jam 2"), Contains("freeze clog|rule SECONDS"));
  CHECK_THROWS_WITH(insp.execute("camera-path 0:split"), Contains("a path moves one"));
  // Arches and grains as camera subjects are record's (it simulates ahead to find them).
  CHECK_THROWS_WITH(insp.execute("zoom arch:1"), Contains("`record` does"));
  CHECK_THROWS_WITH(insp.execute("camera-path 0:hopper,1:grain:3"), Contains("`record` does"));
}

TEST_CASE("each colouring keeps its own colour range and a refused colour line changes nothing", "[ui]") {
  fs::path d = temp_dir("ranges");
  io::Trajectory t(test::synthetic_trajectory(d));
  const app::TrajectoryFrames frames(t);
  ui::Inspector insp(frames, core::compile(two_disk_scene()), nullptr);
  insp.execute("color force 1.63:20");
  insp.execute("color speed");  // was "from 1.63 to 0.5", a range the script itself refuses
  CHECK(insp.style.color_min == 0);
  insp.execute("color speed 0.1:0.5");
  insp.set_color(render::ColorMode::Force, "force");  // the panel's radio button
  CHECK(insp.style.color_min == 1.63);
  CHECK(insp.style.force_max == 20);
  insp.execute("color speed");
  CHECK(insp.style.color_min == 0.1);
  CHECK(insp.style.speed_max == 0.5);
  CHECK_THROWS(insp.execute("color force 3:2"));
  CHECK(insp.style.color == render::ColorMode::Speed);
  insp.execute("color force");
  CHECK(insp.style.color_min == 1.63);
  // The saved session writes each line with its range, so a replay needs none of this memory.
  const auto lines = insp.state_lines();
  std::string all;
  for (const auto& line : lines) all += line + "\n";
  CHECK_THAT(all, Contains("\ncolor force 1.63:20.0\n"));
}

TEST_CASE("a window session saved as a script replays off-screen to the same snapshot bytes (Xvfb, xdotool)",
          "[ui][heavy]") {
  fs::path d = temp_dir("session");
  REQUIRE(sh(kBin + " record " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/assets/scenes/paper.toml --duration 12 --size 320x240 --fps 30 --quiet --out " +
             (d / "rec").string()) == 0);
  const std::string log = (d / "log.txt").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' bash " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/tests/ui/ui_session.sh " + kBin + " " + (d / "rec").string() + " " + d.string() + " > " + log +
             " 2>&1") == 0);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  INFO(text);
  CHECK_THAT(text, Contains("window exit 0") && Contains("replay exit 0"));
  // What was done in the window, written down: the navigation, the colouring clicked, the wheel's zoom,
  // the grain clicked, the snapshot.
  CHECK_THAT(text, Contains("\nnext clog\nnext clog\ngoto clog 2 arch\ncolor force\nzoom to 1.32"));
  CHECK_THAT(text, Contains("\nselect ") && Contains("\nsnapshot snapshot-{frame}.png 1920x1080\n"));
  CHECK(text.find("\nselect off\nsnapshot") == std::string::npos);  // the click hit a grain
  auto path_after = [&](const std::string& key) {
    const auto at = text.find("\n" + key + " ");
    REQUIRE(at != std::string::npos);
    return text.substr(at + key.size() + 2, text.find('\n', at + 1) - at - key.size() - 2);
  };
  const std::string a = path_after("window-snapshot"), b = path_after("replay-snapshot");
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  REQUIRE(fa);
  REQUIRE(fb);
  const std::string pa((std::istreambuf_iterator<char>(fa)), std::istreambuf_iterator<char>());
  const std::string pb((std::istreambuf_iterator<char>(fb)), std::istreambuf_iterator<char>());
  CHECK(pa.size() > 10000);
  CHECK(pa == pb);
}

TEST_CASE(
    "every click on the step buttons and the colourings is on screen before the window goes idle (Xvfb)",
    "[ui][heavy]") {
  fs::path d = temp_dir("clicks");
  REQUIRE(sh(kBin + " run " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/assets/scenes/paper.toml --duration 3 --trajectory-fps 30 --quiet --out " +
             (d / "rec").string()) == 0);
  const std::string log = (d / "log.txt").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' bash " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/tests/ui/ui_clicks.sh " + kBin + " " + (d / "rec").string() + " " + d.string() + " > " + log +
             " 2>&1") == 0);
  const std::string text = test::slurp(log);
  INFO(text);
  CHECK_THAT(text, Contains("inspector exit 0") && Contains("inspector closed at frame 30"));
  // Each click's latency counted to the first picture that shows what it did (the grain's click too).
  CHECK_THAT(text, Contains("(21 clicks that changed the picture)"));
  // The click that closed the key overlay left the grain selected.
  // Ctrl-C and SIGTERM close an idle window (it slept through them in GLFW's event wait).
  const std::string signal_log = (d / "signal.txt").string();
  REQUIRE(sh("xvfb-run -a -s '-screen 0 1280x720x24' bash " + std::string(SILOSCOPE_SOURCE_DIR) +
             "/tests/ui/ui_signal.sh " + kBin + " " + (d / "rec").string() + " " + (d / "signal").string() +
             " > " + signal_log + " 2>&1") == 0);
  const std::string signals = test::slurp(signal_log);
  CHECK_THAT(signals, Contains("INT exit 130 after") && Contains("TERM exit 130 after"));
  const auto last_select = text.rfind("\nselect ");
  REQUIRE(last_select != std::string::npos);
  CHECK(text.compare(last_select, 12, "\nselect off") != 0);
  // The scene (left of the 400-pixel panel, above the 80-pixel timeline) after each click against before it:
  // the first 12 clicks step through flowing frames, the other 8 switch the colouring, so every one changes
  // it.
  auto scene = [&](int k) {
    char name[32];
    std::snprintf(name, sizeof name, "shot-%02d.rgb", k);
    const std::string raw = test::slurp(d / name);
    REQUIRE(raw.size() == 1280u * 720 * 3);
    std::string out;
    for (int y = 0; y < 640; ++y) out += raw.substr(static_cast<size_t>(y) * 1280 * 3, 880 * 3);
    return out;
  };
  std::string before = scene(0);
  int unchanged = 0;
  for (int k = 1; k <= 20; ++k) {
    std::string now = scene(k);
    if (now == before) {
      ++unchanged;
      UNSCOPED_INFO("click " << k << " is not on screen");
    }
    before = std::move(now);
  }
  CHECK(unchanged == 0);
}

namespace {
// Synthetic mouse input for a panel drawn by `draw` (between NewFrame and Render): a click (press, release)
// at every point of a grid over [x0, x1] x [y0, y1], then a 40-pixel drag to the right from the same point,
// rows from the top. `skip(y)` leaves rows out. `between` runs after each point (the live panel's
// simulation).
struct GridClicker {
  ImGuiIO& io;
  std::function<void()> draw;
  long frames = 0;
  void frame(ImVec2 mouse, bool down) {
    io.DeltaTime = 1.0f / 60;
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    draw();
    ImGui::Render();
    ++frames;
  }
  void click(ImVec2 p) {
    frame(p, false);
    frame(p, true);
    frame(p, false);
  }
  void grid(float x0, float y0, float x1, float y1, float step, const std::function<bool(float)>& skip = {},
            const std::function<void()>& between = {}) {
    for (float y = y0; y <= y1; y += step) {
      if (skip && skip(y)) continue;
      for (float x = x0; x <= x1; x += step) {
        click(ImVec2(x, y));
        frame(ImVec2(x, y), true);
        frame(ImVec2(x + 20, y), true);
        frame(ImVec2(x + 40, y), true);
        frame(ImVec2(x + 40, y), false);
        frame(ImVec2(-1, -1), false);
        if (between) between();
      }
    }
  }
};
}  // namespace

TEST_CASE(
    "every control of the inspector's and the live window's panels survives clicks and drags (paper, "
    "pentagons)",
    "[ui][heavy]") {
  gl();
  for (const std::string scene : {"paper", "pentagons"}) {
    INFO(scene);
    fs::path d = temp_dir("click_" + scene);
    const std::string file = std::string(SILOSCOPE_SOURCE_DIR) + "/assets/scenes/" + scene + ".toml";
    REQUIRE(sh(kBin + " record " + file + " --duration 4 --size 320x240 --fps 10 --quiet --out " +
               (d / "rec").string()) == 0);
    const io::Run run = io::Run::open(d / "rec", "test", io::Run::kTrajectory);
    const io::Trajectory& t = run.trajectory();
    const app::TrajectoryFrames frames(run);
    const app::RecordFiles files;
    const core::Model& model = run.model();
    ui::Inspector insp(frames, model, &files);
    ui::Painter painter;
    ImGuiContext* ctx = ImGui::CreateContext();
    ImGui::SetCurrentContext(ctx);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280, 720);
    REQUIRE(ImGui_ImplOpenGL3_Init("#version 330 core"));
    ui::PanelState ps;
    ps.export_to = static_cast<int>(t.size() - 1);
    for (auto [field, name] :
         {std::pair{ps.snapshot_path, "snap-{frame}.png"}, std::pair{ps.export_path, "clip-{frame}.mp4"},
          std::pair{ps.session_path, "session-{frame}.txt"}})
      std::snprintf(field, 256, "%s", (d / name).c_str());
    GridClicker g{io, [&] {
                    ui::draw_panels(insp, ps, &painter, 880, 400, 720, 640, 880, 80);
                    ImGui::SetCurrentContext(ctx);  // the painter's overlay has an ImGui context of its own
                  }};
    g.frame(ImVec2(-1, -1), false);
    // The panel and the timeline, twice: the outputs tab ends up open for the rows below the tabs in the
    // first pass, the arch tab (clicked) in the second.
    auto advance = [&] {
      if (ps.playing) ui::advance_playback(insp, ps, 3);
    };
    g.grid(884, 4, 1276, 716, 12, {}, advance);
    g.grid(4, 644, 876, 716, 24);
    REQUIRE(ps.rects.count("arch tab"));
    const auto tab = ps.rects["arch tab"];
    g.click(ImVec2(0.5f * (tab[0] + tab[2]), 0.5f * (tab[1] + tab[3])));
    g.grid(884, tab[3] + 4, 1276, 716, 12, {}, advance);
    // The key overlay and its close button.
    ps.show_keys = true;
    g.frame(ImVec2(-1, -1), false);
    REQUIRE(ps.rects.count("close keys"));
    const auto close = ps.rects["close keys"];
    g.click(ImVec2(0.5f * (close[0] + close[2]), 0.5f * (close[1] + close[3])));
    CHECK_FALSE(ps.show_keys);
    // The clicks did things: the window's session holds many kinds of command.
    insp.sync_history();
    std::set<std::string> kinds;
    for (const auto& line : insp.history()) kinds.insert(line.substr(0, line.find(' ')));
    INFO(kinds.size() << " kinds of command after " << g.frames << " frames");
    CHECK(kinds.size() >= 8);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(ctx);

    // The live window's panel on the running scene (settled for 2 s), the simulation advanced between clicks.
    core::Scene s = model.scene;
    core::apply_overrides(s, {"settle_time=2"});
    app::LiveSilo live(core::compile(s));
    ImGuiContext* lctx = ImGui::CreateContext();
    ImGui::SetCurrentContext(lctx);
    ImGuiIO& lio = ImGui::GetIO();
    lio.IniFilename = nullptr;
    lio.DisplaySize = ImVec2(1280, 720);
    REQUIRE(ImGui_ImplOpenGL3_Init("#version 330 core"));
    ui::LiveState st;
    st.edit = live.scene();
    core::Frame f = live.frame(false);
    GridClicker lg{lio,
                   [&] { ui::draw_live_window(live, st, f, live.overlay_data(), nullptr, 880, 400, 720); }};
    long points = 0;
    lg.grid(884, 4, 1276, 716, 20, {}, [&] {
      if (++points % 15 || st.paused) return;
      try {
        live.advance(ui::kLiveStep);
      } catch (const std::exception& e) {
        st.message = e.what(), st.paused = true;  // as the window does: the health monitor's word, paused
      }
      f = live.frame(st.style.color == render::ColorMode::Force || st.style.chains);
    });
    CHECK(lg.frames > 3000);
    CHECK(st.rects.count("pause") + st.rects.count("speed") == 2);
    CHECK(st.message != "running");  // a restart (or the health monitor) spoke
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(lctx);
  }
}

TEST_CASE("vector snapshots carry the information box, legend, colour bar and scale bar as text and paths",
          "[ui][heavy]") {
  fs::path d = temp_dir("vector_key");
  REQUIRE(test::cli("record " + test::kScene +
                    " --duration 3 --size 320x180 --no-movie --png-every 1000 --quiet --out " +
                    (d / "run").string())
              .code == 0);
  std::ofstream(d / "s.txt") << "goto clog 1 arch\nsnapshot " << (d / "a.svg").string()
                             << " 640x360\ncolor speed\n"
                             << "snapshot " << (d / "b.svg").string() << " 640x360\noverlay none\nsnapshot "
                             << (d / "c.svg").string() << " 640x360\n";
  const auto r = test::cli("inspect " + (d / "run").string() + " --quiet --script " + (d / "s.txt").string());
  INFO(r.output);
  REQUIRE(r.code == 0);
  const std::string a = test::slurp(d / "a.svg"), b = test::slurp(d / "b.svg"), c = test::slurp(d / "c.svg");
  const auto count = test::count_of;
  // By species: the legend's names and the arch, the exits, the clog, the scale bar.
  CHECK(count(a, "<image") == 0);
  CHECK(count(a, "1 d = 13 cm") == 1);
  CHECK(count(a, "arch members") == 1);
  // The arch is shown from its formation, usually before the clog is confirmed.
  CHECK(count(a, "clog 1 open") + count(a, "clog 1 forming") == 1);
  CHECK(count(a, ">original<") + count(a, " original<") >= 1);
  // By speed: a colour bar labelled with the scale instead of the species' legend.
  CHECK(count(b, "speed") >= 1);
  CHECK(count(b, "1 d = 13 cm") == 1);
  // Overlay none: the picture alone, as the bitmap.
  CHECK(count(c, "1 d = 13 cm") == 0);
  CHECK(count(c, "arch members") == 0);
}
