#pragma once

#include "engine/particle_bins.hpp"
#include "engine/scene.hpp"
#include "solver/energy_balance.hpp"
#include "solver/pass_timer.hpp"
#include "solver/passes.hpp"
#include "solver/pore_water_coupling.hpp"
#include "solver/run_log.hpp"
#include "solver/simulation_error.hpp"
#include "solver/solver_settings.hpp"
#include "solver/xpic.hpp"

#include <limits>
#include <memory>
#include <vector>

namespace mpile {

/// What a checkpoint must keep of the integrator to continue a run bitwise identically.
struct SolverState {
  double time = 0.0;
  long steps = 0;
  double stable_dt = 0.0;
  double last_dt = 0.0;
  double min_dt = 0.0; // the floor below which the time step counts as collapsed
  EnergyLedger energy;
};

/// The longest step (s) towards a target `remaining` seconds away that leaves no sliver: the
/// remainder itself when one stable step reaches it, half of it when it lies between one and two
/// stable steps (so the last two steps are at least half a stable step each), else infinity (a
/// full stable step). A sliver step of 1e-8 s would divide the contact corrections, impulses that
/// do not shrink with the step, by a tiny dt and record forces a thousand times too large.
double landing_step(double remaining, double stable_dt);

/// The explicit MPM time integrator (MUSL, physics.md section 3) over a scene.
class ExplicitSolver {
public:
  /// Locates and bins the particles, sorts them by cell and checks the scene; throws
  /// std::invalid_argument for a particle outside the grid or on the axis, or settings out of
  /// range.
  ExplicitSolver(Scene& scene, SolverSettings settings, RunLog& log);
  /// Continues a run from a checkpoint: the particles keep their order and the step its size.
  ExplicitSolver(Scene& scene, SolverSettings settings, RunLog& log, const SolverState& restored);
  /// The pore water keeps references to the solver's bins, settings and timings: the solver stays
  /// where it was made.
  ExplicitSolver(const ExplicitSolver&) = delete;
  ExplicitSolver& operator=(const ExplicitSolver&) = delete;

  /// One explicit step of length min(stable dt, max_dt).
  void step(double max_dt = std::numeric_limits<double>::infinity());
  /// Steps until end_time; the last steps are shortened to land on it (landing_step).
  void advance_to(double end_time);

  double time() const { return time_; }
  long step_count() const { return steps_; }
  /// Work done on the material since the start by gravity, loads, supports and rigid-body drives
  /// (J, per radian in axisymmetric mode).
  double external_work() const;
  /// The energy balance now (docs/design.md, "Energy balance").
  EnergyBalance energy_balance() const;
  /// To call after the stresses were set anew (a K0 procedure between phases) from a state whose
  /// stored elastic energy was elastic_before: the balance carries on from the new stresses.
  void account_for_stress_reset(double elastic_before);
  /// Stable time step for the next step (s).
  double stable_time_step() const { return stable_dt_; }
  /// Length of the last step taken (s).
  double last_time_step() const { return last_dt_; }
  SolverState state() const { return {time_, steps_, stable_dt_, last_dt_, min_dt_, energy_}; }
  const SolverSettings& settings() const { return settings_; }
  /// Replaces the settings between phases (damping on or off, for example).
  void change_settings(const SolverSettings& settings);
  const ParticleBins& bins() const { return bins_; }
  const PassTimings& timings() const { return timings_; }
  const Scene& scene() const { return scene_; }

  /// The out-of-balance force of the current state on the free nodal DOFs, relative to the forces
  /// that hold it (reactions at supports, gravity, loads): sqrt(sum f_free^2 / sum f_held^2).
  /// Maps the particles to the grid once; nothing of the run's state changes.
  double unbalanced_force_ratio();

  /// Switches the scene's absorbing faces with these indices on in the state now
  /// (passes::switch_on_absorbing_faces); the state does not change.
  void switch_on_absorbing(const std::vector<std::size_t>& faces);

private:
  /// What stops a step: the lowest index of a node or particle gone non-finite, or of a particle
  /// that left the grid (-1: none).
  struct StepFailure {
    std::int64_t node_nonfinite = -1;
    std::int64_t particle_nonfinite = -1;
    std::int64_t particle_outside = -1;
  };

