#pragma once

// The contact and rigid-body passes of a step (physics.md sections 5 and 6), used only by scenes
// with contact. Order within a step: predict_rigid_bodies, resolve_contact_with_rigid_bodies
// (recording), finish_rigid_bodies; after the MUSL remap: reset_rigid_fields, resolve_contact (not
// recording); after the particles moved: move_rigid_bodies.

#include "solver/passes.hpp"

#include <array>
#include <vector>

namespace mpile::passes {

/// Sizes the contact arrays (and the mass gradients of structures without an outline).
void prepare_contact(Scene& scene);

/// DOF velocities of every rigid body at the end of the step before contact; sets their fields.
std::vector<std::array<double, 3>>
predict_rigid_bodies(Scene& scene, const SolverSettings& settings, const StepParameters& step);

/// The Bardenhagen correction at every node both the soil and a structure occupy. After the
/// momentum balance, also the FLIP increments, the per-node and per-surface forces and the
/// rigid-body reactions (the outlines' nodal areas are refreshed first), and returns the kinetic
/// energy the normal correction took (J [/rad]); after the remap, the same kind of correction at
/// the same nodes, and returns the work friction and adhesion did on the slip of the remapped
/// velocities.
template <GeometryMode mode>
double resolve_contact(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                       CorrectionPass pass);

/// resolve_contact without refreshing the outlines' nodal areas: the pairs' correction alone.
template <GeometryMode mode>
double resolve_contact_pairs(Scene& scene, const SolverSettings& settings,
                             const StepParameters& step, CorrectionPass pass);
/// Sets a rigid body's field to the motion of DOF velocities u, its FLIP increment the change from
/// the body's velocity at the start of the step.
void set_rigid_motion(Grid& grid, const RigidBody& body, const std::array<double, 3>& u,
                      double mass_floor);
/// resolve_contact after the momentum balance at the DOF velocities the rigid bodies end the step
/// with: a force-driven DOF's velocity follows from the reaction the correction gives it, so the
/// two are solved together (regula falsi per DOF, to rounding); other DOFs keep `predicted`
/// (solver/rigid_contact.cpp).
template <GeometryMode mode>
double resolve_contact_with_rigid_bodies(Scene& scene, const SolverSettings& settings,
                                         const StepParameters& step,
                                         const std::vector<std::array<double, 3>>& predicted);
/// Force-driven DOFs take the contact reactions; fields are set to the final rigid motion.
void finish_rigid_bodies(Scene& scene, const SolverSettings& settings, const StepParameters& step,
                         const std::vector<std::array<double, 3>>& predicted);

/// Rigid fields back to the rigid motion after the momentum remap.
void reset_rigid_fields(Scene& scene, const StepParameters& step);

/// Rigid bodies' centres and outlines follow their motion over the step.
void move_rigid_bodies(Scene& scene, const StepParameters& step);

} // namespace mpile::passes
