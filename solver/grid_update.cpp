// Grid update: the nodal momentum balance M a = f_ext - f_int (+ local damping). Reads node mass,
// momentum, force and the constrained-DOF mask; writes node velocity v^{n+1} (in the momentum
// slot) and the velocity increment v^{n+1} - v^n (in the force slot).
#include "solver/passes.hpp"

#include <cmath>

namespace mpile::passes {

void apply_nodal_loads(Scene& scene, const StepParameters& step) {
  for (const NodalLoad& load : scene.boundaries.loads) {
    // The mean traction over the step gives the exact impulse whatever dt is.
    const double traction = load.traction.mean(step.time, step.time + step.dt);
    for (std::size_t k = 0; k < load.nodes.size(); ++k) {
      scene.grid.nodes[static_cast<std::size_t>(load.nodes[k])].force[load.component] +=
          load.weight[k] * traction;
    }
  }
}

namespace {

template <int dofs>
void update_field_velocities(std::vector<GridNode>& nodes, const std::vector<std::uint8_t>& mask,
                             const SolverSettings& settings, const StepParameters& step) {
  const double alpha = settings.local_damping;
  const double dt_over_beta = step.dt / settings.mass_scaling;
  parallel_for(nodes.size(), [&](std::size_t i) {
    GridNode& node = nodes[i];
    if (node.mass <= step.mass_floor) {
      node = GridNode{};
      return;
    }
    const double inverse_mass = 1.0 / node.mass;
    const std::uint8_t constrained = mask[i];
    for (int d = 0; d < dofs; ++d) {
      const double velocity = node.momentum[d] * inverse_mass;
      double force = node.force[d];
      // Local damping opposes the motion with a fraction of the unbalanced force; constrained DOFs
      // are left alone so that their reactions stay free of it.
      if (alpha > 0.0 && (constrained & (1u << d)) == 0 && velocity != 0.0) {
        force -= alpha * std::abs(force) * std::copysign(1.0, velocity);
      }
      const double increment = dt_over_beta * force * inverse_mass;
      node.momentum[d] = velocity + increment;
      node.force[d] = increment;
    }
  });
}

} // namespace

template <GeometryMode mode>
void update_grid_velocities(Scene& scene, const SolverSettings& settings,
                            const StepParameters& step) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  update_field_velocities<dofs>(grid.nodes, grid.constrained, settings, step);
  // Deformable structures have their own momentum balance; rigid bodies set their fields from
  // their DOFs instead.
  for (const ContactPair& pair : scene.contacts) {
    if (pair.rigid_body < 0) {
      update_field_velocities<dofs>(grid.field_nodes(pair.field),
                                    grid.field_constrained(pair.field), settings, step);
    }
  }
}

template void update_grid_velocities<GeometryMode::axisymmetric>(Scene&, const SolverSettings&,
                                                                 const StepParameters&);
template void update_grid_velocities<GeometryMode::plane_strain>(Scene&, const SolverSettings&,
                                                                 const StepParameters&);

} // namespace mpile::passes