  // The step as its passes (solver/explicit_step.cpp, docs/design.md's pass table).
  template <GeometryMode mode, bool contact, ShapeFunctions shape> void step_in_mode(double dt);
  template <GeometryMode mode, bool contact> void step_with_contact(double dt);
  template <GeometryMode mode, bool contact, ShapeFunctions shape> void map_particles_to_grid();
  /// Loads, absorbing faces' holding forces, the water folded into the skeleton's nodes (coupled
  /// soil), the momentum balance with damping, the dashpots.
  template <GeometryMode mode> EnergyIncrement balance_momentum(const passes::StepParameters& step);
  /// The structures' supports, the rigid bodies' prediction, contact, the bodies' accelerations.
  template <GeometryMode mode>
  EnergyIncrement correct_for_contact(const passes::StepParameters& step);
  template <bool contact> EnergyIncrement enforce_supports(const passes::StepParameters& step);
  EnergyIncrement work_of_loads(const passes::StepParameters& step);
  /// The skeleton's particle velocities, then their water's (coupled soil): adds both to the
  /// ledger.
  template <GeometryMode mode, bool contact, ShapeFunctions shape>
  void update_particle_velocities(const passes::StepParameters& step);
  /// The MUSL remap (the skeleton's as the mixture's where it carries water) and the same
  /// corrections on the remapped velocities.
  template <GeometryMode mode, bool contact, ShapeFunctions shape>
  EnergyIncrement remap_momentum(const passes::StepParameters& step);
  template <GeometryMode mode, bool contact, ShapeFunctions shape>
  passes::StressPassResult update_stress(const passes::StepParameters& step);
  /// Moves the rigid bodies and the mesh and splits grown particles; returns the crossing time in
  /// the moved cells (with a moving mesh).
  template <bool contact>
  double move_bodies_and_mesh(const passes::StepParameters& step, passes::StressPassResult& stress);
  /// Advances the clock, stops a failed step and sets the next step's length.
  void finish_step(double dt, const passes::StressPassResult& stress, double moved_crossing_time);
  /// Throws SimulationError naming what failed at (step, time); returns when nothing did.
  void stop_if_failed(const StepFailure& failure, long step, double time) const;
  void report_stress_free_inside_rigid(std::int64_t count);
  /// Particle-to-grid alone (for the equilibrium check), in the scene's mode and shape functions.
  void particle_to_grid();
  void prepare();
  void locate_all_particles();
  /// Moves the y-lines with the mesh's rigid body, relocates the particles in the moved cells and
  /// returns their crossing time in the moved cells (for the next step).
  double move_mesh();
  void rebin();
  /// Sets the next step from the particles' crossing time in their cells now and stops the run if
  /// the step just taken was longer than the material allows now in the cells the step was
  /// computed in (Courant number above 1) or the step collapsed.
  void set_stable_time_step(double step_crossing_time, double crossing_time, double dt_taken);
  /// The smallest crossing time over the particles, for a phase's first step; stops the run,
  /// naming the particle, where a material reports no finite modulus.
  double first_crossing_time() const;
  void report_step_limit(double earlier_step);
  void sort_particles_by_cell();
  /// Removes the rigid bodies' particles the stress pass found outside the grid (cell_r = -1).
  void drop_rigid_particles_outside();
  /// Splits the particles that have grown larger than their cells (SolverSettings::
  /// split_particles); returns whether any was.
  bool split_oversized();
  void report_settings();

  Scene& scene_;
  SolverSettings settings_;
  RunLog& log_;
  ParticleBins bins_;
  PassTimings timings_;
  passes::XpicFields xpic_;
  double time_ = 0.0;
  double stable_dt_ = 0.0;
  double mass_floor_ = 0.0;
  /// The scene's pore water; null in a dry scene, whose step then runs no water pass.
  std::unique_ptr<PoreWaterCoupling> water_;
  double min_dt_ = 0.0;
  /// The log says what sets the step when it falls below this: half the step at the start, then
  /// half the step last reported (not in checkpoints: a restart reports from its own step).
  double step_report_below_ = 0.0;
  EnergyLedger energy_;
  /// The log says how many soil particles lie inside rigid bodies when a step's count reaches this
  /// (then the next power of ten); not in checkpoints.
  std::int64_t stress_free_report_at_ = 1;
  /// Each particle's c_p + |v_p| from the last stress update, kept only with a moving mesh.
  std::vector<double> signal_speed_;
  double last_dt_ = 0.0;
  long steps_ = 0;
};

} // namespace mpile
