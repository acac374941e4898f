// Contacts and the blocking arch of a lab's frame from positions alone (no forces are measured in a film):
// two grains touch when the gap between them is at most `tolerance` times the smaller diameter, a grain
// touches a wall or the obstacle within the same gap (lab/import.h), and the arch is the simulation's own
// (core/arch.h).
#pragma once

#include <vector>

#include "core/arch.h"
#include "core/model.h"

namespace lab {

// The contact graph by distance: every grain with a finite position, walls and obstacle.
core::ContactGraph contacts_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                        const std::vector<bool>& present, const core::Geometry& geo,
                                        double tolerance);

// The blocking arch at a frame by distance (empty if none).
std::vector<int> arch_by_distance(const std::vector<core::Vec2>& pos, const std::vector<double>& radius,
                                  const std::vector<bool>& present, const core::Model& model,
                                  double tolerance);

}  // namespace lab
