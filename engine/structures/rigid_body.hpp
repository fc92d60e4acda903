#pragma once

#include "engine/geometry_mode.hpp"
#include "engine/time_function.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace mpile {

/// How one degree of freedom of a rigid body is driven: a prescribed velocity (the force it takes
/// is recorded), or a prescribed force (a zero force leaves the DOF free). Gravity (and the sea's
/// uplift) act on the body in either case.
struct RigidDrive {
  enum class Kind { velocity, force };
  Kind kind = Kind::force;
  TimeFunction function; // m/s or rad/s; N or N m (per radian in axisymmetric mode)
};

/// DOF slots of a rigid body: translation along r (x in plane strain), translation along y, and
/// rotation (about the axis in axisymmetric mode, in-plane about the centre in plane strain).
enum RigidDof { RIGID_X = 0, RIGID_Y = 1, RIGID_ROTATION = 2 };

/// A structure that moves as one (physics.md section 6). Its particles only tell which nodes it
/// occupies; its motion is that of the DOFs, integrated from the drives, gravity and the contact
/// reactions. In axisymmetric mode the radial translation is zero by symmetry. Mass and inertia may
/// be those of the whole structure (the seed pile's 14 m are not all meshed).
struct RigidBody {
  std::string name;
  std::uint16_t body = 0; // the scene's body index of its particles
  int field = 0;          // its nodal velocity field
  GeometryMode mode = GeometryMode::axisymmetric;
  double mass = 0.0;    // kg (per radian in axisymmetric mode)
  double inertia = 0.0; // polar about the axis, or in-plane about the centre (kg m^2 [/rad])
  std::array<RigidDrive, 3> drive;
  /// The sea's uplift on the part of the body the soil's pore pressure leaves out (N [/rad]; r and
  /// y): the water column's pressure on the seabed times the body's cross-section there
  /// (physics.md section 9c). Acts, as gravity, whatever the drives.
  std::array<double, 2> water_load{0.0, 0.0};

  // State at the end of the last step.
  std::array<double, 3> velocity{0.0, 0.0, 0.0};     // (V_x, V_y, omega)
  std::array<double, 3> displacement{0.0, 0.0, 0.0}; // (u_x, u_y, rotation angle)
  std::array<double, 2> centre{0.0, 0.0};            // current centre of rotation (plane strain)

  // Of the last step (force of the soil on the body; force of the drive on the body): N or N m.
  std::array<double, 3> contact{0.0, 0.0, 0.0};
  std::array<double, 3> driving{0.0, 0.0, 0.0};
  // Work done on the body by its drives and by gravity since the start (J [/rad]).
  double external_work = 0.0;

  /// The nodal unknowns of the body's field at (r, y) for DOF velocities u: in axisymmetric mode
  /// (v_r, v_y, omega), the theta unknown of a node being its angular velocity (v_theta = omega r);
  /// in plane strain (v_x, v_y, unused).
  std::array<double, 3> node_motion(const std::array<double, 3>& u, double r, double y) const {
    if (mode == GeometryMode::axisymmetric) {
      return {0.0, u[RIGID_Y], u[RIGID_ROTATION]};
    }
    return {u[RIGID_X] - u[RIGID_ROTATION] * (y - centre[1]),
            u[RIGID_Y] + u[RIGID_ROTATION] * (r - centre[0]), 0.0};
  }

  /// The moment about the body's axis (or centre) of a force (f_r, f_y, f_theta) at (r, y).
  double moment_of(const std::array<double, 3>& f, double r, double y) const {
    if (mode == GeometryMode::axisymmetric) {
      return r * f[2];
    }
    return (r - centre[0]) * f[1] - (y - centre[1]) * f[0];
  }

  /// True for the DOFs that exist in the mode (the radial translation does not in axisymmetry).
  bool has_dof(int dof) const { return mode == GeometryMode::plane_strain || dof != RIGID_X; }

  /// Kinetic energy 1/2 M V^2 + 1/2 J omega^2 (J [/rad]).
  double kinetic_energy() const;

  /// DOF velocities at the end of a step before contact: prescribed ones at their mean over the
  /// step, force-driven ones advanced by the drive and gravity. inertia_scale multiplies M and J
  /// in the inertia terms (mass scaling), never in gravity.
  std::array<double, 3> predict(double time, double dt, const std::array<double, 2>& gravity,
                                double inertia_scale) const;

  /// Closes the step: force-driven DOFs take the contact reaction (stored in contact) on top of
  /// the prediction; prescribed DOFs keep it, and the force their drive needed is recorded. Updates
  /// velocity, displacement, driving and external_work.
  void finish_step(const std::array<double, 3>& predicted, double time, double dt,
                   const std::array<double, 2>& gravity, double inertia_scale);
  /// Moves the centre of rotation by the step's translation (after the particles have moved: the
  /// rigid motion of the step is about the centre at its start).
  void move_centre(double dt);
};

} // namespace mpile
