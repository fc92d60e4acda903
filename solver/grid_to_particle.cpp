// Grid-to-particle. Reads node velocity v^{n+1} and velocity increment; writes particle velocity
// (FLIP/PIC blend), the position increment du (applied after the stress update, so that every pass
// of the step uses the shape functions at x^n) and the circumferential displacement. The theta DOF
// is the node's angular velocity: a particle moves at v_theta = r_p sum N omega, so the angular
// momentum sum m r v_theta the nodes held is handed back exactly (sum_p m r_p^2 N = the inertia).
#include "engine/shape_functions.hpp"
#include "solver/particle_fields.hpp"
#include "solver/passes.hpp"

#include <optional>

namespace mpile::passes {

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void grid_to_particle(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                      const StepParameters& step) {
  Grid& grid = scene.grid;
  Particles& p = scene.particles;
  const double flip = settings.flip_fraction;
  const double pic = 1.0 - flip;
  const double dt = step.dt;
  [[maybe_unused]] const auto fields =
      contact ? std::optional<ParticleFields>(std::in_place, grid, scene) : std::nullopt;
  bins.for_each_block([&](int block, std::span<const std::int32_t> particles) {
    // A block of soil particles only gathers from field 0.
    [[maybe_unused]] const bool mixed = contact && bins.block_tag(block) != 0;
    for (const std::int32_t q : particles) {
      const auto i = static_cast<std::size_t>(q);
      const GridNode* nodes = grid.nodes.data();
      if constexpr (contact) {
        if (mixed) {
          nodes = fields->nodes(p.body[i]);
        }
      }
      const auto w = particle_weights<shape>(grid, p, i);
      double velocity[3] = {0.0, 0.0, 0.0};
      double increment[3] = {0.0, 0.0, 0.0};
      constexpr int dofs = has_theta(mode) ? 3 : 2;
      for (int k = 0; k < w.size; ++k) {
        const GridNode& node = nodes[static_cast<std::size_t>(w.node[k])];
        for (int d = 0; d < dofs; ++d) {
          velocity[d] += w.N[k] * node.momentum[d];
          increment[d] += w.N[k] * node.force[d];
        }
      }
      p.v_r[i] = flip * (p.v_r[i] + increment[0]) + pic * velocity[0];
      p.v_y[i] = flip * (p.v_y[i] + increment[1]) + pic * velocity[1];
      p.du_r[i] = dt * velocity[0];
      p.du_y[i] = dt * velocity[1];
      if constexpr (has_theta(mode)) {
        const double r = p.r[i];
        p.v_theta[i] = flip * (p.v_theta[i] + r * increment[2]) + pic * r * velocity[2];
        p.u_theta[i] += dt * r * velocity[2];
      }
    }
  });
}

template void grid_to_particle<GeometryMode::axisymmetric, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::axisymmetric, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::axisymmetric, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::axisymmetric, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::plane_strain, false, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::plane_strain, false, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::plane_strain, true, ShapeFunctions::linear>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);
template void grid_to_particle<GeometryMode::plane_strain, true, ShapeFunctions::gimp>(
    Scene&, const ParticleBins&, const SolverSettings&, const StepParameters&);

} // namespace mpile::passes
