#pragma once

// The pore water of a saturated soil and how it drains (PLAXIS's drainage types). A drained
// material carries no water state and runs exactly as a dry one; an undrained one adds the water's
// stiffness K_w / n to the skeleton's volumetric response at each material point (UndrainedSoil);
// a coupled one also lets the water flow through the skeleton (Darcy), each material point
// carrying the water's velocity as well as the skeleton's (physics.md section 9b).

#include "engine/parameter_range.hpp"

#include <limits>
#include <string>
#include <vector>

namespace mpile {

/// drained: no pore-water state, effective and total stress are one (a dry sand); undrained: no
/// flow, the pore pressure follows the volumetric strain (PLAXIS's Undrained A); coupled: the
/// water flows relative to the skeleton against Darcy's drag, and the pore pressure follows the
/// volumetric strains of both phases (two-phase single-point MPM).
enum class Drainage { drained, undrained, coupled };

/// Drainage names as written in a case file, in enum order.
const std::vector<std::string>& drainage_names();

struct PoreWater {
  Drainage drainage = Drainage::drained;
  double density = 1000.0;       // rho_w (kg/m^3)
  double bulk_modulus = 2.2e9;   // K_w (Pa): fresh or sea water at 10 to 20 degrees C
  double grain_density = 2650.0; // rho_s (kg/m^3): quartz; with the dry density, the porosity
  /// k (m/s), coupled only: Darcy's hydraulic conductivity, the discharge per unit hydraulic
  /// gradient; 0 when not given (a coupled material must give it).
  double hydraulic_conductivity = 0.0;
  /// The sea's: not a material key, set from the case's [water] table. The water column's
  /// pressure on the seabed, rho_w g (level - seabed) (Pa): the particle's pore pressure is kept
  /// relative to it (physics.md section 9c), so that the seabed stays a traction-free surface.
  double column_pressure = 0.0;
  /// The tension (Pa, relative to the atmosphere) at which the pore water cavitates: its pore
  /// pressure rises no further (PLAXIS's cavitation cut-off). Infinite: no cut-off.
  double cavitation_stress = std::numeric_limits<double>::infinity();
  /// Not a material key: set from [solver] implicit_pore_pressure. The solver finds the pore
  /// pressure's increment on the grid each step, implicitly in the water's stiffness (physics.md
  /// section 9d): the material then leaves the pore pressure to it and its water adds nothing to
  /// the stiffness the time step follows.
  bool implicit_pressure = false;
};

/// Standard gravity (m/s^2): a hydraulic conductivity is measured under it, k = kappa rho_w g / mu,
/// whatever gravity a scene sets (a scene without gravity still drains).
inline constexpr double standard_gravity = 9.80665;

/// What the solver's water passes need of a coupled material: where its particles keep the water's
/// state, and the constants of its two phases. Each material point carries both phases' mass, as
/// Anura3D's single-point formulation does: its grains', (1 - n) rho_s V, kept, and its water's,
/// n rho_w V, the water that fills its pores now (the stress pass sets the mixture's mass from the
/// volume and porosity each step), so that a soil consolidating under its own weight drains its
/// water's weight with its water.
struct LiquidPhase {
  int pore_slot = 0;     // state[pore_slot]: the pore pressure p (tension positive)
  int velocity_slot = 0; // state[velocity_slot + 0, 1, 2]: the water's velocity w (r, y, theta)
  int porosity_slot = 0; // state[porosity_slot]: the porosity n now
  double water_density = 0.0; // rho_w (kg/m^3)
  double grain_density = 0.0; // rho_s (kg/m^3): the dry density over 1 - n0
  double drag_per_mass = 0.0; // g / k (1/s): Darcy's drag n rho_w g / k per unit water mass
  double bulk_modulus = 0.0;  // K_w (Pa)
  /// The highest p the water may reach before it cavitates (column_pressure +
  /// cavitation_stress; infinite without a cut-off).
  double pore_limit = std::numeric_limits<double>::infinity();

  /// The mixture's density at porosity n, (1 - n) rho_s + n rho_w.
  double mixture_density(double n) const { return (1.0 - n) * grain_density + n * water_density; }
  /// The water's share of the mixture's mass at porosity n, n rho_w / ((1 - n) rho_s + n rho_w).
  double water_fraction(double n) const { return n * water_density / mixture_density(n); }
};

/// What the solver's implicit pore pressure needs of a saturated material (undrained or
/// coupled): where the pore pressure is kept and how much water a unit of pressure stores.
struct PoreStorage {
  int pore_slot = 0;      // state[pore_slot]: p; state[pore_slot + 1]: its change since the start
  int porosity_slot = -1; // state[porosity_slot]: the porosity now; -1: constant (undrained)
  double porosity = 0.0;  // n0, the porosity of an undrained material
  double bulk_modulus = 0.0;                                   // K_w (Pa)
  double pore_limit = std::numeric_limits<double>::infinity(); // as LiquidPhase's
  /// n / K_w (1/Pa): the pore water's volume change per unit volume of soil and unit pressure.
  double compressibility(const double* state) const {
    return (porosity_slot < 0 ? porosity : state[porosity_slot]) / bulk_modulus;
  }
};

/// A water parameter as the case layer sees it: its key, unit, meaning, default and range, bound
/// to its member of PoreWater (declared once, in pore_water.cpp).
struct PoreWaterParameter {
  std::string name;
  std::string unit;
  std::string meaning;
  double PoreWater::*member;
  ParameterRange range;
};
const std::vector<PoreWaterParameter>& pore_water_parameters();

/// Porosity n = 1 - rho_d / rho_s of a skeleton of dry density rho_d.
double porosity(double dry_density, const PoreWater& water);

/// What a skeleton of drained bulk modulus K' and shear modulus G becomes with the water undrained
/// (incompressible grains): K_u = K' + K_w / n, Skempton's B = (K_w / n) / K_u and the undrained
/// Poisson ratio (3 K_u - 2 G) / (2 (3 K_u + G)).
struct UndrainedResponse {
  double bulk_modulus = 0.0;
  double skempton_b = 0.0;
  double poisson_ratio = 0.0;
};
UndrainedResponse undrained_response(double drained_bulk, double shear, double water_stiffness);

} // namespace mpile
