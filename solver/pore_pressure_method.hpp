#pragma once

// The pore pressure's increment over a step, by one of two methods the solver chooses once, from
// [solver] implicit_pore_pressure (physics.md sections 9b and 9d):
//   FlowPorePressure       explicit: each coupled particle's share K_w div w dt from its water's
//                          flow (undrained soil's comes with its skeleton's, in its material's
//                          update); the water's stiffness then sets the step
//   ProjectedPorePressure  implicit: one increment per saturated cell solved on the grid
//                          (PorePressureProjection), which corrects the velocities the stress pass
//                          reads, so that the step follows the skeleton
// Both find the increment before the stress pass, from the velocities it reads, and apply it after
// it, so that the pass takes the stress at the step's start (PorePressureMethod says how).

#include "engine/geometry_mode.hpp"
#include "engine/particle_bins.hpp"
#include "engine/scene.hpp"
#include "engine/shape_functions.hpp"
#include "solver/energy_balance.hpp"
#include "solver/pass_timer.hpp"
#include "solver/passes.hpp"
#include "solver/pore_pressure_projection.hpp"
#include "solver/solver_settings.hpp"

#include <concepts>
#include <vector>

namespace mpile {

/// What the pore water's passes work on: the solver's scene, bins, settings and timings, and each
/// material's water phase (passes::liquid_phases; empty in a scene without coupled soil).
struct WaterContext {
  Scene& scene;
  const ParticleBins& bins;
  const SolverSettings& settings;
  PassTimings& timings;
  const std::vector<const LiquidPhase*>& phases;
};

/// The interface both methods keep.
///   find<mode, shape>(water, step, step_number)  before the stress pass: the step's increment,
///       from the velocities the pass reads; returns what it adds to the ledger; throws
///       SimulationError when it cannot find one (step_number names the step)
///   apply(water, some_made_stress_free, energy)   after it: the particles' pore pressure and total
///       stress take the increment; adds the pore water's work beyond the stress pass's, pass by
///       pass, to `energy` (some_made_stress_free: the stress pass made soil inside a rigid body
///       stress-free, which takes none)
///   drag_booked_at_correction  whether Darcy's drag is booked by find, at the velocities its
///       correction leaves (else where the water's grid velocities are updated)
template <class Method>
concept PorePressureMethod = requires(Method method, const WaterContext& water,
                                      const passes::StepParameters& step, long step_number,
                                      bool some_made_stress_free, EnergyLedger& energy) {
  {
    method.template find<GeometryMode::plane_strain, ShapeFunctions::linear>(water, step,
                                                                             step_number)
    } -> std::same_as<EnergyIncrement>;
  { method.apply(water, some_made_stress_free, energy) } -> std::same_as<void>;
  { Method::drag_booked_at_correction } -> std::convertible_to<bool>;
};

/// The explicit pore pressure: coupled soil's share from its water's flow.
class FlowPorePressure {
public:
  static constexpr bool drag_booked_at_correction = false;

  template <GeometryMode mode, ShapeFunctions shape>
  EnergyIncrement find(const WaterContext& water, const passes::StepParameters& step,
                       long step_number);
  void apply(const WaterContext& water, bool some_made_stress_free, EnergyLedger& energy);

  /// Each particle's change from the flow, between find and apply (scratch of one step).
  std::vector<passes::PendingPorePressure>& pending() { return pending_; }

private:
  std::vector<passes::PendingPorePressure> pending_;
};

/// The implicit pore pressure: the grid's projection. Coupled soil still takes its flow's strains
/// (for the water's work), with the pressure the solve found; undrained soil takes the solve's
/// increment alone.
class ProjectedPorePressure {
public:
  static constexpr bool drag_booked_at_correction = true;

  template <GeometryMode mode, ShapeFunctions shape>
  EnergyIncrement find(const WaterContext& water, const passes::StepParameters& step,
                       long step_number);
  void apply(const WaterContext& water, bool some_made_stress_free, EnergyLedger& energy);

private:
  FlowPorePressure flow_;
  /// Its system and solver kept from step to step.
  passes::PorePressureProjection projection_;
};

static_assert(PorePressureMethod<FlowPorePressure>);
static_assert(PorePressureMethod<ProjectedPorePressure>);

} // namespace mpile
