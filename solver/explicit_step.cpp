// One explicit MUSL step as its passes, in the order of docs/design.md's pass table ("One explicit
// step"): each named call below is one row of that table. A pass returns the energy it adds to the
// ledger, and the step adds it in pass order; what stops a step is judged in one place
// (stop_if_failed).

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
  if constexpr (contact) {
    map_pore_force<mode, shape>();
  }
  map_water_to_grid<mode, shape>();
  energy_ += balance_momentum<mode>(step);
  if constexpr (contact) {
    energy_ += correct_for_contact<mode>(step);
  }
  energy_ += enforce_supports<contact>(step);
  energy_ += work_of_loads(step);
  energy_ += update_water_velocities<mode>(step);
  energy_ += update_particle_velocities<mode, contact, shape>(step);
  energy_ += update_water_particle_velocities<mode, shape>(step);
  if (settings_.musl) {
    energy_ += remap_momentum<mode, contact, shape>(step);
  }
  energy_ += project_pore_pressure<mode, shape>(step);
  find_pore_pressure_from_flow<mode, shape>(step);
  passes::StressPassResult stress = update_stress<mode, contact, shape>(step);
  energy_ +=
      EnergyIncrement{.external_work = stress.gravity_work, .internal_work = stress.internal_work};
  energy_ += apply_pore_pressure_from_flow(stress.stress_free_inside_rigid > 0);
  energy_ += apply_projected_pore_pressure(stress.stress_free_inside_rigid > 0);
  const double moved_crossing_time = move_bodies_and_mesh<contact>(step, stress);
  finish_step(dt, stress, moved_crossing_time);
  if (settings_.cell_mean_pore_pressure && has_pore_water(scene_)) {
    // Once the particles are binned where the stress pass moved them: each block then holds the
    // particles of its own cells.
    PassTimer timer(timings_.stress_update);
    passes::smooth_excess_pore_pressure(scene_, bins_);
  }
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
void ExplicitSolver::map_particles_to_grid() {
  PassTimer timer(timings_.particle_to_grid);
  passes::particle_to_grid<mode, contact, shape>(scene_, bins_, settings_);
}

template <GeometryMode mode, ShapeFunctions shape> void ExplicitSolver::map_pore_force() {
  if (!pore_water_at_contact_) {
    return;
  }
  PassTimer timer(timings_.contact);
  passes::map_pore_force<mode, shape>(scene_, bins_);
}

template <GeometryMode mode, ShapeFunctions shape> void ExplicitSolver::map_water_to_grid() {
  if (liquid_phases_.empty()) {
    return;
  }
  PassTimer timer(timings_.particle_to_grid);
  passes::map_water_to_grid<mode, shape>(scene_, bins_, liquid_phases_, settings_);
  passes::apply_drained_face_water(scene_, liquid_phases_, settings_);
}

template <GeometryMode mode>
EnergyIncrement ExplicitSolver::update_water_velocities(const passes::StepParameters& step) {
  if (liquid_phases_.empty()) {
    return {};
  }
  PassTimer timer(timings_.grid_update);
  const passes::WaterVelocityResult water =
      passes::update_water_velocities<mode>(scene_, step, settings_.mass_scaling);
  // A support's reaction holds the water too, where its face is impermeable: without that part a
  // saturated slab's base carried 5.8 % less than its load (the explicit water) and a lid's
  // reaction read 0.79 of the load under a consolidating cell.
  // A node two supports hold (a corner) is the first's, as its skeleton's reaction is.
  std::vector<std::uint8_t> claimed(scene_.grid.nodes.size(), 0);
  for (NodeConstraint& c : scene_.boundaries.constraints) {
    if (c.drained || (c.field != NodeConstraint::all_fields && c.field != 0)) {
      continue;
    }
    for (const int node : c.nodes) {
      const auto i = static_cast<std::size_t>(node);
      const LiquidNode& held = scene_.grid.liquid[i];
      for (int d = 0; d < 2; ++d) {
        if ((c.dofs & (1u << d)) != 0 && (claimed[i] & (1u << d)) == 0) {
          c.reaction[static_cast<std::size_t>(d)] += held.held_force[d];
          claimed[i] |= static_cast<std::uint8_t>(1u << d);
        }
      }
    }
  }
  // With the pore pressure solved on the grid the drag is booked there, at the corrected
  // velocities: the predictor's drag and the correction's add to one drag implicit in the
  // corrected relative flow, and the pore pressure's work is booked on the same velocities
  // (docs/saturated.md, "The step's energy identity").
  const double far_field =
      scene_.boundaries.drained_water.empty() ? 0.0 : passes::drained_face_water_work(scene_, step);
  return {.external_work = water.support_work + water.drain_work + far_field,
          .drag = water.tied_drag + (settings_.implicit_pore_pressure ? 0.0 : water.drag)};
}

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement
ExplicitSolver::update_water_particle_velocities(const passes::StepParameters& step) {
  if (liquid_phases_.empty()) {
    return {};
  }
  PassTimer timer(timings_.grid_to_particle);
  const passes::WaterParticleResult water = passes::update_water_particle_velocities<mode, shape>(
      scene_, bins_, liquid_phases_, settings_, step);
  return {.external_work = water.external_work, .transfer = water.transfer, .drag = water.drag};
}

