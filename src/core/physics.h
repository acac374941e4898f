// Physical scales derived from a scene, used by the simulation's checks and written to every metadata file.
#pragma once

#include <cmath>

#include "core/scene.h"

namespace core {

struct Setup;

constexpr double kPi = 3.14159265358979323846;
// 3 mu0 / (4 pi): the dipole force between two perpendicular dipoles is 3e-7 mu_i mu_j / r^4 N (A*m^2).
constexpr double kDipolePrefactor = 3e-7;

inline double mass_of(double radius, double density) {
  return kPi * radius * radius * density;
}

// The two-species shorthand: dipole force between two added disks in contact, N.
inline double dipole_contact_force(const Scene& s) {
  const double d = 2.0 * s.radius_added();
  return kDipolePrefactor * s.mu * s.mu / (d * d * d * d);
}

// mu (A*m^2) for which the contact dipole force between two added disks of the shorthand is `ratio` times an
// added disk's weight.
inline double mu_for_force_ratio(const Scene& s, double ratio) {
  const double d = 2.0 * s.radius_added();
  const double weight = mass_of(s.radius_added(), s.density) * s.gravity;
  return std::sqrt(ratio * weight * d * d * d * d / kDipolePrefactor);
}

// Largest time step (s) that resolves the dipole repulsion between the two stiffest grains at contact (the
// smallest grains of the species with dipoles): the pair's stiffness k = dF/dr = 4 |F| / r at contact gives
// omega = sqrt(k / m_reduced); we ask omega * dt <= 1, a margin of 2 below the symplectic-Euler stability
// limit omega * dt = 2. The stability map (`siloscope bench stability`, docs/accuracy/stability.png) shows
// runs breaking near omega * dt = 2. Infinite without dipoles.
double dipole_safe_dt(const Setup& setup);

// Largest time step (s) at which no grain moves more than the smallest diameter in one step at the free-fall
// speed from the top of the container, sqrt(2 g H), plus the container's own speed when it vibrates: beyond
// it grains tunnel through each other and the walls.
double kinematic_safe_dt(const Setup& setup, double gravity);

}  // namespace core
