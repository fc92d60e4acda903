// The stable time step's particle limit from the materials' current stiffness (physics.md
// section 8), for the first step; later steps get it from the stress update. Reads particle cell,
// mass, volume, velocity, stress and state.
#include "solver/passes.hpp"
#include "solver/rigid_interiors.hpp"

#include "engine/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mpile::passes {

namespace {

/// Particle i's crossing time and what makes it; soil inside a rigid body carries no stress and
/// has no wave speed (RigidInteriors).
StepLimit crossing_of(const Scene& scene, const SolverSettings& settings,
                      const std::optional<RigidInteriors>& interiors, std::size_t i) {
  const Particles& p = scene.particles;
  const Material& material = *scene.materials[p.material[i]];
  const double modulus = material.constrained_modulus(
      p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
  const double density = settings.mass_scaling * p.mass[i] / p.volume[i];
  double speed = p.v_r[i] * p.v_r[i] + p.v_y[i] * p.v_y[i];
  if (has_theta(scene.mode)) {
    speed += p.v_theta[i] * p.v_theta[i];
  }
  const double h = scene.grid.cell_min_size(p.cell_r[i], p.cell_y[i]);
  const double wave_speed =
      interiors && interiors->holds_soil(p, i) ? 0.0 : std::sqrt(modulus / density);
  const double velocity = std::sqrt(speed);
  return {i, h / (wave_speed + velocity), wave_speed, p.mass[i] / p.volume[i], velocity, h};
}

/// The smaller crossing time, NaN where either is: std::min passes over a NaN (its comparison is
/// false), and a particle whose material reports no finite modulus would then set no step at all.
double smaller_crossing(double a, double b) {
  return std::isnan(a) || a < b ? a : b;
}

} // namespace

double min_crossing_time(const Scene& scene, const SolverSettings& settings) {
  const std::optional<RigidInteriors> interiors = kept_rigid_interiors(scene, settings);
  return parallel_reduce(
      scene.particles.size(), std::numeric_limits<double>::infinity(),
      [&](std::size_t begin, std::size_t end, double limit) {
        for (std::size_t i = begin; i != end; ++i) {
          limit = smaller_crossing(limit, crossing_of(scene, settings, interiors, i).crossing_time);
        }
        return limit;
      },
      smaller_crossing);
}

StepLimit step_limit(const Scene& scene, const SolverSettings& settings) {
  const std::optional<RigidInteriors> interiors = kept_rigid_interiors(scene, settings);
  StepLimit limit;
  limit.crossing_time = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const StepLimit here = crossing_of(scene, settings, interiors, i);
    if (std::isnan(here.crossing_time)) {
      return here; // the first particle without a finite crossing time is the one to name
    }
    limit = here.crossing_time < limit.crossing_time ? here : limit;
  }
  return limit;
}

} // namespace mpile::passes
