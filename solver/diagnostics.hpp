#pragma once

#include "engine/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mpile {

/// Kinetic energy sum of m |v|^2 / 2 (J, per radian in axisymmetric mode).
double kinetic_energy(const Scene& scene);
/// Recoverable energy stored in the particles, sum of Omega w(sigma) (J, per radian when
/// axisymmetric).
double elastic_energy(const Scene& scene);
/// Mass-weighted mean particle velocity of one body (all bodies when body < 0).
std::array<double, 3> mean_velocity(const Scene& scene, int body = -1);

/// "particle i at (r, y) = (r, y)", how messages name a particle.
std::string particle_position(const Particles& particles, std::size_t i);

/// Where the kinetic energy is: per body (a rigid body's that of its DOFs), and the particle of a
/// non-rigid body with the most (the lowest index among equals). A run whose energy balance fails
/// has its excess here: it names where to look.
struct KineticHotspot {
  std::vector<double> body_energy; // J [/rad], indexed by body
  std::int64_t particle = -1;      // -1 when no particle moves
  double particle_energy = 0.0;
  double particle_speed = 0.0;
};
KineticHotspot kinetic_hotspot(const Scene& scene);

/// One line for a message: the body with the most kinetic energy and its share, and the particle
/// with the most, with its position, cell and speed; energies times the mass scaling, as the
/// energy balance counts them.
std::string describe_kinetic_hotspot(const Scene& scene, double mass_scaling);

} // namespace mpile
