#include "app/services/live_silo.h"

#include "app/services/session.h"
#include "render/overlay.h"
#include "sim/silo.h"

namespace app {

LiveSilo::LiveSilo(const core::Model& model)
    : model_(model), session_(std::make_unique<Session>(std::vector{model})) {}

LiveSilo::~LiveSilo() = default;

void LiveSilo::advance(double seconds) {
  session_->run(session_->world(0).time() + seconds, FrameClock::none(), {});
}

core::Frame LiveSilo::frame(bool forces) const {
  return session_->world(0).frame(forces);
}

const core::Geometry& LiveSilo::geometry() const {
  return session_->world(0).geometry();
}

std::vector<std::string> LiveSilo::live_keys() const {
  const core::Scene& scene = model_.scene;
  if (scene.shorthand()) return {"size_ratio", "chi", "mu", "kick_impulse_max"};
  std::vector<std::string> keys = {"kick_impulse_max", "aperture", "tilt"};
  if (scene.vibration_amplitude > 0) keys.push_back("vibration_amplitude");
  if (scene.vibration_gamma > 0) keys.push_back("vibration_gamma");
  if (scene.vibration_amplitude > 0 || scene.vibration_gamma > 0) keys.push_back("vibration_frequency");
  if (scene.obstacle != "none") keys.push_back("obstacle_height");
  for (const auto& sp : scene.species) keys.push_back("species." + sp.name + ".dipole");
  return keys;
}

void LiveSilo::restart(const core::Scene& s) {
  core::Model m = core::compile(s);
  session_ = std::make_unique<Session>(std::vector{m});
  model_ = std::move(m);
}

}  // namespace app
