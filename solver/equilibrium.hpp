#pragma once

#include "solver/explicit_solver.hpp"

namespace mpile {

struct EquilibriumResult {
  bool reached = false;
  double kinetic_ratio = 0.0; // kinetic / elastic energy when the run stopped
  double time = 0.0;
};

/// Steps a damped (quasi-static) run until the kinetic energy has fallen below tolerance times the
/// stored elastic energy, checked every check_interval steps, or until max_time. A run at rest
/// under damping is in equilibrium: any unbalanced force would accelerate it.
EquilibriumResult advance_to_equilibrium(ExplicitSolver& solver, double tolerance, double max_time,
                                         int check_interval = 20);

} // namespace mpile
