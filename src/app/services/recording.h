// What `record` marks on its frames, and its colour-scale look-ahead.
#pragma once

#include <string>
#include <vector>

#include "core/events.h"
#include "core/frame.h"
#include "core/model.h"
#include "core/scene.h"
#include "render/camera.h"
#include "render/overlay.h"

namespace sim {
class Silo;
}

namespace app {

// --color-max auto: the top of the speed (forces = false) or contact-force scale taken from the data, the
// 99th percentile of every grain's value over frames every 0.1 s of the first `seconds` of discharge,
// simulated ahead from the same scene and seed (a session of its own, one extra settling). 0 if everything
// stayed at rest.
double color_scale_from_data(const core::Model& model, bool forces, double seconds, bool progress = true);

// Look-aheads for tagging grains (the run repeats exactly from its seed): the ids of the grains whose centres
// are in the box at time t (the first frame at or after it, frames every dt), and the members of the k-th
// long-lasting arch (k >= 1; throws core::InputError naming how many the run has). `progress`: how far each
// look-ahead has got, on a terminal (commands pass !--quiet).
std::vector<int> grains_in_box(const core::Model& model, double x0, double y0, double x1, double y1, double t,
                               bool progress = true);
std::vector<int> long_arch_members(const core::Model& model, int k, bool progress = true);
// The members of the arch of the k-th clog as it opens (k >= 1; row k of clogs.csv).
std::vector<int> clog_arch_members(const core::Model& model, int k, bool progress = true);

// A camera's subjects (arch:K, grain:ID keys of `path`; a lone --camera arch:K is a path of one key) found by
// simulating the scene ahead from the same seed (a run repeats exactly): the arch of the K-th clog where it
// stands as the clog forms, a followed grain's centre every 0.01 s over the times its key is shown. `what`
// names the option in errors; throws core::InputError naming the key when the run has fewer clogs, no arch
// blocks that clog, or the scene has no such grain. Nothing is simulated when no key names a subject.
void resolve_camera_subjects(const core::Model& model, render::CameraPath& path, const std::string& what,
                             bool progress = true);

// The annotations record puts on a panel's frames: the members of the last rule removal, ringed where they
// stood, and a caption, after each rule firing or clog broken by vibration, for at least kMinFrames frames
// and kMinSeconds of simulated time.
class EventMarks {
 public:
  static constexpr int kMinFrames = 10;
  static constexpr double kMinSeconds = 0.7;
  // `events`: what world h's steps reported since the previous frame.
  render::Annotations update(const sim::Silo& h, const core::StepEvents& events, const core::Frame& f);

 private:
  void start(const std::string& caption, double t, bool keep_rings);
  std::vector<render::Annotations::Ring> rings_;
  std::string caption_;
  double since_ = -1e9;
  int frames_left_ = 0;
};

}  // namespace app
