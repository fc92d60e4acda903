#include "solver/equilibrium.hpp"

#include "solver/diagnostics.hpp"

namespace mpile {

EquilibriumResult advance_to_equilibrium(ExplicitSolver& solver, double tolerance, double max_time,
                                         int check_interval) {
  EquilibriumResult result;
  while (true) {
    const double elastic = elastic_energy(solver.scene());
    result.kinetic_ratio = elastic > 0.0 ? kinetic_energy(solver.scene()) / elastic : 0.0;
    result.time = solver.time();
    if (elastic > 0.0 && result.kinetic_ratio < tolerance) {
      result.reached = true;
      return result;
    }
    if (solver.time() >= max_time) {
      return result;
    }
    for (int s = 0; s < check_interval && solver.time() < max_time; ++s) {
      solver.step(max_time - solver.time());
    }
  }
}

} // namespace mpile
