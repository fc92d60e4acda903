#include "engine/structures/rigid_body.hpp"

namespace mpile {

namespace {

/// The loads that act whatever the drives: gravity on the body's mass and the sea's uplift.
double gravity_on(const RigidBody& body, int dof, const std::array<double, 2>& gravity) {
  if (dof == RIGID_ROTATION) {
    return 0.0;
  }
  const auto d = static_cast<std::size_t>(dof);
  return body.mass * gravity[d] + body.water_load[d];
}

} // namespace

double RigidBody::kinetic_energy() const {
  double energy = 0.5 * inertia * velocity[RIGID_ROTATION] * velocity[RIGID_ROTATION];
  for (const int d : {RIGID_X, RIGID_Y}) {
    energy +=
        0.5 * mass * velocity[static_cast<std::size_t>(d)] * velocity[static_cast<std::size_t>(d)];
  }
  return energy;
}

std::array<double, 3> RigidBody::predict(double time, double dt,
                                         const std::array<double, 2>& gravity,
                                         double inertia_scale) const {
  std::array<double, 3> u{0.0, 0.0, 0.0};
  for (int d = 0; d < 3; ++d) {
    if (!has_dof(d)) {
      continue;
    }
    const auto k = static_cast<std::size_t>(d);
    const RigidDrive& dof_drive = drive[k];
    if (dof_drive.kind == RigidDrive::Kind::velocity) {
      // The mean over the step, so that the displacement is exact whatever dt is.
      u[k] = dof_drive.function.mean(time, time + dt);
    } else {
      const double m = inertia_scale * (d == RIGID_ROTATION ? inertia : mass);
      const double force = dof_drive.function.mean(time, time + dt) + gravity_on(*this, d, gravity);
      u[k] = velocity[k] + dt * force / m;
    }
  }
  return u;
}

void RigidBody::finish_step(const std::array<double, 3>& predicted, double time, double dt,
                            const std::array<double, 2>& gravity, double inertia_scale) {
  for (int d = 0; d < 3; ++d) {
    if (!has_dof(d)) {
      continue;
    }
    const auto k = static_cast<std::size_t>(d);
    const double m = inertia_scale * (d == RIGID_ROTATION ? inertia : mass);
    const double weight = gravity_on(*this, d, gravity);
    double next = predicted[k];
    if (drive[k].kind == RigidDrive::Kind::velocity) {
      // The force the drive had to apply: M dV/dt = F_drive + M g + R.
      driving[k] = m * (next - velocity[k]) / dt - weight - contact[k];
    } else {
      next += dt * contact[k] / m;
      driving[k] = drive[k].function.mean(time, time + dt);
    }
    // The work over the step at the mean velocity, so that it matches the change of the kinetic
    // energy of the DOF (a harmonic torque turns the pile by a lot within one step).
    external_work += (driving[k] + weight) * 0.5 * (velocity[k] + next) * dt;
    velocity[k] = next;
    displacement[k] += next * dt;
  }
}

void RigidBody::move_centre(double dt) {
  if (mode == GeometryMode::plane_strain) {
    centre[0] += velocity[RIGID_X] * dt;
    centre[1] += velocity[RIGID_Y] * dt;
  }
}

} // namespace mpile
