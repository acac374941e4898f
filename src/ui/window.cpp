// The GLFW windows: the inspector (timeline, panels) and the live view (edit and restart a running scene).
// Over 400 lines because both share one Window class, its key queue and frame helpers, which stay private
// to this file rather than becoming a header only these two functions would include.
#include "ui/window.h"
#include "core/format.h"
#include "core/physics.h"

#include "render/gl.h"  // glad first: GLFW must not pull in a GL header
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/median.h"
#include "render/context.h"
#include "render/painter.h"
#include "render/target.h"
#include "ui/live_panel.h"
#include "ui/panels.h"

bool ImGui_ImplOpenGL3_Init(const char* glsl_version);
void ImGui_ImplOpenGL3_Shutdown();
void ImGui_ImplOpenGL3_NewFrame();
void ImGui_ImplOpenGL3_RenderDrawData(ImDrawData* draw_data);

namespace ui {

namespace {
using Clock = std::chrono::steady_clock;
constexpr float kPanelWidth = 400, kTimelineHeight = 80;  // pixels at text size 1

void* glfw_proc(const char* name) {
  return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

// Key presses as GLFW delivers them, queued, so that quick taps between two redraws are never lost (ImGui's
// per-frame key state saw 2 of 5 quick taps). ImGui's own callback is chained after this one.
struct KeyQueue {
  std::vector<int> keys;
  std::vector<int> down_since_frame, taps;  // taps: pressed and released between two frames
  Clock::time_point last_key, last_click;   // when the newest key press and mouse release arrived (latency)
};
void on_key(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
  auto* q = static_cast<KeyQueue*>(glfwGetWindowUserPointer(w));
  if (q && key >= 0 && action == GLFW_PRESS) q->down_since_frame.push_back(key);
  if (q && action == GLFW_RELEASE &&
      std::find(q->down_since_frame.begin(), q->down_since_frame.end(), key) != q->down_since_frame.end())
    q->taps.push_back(key);
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (q) {
    q->last_key = Clock::now();
    q->keys.push_back(action == GLFW_REPEAT ? -key : key);
  }
}
// A click acts on its release (ImGui's buttons): the time the picture's latency is counted from.
void on_mouse_button(GLFWwindow* w, int /*button*/, int action, int /*mods*/) {
  if (action != GLFW_RELEASE) return;
  if (auto* q = static_cast<KeyQueue*>(glfwGetWindowUserPointer(w))) q->last_click = Clock::now();
}

// A GLFW window with a GL 3.3 core context and an ImGui context of its own.
class Window {
 public:
  Window(int w, int h, const char* title) {
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
      throw core::InputError(
          "no display (DISPLAY is not set): the window needs one; use --script FILE for the "
          "scripted, off-screen inspector, or run under xvfb-run");
    if (!glfwInit())
      throw core::InputError("cannot open a window on this display; use --script FILE instead");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    win_ = glfwCreateWindow(w, h, title, nullptr, nullptr);
    if (!win_) {
      glfwTerminate();
      throw core::InputError("cannot create an OpenGL 3.3 window on this display; use --script FILE instead");
    }
    glfwMakeContextCurrent(win_);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(win_, &queue_);
    glfwSetKeyCallback(win_, on_key);  // before ImGui's, which chain to them
    glfwSetMouseButtonCallback(win_, on_mouse_button);
    render::load_gl(&glfw_proc);
    ctx_ = ImGui::CreateContext();
    ImGui::SetCurrentContext(ctx_);
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsLight();
    ImGui_ImplGlfw_InitForOpenGL(win_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    // GLFW's wait resumes after a signal, so an idle window never saw Ctrl-C or SIGTERM: a watcher wakes it
    // (glfwPostEmptyEvent may be called from any thread) and the loop ends on the interrupt flag.
    watcher_ = std::thread([this] {
      while (!closing_) {
        if (core::interrupt_requested()) {
          glfwPostEmptyEvent();
          return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    });
  }
  ~Window() {
    closing_ = true;
    if (watcher_.joinable()) watcher_.join();
    ImGui::SetCurrentContext(ctx_);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(ctx_);
    glfwDestroyWindow(win_);
    glfwTerminate();
  }
  GLFWwindow* get() const { return win_; }
  ImGuiContext* imgui() const { return ctx_; }
  // The key presses since the last call (negative: auto-repeat of a held key).
  std::vector<int> take_keys() { return std::exchange(queue_.keys, {}); }
  // When the newest key press and the newest mouse release arrived.
  Clock::time_point last_key() const { return queue_.last_key; }
  Clock::time_point last_click() const { return queue_.last_click; }
  // Poll while something moves (playing, a test's frame budget, the few frames ImGui needs to settle after an
  // event); otherwise sleep until the next event: an idle window costs no CPU. `stale`: the picture on screen
  // is older than the state (the panels run after the picture is drawn, so a key or a click changed the
  // frame, the colouring or the camera after it): redraw at once rather than sleep on it.
  void wait_or_poll(bool busy, bool stale = false) {
    if (stale && !busy && settle_ == 0) ++stale_frames_;
    if (busy || stale || settle_ > 0) {
      glfwPollEvents();
      if (settle_ > 0) --settle_;
    } else {
      glfwWaitEvents();
      settle_ = 3;
    }
  }
  // ImGui (1.86) reads a key's state once per frame, so a key pressed and released between two frames (a
  // quick Return in a typed field) was never seen: such a tap is held down for one frame, released in the
  // next.
  void hold_taps() {
    ImGuiIO& io = ImGui::GetIO();
    for (int k : held_)
      if (glfwGetKey(win_, k) != GLFW_PRESS) io.KeysDown[k] = false;
    held_.clear();
    for (int k : queue_.taps)
      if (k < IM_ARRAYSIZE(io.KeysDown)) io.KeysDown[k] = true, held_.push_back(k);
    if (!held_.empty()) settle_ = std::max(settle_, 2);  // the frame that releases it
    queue_.taps.clear();
    queue_.down_since_frame.clear();
  }
  // Redraws made because the window would otherwise have slept on a picture older than the state.
  long stale_frames() const { return stale_frames_; }

 private:
  KeyQueue queue_;
  std::thread watcher_;
  std::atomic<bool> closing_{false};
  std::vector<int> held_;  // taps held down for this frame
  int settle_ = 3;
  long stale_frames_ = 0;
  GLFWwindow* win_ = nullptr;
  ImGuiContext* ctx_ = nullptr;
};

// Over the scene (not the panels): the mouse wheel zooms, dragging pans the most magnified view. Returns the
// scene's view under the cursor, or null.
const render::View* mouse_zoom_pan(const std::vector<render::View>& views, double& zoom, core::Vec2& pan,
                                   float scene_w, float scene_h) {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse || io.MousePos.x < 0 || io.MousePos.y < 0 || io.MousePos.x > scene_w ||
      io.MousePos.y > scene_h)
    return nullptr;
  const render::View* main = &views.front();
  for (const auto& v : views)
    if (v.px_per_m() > main->px_per_m()) main = &v;
  if (io.MouseWheel != 0) zoom = std::clamp(zoom * std::pow(1.15, io.MouseWheel), 0.1, 100.0);
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
    pan.x -= io.MouseDelta.x / main->px_per_m();
    pan.y += io.MouseDelta.y / main->px_per_m();
  }
  for (const auto& v : views)
    if (io.MousePos.x >= v.rect.x && io.MousePos.x < v.rect.x + v.rect.w && io.MousePos.y >= v.rect.y &&
        io.MousePos.y < v.rect.y + v.rect.h)
      return &v;
  return nullptr;
}

// The inspector's mouse: zoom and pan, a click (no drag) on a grain selects it (on empty space: none), and a
// grain under the resting cursor names itself in a tooltip.
void mouse_view(Inspector& insp, PanelState& ps, float scene_w, float scene_h) {
  // The key overlay takes the scene's clicks; the click that closes it ends there (it kept clearing the
  // selection on its release).
  if (ps.show_keys) return;
  if (ps.swallow_release) {
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) ps.swallow_release = false;
    return;
  }
  const auto views = insp.screen_views(static_cast<int>(scene_w), static_cast<int>(scene_h));
  const render::View* under = mouse_zoom_pan(views, insp.zoom, insp.pan, scene_w, scene_h);
  if (!under) return;
  const ImGuiIO& io = ImGui::GetIO();
  const core::Vec2 at = under->pixel_to_world({io.MousePos.x, io.MousePos.y});
  const long id = insp.grain_at(at);
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[0] < 16)
    act(insp, ps, [&] { insp.select_grain(id); });
  else if (id >= 0 && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    const core::Frame f = insp.current();
    const auto& g = f.particles[static_cast<size_t>(id)];
    const size_t sp = static_cast<size_t>(core::species_index(g.species));
    const auto& names = insp.overlay_data.species_names;
    ImGui::SetTooltip("grain %ld (%s), %.3f m/s; click for details", id,
                      sp < names.size() ? names[sp].c_str() : "?",
                      std::hypot(static_cast<double>(g.vx), static_cast<double>(g.vy)));
  }
}

// Every queued key press, in order: arrows step (held: repeat), space plays, N/P next/previous clog (at its
// start; playback stops), A the final arch of this clog (or the next), '.'/',' the next/previous change of
// arch, C plays until the next clog starts, Home/End, Q or Escape closes. Ignored while a text field has the
// keyboard.
void keys(Window& win, Inspector& insp, PanelState& ps, Painter* painter) {
  const std::vector<int> pressed = win.take_keys();
  if (ImGui::GetIO().WantTextInput) return;
  for (int k : pressed) {
    const bool repeat = k < 0;
    const int key = repeat ? -k : k;
    if (key == GLFW_KEY_RIGHT)
      insp.set_frame(insp.frame_index() + 1);
    else if (key == GLFW_KEY_LEFT)
      insp.set_frame(insp.frame_index() - 1);
    else if (repeat)
      continue;
    else if (key == GLFW_KEY_SPACE)
      ps.playing = !ps.playing;
    else if (key == GLFW_KEY_N || key == GLFW_KEY_P) {
      ps.playing = false;  // landing on a clog stops playback there
      act(insp, ps, [&] { insp.next_clog(key == GLFW_KEY_N); });
    } else if (key == GLFW_KEY_A) {
      ps.playing = false;
      act(insp, ps, [&] { final_arch(insp); });
    } else if (key == GLFW_KEY_PERIOD || key == GLFW_KEY_COMMA) {
      ps.playing = false;
      act(insp, ps, [&] { insp.next_arch_change(key == GLFW_KEY_PERIOD); });
    } else if (key == GLFW_KEY_C) {
      play_to_next_clog(insp, ps);
    } else if (key == GLFW_KEY_HOME)
      act(insp, ps, [&] { insp.goto_start(); });
    else if (key == GLFW_KEY_END)
      act(insp, ps, [&] { insp.goto_end(); });
    else if (key == GLFW_KEY_S)
      act(
          insp, ps, [&] { snapshot_from_panel(insp, ps, painter); }, true);
    else if (key == GLFW_KEY_W)
      act(
          insp, ps, [&] { insp.save_session(ps.session_path, ps.trajectory_name); }, true);
    else if (key == GLFW_KEY_SLASH || key == GLFW_KEY_F1)
      ps.show_keys = !ps.show_keys;
    else if (key == GLFW_KEY_ESCAPE && ps.show_keys)
      ps.show_keys = false;
    else if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE)
      glfwSetWindowShouldClose(win.get(), GLFW_TRUE);
  }
}

core::Image window_pixels(int w, int h) {
  core::Image img;
  std::vector<std::uint8_t> scratch;
  render::read_framebuffer(0, w, h, img, scratch, render::has_pack_invert());  // a screenshot: rare
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
  return img;
}

void save_screenshot(const ImageFiles* files, const std::string& path, int w, int h) {
  if (!files) throw core::InputError("--screenshot " + path + ": this window has nowhere to write files");
  files->write_png(path, window_pixels(w, h));
}

// Start ImGui's frame, run `panels`, draw ImGui over the window.
template <class Panels>
void imgui_frame(Window& win, int fw, int fh, Panels&& panels) {
  ImGui::SetCurrentContext(win.imgui());
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  win.hold_taps();
  ImGui::NewFrame();
  panels();
  ImGui::Render();
  glViewport(0, 0, fw, fh);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

// One window frame: the scene (painter: renderer + in-frame overlay) on the left, ImGui panels over the rest.
template <class Panels>
void draw_frame(Window& win, Painter& painter, const core::Frame& f, const Inspector& insp, float text_scale,
                Panels&& panels) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(win.get(), &fw, &fh);
  // The panel and the timeline grow with the text.
  const int scene_w = std::max(64, fw - static_cast<int>(kPanelWidth * text_scale));
  const int scene_h = std::max(64, fh - static_cast<int>(kTimelineHeight * text_scale));
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  render::OverlayOptions overlay = insp.overlay;
  // Views are zoomed and panned at will: keep the information box off the container, or beside the picture.
  overlay.place_clear = overlay.may_leave = true;
  const core::Frame ref = insp.reference_frame();  // displacement from the trajectory's own reference frame
  render::Annotations notes;
  notes.selected = static_cast<int>(insp.selected);
  const core::Frame* r = ref.particles.empty() ? nullptr : &ref;
  if (insp.branch()) {
    // "What if": the recording on the left, the branch on the right, at one time.
    std::vector<render::View> left, right;
    render::OverlayData od, ob;
    insp.branch_panels(scene_w, scene_h, left, right, od, ob);
    const core::Frame g = insp.branch()->frame();
    render::Annotations notes_b = notes;
    notes.caption = od.title, notes_b.caption = ob.title;  // which is which, whatever the boxes do
    overlay.events = true;
    painter.draw(
        {{&f, &insp.geometry(), &left, &od, &notes, r}, {&g, &insp.geometry(), &right, &ob, &notes_b, r}},
        insp.style, overlay, fw, fh, scene_w);
  } else {
    const auto views = insp.views(scene_w, scene_h);
    painter.draw({{&f, &insp.geometry(), &views, &insp.overlay_data, &notes, r}}, insp.style, overlay, fw, fh,
                 scene_w);
  }
  imgui_frame(win, fw, fh, [&] {
    panels(static_cast<float>(scene_w), static_cast<float>(fw), static_cast<float>(fh),
           static_cast<float>(scene_h));
  });
}
}  // namespace

