// Physical scales derived from a scene, used by the simulation's checks and written to every metadata file.
#pragma once

#include <cmath>

#include "core/scene.h"

namespace core {

constexpr double kPi = 3.14159265358979323846;
// 3 mu0 / (4 pi): the dipole force between two perpendicular dipoles is 3e-7 mu^2 / r^4 N (mu in A*m^2).
constexpr double kDipolePrefactor = 3e-7;

inline double mass_of(double radius, double density) {
  return kPi * radius * radius * density;
}

// Dipole force between two added disks in contact, N.
inline double dipole_contact_force(const Scene& s) {
  const double d = 2.0 * s.radius_added();
  return kDipolePrefactor * s.mu * s.mu / (d * d * d * d);
}

// Largest time step (s) that resolves the dipole repulsion between two added disks at contact: the pair's
// stiffness k = dF/dr = 4 |F| / r at r = 2 r_a gives omega = sqrt(2 k / m) (reduced mass m / 2); we ask
// omega * dt <= 1, a margin of 2 below the symplectic-Euler stability limit omega * dt = 2. The stability map
// (`siloscope bench stability`, docs/accuracy/stability.png) shows runs breaking near omega * dt = 2.
inline double dipole_safe_dt(const Scene& s) {
  if (s.mu <= 0.0 || s.n_added() < 2) return INFINITY;
  const double stiffness = 4.0 * dipole_contact_force(s) / (2.0 * s.radius_added());
  const double omega = std::sqrt(2.0 * stiffness / mass_of(s.radius_added(), s.density));
  return 1.0 / omega;
}

// mu (A*m^2) for which the contact dipole force between two added disks is `ratio` times an added disk's
// weight.
inline double mu_for_force_ratio(const Scene& s, double ratio) {
  const double d = 2.0 * s.radius_added();
  const double weight = mass_of(s.radius_added(), s.density) * s.gravity;
  return std::sqrt(ratio * weight * d * d * d * d / kDipolePrefactor);
}

// Largest time step (s) at which no disk moves more than the smallest diameter in one step at the free-fall
// speed from the top of the container, sqrt(2 g H): beyond it disks tunnel through each other and the walls.
inline double kinematic_safe_dt(const Scene& s) {
  const double smallest = s.n_added() > 0 ? std::min(s.radius_added(), s.radius_original) : s.radius_original;
  const double v = std::sqrt(2.0 * s.gravity * (s.silo_height + s.hopper_height));
  return v > 0 ? 2.0 * smallest / v : INFINITY;
}

}  // namespace core
