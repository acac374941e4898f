// Arches seen from the moment they form. A clog is confirmed clog_min_gap after its last exit; its arch has
// usually stood for part of that time already. This sink holds the frames it is given for that latency (plus
// a frame) before handing them on to the sinks behind it (the movie, the trajectory), and when a clog is
// confirmed it marks the frames it holds from the arch's formation on: the arch's members, the clog's number
// and `arch_forming`. Every picture and file made downstream then shows the arch from its formation, with the
// statistics' clog definitions unchanged (clogs.csv keeps its start and end). Frames are small (positions of
// a few hundred grains), so the latency costs a few frames of memory, not pixels.
#pragma once

#include <deque>
#include <vector>

#include "app/services/session.h"

namespace app {

class HindsightSink : public Sink {
 public:
  // `latency`: s of simulated time frames are held (the scene's clog_min_gap, with a frame's margin).
  HindsightSink(std::vector<Sink*> inner, double latency);
  void frame(const FrameTick& tick) override;
  bool wants_frames() const override;
  bool wants_forces() const override;
  bool wants_steps() const override;
  void step(const sim::Silo& h, const core::StepEvents& e, size_t world) override;
  void finished(const std::vector<core::StepEvents>& closed) override;
  bool done() const override;
  // Hands on every frame still held (call after the run, before finished(): Session::finish does it).
  void flush();

 private:
  void mark(const FrameTick& opening);
  std::vector<Sink*> inner_;
  double latency_;
  std::deque<FrameTick> held_;
};

}  // namespace app
