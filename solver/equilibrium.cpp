#include "solver/equilibrium.hpp"

#include "solver/diagnostics.hpp"
#include "solver/phase_runner.hpp"

#include <cmath>
#include <limits>

namespace mpile {

EquilibriumMeasure measure_equilibrium(ExplicitSolver& solver, double tolerance) {
  EquilibriumMeasure measure;
  const double kinetic = kinetic_energy(solver.scene());
  const double work = std::abs(solver.external_work());
  measure.kinetic_ratio = work > 0.0 ? kinetic / work : 0.0;
  if (kinetic <= tolerance * work) {
    measure.force_ratio = solver.unbalanced_force_ratio();
    measure.reached = measure.force_ratio < tolerance;
  }
  return measure;
}

EquilibriumResult advance_to_equilibrium(ExplicitSolver& solver, double tolerance,
                                         double max_time) {
  RunLog quiet;
  RunProgress progress;
  const std::vector<RunPhase> phases{
      RunPhase{"equilibrium", max_time - solver.time(), tolerance, std::nullopt}};
  begin_phase(progress, phases, solver.scene(), 0, solver.time());
  OutputSchedule no_rows;
  no_rows.history_interval = std::numeric_limits<double>::infinity();
  PhaseRunner runner(solver, phases, no_rows, progress, quiet);
  runner.start();
  runner.run([](std::size_t, double) {}, [](long) { return false; });
  EquilibriumResult result;
  result.measure = measure_equilibrium(solver, tolerance);
  result.reached = result.measure.reached;
  result.time = solver.time();
  return result;
}

} // namespace mpile