double run_inspector_window(Inspector& insp, const WindowOptions& o) {
  Window win(o.width, o.height, "siloscope inspect");
  Painter painter;
  PanelState ps;
  ps.export_to = static_cast<int>(insp.trajectory().size() - 1);
  ps.trajectory_name = o.source_name;
  {
    // Text that reads at the window's size: 1x at 720 pixels high, up to 2x.
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win.get(), &fw, &fh);
    ps.font_scale = std::clamp(static_cast<float>(fh) / 720.0f, 1.0f, 2.0f);
  }
  std::vector<double> redraws, key_to_picture, click_to_picture;
  // The key or click that changed the state, waiting for the picture that shows it.
  Clock::time_point cause_at, counted;
  bool awaiting = false, by_click = false;
  long shown = -1;
  double play_acc = 0;
  bool stale = false;  // the panels changed the state after the picture was drawn
  auto last = Clock::now();
  for (int n = 0; !glfwWindowShouldClose(win.get()) && !core::interrupt_requested(); ++n) {
    win.wait_or_poll(ps.playing || o.frames > 0, stale);
    const auto now = Clock::now();
    // At most 0.1 s per redraw: time spent waiting for an event does not fast-forward playback.
    const double dt = std::min(0.1, std::chrono::duration<double>(now - last).count());
    last = now;
    if (ps.playing) {
      // Play at the recording's own pace times the playback speed.
      play_acc += dt * ps.speed / insp.trajectory().frame_interval();
      const long step = static_cast<long>(play_acc);
      play_acc -= step;
      advance_playback(insp, ps, step);
    }
    const auto t0 = Clock::now();
    const core::Frame f = insp.current();
    const long drawn = insp.frame_index();
    const std::vector<std::string> drawn_state = insp.state_lines();
    draw_frame(win, painter, f, insp, ps.font_scale, [&](float scene_w, float fw, float fh, float scene_h) {
      ImGui::SetCurrentContext(win.imgui());
      ImGui::GetIO().FontGlobalScale = ps.font_scale;
      keys(win, insp, ps, &painter);
      mouse_view(insp, ps, scene_w, scene_h);
      draw_panels(insp, ps, &painter, scene_w, fw - scene_w, fh, scene_h, scene_w, fh - scene_h);
      insp.sync_history();  // what the controls changed, written down as script lines
    });
    // The picture is drawn before the panels run, so a key or a click that changed the frame, the colouring,
    // the camera or the selection shows in the next redraw: make it now.
    stale = insp.state_lines() != drawn_state;
    if (stale) {
      // Caused by the newest key or click not yet counted (none: the panels' own doing, e.g. a camera glide).
      const Clock::time_point key = win.last_key(), click = win.last_click();
      const Clock::time_point newest = std::max(key, click);
      if (newest > counted) awaiting = true, by_click = click > key, cause_at = newest;
    }
    const bool shows_cause = awaiting && !stale;  // this picture was drawn with the state the input made
    if (drawn != shown || n == 0 || shows_cause) {
      glFinish();  // the redraw is done when the pixels are
      const auto done = Clock::now();
      ps.last_redraw_ms = 1e3 * std::chrono::duration<double>(done - t0).count();
      if (n > 0 && drawn != shown) redraws.push_back(ps.last_redraw_ms);
      shown = drawn;
      // From the key's or click's arrival to the pixels of the first picture showing what it did (before the
      // buffer swap), not to the redraw whose panels took it.
      if (shows_cause) {
        (by_click ? click_to_picture : key_to_picture)
            .push_back(1e3 * std::chrono::duration<double>(done - cause_at).count());
        awaiting = false, counted = cause_at;
      }
    }
    if (o.frames > 0 && n + 1 >= o.frames) {
      int fw = 0, fh = 0;
      glfwGetFramebufferSize(win.get(), &fw, &fh);
      if (!o.screenshot.empty()) save_screenshot(o.files, o.screenshot, fw, fh);
      break;
    }
    glfwSwapBuffers(win.get());
    // In tests, step through frames so redraw times are measured.
    if (o.frames > 0) insp.set_frame(insp.frame_index() + 1);
  }
  if (core::interrupt_requested()) throw core::Interrupted();  // exit 130; the window closes with the Window
  std::fprintf(stderr, "siloscope: inspector closed at frame %ld\n", insp.frame_index());
  std::fprintf(stderr, "redraws for a picture older than the panels: %ld\n", win.stale_frames());
  for (const auto& [what, ms] : {std::pair{"key", &key_to_picture}, std::pair{"click", &click_to_picture}})
    if (!ms->empty())
      std::fprintf(stderr,
                   "%s to picture: median %.1f ms, largest %.1f ms (%zu %s%s that changed the picture)\n",
                   what, core::median(*ms), *std::max_element(ms->begin(), ms->end()), ms->size(), what,
                   ms->size() == 1 ? "" : "s");
  return redraws.empty() ? 0.0 : core::median(redraws);
}

