// Arches seen from the moment they form (app/services/hindsight.h).
#include "app/services/hindsight.h"

#include <algorithm>
#include <cmath>

#include "sim/silo.h"

namespace app {

HindsightSink::HindsightSink(std::vector<Sink*> inner, double latency)
    : inner_(std::move(inner)), latency_(latency) {}

bool HindsightSink::wants_frames() const {
  for (const Sink* s : inner_)
    if (s->wants_frames()) return true;
  return false;
}
bool HindsightSink::wants_forces() const {
  for (const Sink* s : inner_)
    if (s->wants_forces()) return true;
  return false;
}
bool HindsightSink::wants_steps() const {
  for (const Sink* s : inner_)
    if (s->wants_steps()) return true;
  return false;
}
bool HindsightSink::done() const {
  for (const Sink* s : inner_)
    if (s->done()) return true;
  return false;
}

void HindsightSink::step(const sim::Silo& h, const core::StepEvents& e, size_t world) {
  for (Sink* s : inner_)
    if (s->wants_steps()) s->step(h, e, world);
}

void HindsightSink::mark(const FrameTick& opening) {
  for (size_t k = 0; k < opening.events.size() && k < opening.worlds.size(); ++k) {
    const core::StepEvents& ev = opening.events[k];
    if (ev.clogs_opened.empty() || !opening.worlds[k]) continue;
    const core::ClogState& st = opening.worlds[k]->clog();
    // The clog confirmed in this tick: still open, or (a clog that ended right after its confirmation) closed
    // before the tick's frame, its arch then in its closing record (members in the order they arrived).
    std::vector<int> members;
    double formed = NAN, end = INFINITY;
    bool left_to_right = true;
    if (st.open && !st.arch.empty()) {
      members = st.arch;
      formed = st.formed;
    } else if (!st.open && !ev.clogs_closed.empty()) {
      members = ev.clogs_closed.back().arrival;
      formed = ev.clogs_closed.back().formed;
      end = ev.clogs_closed.back().end;
      left_to_right = false;
    }
    if (members.size() < 2 || !(formed == formed)) continue;
    // Every frame held from the formation on, and the opening's own, shows the arch as forming.
    auto show = [&](core::Frame& f) {
      if (f.clog_open || f.t < formed - 1e-9 || f.t > end + 1e-9) return;
      f.arch = members;
      if (!left_to_right)
        std::sort(f.arch.begin(), f.arch.end(), [&](int a, int b) {
          return f.particles[static_cast<size_t>(a)].x < f.particles[static_cast<size_t>(b)].x;
        });
      f.arch_forming = true;
      f.clog_number = ev.clogs_opened.back();
    };
    for (FrameTick& held : held_)
      if (k < held.frames.size()) show(held.frames[k]);
  }
}

void HindsightSink::frame(const FrameTick& tick) {
  if (tick.frames.empty()) {  // nothing to mark: straight on
    for (Sink* s : inner_) s->frame(tick);
    return;
  }
  held_.push_back(tick);
  mark(held_.back());
  // What is older than the latency cannot be marked any more: handed on, in order.
  const double now = tick.frames.front().t;
  while (!held_.empty() && held_.front().frames.front().t < now - latency_ - 1e-9) {
    for (Sink* s : inner_) s->frame(held_.front());
    held_.pop_front();
  }
}

void HindsightSink::flush() {
  while (!held_.empty()) {
    for (Sink* s : inner_) s->frame(held_.front());
    held_.pop_front();
  }
}

void HindsightSink::finished(const std::vector<core::StepEvents>& closed) {
  // The run's end may confirm a clog (its gap reached clog_min_gap by then): its arch is marked too.
  if (!held_.empty()) {
    FrameTick last;
    last.events = closed;
    last.worlds = held_.back().worlds;
    mark(last);
  }
  flush();
  for (Sink* s : inner_) s->finished(closed);
}

}  // namespace app