template <GeometryMode mode, ShapeFunctions shape>
void ExplicitSolver::find_pore_pressure_from_flow(const passes::StepParameters& step) {
  if (liquid_phases_.empty()) {
    return;
  }
  PassTimer timer(timings_.stress_update);
  passes::pore_pressure_from_flow<mode, shape>(scene_, bins_, liquid_phases_, settings_, step,
                                               pending_pore_);
  if (settings_.implicit_pore_pressure) {
    // The flow's strains as found; the pressure is the one the grid's solve found.
    const std::vector<double>& increment = projection_.particle_increment();
    const std::vector<std::uint8_t>& cavitated = projection_.particle_cavitated();
    parallel_for(pending_pore_.size(), [&](std::size_t i) {
      if (liquid_phases_[scene_.particles.material[i]] != nullptr) {
        pending_pore_[i].pressure = increment[i];
        pending_pore_[i].cavitated = cavitated[i] != 0;
      }
    });
  }
}

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement ExplicitSolver::project_pore_pressure(const passes::StepParameters& step) {
  if (!settings_.implicit_pore_pressure) {
    return {};
  }
  PassTimer timer(timings_.grid_update);
  const passes::ProjectionResult solved =
      projection_.project<mode, shape>(scene_, bins_, settings_, step);
  if (!solved.converged) {
    std::ostringstream s;
    s << at_step(steps_ + 1, time_) << "the pore pressure's system over " << solved.cells
      << " cells did not converge (relative residual " << solved.residual << " after "
      << solved.iterations << " conjugate-gradient iterations): the run went unstable";
    throw SimulationError(s.str());
  }
  // The vapour's share is work on the soil's pore volume, as the cut-off's is in the explicit
  // water: internal work, dissipated.
  return {.internal_work = solved.vapour_work, .damping = solved.dissipated, .drag = solved.drag};
}

EnergyIncrement ExplicitSolver::apply_projected_pore_pressure(bool some_made_stress_free) {
  if (!settings_.implicit_pore_pressure) {
    return {};
  }
  PassTimer timer(timings_.stress_update);
  return {.internal_work = passes::apply_projected_pore_pressure(
              scene_, bins_, projection_.particle_increment(), projection_.particle_cavitated(),
              some_made_stress_free)};
}

EnergyIncrement ExplicitSolver::apply_pore_pressure_from_flow(bool some_made_stress_free) {
  if (liquid_phases_.empty()) {
    return {};
  }
  PassTimer timer(timings_.stress_update);
  return {.internal_work = passes::apply_pore_pressure_from_flow(
              scene_, bins_, liquid_phases_, pending_pore_, some_made_stress_free)};
}

