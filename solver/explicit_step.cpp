// One explicit MUSL step as its passes, in the order of docs/design.md's pass table ("One explicit
// step"): each named call below is one row of that table. A pass returns the energy it adds to the
// ledger, and the step adds it in pass order; what stops a step is judged in one place
// (stop_if_failed). The pore water (solver/pore_water_coupling.hpp), absent in a dry scene, has
// four points of its own in the step; the momentum balance, the grid-to-particle pass, the remap
// and the re-binning take its share inside them, where its arithmetic falls between the
// skeleton's.

#include "engine/parallel.hpp"
#include "solver/contact_passes.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/pass_timer.hpp"
#include "solver/passes.hpp"
#include "solver/run_log.hpp"

#include <cmath>
#include <sstream>

namespace mpile {

namespace {

/// The constraints applied after contact: with contact, the soil's (the structures' come before
/// the contact correction); without, all of them.
template <bool contact> constexpr passes::ConstraintFields soil_fields() {
  return contact ? passes::ConstraintFields::soil : passes::ConstraintFields::all;
}

} // namespace

void ExplicitSolver::step(double max_dt) {
  const double dt = std::min(stable_dt_, max_dt);
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream s;
    s << at_step(steps_, time_) << "the time step is " << dt << " s (not a positive finite number)";
    throw SimulationError(s.str());
  }
  const bool contact = scene_.has_contact();
  if (scene_.mode == GeometryMode::axisymmetric) {
    contact ? step_with_contact<GeometryMode::axisymmetric, true>(dt)
            : step_with_contact<GeometryMode::axisymmetric, false>(dt);
  } else {
    contact ? step_with_contact<GeometryMode::plane_strain, true>(dt)
            : step_with_contact<GeometryMode::plane_strain, false>(dt);
  }
}

