// Physical scales derived from a scene, used by the simulation's checks and written to every metadata file.
#pragma once

#include <cmath>

#include "core/scene.h"

namespace core {

constexpr double kPi = 3.14159265358979323846;
// 3 mu0 / (4 pi): the dipole force between two perpendicular dipoles is 3e-7 mu^2 / r^4 N (mu in A*m^2).
constexpr double kDipolePrefactor = 3e-7;

inline double mass_of(double radius, double density) { return kPi * radius * radius * density; }

// Dipole force between two added disks in contact, N.
inline double dipole_contact_force(const Scene& s) {
  const double d = 2.0 * s.radius_added();
  return kDipolePrefactor * s.mu * s.mu / (d * d * d * d);
}

// Largest time step (s) that resolves the dipole repulsion between two added disks at contact: the pair's
// stiffness k = dF/dr = 4 |F| / r at r = 2 r_a gives omega = sqrt(2 k / m) (reduced mass m / 2); we ask
// omega * dt <= 0.5, a margin of 4 below the symplectic-Euler stability limit omega * dt = 2.
inline double dipole_safe_dt(const Scene& s) {
  if (s.mu <= 0.0) return INFINITY;
  const double stiffness = 4.0 * dipole_contact_force(s) / (2.0 * s.radius_added());
  const double omega = std::sqrt(2.0 * stiffness / mass_of(s.radius_added(), s.density));
  return 0.5 / omega;
}

}  // namespace core
