#pragma once

#include "solver/explicit_solver.hpp"

#include <limits>

namespace mpile {

/// How near a state is to equilibrium (physics.md 9): the out-of-balance force on the free nodal
/// DOFs relative to the forces that hold the state, and the kinetic energy relative to the work
/// done on it. A state is at equilibrium when both are below the tolerance; a state at rest with
/// no work done counts too.
struct EquilibriumMeasure {
  bool reached = false;
  double force_ratio = std::numeric_limits<double>::quiet_NaN(); // measured once kinetic passes
  double kinetic_ratio = 0.0;                                    // kinetic / |external work|
};

/// The one equilibrium test of a run's phases (`equilibrium_tolerance`). The force ratio maps the
/// particles to the grid (ExplicitSolver::unbalanced_force_ratio), so it is measured only once
/// the kinetic energy passes; the state does not change.
EquilibriumMeasure measure_equilibrium(ExplicitSolver& solver, double tolerance);

struct EquilibriumResult {
  bool reached = false;
  EquilibriumMeasure measure; // when the run stopped
  double time = 0.0;
};

/// Steps a damped (quasi-static) run as one phase of the phase runner until equilibrium
/// (measure_equilibrium within tolerance, checked every 20 steps as in a case's phase), or until
/// max_time. The energy guard watches it as it watches a case's run.
EquilibriumResult advance_to_equilibrium(ExplicitSolver& solver, double tolerance, double max_time);

} // namespace mpile
