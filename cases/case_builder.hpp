#pragma once

#include "cases/case_spec.hpp"
#include "engine/scene.hpp"
#include "solver/explicit_solver.hpp"

#include <memory>

namespace mpile {

/// Builds the scene a case describes: grid, materials, bodies (particles with their initial
/// velocity), face and axis constraints, prescribed motions and loads (inactive until their phase
/// starts: activate_phase_boundaries does that).
std::unique_ptr<Scene> build_scene(const CaseSpec& spec);

/// The moving mesh a case describes on its y-lines (its rigid body is set once the bodies exist).
/// The travel is rounded up to whole cells of the band, so that the band's bottom line at the start
/// is also a line of the mesh at the end of the travel.
MovingMesh moving_mesh_of(const MovingMeshSpec& spec, const GradedAxis& y);

/// How many particles build_scene seeds for a body, from the grid alone (the reader's check that
/// a region is not too small for its cells).
std::size_t count_body_particles(const CaseSpec& spec, const BodySpec& body);

/// Starts the prescribed motions and loads that begin with phase `phase_index`: their time
/// functions count from start_time. Motions and loads without a phase start with the first.
void activate_phase_boundaries(Scene& scene, const CaseSpec& spec, std::size_t phase_index,
                               double start_time);

/// Switches the case's absorbing faces on when phase `phase_index` is the one they start with, from
/// the state now (after the phase's K0 procedure and settings are in place): their supports give
/// way to dashpots and the forces that held them.
void switch_on_absorbing_faces(ExplicitSolver& solver, const CaseSpec& spec,
                               std::size_t phase_index);

/// Applies the K0 procedures of a phase (geostatic stress from each body's density and gravity).
void apply_k0(Scene& scene, const CaseSpec& spec, const PhaseSpec& phase);

/// The solver settings in force during a phase.
SolverSettings phase_settings(const CaseSpec& spec, const PhaseSpec& phase);

} // namespace mpile
