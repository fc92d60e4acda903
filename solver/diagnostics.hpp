#pragma once

#include "engine/scene.hpp"

namespace mpile {

/// Kinetic energy sum of m |v|^2 / 2 (J, per radian in axisymmetric mode).
double kinetic_energy(const Scene& scene);
/// Recoverable energy stored in the particles, sum of Omega w(sigma) (J, per radian when
/// axisymmetric).
double elastic_energy(const Scene& scene);
/// Mass-weighted mean particle velocity of one body (all bodies when body < 0).
std::array<double, 3> mean_velocity(const Scene& scene, int body = -1);

} // namespace mpile
