#pragma once

// A case's phases set up on its scene and solver, in one place for every way a run begins or goes
// on: `mpile run` (a fresh run, a restart, each phase the runner begins), `mpile check` (its trial
// steps) and `mpile verify`. Setting up a phase means, in this order: its prescribed motions and
// loads, its K0 stresses (and the elastic energy they reset), its solver settings and the
// absorbing faces that start with it.

#include "cases/case_builder.hpp"
#include "cases/case_spec.hpp"
#include "engine/scene.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/phase_runner.hpp"
#include "solver/run_log.hpp"
#include "solver/run_phase.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace mpile {

/// The owner of setting up a case's phases on its scene and solver, from the pieces of
/// cases/case_builder.hpp (activate_phase_boundaries, apply_k0, phase_settings,
/// switch_on_absorbing_faces). The case and the scene must outlive it.
class CasePhases {
public:
  /// Applied to every phase's settings (`mpile verify`'s solver options); none by default.
  using SettingsChange = std::function<SolverSettings(SolverSettings)>;

  CasePhases(const CaseSpec& spec, Scene& scene, SettingsChange change = {});

  /// The phases as the phase runner sees them.
  const std::vector<RunPhase>& phases() const { return phases_; }
  /// The solver settings in force during phase p.
  SolverSettings settings(std::size_t p) const;

  /// A fresh run: the first phase begins at t = 0 (recorded in `progress`) with its K0 stresses
  /// and boundaries, the solver is made from that state with the phase's settings, and the
  /// phase's absorbing faces switch on.
  std::unique_ptr<ExplicitSolver> start(RunProgress& progress, RunLog& log) const;

  /// A run continued from a checkpoint: the boundaries of every phase begun, each from its start,
  /// and the solver restored with the settings of the phase it was in. A complete run whose case
  /// now has a phase more begins that phase as the runner begins one (begin_phase, set_up).
  std::unique_ptr<ExplicitSolver> resume(RunProgress& progress, RunLog& log,
                                         const SolverState& restored) const;

  /// Phase p beginning at `start` in a running solver (after begin_phase): its boundaries, its K0
  /// stresses with the elastic energy they reset, its settings, its absorbing faces.
  void set_up(ExplicitSolver& solver, std::size_t p, double start) const;

  /// set_up on this solver, as the phase runner calls it.
  PhaseRunner::PhaseSetUp set_up_on(ExplicitSolver& solver) const;

private:
  const CaseSpec& spec_;
  Scene& scene_;
  std::vector<RunPhase> phases_;
  SettingsChange change_;
};

} // namespace mpile
