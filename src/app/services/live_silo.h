// The live window's simulation (siloscope live): a Silo behind the window's LiveSource, so that ui never sees
// the simulation (and tests can drive the live panel with a real one).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/model.h"
#include "render/overlay.h"
#include "ui/window.h"

namespace app {

class Session;

// The live window's simulation: a Silo the window never sees (ui knows no simulation).
class LiveSilo final : public ui::LiveSource {
 public:
  explicit LiveSilo(const core::Model& model);
  ~LiveSilo() override;
  void advance(double seconds) override;
  core::Frame frame(bool forces) const override;
  const core::Geometry& geometry() const override;
  render::OverlayData overlay_data() const override {
    render::OverlayData d = render::overlay_data_for(model_);
    for (size_t k = 0; k < species_colors.size() && k < d.species_colors.size(); ++k)
      if (species_colors[k].a > 0) d.species_colors[k] = species_colors[k];
    return d;
  }
  std::vector<render::Rgba> species_colors;  // the look's (--species-color), by species index
  const core::Scene& scene() const override { return model_.scene; }
  // The keys worth changing live: the paper's shorthand (r, chi, mu, the kick), or a scene's drive, outlet,
  // obstacle, tilt and each species' dipole.
  std::vector<std::string> live_keys() const override;
  void restart(const core::Scene& s) override;

 private:
  core::Model model_;
  std::unique_ptr<Session> session_;
};

}  // namespace app