template <GeometryMode mode, bool contact> void ExplicitSolver::step_with_contact(double dt) {
  settings_.shape_functions == ShapeFunctions::gimp
      ? step_in_mode<mode, contact, ShapeFunctions::gimp>(dt)
      : step_in_mode<mode, contact, ShapeFunctions::linear>(dt);
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void ExplicitSolver::step_in_mode(double dt) {
  const passes::StepParameters step{time_, dt, mass_floor_};
  map_particles_to_grid<mode, contact, shape>();
  if (water_) {
    water_->to_grid<mode, contact, shape>();
  }
  energy_ += balance_momentum<mode>(step);
  if constexpr (contact) {
    energy_ += correct_for_contact<mode>(step);
  }
  energy_ += enforce_supports<contact>(step);
  energy_ += work_of_loads(step);
  if (water_) {
    energy_ += water_->update_grid_velocities<mode>(step);
  }
  update_particle_velocities<mode, contact, shape>(step);
  if (settings_.musl) {
    energy_ += remap_momentum<mode, contact, shape>(step);
  }
  if (water_) {
    energy_ += water_->find_pore_pressure<mode, shape>(step, steps_ + 1);
  }
  passes::StressPassResult stress = update_stress<mode, contact, shape>(step);
  energy_ +=
      EnergyIncrement{.external_work = stress.gravity_work, .internal_work = stress.internal_work};
  if (water_) {
    water_->apply_pore_pressure(stress.stress_free_inside_rigid > 0, energy_);
  }
  const double moved_crossing_time = move_bodies_and_mesh<contact>(step, stress);
  finish_step(dt, stress, moved_crossing_time);
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void ExplicitSolver::map_particles_to_grid() {
  PassTimer timer(timings_.particle_to_grid);
  passes::particle_to_grid<mode, contact, shape>(scene_, bins_, settings_);
}

template <GeometryMode mode>
EnergyIncrement ExplicitSolver::balance_momentum(const passes::StepParameters& step) {
  PassTimer timer(timings_.grid_update);
  passes::apply_nodal_loads(scene_, step);
  // Absorbing faces' terms from the grid's coordinates this step, for both of their passes.
  const std::vector<passes::FaceNodeTerms> faces = passes::absorbing_face_terms(scene_);
  passes::apply_holding_tractions(scene_, faces, step);
  const passes::CoupledPhasesResult coupled =
      water_ ? water_->couple_to_skeleton<mode>(step) : passes::CoupledPhasesResult{};
  const passes::GridUpdateResult grid =
      passes::update_grid_velocities<mode>(scene_, settings_, step);
  const passes::AbsorbedWork absorbed = passes::absorb_at_faces(scene_, faces, settings_, step);
  stop_if_failed(StepFailure{.node_nonfinite = grid.node_nonfinite}, steps_ + 1, time_);
  return {.external_work = absorbed.holding,
          .damping = grid.damping_dissipation,
          .radiated = absorbed.radiated,
          .drag = coupled.tied_drag};
}

template <GeometryMode mode>
EnergyIncrement ExplicitSolver::correct_for_contact(const passes::StepParameters& step) {
  PassTimer timer(timings_.contact);
  // The structures' own supports first: the contact correction then sees their prescribed
  // velocity.
  const double supports =
      passes::apply_constraints(scene_, settings_, step, passes::CorrectionPass::after_balance,
                                passes::ConstraintFields::structures);
  const auto predicted = passes::predict_rigid_bodies(scene_, settings_, step);
  const double dissipated =
      passes::resolve_contact_with_rigid_bodies<mode>(scene_, settings_, step, predicted);
  passes::finish_rigid_bodies(scene_, settings_, step, predicted);
  return {.external_work = supports, .contact = dissipated};
}

template <bool contact>
EnergyIncrement ExplicitSolver::enforce_supports(const passes::StepParameters& step) {
  PassTimer timer(timings_.grid_update);
  return {.external_work = passes::apply_constraints(scene_, settings_, step,
                                                     passes::CorrectionPass::after_balance,
                                                     soil_fields<contact>())};
}

EnergyIncrement ExplicitSolver::work_of_loads(const passes::StepParameters& step) {
  if (scene_.boundaries.loads.empty()) {
    return {};
  }
  PassTimer timer(timings_.grid_update);
  return {.external_work = passes::nodal_load_work(scene_, step)};
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void ExplicitSolver::update_particle_velocities(const passes::StepParameters& step) {
  {
    PassTimer timer(timings_.grid_to_particle);
    const passes::XpicFields* xpic = nullptr;
    if (settings_.xpic_order > 0) {
      passes::extrapolate_xpic<mode, contact, shape>(scene_, bins_, settings_.xpic_order, step,
                                                     xpic_);
      xpic = &xpic_;
    }
    energy_ += EnergyIncrement{.transfer = settings_.mass_scaling *
                                           passes::grid_to_particle<mode, contact, shape>(
                                               scene_, bins_, settings_, step, xpic)};
  }
  if (water_) {
    // The water's FLIP/PIC update reads the skeleton's particle velocities just updated and the
    // grid's before the MUSL remap replaces them.
    energy_ += water_->to_particles<mode, shape>(step);
  }
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
EnergyIncrement ExplicitSolver::remap_momentum(const passes::StepParameters& step) {
  PassTimer timer(timings_.momentum_remap);
  passes::remap_momentum<mode, contact, shape>(scene_, bins_, step);
  if (water_) {
    water_->rescale_remapped_skeleton<mode>();
  }
  // The remapped velocities take the same corrections as the balanced ones; contact books the
  // work friction and adhesion do on the slip they leave (the strain increments' slip).
  double slip = 0.0;
  if constexpr (contact) {
    passes::apply_constraints(scene_, settings_, step, passes::CorrectionPass::after_remap,
                              passes::ConstraintFields::structures);
    passes::reset_rigid_fields(scene_, step);
    slip =
        passes::resolve_contact<mode>(scene_, settings_, step, passes::CorrectionPass::after_remap);
  }
  passes::apply_constraints(scene_, settings_, step, passes::CorrectionPass::after_remap,
                            soil_fields<contact>());
  // The water's remap follows, with its pore pressure (PoreWaterCoupling::find_pore_pressure).
  return {.contact = slip};
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
passes::StressPassResult ExplicitSolver::update_stress(const passes::StepParameters& step) {
  PassTimer timer(timings_.stress_update);
  return passes::update_stress_and_positions<mode, contact, shape>(scene_, bins_, settings_, step,
                                                                   signal_speed_);
}

template <bool contact>
double ExplicitSolver::move_bodies_and_mesh(const passes::StepParameters& step,
                                            passes::StressPassResult& stress) {
  const bool particles_sound = stress.particle_nonfinite < 0 && stress.particle_outside < 0;
  if constexpr (contact) {
    passes::move_rigid_bodies(scene_, step);
    if (stress.rigid_left_grid && particles_sound) {
      drop_rigid_particles_outside();
      stress.block_changed = true; // the bins index the particles: rebuild them
    }
  }
  double moved_crossing_time = 0.0;
  if (scene_.moving_mesh) {
    PassTimer timer(timings_.binning);
    moved_crossing_time = move_mesh();
  }
  if (settings_.split_particles && (stress.cell_changed || scene_.moving_mesh) && particles_sound) {
    PassTimer timer(timings_.binning);
    if (split_oversized()) {
      // The bins index the particles (move_mesh rebinned before the split).
      stress.block_changed = true;
      if (scene_.moving_mesh) {
        rebin();
      }
    }
  }
  return moved_crossing_time;
}

void ExplicitSolver::finish_step(double dt, const passes::StressPassResult& stress,
                                 double moved_crossing_time) {
  time_ += dt;
  last_dt_ = dt;
  ++steps_;
  report_stress_free_inside_rigid(stress.stress_free_inside_rigid);
  if (water_ && steps_ % 64 == 0) {
    water_->report_tension(log_, steps_, time_);
  }
  stop_if_failed(StepFailure{.particle_nonfinite = stress.particle_nonfinite,
                             .particle_outside = stress.particle_outside},
                 steps_, time_);
  if (scene_.moving_mesh) {
    // move_mesh has relocated and rebinned; the step follows from the moved cells.
    set_stable_time_step(stress.step_crossing_time, moved_crossing_time, dt);
  } else {
    set_stable_time_step(stress.step_crossing_time, stress.min_crossing_time, dt);
    if (stress.block_changed) {
      PassTimer timer(timings_.binning);
      rebin();
    }
  }
  if (water_) {
    // Once the particles are binned where the stress pass moved them: each block then holds the
    // particles of its own cells.
    water_->smooth_excess_pore_pressure();
  }
}

void ExplicitSolver::stop_if_failed(const StepFailure& failure, long step, double time) const {
  std::ostringstream s;
  s << at_step(step, time);
  if (failure.node_nonfinite >= 0) {
    const int node = static_cast<int>(failure.node_nonfinite);
    s << "node " << node << " at (r, y) = (" << scene_.grid.node_r(node) << ", "
      << scene_.grid.node_y(node) << ") has a non-finite velocity: the run went unstable";
  } else if (failure.particle_nonfinite >= 0) {
    s << particle_position(scene_.particles, static_cast<std::size_t>(failure.particle_nonfinite))
      << " has a non-finite stress, velocity or wave speed: the run went unstable";
  } else if (failure.particle_outside >= 0) {
    s << particle_position(scene_.particles, static_cast<std::size_t>(failure.particle_outside))
      << " left the grid";
  } else {
    return;
  }
  throw SimulationError(s.str());
}

void ExplicitSolver::report_stress_free_inside_rigid(std::int64_t count) {
  if (count < stress_free_report_at_) {
    return;
  }
  while (stress_free_report_at_ <= count) {
    stress_free_report_at_ *= 10;
  }
  std::ostringstream s;
  s << at_step(steps_, time_) << count
    << " soil particle(s) lie inside rigid bodies: they carry no stress there and set no time "
       "step ([solver] stress_free_inside_rigid)";
  log_.info(s.str());
}

} // namespace mpile
