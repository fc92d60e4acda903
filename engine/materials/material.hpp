#pragma once

#include "engine/parameter_range.hpp"
#include "engine/tensor.hpp"

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mpile {

/// The ranges of the constants every elastic model shares, declared once: the material registry
/// gives them to the case's keys and each model's constructor checks them (require_in_range).
inline const ParameterRange young_modulus_range = above(0.0);
inline const ParameterRange poisson_ratio_range = between(-1.0, false, 0.5, false);
inline const ParameterRange density_range = above(0.0);

struct LiquidPhase;
struct PoreStorage;

/// A run of material points of one material handed to its stress update. Strain increments and the
/// constrained modulus are per entry of the run; stress and state are the particles' own.
struct StressUpdateBatch {
  std::span<const std::int32_t> particles; // particle indices
  std::span<const StrainIncrement> strain; // per entry: engineering shear, tension positive
  std::span<double> constrained_modulus;   // per entry, out: current M for the time step
  Stress* stress = nullptr;                // indexed by particle
  double* state = nullptr;                 // indexed by particle * state_stride
  int state_stride = 0;
};

/// A constitutive model: a function of (stress, strain increment, state) returning the new stress
/// and state. A new model is a new file with a class derived from this one plus one registration
/// in material_registry.cpp; the solver knows nothing else about it.
class Material {
public:
  virtual ~Material() = default;

  /// Registered type name (as written in a case file).
  virtual std::string_view type() const = 0;
  /// Initial density (kg/m^3), for particle masses.
  virtual double density() const = 0;
  /// True for the particles of a rigid body (no stress, not counted in the soil's energies).
  virtual bool is_rigid() const { return false; }

  /// Names of the per-particle state variables; a model without state carries none.
  virtual std::span<const std::string> state_names() const { return {}; }
  std::size_t state_size() const { return state_names().size(); }
  /// Where the pore pressure is kept in the state of a saturated, undrained material (the
  /// particle's stress is then total: sigma' + p 1); -1 for a dry or drained one.
  virtual int pore_pressure_index() const { return -1; }
  /// The sea's pressure on the seabed (Pa) that a saturated material's pore pressure and total
  /// stress are kept relative to (physics.md section 9c); outputs add it back. 0 for every other.
  virtual double water_column_pressure() const { return 0.0; }
  /// The highest pore pressure p (tension positive, the sea's column included as the state keeps
  /// it) the water may reach before it cavitates: infinite without a cut-off or without water.
  virtual double pore_pressure_limit() const { return std::numeric_limits<double>::infinity(); }
  /// A particle's total stress as outputs report it, the sea's pressure added back.
  Stress reported_stress(Stress stress) const {
    const double column = water_column_pressure();
    stress[RR] -= column;
    stress[YY] -= column;
    stress[TT] -= column;
    return stress;
  }
  /// A state variable as outputs report it: the pore pressure relative to the atmosphere.
  double reported_state(int slot, double value) const {
    return slot == pore_pressure_index() ? value - water_column_pressure() : value;
  }
  /// A saturated material whose water flows (drainage = "coupled"): where its particles keep the
  /// water's state and the constants of its two phases; null for every other.
  virtual const LiquidPhase* liquid_phase() const { return nullptr; }
  /// A saturated material whose pore pressure the solver finds implicitly ([solver]
  /// implicit_pore_pressure): where its pore pressure is kept and its water's compressibility;
  /// null for every other (then the material updates its own pore pressure, if it has one).
  virtual const PoreStorage* implicit_pore_storage() const { return nullptr; }
  /// Where a model that carries the void ratio e keeps it in its state: saturated, its pores are
  /// the water's (n = e / (1 + e)), one state for both. -1 for every other.
  virtual int void_ratio_index() const { return -1; }
  /// Sets the state consistent with a given initial stress (for example after a K0 procedure).
  virtual void initialise_state(const Stress& /*stress*/, double* /*state*/) const {}

  /// A state no soil can be in (a sand looser than its loosest at its pressure): the parameter
  /// that sets it and why; an empty key for a state the model admits.
  struct Inadmissible {
    std::string key;
    std::string reason;
  };
  virtual Inadmissible inadmissible_state(const Stress& /*stress*/, const double* /*state*/) const {
    return {};
  }

  /// Advances stress and state of every particle of the batch by its strain increment, and writes
  /// the current constrained modulus used by the time step.
  virtual void update_stress(const StressUpdateBatch& batch) const = 0;

  /// Constrained (P-wave) modulus at a stress state, for the initial time step (Pa).
  virtual double constrained_modulus(const Stress& stress, const double* state) const = 0;

  /// Shear modulus at a stress state (Pa); with the constrained modulus it gives the P and S wave
  /// impedances of an absorbing boundary.
  virtual double shear_modulus(const Stress& stress, const double* state) const = 0;

  /// Recoverable (elastic) energy per unit volume stored at a stress state (J/m^3).
  virtual double elastic_energy_density(const Stress& stress, const double* state) const = 0;
};

/// Advances one material point outside any particle set (element tests, unit tests): a batch of
/// one. Returns the constrained modulus the material reports.
inline double update_single_point(const Material& material, Stress& stress, double* state,
                                  const StrainIncrement& strain) {
  const std::int32_t index = 0;
  double modulus = 0.0;
  StressUpdateBatch batch;
  batch.particles = std::span<const std::int32_t>(&index, 1);
  batch.strain = std::span<const StrainIncrement>(&strain, 1);
  batch.constrained_modulus = std::span<double>(&modulus, 1);
  batch.stress = &stress;
  batch.state = state;
  batch.state_stride = static_cast<int>(material.state_size());
  material.update_stress(batch);
  return modulus;
}

} // namespace mpile
