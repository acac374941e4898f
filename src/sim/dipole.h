// Dipole-dipole repulsion between grains that carry a dipole moment, dipoles perpendicular to the plane:
//   F_i = sum_j 3 mu0 mu_i mu_j / (4 pi |r_ij|^5) r_ij,  r_ij = x_i - x_j,  mu0 = 4 pi 1e-7 H/m,
// i.e. |F| = 3e-7 mu_i mu_j / |r|^4 N with moments in A*m^2 and r in m. No torque.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "core/physics.h"

namespace sim {

using core::kDipolePrefactor;

// Force on a dipole at distance vector r (from the other dipole to this one), N, both of moment mu.
inline core::Vec2 dipole_force(core::Vec2 r, double mu) {
  double r2 = core::dot(r, r);
  double k = kDipolePrefactor * mu * mu / (r2 * r2 * std::sqrt(r2));
  return k * r;
}

// Scratch space of the cell list (kept between steps: no allocation per step).
struct DipoleCells {
  std::vector<int> cell_of, start, order;
};

// Forces on every grain of `pos` (moments `moment`, A*m^2) from all others, N. Without a cutoff (<= 0) every
// pair is summed (n^2 / 2 pairs, in index order); with one, pairs farther apart are skipped and the others
// are found through a cell list of cells at least `cutoff` wide (work in proportion to n). `out` is resized
// and overwritten. Returns the number of pairs evaluated.
long dipole_forces(const std::vector<core::Vec2>& pos, const std::vector<double>& moment, double cutoff,
                   std::vector<core::Vec2>& out, DipoleCells& cells);
// Every grain with the same moment mu.
long dipole_forces(const std::vector<core::Vec2>& pos, double mu, double cutoff,
                   std::vector<core::Vec2>& out);

// Potential energy of a pair of moment mu, J: U = mu0 mu^2 / (4 pi r^3) = 1e-7 mu^2 / r^3.
inline double dipole_energy(double r, double mu) {
  return kDipolePrefactor / 3.0 * mu * mu / (r * r * r);
}

}  // namespace sim
