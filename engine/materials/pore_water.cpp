#include "engine/materials/pore_water.hpp"

namespace mpile {

const std::vector<std::string>& drainage_names() {
  static const std::vector<std::string> names{"drained", "undrained", "coupled"};
  return names;
}

const std::vector<PoreWaterParameter>& pore_water_parameters() {
  // The ranges refuse only what no pore water is; what is merely implausible is the warnings'.
  static const std::vector<PoreWaterParameter> parameters{
      {"water_density",
       "kg/m^3",
       "density of the pore water rho_w",
       &PoreWater::density,
       {Bound{0.0, false}, std::nullopt}},
      {"water_bulk_modulus",
       "Pa",
       "bulk modulus K_w of the pore water; a smaller one softens the undrained response "
       "(Skempton's B below 1), and `mpile check` prints what it implies",
       &PoreWater::bulk_modulus,
       {Bound{0.0, false}, std::nullopt}},
      {"grain_density",
       "kg/m^3",
       "density rho_s of the grains; with the dry density it gives the porosity "
       "n = 1 - rho_d / rho_s",
       &PoreWater::grain_density,
       {Bound{0.0, false}, std::nullopt}},
      {"hydraulic_conductivity",
       "m/s",
       "Darcy's hydraulic conductivity k of the skeleton (coupled only, and required there): "
       "the water's discharge per unit hydraulic gradient",
       &PoreWater::hydraulic_conductivity,
       {Bound{0.0, false}, std::nullopt}},
  };
  return parameters;
}

double porosity(double dry_density, const PoreWater& water) {
  return 1.0 - dry_density / water.grain_density;
}

UndrainedResponse undrained_response(double drained_bulk, double shear, double water_stiffness) {
  const double bulk = drained_bulk + water_stiffness;
  return {bulk, water_stiffness / bulk, (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear))};
}

} // namespace mpile