namespace {
// A free name for a snapshot: live-t12.345s.png, then live-t12.345s-2.png, ... (never over an existing file).
std::string free_snapshot_name(double t) {
  char stem_buf[48];
  std::snprintf(stem_buf, sizeof stem_buf, "live-t%.3fs", t);
  const std::string stem = stem_buf;
  std::string name = stem + ".png";
  for (int k = 2; std::filesystem::exists(name); ++k) name = stem + "-" + std::to_string(k) + ".png";
  return name;
}
}  // namespace

namespace {
void live_keys_pressed(Window& win, LiveState& st) {
  for (int k : win.take_keys()) {
    if (ImGui::GetIO().WantTextInput) break;
    const int key = k < 0 ? -k : k;
    if (key == GLFW_KEY_RIGHT && st.paused)
      st.step_pending += kLiveStep;
    else if (k < 0)
      continue;
    else if (key == GLFW_KEY_SPACE)
      st.paused = !st.paused;
    else if (key == GLFW_KEY_S)
      st.snapshot = true;
    else if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE)
      glfwSetWindowShouldClose(win.get(), GLFW_TRUE);
  }
}

}  // namespace

void run_live_window(LiveSource& source, const WindowOptions& o) {
  Window win(o.width, o.height, "siloscope live");
  Painter painter;
  LiveState st;
  st.edit = source.scene();
  {
    int fw = 0, fh = 0;  // text that reads at the window's size, as in the inspector: 1x at 720 pixels high
    glfwGetFramebufferSize(win.get(), &fw, &fh);
    st.font_scale = std::clamp(static_cast<float>(fh) / 720.0f, 1.0f, 2.0f);
  }
  st.style = o.style;
  st.overlay = o.overlay;
  st.overlay.place_clear = st.overlay.may_leave = true;
  auto last = Clock::now();
  for (int n = 0; !glfwWindowShouldClose(win.get()) && !core::interrupt_requested(); ++n) {
    win.wait_or_poll(!st.paused || o.frames > 0);
    const auto now = Clock::now();
    const double real = std::chrono::duration<double>(now - last).count();
    const double wall = std::min(0.1, real);
    last = now;
    live_keys_pressed(win, st);
    try {
      const double advance = st.paused ? std::exchange(st.step_pending, 0.0) : st.speed * wall;
      if (advance > 0) source.advance(advance);
      // What the loop keeps up with: the simulated time over the wall clock's (a slow step stretches `real`
      // past the 0.1 s the advance is capped at).
      if (st.paused)
        st.achieved = 0;
      else if (real > 0 && real < 1)  // (a longer gap is the window waiting, not the simulation)
        st.achieved = st.achieved > 0 ? 0.9 * st.achieved + 0.1 * advance / real : advance / real;
    } catch (const std::exception& e) {
      st.message = blame_edits(st, e.what());  // a failure after a restart names the edits it ran with
      st.paused = true;
    }
    const core::Frame f = source.frame(st.style.color == render::ColorMode::Force ||
                                       st.style.color == render::ColorMode::Stress || st.style.chains);
    const render::OverlayData od = source.overlay_data();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win.get(), &fw, &fh);
    const int scene_w = std::max(64, fw - static_cast<int>(kPanelWidth * st.font_scale));
    auto views_for = [&](int w, int h) { return live_views(st, source.geometry(), w, h); };
    if (st.snapshot) {
      st.snapshot = false;
      try {
        const auto views = views_for(1920, 1080);
        const std::string name = free_snapshot_name(f.t);
        render::OverlayOptions in_picture = st.overlay;  // a snapshot has no side panel to hold the box
        in_picture.may_leave = false;
        if (!o.files) throw core::InputError("this window has nowhere to write files");
        o.files->write_png(
            name, painter.paint({{&f, &source.geometry(), &views, &od}}, st.style, in_picture, 1920, 1080));
        st.message = "snapshot " + name;
      } catch (const std::exception& e) {
        st.message = std::string("snapshot failed: ") + e.what();
      }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const auto views = views_for(scene_w, fh);
    painter.draw({{&f, &source.geometry(), &views, &od}}, st.style, st.overlay, fw, fh, scene_w);
    imgui_frame(win, fw, fh, [&] {
      ImGui::GetIO().FontGlobalScale = st.font_scale;
      draw_live_window(source, st, f, od, &painter, static_cast<float>(scene_w),
                       static_cast<float>(fw - scene_w), static_cast<float>(fh));
      mouse_zoom_pan(views, st.zoom, st.pan, static_cast<float>(scene_w), static_cast<float>(fh));
    });
    if (o.frames > 0 && n + 1 >= o.frames) {
      if (!o.screenshot.empty()) save_screenshot(o.files, o.screenshot, fw, fh);
      break;
    }
    glfwSwapBuffers(win.get());
  }
  if (core::interrupt_requested()) throw core::Interrupted();
  std::fprintf(stderr, "siloscope: live window closed at t = %.3f s\n", source.frame(false).t);
}

}  // namespace ui
