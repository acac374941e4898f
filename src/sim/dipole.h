// Dipole-dipole repulsion between added disks, dipoles perpendicular to the plane:
//   F_i = sum_j 3 mu0 mu^2 / (4 pi |r_ij|^5) r_ij,  r_ij = x_i - x_j,  mu0 = 4 pi 1e-7 H/m,
// i.e. |F| = 3e-7 mu^2 / |r|^4 N with mu in A*m^2 and r in m. No torque.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "core/physics.h"

namespace sim {

using core::kDipolePrefactor;

// Force on a dipole at distance vector r (from the other dipole to this one), N.
inline core::Vec2 dipole_force(core::Vec2 r, double mu) {
  double r2 = core::dot(r, r);
  double k = kDipolePrefactor * mu * mu / (r2 * r2 * std::sqrt(r2));
  return k * r;
}

// Forces on every disk of `pos` from all others (pairs farther than cutoff skipped; cutoff <= 0: all pairs).
// `out` is resized and overwritten. Returns the number of pairs evaluated.
long dipole_forces(const std::vector<core::Vec2>& pos, double mu, double cutoff,
                   std::vector<core::Vec2>& out);

// Potential energy of the pair, J: U = mu0 mu^2 / (4 pi r^3) = 1e-7 mu^2 / r^3.
inline double dipole_energy(double r, double mu) {
  return kDipolePrefactor / 3.0 * mu * mu / (r * r * r);
}

}  // namespace sim
