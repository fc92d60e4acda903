// Boundary conditions on the grid. Reads node mass, rotational inertia and velocity; writes the
// velocity (and, after the momentum balance, the velocity increment and each constraint's
// reaction). Constraint node sets are small (faces and lines), so this runs serially, which also
// fixes the summation order of the reactions.
#include "solver/passes.hpp"

namespace mpile::passes {

namespace {

/// Every node of the soil's field moved as the scene's velocity field says ([affine_motion]);
/// returns the work of the nodal forces that does over the step (when record_increment). The
/// particles take only the field's change over the step (as next to a support), so the force at a
/// node is its mass times that change over dt, less the force the momentum balance applied (its
/// velocity increment, which this overwrites): against a steady field, the work of the internal
/// forces. (The jump from the balance's velocity to the field's never reaches the particles, so
/// booking it, as a support's reaction does, would count energy no particle receives.)
double apply_velocity_field(Scene& scene, const StepParameters& step, bool record_increment,
                            double inertia_per_dt) {
  Grid& grid = scene.grid;
  const bool angular = has_theta(scene.mode);
  const double t_mid = step.time + 0.5 * step.dt;
  double work = 0.0;
  for (std::size_t i = 0; i < grid.nodes.size(); ++i) {
    GridNode& node = grid.nodes[i];
    if (node.mass <= step.mass_floor) {
      continue;
    }
    const double r = grid.node_r(static_cast<int>(i));
    const double y = grid.node_y(static_cast<int>(i));
    auto v = scene.velocity_field(r, y, t_mid);
    auto v_before = scene.velocity_field(r, y, t_mid - step.dt);
    if (angular) {
      // The theta DOF is the angular velocity v_theta / r. On the axis, where that quotient has
      // no value, the node takes the one of the next node line (exact for a rigid spin).
      const double r_theta = r > 0.0 ? r : grid.r_axis().node(1);
      v[2] = scene.velocity_field(r_theta, y, t_mid)[2] / r_theta;
      v_before[2] = scene.velocity_field(r_theta, y, t_mid - step.dt)[2] / r_theta;
    }
    for (std::size_t d = 0; d < 3; ++d) {
      if (record_increment) {
        const double inertia = angular && d == 2 ? node.inertia : node.mass;
        const double change = (v[d] - v_before[d]) - node.velocity_increment()[d];
        work += inertia * change * inertia_per_dt * v[d] * step.dt;
        node.velocity_increment()[d] = v[d] - v_before[d];
      }
      node.velocity()[d] = v[d];
    }
  }
  return work;
}

} // namespace

double apply_constraints(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                         CorrectionPass pass, ConstraintFields fields) {
  const bool record_reactions = pass == CorrectionPass::after_balance;
  Grid& grid = scene.grid;
  const bool angular = has_theta(scene.mode);
  double work = 0.0;
  const double inertia_per_dt = settings.mass_scaling / step.dt;
  // The fields this call constrains: the soil's, the deformable structures', or both.
  std::vector<int> field_list;
  if (fields != ConstraintFields::structures) {
    field_list.push_back(0);
  }
  if (fields != ConstraintFields::soil) {
    for (const ContactPair& pair : scene.contacts) {
      if (pair.rigid_body < 0) {
        field_list.push_back(pair.field);
      }
    }
  }
  // Reactions are summed over the fields; the first call of a step starts them from zero.
  const bool reset_reactions = record_reactions && fields != ConstraintFields::soil;
  for (NodeConstraint& c : scene.boundaries.constraints) {
    if (c.dofs == 0) {
      continue;
    }
    // The prescribed velocity is the mean over the step, so displacements are exact. The FLIP
    // velocity increment of a constrained DOF is the change of the prescribed velocity (the
    // prescribed acceleration times dt), never the jump from the velocity mapped from particles:
    // that jump would drag particles next to a support towards its velocity. A motion prescribed
    // on one structure's field instead drives that body, whose particles surround the nodes: they
    // take the jump, so that their velocities stay the motion they make (docs/design.md,
    // "Numerical choices").
    const bool drives_a_body = c.field > 0;
    double prescribed[3] = {0.0, 0.0, 0.0};
    double prescribed_change[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < 3; ++d) {
      const auto& f = c.velocity[static_cast<std::size_t>(d)];
      if (f) {
        prescribed[d] = f->mean(step.time, step.time + step.dt);
        prescribed_change[d] = prescribed[d] - f->mean(step.time - step.dt, step.time);
      }
    }
    if (reset_reactions) {
      c.reaction = {0.0, 0.0, 0.0};
      c.torque = 0.0;
    }
    for (const int field : field_list) {
      if (c.field != NodeConstraint::all_fields && c.field != field) {
        continue;
      }
      std::vector<GridNode>& nodes = grid.field_nodes(field);
      for (const int index : c.nodes) {
        GridNode& node = nodes[static_cast<std::size_t>(index)];
        if (node.mass <= step.mass_floor) {
          continue;
        }
        const double r = grid.node_r(index);
        for (int d = 0; d < 3; ++d) {
          if ((c.dofs & (1u << d)) == 0) {
            continue;
          }
          // In axisymmetric mode the theta DOF is the node's angular velocity: a rotation is
          // prescribed as it is, a velocity v_theta as v_theta / r. A velocity held at a node on
          // the axis (the corner of a face across it) holds omega = 0 there: v_theta = 0 along
          // the face needs omega = 0 at both ends of its first cell. (The axis line itself holds
          // no theta: axis_constraint.)
          const bool angular_dof = angular && d == 2;
          const double scale =
              angular_dof && !c.theta_is_rotation ? (r > 0.0 ? 1.0 / r : 0.0) : 1.0;
          const double target = prescribed[d] * scale;
          const double change = target - node.velocity()[d];
          if (record_reactions) {
            // A force, or for the angular DOF a torque; its work is the same product.
            const double reaction =
                (angular_dof ? node.inertia : node.mass) * change * inertia_per_dt;
            if (drives_a_body) {
              // The particles' mean velocity over the step runs from the one mapped to the node
              // to the prescribed one: the kinetic energy the impulse gives them exactly.
              const double start = node.velocity()[d] - node.velocity_increment()[d];
              node.velocity_increment()[d] = target - start;
              work += reaction * step.dt * 0.5 * (start + target);
            } else {
              node.velocity_increment()[d] = prescribed_change[d] * scale;
              work += reaction * target * step.dt;
            }
            if (angular_dof) {
              c.torque += reaction;
              // The torque as a theta force at the node (on the axis a torque has none).
              c.reaction[2] += r > 0.0 ? reaction / r : 0.0;
            } else {
              c.reaction[static_cast<std::size_t>(d)] += reaction;
            }
          }
          node.velocity()[d] = target;
        }
      }
    }
  }
  if (scene.velocity_field && fields != ConstraintFields::structures) {
    work += apply_velocity_field(scene, step, record_reactions, inertia_per_dt);
  }
  return work;
}

double nodal_load_work(const Scene& scene, const StepParameters& step) {
  double work = 0.0;
  for (const NodalLoad& load : scene.boundaries.loads) {
    const double traction = load.traction.mean(step.time, step.time + step.dt);
    for (std::size_t k = 0; k < load.nodes.size(); ++k) {
      const GridNode& node = scene.grid.nodes[static_cast<std::size_t>(load.nodes[k])];
      // A force times a velocity, or a theta load's torque times the angular velocity.
      work += load.weight[k] * traction * node.velocity()[load.component] * step.dt;
    }
  }
  return work;
}

} // namespace mpile::passes