template <GeometryMode mode>
EnergyIncrement ExplicitSolver::balance_momentum(const passes::StepParameters& step) {
  PassTimer timer(timings_.grid_update);
  passes::apply_nodal_loads(scene_, step);
  // Absorbing faces' terms from the grid's coordinates this step, for both of their passes.
  const std::vector<passes::FaceNodeTerms> faces = passes::absorbing_face_terms(scene_);
  passes::apply_holding_tractions(scene_, faces, step);
  const passes::CoupledPhasesResult coupled =
      liquid_phases_.empty() ? passes::CoupledPhasesResult{}
                             : passes::couple_phases<mode>(scene_, step, settings_.mass_scaling);
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
EnergyIncrement ExplicitSolver::update_particle_velocities(const passes::StepParameters& step) {
  PassTimer timer(timings_.grid_to_particle);
  const passes::XpicFields* xpic = nullptr;
  if (settings_.xpic_order > 0) {
    passes::extrapolate_xpic<mode, contact, shape>(scene_, bins_, settings_.xpic_order, step,
                                                   xpic_);
    xpic = &xpic_;
  }
  return {.transfer = settings_.mass_scaling * passes::grid_to_particle<mode, contact, shape>(
                                                   scene_, bins_, settings_, step, xpic)};
}

template <GeometryMode mode, bool contact, ShapeFunctions shape>
EnergyIncrement ExplicitSolver::remap_momentum(const passes::StepParameters& step) {
  PassTimer timer(timings_.momentum_remap);
  passes::remap_momentum<mode, contact, shape>(scene_, bins_, step);
  if (!liquid_phases_.empty()) {
    passes::rescale_remapped_skeleton<mode>(scene_);
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
  if (!liquid_phases_.empty()) {
    passes::remap_water<mode, shape>(scene_, bins_, liquid_phases_, step.mass_floor);
  }
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
  if (steps_ % 64 == 0) {
    report_water_tension();
  }
  stop_if_failed(StepFailure{.particle_nonfinite = stress.particle_nonfinite,
                             .particle_outside = stress.particle_outside},
                 steps_, time_);
  if (scene_.moving_mesh) {
    // move_mesh has relocated and rebinned; the step follows from the moved cells.
    set_stable_time_step(stress.step_crossing_time, moved_crossing_time, dt);
    return;
  }
  set_stable_time_step(stress.step_crossing_time, stress.min_crossing_time, dt);
  if (stress.block_changed) {
    PassTimer timer(timings_.binning);
    rebin();
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
      << " has a non-finite stress or velocity: the run went unstable";
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

void ExplicitSolver::report_water_tension() {
  // Water at the atmosphere's pressure cavitates about 100 kPa below it. Without a cut-off the
  // pore pressure of an undrained or slowly draining dilative sand keeps falling (the coarse CPT
  // chamber undrained at psi = 7.5 degrees reached 33 MPa of suction and a q_c of 168 MPa), and
  // the effective stress it lends the skeleton is not one water could give.
  constexpr double tension_water_holds = 100e3; // Pa
  if (water_tension_reported_) {
    return;
  }
  const Particles& p = scene_.particles;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  std::vector<const Material*> unbounded(scene_.materials.size(), nullptr);
  bool any = false;
  for (std::size_t m = 0; m < scene_.materials.size(); ++m) {
    const Material& material = *scene_.materials[m];
    if (material.pore_pressure_index() >= 0 && std::isinf(material.pore_pressure_limit())) {
      unbounded[m] = &material;
      any = true;
    }
  }
  if (!any) {
    water_tension_reported_ = true; // nothing to watch in this scene
    return;
  }
  struct Worst {
    double tension = 0.0;
    std::int64_t particle = -1;
  };
  const Worst worst = parallel_reduce(
      p.size(), Worst{},
      [&](std::size_t begin, std::size_t end, Worst found) {
        for (std::size_t i = begin; i < end; ++i) {
          const Material* material = unbounded[p.material[i]];
          if (material == nullptr) {
            continue;
          }
          const double tension =
              p.state[i * stride + static_cast<std::size_t>(material->pore_pressure_index())] -
              material->water_column_pressure();
          if (tension > found.tension) {
            found = {tension, static_cast<std::int64_t>(i)};
          }
        }
        return found;
      },
      [](const Worst& a, const Worst& b) {
        // The larger tension, the lower index on a tie: the same particle on any thread count.
        if (a.tension != b.tension) {
          return a.tension > b.tension ? a : b;
        }
        return lowest_found(a.particle, b.particle) == a.particle ? a : b;
      },
      true);
  if (worst.particle < 0 || !(worst.tension > tension_water_holds)) {
    return;
  }
  water_tension_reported_ = true;
  std::ostringstream s;
  s << at_step(steps_, time_) << "the pore water of "
    << particle_position(p, static_cast<std::size_t>(worst.particle)) << " is in "
    << worst.tension / 1e3
    << " kPa of tension, more than water holds (it cavitates about 100 kPa below the "
       "atmosphere), and nothing caps it: the effective stress it lends the soil is not one water "
       "could give; [water] cavitation_stress = 100e3 caps it (docs/physics.md section 9c)";
  log_.warn(s.str());
}

} // namespace mpile
