// "What if" in the inspector: a branch of the run (ui/sources.h, made by the app) changed and continued,
// drawn on the right of the recorded run at the same time.
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "ui/inspector.h"

namespace ui {

Branch& Inspector::need_branch(const char* what) const {
  if (!branch_)
    throw core::InputError(std::string(what) +
                           ": no branch; `branch at FRAME` (the button \"branch here\") "
                           "starts one");
  return *branch_;
}

void Inspector::branch_at(long k) {
  if (!brancher_)
    throw core::InputError(
        "branch: this inspector cannot re-simulate (a lone trajectory file, or a script "
        "without its run); open the run's directory");
  std::unique_ptr<Branch> b = brancher_->branch(in_range(k));
  branch_ = std::move(b);
  frame_ = k;
  log("branch at " + std::to_string(k));
}

void Inspector::branch_off() {
  branch_.reset();
  log("branch off");
}

void Inspector::branch_remove(long id) {
  Branch& b = need_branch("remove grain");
  const long n = static_cast<long>(b.frame().particles.size());
  if (id < 0 || id >= n)
    throw core::InputError("remove grain " + std::to_string(id) + ": ids run from 0 to " +
                           std::to_string(n - 1));
  b.remove_grain(static_cast<int>(id));
  log("remove grain " + std::to_string(id));
}

void Inspector::branch_kick(double dv) {
  need_branch("kick").kick(dv);
  log("kick " + core::format_g(dv, 17));
}

void Inspector::branch_set(const std::string& key, double value) {
  need_branch("set").set_key(key, value);
  log("set " + key + " " + core::format_g(value, 17));
}

void Inspector::branch_continue(double seconds) {
  Branch& b = need_branch("continue");
  if (!(seconds > 0 && seconds <= 3600))
    throw core::InputError("continue " + core::format_g(seconds) +
                           ": allowed more than 0 and at most 3600 s");
  b.advance_to(b.time() + seconds);
  // One clock: the recording moves to the branch's time (it stays at its end past it).
  long k = frame_;
  while (k + 1 < traj_.size() && traj_.time(k + 1) <= b.time() + 1e-9) ++k;
  frame_ = k;
  log("continue " + core::format_g(seconds, 17));
}

std::string Inspector::save_branch(const std::string& pattern) {
  Branch& b = need_branch("save branch");
  const std::string dir = output_name(pattern, "save branch " + pattern);
  b.save(dir);
  last_output = dir;
  log("save branch " + pattern);
  return dir;
}

void Inspector::branch_panels(int w, int h, std::vector<render::View>& left, std::vector<render::View>& right,
                              render::OverlayData& od, render::OverlayData& ob) const {
  const int half = w / 2;
  left = views(half, h);
  right = left;
  for (auto& v : right) v.rect.x += half;
  od = ob = overlay_data;
  od.panel_x = 0, od.panel_w = half;
  ob.panel_x = half, ob.panel_w = w - half;
  od.title = "recorded";
  const std::vector<std::string> changes = branch_->changes();
  const std::string last =
      changes.empty() ? "unchanged" : changes.back().substr(changes.back().find(": ") + 2);
  ob.title = "what if: " + last;
}

std::vector<render::View> Inspector::screen_views(int w, int h) const {
  if (!branch_) return views(w, h);
  std::vector<render::View> left, right;
  render::OverlayData od, ob;
  branch_panels(w, h, left, right, od, ob);
  left.insert(left.end(), right.begin(), right.end());
  return left;
}

core::Image Inspector::render_branch(Painter& p, int w, int h) const {
  // Two panels on one clock: the recording on the left at its frame, the branch on the right at its time.
  render::OverlayOptions o = overlay;
  o.place_clear = true;
  o.may_leave = false;
  o.events = true;  // the captions
  std::vector<render::View> left, right;
  render::OverlayData od, ob;
  branch_panels(w, h, left, right, od, ob);
  const core::Frame f = current(), g = branch_->frame();
  // Each panel's title is also its caption: the information box may not be in the picture.
  render::Annotations marks, marks_b;
  marks.selected = marks_b.selected = static_cast<int>(selected);
  marks.caption = od.title, marks_b.caption = ob.title;
  const core::Frame ref = reference_frame();
  const core::Frame* r = ref.particles.empty() ? nullptr : &ref;
  return p.paint({{&f, &geo_, &left, &od, &marks, r}, {&g, &geo_, &right, &ob, &marks_b, r}}, style, o, w, h);
}

}  // namespace ui
