#pragma once

// The pore water of saturated soil (physics.md sections 9a to 9d) as one object: the water's
// passes (solver/pore_water_passes.cpp), the pore pressure's method (solver/
// pore_pressure_method.hpp) and what they keep from pass to pass. A dry scene has none, and its
// step runs no water pass.
//
// The step (solver/explicit_step.cpp) calls it at four points of its own:
//   to_grid                 after particle-to-grid: the water's nodes, the drained faces' far
//                           field, the pore water's share of the soil's node forces at a structure
//   update_grid_velocities  after contact and supports: the water's velocities from the
//                           skeleton's
//   find_pore_pressure      before the stress pass: with MUSL the water's remap, then the step's
//                           pore pressure increment
//   apply_pore_pressure     after the stress pass: the particles take it
// and three passes of the mixture take the water's share where its arithmetic falls between the
// skeleton's: the momentum balance (couple_to_skeleton, between the loads and the balance), the
// grid-to-particle pass (to_particles, between the skeleton's velocities and the MUSL remap), the
// remap (rescale_remapped_skeleton, before the remapped velocities' supports) and, once the
// particles are rebinned at the step's end, smooth_excess_pore_pressure.

#include "engine/geometry_mode.hpp"
#include "engine/particle_bins.hpp"
#include "engine/scene.hpp"
#include "engine/shape_functions.hpp"
#include "solver/energy_balance.hpp"
#include "solver/pass_timer.hpp"
#include "solver/passes.hpp"
#include "solver/pore_pressure_method.hpp"
#include "solver/run_log.hpp"
#include "solver/solver_settings.hpp"
#include "solver/xpic.hpp"

#include <memory>
#include <variant>
#include <vector>

namespace mpile {

class PoreWaterCoupling {
public:
  /// The scene's pore water, or null when no material keeps a pore pressure. The references are
  /// the solver's own, kept for its life. Throws std::invalid_argument for settings the water
  /// cannot take (check) or coupled soil in a structure's body.
  static std::unique_ptr<PoreWaterCoupling>
  of(Scene& scene, const ParticleBins& bins, const SolverSettings& settings, PassTimings& timings);
  PoreWaterCoupling(Scene& scene, const ParticleBins& bins, const SolverSettings& settings,
                    PassTimings& timings);
  PoreWaterCoupling(const PoreWaterCoupling&) = delete;
  PoreWaterCoupling& operator=(const PoreWaterCoupling&) = delete;

  /// Throws std::invalid_argument for settings the water cannot take: mass scaling with the
  /// water's stiffness explicit, or a pore pressure method the materials were not built for.
  void check(const SolverSettings& settings) const;

  // The step's four points.
  template <GeometryMode mode, bool contact, ShapeFunctions shape> void to_grid();
  template <GeometryMode mode>
  EnergyIncrement update_grid_velocities(const passes::StepParameters& step);
  /// step_number: the step being taken, for the message when the pressure cannot be found.
  template <GeometryMode mode, ShapeFunctions shape>
  EnergyIncrement find_pore_pressure(const passes::StepParameters& step, long step_number);
  /// Adds the pore water's work beyond the stress pass's to `energy`, pass by pass.
  void apply_pore_pressure(bool some_made_stress_free, EnergyLedger& energy);

  // Its share of the mixture's passes.
  /// In the momentum balance, after the loads: the water's inertia and drag folded into the
  /// skeleton's nodes.
  template <GeometryMode mode>
  passes::CoupledPhasesResult couple_to_skeleton(const passes::StepParameters& step);
  /// After the skeleton's particle velocities, before the MUSL remap: the particles' water
  /// velocities.
  template <GeometryMode mode, ShapeFunctions shape>
  EnergyIncrement to_particles(const passes::StepParameters& step);
  /// In the MUSL remap, before its supports: the skeleton's remapped velocities as the mixture's
  /// mass-weighted mean.
  template <GeometryMode mode> void rescale_remapped_skeleton();
  /// With cell_mean_pore_pressure, once the particles are binned where the stress pass moved
  /// them: each block then holds the particles of its own cells.
  void smooth_excess_pore_pressure();
  /// Warns, once, of pore water in more tension than water can carry where nothing caps it.
  void report_tension(RunLog& log, long step, double time);

private:
  Scene& scene_;
  const ParticleBins& bins_;
  const SolverSettings& settings_;
  PassTimings& timings_;
  /// Each material's water phase when it is coupled soil; empty without coupled soil.
  std::vector<const LiquidPhase*> phases_;
  WaterContext context_;
  /// A scene with contact: the contact's friction needs the pore water's share of the soil's
  /// node forces.
  bool at_contact_ = false;
  /// Chosen once, from implicit_pore_pressure (the materials are built for one of the two).
  std::variant<FlowPorePressure, ProjectedPorePressure> pressure_;
  /// The water's own XPIC(m) correction and scratch, under XPIC (empty otherwise).
  passes::WaterXpic xpic_;
  /// Whether report_tension has warned (not in checkpoints: a restart warns again).
  bool tension_reported_ = false;
};

} // namespace mpile
