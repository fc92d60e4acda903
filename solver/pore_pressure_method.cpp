#include "solver/pore_pressure_method.hpp"

#include "engine/parallel.hpp"
#include "solver/run_log.hpp"
#include "solver/simulation_error.hpp"

#include <sstream>

namespace mpile {

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement FlowPorePressure::find(const WaterContext& water,
                                       const passes::StepParameters& step, long) {
  if (water.phases.empty()) {
    return {};
  }
  PassTimer timer(water.timings.stress_update);
  passes::pore_pressure_from_flow<mode, shape>(water.scene, water.bins, water.phases,
                                               water.settings, step, pending_);
  return {};
}

void FlowPorePressure::apply(const WaterContext& water, bool some_made_stress_free,
                             EnergyLedger& energy) {
  if (water.phases.empty()) {
    return;
  }
  PassTimer timer(water.timings.stress_update);
  energy +=
      EnergyIncrement{.internal_work = passes::apply_pore_pressure_from_flow(
                          water.scene, water.bins, water.phases, pending_, some_made_stress_free)};
}

template <GeometryMode mode, ShapeFunctions shape>
EnergyIncrement ProjectedPorePressure::find(const WaterContext& water,
                                            const passes::StepParameters& step, long step_number) {
  EnergyIncrement found;
  {
    PassTimer timer(water.timings.grid_update);
    const passes::ProjectionResult solved =
        projection_.project<mode, shape>(water.scene, water.bins, water.settings, step);
    if (!solved.converged) {
      std::ostringstream s;
      s << at_step(step_number, step.time) << "the pore pressure's system over " << solved.cells
        << " cells did not converge (relative residual " << solved.residual << " after "
        << solved.iterations << " conjugate-gradient iterations): the run went unstable";
      throw SimulationError(s.str());
    }
    // The vapour's share is work on the soil's pore volume, as the cut-off's is in the explicit
    // water: internal work, dissipated. Darcy's drag is booked here, at the corrected velocities
    // (docs/saturated.md, "The step's energy identity").
    found = {
        .internal_work = solved.vapour_work, .damping = solved.dissipated, .drag = solved.drag};
  }
  if (water.phases.empty()) {
    return found;
  }
  flow_.find<mode, shape>(water, step, step_number);
  // The flow's strains as found; the pressure is the one the grid's solve found.
  PassTimer timer(water.timings.stress_update);
  std::vector<passes::PendingPorePressure>& pending = flow_.pending();
  const std::vector<double>& increment = projection_.particle_increment();
  const std::vector<std::uint8_t>& cavitated = projection_.particle_cavitated();
  const Particles& p = water.scene.particles;
  parallel_for(pending.size(), [&](std::size_t i) {
    if (water.phases[p.material[i]] != nullptr) {
      pending[i].pressure = increment[i];
      pending[i].cavitated = cavitated[i] != 0;
    }
  });
  return found;
}

void ProjectedPorePressure::apply(const WaterContext& water, bool some_made_stress_free,
                                  EnergyLedger& energy) {
  // Coupled soil takes the increment with its flow's, undrained soil after it: two sums, added to
  // the ledger in that order.
  flow_.apply(water, some_made_stress_free, energy);
  PassTimer timer(water.timings.stress_update);
  energy += EnergyIncrement{.internal_work = passes::apply_projected_pore_pressure(
                                water.scene, water.bins, projection_.particle_increment(),
                                projection_.particle_cavitated(), some_made_stress_free)};
}

#define MPILE_PORE_PRESSURE_METHODS(MODE, SHAPE)                                                   \
  template EnergyIncrement FlowPorePressure::find<MODE, SHAPE>(                                    \
      const WaterContext&, const passes::StepParameters&, long);                                   \
  template EnergyIncrement ProjectedPorePressure::find<MODE, SHAPE>(                               \
      const WaterContext&, const passes::StepParameters&, long);
MPILE_PORE_PRESSURE_METHODS(GeometryMode::axisymmetric, ShapeFunctions::linear)
MPILE_PORE_PRESSURE_METHODS(GeometryMode::axisymmetric, ShapeFunctions::gimp)
MPILE_PORE_PRESSURE_METHODS(GeometryMode::plane_strain, ShapeFunctions::linear)
MPILE_PORE_PRESSURE_METHODS(GeometryMode::plane_strain, ShapeFunctions::gimp)
#undef MPILE_PORE_PRESSURE_METHODS

} // namespace mpile
