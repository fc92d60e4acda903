// The stable time step's particle limit from the materials' current stiffness (physics.md
// section 8), for the first step; later steps get it from the stress update. Reads particle cell,
// mass, volume, velocity, stress and state.
#include "solver/passes.hpp"

#include "engine/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpile::passes {

double min_crossing_time(const Scene& scene, const SolverSettings& settings) {
  const Particles& p = scene.particles;
  const bool theta = has_theta(scene.mode);
  return parallel_reduce(
      p.size(), std::numeric_limits<double>::infinity(),
      [&](std::size_t begin, std::size_t end, double limit) {
        for (std::size_t i = begin; i != end; ++i) {
          const Material& material = *scene.materials[p.material[i]];
          const double modulus = material.constrained_modulus(
              p.stress[i], p.state.data() + i * static_cast<std::size_t>(p.state_stride));
          const double density = settings.mass_scaling * p.mass[i] / p.volume[i];
          double speed = p.v_r[i] * p.v_r[i] + p.v_y[i] * p.v_y[i];
          if (theta) {
            speed += p.v_theta[i] * p.v_theta[i];
          }
          const double h = scene.grid.cell_min_size(p.cell_r[i], p.cell_y[i]);
          limit = std::min(limit, h / (std::sqrt(modulus / density) + std::sqrt(speed)));
        }
        return limit;
      },
      [](double a, double b) { return std::min(a, b); });
}

} // namespace mpile::passes
