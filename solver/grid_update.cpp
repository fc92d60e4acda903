// Grid update: the nodal momentum balance M a = f_ext - f_int (+ local damping), and in
// axisymmetric mode the angular one J d(omega)/dt = torque for the theta DOF. Reads node mass,
// rotational inertia, momentum, force and the constrained-DOF mask; writes node velocity v^{n+1}
// (in the momentum slot) and the velocity increment v^{n+1} - v^n (in the force slot). Returns the
// energy the damping took and the first node whose velocity is not finite.
#include "solver/passes.hpp"

#include "engine/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::passes {

void apply_nodal_loads(Scene& scene, const StepParameters& step) {
  for (const NodalLoad& load : scene.boundaries.loads) {
    // The mean traction over the step gives the exact impulse whatever dt is. A theta load's
    // weights give node torques (NodalLoad), the theta DOF being angular.
    const double traction = load.traction.mean(step.time, step.time + step.dt);
    for (std::size_t k = 0; k < load.nodes.size(); ++k) {
      scene.grid.nodes[static_cast<std::size_t>(load.nodes[k])].force[load.component] +=
          load.weight[k] * traction;
    }
  }
}

namespace {

GridUpdateResult combine(GridUpdateResult a, const GridUpdateResult& b) {
  a.damping_dissipation += b.damping_dissipation;
  a.node_nonfinite = lowest_found(a.node_nonfinite, b.node_nonfinite);
  return a;
}

/// partner_occupies(i): whether the field's contact partner has mass at node i. Nodes outside
/// `box` hold no mass of the field.
template <int dofs, class PartnerOccupies>
GridUpdateResult
update_field_velocities(std::vector<GridNode>& nodes, const std::vector<std::uint8_t>& mask,
                        const NodeBox& box, int nodes_r, PartnerOccupies partner_occupies,
                        const SolverSettings& settings, const StepParameters& step) {
  const double alpha = settings.local_damping;
  const double dt_over_beta = step.dt / settings.mass_scaling;
  auto update = [&](std::size_t begin, std::size_t end, GridUpdateResult result) {
    box.visit(begin, end, nodes_r, [&](std::size_t i) {
      GridNode& node = nodes[i];
      if (node.mass <= step.mass_floor) {
        node = GridNode{};
        return;
      }
      const double inverse_mass = 1.0 / node.mass;
      // The theta DOF is the angular velocity: its inertia is the rotational one, which is > 0
      // wherever the mass is (every particle has r > 0).
      const double inverse_inertia[3] = {inverse_mass, inverse_mass,
                                         dofs == 3 ? 1.0 / node.inertia : 0.0};
      const std::uint8_t constrained = mask[i];
      // A node the field shares with a contact partner is held there by the contact force, which
      // acts after this update: its unbalanced force is mostly that support, not out-of-balance,
      // and damping it would hold the bodies apart like friction (a disc resting on soil kept
      // two thirds of its weight off the soil). The equilibrium check counts it as held too.
      const bool shared = alpha > 0.0 && partner_occupies(i);
      double finite_check = 0.0;
      for (int d = 0; d < dofs; ++d) {
        const double velocity = node.momentum[d] * inverse_inertia[d];
        double force = node.force[d];
        // Local damping opposes the motion with a fraction of the unbalanced force; constrained
        // DOFs are left alone so that their reactions stay free of it.
        if (alpha > 0.0 && !shared && (constrained & (1u << d)) == 0 && velocity != 0.0) {
          const double damping = alpha * std::abs(force) * std::copysign(1.0, velocity);
          force -= damping;
          // The damping force's work over the step at the mean velocity, v + dv / 2 (a torque's
          // at the mean angular velocity).
          result.damping_dissipation +=
              damping * (velocity + 0.5 * dt_over_beta * force * inverse_inertia[d]) * step.dt;
        }
        const double increment = dt_over_beta * force * inverse_inertia[d];
        node.velocity()[d] = velocity + increment;
        node.velocity_increment()[d] = increment;
        finite_check += node.velocity()[d];
      }
      if (!std::isfinite(finite_check) && result.node_nonfinite < 0) {
        result.node_nonfinite = static_cast<std::int64_t>(i);
      }
    });
    return result;
  };
  // The damping sum must not depend on the thread count; without damping the split is free.
  return parallel_reduce(box.count(), GridUpdateResult{}, update, combine, alpha > 0.0);
}

} // namespace

template <GeometryMode mode>
GridUpdateResult update_grid_velocities(Scene& scene, const SolverSettings& settings,
                                        const StepParameters& step) {
  constexpr int dofs = has_theta(mode) ? 3 : 2;
  Grid& grid = scene.grid;
  // The soil's contact partners are the structures; a structure's partner is the soil.
  const NodeBox all{0, grid.nodes_r(), 0, grid.nodes_y()};
  const bool any_structure =
      std::any_of(grid.structure_fields.begin(), grid.structure_fields.end(),
                  [](const NodeField& field) { return !field.reach.empty(); });
  GridUpdateResult result =
      any_structure
          ? update_field_velocities<dofs>(
                grid.nodes, grid.constrained, all, grid.nodes_r(),
                [&](std::size_t i) { return grid.structure_occupies(i, step.mass_floor); },
                settings, step)
          : update_field_velocities<dofs>(
                grid.nodes, grid.constrained, all, grid.nodes_r(),
                [](std::size_t) { return false; }, settings, step);
  const auto soil_occupies = [&](std::size_t i) { return grid.nodes[i].mass > step.mass_floor; };
  // Deformable structures have their own momentum balance; rigid bodies set their fields from
  // their DOFs instead.
  for (const ContactPair& pair : scene.contacts) {
    if (pair.rigid_body < 0) {
      const NodeBox& reach = grid.structure_fields[static_cast<std::size_t>(pair.field - 1)].reach;
      GridUpdateResult field = update_field_velocities<dofs>(
          grid.field_nodes(pair.field), grid.field_constrained(pair.field), reach, grid.nodes_r(),
          soil_occupies, settings, step);
      result = combine(result, field);
    }
  }
  return result;
}

template GridUpdateResult update_grid_velocities<GeometryMode::axisymmetric>(Scene&,
                                                                             const SolverSettings&,
                                                                             const StepParameters&);
template GridUpdateResult update_grid_velocities<GeometryMode::plane_strain>(Scene&,
                                                                             const SolverSettings&,
                                                                             const StepParameters&);

} // namespace mpile::passes
